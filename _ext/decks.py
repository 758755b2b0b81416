"""Sphinx extension: lecture decks from the chapter sources, by the book's own toolchain.

The decks are a second Sphinx build of the same sources with the ``revealjs``
builder of ``sphinx-revealjs`` (``tools/build_slides.py`` runs it after the
book). Both builds load this extension and ``sphinx_revealjs`` with the same
configuration, so the deck build reuses the book's pickled environment: no
page is read or executed again, and every directive, role, cross-reference
and number on a slide is the one the book resolved.

What a slide shows (:func:`to_slides`, run on ``doctree-resolved`` for the
``revealjs`` builder only; the book's pages are untouched):

* one slide per ``##``/``###`` heading, per cell whose slide type is
  ``slide`` or ``subslide``, and per ``{slide} Title`` block; every slide has
  a heading (the block's title, else the section's);
* the book's *display* material of cells not typed ``skip``: display math,
  figures and images, code-cell outputs (images, HTML, and displayed
  formulas of a cell typed for the slides or tagged ``slide-only``; never a
  text printout; code only with the tag
  ``slide-show-code``; a cell tagged ``slide-only`` shows in the deck and
  not in the book), definitions,
  theorems and propositions (proofs, exercises, solutions and admonitions stay
  in the book);
* words only from ``{slide}`` blocks: slide-only text written beside the book
  text in the chapter source (the book shows nothing of it). Book prose never
  reaches a slide; it is what the book is for. A statement of more than
  :data:`STATEMENT_WORDS` words shows as its number, title and display
  equations, and goes in full into the speaker notes;
* speaker notes from ``{slide-notes}`` blocks (``:minutes:`` the rough time),
  also invisible in the book, and from cells typed ``notes``;
* a cell typed ``fragment`` appears on the next key press.

Cross-references on a slide point to the book's page (the deck sits in
``slides/`` of the built book), so a reference opens the text it names.
"""

from __future__ import annotations

import os
import posixpath
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.application import Sphinx
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

from jacobians.plotting.animation import SLIDE_MIME

logger = logging.getLogger(__name__)

BUILDER = "revealjs"
#: reveal.js canvas, the size the decks are designed and tested at
WIDTH, HEIGHT = 1280, 720
#: the decks' own CSS and script (not in the book's _static)
STATIC = Path(__file__).resolve().parent / "decks_static"


class slide_cell(nodes.Element, nodes.Invisible):
    """Where a Markdown cell starts, with its slide type (``slideshow.slide_type``)."""


class slide_only(nodes.General, nodes.Element):
    """Content written for the deck (``{slide}``); ``title`` starts a new slide."""


class slide_notes(nodes.General, nodes.Element):
    """Speaker notes (``{slide-notes}``); not shown in the book."""


def _skip(self: Any, node: nodes.Node) -> None:
    raise nodes.SkipNode


def _visit_notes(self: Any, node: nodes.Element) -> None:
    if self.builder.name != BUILDER:
        raise nodes.SkipNode
    self.body.append('<aside class="notes">\n')
    if node.get("minutes"):
        self.body.append(f'<p class="minutes">About {node["minutes"]} min.</p>\n')


def _depart_notes(self: Any, node: nodes.Element) -> None:
    self.body.append("</aside>\n")


def _visit_only(self: Any, node: nodes.Element) -> None:
    if self.builder.name != BUILDER:
        raise nodes.SkipNode


def _depart_only(self: Any, node: nodes.Element) -> None:
    pass


class SlideDirective(SphinxDirective):
    """``{slide} [Title]``: text for the deck only; with a title it opens a new slide."""

    has_content = True
    optional_arguments = 1
    final_argument_whitespace = True

    def run(self) -> list[nodes.Node]:
        node = slide_only(title=self.arguments[0] if self.arguments else "")
        self.set_source_info(node)
        if self.arguments:
            textnodes, _ = self.state.inline_text(self.arguments[0], self.lineno)
            node["title_nodes"] = len(textnodes)
            node += nodes.rubric("", "", *textnodes, classes=["slide-title"])
        node += self.parse_content_to_nodes()
        return [node]


class SlideNotesDirective(SphinxDirective):
    """``{slide-notes}``: speaker notes for the slide it sits in (``:minutes:`` its rough time)."""

    has_content = True
    option_spec = {"minutes": directives.unchanged}

    def run(self) -> list[nodes.Node]:
        node = slide_notes(minutes=self.options.get("minutes", ""))
        self.set_source_info(node)
        node += self.parse_content_to_nodes()
        return [node]


# ---------------------------------------------------------------- cell markers


_MONTHS = ("January", "February", "March", "April", "May", "June", "July", "August", "September", "October",
           "November", "December")


def title_date(setting: str, environ: dict[str, str] | None = None) -> str:
    """The date or term on a deck's title slide: ``decks_date`` (``_config.yml``), else ``COURSE_DATE`` from
    the environment, else the month and year of the build (``SOURCE_DATE_EPOCH`` when set, as the book's
    footer: ``_ext/publishing.py``), e.g. "November 2026"."""
    import publishing

    env = dict(os.environ) if environ is None else environ
    chosen = str(setting or env.get("COURSE_DATE") or "").strip()
    if chosen:
        return chosen
    year, month, _ = publishing.build_date(env).split("-")
    return f"{_MONTHS[int(month) - 1]} {year}"


def _patch_slide_players() -> None:
    """An animation's player drawn for the slides (:data:`SLIDE_MIME`, ``jacobians.plotting.animation``) is
    HTML to myst-nb: the decks pick it before the book's player (:func:`configure`), the book never does."""
    from myst_nb.core.render import NbElementRenderer

    original = NbElementRenderer.render_mime_type
    if getattr(original, "_decks", False):
        return

    def render_mime_type(self: Any, data: Any) -> Any:
        if data.mime_type == SLIDE_MIME:
            return self.render_text_html(data)
        return original(self, data)

    render_mime_type._decks = True  # type: ignore[attr-defined]
    NbElementRenderer.render_mime_type = render_mime_type


def _patch_markdown_cells() -> None:
    """Keep each Markdown cell's slide type in the doctree (myst-nb drops Markdown cell metadata)."""
    from myst_nb.core.render import MditRenderMixin

    original = MditRenderMixin.render_nb_cell_markdown
    if getattr(original, "_decks", False):
        return

    def render_nb_cell_markdown(self: Any, token: Any) -> None:
        meta = token.meta.get("metadata", {}) or {}
        kind = (meta.get("slideshow") or {}).get("slide_type", "-")
        self.current_node.append(slide_cell(slide_type=kind))
        original(self, token)

    render_nb_cell_markdown._decks = True  # type: ignore[attr-defined]
    MditRenderMixin.render_nb_cell_markdown = render_nb_cell_markdown


# ---------------------------------------------------------------- doctree -> slides


#: a code cell with this tag shows its output in the deck only (a worked example's numbers as a matrix,
#: where the book prints them in a sentence or a printout)
SLIDE_ONLY_TAG = "slide-only"
DISPLAY_PRF = {"definition_node", "theorem_node", "proposition_node", "corollary_node", "lemma_node"}
#: one idea a slide, about 40 words: a statement longer than this (words, math not counted) shows on a slide
#: as its number, title and display equations, and the speaker notes carry it in full
STATEMENT_WORDS = 20


def _words(node: nodes.Node) -> int:
    """Words of a node's text, math not counted."""
    count = 0
    for text in node.findall(nodes.Text):
        parent = text.parent
        inside_math = False
        while parent is not None:
            if isinstance(parent, nodes.math | nodes.math_block):
                inside_math = True
                break
            parent = parent.parent
        if not inside_math:
            count += sum(1 for w in text.astext().split() if any(c.isalnum() for c in w))
    return count


def _statement_in_full(statement: nodes.Element) -> nodes.Element:
    """A statement's full text for the speaker notes: plain paragraphs and equations (no ids, no numbers)."""
    kind = str(statement.get("realtype", "statement")).capitalize()
    box = nodes.container("", nodes.paragraph("", f"{kind}{statement.get('title', '')}, in full:"),
                          classes=["statement-in-full"])
    content = next(iter(statement.findall(nodes.section)), None)
    for child in (content.children if content is not None else []):
        copy = child.deepcopy()
        for inner in copy.findall(nodes.Element):
            inner["ids"] = []
            if isinstance(inner, nodes.math_block):
                inner["number"] = None
                inner["label"] = None
        box += copy
    return box


def _short_statement(statement: nodes.Element) -> nodes.Element:
    """A long statement as a slide shows it: its number and title, and its display equations only."""
    short = statement.deepcopy()
    for content in list(short.findall(nodes.section)):
        equations = [m.deepcopy() for m in content.findall(nodes.math_block)]
        if not equations:
            # no display equation: the statement's formulas are inline; its first block that holds one
            # shows them, each list item's with its label (its bold or italic words)
            first = next((c for c in content.children
                          if not isinstance(c, nodes.title) and any(True for _ in c.findall(nodes.math))), None)
            equations = _formulas_of(first) if first is not None else []
        del content[:]
        if equations:
            content += equations
        else:
            content.parent.remove(content)
    short["classes"] = [*short.get("classes", []), "statement-short"]
    return short


_RELATION = re.compile(r"=|<|>|\\(?:in|iff|ne|neq|le|leq|ge|geq|to|mapsto|subset|approx|equiv|Rightarrow)\b")
#: the words of a statement's first clause that its short form shows (more: its formulas instead)
CLAUSE_WORDS = 8
_CLAUSE_END = re.compile(r"[.:;](?:\s|$)")


def _first_clause(paragraph: nodes.Element) -> nodes.paragraph:
    """A paragraph up to the end of its first clause (``.``, ``:`` or ``;`` outside math), as one line."""
    line = nodes.paragraph(classes=["statement-formulas"])
    for child in paragraph.children:
        if isinstance(child, nodes.Text):
            m = _CLAUSE_END.search(str(child))
            if m:
                line += nodes.Text(str(child)[:m.start()].rstrip() + ".")
                return line
        line += child.deepcopy()
    return line


def _formulas_of(block: nodes.Element) -> list[nodes.Node]:
    """The short form of a statement whose formulas are inline: a list shows, per item, its label (its
    bold or italic words) and its formulas that state a relation; a paragraph its first clause."""
    if not isinstance(block, nodes.Sequential):
        para = block if isinstance(block, nodes.paragraph) else next(iter(block.findall(nodes.paragraph)), None)
        if para is None:
            return []
        clause = _first_clause(para)
        if _words(clause) <= CLAUSE_WORDS:
            return [clause]
        # a long clause: its formulas that state a relation, else its first words
        maths = [m.deepcopy() for m in para.findall(nodes.math) if _RELATION.search(m.astext())]
        if maths:
            line = nodes.paragraph(classes=["statement-formulas"])
            for k, m in enumerate(maths[:3]):
                if k:
                    line += nodes.Text(",  ")
                line += m
            return [line]
        words = clause.astext().split()
        return [nodes.paragraph("", " ".join(words[:CLAUSE_WORDS]) + " \N{HORIZONTAL ELLIPSIS}",
                                classes=["statement-formulas"])]
    lines: list[nodes.Node] = []
    for part in block.findall(nodes.list_item):
        maths = [m for m in part.findall(nodes.math)]
        maths = [m.deepcopy() for m in maths if _RELATION.search(m.astext())] or [m.deepcopy() for m in maths]
        if not maths:
            continue
        line = nodes.paragraph(classes=["statement-formulas"])
        label = next(iter(part.findall(lambda n: isinstance(n, nodes.strong | nodes.emphasis))), None)
        if label is not None:
            line += nodes.strong("", label.astext())
            line += nodes.Text(": ")
        for k, m in enumerate(maths):
            if k:
                line += nodes.Text(",  ")
            line += m
        lines.append(line)
    return lines


def _code_kind(node: nodes.Element) -> str:
    meta = node.get("cell_metadata") or {}
    return str((meta.get("slideshow") or {}).get("slide_type", "-"))


def _is_code_cell(node: nodes.Node) -> bool:
    return isinstance(node, nodes.container) and node.get("nb_element") == "cell_code"


def _events(section: nodes.Element, level: int) -> Iterator[tuple[str, Any]]:
    """The section's content in reading order: headings, cell starts and blocks."""
    for child in section.children:
        if isinstance(child, nodes.title):
            continue
        if isinstance(child, nodes.section):
            yield "heading", child
            yield from _events(child, level + 1)
        elif isinstance(child, slide_cell):
            yield "cell", child["slide_type"]
        elif _is_code_cell(child):
            yield "cell", _code_kind(child)
            yield "block", child
        elif isinstance(child, nodes.target):
            continue
        else:
            yield "block", child


def _code_for_slide(cell: nodes.Element) -> nodes.Element | None:
    """A code cell as a slide shows it: outputs that are pictures or HTML, code only if tagged."""
    tags = (cell.get("cell_metadata") or {}).get("tags", [])
    kinds: tuple[type, ...] = (nodes.image, nodes.raw)
    if _code_kind(cell) in ("slide", "subslide", "fragment") or SLIDE_ONLY_TAG in tags:
        kinds = (*kinds, nodes.math_block)
    keep = nodes.container("", classes=list(cell.get("classes", [])))
    for part in cell.findall(nodes.container):
        kind = part.get("nb_element", "")
        if kind == "cell_code_source" and "slide-show-code" in tags:
            keep += part.deepcopy()
        elif kind == "cell_code_output":
            out = part.deepcopy()
            for lit in list(out.findall(nodes.literal_block)):
                lit.parent.remove(lit)       # text printouts belong to the book
            # pictures, HTML, and displayed formulas (a worked example's matrix: ``display(Math(...))``) of a
            # cell the author put on the deck: typed for the slides, or tagged slide-only
            if any(True for _ in out.findall(lambda n: isinstance(n, kinds))):
                keep += out
    if not keep.children:
        return None
    return keep


def _display(block: nodes.Node) -> list[nodes.Node]:
    """What of a book block a slide shows (see the module docstring)."""
    if isinstance(block, nodes.math_block):
        return [_without_sentence_punctuation(block.deepcopy())]
    if isinstance(block, nodes.figure | nodes.image):
        copy = block.deepcopy()
        # a live view is a numbered figure around its host (``_ext/live_views.py``): mount it the deck's way
        for raw in list(copy.findall(nodes.raw)):
            raw.replace_self(_classic_live_view(raw))
        return [copy]
    if _is_code_cell(block):
        cell = _code_for_slide(block)
        return [cell] if cell is not None else []
    if type(block).__name__ in DISPLAY_PRF:
        copy = block.deepcopy()
        _equations_without_punctuation(copy)
        return [copy]
    if isinstance(block, nodes.raw):
        return [_classic_live_view(block.deepcopy())]
    if (isinstance(block, nodes.container) and block.get("nb_element") is None
            and "live-view" in block.get("classes", [])):
        copy = block.deepcopy()
        for raw in list(copy.findall(nodes.raw)):
            raw.replace_self(_classic_live_view(raw))
        return [copy]
    if isinstance(block, nodes.paragraph | nodes.bullet_list | nodes.enumerated_list | nodes.table
                  | nodes.block_quote | nodes.Admonition | nodes.comment | nodes.literal_block
                  | nodes.definition_list | nodes.rubric | nodes.line_block):
        return []
    if isinstance(block, nodes.container | nodes.compound):
        out: list[nodes.Node] = []
        for child in block.children:
            out.extend(_display(child))
        return out
    return []


#: punctuation a display formula keeps from the sentence around it in the book, at its end (before any
#: closing ``\\end{...}``, after any spacing command): a slide shows the formula alone
_TRAILING_PUNCTUATION = re.compile(
    r"(?:\\[,;:!]|\\quad|\\qquad|\\ |~|\s)*(?<!\\)[,;:.](?P<end>(?:\s|\\end\{[A-Za-z*]+\})*)$")


def strip_sentence_punctuation(latex: str) -> str:
    """``latex`` without the comma, semicolon, colon or full stop the sentence put at its end."""
    return _TRAILING_PUNCTUATION.sub(lambda m: m.group("end"), latex.rstrip()).rstrip()


def _without_sentence_punctuation(block: nodes.math_block) -> nodes.math_block:
    latex = block.astext()
    clean = strip_sentence_punctuation(latex)
    if clean != latex:
        block.children = []
        block += nodes.Text(clean)
    return block


def _equations_without_punctuation(node: nodes.Element) -> None:
    for block in list(node.findall(nodes.math_block)):
        _without_sentence_punctuation(block)


#: a live view's module script (``_ext/live_views.py``): a deck mounts its views with the classic script
#: ``_static/live/jac-live.js`` instead (built by esbuild from the same modules), which also works from disk
_LIVE_MODULE = re.compile(r'<script type="module">.*?</script>', re.S)
_LIVE_NOSCRIPT = re.compile(r"<noscript>.*?</noscript>", re.S)
LIVE_BUNDLE = "live/jac-live.js"
#: the live views' own rules on a slide (each view's ``deck.css``), bundled beside it
LIVE_STYLE = "live/jac-live.css"


def live_fallback(view: str) -> str:
    """What a live view's slide shows until (or unless) the view starts: what it is, and why it is not there."""
    what = view.replace("_", " ")
    return (f'<div class="jl-static"><p class="jl-static-title">Live view: {what}</p>'
            '<p>It starts when the deck\'s script <code>_static/live/jac-live.js</code> runs; if you read this, '
            "JavaScript is off or that file is missing next to the deck. The book's chapter shows the same "
            "view.</p></div>")


def _classic_live_view(raw: nodes.raw) -> nodes.raw:
    text = raw.astext()
    if 'class="jac-live"' not in text:
        return raw
    m = re.search(r'data-view="([^"]+)"', text)
    text = _LIVE_MODULE.sub("", text)
    text = _LIVE_NOSCRIPT.sub(live_fallback(m.group(1) if m else "view"), text)
    return nodes.raw("", text, format="html")


def _is_picture(node: nodes.Node) -> bool:
    if isinstance(node, nodes.image | nodes.raw | nodes.figure):
        return True
    return isinstance(node, nodes.Element) and any(
        True for _ in node.findall(lambda n: isinstance(n, nodes.image | nodes.raw)))


class _Slide:
    def __init__(self, title: nodes.Node | None, ids: list[str], anchor: str = ""):
        self.title = title
        self.ids = ids
        #: the id of the book's section this slide comes from (its small link to the book)
        self.anchor = anchor
        self.body: list[nodes.Node] = []
        self.notes: list[nodes.Node] = []
        #: holds display material of the book (not only slide text and notes)
        self.display = False
        #: holds a picture (figure, animation, live view) or a statement (definition, theorem): one a slide
        self.picture = False
        self.statement = False

    def empty(self) -> bool:
        return not self.body and not self.notes


def to_slides(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    """Rewrite a resolved doctree into one section per slide (revealjs builder only)."""
    if app.builder.name != BUILDER:
        # the book: slide text and notes are not on the page, so not in its search index either
        for node in list(doctree.findall(lambda n: isinstance(n, slide_only | slide_notes) or (
                _is_code_cell(n) and SLIDE_ONLY_TAG in ((n.get("cell_metadata") or {}).get("tags") or [])))):
            node.parent.remove(node)
        return
    top = next(iter(doctree.findall(nodes.section)), None)
    if top is None:
        return
    _book_links(doctree, docname)
    title = top[0].deepcopy() if top.children and isinstance(top[0], nodes.title) else nodes.title("", docname)
    slides: list[_Slide] = []
    current = _Slide(None, [])
    section_title: nodes.Node | None = None
    section_ids: list[str] = []
    kind = "-"

    def start(heading: nodes.Node | None, ids: list[str]) -> _Slide:
        slides.append(_Slide(heading, ids, section_ids[0] if section_ids else ""))
        return slides[-1]

    for event, value in _events(top, 1):
        if event == "heading":
            section_title = value[0].deepcopy() if value.children and isinstance(value[0], nodes.title) else None
            section_ids = list(value["ids"])
            current = start(section_title, section_ids)
            continue
        if event == "cell":
            kind = value
            # a new slide, unless this one holds only its heading, slide text and notes so far
            if kind in ("slide", "subslide") and current.display:
                current = start(section_title, section_ids)
            continue
        block = value
        if isinstance(block, slide_notes):
            current.notes.append(block.deepcopy())
            continue
        found_only = isinstance(block, slide_only)
        if found_only:
            if block.get("title"):
                rubric = block[0]
                heading = nodes.title("", "", *[c.deepcopy() for c in rubric.children])
                current = start(heading, [])
                body = [c.deepcopy() for c in block.children[1:]]
            else:
                body = [c.deepcopy() for c in block.children]
            for item in body:
                if isinstance(item, slide_notes):
                    current.notes.append(item)
                else:
                    current.body.append(item)
            continue
        if kind == "skip":
            # notes and slide-only text inside a skipped cell still count
            for inner in list(block.findall(slide_notes)) if isinstance(block, nodes.Element) else []:
                current.notes.append(inner.deepcopy())
            continue
        if kind == "notes":
            current.notes.append(nodes.container("", block.deepcopy(), classes=["book-notes"]))
            continue
        shown = _display(block)
        if isinstance(block, nodes.Element) and not found_only:
            for inner in block.findall(slide_notes):
                current.notes.append(inner.deepcopy())
        if not shown:
            continue
        picture = any(_is_picture(s) for s in shown)
        statement = any(type(s).__name__ in DISPLAY_PRF for s in shown)
        in_full: list[nodes.Node] = []
        for k, item in enumerate(shown):
            if type(item).__name__ in DISPLAY_PRF and isinstance(item, nodes.Element) and _words(
                    next(iter(item.findall(nodes.section)), item)) > STATEMENT_WORDS:
                shown[k] = _short_statement(item)
                in_full.append(_statement_in_full(item))
        # one idea a slide: a picture or a statement gets a slide of its own, with the section's heading
        if (picture and current.display) or current.picture or (statement and current.statement):
            current = start(current.title.deepcopy() if current.title is not None else section_title,
                            section_ids)
        current.notes.extend(in_full)
        if kind == "fragment":
            shown = [nodes.container("", s, classes=["fragment"]) for s in shown]
        current.body.extend(shown)
        current.display = True
        current.picture = current.picture or picture
        current.statement = current.statement or statement

    # title slide, then every slide with something on it
    new_top = nodes.section("", ids=list(top["ids"]), classes=["title-slide"])
    new_top += title
    new_top += nodes.paragraph("", app.config.decks_course or app.config.html_title or app.config.project,
                               classes=["deck-course"])
    who = " \N{MIDDLE DOT} ".join(t for t in (
        app.config.decks_lecturer or os.environ.get("COURSE_LECTURER") or app.config.author,
        title_date(app.config.decks_date)) if t)
    if who:
        new_top += nodes.paragraph("", who, classes=["deck-lecturer"])
    kept: list[_Slide] = []
    for slide in slides:
        authored = any(isinstance(n, slide_notes) for n in slide.notes)
        if not slide.body and not authored:
            if kept:   # the book's notes of a slide with nothing to show go to the slide before
                kept[-1].notes.extend(slide.notes)
            continue
        kept.append(slide)
    kept = _merge_thin_slides(kept)
    for slide in kept:
        _first_view_not_blank(slide)
    if kept and not _is_summary(kept[-1]):
        kept.append(_summary_slide(kept, lambda st: _statement_number(app, docname, st)))
    new_top += _title_notes(kept)
    for number, slide in enumerate(kept):
        # a slide of its own title has an id of its own (HTML writers number titles by their section's id)
        sec = nodes.section("", ids=list(slide.ids) or [f"slide-{number}"])
        if not slide.ids:  # and no section number (the writer would fall back to the chapter's)
            app.env.toc_secnumbers.setdefault(docname, {})[f"#slide-{number}"] = ()
        sec += slide.title if slide.title is not None else title.deepcopy()
        sec += _book_link(docname, slide.anchor)
        for item in slide.body:
            sec += item
        if slide.notes:
            box = slide_notes(minutes="")
            minutes = 0.0
            for note in slide.notes:
                if isinstance(note, slide_notes):
                    minutes += _minutes(note.get("minutes", ""))
                    box.extend(c.deepcopy() for c in note.children)
                else:
                    box += note
            if minutes:   # notes merged onto one slide: their times add up
                box["minutes"] = f"{minutes:g}"
            _one_key_point_one_question(box)
            sec += box
        new_top += sec
    # every display formula on a slide (book material or slide text) without the sentence's punctuation
    for block in list(new_top.findall(nodes.math_block)):
        parent = block.parent
        while parent is not None and not isinstance(parent, slide_notes):
            parent = parent.parent
        if parent is None:
            _without_sentence_punctuation(block)
    # sections inside blocks (sphinx-proof wraps a statement in one) are not slides
    for inner in list(new_top.findall(nodes.section)):
        if inner is not new_top and not isinstance(inner.parent, nodes.section):
            box = nodes.container("", *inner.children, classes=["slide-block"])
            inner.replace_self(box)
    doctree.children = []
    doctree += new_top


def _minutes(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return 0.0


#: the labels a note starts with; a slide's merged notes keep the first of each, the others read "Also"
_NOTE_LABELS = {"Key point": "Also", "Ask": "Or ask"}


def _one_key_point_one_question(box: nodes.Element) -> None:
    """Notes merged onto one slide say "Key point" and "Ask" once each: later ones are relabelled."""
    seen: set[str] = set()
    for para in box.findall(nodes.paragraph):
        first = next(iter(para.findall(nodes.Text)), None)
        if first is None:
            continue
        for label, again in _NOTE_LABELS.items():
            if str(first).lstrip().startswith(label):
                if label in seen:
                    first.parent.replace(first, nodes.Text(str(first).replace(label, again, 1)))
                seen.add(label)


def _title_notes(slides: list[_Slide]) -> slide_notes:
    """The title slide's notes: the lecture's plan (its sections in order) and its length by the notes."""
    total = sum(_minutes(n.get("minutes", "")) for s in slides for n in s.notes if isinstance(n, slide_notes))
    # headings as plain words (a heading's TeX, e.g. B(\phi), read as B(phi))
    plan = list(dict.fromkeys(re.sub(r"\\([A-Za-z]+)", r"\1", s.title.astext()).replace("{", "").replace("}", "")
                              for s in slides if s.title is not None))
    notes = slide_notes(minutes="")
    notes.append(nodes.paragraph("", f"This lecture: about {total:g} min by the slides' notes, {len(slides)} slides."))
    notes.append(nodes.paragraph("", "Plan: " + "; ".join(plan) + "."))
    return notes


#: a slide of words alone (no formula, picture, statement, table or output) with fewer words than this is a
#: heading and a sentence: it joins a neighbour (:func:`_merge_thin_slides`)
THIN_WORDS = 30
#: a slide that takes in a thin neighbour stays within this many words (one idea a slide: about 40)
MERGED_WORDS = 42


def _shows_material(slide: _Slide) -> bool:
    """True if a slide shows more than words: a display formula, a picture, a statement, a table, a view."""
    def material(n: nodes.Node) -> bool:
        return (isinstance(n, nodes.math_block | nodes.image | nodes.figure | nodes.raw | nodes.table)
                or type(n).__name__ in DISPLAY_PRF or _is_code_cell(n))
    return any(material(b) or (isinstance(b, nodes.Element) and any(True for _ in b.findall(material)))
               for b in slide.body)


def _slide_words(slide: _Slide) -> int:
    return sum(_words(b) for b in slide.body) + (_words(slide.title) if slide.title is not None else 0)


def _merge_thin_slides(slides: list[_Slide]) -> list[_Slide]:
    """A thin slide (words alone, fewer than :data:`THIN_WORDS`) joins its neighbour: the slide before it
    if that one is not a picture and the two stay within :data:`MERGED_WORDS`, else the slide after it on
    the same terms if it is of the same section of the book. Its heading goes with it as the bold start of
    its text (unless the two share it), its notes and minutes join the neighbour's. A thin slide with no
    such neighbour stays (the deck tests name it: it needs content of its own in the chapter's markup)."""
    out = list(slides)
    k = 0
    while k < len(out):
        thin = out[k]
        if _shows_material(thin) or not thin.body or _slide_words(thin) >= THIN_WORDS:
            k += 1
            continue
        host = None
        for j in (k - 1, k + 1):
            if j == k + 1 and j < len(out) and out[j].anchor != thin.anchor:
                continue   # a slide opens its section: what comes before it does not go under its heading
            if 0 <= j < len(out) and not out[j].picture and _slide_words(out[j]) + _slide_words(thin) <= MERGED_WORDS:
                host = j
                break
        if host is None:
            k += 1
            continue
        other = out[host]
        same = (thin.title is not None and other.title is not None and thin.title.astext() == other.title.astext())
        body = [b.deepcopy() for b in thin.body]
        if not same and thin.title is not None and body and isinstance(body[0], nodes.paragraph):
            lead = re.sub(r"^[\d.]+\s*", "", thin.title.astext()).strip()   # without its section number
            body[0].insert(0, nodes.Text(" "))
            body[0].insert(0, nodes.strong("", lead + ":"))
        if host < k:
            other.body.extend(body)
            other.notes.extend(thin.notes)
        else:
            other.body[0:0] = body
            other.notes[0:0] = thin.notes
        other.display = other.display or thin.display
        del out[k]
        k = min(k, host)   # the grown neighbour is looked at again
    return out


def _first_view_not_blank(slide: _Slide) -> None:
    """A slide whose whole content is a build step opens on a bare heading: its first step shows at once."""
    if slide.body and all(isinstance(b, nodes.Element) and "fragment" in b.get("classes", []) for b in slide.body):
        slide.body[0]["classes"] = [c for c in slide.body[0]["classes"] if c != "fragment"]


_SUMMARY = re.compile(r"\b(summary|recap|in short|take-?aways?|what we (?:saw|learned))\b", re.I)
#: at most this many statements on the summary slide (one idea a slide: about 40 words)
SUMMARY_ITEMS = 5


def _is_summary(slide: _Slide) -> bool:
    return slide.title is not None and bool(_SUMMARY.search(slide.title.astext()))


def _statement_number(app: Sphinx, docname: str, statement: nodes.Element) -> str:
    """A statement's name as the book prints it, e.g. "Definition 6.1" (sphinx-proof's numbering)."""
    ids = statement.get("ids") or [""]
    number = app.env.toc_fignumbers.get(docname, {}).get(statement.get("countertype", ""), {}).get(ids[0], ())
    return f"{str(statement.get('realtype', 'statement')).title()} {'.'.join(map(str, number))}".strip()


def _summary_slide(slides: list[_Slide], name: Any) -> _Slide:
    """The deck's closing slide: the statements it set up (numbers and titles), linked to the book."""
    statements: list[nodes.Element] = []
    for slide in slides:
        for item in slide.body:
            for node in ([item] if type(item).__name__ in DISPLAY_PRF else []) + [
                    n for n in (item.findall(nodes.Element) if isinstance(item, nodes.Element) else [])
                    if type(n).__name__ in DISPLAY_PRF and n is not item]:
                statements.append(node)
    summary = _Slide(nodes.title("", "Summary"), [], slides[-1].anchor)
    items = nodes.bullet_list()
    for st in statements[:SUMMARY_ITEMS]:
        title = next(iter(st.findall(nodes.title)), None)
        text = title.astext() if title is not None else str(st.get("realtype", "Statement")).capitalize()
        para = nodes.paragraph("", name(st) + " ")
        para += [c.deepcopy() for c in title.children] if title is not None else nodes.Text(text)
        items += nodes.list_item("", para)
    if len(items):
        summary.body.append(nodes.paragraph("", "This lecture set up:"))
        summary.body.append(items)
        if len(statements) > SUMMARY_ITEMS:
            summary.body.append(nodes.paragraph("", f"and {len(statements) - SUMMARY_ITEMS} more in the book."))
    else:
        headings = [s.title.astext() for s in slides if s.title is not None]
        seen = list(dict.fromkeys(headings))[:SUMMARY_ITEMS]
        summary.body.append(nodes.paragraph("", "This lecture covered:"))
        summary.body.append(nodes.bullet_list("", *[nodes.list_item("", nodes.paragraph("", h)) for h in seen]))
    notes = slide_notes(minutes="2")
    notes += nodes.paragraph("", "Key point: the statements above are the lecture's working tools; each is "
                                 "stated in full, with its proof and a check by code, in the book.")
    notes += nodes.paragraph("", "Ask: which of these would you reach for first in the next exercise, and why?")
    summary.notes.append(notes)
    summary.display = True
    return summary


def _book_link(docname: str, anchor: str) -> nodes.raw:
    """The slide's small link to its section of the book, opened in a new tab."""
    href = "../" * (docname.count("/") + 1) + docname + ".html" + (f"#{anchor}" if anchor else "")
    return nodes.raw("", f'<a class="book-link" href="{href}" target="_blank" rel="noopener" '
                         f'title="This slide\'s section in the book (new tab)">book \u2197</a>', format="html")


def _book_links(doctree: nodes.document, docname: str) -> None:
    """Internal references open the book's page (the deck is in ``slides/`` of the book), in a new tab."""
    up = "../" * (docname.count("/") + 1)
    here = posixpath.dirname(docname)
    for ref in doctree.findall(nodes.reference):
        uri = ref.get("refuri", "")
        if not ref.get("internal") or not uri or "://" in uri:
            continue
        ref["target"] = "_blank"
        if uri.startswith("#"):
            target = posixpath.basename(docname) + ".html" + uri
            ref["refuri"] = up + posixpath.join(here, target)
        else:
            ref["refuri"] = up + posixpath.normpath(posixpath.join(here, uri))


# ---------------------------------------------------------------- configuration


#: scripts of the book's theme and extensions that a deck does not use
UNUSED_SCRIPTS = ("clipboard", "copybutton", "sphinx-book-theme", "togglebutton", "design-tabs", "thebe",
                  "documentation_options", "doctools", "sphinx_highlight", "searchtools", "language_data")
UNUSED_STYLES = ("copybutton", "togglebutton", "sphinx-thebe", "basic.css", "pygments")


def deck_assets(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    """A deck loads reveal.js, MathJax, its own CSS and script and the styles of the book's boxes."""
    if app.builder.name != BUILDER:
        return
    # no <link rel="next"/"prev"> to the book's pages: a deck stands alone (its book links are in the slides)
    context["next"] = context["prev"] = None
    context["script_files"] = [s for s in context.get("script_files", [])
                               if not any(u in str(getattr(s, "filename", s) or "") for u in UNUSED_SCRIPTS)]
    context["css_files"] = [c for c in context.get("css_files", [])
                            if not any(u in str(getattr(c, "filename", c) or "") for u in UNUSED_STYLES)]
    for css in ("_static/proof.css", "_static/sphinx-design.min.css"):
        if css not in [str(getattr(c, "filename", c)) for c in context["css_files"]]:
            context["css_files"].insert(2, css)


def configure(app: Sphinx, config: Any) -> None:
    """Settings of the deck build; the same in both builds, so the environment is shared."""
    html = [("revealjs", mime, prio) for mime, prio in (
        ("application/vnd.jupyter.widget-view+json", 10), ("application/javascript", 20), (SLIDE_MIME, 25),
        ("text/html", 30),
        ("image/svg+xml", 40), ("image/png", 50), ("image/gif", 60), ("image/jpeg", 70),
        ("text/markdown", 80), ("text/latex", 90), ("text/plain", 100))]
    # a chapter's figure carries a PNG (the book's) and an SVG drawn for the slides, its text enlarged
    # (``course.chapter.slide_svg``): the book's builders take the PNG, the decks the SVG
    book = [(builder, "image/png", 35) for builder in ("html", "dirhtml", "singlehtml", "epub")]
    config.nb_mime_priority_overrides = list(config.nb_mime_priority_overrides or []) + html + book
    config.revealjs_html_theme = "revealjs-basic"
    config.revealjs_style_theme = "white"
    config.revealjs_static_path = [str(STATIC)]
    config.revealjs_css_files = ["course_decks.css", LIVE_STYLE, "plugins/chalkboard/style.css"]
    config.revealjs_js_files = [("course_decks.js", {}), (LIVE_BUNDLE, {})]
    config.revealjs_script_conf = {
        "width": WIDTH, "height": HEIGHT, "margin": 0.04, "minScale": 0.2, "maxScale": 2.0,
        "hash": True, "hashOneBasedIndex": True, "slideNumber": "c/t", "transition": "none", "center": False,
        "pdfMaxPagesPerSlide": 1, "pdfSeparateFragments": False,
        # the presenter's toolkit: M (or a click on the slide number) the slide menu (its icons from its own
        # copy of Font Awesome, no CDN), T the pacing timer (course_decks.js),
        # W the chalkboard and C a pen on the slide (B stays reveal's black screen), Ctrl+Shift+F search,
        # Alt+click zoom, S the speaker notes
        "menu": {"side": "left", "numbers": True, "titleSelector": "h1, h2", "hideMissingTitles": False,
                 "loadIcons": True, "transitions": False, "themes": False, "openButton": False,
                 "openSlideNumber": True},
        "chalkboard": {"boardmarkerWidth": 4, "chalkWidth": 6, "toggleChalkboardButton": False,
                       "toggleNotesButton": False, "colorButtons": True,
                       "keyBindings": {"toggleChalkboard": {"keyCode": 87, "key": "W",
                                                            "description": "Toggle chalkboard"},
                                       "resetAll": {"keyCode": 0, "key": "", "description": "Reset all drawings"},
                                       "download": {"keyCode": 0, "key": "", "description": "Download drawings"}}},
    }
    config.revealjs_script_plugins = [
        {"name": "RevealNotes", "src": "revealjs/plugin/notes/notes.js"},
        {"name": "RevealSearch", "src": "revealjs/plugin/search/search.js"},
        {"name": "RevealZoom", "src": "revealjs/plugin/zoom/zoom.js"},
        {"name": "RevealMenu", "src": "plugins/menu/menu.js"},
        {"name": "RevealChalkboard", "src": "plugins/chalkboard/plugin.js"},
    ]


def setup(app: Sphinx) -> dict[str, Any]:
    app.setup_extension("sphinx_revealjs")
    _patch_markdown_cells()
    _patch_slide_players()
    visitors: dict[str, Any] = {"html": (_skip, None), "latex": (_skip, None), "text": (_skip, None),
                "man": (_skip, None), "texinfo": (_skip, None)}
    app.add_node(slide_cell, **visitors)
    app.add_node(slide_only, **{**visitors, "html": (_visit_only, _depart_only),
                                BUILDER: (_visit_only, _depart_only)})
    app.add_node(slide_notes, **{**visitors, "html": (_visit_notes, _depart_notes),
                                 BUILDER: (_visit_notes, _depart_notes)})
    # the title slide's course, lecturer and date: _config.yml (sphinx: config:) or the environment
    # (COURSE_TITLE, COURSE_LECTURER, COURSE_DATE: `make slides COURSE_LECTURER=...`); no rebuild on change;
    # an empty setting falls back to the environment, then to the book's title and author and the month and
    # year of the build (title_date)
    app.add_config_value("decks_course", os.environ.get("COURSE_TITLE", ""), "")
    app.add_config_value("decks_lecturer", os.environ.get("COURSE_LECTURER", ""), "")
    app.add_config_value("decks_date", os.environ.get("COURSE_DATE", ""), "")
    # the lectures: the decks cut and joined into lectures of 45-55 minutes (tools/build_slides.py reads it)
    app.add_config_value("decks_lectures", [], "")
    app.add_directive("slide", SlideDirective)
    app.add_directive("slide-notes", SlideNotesDirective)
    app.connect("config-inited", configure, priority=900)
    app.connect("doctree-resolved", to_slides)
    app.connect("html-page-context", deck_assets, priority=900)
    return {"version": "1.0", "env_version": 1, "parallel_read_safe": True, "parallel_write_safe": True}
