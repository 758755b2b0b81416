"""Sphinx extension: live views (issue #13) mounted on the static book page, no kernel.

A MyST page writes::

    ```{live-view} planar_explorer
    :robot: planar_2r
    :theta: 0.3 1.2
    :frame: space
    ```

and gets a host ``<div class="jac-live" data-view=... data-model='JSON'>``
holding the model computed here by the library at build time (screw axes,
home, joint axis points, initial angles, frame, reach, the singularity
threshold of the matplotlib explorer), plus one ``<script type="module">``
that imports ``_static/live/host.js`` and ``_static/live/<view>.js``
(``_theme/live/`` is copied there by ``html_static_path``) relative to the
page and renders the view. Nothing loads from another host.
"""

from __future__ import annotations

import html
import json
import math
from collections.abc import Sequence
from typing import Any

from docutils import nodes
from docutils.parsers.rst import directives
from live_views_spatial import SPATIAL_OPTIONS, SPATIAL_VIEWS, spatial_model  # the 3-D views (chapters 4, 6)
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective

from jacobians import robots
from jacobians.plotting import arm_reach

VIEWS = ("planar_explorer", *SPATIAL_VIEWS)
ROBOTS = {"planar_2r": robots.planar_2r, "planar_3r": robots.planar_3r}
FRAMES = ("space", "body", "geometric")
LIVE_DIR = "_static/live"
SING_TOL = 0.08  # x reach: jacobians.widgets.planar.PlanarArmExplorer.sing_tol
VEL_SCALE = 0.35  # drawn metres per m/s, as that explorer
LIMIT = 3.14  # the view's slider range, rad


def planar_model(robot: str, theta: Sequence[float] | None = None, frame: str = "space") -> dict[str, Any]:
    """The model of the planar explorer for ``robot`` at ``theta`` (rad), as the view reads it.

    >>> m = planar_model("planar_2r", [0.3, 1.2], "body")
    >>> len(m["S"]), len(m["S"][0]), m["theta"], m["frame"], round(m["sing_tol"], 3)
    (6, 2, [0.3, 1.2], 'body', 0.16)
    """
    if robot not in ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(ROBOTS)}, got {robot!r}")
    if frame not in FRAMES:
        raise ValueError(f"Expected frame one of {', '.join(FRAMES)}, got {frame!r}")
    chain = ROBOTS[robot]()
    n = chain.dof
    if theta is None:
        th = [0.5, 1.2, -0.8][:n]  # the matplotlib explorer's default
    else:
        th = [float(t) for t in theta]
        if len(th) != n:
            raise ValueError(f"Expected theta with {n} angles (rad) for {robot}, got {len(th)}: {list(theta)!r}")
        bad = [t for t in th if not math.isfinite(t) or abs(t) > LIMIT]
        if bad:
            raise ValueError(f"Expected theta as finite angles within ±{LIMIT} rad, got {bad!r}")
    reach = arm_reach(chain)
    return {
        "name": chain.name,
        "S": chain.screw_axes.tolist(),
        "M": chain.home.tolist(),
        "Q": chain.axis_points().tolist(),
        "theta": th,
        "frame": frame,
        "reach": reach,
        "sing_tol": SING_TOL * reach,
        "vel_scale": VEL_SCALE,
    }


def host_html(view: str, model: dict[str, Any], depth: int, uid: str) -> str:
    """The host element and its module script, for a page ``depth`` folders below the root."""
    if view not in VIEWS:
        raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
    base = ("../" * depth or "./") + LIVE_DIR  # a module specifier must start with ./ or ../
    data = html.escape(json.dumps(model, separators=(",", ":")), quote=True)
    return (
        f'<div class="jac-live" id="{uid}" data-view="{view}" data-model="{data}">'
        f"<noscript>This live figure needs JavaScript.</noscript></div>\n"
        f'<script type="module">import {{ mount }} from "{base}/host.js";\n'
        f'import view from "{base}/{view}.js";\n'
        f'mount(document.getElementById("{uid}"), view);</script>'
    )


def _angles(text: str) -> list[float]:
    try:
        return [float(t) for t in text.replace(",", " ").split()]
    except ValueError as exc:
        raise ValueError(f"Expected :theta: as angles in rad separated by spaces, got {text!r}") from exc


class LiveView(SphinxDirective):
    """``{live-view} <view>`` with ``:robot:``, ``:theta:`` and ``:frame:``."""

    required_arguments = 1
    option_spec = {"robot": directives.unchanged, "theta": directives.unchanged, "frame": directives.unchanged,
                   **SPATIAL_OPTIONS}

    def run(self) -> list[nodes.Node]:
        view = self.arguments[0]
        try:
            if view not in VIEWS:
                raise ValueError(f"Expected a live view one of {', '.join(VIEWS)}, got {view!r}")
            theta = _angles(self.options["theta"]) if "theta" in self.options else None
            if view in SPATIAL_VIEWS:
                model = spatial_model(view, self.options)
            else:
                model = planar_model(self.options.get("robot", "planar_2r"), theta, self.options.get("frame", "space"))
        except ValueError as exc:
            raise self.error(f"live-view: {exc}") from exc
        serial = self.env.new_serialno("live-view")
        uid = f"jac-live-{self.env.docname.replace('/', '-')}-{serial}"
        depth = self.env.docname.count("/")
        return [nodes.raw("", host_html(view, model, depth, uid), format="html")]


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("live-view", LiveView)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
