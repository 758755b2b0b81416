"""The nbconvert preprocessor that turns an executed chapter into slide cells.

Runs before nbconvert's own reveal metadata preprocessor. For each cell:

* Markdown is split before every ``#``/``##``/``###`` heading and around
  every top-level directive, then converted by
  :func:`slides.myst.convert_markdown` (directives as styled boxes, roles as
  text, solutions dropped).
* Slide metadata the author gave (``slideshow.slide_type``) holds for the
  cell's first piece (see :func:`piece_slide_type` for the rest). Where there
  is none: a ``#`` or ``##`` heading starts a slide, a ``###`` heading or a
  definition / theorem / proposition / lemma / corollary / exercise starts a
  subslide, and so does a proof that follows other content in its cell;
  anything else continues the current slide. A cell marked
  ``skip`` keeps its prose off the slides but still shows the definitions,
  results, exercises and warnings in it (proofs on a subslide): the authoring
  guide uses ``skip`` for long prose, and a definition must reach the slides.
* Code is hidden unless the cell has the tag ``slide-show-code``. Cells tagged
  ``remove-cell`` and cells inside a solution are dropped; ``remove-output`` /
  ``hide-output`` drop the outputs; stderr streams (warnings) are dropped; a
  cell left with nothing to show is dropped.
* Widget views cannot run without a kernel (a dead slider on a slide is a
  bug), so they are replaced by a pointer to the live version, and the saved
  widget state is dropped (the deck then loads no widget manager).
* Any ``<link>`` or ``<script src>`` to another host left in an HTML output
  (e.g. matplotlib's jshtml font-awesome link) is removed: the deck links its
  local font-awesome copy instead.
"""

from __future__ import annotations

import copy
import re
from pathlib import Path
from typing import Any

import nbformat
from nbconvert.preprocessors import Preprocessor
from nbformat import NotebookNode
from traitlets import Dict, Unicode

from . import myst, reader

WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
SHOW_CODE_TAG = "slide-show-code"
_REMOTE_TAG = re.compile(
    r"<link\b[^>]*\bhref=[\"']?(?:https?:)?//[^>]*>|<script\b[^>]*\bsrc=[\"']?(?:https?:)?//[^>]*>\s*</script>",
    re.I,
)

LIVE_DEMO_HTML = (
    '<div class="live-demo">Interactive demo: run this chapter in JupyterLab '
    "(<code>make lab</code>) to move the sliders.</div>"
)


#: boxes shown even when the author marked their cell ``skip`` (meant for its prose)
SHOWN_EVEN_IF_SKIPPED = {"definition", "theorem", "proposition", "lemma", "corollary", "proof", "algorithm",
                         "exercise", "warning", "important"}


def _explicit_type(cell: NotebookNode) -> str | None:
    value = cell.get("metadata", {}).get("slideshow", {}).get("slide_type")
    return str(value) if value is not None else None


def _set_type(cell: NotebookNode, slide_type: str) -> None:
    cell.metadata.setdefault("slideshow", {})["slide_type"] = slide_type


def auto_slide_type(markdown: str) -> str:
    """Slide type for a Markdown piece without author metadata (see module doc)."""
    level = reader.leading_heading_level(markdown)
    if level in (1, 2):
        return "slide"
    if level == 3:
        return "subslide"
    name = reader.leading_directive(markdown)
    if name is not None:
        kind = name.split(":", 1)[-1]
        if kind in myst.KEY_KINDS or kind == "proof":
            return "subslide"
    return "-"


def piece_slide_type(piece: str, k: int, explicit: str | None, in_solution: bool = False,
                     boxes_before: int = 0) -> str:
    """Slide type of the ``k``-th piece of a Markdown cell whose metadata says ``explicit``.

    * no metadata: the first piece by :func:`auto_slide_type`, later pieces
      continue the slide unless they start with a heading;
    * ``skip``: the prose stays off the slides, but a definition, result,
      exercise or warning in the cell is shown: the first on the current
      slide, each further one on a subslide of its own (``boxes_before``
      counts those already shown from this cell), a proof on a subslide after
      its result; a later ``#``/``##`` heading starts a slide;
    * ``notes``: stays notes, except a later ``#``/``##`` heading;
    * anything else: the first piece has it, later pieces as with no metadata;
    * a proof that is not the first piece of its cell starts a subslide.
    """
    level = reader.leading_heading_level(piece)
    name = reader.leading_directive(piece)
    kind = name.split(":", 1)[-1] if name else None
    if in_solution:
        return "-"
    if explicit == "skip":
        if k > 0 and level in (1, 2):
            return "slide"
        if kind in SHOWN_EVEN_IF_SKIPPED:
            if kind == "proof":
                return "subslide"
            return "subslide" if boxes_before else "-"
        return "skip"
    if explicit == "notes":
        return "slide" if (k > 0 and level in (1, 2)) else "notes"
    if k == 0:
        return explicit if explicit is not None else auto_slide_type(piece)
    if level:
        return auto_slide_type(piece)
    if kind == "proof":
        return "subslide"  # a derivation gets its own room below its result
    return "-"


class MystSlidesPreprocessor(Preprocessor):
    """Apply the MyST conversion and the slide rules above to a whole notebook."""

    labels = Dict(help="label -> text shown for a reference to it").tag(config=True)
    source_dir = Unicode("", help="folder of the chapter source (for local images)").tag(config=True)
    asset_prefix = Unicode("", help="prefix of image files copied next to the deck").tag(config=True)

    def preprocess(self, nb: NotebookNode, resources: dict[str, Any]) -> tuple[NotebookNode, dict[str, Any]]:
        ctx = myst.Context(
            labels=dict(self.labels),
            source_dir=Path(self.source_dir) if self.source_dir else None,
            asset_prefix=self.asset_prefix,
        )
        cells = []
        for cell in nb.cells:
            if cell.cell_type == "markdown":
                cells.extend(self._markdown(cell, ctx))
            elif cell.cell_type == "code":
                kept = self._code(cell, ctx)
                if kept is not None:
                    cells.append(kept)
            # raw cells are not slide material
        if not any(_explicit_type(c) not in ("skip", "notes") for c in cells):
            raise ValueError("no cell is left to show on a slide")
        nb.cells = cells
        nb.metadata.pop("widgets", None)  # no widget view is left to render
        resources.setdefault("slides", {})
        resources["slides"]["images"] = ctx.images
        resources["slides"]["warnings"] = ctx.warnings
        return nb, resources

    # -------------------------------------------------------------- markdown
    def _markdown(self, cell: NotebookNode, ctx: myst.Context) -> list[NotebookNode]:
        explicit = _explicit_type(cell)
        out = []
        boxes = 0
        for k, piece in enumerate(reader.split_cell(cell.source)):
            was_in_solution = ctx.in_solution
            text = myst.convert_markdown(piece, ctx)
            if not text.strip():
                continue
            new = nbformat.v4.new_markdown_cell(text)
            new.metadata = copy.deepcopy(dict(cell.metadata)) if k == 0 else {}
            slide_type = piece_slide_type(piece, k, explicit, was_in_solution, boxes)
            if slide_type == "slide":
                boxes = 0
            elif explicit == "skip" and slide_type in ("-", "subslide"):
                boxes += 1
            _set_type(new, slide_type)
            out.append(new)
        return out

    # -------------------------------------------------------------- code
    def _code(self, cell: NotebookNode, ctx: myst.Context) -> NotebookNode | None:
        if ctx.in_solution:
            return None
        tags = set(cell.metadata.get("tags", []))
        if "remove-cell" in tags:
            return None
        cell = copy.deepcopy(cell)
        if "remove-output" in tags or "hide-output" in tags:
            cell.outputs = []
        outputs = []
        for out in cell.get("outputs", []):
            if out.output_type == "stream" and out.get("name") == "stderr":
                continue
            if out.output_type == "error":
                continue
            if out.output_type in ("display_data", "execute_result"):
                data = out.get("data", {})
                if WIDGET_MIME in data:
                    out = nbformat.v4.new_output("display_data", data={"text/html": LIVE_DEMO_HTML})
                elif "text/html" in data:
                    data["text/html"] = _REMOTE_TAG.sub("", _as_text(data["text/html"]))
            outputs.append(out)
        cell.outputs = outputs
        show_code = SHOW_CODE_TAG in tags and "remove-input" not in tags
        if (
            "remove-input" in tags
            and _explicit_type(cell) is None
            and all(o.output_type == "stream" for o in outputs)
        ):
            return None  # a hidden check cell: its printed "checked" line is not slide material
        if not show_code:
            cell.metadata.setdefault("transient", {})["remove_source"] = True
        if not show_code and not outputs:
            return None
        if _explicit_type(cell) is None:
            _set_type(cell, "-")
        return cell


def _as_text(value: str | list[str]) -> str:
    return "".join(value) if isinstance(value, list) else value
