"""The browser checks can fail: pages broken on purpose must be reported.

A scratch copy of the built book is made in a temp folder (symlinks to the
real build, so it is cheap); one page is copied and broken in several ways,
each in its own file, and :func:`bookcheck.check_page` must name the breakage.
The sources and the real build are never touched.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

import bookcheck
from conftest import ROOT

sys.path.insert(0, str(ROOT / "_ext"))
import offline_fixes  # noqa: E402

CDN = "https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-mml-chtml.js"

# name -> (how the page is broken, aspect that must complain, text the complaint must contain)
BREAKAGES = {
    "raw_latex": ("insert", '<p class="mathjax_ignore">Broken on purpose: $$x^2$$ is not typeset here.</p>', "math", "$$"),
    "no_mathjax": ("drop_mathjax", None, "math", "typeset"),
    "missing_image": ("insert", '<img src="../_images/deleted-on-purpose.png" alt="a figure that was deleted">',
                      "images", "did not load"),
    "missing_image_404": ("insert", '<img src="../_images/deleted-on-purpose.png" alt="a figure that was deleted">',
                          "load", "404"),
    "image_without_alt": ("insert", '<img src="../_static/favicon.svg">', "images", "without alt"),
    "image_alt_is_filename": ("insert", '<img src="../_static/favicon.svg" alt="../_images/3f2a.png">',
                              "images", "file name"),
    "cdn_script": ("insert", f'<script src="{CDN}"></script>', "offline", "cdn.jsdelivr.net"),
    "cdn_stylesheet": ("insert_head", '<link rel="stylesheet" '
                       'href="https://maxcdn.bootstrapcdn.com/font-awesome/4.4.0/css/font-awesome.min.css">',
                       "offline", "maxcdn.bootstrapcdn.com"),
    "console_error": ("insert", "<script>console.error('broken on purpose')</script>", "console", "broken on purpose"),
    "uncaught_exception": ("insert", "<script>null.oops()</script>", "console", "page error"),
    "dead_link": ("insert", '<a href="no-such-page.html">a link to nowhere</a>', "links", "no-such-page.html"),
    "dead_anchor": ("insert", '<a href="#no-such-anchor">a link to nowhere</a>', "links", "no-such-anchor"),
    "traceback": ("insert", '<div class="output traceback"><pre>Traceback (most recent call last):\n'
                  'ZeroDivisionError</pre></div>', "errors", "traceback"),
    "dead_animation": ("insert", '<div class="animation"><img id="_anim_imgX" alt="an animation" '
                       'src="../_static/favicon.svg"><button onclick="void 0 /* play_animation */">play</button>'
                       '</div>', "animations", "did not change the frame"),
    "solution_never_opens": ("insert", '<details class="sd-dropdown"><summary onclick="event.preventDefault()">'
                             'Solution</summary><p>hidden forever</p></details>', "solutions", "does not open"),
}


def _overlay(book: Path, dest: Path) -> Path:
    """A folder that looks like the build: symlinks to it, except chapters/, whose files are linked one by one."""
    for entry in book.iterdir():
        if entry.name != "chapters":
            (dest / entry.name).symlink_to(entry, target_is_directory=entry.is_dir())
    (dest / "chapters").mkdir()
    for entry in (book / "chapters").iterdir():
        (dest / "chapters" / entry.name).symlink_to(entry, target_is_directory=entry.is_dir())
    return dest


def _break(html: str, how: str, payload: str | None) -> str:
    if how == "insert":
        new, n = re.subn(r"(<h1[^>]*>.*?</h1>)", lambda m: m.group(1) + payload, html, count=1, flags=re.S)
        assert n == 1, "the page has no <h1> to insert after"
        return new
    if how == "insert_head":
        return html.replace("</head>", payload + "</head>", 1)
    if how == "drop_mathjax":
        new, n = re.subn(r"<script[^>]*tex-mml-chtml\.js[^>]*></script>", "", html)
        assert n == 1, "the page does not load MathJax"
        return new
    raise ValueError(how)


@pytest.fixture(scope="module")
def broken_book(book_html, tmp_path_factory):
    """The scratch build, and the page (with math) that is broken in it."""
    base_page = "chapters/conventions.html"
    if not (book_html / base_page).exists():
        pytest.fail(f"{book_html / base_page} is missing: the breakage tests copy that page", pytrace=False)
    root = _overlay(book_html, tmp_path_factory.mktemp("broken-book"))
    original = (book_html / base_page).read_text(encoding="utf-8")
    assert "tex-mml-chtml.js" in original and 'class="math' in original, "conventions page should have math"
    for name, (how, payload, _aspect, _text) in BREAKAGES.items():
        (root / "chapters" / f"broken_{name}.html").write_text(_break(original, how, payload), encoding="utf-8")
    with bookcheck.BookServer(root) as server:
        yield root, server.base


@pytest.fixture(scope="module")
def broken_reports(broken_book, browser_context):
    root, base = broken_book
    cache = {}

    def get(name):
        if name not in cache:
            cache[name] = bookcheck.check_page(browser_context, base, root, f"chapters/broken_{name}.html",
                                               shots=None, settle_ms=100)
        return cache[name]

    return get


@pytest.fixture(scope="module")
def control(broken_book, browser_context):
    """The same page, unmodified, in the scratch copy: what it already complains about."""
    root, base = broken_book
    return bookcheck.check_page(browser_context, base, root, "chapters/conventions.html", shots=None, settle_ms=100)


def test_control_page_is_typeset(control):
    assert control.counts["math_source"] > 10
    assert control.counts["math_rendered"] >= control.counts["math_source"], control.problems["math"]
    assert not control.problems["math"] and not control.problems["offline"] and not control.problems["console"]


@pytest.mark.parametrize("name", list(BREAKAGES))
def test_breakage_is_reported(broken_reports, control, name):
    """Each breakage adds a complaint, under the right aspect, that the unmodified page does not have."""
    _how, _payload, aspect, text = BREAKAGES[name]
    report = broken_reports(name)
    already = set(control.problems.get(aspect, []))
    new = [c for c in report.problems.get(aspect, []) if c not in already]
    assert new, f"{name}: broken on purpose, yet nothing new was reported under {aspect!r}: {report.problems}"
    assert any(text.lower() in c.lower() for c in new), (
        f"{name}: expected a complaint mentioning {text!r} under {aspect!r}, got {new}"
    )


def test_missing_page_is_reported(broken_book, browser_context):
    root, base = broken_book
    report = bookcheck.check_page(browser_context, base, root, "chapters/not_built.html", shots=None)
    assert any("not in the build" in m for m in report.problems["load"]), report.problems


def test_missing_book_gives_a_clear_message(tmp_path):
    """BOOK_HTML pointing at nothing fails with a message naming the folder and `make book`."""
    import subprocess

    env = {**__import__("os").environ, "BOOK_HTML": str(tmp_path / "nowhere")}
    out = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
         str(Path(__file__).with_name("test_pages.py")) + "::test_search_finds_adjoint"],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=120,
    )
    assert out.returncode != 0
    assert "The built book is missing" in out.stdout and "make book" in out.stdout, out.stdout[-2000:]


# ---------------------------------------------------------------- pure helpers
def test_raw_tex_detection():
    assert bookcheck.raw_tex_in(r"the twist \(\mathcal V_s\) is") != []
    assert bookcheck.raw_tex_in(r"\begin{bmatrix} 1 \end{bmatrix}") != []
    assert bookcheck.raw_tex_in("a table cell $P\\,$$J$ here") != []
    assert bookcheck.raw_tex_in("J_s maps joint rates to twists; it costs nothing.") == []


def test_alt_text_from_cell_code():
    code = 'fig, ax = plt.subplots()\nax.set_title(r"Columns of $J_s$ at $\\theta_0$")\nfig.suptitle(f"UR5 {n}")\n'
    assert offline_fixes.titles_from_code(code) == ["Columns of J_s at theta_0", "UR5"]
    assert offline_fixes.titles_from_code("plt.plot(x)") == []
    assert offline_fixes.titles_from_code("this is ( not python") == []


def test_alt_added_only_where_missing():
    frag = '<div><img id="a" src="x.png"><img alt="kept" src="y.png"></div>'
    fixed = offline_fixes.add_alt_to_html(frag, 'Animation: "arm"')
    assert '<img alt="Animation: &quot;arm&quot;" id="a" src="x.png">' in fixed
    assert '<img alt="kept" src="y.png">' in fixed


def test_alt_text_reads_as_words():
    assert offline_fixes.plain(r"The arm at $\theta = (0.5, 0.6)$ rad, $T_{sb}$, $\mathrm{Ad}_T$") == (
        "The arm at theta = (0.5, 0.6) rad, T_sb, Ad_T"
    )
