"""Fixtures for the browser tests: the built book served on 127.0.0.1 and Debian's Chromium.

Environment:
  BOOK_HTML   the built HTML folder (default: _build/html of the repository)
  BOOK_TOC    the table of contents naming the pages to test (default: _toc.yml)
  BOOK_ARTIFACTS  where screenshots go (default: _build/test-artifacts/browser)
  BOOK_SHOTS  0: no full-page screenshots of the pages, nor of each slide in tests/slides (make test: they are
              for a person to look at, no test reads them, and they take about a third of each page's time);
              anything else or unset: take them
"""

from __future__ import annotations

import os
from pathlib import Path

import bookcheck
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent



def _env_path(name: str, default: Path) -> Path:
    value = os.environ.get(name)
    path = Path(value) if value else default
    return path if path.is_absolute() else (ROOT / path)


BOOK_HTML = _env_path("BOOK_HTML", ROOT / "_build" / "html")
BOOK_TOC = _env_path("BOOK_TOC", ROOT / "_toc.yml")
ARTIFACTS = _env_path("BOOK_ARTIFACTS", ROOT / "_build" / "test-artifacts" / "browser")
SHOTS = os.environ.get("BOOK_SHOTS", "1") != "0"


def pytest_report_header(config):
    return [f"browser tests: book {BOOK_HTML}, toc {BOOK_TOC}, screenshots {ARTIFACTS if SHOTS else 'none (BOOK_SHOTS=0)'}"]


# ---------------------------------------------------------------- on both cores (make test-browser: -n 2)
# With pytest-xdist's --dist loadscope and tests/conftest.py's work units, each page's tests of test_pages.py run
# in one worker (the page is loaded once) and the pages spread over the workers; every other module runs whole in
# one worker (its browser page or JupyterLab server is started once). The page summary a worker writes is printed
# by the controller at the end.
WORKER = os.environ.get("PYTEST_XDIST_WORKER", "")


def pytest_sessionstart(session):
    if session.config.getoption("markexpr", "") == "not browser":
        return  # make test-lib (it may run beside make test-browser: leave that run's summaries alone)
    if not WORKER:  # the controller (or a run without xdist): no summary left from an earlier run
        for old in ARTIFACTS.glob("summary-*.txt"):
            old.unlink()


@pytest.fixture(scope="session")
def book_html() -> Path:
    if not (BOOK_HTML / "index.html").exists():
        pytest.fail(
            f"The built book is missing: no {BOOK_HTML / 'index.html'}. "
            "Build it first (`make book`), or point BOOK_HTML at a built HTML folder.",
            pytrace=False,
        )
    return BOOK_HTML


@pytest.fixture(scope="session")
def book_url(book_html):
    with bookcheck.BookServer(book_html) as server:
        yield server.base


# browser_context (one Chromium per worker) is tests/conftest.py's, shared with tests/install and tests/slides


@pytest.fixture(scope="session")
def artifacts() -> Path:
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    return ARTIFACTS


@pytest.fixture(scope="session")
def page_reports(book_html, book_url, browser_context, artifacts):
    """Each page is opened once; the per-aspect tests read its report."""
    cache: dict[str, bookcheck.PageReport] = {}

    def get(path: str) -> bookcheck.PageReport:
        if path not in cache:
            cache[path] = bookcheck.check_page(browser_context, book_url, book_html, path,
                                               shots=artifacts if SHOTS else None)
        return cache[path]

    yield get
    if cache:
        lines = ["", "Page weight and what was checked, per page:"]
        lines += ["  " + r.summary() for r in cache.values()]
        notes = [(r.path, n) for r in cache.values() for n in dict.fromkeys(r.notes)]
        if notes:
            lines.append("Notes (not failures):")
            lines += [f"  {p}: {n}" for p, n in notes]
        (artifacts / f"summary-{WORKER or 'main'}.txt").write_text("\n".join(lines) + "\n", encoding="utf-8")


def pytest_terminal_summary(terminalreporter):
    """Page weights and notes, from every worker (sorted by page)."""
    if WORKER:
        return
    pages: list[str] = []
    notes: list[str] = []
    for f in sorted(ARTIFACTS.glob("summary-*.txt")):
        part = "pages"
        for line in f.read_text(encoding="utf-8").splitlines():
            if line.startswith("Notes (not failures)"):
                part = "notes"
            elif line.startswith("  "):
                (pages if part == "pages" else notes).append(line)
    if pages:
        terminalreporter.write_line("")
        terminalreporter.write_line("Page weight and what was checked, per page:")
        for line in sorted(pages):
            terminalreporter.write_line(line)
        if notes:
            terminalreporter.write_line("Notes (not failures):")
            for line in notes:
                terminalreporter.write_line(line)
        if SHOTS:
            terminalreporter.write_line(f"Screenshots: {ARTIFACTS}")
