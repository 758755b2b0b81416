"""The models of the two 3-D live views (issue #13), for the ``{live-view}`` directive of ``live_views.py``.

* ``columns_explorer`` (chapter 4): the spatial 5R arm; which joints move which
  column of J_s and J_b. Options ``:robot:`` (``spatial_5r``), ``:theta:`` (rad),
  ``:column:`` (the watched column, 1-based).
* ``gimbal_lock`` (chapter 6): a spherical wrist (``zyz_wrist`` or ``zyx_wrist``),
  its ZYX or ZYZ coordinates φ, B(φ), det B, J_a next to J. Options ``:robot:``,
  ``:theta:`` (rad), ``:rep:`` (``zyx`` or ``zyz``).

The model holds what the library says about the chain (screw axes, home, joint
axis points, reach) and the initial state; the views compute what they draw
with ``_theme/live/kinematics.js``, which the browser tests keep equal to the
library. Colours are the course palette (:data:`jacobians.plotting.style.PALETTE`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from docutils.parsers.rst import directives

from jacobians import robots
from jacobians.plotting import arm_reach
from jacobians.plotting.style import COLUMN_COLORS, PALETTE

SPATIAL_VIEWS = ("columns_explorer", "gimbal_lock")
SPATIAL_OPTIONS = {"column": directives.unchanged, "rep": directives.unchanged}
COLUMN_ROBOTS = {"spatial_5r": robots.spatial_5r}
WRIST_TOOL = 0.3  # m, as jacobians.widgets.gimbal
WRISTS = {"zyz_wrist": lambda: robots.zyz_wrist(WRIST_TOOL), "zyx_wrist": lambda: robots.zyx_wrist(WRIST_TOOL)}
REPS = ("zyx", "zyz")
LIMIT = 3.14  # the sliders' range, rad (as the planar explorer)
GIMBAL_LIMIT_DEG = 180.0  # the gimbal view's sliders, degrees
NEAR_LOCK = 0.1  # |det B| below this: "near gimbal lock" (jacobians.widgets.gimbal's margin)
WRIST_SINGULAR = 1e-3  # sigma_min of J's angular rows below this: the wrist itself is singular


def _palette() -> dict[str, str]:
    keys = ("space", "body", "link", "joint", "muted", "analytic", "geometric", "singular", "warning", "ok")
    return {k: PALETTE[k] for k in keys if k in PALETTE}


def _theta(theta: Sequence[float] | None, default: Sequence[float], n: int, name: str, limit: float) -> list[float]:
    if theta is None:
        return [float(t) for t in default]
    th = [float(t) for t in theta]
    if len(th) != n:
        raise ValueError(f"Expected theta with {n} angles (rad) for {name}, got {len(th)}: {list(theta)!r}")
    bad = [t for t in th if not math.isfinite(t) or abs(t) > limit]
    if bad:
        raise ValueError(f"Expected theta as finite angles within ±{limit:.4g} rad, got {bad!r}")
    return th


def columns_model(robot: str = "spatial_5r", theta: Sequence[float] | None = None, column: int = 3) -> dict[str, Any]:
    """The model of the columns explorer, as ``_theme/live/columns_explorer.js`` reads it.

    >>> m = columns_model(theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=3)
    >>> len(m["S"]), len(m["S"][0]), m["column"], m["theta"][2], m["name"]
    (6, 5, 3, 0.9, 'spatial 5R')
    """
    if robot not in COLUMN_ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(COLUMN_ROBOTS)}, got {robot!r}")
    chain = COLUMN_ROBOTS[robot]()
    n = chain.dof
    th = _theta(theta, [0.3, -0.5, 0.9, 0.4, 0.3], n, robot, LIMIT)
    if isinstance(column, bool) or not isinstance(column, int) or not 1 <= column <= n:
        raise ValueError(f"Expected column as an integer from 1 to {n}, got {column!r}")
    reach = arm_reach(chain)
    # the view turns about the middle of the joints' heights; it must hold every pose and the axes drawn
    z = [float(q[2]) for q in chain.axis_points()]
    center = np.array([0.0, 0.0, 0.5 * (min(z) + max(z))])
    rng = np.random.default_rng(0)
    poses = np.vstack([np.zeros(n), rng.uniform(-np.pi, np.pi, (256, n))])
    radius = float(np.linalg.norm(chain.joint_positions(poses) - center, axis=-1).max())
    axis_length = 0.22 * reach
    return {
        "name": chain.name,
        "S": chain.screw_axes.tolist(),
        "M": chain.home.tolist(),
        "Q": chain.axis_points().tolist(),
        "theta": th,
        "column": column,
        "limit": LIMIT,
        "step": 0.01,
        "reach": reach,
        "center": center.tolist(),
        "extent": 0.85 * radius + 0.3 * axis_length,  # a rare far-stretched pose may touch the edge
        "axis_length": axis_length,
        "palette": _palette(),
    }


def gimbal_model(robot: str = "zyz_wrist", theta: Sequence[float] | None = None, rep: str = "zyx") -> dict[str, Any]:
    """The model of the gimbal-lock view, as ``_theme/live/gimbal_lock.js`` reads it.

    Both wrists are in the model (the view switches between them); ``robot`` is
    the one shown first. ``theta`` in rad (default 30°, 60°, 0°).

    >>> m = gimbal_model(theta=[0.5, 1.0, 0.0], rep="zyx")
    >>> m["wrist"], m["rep"], sorted(m["wrists"]), len(m["wrists"]["zyz_wrist"]["S"][0])
    ('zyz_wrist', 'zyx', ['zyx_wrist', 'zyz_wrist'], 3)
    """
    if robot not in WRISTS:
        raise ValueError(f"Expected robot one of {', '.join(WRISTS)}, got {robot!r}")
    if rep not in REPS:
        raise ValueError(f"Expected rep one of {', '.join(REPS)}, got {rep!r}")
    lim = math.radians(GIMBAL_LIMIT_DEG)
    th = _theta(theta, [math.radians(30.0), math.radians(60.0), 0.0], 3, robot, lim + 1e-12)
    wrists = {}
    for key, make in WRISTS.items():
        chain = make()
        wrists[key] = {"name": chain.name, "S": chain.screw_axes.tolist(), "M": chain.home.tolist(),
                       "Q": chain.axis_points().tolist()}
    return {
        "wrist": robot,
        "wrists": wrists,
        "theta": th,
        "rep": rep,
        "limit_deg": GIMBAL_LIMIT_DEG,
        "step_deg": 0.5,
        "tool": WRIST_TOOL,
        "near": NEAR_LOCK,
        "wrist_singular": WRIST_SINGULAR,
        "palette": _palette(),
        "column_colors": list(COLUMN_COLORS),
    }


def _angles(text: str) -> list[float]:
    try:
        return [float(t) for t in text.replace(",", " ").split()]
    except ValueError as exc:
        raise ValueError(f"Expected :theta: as angles in rad separated by spaces, got {text!r}") from exc


def spatial_model(view: str, options: Mapping[str, Any]) -> dict[str, Any]:
    """The model of ``view`` (one of :data:`SPATIAL_VIEWS`) from the directive's options."""
    theta = _angles(options["theta"]) if "theta" in options else None
    if view == "columns_explorer":
        unknown = set(options) - {"robot", "theta", "column"}
        if unknown:
            raise ValueError(f"Expected options robot, theta, column for columns_explorer, got {sorted(unknown)}")
        text = str(options.get("column", "3")).strip()
        if not text.isdigit():
            raise ValueError(f"Expected :column: as an integer, got {text!r}")
        return columns_model(options.get("robot", "spatial_5r"), theta, int(text))
    if view == "gimbal_lock":
        unknown = set(options) - {"robot", "theta", "rep"}
        if unknown:
            raise ValueError(f"Expected options robot, theta, rep for gimbal_lock, got {sorted(unknown)}")
        return gimbal_model(options.get("robot", "zyz_wrist"), theta, options.get("rep", "zyx"))
    raise ValueError(f"Expected a 3-D live view one of {', '.join(SPATIAL_VIEWS)}, got {view!r}")
