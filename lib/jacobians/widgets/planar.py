"""The planar arm explorer (chapters 2 and 5) and its animation."""

from __future__ import annotations

from typing import Any

import ipywidgets as W
import numpy as np
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from .. import robots
from .._validation import theta_array
from ..analysis import force_ellipsoid, velocity_ellipsoid
from ..chain import SerialChain
from ..frames import FRAMES, JACOBIAN_SYMBOLS, Frame, check_frame
from ..jacobian import geometric_jacobian, jacobian, space_jacobian
from ..plotting import (
    COLUMN_COLORS,
    PALETTE,
    EllipseArtist,
    FrameSource,
    MatrixArtist,
    PlanarArmArtist,
    TwistArtist,
    arm_reach,
    check_planar,
    matrix_latex,
    setup_planar_axes,
)
from .base import (
    FONT,
    ROW_LABELS,
    _Explorer,
    _latex_block,
    _planar_theta,
    _slider,
    _status_html,
)

__all__ = ["PlanarArmExplorer", "planar_arm_explorer", "planar_arm_explorer_animation", "JACOBIAN_FORMULAS",
           "JACOBIAN_SYMBOLS", "TWIST_SYMBOLS", "FORCE_LABELS"]

JACOBIAN_FORMULAS = {
    "space": (r"J_s(\theta) = \begin{bmatrix} \mathcal S_1 & [\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}}]\mathcal S_2"
              r" & \cdots & [\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_{n-1}]\theta_{n-1}}}]"
              r"\mathcal S_n \end{bmatrix}, \quad \mathcal V_s = J_s(\theta)\dot\theta"),
    "body": (r"J_b(\theta) = \begin{bmatrix} "
             r"[\mathrm{Ad}_{e^{-[\mathcal B_n]\theta_n}\cdots e^{-[\mathcal B_2]\theta_2}}]"
             r"\mathcal B_1 & \cdots & [\mathrm{Ad}_{e^{-[\mathcal B_n]\theta_n}}]\mathcal B_{n-1} & \mathcal B_n"
             r"\end{bmatrix}, \quad \mathcal V_b = J_b(\theta)\dot\theta"),
    "geometric": (r"J(\theta) = \begin{bmatrix} R_{sb} & 0 \\ 0 & R_{sb} \end{bmatrix} J_b(\theta), \quad"
                  r"\begin{bmatrix}\omega_s \\ \dot p\end{bmatrix} = J(\theta)\dot\theta"),
    "analytic": (r"J_a(\theta) = \begin{bmatrix} B(\phi)^{-1} & 0 \\ 0 & I \end{bmatrix} J(\theta), \quad"
                 r"\begin{bmatrix}\dot\phi \\ \dot p\end{bmatrix} = J_a(\theta)\dot\theta,"
                 r"\ \phi = \text{ZYX angles of } R_{sb}"),
}
# legend entries of the force ellipse and of the mark along a clipped semi-axis, by state
FORCE_LABELS = {
    None: (r"force ellipse, $\|\tau\|=1$", None),
    "clipped": (r"force ellipse, $\|\tau\|=1$ (dotted: clipped)",
                r"force semi-axis longer than drawn (clipped at %.2f m)"),
    "inf": (r"force ellipse, $\|\tau\|=1$ (dotted: clipped)",
            r"force semi-axis $\infty$ (singular direction), clipped at %.2f m"),
}
TWIST_SYMBOLS = {"space": r"\mathcal V_s", "body": r"\mathcal V_b", "geometric": r"(\omega_s, \dot p)",
                 "analytic": r"(\dot\phi, \dot p)"}


class PlanarArmExplorer(_Explorer):
    """Planar arm explorer; see :func:`planar_arm_explorer`."""

    FRAMES = FRAMES

    def __init__(self, chain: SerialChain | None = None, theta: ArrayLike | None = None,
                 rates: ArrayLike | None = None, frame: Frame | None = None, *, static: bool = False,
                 show_ellipses: bool = True, figsize: tuple[float, float] = (5.6, 5.4), dpi: float = 80,
                 matrix_panel: bool | None = None) -> None:
        super().__init__()
        chain = robots.planar_2r() if chain is None else chain
        self.chain = check_planar(chain, "the planar arm explorer")
        n = self.chain.dof
        theta = _planar_theta(self.chain, theta, [0.5, 1.2, -0.8])
        rates = np.ones(n) * 0.5 if rates is None else theta_array(rates, n, "rates")
        frame = check_frame("space" if frame is None else frame, FRAMES)
        self.reach = arm_reach(self.chain)
        self.vel_scale = 0.35  # drawn metres per m/s
        self.force_scale = 0.1 * self.reach ** 2  # drawn metres per (N per N m)
        self.sing_tol = 0.08 * self.reach
        # a force semi-axis longer than this (infinite at a singularity) is drawn at this length and
        # marked; force_scale / force_clip = sing_tol, so clipping starts where "near a singularity" does
        self.force_clip = 1.25 * self.reach

        # controls
        self.angle_sliders = [_slider(f"θ{i + 1} (rad)", theta[i], -np.pi, np.pi, 0.01, COLUMN_COLORS[i % 7])
                              for i in range(n)]
        self.rate_sliders = [_slider(f"θ̇{i + 1} (rad/s)", rates[i], -2.0, 2.0, 0.05, COLUMN_COLORS[i % 7])
                             for i in range(n)]
        self.frame_dropdown = W.Dropdown(options=[(f"{k} Jacobian", k) for k in FRAMES], value=frame,
                                        description="show", layout=W.Layout(width="260px"))
        self.ellipse_checkbox = W.Checkbox(value=show_ellipses, description="velocity and force ellipses",
                                           indent=False)
        self.sweep_dropdown = W.Dropdown(options=[(f"sweep θ{i + 1}", i) for i in range(n)], value=n - 1,
                                         layout=W.Layout(width="120px"))
        self.play = W.Play(value=0, min=0, max=72, step=1, interval=120, description="Play", repeat=True)
        self.status = W.HTML()
        self.matrix_html = W.HTMLMath()

        # figure
        with_matrix = static if matrix_panel is None else matrix_panel
        if with_matrix:
            fig = Figure(figsize=(figsize[0] + 3.6, figsize[1]), dpi=dpi)
            ax = fig.add_axes((0.08, 0.1, 0.52, 0.8))
            axm = fig.add_axes((0.7, 0.12, 0.28, 0.72))
        else:
            fig = Figure(figsize=figsize, dpi=dpi)
            ax = fig.add_axes((0.14, 0.1, 0.82, 0.82))
            axm = None
        self._setup(fig, static)
        self.ax = ax
        setup_planar_axes(ax, self.chain, title=f"{self.chain.name}: tool velocity from $J\\dot\\theta$", margin=0.3)
        self.arm = PlanarArmArtist(ax, self.chain, theta)
        pts = self.arm.points
        (self.axis_dots,) = ax.plot(pts[:-1, 0], pts[:-1, 1], linestyle="none", marker=".", ms=5, color="black",
                                    zorder=5)
        self.joint_labels = [ax.text(0, 0, f"{i + 1}", fontsize=FONT - 1, color="black", zorder=6)
                             for i in range(n)]
        self.pdot_arrow = TwistArtist(ax, pts[-1], [0, 0], color=PALETTE["velocity"],
                                      label=rf"$\dot p$, tool velocity (×{self.vel_scale:.2f} s)",
                                      scale=self.vel_scale)
        self.vs_arrow = TwistArtist(ax, [0, 0], [0, 0], color=PALETTE["space"],
                                    label=rf"$v_s$ at {{s}}, from $\mathcal{{V}}_s$ (×{self.vel_scale:.2f} s)",
                                    scale=self.vel_scale)
        eye2 = np.eye(2)
        self.vel_ellipse = EllipseArtist(ax, pts[-1], [0, 0], eye2, color=PALETTE["velocity"], lw=1.8,
                                         label=r"velocity ellipse, $\|\dot\theta\|=1$")
        self.force_ellipse = EllipseArtist(ax, pts[-1], [0, 0], eye2, color=PALETTE["force"], lw=1.8, ls="--",
                                           label=FORCE_LABELS[None][0])
        # along a clipped force semi-axis: a line through the tool, both ways, to the clip length
        (self.force_clip_line,) = ax.plot([], [], color=PALETTE["force"], lw=1.4, ls="-.", visible=False,
                                          zorder=2)
        self.force_clipped = np.zeros(2, dtype=bool)
        self.indicator = ax.text(0.02, 0.02, "", transform=ax.transAxes, fontsize=FONT, va="bottom",
                                 bbox=dict(boxstyle="round", fc="white", ec="0.6", alpha=0.9), zorder=7)
        self._legend_kind: tuple[Any, ...] | None = None
        self.matrix_artist = None
        if axm is not None:
            self.matrix_artist = MatrixArtist(axm, np.zeros((6, n)), digits=2, row_labels=ROW_LABELS,
                                              col_labels=[f"col {i + 1}" for i in range(n)],
                                              title=JACOBIAN_SYMBOLS[frame], fontsize=11)
            self.matrix_title = axm.title
        self.blitter.add(self.arm.artists, self.axis_dots, self.joint_labels, self.pdot_arrow.artists,
                         self.vs_arrow.artists, self.vel_ellipse.artists, self.force_ellipse.artists,
                         self.force_clip_line, self.indicator)
        if self.matrix_artist is not None:
            self.blitter.add([t for row in self.matrix_artist.texts for t in row], self.matrix_title)

        for s in self.angle_sliders + self.rate_sliders:
            s.observe(self._changed, names="value")
        self.frame_dropdown.observe(self._changed, names="value")
        self.ellipse_checkbox.observe(self._changed, names="value")
        self.play.observe(self._on_play, names="value")

        controls = W.VBox([W.HTML("<b>joint angles</b>"), *self.angle_sliders, W.HTML("<b>joint rates</b>"),
                           *self.rate_sliders, self.frame_dropdown, self.ellipse_checkbox,
                           W.HBox([self.play, self.sweep_dropdown])])
        self.children = [W.HBox([controls, self.image]), self.status, self.matrix_html]
        self.refresh()

    # ---- programmatic control
    @property
    def theta(self) -> np.ndarray:
        return np.array([s.value for s in self.angle_sliders])

    @property
    def rates(self) -> np.ndarray:
        return np.array([s.value for s in self.rate_sliders])

    @property
    def frame(self) -> Frame:
        """The frame of the Jacobian shown."""
        frame: Frame = self.frame_dropdown.value
        return frame

    def set(self, theta: ArrayLike | None = None, rates: ArrayLike | None = None,
            frame: Frame | None = None) -> PlanarArmExplorer:
        """Set joint angles (rad), joint rates (rad/s) and/or the frame of the Jacobian shown; redraw once."""
        if frame is not None:
            frame = check_frame(frame, FRAMES)
        with self.hold_updates():
            if theta is not None:
                th = theta_array(theta, self.chain.dof)
                for s, v in zip(self.angle_sliders, th, strict=True):
                    s.value = float(np.clip(v, s.min, s.max))
            if rates is not None:
                r = theta_array(rates, self.chain.dof, "rates")
                for s, v in zip(self.rate_sliders, r, strict=True):
                    s.value = float(np.clip(v, s.min, s.max))
            if frame is not None:
                self.frame_dropdown.value = frame
        return self

    def _on_play(self, change: dict[str, Any]) -> None:
        k = change["new"]
        j = self.sweep_dropdown.value
        self.angle_sliders[j].value = float(np.round(-np.pi + 2 * np.pi * k / self.play.max, 2))

    # ---- drawing
    def _compute_and_update(self) -> None:
        th, rates, frame = self.theta, self.rates, self.frame
        chain = self.chain
        J = jacobian(chain, th, frame, "zyx", on_singularity="nan")  # analytic: NaN at gimbal lock
        J_g = geometric_jacobian(chain, th)
        J_s = space_jacobian(chain, th)
        self.jacobian = J
        self.twist = J @ rates
        self.pdot = J_g[3:5] @ rates
        self.arm.update(th)
        pts = self.arm.points
        tip = pts[-1, :2]
        self.axis_dots.set_data(pts[:-1, 0], pts[:-1, 1])
        off = 0.05 * self.reach
        for i, t in enumerate(self.joint_labels):
            t.set_position((pts[i, 0] + off, pts[i, 1] - 1.6 * off))
        self.pdot_arrow.update(tip, self.pdot)
        V_s = J_s @ rates
        self.vs_arrow.update([0.0, 0.0], V_s[3:5] if frame == "space" else [0.0, 0.0])
        self.vs_arrow.quiver.set_visible(frame == "space")
        show = self.ellipse_checkbox.value
        J_v = J_g[3:5]
        sigma, U = velocity_ellipsoid(J_v)
        self.sigma = sigma
        self.sigma_min = float(sigma[-1])
        self.vel_ellipse.update(tip, sigma * self.vel_scale, U)
        # force: 1/sigma_i along the same U[:, i]; inf along a singular direction
        f_axes, U_f = force_ellipsoid(J_v)
        self.force_semi_axes = f_axes  # the library's values (N per N m), inf where singular
        drawn = f_axes * self.force_scale
        clipped = drawn > self.force_clip
        drawn = np.where(clipped, self.force_clip, drawn)
        self.force_clipped, self.force_drawn_semi_axes = clipped, drawn
        self.force_ellipse.update(tip, drawn, U_f)
        force_state = ("inf" if np.isinf(f_axes[clipped]).any() else "clipped") if clipped.any() else None
        if clipped.any():
            seg = np.concatenate([np.array([tip - self.force_clip * U_f[:, i], tip + self.force_clip * U_f[:, i],
                                            [np.nan] * 2]) for i in np.flatnonzero(clipped)])
            self.force_clip_line.set_data(seg[:, 0], seg[:, 1])
        self.force_ellipse.line.set_linestyle(":" if force_state else "--")
        self.vel_ellipse.line.set_visible(show)
        self.force_ellipse.line.set_visible(show)
        self.force_clip_line.set_visible(show and force_state is not None)
        self.force_state = force_state
        # singularity indicator
        s = self.sigma_min
        if s < 1e-9:
            level, word = "bad", "SINGULAR: the tool cannot move along one direction"
        elif s < self.sing_tol:
            level, word = "warn", "near a singularity"
        else:
            level, word = "ok", "well away from singularities"
        self.level = level
        colour = {"ok": PALETTE["ok"], "warn": PALETTE["warning"], "bad": PALETTE["singular"]}[level]
        self.indicator.set_text(f"smallest singular value of $J_v$: {s:.3f} m\n{word}")
        box = self.indicator.get_bbox_patch()
        if box is not None:
            box.set_edgecolor(colour)
            box.set_linewidth(3)
        self.arm.link_line.set_color(PALETTE["link"] if level == "ok" else colour)
        # legend entries are copies made when the legend is built (arm colour, force line style):
        # rebuild it when what they show changes
        legend_key = (frame, show, force_state, level)
        if legend_key != self._legend_kind:  # the v_s arrow and the clip mark are listed only when drawn
            handles = [self.arm.link_line, self.pdot_arrow.quiver]
            handles += [self.vs_arrow.quiver] if frame == "space" else []
            handles += [self.vel_ellipse.line, self.force_ellipse.line]
            ell_label, clip_label = FORCE_LABELS[force_state]
            self.force_ellipse.line.set_label(ell_label)
            if show and force_state:
                self.force_clip_line.set_label((clip_label or "%.2f") % self.force_clip)
                handles.append(self.force_clip_line)
            self.legend = self.ax.legend(handles=handles, loc="upper left", fontsize=8.5, framealpha=0.85)
            self._legend_kind = legend_key
            self.blitter.invalidate()
        self.status.value = _status_html(
            f"σ<sub>min</sub>(J<sub>v</sub>) = {s:.4f} m (J<sub>v</sub>: the x, y rows of ṗ) — <b>{word}</b>; "
            f"manipulability √det(J<sub>v</sub>J<sub>v</sub><sup>T</sup>) = {np.prod(sigma):.4f} m²", level)
        sym = JACOBIAN_SYMBOLS[frame]
        th_txt = ", ".join(f"{v:.2f}" for v in th)
        self.matrix_latex = matrix_latex(J, f"{sym}(\\theta)", digits=3)
        twist_tex = matrix_latex(self.twist[:, None], f"{TWIST_SYMBOLS[frame]} = {sym}\\dot\\theta", digits=3)
        shown = _latex_block(self.matrix_latex + r"\qquad " + twist_tex)
        self.matrix_html.value = (
            f"<div style='font-size:14px'>Formula: {_latex_block(JACOBIAN_FORMULAS[frame])}"
            f"At θ = ({th_txt}) rad, rows (ω<sub>x</sub>, ω<sub>y</sub>, ω<sub>z</sub>, v<sub>x</sub>, "
            f"v<sub>y</sub>, v<sub>z</sub>)"
            f"{' (first three rows: ZYX angle rates)' if frame == 'analytic' else ''}:"
            f"{shown}</div>"
        )
        if self.matrix_artist is not None:
            self.matrix_artist.update(J)
            self.matrix_title.set_text(f"${sym}(\\theta)$, columns per joint")


def planar_arm_explorer(chain: SerialChain | None = None, theta: ArrayLike | None = None,
                        rates: ArrayLike | None = None, frame: Frame | None = None, **kw: Any) -> PlanarArmExplorer:
    r"""A live explorer of a planar arm's Jacobians (chapters 2 and 5).

    Parameters
    ----------
    chain : SerialChain, optional
        A planar arm (default :func:`jacobians.robots.planar_2r`); a non-planar
        chain raises ``ValueError``.
    theta, rates : array_like, shape (n,), optional
        Initial joint angles (rad) and rates (rad/s).
    frame : {"space", "body", "geometric", "analytic"}, default "space"
        The Jacobian shown as a matrix.

    Returns
    -------
    PlanarArmExplorer
        An ``ipywidgets.VBox``. ``.set(theta=, rates=, frame=)`` drives it;
        ``.jacobian``, ``.twist``, ``.pdot``, ``.sigma_min``, ``.matrix_latex``,
        ``.arm`` (the drawn artists) and ``.png`` hold what it shows.

    The ellipses are :func:`jacobians.analysis.velocity_ellipsoid` and
    :func:`jacobians.analysis.force_ellipsoid` of :math:`J_v` (the x, y rows of
    the geometric Jacobian), kept as ``.sigma`` and ``.force_semi_axes``
    (``inf`` along a singular direction). A force semi-axis drawn longer than
    ``.force_clip`` (1.25 x the reach) is drawn at that length: the outline turns
    dotted, a dash-dot line marks the clipped direction, and the legend says so
    (``.force_clipped``, ``.force_state``: None, ``"clipped"`` or ``"inf"``).
    """
    return PlanarArmExplorer(chain, theta, rates, frame, **kw)


def planar_arm_explorer_animation(chain: SerialChain | None = None, theta: ArrayLike | None = None,
                                  rates: ArrayLike | None = None, frame: Frame | None = None, sweep: int | None = None,
                                  frames: int = 36, dpi: float = 72, interval: float = 150) -> FrameSource:
    r"""The explorer's view as a :class:`~jacobians.plotting.FrameSource`, sweeping joint ``sweep``
    (1-based; default the last) over [-π, π].

    Shows the arm, :math:`\dot p`, both ellipses, the singularity indicator and
    the chosen Jacobian's numbers in a panel; embed with
    :func:`jacobians.plotting.animation_html`. ``.explorer`` is the
    :class:`PlanarArmExplorer` that draws the frames, ``.path`` the (frames, n)
    joint angles of the frames.
    """
    w = PlanarArmExplorer(chain, theta, rates, frame, static=True, dpi=dpi)
    n = w.chain.dof
    j = n - 1 if sweep is None else int(sweep) - 1
    if not 0 <= j < n:
        raise ValueError(f"Expected sweep between 1 and {n}, got {sweep!r}")
    th0 = w.theta
    angles = np.linspace(-np.pi, np.pi, int(frames))

    def draw(k: int) -> list:
        th = th0.copy()
        th[j] = angles[k]
        w.set(theta=th)
        return []

    draw(0)
    path = np.tile(th0, (len(angles), 1))
    path[:, j] = angles
    return FrameSource(w.fig, draw, len(angles), interval=interval, render=w.blitter.render_rgba, explorer=w,
                       path=path)
