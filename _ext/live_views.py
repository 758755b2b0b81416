"""Sphinx extension: live views mounted on the static book page, no kernel.

A MyST page writes::

    ```{live-view} planar_explorer
    :robot: planar_2r
    :theta: 0.3 1.2
    :frame: space
    ```

with the options of that view's spec (``jacobians.widgets.live.VIEWS[view].options``: each option's text
is parsed into the view's model builder's keyword), and, for any view, ``:caption:`` (MyST inline text)
and ``:name:`` (a label): the view then sits in a numbered figure (``<figure>`` with "Fig. 2.4" and the
caption, which is also the figure's accessible name) that the text refers to
with ``{numref}`label```. A live view without a caption is an error,
and gets a host ``<div class="jac-live" data-view=... data-model='JSON'>``
holding the model computed here by the library at build time (the spec's ``model``: screw axes, home,
joint axis points, the initial state), plus one ``<script type="module">`` that imports
``_static/live/host.js`` and ``_static/live/<view>/view.js`` relative to the page and renders the
view. The package's tree of modules (``jacobians/widgets/live/``, without its Python) is copied to
``_static/live/`` when the build ends. Nothing loads from another host. A new view is a new folder of
that package; nothing here changes.
"""

from __future__ import annotations

import html
import json
import shutil
from pathlib import Path
from typing import Any

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective

from jacobians.widgets.live import LIMIT, ROBOTS, VIEWS, angles, live_dir, planar_model, resolved_rate_model

__all__ = ["VIEWS", "ROBOTS", "LIMIT", "planar_model", "resolved_rate_model", "host_html", "model_for", "LiveView",
           "setup"]

LIVE_DIR = "_static/live"
_angles = angles  # the :theta: parser (tests call it by this name)
#: every option some view takes (a view rejects the others: ViewSpec.model_from_options)
OPTIONS = sorted({k for spec in VIEWS.values() for k in spec.options})


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
        f'import view from "{base}/{view}/view.js";\n'
        f'mount(document.getElementById("{uid}"), view);</script>'
    )


def model_for(view: str, options: dict[str, str]) -> dict[str, Any]:
    """The model of ``view`` from the directive's option texts (ValueError on a bad one)."""
    if view not in VIEWS:
        raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
    return VIEWS[view].model_from_options(options)


def copy_modules(app: Sphinx, exception: Exception | None) -> None:
    """The views' ES modules (``*.js`` of ``jacobians/widgets/live/``, no Python) into the HTML's ``_static/live``."""
    if exception is not None or app.builder.format != "html" or app.builder.name == "revealjs":
        return
    src, dest = live_dir(), Path(app.outdir) / LIVE_DIR
    for module in sorted(src.rglob("*.js")):
        target = dest / module.relative_to(src)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(module, target)


class LiveView(SphinxDirective):
    """``{live-view} <view>`` with the options of its spec (``OPTIONS`` is every view's)."""

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
    app.connect("build-finished", copy_modules)
    return {"version": "1.1", "parallel_read_safe": True, "parallel_write_safe": True}
