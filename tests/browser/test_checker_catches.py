"""The browser checks can fail: pages broken on purpose must be reported.

A scratch copy of the built book is made in a temp folder (symlinks to the
real build, so it is cheap); one page (the conventions page, cut to its first
section) is copied and broken in several ways, each in its own file, and
:func:`bookcheck.check_page` must name the breakage.
The sources and the real build are never touched.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import bookcheck
import math_prerender
import offline_fixes
import pytest
from conftest import ROOT

CDN = "https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-mml-chtml.js"
WIDE_TEX = " + ".join(f"a_{{{i}}} b_{{{i}}}" for i in range(1, 41))   # about 2000 px: wider than any screen
MEDIUM_TEX = " + ".join(f"a_{{{i}}} b_{{{i}}}" for i in range(1, 11))  # about 500 px: fits 1280, not 390

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
    "solution_under_a_cover": ("insert", '<div style="position:relative"><details class="sd-dropdown"><summary>Solution'
                               '</summary><p>out of reach</p></details><div style="position:absolute;left:0;top:0;'
                               'right:0;height:4em;z-index:5"></div></div>', "solutions", "covered"),
    # ---- page quality
    "overflowing_output": ("insert", '<div class="cell docutils container"><div class="cell_output docutils container">'
                           '<div style="width:1600px">an output wider than its box, broken on purpose</div></div></div>',
                           "overflow", "cell output is"),
    "overflowing_verified_box": ("insert", '<div class="admonition dropdown verified"><p class="admonition-title">'
                                 'Verified by code (1 check)</p><ul><li><span style="white-space:nowrap">'
                                 + "J_s(theta) = [Ad_{e^{[S1]theta1}}] S2, " * 12 + '</span></li></ul></div>',
                                 "overflow", 'box "Verified by code'),
    "box_cut_off_at_phone_width": ("insert", '<div class="admonition note" style="overflow:hidden">'
                                   '<p class="admonition-title">Note</p><div style="width:600px">'
                                   'fits at 1280 px, cut off at 390 px</div></div>', "overflow", "at 390 px a box"),
    "page_scrolls_sideways": ("insert", '<p><span style="white-space:nowrap">' + "unbreakable_" * 30 + '</span></p>',
                              "overflow", "whole page scrolls sideways"),
    "image_outside_figure": ("insert", '<div class="cell_output docutils container"><img src="../_static/favicon.svg" '
                             'alt="a plot of the arm"></div>', "figures", "image 'a plot of the arm' is not in a figure"),
    "animation_outside_figure": ("insert", '<div class="animation"><img id="_anim_imgY" alt="an animation of the arm" '
                                 'src="../_static/favicon.svg"><button onclick="void 0 /* play_animation */">play</button>'
                                 '</div>', "figures", "animation 'an animation of the arm' is not in a figure"),
    "figure_without_number": ("insert", '<figure><img src="../_static/favicon.svg" alt="a plot"><figcaption><p>'
                              'A caption without a number.</p></figcaption></figure>', "figures", "has no number"),
    "figure_without_caption": ("insert", '<figure><img src="../_static/favicon.svg" alt="a plot"></figure>',
                               "figures", "without a caption"),
    "correct_under_empty_answer": ("insert", '<div class="cell docutils container"><div class="cell_input docutils container">'
                                   '<div class="highlight-ipython3 notranslate"><div class="highlight"><pre>'
                                   'answer = None  # your answer here</pre></div></div></div>'
                                   '<div class="cell_output docutils container"><div class="jacobians-feedback '
                                   'jacobians-feedback-correct" role="status"><strong>&#10004; Correct</strong> '
                                   '(ch02_ex1)<br>Your column matches the reference.</div></div></div>',
                                   "verdicts", "empty answer `answer = None`"),
    "verdict_outside_solution": ("insert", '<div class="exercise admonition"><p class="admonition-title">Exercise</p>'
                                 '<p>Compute something.</p></div><div class="cell_output docutils container">'
                                 '<div class="jacobians-feedback jacobians-feedback-wrong" role="status"><strong>'
                                 '&#10008; Not yet</strong> (ch02_ex1)</div></div>', "verdicts",
                                 "outside a solution dropdown"),
    "display_math_clipped": ("insert", '<style>.broken-clip mjx-container { overflow: hidden !important; }</style>'
                             '<div class="math notranslate nohighlight broken-clip">\\[' + WIDE_TEX + '\\]</div>',
                             "phone_math", "cut off at"),
    "display_math_off_screen": ("insert", '<style>.broken-run, .broken-run mjx-container { overflow: visible !important; }'
                                '</style><div class="math notranslate nohighlight broken-run">\\[' + WIDE_TEX + '\\]</div>',
                                "phone_math", "runs off the"),
    "display_math_spills_out": ("insert", '<style>.broken-run, .broken-run mjx-container { overflow: visible !important; }'
                                '</style><div class="math notranslate nohighlight broken-run">\\[' + WIDE_TEX + '\\]</div>',
                                "overflow", "display-math box is"),
    "display_math_clipped_only_on_phones": ("insert", '<style>.broken-clip mjx-container { overflow: hidden !important; }'
                                            '</style><div class="math notranslate nohighlight broken-clip">\\['
                                            + MEDIUM_TEX + '\\]</div>', "phone_math", "at 390 px a display equation"),
    "negative_zero_in_output": ("insert", '<div class="cell_output docutils container"><div class="output text_plain">'
                                '<pre>array([ 0.5   , -0.    ,  1.    ])</pre></div></div>', "negative_zero", "-0."),
    "negative_zero_in_formula": ("insert", '<p>So <span class="math notranslate nohighlight">\\(x = -0.000\\)</span>.</p>',
                                 "negative_zero", "in a formula"),
    "negative_zero_in_prose": ("insert", '<p>The angle is \u22120.0 rad.</p>', "negative_zero", "\u22120.0"),
    "check_printout": ("insert", '<div class="cell_output docutils container"><div class="output stream '
                       'highlight-myst-ansi"><pre>\u2713 checked: e^{+[S1]\u03b81} on the right is not a twist</pre>'
                       '</div></div>', "check_lines", "\u2713 checked"),
}

# Pages changed in a way that is fine: each must add no complaint under the aspects named.
NOT_BROKEN = {
    "verdict_inside_solution": ('<div class="exercise admonition"><p class="admonition-title">Exercise</p><p>Compute.</p>'
                                '</div><div class="solution dropdown admonition"><p class="admonition-title">Solution</p>'
                                '<div class="cell_output docutils container"><div class="jacobians-feedback '
                                'jacobians-feedback-correct" role="status"><strong>&#10004; Correct</strong></div></div>'
                                '</div>', ("verdicts",)),
    "numbered_figure": ('<figure><img src="../_static/favicon.svg" alt="a plot"><figcaption><p><span class="caption-number">'
                        'Fig. 9.9 </span><span class="caption-text">A caption.</span></p></figcaption></figure>',
                        ("figures",)),
    "wide_math_that_scrolls": ('<div class="math notranslate nohighlight">\\[' + WIDE_TEX + '\\]</div>',
                               ("phone_math", "overflow")),
    "numbers_that_are_not_negative_zeros": ('<p>x = -0.5, 1e-05, \u22120.25, 10-0.3, v_0.0 and '
                                            '<span class="math notranslate nohighlight">\\(-0.05 + 0.0\\)</span></p>'
                                            '<div class="cell_output docutils container"><div class="output text_plain">'
                                            '<pre>array([-0.5  ,  0.   , -0.001])</pre></div></div>', ("negative_zero",)),
    "verified_box": ('<div class="admonition dropdown verified"><p class="admonition-title">Verified by code (1 check)</p>'
                     '<ul><li>The columns of J_s are the current screw axes<br><em>Checked by:</em> finite differences</li>'
                     '</ul></div>', ("check_lines", "overflow")),
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


def _first_section_only(html: str) -> str:
    """The page with only the first section under its title (and that section's entry in the page's contents):
    each check of a copy then reads a quarter of the conventions page, with its math, its title and the book
    around it."""
    start, end = html.find("<article"), html.find("</article>")
    assert 0 < start < end, "the page has no <article>"
    depth, parts = 0, []  # [id, start, end] of each section just under the page's own section
    for m in re.finditer(r'<section\b[^>]*>|</section>', html[start:end]):
        if m.group(0) == "</section>":
            if depth == 2:
                parts[-1][2] = start + m.end()
            depth -= 1
        else:
            depth += 1
            if depth == 2:
                sid = re.search(r'\bid="([^"]*)"', m.group(0))
                assert sid, f"a section without an id: {m.group(0)}"
                parts.append([sid.group(1), start + m.start(), None])
    assert len(parts) >= 2 and depth == 0, f"expected two sections or more under the title, got {[p[0] for p in parts]}"
    out = html[:parts[1][1]] + html[parts[-1][2]:]
    for sid, _s, _e in parts[1:]:
        out, n = re.subn(r'<li class="toc-h\d nav-item toc-entry"><a class="reference internal nav-link" href="#'
                         + re.escape(sid) + r'">[^<]*</a></li>', "", out)
        assert n >= 1, f"no entry of the page's contents links to #{sid}"
        assert f'href="#{sid}"' not in out, f"a link to the dropped section #{sid} is left"
    return out


def _break(html: str, how: str, payload: str | None) -> str:
    if how == "insert":  # after the page's title in the article (the first <h1> is a print-only copy)
        start = max(html.find("<article"), 0)
        new, n = re.subn(r"(<h1[^>]*>.*?</h1>)", lambda m: m.group(1) + payload, html[start:], count=1, flags=re.S)
        assert n == 1, "the page has no <h1> to insert after"
        return html[:start] + new
    if how == "insert_head":
        return html.replace("</head>", payload + "</head>", 1)
    if how == "drop_mathjax":  # the math left as TeX, as if nothing typeset it (at build time or in the page)
        new, n = re.subn(r'<span class="math notranslate nohighlight" data-tex="([^"]*)">.*?</mjx-container></span>',
                         lambda m: '<span class="math notranslate nohighlight">\\(' + m.group(1) + '\\)</span>', html,
                         flags=re.S)
        assert n > 0, "the page has no typeset inline math"
        return new
    raise ValueError(how)


@pytest.fixture(scope="module")
def broken_book(book_html, tmp_path_factory):
    """The scratch build, and the page (with math) that is broken in it."""
    base_page = "chapters/conventions.html"
    if not (book_html / base_page).exists():
        pytest.fail(f"{book_html / base_page} is missing: the breakage tests copy that page", pytrace=False)
    root = _overlay(book_html, tmp_path_factory.mktemp("broken-book"))
    original = _first_section_only((book_html / base_page).read_text(encoding="utf-8"))
    assert original.count('data-tex="') > 10 and 'class="math' in original, "the page copied should have typeset math"
    (root / "chapters" / "conventions.html").unlink()  # the control: the same page, trimmed the same way
    (root / "chapters" / "conventions.html").write_text(original, encoding="utf-8")
    for name, (how, payload, _aspect, _text) in BREAKAGES.items():
        (root / "chapters" / f"broken_{name}.html").write_text(_break(original, how, payload), encoding="utf-8")
    for name, (payload, _aspects) in NOT_BROKEN.items():
        (root / "chapters" / f"fine_{name}.html").write_text(_break(original, "insert", payload), encoding="utf-8")
    # the math inserted above is typeset as the build typesets the book's (_ext/math_prerender.py), except on
    # the page whose breakage is math that nothing typeset
    math_prerender.typeset(root / "_static", [p for p in sorted((root / "chapters").glob("*_*.html"))
                                              if not p.is_symlink() and p.name != "broken_no_mathjax.html"], {})
    with bookcheck.BookServer(root) as server:
        yield root, server.base


#: the aspects the second pass at phone width (390 px) reports under; a page broken under any other aspect is
#: checked at 1280 px only, where all of those are found (the tests read only the breakage's aspect)
PHONE_ASPECTS = {"overflow", "phone_math", "phone_figures"}


@pytest.fixture(scope="module")
def broken_reports(broken_book, browser_context):
    root, base = broken_book
    cache = {}

    def get(name):
        how, payload, _aspect, _text = BREAKAGES[name]
        # breakages that write the same page (one missing image, judged under two aspects) share one load
        first = next(n for n, b in BREAKAGES.items() if b[:2] == (how, payload))
        phone = any(b[2] in PHONE_ASPECTS for b in BREAKAGES.values() if b[:2] == (how, payload))
        if first not in cache:
            cache[first] = bookcheck.check_page(browser_context, base, root, f"chapters/broken_{first}.html",
                                                shots=None, settle_ms=100, phone=phone)
        return cache[first]

    return get


@pytest.fixture(scope="module")
def control(broken_book, browser_context):
    """The same page, cut the same way and otherwise unmodified, in the scratch copy: what it already complains
    about."""
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


@pytest.mark.parametrize("name, aspect", [("box_cut_off_at_phone_width", "overflow"),
                                          ("display_math_clipped_only_on_phones", "phone_math")])
def test_phone_only_faults_are_found_at_phone_width_only(broken_reports, name, aspect):
    """The layout checks run at both widths: a fault that only a phone shows is reported at 390 px, not 1280 px."""
    msgs = broken_reports(name).problems[aspect]
    assert any(m.startswith("at 390 px") for m in msgs), msgs
    assert not any(m.startswith("at 1280 px") for m in msgs), msgs


@pytest.mark.parametrize("name", list(NOT_BROKEN))
def test_fine_change_is_not_reported(broken_book, browser_context, control, name):
    """No false alarm: a change that is fine adds no complaint under the aspects it touches."""
    root, base = broken_book
    _payload, aspects = NOT_BROKEN[name]
    report = bookcheck.check_page(browser_context, base, root, f"chapters/fine_{name}.html", shots=None, settle_ms=100)
    for aspect in aspects:
        new = [c for c in report.problems.get(aspect, []) if c not in set(control.problems.get(aspect, []))]
        assert not new, f"{name}: a fine change, yet {aspect!r} complains: {new}"


def test_control_page_is_clean_under_the_page_quality_checks(control):
    """The conventions page has no output, figure or verdict: the new checks find nothing on it."""
    for aspect in ("overflow", "figures", "verdicts", "phone_math", "negative_zero", "check_lines"):
        assert not control.problems[aspect], (aspect, control.problems[aspect])


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
def test_negative_zero_detection():
    assert bookcheck.negative_zeros_in("array([ 0.    , -0.    ,  1.    ])")
    assert bookcheck.negative_zeros_in("the angle is \u22120.000 rad")
    assert bookcheck.negative_zeros_in("(1, -0, 2)")
    assert bookcheck.negative_zeros_in(r"\begin{bmatrix}1 & -0.000\end{bmatrix}", tex=True)
    assert not bookcheck.negative_zeros_in("x = -0.5, 1e-05, \u22120.25, 10-0.3, [-0.001]")
    assert not bookcheck.negative_zeros_in(r"x_{k-0.5} = -0.05", tex=True)


def test_check_line_detection():
    assert bookcheck.check_lines_in("\u2713 checked (sympy): [w]x = w \u00d7 x")
    assert bookcheck.check_lines_in("\u2713 4 conversions agree", monospace=True)
    assert not bookcheck.check_lines_in("\u2713 4 conversions agree")  # a tick in prose is fine
    assert not bookcheck.check_lines_in("Verified by code (2 checks)")


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
