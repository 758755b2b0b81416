"""MyST -> slide Markdown conversion and the slide preprocessor (no browser, fast)."""

from __future__ import annotations

import re

import nbformat
import pytest
from tools import build_slides
from tools.slides import myst, reader
from tools.slides.preprocess import LIVE_DEMO_HTML, MystSlidesPreprocessor, auto_slide_type

LABELS = {
    "ch02-def-sj": "Definition (Space Jacobian)",
    "conventions": "Conventions and notation",
    "sec-columns": "Columns of the Jacobian",
}


def conv(text, **kw):
    return myst.convert_markdown(text, myst.Context(labels=dict(LABELS), **kw))


def test_definition_backtick_form_becomes_box_with_title_and_markdown_body():
    out = conv("```{prf:definition} Space Jacobian\n:label: ch02-def-sj\n\nThe **space** $J_s$ maps.\n```")
    assert '<div class="box box-definition">' in out
    assert "**Definition** (Space Jacobian)" in out
    assert "The **space** $J_s$ maps." in out
    assert ":label:" not in out and "```" not in out and "ch02-def-sj" not in out


def test_colon_form_and_yaml_options():
    out = conv(":::{prf:theorem} Columns\n---\nlabel: thm\nnonumber: true\n---\nBody $x$.\n:::")
    assert '<div class="box box-theorem">' in out and "**Theorem** (Columns)" in out
    assert "Body $x$." in out and "label" not in out and ":::" not in out


def test_nested_directives_four_backticks():
    src = "````{prf:theorem} T\n:label: t\nIntro\n```{math}\n:label: eq1\na = b \\\\ c = d\n```\nafter\n````"
    out = conv(src)
    assert out.count('class="box box-') == 1
    assert "$$\n\\begin{split}a = b \\\\ c = d\\end{split}\n$$" in out
    assert "after" in out and "{math}" not in out


def test_math_directive_with_environment_is_not_wrapped_twice():
    out = conv("```{math}\n\\begin{aligned} a &= b \\\\ c &= d \\end{aligned}\n```")
    assert out.count("\\begin{split}") == 0 and out.startswith("$$")


def test_proof_and_admonitions():
    out = conv(":::{prf:proof}\nBecause.\n:::\n\n```{warning} Common mistake\nThe notes are wrong.\n```\n\n"
               "```{note}\nA note.\n```\n\n```{tip}\nA tip.\n```\n\n```{important}\nKey.\n```\n\n"
               "```{admonition} Custom title\n:class: warning\nCustom body.\n```")
    for cls in ("box-proof", "box-warning", "box-note", "box-tip", "box-important"):
        assert f'class="box {cls}"' in out, cls
    assert "**Common mistake**" in out and "**Custom title**" in out and "&#8718;" in out
    assert out.count('class="box box-warning"') == 2  # the admonition with :class: warning


def test_exercise_is_try_it_and_solutions_vanish_even_across_cells():
    ctx = myst.Context(labels={})
    a = myst.convert_markdown("```{exercise} Compute it\n:label: ch02_ex1\nDo $x$.\n```\n\n```{solution-start} ch02_ex1\n:class: dropdown\n```\nSECRET one", ctx)
    assert "**Try it** (Compute it)" in a and "Do $x$." in a and "SECRET" not in a
    assert ctx.in_solution
    b = myst.convert_markdown("SECRET two", ctx)
    assert b == "" and ctx.in_solution
    c = myst.convert_markdown("SECRET three\n```{solution-end}\n```\nVisible again", ctx)
    assert "SECRET" not in c and "Visible again" in c and not ctx.in_solution
    d = myst.convert_markdown("```{solution} ch02_ex1\n:class: dropdown\nSECRET four\n```\nAfter.", ctx)
    assert "SECRET" not in d and "After." in d


def test_roles_become_plain_text():
    out = conv("See {doc}`conventions`, {ref}`the columns <sec-columns>`, {prf:ref}`ch02-def-sj`, "
               "{ref}`sec-columns`, {numref}`Figure %s <unknown-fig>`, {math}`x^2`, {unknownrole}`kept text`.")
    assert out == ("See Conventions and notation, the columns, Definition (Space Jacobian), "
                   "Columns of the Jacobian, Figure, $x^2$, kept text.")


def test_targets_comments_equation_labels_and_links():
    out = conv("(sec-columns)=\n## Columns\n% a comment\n$$ a = b $$ (eq-label)\n\n[see here](#sec-columns) "
               "and [](#sec-columns) and [web](https://example.org) and $[V](x)$")
    assert "(sec-columns)=" not in out and "comment" not in out and "eq-label" not in out
    assert "$$ a = b $$" in out
    assert "see here and Columns of the Jacobian" in out
    assert "[web](https://example.org)" in out
    assert "$[V](x)$" in out  # math is not a link


def test_code_fences_are_left_alone():
    src = "````markdown\n```{prf:definition} X\n:label: y\n```\n{ref}`z`\n````"
    assert conv(src) == src.replace("{ref}`z`", "{ref}`z`")
    assert "```{prf:definition}" in conv(src)


def test_split_at_headings_keeps_targets_with_heading_and_directives_whole():
    text = "Intro.\n\n(sec-a)=\n## A\n\n```{note}\n## not a heading\n```\n\n### B\ntext"
    pieces = reader.split_at_headings(text)
    assert len(pieces) == 3
    assert pieces[0] == "Intro."
    assert pieces[1].startswith("(sec-a)=\n## A") and "## not a heading" in pieces[1]
    assert pieces[2].startswith("### B")
    assert [auto_slide_type(p) for p in pieces] == ["-", "slide", "subslide"]
    assert auto_slide_type("```{prf:theorem} T\nx\n```") == "subslide"
    assert auto_slide_type("```{note}\nx\n```") == "-"


def _nb(cells):
    nb = nbformat.v4.new_notebook()
    nb.cells = cells
    return nb


def _code(src, tags=(), outputs=(), slide_type=None):
    c = nbformat.v4.new_code_cell(src)
    if tags:
        c.metadata["tags"] = list(tags)
    if slide_type:
        c.metadata["slideshow"] = {"slide_type": slide_type}
    c.outputs = [nbformat.from_dict(o) for o in outputs]
    return c


def _md(src, slide_type=None):
    c = nbformat.v4.new_markdown_cell(src)
    if slide_type:
        c.metadata["slideshow"] = {"slide_type": slide_type}
    return c


STDOUT = {"output_type": "stream", "name": "stdout", "text": "checked\n"}
STDERR = {"output_type": "stream", "name": "stderr", "text": "DeprecationWarning\n"}
PNG = {"output_type": "display_data", "data": {"image/png": "iVBORw0KGgo=", "text/plain": "<Figure>"}, "metadata": {}}


def test_preprocessor_cell_rules():
    nb = _nb([
        _md("(ch)=\n# Title\n\nIntro.\n\n## First section\ntext", slide_type=None),
        _code("import numpy", tags=["remove-cell"], outputs=[STDOUT]),
        _code("assert True; print('checked')", tags=["remove-input"], outputs=[STDOUT]),
        _code("plot()", tags=["remove-input"], outputs=[PNG, STDERR]),
        _code("J = 1", tags=["slide-show-code"]),
        _code("hidden()", tags=["hide-input"], outputs=[STDOUT]),
        _md("Speaker text.", slide_type="notes"),
        _md("Step two $x$.", slide_type="fragment"),
        _md("```{exercise}\n:label: e1\nTry.\n```\n```{solution-start} e1\n```\nSECRET"),
        _code("print('SECRET')", outputs=[{"output_type": "stream", "name": "stdout", "text": "SECRET\n"}]),
        _md("```{solution-end}\n```\n## After"),
        _code("w", outputs=[{"output_type": "display_data", "metadata": {},
                             "data": {"application/vnd.jupyter.widget-view+json": {"model_id": "x"}, "text/plain": "w"}}]),
        _code("anim", outputs=[{"output_type": "display_data", "metadata": {}, "data": {
            "text/html": '<link rel="stylesheet" href="https://cdn.example/fa.css"><div class="animation">A</div>'}}]),
    ])
    nb, res = MystSlidesPreprocessor().preprocess(nb, {})
    kinds = [(c.cell_type, c.metadata.get("slideshow", {}).get("slide_type")) for c in nb.cells]
    assert kinds == [
        ("markdown", "slide"), ("markdown", "slide"),  # title; "## First section" split off
        ("code", "-"),  # the figure of the remove-input cell, stderr dropped
        ("code", "-"),  # slide-show-code
        ("code", "-"),  # hide-input with output
        ("markdown", "notes"), ("markdown", "fragment"),
        ("markdown", "subslide"),  # the exercise
        ("markdown", "slide"),  # ## After
        ("code", "-"), ("code", "-"),
    ]
    text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    assert "SECRET" not in text and "**Try it**" in text and "(ch)=" not in text
    codes = [c for c in nb.cells if c.cell_type == "code"]
    assert all("SECRET" not in str(c.outputs) for c in codes)
    figure, shown, hidden, widget, anim = codes
    assert figure.metadata["transient"]["remove_source"] is True
    assert [o.output_type for o in figure.outputs] == ["display_data"]
    assert "transient" not in shown.metadata
    assert hidden.metadata["transient"]["remove_source"] is True and hidden.outputs[0].text == "checked\n"
    assert widget.outputs[0].data == {"text/html": LIVE_DEMO_HTML}
    assert "cdn.example" not in anim.outputs[0].data["text/html"] and "animation" in anim.outputs[0].data["text/html"]


def test_preprocessor_refuses_a_notebook_with_nothing_to_show():
    with pytest.raises(ValueError, match="no cell is left"):
        MystSlidesPreprocessor().preprocess(_nb([_code("x", tags=["remove-cell"])]), {})


@pytest.mark.parametrize("source", build_slides.deck_sources(), ids=lambda p: p.stem)
def test_every_chapter_converts_without_raw_myst_left(source):
    """Every directive and role of the real chapters is converted (none left as literal text)."""
    import jupytext

    nb = jupytext.read(source)
    ctx = myst.Context(labels=build_slides.all_labels())
    for cell in nb.cells:
        if cell.cell_type != "markdown":
            continue
        for piece in reader.split_at_headings(cell.source):
            out = myst.convert_markdown(piece, ctx)
            outside_code = re.sub(r"(?ms)^(`{3,}|~{3,})(?!\{).*?^\1\s*$", "", out)
            assert not re.search(r"^\s*(`{3,}|:{3,})\{", outside_code, re.M), out
            assert not re.search(r"\{[\w:-]+\}`", outside_code), out
            assert not re.search(r"^\s*\([^()\s]+\)=\s*$", outside_code, re.M), out
    assert not ctx.in_solution, "a {solution-start} without {solution-end}"


def test_skipped_prose_keeps_its_definition_results_and_warnings():
    from tools.slides.preprocess import piece_slide_type

    cell = ("Long prose the author skipped.\n\n```{prf:definition} D\n:label: d\nBody.\n```\n\n"
            "More prose.\n\n```{prf:proof}\nBecause.\n```\n\n```{tip}\nA tip.\n```\n\n## Next section\ntext")
    pieces = reader.split_cell(cell)
    assert len(pieces) == 6
    types = [piece_slide_type(p, k, "skip") for k, p in enumerate(pieces)]
    assert types == ["skip", "-", "skip", "subslide", "skip", "slide"]
    assert piece_slide_type(pieces[1], 1, "skip", boxes_before=1) == "subslide"
    assert [piece_slide_type(p, k, None) for k, p in enumerate(pieces)] == ["-", "-", "-", "subslide", "-", "slide"]
    assert [piece_slide_type(p, k, "notes") for k, p in enumerate(pieces)][-1] == "slide"
    # the re-serialised directive converts exactly like the original
    ctx = myst.Context()
    assert myst.convert_markdown(pieces[1], ctx) == myst.convert_markdown(
        "```{prf:definition} D\n:label: d\nBody.\n```", myst.Context())


def test_colon_directive_survives_splitting():
    pieces = reader.split_cell(":::{important}\n:class: x\nKey **fact**.\n:::\nafter")
    assert len(pieces) == 2
    out = myst.convert_markdown(pieces[0], myst.Context())
    assert 'class="box box-important"' in out and "Key **fact**." in out and ":class:" not in out


def test_inline_math_over_lines_is_joined_so_plus_is_not_a_list():
    from nbconvert.filters.markdown_mistune import markdown2html_mistune

    out = conv("Then $\\|J\\| = a\n+ b$, and $c$\n- a real item")
    assert "$\\|J\\| = a + b$" in out
    html = markdown2html_mistune(out)
    assert "<li>" not in html.split("a real item")[0].split("$c$")[0]
    assert "\\|J\\|" in html
