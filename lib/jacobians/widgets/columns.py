"""Which joints change column i of J_s and of J_b (chapter 4): the explorer and its animation."""

from __future__ import annotations

from typing import Any

import ipywidgets as W
import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from .. import robots
from .._validation import theta_array
from ..chain import SerialChain, _as_chain
from ..jacobian import body_jacobian, space_jacobian
from ..plotting import (
    PALETTE,
    FrameSource,
    MatrixArtist,
    PlanarArmArtist,
    SpatialChainArtist,
    arm_reach,
    check_planar,
    matrix_latex,
    setup_3d_axes,
    setup_planar_axes,
)
from .base import (
    ROW_LABELS,
    _Explorer,
    _latex_block,
    _planar_theta,
    _slider,
)

__all__ = ["ColumnsExplorer", "columns_explorer", "columns_explorer_animation"]


class ColumnsExplorer(_Explorer):
    """Space-vs-body columns; see :func:`columns_explorer`."""

    def __init__(self, chain: SerialChain | None = None, column: int = 3, theta: ArrayLike | None = None, *,
                 static: bool = False, figsize: tuple[float, float] = (6.0, 5.2), dpi: float = 80) -> None:
        super().__init__()
        chain = robots.spatial_5r() if chain is None else _as_chain(chain)
        self.chain = chain
        n = chain.dof
        if n < 2:
            raise ValueError(f"Expected a chain with at least 2 joints for the columns explorer, got {n}")
        try:
            check_planar(chain)
            self.planar = True
        except ValueError:
            self.planar = False
        theta = _planar_theta(chain, theta, [0.3, -0.5, 0.7, 0.4, -0.6, 0.2])
        column = int(column)
        if not 1 <= column <= n:
            raise ValueError(f"Expected column between 1 and {n}, got {column}")
        self.column_dropdown = W.Dropdown(options=[(f"column {i + 1}", i + 1) for i in range(n)], value=column,
                                          description="watch", layout=W.Layout(width="220px"))
        self.angle_sliders = [_slider(f"θ{i + 1} (rad)", theta[i], -np.pi, np.pi, 0.01) for i in range(n)]
        self.legend_html = W.HTML()
        self.matrix_html = W.HTMLMath()
        self.change_html = W.HTML()
        fig = Figure(figsize=figsize, dpi=dpi)
        self._setup(fig, static)
        title = f"{chain.name}: joints that move column"
        self.arm: Any  # a PlanarArmArtist (planar chain) or a SpatialChainArtist
        if self.planar:
            ax = fig.add_axes((0.14, 0.1, 0.82, 0.82))
            setup_planar_axes(ax, chain, title=title, margin=0.15)
            self.arm = PlanarArmArtist(ax, chain, theta)
            (self.role_markers,) = ax.plot([], [], linestyle="none")
            self.role_points = [ax.plot([], [], linestyle="none", marker="o", ms=15, mew=3, mfc="none",
                                        zorder=6)[0] for _ in range(n)]
            moving = self.arm.artists + self.role_points
        else:
            ax = fig.add_subplot(projection="3d")
            fig.subplots_adjust(left=0.0, right=0.95, bottom=0.05, top=0.92)
            setup_3d_axes(ax, chain, title=title, margin=-0.2)
            ax.view_init(elev=25, azim=-60)
            self.arm = SpatialChainArtist(ax, chain, theta, axis_length=0.18 * arm_reach(chain))
            self.role_points = []
            moving = [self.arm.link_line, self.arm.joint_markers] + self.arm.axis_lines + self.arm.axis_texts
            for f in self.arm.frames:
                moving += f.artists
        self.ax = ax
        self.title_text = ax.title
        # proxy legend entries for the roles
        from matplotlib.lines import Line2D

        handles = [Line2D([], [], color=PALETTE["space"], lw=4, label="joints before i: change column i of $J_s$"),
                   Line2D([], [], color=PALETTE["body"], lw=4, label="joints after i: change column i of $J_b$"),
                   Line2D([], [], color="black", lw=4, label="joint i")]
        ax.legend(handles=handles, loc="upper left", fontsize=8.5, framealpha=0.85)
        self.blitter.add(moving, self.title_text)
        self._last_J: tuple[Any, ...] | None = None
        self.changed_space_columns: list = []
        self.changed_body_columns: list = []
        self.last_moved_joint: int | None = None
        for k, s in enumerate(self.angle_sliders):
            s.observe(lambda ch, k=k: self._joint_moved(k), names="value")
        self.column_dropdown.observe(self._changed, names="value")
        controls = W.VBox([self.column_dropdown, W.HTML("<b>joint angles</b>"), *self.angle_sliders,
                           self.legend_html])
        self.children = [W.HBox([controls, self.image]), self.change_html, self.matrix_html]
        self.refresh()

    @property
    def theta(self) -> np.ndarray:
        return np.array([s.value for s in self.angle_sliders])

    @property
    def column(self) -> int:
        return int(self.column_dropdown.value)

    def set(self, theta: ArrayLike | None = None, column: int | None = None) -> ColumnsExplorer:
        """Set joint angles (rad) and/or the watched column (1-based); redraw once."""
        with self.hold_updates():
            if column is not None:
                if not 1 <= int(column) <= self.chain.dof:
                    raise ValueError(f"Expected column between 1 and {self.chain.dof}, got {column!r}")
                self.column_dropdown.value = int(column)
            if theta is not None:
                th = theta_array(theta, self.chain.dof)
                moved = [k for k in range(self.chain.dof) if abs(self.angle_sliders[k].value - th[k]) > 0]
                for s, v in zip(self.angle_sliders, th, strict=True):
                    s.value = float(np.clip(v, s.min, s.max))
                self.last_moved_joint = moved[0] + 1 if len(moved) == 1 else None
        return self

    def move_joint(self, joint: int, value: float) -> ColumnsExplorer:
        """Move one joint (1-based) to ``value`` rad; records which columns of J_s and J_b changed."""
        self.angle_sliders[int(joint) - 1].value = float(value)
        return self

    def _joint_moved(self, k: int) -> None:
        if self._hold == 0:
            self.last_moved_joint = k + 1
            self.refresh()

    def roles(self, column: int | None = None) -> tuple[list[int], list[int]]:
        """For column i (1-based): (joints before i, joints after i), 1-based lists."""
        i = self.column if column is None else int(column)
        return list(range(1, i)), list(range(i + 1, self.chain.dof + 1))

    def _compute_and_update(self) -> None:
        th = self.theta
        chain = self.chain
        n = chain.dof
        i = self.column
        J_s = space_jacobian(chain, th)
        J_b = body_jacobian(chain, th)
        if self._last_J is not None:
            dS = np.abs(J_s - self._last_J[0]).max(axis=0) > 1e-12
            dB = np.abs(J_b - self._last_J[1]).max(axis=0) > 1e-12
            self.changed_space_columns = [int(c) + 1 for c in np.flatnonzero(dS)]
            self.changed_body_columns = [int(c) + 1 for c in np.flatnonzero(dB)]
        self._last_J = (J_s, J_b)
        self.J_s, self.J_b = J_s, J_b
        before, after = self.roles(i)
        colours = [PALETTE["space"] if k + 1 in before else PALETTE["body"] if k + 1 in after else "black"
                   for k in range(n)]
        self.role_colors = colours
        self.arm.update(th)
        if self.planar:
            pts = self.arm.points
            for k, m in enumerate(self.role_points):
                m.set_data([pts[k, 0]], [pts[k, 1]])
                m.set_markeredgecolor(colours[k])
        else:
            for k, ln in enumerate(self.arm.axis_lines):
                ln.set_color(colours[k])
                ln.set_linewidth(5 if k + 1 != i else 6)
                self.arm.axis_texts[k].set_color(colours[k])
        self.title_text.set_text(f"{chain.name}: who moves column {i}")
        for k, s in enumerate(self.angle_sliders):
            s.style.handle_color = colours[k]
        self.legend_html.value = (
            f"<div style='font-size:14px;line-height:1.5'><span style='color:{PALETTE['space']}'>&#9632;</span> "
            f"θ{', θ'.join(map(str, before)) if before else ' (none)'} change column {i} of J<sub>s</sub><br>"
            f"<span style='color:{PALETTE['body']}'>&#9632;</span> "
            f"θ{', θ'.join(map(str, after)) if after else ' (none)'} change column {i} of J<sub>b</sub></div>")
        cols = [i - 1]
        self.matrix_html.value = (
            "<div style='font-size:14px'>"
            + _latex_block(matrix_latex(J_s, "J_s(\\theta)", 3, highlight_columns=cols, highlight_color="orange"),
                           matrix_latex(J_b, "J_b(\\theta)", 3, highlight_columns=cols,
                                        highlight_color="RoyalBlue"))
            + "</div>")
        if self.last_moved_joint is not None:
            j = self.last_moved_joint
            self.change_html.value = (
                f"<div style='font-size:15px'>You moved θ{j}: columns of J<sub>s</sub> that changed: "
                f"<b>{self.changed_space_columns or 'none'}</b> (those after joint {j}); columns of "
                f"J<sub>b</sub> that changed: <b>{self.changed_body_columns or 'none'}</b> "
                f"(those before joint {j}).</div>")
        else:
            self.change_html.value = ("<div style='font-size:15px'>Move one joint and watch which columns "
                                      "change.</div>")


def columns_explorer(chain: SerialChain | None = None, column: int = 3, theta: ArrayLike | None = None,
                     **kw: Any) -> ColumnsExplorer:
    r"""Which joints change column i of :math:`J_s` and of :math:`J_b` (chapter 4).

    Column i of the space Jacobian is :math:`[\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}\cdots
    e^{[\mathcal S_{i-1}]\theta_{i-1}}}]\mathcal S_i`: it depends on the joints before i only.
    Column i of the body Jacobian depends on the joints after i only. Default
    chain: :func:`jacobians.robots.spatial_5r` (drawn in 3-D); a planar arm is drawn in 2-D.

    ``.set(theta=, column=)`` or ``.move_joint(j, value)`` drive it; after a move,
    ``.changed_space_columns`` and ``.changed_body_columns`` (1-based) list the
    columns whose values changed; ``.J_s``, ``.J_b`` hold the shown matrices.
    """
    return ColumnsExplorer(chain, column, theta, **kw)


def columns_explorer_animation(chain: SerialChain | None = None, column: int = 3, frames: int = 36, dpi: float = 72,
                               interval: float = 150) -> FrameSource:
    """The columns view as a :class:`~jacobians.plotting.FrameSource`: each joint in turn swings by ±0.8 rad
    while column ``column`` is watched.

    A panel lists the values of column i of J_s and of J_b, so a reader sees
    which swings change which. ``.explorer`` is the :class:`ColumnsExplorer`,
    ``.path`` the joint angles of the frames.
    """
    w = ColumnsExplorer(chain, column, static=True, dpi=dpi, figsize=(8.6, 5.0))
    chain = w.chain
    n = chain.dof
    fig = w.fig
    w.ax.set_position((0.0, 0.04, 0.58, 0.9))
    axm = fig.add_axes((0.66, 0.16, 0.3, 0.66))
    i = w.column
    mat = MatrixArtist(axm, np.column_stack([w.J_s[:, i - 1], w.J_b[:, i - 1]]), digits=2, row_labels=ROW_LABELS,
                       col_labels=[f"$J_s$ col {i}", f"$J_b$ col {i}"], fontsize=11)
    note = axm.text(0.5, -0.12, "", transform=axm.transAxes, ha="center", va="top", fontsize=11)
    w.blitter.add([t for row in mat.texts for t in row], note)
    th0 = w.theta
    per = max(int(frames) // n, 4)
    seq = []
    for j in range(n):
        for t in np.linspace(0, 2 * np.pi, per, endpoint=False):
            th = th0.copy()
            th[j] += 0.8 * np.sin(t)
            seq.append((j, th))

    def draw(k: int) -> list:
        j, th = seq[k]
        w.set(theta=th)
        colours = [PALETTE["space"], PALETTE["body"]]
        mat.update(np.column_stack([w.J_s[:, i - 1], w.J_b[:, i - 1]]), colors=colours)
        role = "before" if j + 1 < i else "after" if j + 1 > i else "is"
        changes = {"before": f"changes $J_s$ col {i} only", "after": f"changes $J_b$ col {i} only",
                   "is": f"changes neither col {i}"}[role]
        note.set_text(f"moving $\\theta_{j + 1}$: {changes}")
        return []

    draw(0)
    return FrameSource(fig, draw, len(seq), interval=interval, render=w.blitter.render_rgba, explorer=w,
                       path=np.array([th for _, th in seq]))
