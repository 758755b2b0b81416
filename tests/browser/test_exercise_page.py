"""The exercise pages check answers in the page, and agree with the notebook's checker.

Agreement: for every exercise the page checks, 20 student IDs and the answers of
:func:`exercise_answers.answers_for` (the reference three ways, rounded to the decimals asked and coarser, every
catalogued mistake, near the edges of the margin, a transpose, wrong shapes, other orders, an empty box, garbage
text, NaN, an unknown symbol), the page's verdict (``window.courseExercises.checkText``, called in batches on the
built page, one load per exercise page) has the kind, verdict, mistake name and message of
:func:`course.exercises.check` for the same answer and ID (for an empty box or text it cannot read, the kind).

The ID: the page picks the variant the library picks (``variant_index``), and shows the statement of
``exercises.load(id)``; two IDs show different statements. Use: a reader with the keyboard only sets an ID,
checks a right answer, a catalogued mistake and one at the precision limit, sees progress, and saves the answers
file; at 390 px and in dark mode nothing overflows; no console error, no request to another host.
"""

from __future__ import annotations

import json
import re
import urllib.parse
from pathlib import Path

import numpy as np
import pytest
from exercise_answers import answers_for

from course import exercises
from course.classroom.page_answers import read_answers_text
from course.exercises._bank import BANK_SIZE, PAGE_KINDS, variant_index
from jacobians.grading.feedback import statement_html

ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted(p.stem for p in (ROOT / "exercises").glob("*.md"))
#: 20 student IDs (and the placeholder), some with spaces and capitals the normalisation removes
IDS = [f"s{2400000 + 37 * i}" for i in range(17)] + ["  Jane DOE ", "Ünïcode-ß 7", "42", "student-id"]


#: The statement shown in an exercise's box with each typeset formula back to its TeX (data-tex) in the delimiters
#: of :func:`~jacobians.grading.feedback.statement_html`
_SHOWN_TEX = r"""(eid) => {
    const s = document.querySelector(`.course-answer[data-exercise="${eid}"] .course-answer-statement`).cloneNode(true);
    s.querySelectorAll('[data-tex]').forEach(m => m.replaceWith(document.createTextNode(
        m.tagName === 'DIV' ? '\\[' + m.dataset.tex + '\\]' : '\\(' + m.dataset.tex + '\\)')));
    return s.innerHTML; }"""


def _page_exercises(page: str) -> list[str]:
    text = (ROOT / "exercises" / f"{page}.md").read_text(encoding="utf-8")
    return re.findall(r"```\{answer-box\} (ch\d+_ex\d+)", text)


def _open(browser_context, book_url: str, page: str, problems: list[str], color_scheme: str = "light"):
    tab = browser_context.new_page()
    tab.emulate_media(color_scheme=color_scheme)
    host = urllib.parse.urlsplit(book_url).netloc
    tab.on("console", lambda m: problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    tab.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    tab.on("request", lambda r: problems.append(f"foreign request {r.url}")
           if urllib.parse.urlsplit(r.url).netloc not in (host, "") and not r.url.startswith(("data:", "blob:"))
           else None)
    tab.goto(f"{book_url}/exercises/{page}.html", wait_until="load")
    tab.wait_for_function("window.courseExercises !== undefined")
    return tab


def _assert_fits_a_phone(tab) -> None:
    """At 390 px, no answer box and no ID panel runs past the screen's right edge."""
    tab.set_viewport_size({"width": 390, "height": 844})
    overflow = tab.evaluate("""() => [...document.querySelectorAll('.course-answer, .course-id-panel')]
        .filter(e => e.getBoundingClientRect().right > document.documentElement.clientWidth + 1).length""")
    assert overflow == 0


@pytest.mark.parametrize("page", PAGES)
def test_page_and_notebook_agree(browser_context, book_url, page, capsys):
    problems: list[str] = []
    tab = _open(browser_context, book_url, page, problems)
    try:
        ids = [e for e in _page_exercises(page) if exercises.load(e, seed="x").kind in PAGE_KINDS]
        boxes = tab.eval_on_selector_all(".course-answer[data-exercise]", "els => els.map(e => e.dataset.exercise)")
        assert sorted(boxes) == sorted(ids), "every exercise the page checks has a box"
        triples = disagreements = 0
        report = []
        for eid in ids:
            batch, expected = [], []
            for sid in IDS:
                ex = exercises.load(eid, seed=sid)
                for text, value in answers_for(ex):
                    fb = ex.check(value)
                    batch.append([variant_index(eid, sid), text])
                    expected.append((sid, text, fb.correct, fb.kind, fb.mistake, fb.message))
            got = tab.evaluate("""([eid, batch]) => batch.map(([k, text]) => {
                const f = window.courseExercises.checkText(eid, k, text);
                return [f.correct, f.kind, f.mistake, f.message]; })""", [eid, batch])
            for (sid, text, ok, kind, mistake, message), (jok, jkind, jmistake, jmessage) in zip(expected, got, strict=True):
                triples += 1
                same = jkind == kind and (kind in ("empty", "invalid") or
                                          (jok, jmistake, jmessage) == (ok, mistake, message))
                if not same:
                    disagreements += 1
                    report.append(f"{eid} ID {sid!r} answer {text[:80]!r}: notebook {kind}/{mistake} {message[:90]!r}"
                                  f", page {jkind}/{jmistake} {jmessage[:90]!r}")
        with capsys.disabled():
            print(f"\n{page}: {len(ids)} exercises, {triples} (exercise, ID, answer) triples, "
                  f"{disagreements} disagreements")
        assert not report, "\n".join(report[:20])
        assert not problems, problems
    finally:
        tab.close()


@pytest.mark.parametrize("page", ["01_twists", "06_analytic_jacobian", "11_redundancy"])
def test_the_page_shows_the_variant_of_the_id(browser_context, book_url, page):
    problems: list[str] = []
    tab = _open(browser_context, book_url, page, problems)
    try:
        ids = [e for e in _page_exercises(page) if exercises.load(e, seed="x").kind in PAGE_KINDS]
        shown = {}
        for sid in ("s2400001", "s2400002"):
            tab.fill("#course-student-id", sid)
            tab.press("#course-student-id", "Enter")
            for eid in ids:
                k = int(tab.get_attribute(f'.course-answer[data-exercise="{eid}"]', "data-variant") or -1)
                assert k == variant_index(eid, sid)
                tab.evaluate("window.courseExercises.typesetDone().then(() => true)")
                html = tab.evaluate(_SHOWN_TEX, eid)
                assert html == statement_html(exercises.load(eid, seed=sid).statement)
                shown[(sid, eid)] = html
        assert any(shown[("s2400001", e)] != shown[("s2400002", e)] for e in ids), "two IDs, two statements"
        # the statement drawn for the ID was typeset at build time: no TeX left, and no MathJax loaded to show it
        assert tab.evaluate("""() => [...document.querySelectorAll('.course-answer-statement')]
            .every(s => !s.textContent.includes('\\\\(') && !s.textContent.includes('\\\\['))""")
        assert tab.locator(".course-answer-statement mjx-container").count() > 0
        assert tab.evaluate("window.MathJax === undefined"), "MathJax was loaded to show a statement"
        assert tab.evaluate(f"Object.values(window.__courseBanks).every(b => b.variants.length === {BANK_SIZE})")
        # the page's hash of an ID is the library's, for IDs with spaces, capitals, accents, other scripts
        tricky = ["s1", " S1 ", "a\tb\n c", "Ünïcode-ß", "ǅemal", "İstanbul", "学生-17", "x" * 200, "0", "12345"]
        page_k = tab.evaluate("([ids, eids, n]) => eids.map(e => ids.map(i => window.courseExercises.variantIndex(e, i, n)))",
                              [tricky, ids, BANK_SIZE])
        assert page_k == [[variant_index(e, i) for i in tricky] for e in ids]
        assert not problems, problems
    finally:
        tab.evaluate("localStorage.clear()")
        tab.close()


def _verdict(tab, eid: str, text: str) -> tuple[str, str]:
    box = f'.course-answer[data-exercise="{eid}"]'
    tab.focus(f"{box} textarea")
    tab.fill(f"{box} textarea", text)
    tab.keyboard.press("Control+Enter")
    out = tab.locator(f"{box} .course-answer-verdict")
    return out.get_attribute("class") or "", out.inner_text()


@pytest.mark.parametrize("mode", ["light", "dark"])
def test_a_reader_answers_with_the_keyboard(browser_context, book_url, artifacts, mode):
    problems: list[str] = []
    tab = _open(browser_context, book_url, "09_using_the_jacobian", problems, color_scheme=mode)
    try:
        sid = "s2401012"
        tab.focus("#course-student-id")
        tab.keyboard.type(sid)
        tab.keyboard.press("Enter")
        eid = "ch09_ex1"
        ex = exercises.load(eid, seed=sid)
        ref = ex.solution()
        kind, text = _verdict(tab, eid, ", ".join(f"{x:.4f}" for x in ref))
        assert "course-answer-correct" in kind and "Correct" in text
        m = ex.mistakes[0]
        kind, text = _verdict(tab, eid, " ".join(f"{x:.4f}" for x in m.value))
        assert "course-answer-wrong" in kind and m.name in text
        # an answer at the precision limit: rounded to fewer decimals than asked (the first exercise and rounding
        # of this page for which the notebook says so)
        limit = next((e, k) for e in ("ch09_ex2", "ch09_ex5", "ch09_ex1", "ch09_ex3") for k in (2, 1)
                     if exercises.check(e, np.round(exercises.load(e, seed=sid).solution(), k), seed=sid).mistake
                     == "too_few_decimals")
        rounded = np.atleast_1d(np.round(exercises.load(limit[0], seed=sid).solution(), limit[1]))
        typed = ", ".join(f"{x:.{limit[1]}f}" for x in rounded)
        kind, text = _verdict(tab, limit[0], typed)
        fb = exercises.check(limit[0], np.round(exercises.load(limit[0], seed=sid).solution(), limit[1]), seed=sid)
        assert fb.mistake == "too_few_decimals" and fb.mistake in text and fb.message in text
        eid_saved, typed_saved = limit[0], typed
        assert f"0 right, {1 if limit[0] == eid else 2} tried" in tab.inner_text(".course-progress")
        tab.screenshot(path=str(artifacts / f"exercise-page-desktop-{mode}.png"), full_page=False,
                       clip={"x": 0, "y": 0, "width": 1280, "height": 900})
        tab.locator(f'.course-answer[data-exercise="{eid}"]').scroll_into_view_if_needed()
        tab.screenshot(path=str(artifacts / f"exercise-page-box-{mode}.png"))
        with tab.expect_download() as dl:
            tab.focus(".course-id-panel button:nth-of-type(3)")
            tab.keyboard.press("Enter")
        saved = json.loads(Path(dl.value.path()).read_text(encoding="utf-8"))
        assert saved["id"] == sid and saved["answers"][eid_saved]["text"] == typed_saved
        if limit[0] != eid:
            assert saved["answers"][eid]["text"] == " ".join(f"{x:.4f}" for x in m.value)
        # make grade regrades the saved file: the verdicts the page showed
        rows = {r.exercise: r for r in read_answers_text(Path(dl.value.path()).read_bytes())[1]}
        assert (rows[limit[0]].correct, rows[limit[0]].mistake) == ("0", "too_few_decimals")
        if limit[0] != eid:
            assert (rows[eid].correct, rows[eid].mistake) == ("0", m.name)
        # phone width: the boxes fit the screen
        _assert_fits_a_phone(tab)
        tab.locator(f'.course-answer[data-exercise="{eid}"]').scroll_into_view_if_needed()
        tab.screenshot(path=str(artifacts / f"exercise-page-phone-{mode}.png"))
        assert not problems, problems
    finally:
        tab.evaluate("localStorage.clear()")
        tab.set_viewport_size({"width": 1280, "height": 900})
        tab.close()


def test_code_exercises_link_to_the_notebook(book_html):
    text = (book_html / "exercises" / "01_twists.html").read_text(encoding="utf-8")
    box = re.search(r'data-exercise-elsewhere="ch01_ex4".*?</div>', text, re.S)
    assert box and 'href="student/01_twists.ipynb"' in box.group(0) and "checked in the notebook" in box.group(0)
    assert (book_html / "exercises" / "student" / "01_twists.ipynb").is_file()


@pytest.mark.parametrize("mode", ["light", "dark"])
def test_a_formula_and_a_grid_with_the_keyboard(browser_context, book_url, artifacts, mode):
    """A symbolic answer typed in the box gets the notebook's verdict and a typeset preview of how it was read; the same
    matrix entered cell by cell in the grid (Tab from cell to cell, Ctrl+Enter checks) too; at 390 px the grid
    scrolls in its own box and the page does not."""
    from exercise_answers import formula_text
    problems: list[str] = []
    tab = _open(browser_context, book_url, "06_analytic_jacobian", problems, color_scheme=mode)
    try:
        sid, eid = "s2401012", "ch06_ex1"
        tab.focus("#course-student-id")
        tab.keyboard.type(sid)
        tab.keyboard.press("Enter")
        ex = exercises.load(eid, seed=sid)
        box = f'.course-answer[data-exercise="{eid}"]'
        kind, text = _verdict(tab, eid, formula_text(ex.reference))
        fb = ex.check(ex.reference)
        assert "course-answer-correct" in kind and fb.message in text
        # the preview is typeset by the book's MathJax, which the first typed formula loads (its MathML is read)
        tab.wait_for_selector(f"{box} .course-answer-preview mjx-container", timeout=60_000)
        preview = tab.text_content(f"{box} .course-answer-preview mjx-assistive-mml") or ""
        assert "cos" in preview or "sin" in preview, preview
        tab.locator(box).scroll_into_view_if_needed()
        tab.screenshot(path=str(artifacts / f"exercise-formula-desktop-{mode}.png"))
        # a catalogued mistake, typed in the grid with the keyboard
        m = ex.mistakes[0]
        tab.fill(f"{box} textarea", "")
        tab.focus(f"{box} .course-answer-grid-toggle")
        tab.keyboard.press("Enter")
        cells = tab.locator(f"{box} .course-answer-grid input")
        assert cells.count() == len(ex.reference)
        assert tab.evaluate("document.activeElement.closest('.course-answer-grid') !== null")
        for i, entry in enumerate(m.value):
            tab.keyboard.type(str(entry))
            if i < len(m.value) - 1:
                tab.keyboard.press("Tab")
        tab.keyboard.press("Control+Enter")
        out = tab.locator(f"{box} .course-answer-verdict")
        assert m.name in out.inner_text() and ex.check(m.value).message in out.inner_text()
        _assert_fits_a_phone(tab)
        tab.locator(f"{box} .course-answer-grid").scroll_into_view_if_needed()
        tab.screenshot(path=str(artifacts / f"exercise-grid-phone-{mode}.png"))
        assert not problems, problems
    finally:
        tab.evaluate("localStorage.clear()")
        tab.set_viewport_size({"width": 1280, "height": 900})
        tab.close()
