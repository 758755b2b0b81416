"""The deck build's rewrites of the book's material (``_ext/decks.py``), without a browser."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "_ext"))
import decks


@pytest.mark.parametrize(("latex", "want"), [
    (r"T = \begin{bmatrix} R & p \\ 0 & 1 \end{bmatrix} \in SE(3),", r"T = \begin{bmatrix} R & p \\ 0 & 1 \end{bmatrix} \in SE(3)"),
    ("a = b;", "a = b"),
    ("a = b \\quad :", "a = b"),
    ("\\begin{gathered} a, \\\\ b .\n\\end{gathered}", "\\begin{gathered} a, \\\\ b\n\\end{gathered}"),
    ("x = 1,\\qquad y = 2.", "x = 1,\\qquad y = 2"),
])
def test_a_display_formula_loses_the_sentences_punctuation_at_its_end(latex, want):
    assert decks.strip_sentence_punctuation(latex) == want


@pytest.mark.parametrize("latex", [r"a \,", r"a\;", r"a \dots", r"x_{1}", r"\{a, b\}", r"f(x)"])
def test_spacing_commands_and_plain_ends_are_kept(latex):
    assert decks.strip_sentence_punctuation(latex) == latex


def test_a_live_view_loses_its_module_script_and_keeps_a_static_text():
    from docutils import nodes

    raw = nodes.raw("", '<div class="jac-live" id="v1" data-view="gimbal_lock" data-model="{}">'
                        "<noscript>This live figure needs JavaScript.</noscript></div>\n"
                        '<script type="module">import { mount } from "../_static/live/host.js";\n'
                        'import view from "../_static/live/gimbal_lock.js";\n'
                        'mount(document.getElementById("v1"), view);</script>', format="html")
    out = decks._classic_live_view(raw).astext()
    assert "type=\"module\"" not in out and "import" not in out
    assert 'class="jl-static"' in out and "gimbal lock" in out and "jac-live.js" in out
    assert out.startswith('<div class="jac-live" id="v1" data-view="gimbal_lock"')


def test_a_live_view_in_its_numbered_figure_loses_its_module_script_on_a_slide():
    from docutils import nodes

    raw = nodes.raw("", '<div class="jac-live" id="v2" data-view="planar_explorer" data-model="{}">'
                        "<noscript>This live figure needs JavaScript.</noscript></div>\n"
                        '<script type="module">import { mount } from "../_static/live/host.js";</script>',
                    format="html")
    figure = nodes.figure("", raw, classes=["jac-live-figure"])
    (shown,) = decks._display(figure)
    out = "".join(r.astext() for r in shown.findall(nodes.raw))
    assert 'type="module"' not in out and 'class="jl-static"' in out and "planar explorer" in out
    assert raw.astext().count('type="module"') == 1  # the book's doctree keeps its module script


def test_a_slide_that_is_all_build_steps_shows_its_first_step_at_once():
    from docutils import nodes

    slide = decks._Slide(None, [])
    slide.body = [nodes.container("", nodes.paragraph("", f"step {k}"), classes=["fragment"]) for k in range(3)]
    decks._first_view_not_blank(slide)
    assert [("fragment" in b["classes"]) for b in slide.body] == [False, True, True]


def test_merged_notes_say_key_point_and_ask_once():
    from docutils import nodes

    box = decks.slide_notes(minutes="")
    for text in ("Key point: one.", "Ask: why?", "Key point: two.", "Ask: how?", "Key point: three."):
        box += nodes.paragraph("", text)
    decks._one_key_point_one_question(box)
    said = [p.astext() for p in box.findall(nodes.paragraph)]
    assert said == ["Key point: one.", "Ask: why?", "Also: two.", "Or ask: how?", "Also: three."]


def test_a_statement_without_display_math_keeps_its_formulas_in_its_box():
    from docutils import nodes

    items = nodes.bullet_list()
    for label, tex, words in (("revolute", r"\mathcal S = (\hat\omega, -\hat\omega\times q)", "a joint about"),
                              ("prismatic", r"\mathcal S = (0, \hat v)", "a joint along")):
        para = nodes.paragraph("", "A ")
        para += nodes.strong("", label)
        para += nodes.Text(f" {words} an axis: ")
        para += nodes.math("", tex)
        items += nodes.list_item("", para)
    lines = decks._formulas_of(items)
    assert [ln.astext() for ln in lines] == [r"revolute: \mathcal S = (\hat\omega, -\hat\omega\times q)",
                                             r"prismatic: \mathcal S = (0, \hat v)"]
    para = nodes.paragraph("", "")
    para += nodes.math("", "J_a")
    para += nodes.Text(" is defined wherever ")
    para += nodes.math("", r"B(\phi)")
    para += nodes.Text(" is invertible: for ZYX away from ")
    para += nodes.math("", r"\cos\phi_2 = 0")
    assert decks._formulas_of(para)[0].astext() == r"J_a is defined wherever B(\phi) is invertible."


def test_the_title_slides_date_is_the_setting_else_the_environment_else_the_builds_month():
    assert decks.title_date("Autumn term 2026", {"COURSE_DATE": "ignored"}) == "Autumn term 2026"
    assert decks.title_date("", {"COURSE_DATE": "Spring 2027"}) == "Spring 2027"
    # 1790812800 s after the epoch is 2026-10-01T00:00:00Z, and a second before it still September
    assert decks.title_date("", {"SOURCE_DATE_EPOCH": "1790812800"}) == "October 2026"
    assert decks.title_date("  ", {"SOURCE_DATE_EPOCH": "1790812799"}) == "September 2026"
