r"""The two 3-D live views in JupyterLab, and their models for the book page.

* ``columns_explorer`` (chapter 4): the spatial 5R arm; which joints move which
  column of :math:`J_s` and :math:`J_b`. :func:`columns_model` and the widget
  :class:`ColumnsExplorer` (``w.theta``, ``w.column`` settable; ``w.Js``,
  ``w.Jb`` from the library, ``w.J`` is ``w.Js``).
* ``gimbal_lock`` (chapter 6): a spherical wrist (``zyz_wrist`` or
  ``zyx_wrist``), its ZYX or ZYZ coordinates φ, :math:`B(\phi)`, det B,
  :math:`J_a` next to :math:`J`. :func:`gimbal_model` and the widget
  :class:`GimbalLock` (``w.theta``, ``w.wrist``, ``w.rep`` settable; ``w.J``,
  ``w.Ja``, ``w.B``, ``w.phi`` from the library).

A model holds what the library says about the chain (screw axes, home, joint
axis points, reach) and the state; the view modules ``lib/jacobians/widgets/static/live/<view>.js``
compute what they draw with ``lib/jacobians/widgets/static/live/kinematics.js``, which the browser
tests keep equal to the library. The same module is the book page's (mounted
by ``{live-view}``, ``_ext/live_views.py``, from :data:`SPATIAL_MODELS`) and
the widget's ``_esm`` (:class:`jacobians.widgets.live.LiveView`). Colours are
the course palette (:data:`jacobians.plotting.style.PALETTE`).

>>> w = ColumnsExplorer(theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=2)
>>> w.view, w.column, w.Js.shape, bool(abs(w.J - w.Js).max() == 0)
('columns_explorer', 2, (6, 5), True)
>>> g = GimbalLock(theta=[0.5, 1.0, 0.0], rep="zyx")
>>> g.view, g.wrist, g.J.shape, g.Ja.shape, round(float(g.det_B), 4)
('gimbal_lock', 'zyz_wrist', (6, 3), (6, 3), -0.5403)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .. import representations as _reps
from .. import robots
from ..chain import SerialChain
from ..jacobian import analytic_jacobian, body_jacobian, geometric_jacobian, pose_coordinates, space_jacobian
from ..plotting import arm_reach
from ..plotting.style import COLUMN_COLORS, PALETTE
from .live import LIMIT, LiveView

__all__ = ["ColumnsExplorer", "GimbalLock", "columns_model", "gimbal_model", "reach_bounds", "SPATIAL_MODELS",
           "SPATIAL_VIEWS",
           "COLUMN_ROBOTS", "WRISTS", "WRIST_TOOL", "REPS"]

SPATIAL_VIEWS = ("columns_explorer", "gimbal_lock")
COLUMN_ROBOTS: dict[str, Callable[[], SerialChain]] = {"spatial_5r": robots.spatial_5r}
WRIST_TOOL = 0.3  # m, as jacobians.widgets.gimbal
WRISTS: dict[str, Callable[[], SerialChain]] = {"zyz_wrist": lambda: robots.zyz_wrist(WRIST_TOOL),
                                                "zyx_wrist": lambda: robots.zyx_wrist(WRIST_TOOL)}
REPS = ("zyx", "zyz")
VIEW_MARGIN = 13 / 200  # the axis keys' dot radius, as a share of the 3-D view's half-width (view3d.js)
GIMBAL_LIMIT_DEG = 180.0  # the gimbal view's sliders, degrees
NEAR_LOCK = 0.1  # |det B| below this: "near gimbal lock" (jacobians.widgets.gimbal's margin)
WRIST_SINGULAR = 1e-3  # sigma_min of J's angular rows below this: the wrist itself is singular


def _palette() -> dict[str, str]:
    keys = ("space", "body", "link", "joint", "muted", "analytic", "geometric", "singular", "warning", "ok")
    return {k: PALETTE[k] for k in keys if k in PALETTE}


def _theta(theta: Sequence[float] | NDArray[np.float64] | None, default: Sequence[float], n: int, name: str,
           limit: float) -> list[float]:
    if theta is None:
        return [float(t) for t in default]
    try:
        th = [float(t) for t in np.asarray(theta, dtype=float).ravel()]
    except (TypeError, ValueError) as exc:
        raise TypeError(f"Expected theta as {n} numbers (rad) for {name}, got {theta!r}") from exc
    if len(th) != n:
        raise ValueError(f"Expected theta with {n} angles (rad) for {name}, got {len(th)}: {list(th)!r}")
    bad = [t for t in th if not math.isfinite(t) or abs(t) > limit]
    if bad:
        raise ValueError(f"Expected theta as finite angles within ±{limit:.4g} rad, got {bad!r}")
    return th


def reach_bounds(chain: SerialChain) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A point c and, for each drawn point of a revolute chain (joint points, then the tool), a radius about c
    that the point never leaves, whatever the joint angles: ``(c, B)``.

    Why it holds: the joint points ``p_i`` (``chain.joint_positions``) lie on their joint's axis, so joint i
    turns everything after it about a line through ``p_i``; the distance ``d_i = |p_{i+1} - p_i|`` is then the
    same at every pose (joints before i move both points rigidly, joint i fixes ``p_i``, joints after i fix
    ``p_{i+1}``). A point ``p_j`` that lies on every axis before it (at home) never moves. From such a fixed
    point, the triangle inequality gives ``|p_k - c| <= |p_j - c| + d_j + ... + d_{k-1}``; B takes the least
    of these over the fixed points, and c is the last fixed point (the arm turns about it).
    tests/test_live_views_spatial_ext.py searches random arms and poses for a point outside its bound.
    """
    S = chain.screw_axes
    pitch = np.abs(np.einsum("ij,ij->j", S[:3], S[3:]))
    if not np.all(np.linalg.norm(S[:3], axis=0) > 0.5) or not np.all(pitch <= 1e-12 * (1 + np.abs(S[3:]).max())):
        raise ValueError("Expected a chain of revolute joints with no pitch: a joint that slides has no such bound")
    P = chain.joint_positions(np.zeros(chain.dof))
    W = S[:3].T

    def on_axis(p: NDArray[np.float64], i: int) -> bool:
        r = p - P[i]
        return bool(np.linalg.norm(r - W[i] * (W[i] @ r)) <= 1e-9 * max(1.0, float(np.linalg.norm(p))))

    fixed = [j for j in range(chain.dof + 1) if all(on_axis(P[j], i) for i in range(min(j, chain.dof)))]
    c = P[fixed[-1]].copy()
    d = np.linalg.norm(np.diff(P, axis=0), axis=1)
    B = np.array([min(float(np.linalg.norm(P[j] - c)) + float(d[j:k].sum()) for j in fixed if j <= k)
                  for k in range(chain.dof + 1)])
    return c, B


def columns_model(robot: str = "spatial_5r", theta: Sequence[float] | None = None, column: int = 3) -> dict[str, Any]:
    """The model of the columns explorer, as ``lib/jacobians/widgets/static/live/columns_explorer.js`` reads it.

    >>> m = columns_model(theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=3)
    >>> len(m["S"]), len(m["S"][0]), m["column"], m["theta"][2], m["name"]
    (6, 5, 3, 0.9, 'spatial 5R')
    """
    if robot not in COLUMN_ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(COLUMN_ROBOTS)}, got {robot!r}")
    chain = COLUMN_ROBOTS[robot]()
    n = chain.dof
    th = _theta(theta, [0.3, -0.5, 0.9, 0.4, 0.3], n, robot, LIMIT)
    if isinstance(column, bool) or not isinstance(column, int | np.integer) or not 1 <= column <= n:
        raise ValueError(f"Expected column as an integer from 1 to {n}, got {column!r}")
    reach = arm_reach(chain)
    axis_length = 0.22 * reach
    # The view turns about the point the arm turns about, and its sphere holds what it draws at every pose
    # (reach_bounds): a joint's axis and its numbered key reach 1.25 axis_length past the joint point, the frame
    # {b}'s arrows 0.175 reach past the tool, {s}'s letters 0.22 reach past the origin. The key's dot is 13 SVG
    # units of the 200 from the centre to the edge: the sphere is that much larger.
    center, bounds = reach_bounds(chain)
    drawn = np.concatenate([bounds[:-1] + 1.25 * axis_length, [bounds[-1] + 0.175 * reach],
                            [float(np.linalg.norm(center)) + 0.22 * reach]])
    extent = float(drawn.max()) / (1.0 - VIEW_MARGIN)
    return {
        "name": chain.name,
        "S": chain.screw_axes.tolist(),
        "M": chain.home.tolist(),
        "Q": chain.axis_points().tolist(),
        "theta": th,
        "column": int(column),
        "limit": LIMIT,
        "step": 0.01,
        "reach": reach,
        "center": center.tolist(),
        "extent": extent,
        "axis_length": axis_length,
        "palette": _palette(),
    }


def gimbal_model(robot: str = "zyz_wrist", theta: Sequence[float] | None = None, rep: str = "zyx") -> dict[str, Any]:
    """The model of the gimbal-lock view, as ``lib/jacobians/widgets/static/live/gimbal_lock.js`` reads it.

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


#: View name -> function of keyword options returning the 3-D view's model (the directive uses it).
SPATIAL_MODELS: dict[str, Callable[..., dict[str, Any]]] = {
    "columns_explorer": columns_model,
    "gimbal_lock": gimbal_model,
}


class ColumnsExplorer(LiveView):
    """The live columns explorer of chapter 4: ``theta`` and ``column`` settable, ``Js``, ``Jb`` from the library.

    ``ColumnsExplorer(theta=[...], column=3)`` on the spatial 5R arm; a slider
    moved in the view sets ``theta`` here, ``w.theta = [...]`` redraws the view.
    """

    def __init__(self, robot: str = "spatial_5r", theta: Sequence[float] | None = None, column: int = 3) -> None:
        model = columns_model(robot, theta, column)
        self.chain = COLUMN_ROBOTS[robot]()
        super().__init__("columns_explorer", model)

    @property
    def Js(self) -> NDArray[np.float64]:
        """The space Jacobian J_s (6×n) at the current ``theta``, as the view's first table."""
        return space_jacobian(self.chain, np.asarray(self.theta, dtype=float))

    @property
    def Jb(self) -> NDArray[np.float64]:
        """The body Jacobian J_b (6×n) at the current ``theta``, as the view's second table."""
        return body_jacobian(self.chain, np.asarray(self.theta, dtype=float))

    @property
    def J(self) -> NDArray[np.float64]:
        """The space Jacobian (the view shows it first); ``Jb`` is the body one."""
        return self.Js


class GimbalLock(LiveView):
    """The live gimbal-lock view of chapter 6: ``theta``, ``wrist``, ``rep`` settable; ``J``, ``Ja``, ``B`` computed.

    ``GimbalLock("zyz_wrist", theta=[...], rep="zyx")``, ``theta`` in rad (the
    view's sliders are in degrees). At the lock ``Ja`` is all NaN (the view
    shows "—": J_a does not exist there).
    """

    def __init__(self, robot: str = "zyz_wrist", theta: Sequence[float] | None = None, rep: str = "zyx") -> None:
        model = gimbal_model(robot, theta, rep)
        self.chains = {k: make() for k, make in WRISTS.items()}
        super().__init__("gimbal_lock", model)

    @property
    def chain(self) -> SerialChain:
        """The wrist shown (``wrist`` picks it)."""
        return self.chains[self.wrist]

    def _th(self) -> NDArray[np.float64]:
        return np.asarray(self.theta, dtype=float)

    @property
    def J(self) -> NDArray[np.float64]:
        """The geometric Jacobian J (6×3, rows (ω, v) in {s}) at the current ``theta``."""
        return geometric_jacobian(self.chain, self._th())

    @property
    def phi(self) -> NDArray[np.float64]:
        """The tool orientation's coordinates φ (rad) in ``rep``."""
        return np.asarray(pose_coordinates(self.chain.fk(self._th()), self.rep)[:3])

    @property
    def B(self) -> NDArray[np.float64]:
        """B(φ) with ω_s = B(φ) φ̇."""
        return _reps.rate_to_angular_velocity(self.phi, self.rep)

    @property
    def det_B(self) -> float:
        """det B(φ): 0 at the lock."""
        return float(np.linalg.det(self.B))

    @property
    def Ja(self) -> NDArray[np.float64]:
        """The analytic Jacobian J_a = diag(B⁻¹, I) J (6×3); NaN at the lock, where it does not exist."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return analytic_jacobian(self.chain, self._th(), self.rep, on_singularity="nan")
