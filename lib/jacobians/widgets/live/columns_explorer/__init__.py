r"""``columns_explorer`` (chapter 4): the spatial 5R arm; which joints move which column of :math:`J_s` and
:math:`J_b`. :func:`columns_model` and the widget :class:`ColumnsExplorer` (``w.theta``, ``w.column``
settable; ``w.Js``, ``w.Jb`` from the library, ``w.J`` is ``w.Js``).

>>> w = ColumnsExplorer(theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=2)
>>> w.view, w.column, w.Js.shape, bool(abs(w.J - w.Js).max() == 0)
('columns_explorer', 2, (6, 5), True)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .... import robots
from ....chain import SerialChain
from ....jacobian import body_jacobian, space_jacobian
from ....plotting import arm_reach
from .._base import LIMIT, LiveView, Shown, ViewSpec, angles, checked_theta, expect, expect_table, palette, text, whole

__all__ = ["ColumnsExplorer", "columns_model", "reach_bounds", "COLUMN_ROBOTS", "VIEW_MARGIN", "SPEC"]

COLUMN_ROBOTS: dict[str, Callable[[], SerialChain]] = {"spatial_5r": robots.spatial_5r}
VIEW_MARGIN = 13 / 200  # the axis keys' dot radius, as a share of the 3-D view's half-width (view3d.js)


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
    """The model of the columns explorer, as ``columns_explorer/view.js`` reads it.

    >>> m = columns_model(theta=[0.3, -0.5, 0.9, 0.4, 0.3], column=3)
    >>> len(m["S"]), len(m["S"][0]), m["column"], m["theta"][2], m["name"]
    (6, 5, 3, 0.9, 'spatial 5R')
    """
    if robot not in COLUMN_ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(COLUMN_ROBOTS)}, got {robot!r}")
    chain = COLUMN_ROBOTS[robot]()
    n = chain.dof
    th = checked_theta(theta, [0.3, -0.5, 0.9, 0.4, 0.3], n, robot, LIMIT)
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
        "palette": palette(),
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


def check_shown(shown: Shown) -> None:
    """The tables J_s and J_b the view shows are the library's at the θ shown, on the arm of its model."""
    w = ColumnsExplorer("spatial_5r", theta=shown["theta"], column=shown["model"]["column"])
    expect(np.array_equal(shown["model"]["S"], w.chain.screw_axes), "columns_explorer: not the spatial 5R arm")
    expect_table(shown, "jl-space", w.Js)
    expect_table(shown, "jl-body", w.Jb)


SPEC = ViewSpec(name="columns_explorer", model=columns_model, widget=ColumnsExplorer,
                options={"robot": text, "theta": angles, "column": whole},
                probe=("input.jl-theta:nth-of-type(2)", -0.85),
                example={"robot": "spatial_5r", "theta": "0.1 0.2 0.3 0.4 0.5", "column": "2"},
                folder=Path(__file__).resolve().parent,
                data_keys=frozenset({"column", "moved", "changedS", "changedB"}), check=check_shown)
