"""Every page of the table of contents, opened in Chromium as a reader would.

Each page is loaded once (see ``page_reports`` in conftest.py); each test
below asserts one aspect of what was seen, so a failure names the page and
the aspect. The run prints each page's weight; screenshots at 1280 px and
390 px wide land in _build/test-artifacts/browser/ (not in make test: BOOK_SHOTS=0).
"""

from __future__ import annotations

import bookcheck
import pytest
from conftest import BOOK_TOC

PAGES = bookcheck.pages_from_toc(BOOK_TOC)


def _assert_clean(report: bookcheck.PageReport, aspect: str) -> None:
    problems = report.problems.get(aspect, [])
    assert not problems, f"{report.path}: {aspect}:\n  " + "\n  ".join(problems)


def test_toc_lists_pages():
    assert len(PAGES) >= 2, f"expected the table of contents {BOOK_TOC} to name pages, got {PAGES}"


@pytest.mark.parametrize("path", PAGES)
def test_page_loads_without_failed_requests(page_reports, path):
    """The page exists in the build, every request it makes succeeds (no 404)."""
    _assert_clean(page_reports(path), "load")


@pytest.mark.parametrize("path", PAGES)
def test_no_console_errors(page_reports, path):
    _assert_clean(page_reports(path), "console")


@pytest.mark.parametrize("path", PAGES)
def test_nothing_loads_from_another_host(page_reports, path):
    """The book works offline: MathJax, scripts, fonts and images all come from the build."""
    _assert_clean(page_reports(path), "offline")


@pytest.mark.parametrize("path", PAGES)
def test_math_is_typeset(page_reports, path):
    _assert_clean(page_reports(path), "math")


@pytest.mark.parametrize("path", PAGES)
def test_images_load_and_have_alt_text(page_reports, path):
    _assert_clean(page_reports(path), "images")


@pytest.mark.parametrize("path", PAGES)
def test_animations_play(page_reports, path):
    _assert_clean(page_reports(path), "animations")


@pytest.mark.parametrize("path", PAGES)
def test_widget_sliders_are_live(page_reports, path):
    """A slider that redraws nothing without a kernel is a dead control for the reader."""
    _assert_clean(page_reports(path), "widgets")


@pytest.mark.parametrize("path", PAGES)
def test_solutions_open(page_reports, path):
    _assert_clean(page_reports(path), "solutions")


@pytest.mark.parametrize("path", PAGES)
def test_internal_links_resolve(page_reports, path):
    _assert_clean(page_reports(path), "links")


@pytest.mark.parametrize("path", PAGES)
def test_no_error_output_shown(page_reports, path):
    """No traceback or Sphinx error box reaches the reader."""
    _assert_clean(page_reports(path), "errors")


@pytest.mark.parametrize("path", PAGES)
def test_page_weight_under_3_mb(page_reports, path):
    report = page_reports(path)
    assert report.total_bytes > 0, f"{path}: no bytes were recorded, the weight check saw nothing"
    _assert_clean(report, "weight")


# ---------------------------------------------------------------- page quality
@pytest.mark.parametrize("path", PAGES)
def test_no_box_overflows(page_reports, path):
    """At 1280 px and 390 px, no output, admonition (a "Verified by code" box too) or display-math box has
    content wider than itself unless it scrolls sideways in its own box; the page itself never does."""
    _assert_clean(page_reports(path), "overflow")


@pytest.mark.parametrize("path", PAGES)
def test_every_figure_and_animation_has_a_numbered_caption(page_reports, path):
    _assert_clean(page_reports(path), "figures")


@pytest.mark.parametrize("path", PAGES)
def test_no_verdict_under_an_empty_answer(page_reports, path):
    """No "Correct" next to `answer = None`; on a page with exercises, verdicts only inside solutions."""
    _assert_clean(page_reports(path), "verdicts")


@pytest.mark.parametrize("path", PAGES)
def test_formulas_scroll_rather_than_being_cut_off(page_reports, path):
    """At 390 px (and 1280 px) a formula wider than its room scrolls in its own box: never clipped by
    overflow: hidden, never running off the screen."""
    _assert_clean(page_reports(path), "phone_math")


@pytest.mark.parametrize("path", PAGES)
def test_wide_figures_scroll_larger_on_a_phone(page_reports, path):
    """At 390 px a figure at least 1.5 times as wide as high is shown at up to twice the page's width
    in a box that scrolls sideways and takes the keyboard, so that its labels stay readable."""
    _assert_clean(page_reports(path), "phone_figures")


@pytest.mark.parametrize("path", PAGES)
def test_no_negative_zero_is_shown(page_reports, path):
    """No "-0." (or "−0.000", "-0") in the text, the outputs or the formulas a reader sees."""
    _assert_clean(page_reports(path), "negative_zero")


@pytest.mark.parametrize("path", PAGES)
def test_no_raw_check_printout(page_reports, path):
    """Checks are reported in "Verified by code" boxes, not as monospace "✓ checked: ..." lines."""
    _assert_clean(page_reports(path), "check_lines")


def test_search_finds_adjoint(book_url, browser_context):
    """The Sphinx search page, fed "adjoint", lists the pages that define it."""
    hits = bookcheck.search(browser_context, book_url, "adjoint")
    assert hits, "searching the book for 'adjoint' found nothing"
    defining = {"chapters/conventions.html", "chapters/01_twists.html"}
    assert defining & set(hits), f"searching 'adjoint' found {hits}, not the conventions page nor chapter 1"
