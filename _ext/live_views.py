"""Sphinx extension: live views mounted on the static book page, no kernel.

A MyST page writes::

    ```{live-view} planar_explorer
    :robot: planar_2r
    :theta: 0.3 1.2
    :frame: space
    ```

or ``{live-view} resolved_rate`` with ``:path:``, ``:method:``, ``:damping:``,
and, for any view, ``:caption:`` (MyST inline text) and ``:name:`` (a label):
the view then sits in a numbered figure (``<figure>`` with "Fig. 2.4" and the
caption, which is also the figure's accessible name) that the text refers to
with ``{numref}`label```. A live view without a caption is an error,
and gets a host ``<div class="jac-live" data-view=... data-model='JSON'>``
holding the model computed here by the library at build time
(``jacobians.widgets.live.MODELS[view]``: screw axes, home, joint axis points,
the initial state), plus one ``<script type="module">`` that imports
``_static/live/host.js`` and ``_static/live/<view>.js`` (``lib/jacobians/widgets/static/live/`` is
copied there by ``html_static_path``) relative to the page and renders the
view. Nothing loads from another host. A new view registers its model
builder in ``MODELS`` and its options in ``OPTIONS``; the 3-D views
(``columns_explorer``, ``gimbal_lock``) take theirs from ``jacobians.widgets.live_spatial``
(``SPATIAL_MODELS``) through ``live_views_spatial``, which reads their option texts.
"""

from __future__ import annotations

import html
import json
from typing import Any

from docutils import nodes
from docutils.parsers.rst import directives
from live_views_spatial import SPATIAL_VIEWS, spatial_model  # the 3-D views (chapters 4, 6), models from the library
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective

from jacobians.widgets.live import LIMIT, MODELS, ROBOTS, planar_model, resolved_rate_model

__all__ = ["VIEWS", "ROBOTS", "LIMIT", "planar_model", "resolved_rate_model", "host_html", "LiveView", "setup"]

VIEWS = (*MODELS, *SPATIAL_VIEWS)
LIVE_DIR = "_static/live"


def _angles(text: str) -> list[float]:
    try:
        return [float(t) for t in text.replace(",", " ").split()]
    except ValueError as exc:
        raise ValueError(f"Expected :theta: as angles in rad separated by spaces, got {text!r}") from exc


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError as exc:
        raise ValueError(f"Expected a whole number, got {text!r}") from exc


def _float(text: str) -> float:
    try:
        return float(text)
    except ValueError as exc:
        raise ValueError(f"Expected a number, got {text!r}") from exc


#: Directive option -> how its text becomes the model builder's keyword argument.
OPTIONS: dict[str, Any] = {"robot": str, "theta": _angles, "frame": str, "sweep": _int, "path": str,
                           "method": str, "damping": _float, "column": str, "rep": str,
                           "story": str}


def host_html(view: str, model: dict[str, Any], depth: int, uid: str) -> str:
    """The host element and its module script, for a page ``depth`` folders below the root."""
    if view not in VIEWS:
        raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
    base = ("../" * depth or "./") + LIVE_DIR  # a module specifier must start with ./ or ../
    data = html.escape(json.dumps(model, separators=(",", ":"), allow_nan=False), quote=True)
    return (
        f'<div class="jac-live" id="{uid}" data-view="{view}" data-model="{data}">'
        f"<noscript>This live figure needs JavaScript.</noscript></div>\n"
        f'<script type="module">import {{ mount }} from "{base}/host.js";\n'
        f'import view from "{base}/{view}.js";\n'
        f'mount(document.getElementById("{uid}"), view);</script>'
    )


def model_for(view: str, options: dict[str, str]) -> dict[str, Any]:
    """The model of ``view`` from the directive's option texts (ValueError on a bad one)."""
    if view not in VIEWS:
        raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
    if view in SPATIAL_VIEWS:  # their models read the option texts themselves (_ext/live_views_spatial.py)
        return spatial_model(view, options)
    kwargs = {k: OPTIONS[k](v) for k, v in options.items()}
    try:
        return MODELS[view](**kwargs)
    except TypeError as exc:
        raise ValueError(f"options {sorted(options)} do not all apply to {view}: {exc}") from exc


class LiveView(SphinxDirective):
    """``{live-view} <view>`` with the options of ``OPTIONS`` that its model builder takes."""

    required_arguments = 1
    option_spec = {**{k: directives.unchanged for k in OPTIONS},
                   "caption": directives.unchanged_required, "name": directives.unchanged_required}

    def run(self) -> list[nodes.Node]:
        view = self.arguments[0]
        options = {k: v for k, v in self.options.items() if k in OPTIONS}
        try:
            model = model_for(view, options)
        except ValueError as exc:
            raise self.error(f"live-view: {exc}") from exc
        serial = self.env.new_serialno("live-view")
        uid = f"jac-live-{self.env.docname.replace('/', '-')}-{serial}"
        depth = self.env.docname.count("/")
        raw = nodes.raw("", host_html(view, model, depth, uid), format="html")
        caption_text = self.options.get("caption")
        if not caption_text:
            raise self.error("live-view: give it a :caption: (and a :name: to refer to it): "
                             "a live figure is numbered like every figure, and its caption is its title")
        figure = nodes.figure("", raw, classes=["jac-live-figure"])
        inline, messages = self.state.inline_text(caption_text, self.lineno)
        figure += nodes.caption(caption_text, "", *inline)
        self.set_source_info(figure)
        if "name" in self.options:
            self.options["name"] = self.options["name"].strip()
            self.add_name(figure)
        return [figure, *messages]


def drop_captions_on_slides(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    """On a slide the heading names the view: its caption (book prose, 20-40 words) stays in the book.

    The decks share the book's doctrees, so this runs when the revealjs builder resolves them, before
    ``_ext/decks.py`` cuts them into slides."""
    if app.builder.name != "revealjs":
        return
    for fig in doctree.findall(lambda n: isinstance(n, nodes.figure) and "jac-live-figure" in n["classes"]):
        for cap in list(fig.findall(nodes.caption)):
            cap.parent.remove(cap)


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("live-view", LiveView)
    app.connect("doctree-resolved", drop_captions_on_slides, priority=400)
    return {"version": "1.1", "parallel_read_safe": True, "parallel_write_safe": True}
