"""Gimbal lock of ZYX coordinates on a spherical wrist (chapter 6): the explorer and its animation."""

from __future__ import annotations

from typing import Any

import ipywidgets as W
import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from .. import robots
from .._validation import as_float_array
from ..chain import SerialChain
from ..jacobian import analytic_jacobian, geometric_jacobian, pose_coordinates
from ..plotting import (
    COLUMN_COLORS,
    PALETTE,
    FrameSource,
    MatrixArtist,
    SpatialChainArtist,
    arm_reach,
    matrix_latex,
    setup_3d_axes,
)
from ..representations import rate_to_angular_velocity, representation_singularity_margin
from .base import (
    FONT,
    _Explorer,
    _latex_block,
    _slider,
    _status_html,
)

__all__ = ["GimbalLockExplorer", "gimbal_lock_explorer", "gimbal_lock_animation"]


def _sigma_min_angular(J: ArrayLike) -> NDArray[np.float64]:
    """Smallest singular value of the angular (ω) rows of geometric Jacobians (..., 6, n)."""
    return np.linalg.svd(np.asarray(J)[..., :3, :], compute_uv=False)[..., -1]


class GimbalLockExplorer(_Explorer):
    """ZYX coordinates of a wrist's tool orientation and their gimbal lock; see :func:`gimbal_lock_explorer`."""

    WRISTS = {"zyz": "ZYZ wrist: only its ZYX coordinates lock", "zyx": "ZYX wrist: both coincide"}

    def __init__(self, angles_deg: ArrayLike = (30.0, 60.0, 0.0), wrist: str = "zyz", tool: float = 0.3, *,
                 theta2_range: tuple[float, float] = (-180.0, 180.0), n_grid: int = 241, static: bool = False,
                 figsize: tuple[float, float] = (8.4, 6.0), dpi: float = 80) -> None:
        super().__init__()
        if wrist not in self.WRISTS:
            raise ValueError(f"Expected wrist 'zyz' or 'zyx', got {wrist!r}")
        lo, hi = (float(v) for v in as_float_array(theta2_range, "theta2_range"))
        if not (-180.0 <= lo < hi <= 180.0):
            raise ValueError(f"Expected theta2_range (lo, hi) in degrees with -180 <= lo < hi <= 180, "
                             f"got {theta2_range!r}")
        self.theta2_range = (lo, hi)
        self._tool = tool
        self.chain = self._wrist_chain(wrist)
        a = as_float_array(angles_deg, "angles_deg")
        if a.shape != (3,):
            raise ValueError(f"Expected angles_deg with shape (3,): joint angles in degrees, got shape {a.shape}")
        lims = [(-180.0, 180.0), (lo, hi), (-180.0, 180.0)]
        self.angle_sliders = [_slider(f"θ{k + 1} (°)", np.clip(a[k], *lims[k]), lims[k][0], lims[k][1], 0.5,
                                      COLUMN_COLORS[k], readout_format=".1f") for k in range(3)]
        self.wrist_dropdown = W.Dropdown(options=[(v, k) for k, v in self.WRISTS.items()], value=wrist,
                                         layout=W.Layout(width="330px"))
        self.matrix_html = W.HTMLMath()
        self.status = W.HTML()
        fig = Figure(figsize=figsize, dpi=dpi)
        self._setup(fig, static)
        fs = FONT
        # left: the wrist in 3-D above the matrix B(phi); right: det B and sigma_min above the two norms
        ax3: Any = fig.add_axes((0.0, 0.40, 0.46, 0.56), projection="3d")
        setup_3d_axes(ax3, self.chain, margin=0.05)
        ax3.view_init(elev=22, azim=-55)
        r = np.floor(0.8 * arm_reach(self.chain) * 10) / 10 or 0.1  # tick labels clear of the box corners
        for axis, set_ticks in ((ax3.xaxis, ax3.set_xticks), (ax3.yaxis, ax3.set_yticks), (ax3.zaxis, ax3.set_zticks)):
            set_ticks([-r, 0.0, r])
            axis.label.set_size(fs - 1)
        ax3.tick_params(labelsize=fs - 1, pad=0)
        self.arm = SpatialChainArtist(ax3, self.chain, np.radians(a), axis_length=0.9 * arm_reach(self.chain),
                                      frame_length=0.18)
        self.title3 = ax3.text2D(0.5, 1.0, "", transform=ax3.transAxes, ha="center", va="top", fontsize=fs)
        axm = fig.add_axes((0.10, 0.03, 0.32, 0.19))
        self.matrix_artist = MatrixArtist(axm, np.eye(3), digits=2, fontsize=fs,
                                          col_labels=[r"$\dot\phi_1$", r"$\dot\phi_2$", r"$\dot\phi_3$"],
                                          row_labels=[r"$\omega_x$", r"$\omega_y$", r"$\omega_z$"])
        axm.tick_params(labelsize=fs)
        axm.xaxis.tick_top()
        self.matrix_title = fig.text(0.26, 0.305, "", ha="center", va="center", fontsize=fs)
        ax_d = fig.add_axes((0.60, 0.60, 0.38, 0.27))
        ax_n = fig.add_axes((0.60, 0.12, 0.38, 0.27), sharex=ax_d)
        self.ax3, self.ax_m, self.ax_det, self.ax = ax3, axm, ax_d, ax_n
        for ax_ in (ax_d, ax_n):
            ax_.tick_params(labelsize=fs - 1)
            ax_.grid(alpha=0.3)
        ax_d.set_xlim(lo, hi)
        ax_d.set_ylim(-1.1, 1.1)
        ax_d.tick_params(labelbottom=False)
        ax_d.axhline(0.0, color="0.5", lw=0.8)
        ax_n.set_yscale("log")
        ax_n.set_ylim(0.3, 3e3)
        ax_n.set_xlabel(r"joint angle $\theta_2$ (degrees); $\theta_1$, $\theta_3$ fixed", fontsize=fs)
        self.theta2_grid = np.linspace(lo, hi, int(n_grid))
        (self.curve_det,) = ax_d.plot([], [], color=PALETTE["analytic"], lw=2.5,
                                      label=r"$\det B(\phi) = -\cos\phi_2$ (ZYX angles $\phi$)")
        (self.curve_s,) = ax_d.plot([], [], color=PALETTE["geometric"], lw=2.5, ls="--",
                                    label=r"$\sigma_{\min}$ of the $\omega$ rows of $J$")
        (self.curve_a,) = ax_n.plot([], [], color=PALETTE["analytic"], lw=2.5, label=r"$\|J_a\|$, analytic (ZYX)")
        (self.curve_g,) = ax_n.plot([], [], color=PALETTE["geometric"], lw=2.5, ls="--", label=r"$\|J\|$, geometric")
        (self.mark_det,) = ax_d.plot([], [], "o", color=PALETTE["analytic"], ms=8)
        (self.mark_s,) = ax_d.plot([], [], "o", color=PALETTE["geometric"], ms=8)
        (self.mark_a,) = ax_n.plot([], [], "o", color=PALETTE["analytic"], ms=8)
        (self.mark_g,) = ax_n.plot([], [], "o", color=PALETTE["geometric"], ms=8)
        self.cursors = [ax_.axvline(lo, color="black", lw=1.0) for ax_ in (ax_d, ax_n)]
        for ax_ in (ax_d, ax_n):
            ax_.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), fontsize=fs - 1, frameon=False,
                       borderaxespad=0.2, handlelength=1.8)
        self.readout = ax_n.text(0.97, 0.95, "", transform=ax_n.transAxes, ha="right", va="top", fontsize=fs - 1)
        moving = [self.arm.link_line, self.arm.joint_markers] + self.arm.axis_lines + self.arm.axis_texts
        for f in self.arm.frames:
            moving += f.artists
        self.blitter.add(moving, self.title3, self.matrix_artist.texts, self.matrix_title, self.curve_det,
                         self.curve_s, self.curve_a, self.curve_g, self.mark_det, self.mark_s, self.mark_a,
                         self.mark_g, self.cursors, self.readout)
        for s_ in self.angle_sliders:
            s_.observe(self._changed, names="value")
        self.wrist_dropdown.observe(self._wrist_changed, names="value")
        controls = W.VBox([self.wrist_dropdown, W.HTML("<b>joint angles</b>"), *self.angle_sliders])
        self.children = [W.HBox([controls, self.status]), self.image, self.matrix_html]
        self._curve_key: tuple[Any, ...] | None = None
        self.refresh()

    def _wrist_chain(self, wrist: str) -> SerialChain:
        return robots.zyz_wrist(self._tool) if wrist == "zyz" else robots.zyx_wrist(self._tool)

    def _wrist_changed(self, change: dict[str, Any]) -> None:
        self.chain = self._wrist_chain(change["new"])
        self.arm.chain = self.chain
        self._changed()

    @property
    def angles_deg(self) -> np.ndarray:
        return np.array([s.value for s in self.angle_sliders])

    @property
    def wrist(self) -> str:
        return str(self.wrist_dropdown.value)

    def set(self, angles_deg: ArrayLike | None = None, theta2_deg: float | None = None,
            wrist: str | None = None) -> GimbalLockExplorer:
        """Set the joint angles (degrees), or only θ2, and/or the wrist ('zyz' or 'zyx'); redraw once."""
        with self.hold_updates():
            if wrist is not None:
                if wrist not in self.WRISTS:
                    raise ValueError(f"Expected wrist 'zyz' or 'zyx', got {wrist!r}")
                self.wrist_dropdown.value = wrist
            if angles_deg is not None:
                a = as_float_array(angles_deg, "angles_deg")
                if a.shape != (3,):
                    raise ValueError(f"Expected angles_deg with shape (3,), got shape {a.shape}")
                for s_, v in zip(self.angle_sliders, a, strict=True):
                    s_.value = float(np.clip(v, s_.min, s_.max))
            if theta2_deg is not None:
                s2 = self.angle_sliders[1]
                s2.value = float(np.clip(theta2_deg, s2.min, s2.max))
        return self

    def _curves(self, th: NDArray[np.float64]) -> None:
        """det B, sigma_min of J's omega rows, ||J_a|| and ||J|| along theta2_grid with theta1, theta3 fixed."""
        g = np.radians(self.theta2_grid)
        grid = np.column_stack([np.full_like(g, th[0]), g, np.full_like(g, th[2])])
        phi = pose_coordinates(self.chain.fk(grid), "zyx")[:, :3]
        Jg = geometric_jacobian(self.chain, grid)
        Ja = analytic_jacobian(self.chain, grid, "zyx", on_singularity="nan")
        self.grid_theta = grid
        self.det_B_grid = np.linalg.det(rate_to_angular_velocity(phi, "zyx"))
        self.sigma_min_grid = _sigma_min_angular(Jg)
        self.norm_Ja_grid = np.linalg.norm(Ja, axis=(-2, -1))
        self.norm_J_grid = np.linalg.norm(Jg, axis=(-2, -1))
        self.curve_det.set_data(self.theta2_grid, self.det_B_grid)
        self.curve_s.set_data(self.theta2_grid, self.sigma_min_grid)
        self.curve_a.set_data(self.theta2_grid, self.norm_Ja_grid)
        self.curve_g.set_data(self.theta2_grid, self.norm_J_grid)

    def _compute_and_update(self) -> None:
        a = self.angles_deg
        th = np.radians(a)
        chain = self.chain
        self.arm.update(th)
        T = chain.fk(th)
        phi = pose_coordinates(T, "zyx")[:3]
        self.phi = phi
        B = rate_to_angular_velocity(phi, "zyx")
        self.B = B
        self.det_B = float(np.linalg.det(B)) + 0.0
        if abs(self.det_B) < 5e-13:
            self.det_B = 0.0  # shown as 0.0000, not -0.0000
        self.margin = float(representation_singularity_margin(phi, "zyx"))
        self.J = geometric_jacobian(chain, th)
        self.J_a = analytic_jacobian(chain, th, "zyx", on_singularity="nan")
        self.singular = bool(np.isnan(self.J_a).any())
        self.sigma_min_omega = float(_sigma_min_angular(self.J))
        key = (self.wrist, a[0], a[2])
        if key != self._curve_key:
            self._curves(th)
            self._curve_key = key
        na = float(np.linalg.norm(self.J_a)) if not self.singular else np.nan
        ng = float(np.linalg.norm(self.J))
        self.norms = (na, ng)
        top = self.ax.get_ylim()[1]
        self.mark_a.set_data([a[1]], [na if np.isfinite(na) else top])
        self.mark_a.set_marker("o" if np.isfinite(na) else "^")
        self.mark_g.set_data([a[1]], [ng])
        self.mark_det.set_data([a[1]], [self.det_B])
        self.mark_s.set_data([a[1]], [self.sigma_min_omega])
        for c in self.cursors:
            c.set_xdata([a[1], a[1]])
        self.matrix_artist.update(B)
        deg = ", ".join(f"{np.degrees(v) + 0.0:.0f}°" for v in phi)
        self.matrix_title.set_text(rf"$B(\phi)$ at ZYX $\phi$ = ({deg})" + "\n"
                                   + rf"$\det B = {self.det_B + 0.0:.2f}$".replace("-", "−"))
        self.readout.set_text(r"$J_a$ undefined" if self.singular else "")
        self.title3.set_text(rf"{chain.name}, $\theta_2$ = {a[1]:.0f}°")
        if self.singular:
            level, word = "bad", "gimbal lock: B(φ) is singular, the analytic Jacobian is <b>undefined</b>"
        elif self.margin < 0.1:
            level, word = "warn", "close to gimbal lock: the analytic Jacobian is huge"
        else:
            level, word = "ok", "ZYX angle rates well defined"
        robot = ("the wrist itself is <b>singular</b> too (σ<sub>min</sub> of J's ω rows = "
                 f"{self.sigma_min_omega:.3g})" if self.sigma_min_omega < 1e-3 else
                 f"the wrist is not singular (σ<sub>min</sub> of J's ω rows = {self.sigma_min_omega:.3f})")
        self.level = level
        self.status.value = _status_html(
            f"ZYX angles φ = ({', '.join(f'{np.degrees(v) + 0.0:.1f}°' for v in phi)})<br>"
            f"det B(φ) = −cos φ<sub>2</sub> = {self.det_B:.4f}<br>{word}<br>{robot}", level)
        Ja_tex = matrix_latex(self.J_a, "J_a(\\theta)", 3)
        self.matrix_latex = {"B": matrix_latex(B, "B(\\phi)", 3), "J_a": Ja_tex,
                             "J": matrix_latex(self.J, "J(\\theta)", 3)}
        self.matrix_html.value = (
            "<div style='font-size:14px'>"
            + _latex_block(r"\omega_s = B(\phi)\dot\phi,\quad " + self.matrix_latex["B"]
                           + rf",\quad \det B(\phi) = -\cos\phi_2 = {self.det_B:.4f}",
                           r"J_a = \begin{bmatrix}B(\phi)^{-1} & 0\\ 0 & I\end{bmatrix}J:\quad " + Ja_tex
                           + (r"\ \text{(undefined at gimbal lock)}" if self.singular else ""),
                           self.matrix_latex["J"])
            + "</div>")


def gimbal_lock_explorer(angles_deg: ArrayLike = (30.0, 60.0, 0.0), wrist: str = "zyz", tool: float = 0.3,
                         **kw: Any) -> GimbalLockExplorer:
    r"""ZYX coordinates of a spherical wrist's tool orientation, and their gimbal lock (chapter 6).

    Default: the ZYZ wrist :func:`jacobians.robots.zyz_wrist`,
    :math:`R = R_z(\theta_1)R_y(\theta_2)R_z(\theta_3)`. Its own (kinematic)
    singularity is at :math:`\theta_2 = 0, \pm 180°`, where axes 1 and 3 line up: the
    smallest singular value of the angular rows of J is
    :math:`\sqrt{1 - |\cos\theta_2|}`. The ZYX coordinates of its tool orientation
    lock where the pitch is ±90°, i.e. at :math:`\theta_2 = \pm 90°` with
    :math:`\theta_3 = 0` (the tool's x axis vertical); there the wrist is as far from
    its own singularity as it gets (σ_min = 1). Near the lock the analytic Jacobian
    :math:`J_a = \mathrm{diag}(B(\phi)^{-1}, I)J` blows up while J stays well-conditioned.
    With ``wrist="zyx"`` (:func:`jacobians.robots.zyx_wrist`, whose ZYX angles are its
    joint angles) the two singularities coincide: the angular block of :math:`J_a` is the
    identity and J loses rank at the lock.

    Shows the wrist, :math:`B(\phi)` (:math:`\omega_s = B(\phi)\dot\phi`), and, as θ2 runs
    over ``theta2_range`` (degrees, default the whole turn) with θ1 and θ3 fixed,
    :math:`\det B = -\cos\phi_2` next to σ_min of J's ω rows, and :math:`\|J_a\|` next to
    :math:`\|J\|`. :math:`J_a` is "undefined" (NaN) at exactly the lock: never an exception.
    The curves drawn are kept in ``grid_theta`` (joint angles, radians), ``det_B_grid``,
    ``sigma_min_grid``, ``norm_Ja_grid`` and ``norm_J_grid``.
    """
    return GimbalLockExplorer(angles_deg, wrist, tool, **kw)


def gimbal_lock_animation(frames: int = 15, dpi: float = 80, interval: float = 250, wrist: str = "zyz",
                          theta1_deg: float = 30.0, theta3_deg: float = 0.0,
                          theta2_deg: tuple[float, float] = (45.0, 135.0)) -> FrameSource:
    r"""The gimbal-lock view as a :class:`~jacobians.plotting.FrameSource` along a path of the wrist.

    θ2 runs once from ``theta2_deg[0]`` to ``theta2_deg[1]`` (both included, ``frames``
    equal steps) with θ1 and θ3 fixed; the curves are drawn over the same θ2 interval.
    Default: the ZYZ wrist from 45° to 135°, through the ZYX lock at 90° (an odd number of
    frames puts a frame on it) and nowhere near the wrist's own singularity at 0° and 180°.
    Play it back and forth with ``animation_html(anim, default_mode="reflect")``.
    ``anim.path`` is the (frames, 3) array of joint angles (radians) of the frames;
    ``anim.explorer`` the :class:`GimbalLockExplorer` that draws them.
    """
    lo, hi = (float(v) for v in as_float_array(theta2_deg, "theta2_deg"))
    n = int(frames)
    if n < 2:
        raise ValueError(f"Expected at least 2 frames, got {frames!r}")
    w = GimbalLockExplorer((theta1_deg, lo, theta3_deg), wrist, static=True, dpi=dpi, theta2_range=(lo, hi))
    angles = np.linspace(lo, hi, n)

    def draw(k: int) -> list:
        w.set(theta2_deg=angles[k])
        return []

    draw(0)
    path = np.radians(np.column_stack([np.full(n, theta1_deg), angles, np.full(n, theta3_deg)]))
    return FrameSource(w.fig, draw, n, interval=interval, render=w.blitter.render_rgba, explorer=w, path=path)
