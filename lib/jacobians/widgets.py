r"""Interactive explorers for the course (ipywidgets 8 + matplotlib), and their static twins.

Four widgets, each a function returning an ``ipywidgets.VBox`` subclass:

* :func:`planar_arm_explorer` (chapters 2 and 5): joint angles and rates, the
  arm with frames {s} and {b}, the tool velocity :math:`\dot p` from
  :math:`J\dot\theta`, a choice of Jacobian shown as a live matrix with its
  formula, velocity and force ellipses, a singularity indicator, a Play button
  that sweeps a joint.
* :func:`columns_explorer` (chapter 4): which joints change column i of
  :math:`J_s` (those before i) and of :math:`J_b` (those after i).
* :func:`gimbal_lock_explorer` (chapter 6): ZYX coordinates of a spherical
  wrist's tool orientation; :math:`B(\phi)` and :math:`\det B` next to the
  smallest singular value of the angular rows of J, and the analytic Jacobian
  blowing up as the ZYX pitch goes to ±90° while the geometric Jacobian stays
  well-conditioned (on a ZYZ wrist, away from its own singularity θ2 = 0).
* :func:`resolved_rate_explorer` (chapter 9): a planar arm following a path with
  the pseudo-inverse or damped least squares; joint rates plotted; what happens
  near a singularity.

How they draw. The figure is a plain :class:`matplotlib.figure.Figure` on an
Agg canvas (no pyplot, no ipympl). Its fixed parts (axes, ticks, labels,
legend) are drawn once and kept as a bitmap; a change of a control updates the
moving artists with ``set_data`` and draws only those over the kept bitmap
(blitting), then sends the PNG to an ``ipywidgets.Image``. That works in any
Jupyter with a kernel and is easy to test: every widget has a ``set(...)``
method and exposes what it drew.

Static book: each widget has a ``*_animation`` function returning a
:class:`jacobians.plotting.FrameSource` of the same view (its ``explorer`` is
the widget that draws the frames), for :func:`jacobians.plotting.animation_html`.

Which Jacobian a widget shows is a ``frame`` (:mod:`jacobians.frames`); the
former parameter name ``kind`` is still accepted.

The numbers come from the library: the ellipses from
:func:`jacobians.analysis.velocity_ellipsoid` and
:func:`jacobians.analysis.force_ellipsoid` (a force semi-axis that is infinite
at a singularity, or too long for the view, is drawn clipped and marked), the
resolved-rate runs from :func:`jacobians.velocity.resolved_rate`.
"""

from __future__ import annotations

import contextlib
import io

import ipywidgets as W
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from . import robots
from . import velocity as _velocity
from ._validation import as_float_array, theta_array
from .analysis import force_ellipsoid, velocity_ellipsoid
from .chain import _as_chain
from .frames import FRAMES, JACOBIAN_SYMBOLS, Frame, check_frame
from .jacobian import analytic_jacobian, body_jacobian, geometric_jacobian, jacobian, pose_coordinates, space_jacobian
from .plotting import (
    COLUMN_COLORS,
    PALETTE,
    EllipseArtist,
    FrameSource,
    MatrixArtist,
    PlanarArmArtist,
    SpatialChainArtist,
    TwistArtist,
    arm_reach,
    check_planar,
    matrix_latex,
    setup_3d_axes,
    setup_planar_axes,
)
from .representations import rate_to_angular_velocity, representation_singularity_margin

__all__ = [
    "PlanarArmExplorer",
    "planar_arm_explorer",
    "planar_arm_explorer_animation",
    "ColumnsExplorer",
    "columns_explorer",
    "columns_explorer_animation",
    "GimbalLockExplorer",
    "gimbal_lock_explorer",
    "gimbal_lock_animation",
    "ResolvedRateExplorer",
    "resolved_rate_explorer",
    "resolved_rate_animation",
]

ROW_LABELS = ["ωx", "ωy", "ωz", "vx", "vy", "vz"]
ROW_LABELS_TEX = [r"\omega_x", r"\omega_y", r"\omega_z", r"v_x", r"v_y", r"v_z"]
FONT = 12


# ---------------------------------------------------------------- drawing machinery

class _Blitter:
    """Draw a figure's fixed part once, then only its moving artists; return PNG bytes."""

    def __init__(self, fig: Figure, live: bool):
        self.fig = fig
        self.canvas = FigureCanvasAgg(fig)
        self.live = live
        self.dynamic: list = []
        self._bg = None

    def add(self, *artists):
        for a in artists:
            if a is None:
                continue
            if isinstance(a, (list, tuple)):
                self.add(*a)
                continue
            if self.live:
                a.set_animated(True)
            self.dynamic.append(a)

    def invalidate(self):
        self._bg = None

    def render_rgba(self) -> np.ndarray:
        """Kept background + moving artists; the canvas's RGBA buffer (h, w, 4)."""
        c = self.canvas
        if self._bg is None:
            c.draw()
            self._bg = c.copy_from_bbox(self.fig.bbox)
        else:
            c.restore_region(self._bg)
        for a in self.dynamic:
            if a.get_visible():
                (a.axes or self.fig).draw_artist(a)
        return np.asarray(c.buffer_rgba())

    def render(self) -> bytes:
        return _png(self.render_rgba())

    def render_from_scratch(self) -> bytes:
        """Full redraw without the kept bitmap (for comparisons)."""
        self._bg = None
        return self.render()


def _png(rgba: np.ndarray) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(rgba[..., :3]).save(buf, format="png", compress_level=1)
    return buf.getvalue()


class _Explorer(W.VBox):
    """Common parts: a figure, an Image, held updates, a render counter."""

    def _setup(self, fig: Figure, static: bool):
        self.static = bool(static)
        self.fig = fig
        # static (book) figures blit too: their FrameSource renders frames with self.blitter.render_rgba
        self.blitter = _Blitter(fig, live=True)
        self.image = W.Image(format="png", layout=W.Layout(width=f"{int(fig.get_figwidth() * fig.dpi)}px"))
        self.render_count = 0
        self._hold = 0

    @contextlib.contextmanager
    def hold_updates(self):
        """Change several controls and redraw once at the end."""
        self._hold += 1
        try:
            yield self
        finally:
            self._hold -= 1
            if self._hold == 0:
                self.refresh()

    def _changed(self, change=None):
        if self._hold == 0:
            self.refresh()

    def refresh(self):
        """Recompute from the controls, move the artists, and (live) send a new PNG."""
        self._compute_and_update()
        if not self.static:
            self.png = self.blitter.render()
            self.image.value = self.png
        self.render_count += 1

    def _compute_and_update(self):  # pragma: no cover - abstract
        raise NotImplementedError

    def close_figure(self):
        self.fig.clear()


def _slider(description, value, lo, hi, step, color=None, readout_format=".2f", width="330px"):
    style = {"description_width": "70px"}
    if color:
        style["handle_color"] = color
    return W.FloatSlider(value=float(value), min=lo, max=hi, step=step, description=description,
                         continuous_update=True, readout_format=readout_format, style=style,
                         layout=W.Layout(width=width))


def _latex_block(*lines) -> str:
    return "".join(f"<div style='margin:2px 0'>$${ln}$$</div>" for ln in lines)


def _status_html(text, ok_level):
    colour = {"ok": PALETTE["ok"], "warn": PALETTE["warning"], "bad": PALETTE["singular"]}[ok_level]
    return (f"<div style='padding:4px 8px;border-left:8px solid {colour};font-size:15px'>"
            f"{text}</div>")


def _planar_theta(chain, theta, default):
    n = chain.dof
    if theta is None:
        base = np.array(default + [0.4] * n)[:n]
        return base
    return theta_array(theta, n)


# ---------------------------------------------------------------- 1. planar arm explorer

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


def _frame_or_kind(frame: Frame | None, kind: Frame | None, default: Frame | None = None) -> Frame | None:
    """``frame``, or ``kind`` (its former name), checked; ``default`` if neither is given."""
    if kind is not None:
        if frame is not None and frame != kind:
            raise ValueError(f"Expected one of frame and its former name kind, got frame={frame!r} and kind={kind!r}")
        frame = kind
    if frame is None:
        return default
    return check_frame(frame, FRAMES)


class PlanarArmExplorer(_Explorer):
    """Planar arm explorer; see :func:`planar_arm_explorer`."""

    FRAMES = FRAMES

    def __init__(self, chain=None, theta=None, rates=None, frame: Frame | None = None, *, static=False,
                 show_ellipses=True, figsize=(5.6, 5.4), dpi=80, matrix_panel=None, kind: Frame | None = None):
        super().__init__()
        chain = robots.planar_2r() if chain is None else chain
        self.chain = check_planar(chain, "the planar arm explorer")
        n = self.chain.dof
        theta = _planar_theta(self.chain, theta, [0.5, 1.2, -0.8])
        rates = np.ones(n) * 0.5 if rates is None else theta_array(rates, n, "rates")
        frame = _frame_or_kind(frame, kind, "space")
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
            ax = fig.add_axes([0.08, 0.1, 0.52, 0.8])
            axm = fig.add_axes([0.7, 0.12, 0.28, 0.72])
        else:
            fig = Figure(figsize=figsize, dpi=dpi)
            ax = fig.add_axes([0.14, 0.1, 0.82, 0.82])
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
        self._legend_kind = None
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
        return self.frame_dropdown.value

    @property
    def kind(self) -> Frame:
        """Former name of :attr:`frame`."""
        return self.frame

    def set(self, theta=None, rates=None, frame: Frame | None = None, *, kind: Frame | None = None):
        """Set joint angles (rad), joint rates (rad/s) and/or the frame of the Jacobian shown; redraw once.

        ``kind`` is the former name of ``frame``.
        """
        frame = _frame_or_kind(frame, kind)
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

    def _on_play(self, change):
        k = change["new"]
        j = self.sweep_dropdown.value
        self.angle_sliders[j].value = float(np.round(-np.pi + 2 * np.pi * k / self.play.max, 2))

    # ---- drawing
    def _compute_and_update(self):
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
            seg = [np.array([tip - self.force_clip * U_f[:, i], tip + self.force_clip * U_f[:, i], [np.nan] * 2])
                   for i in np.flatnonzero(clipped)]
            seg = np.concatenate(seg)
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
        self.indicator.get_bbox_patch().set_edgecolor(colour)
        self.indicator.get_bbox_patch().set_linewidth(3)
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
                self.force_clip_line.set_label(clip_label % self.force_clip)
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


def planar_arm_explorer(chain=None, theta=None, rates=None, frame: Frame | None = None, **kw) -> PlanarArmExplorer:
    r"""A live explorer of a planar arm's Jacobians (chapters 2 and 5).

    Parameters
    ----------
    chain : SerialChain, optional
        A planar arm (default :func:`jacobians.robots.planar_2r`); a non-planar
        chain raises ``ValueError``.
    theta, rates : array_like, shape (n,), optional
        Initial joint angles (rad) and rates (rad/s).
    frame : {"space", "body", "geometric", "analytic"}, default "space"
        The Jacobian shown as a matrix (``kind=`` is its former name).

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


def planar_arm_explorer_animation(chain=None, theta=None, rates=None, frame: Frame | None = None, sweep=None,
                                  frames=36, dpi=72, interval=150, *, kind: Frame | None = None) -> FrameSource:
    r"""The explorer's view as a :class:`~jacobians.plotting.FrameSource`, sweeping joint ``sweep``
    (1-based; default the last) over [-π, π].

    Shows the arm, :math:`\dot p`, both ellipses, the singularity indicator and
    the chosen Jacobian's numbers in a panel; embed with
    :func:`jacobians.plotting.animation_html`. ``.explorer`` is the
    :class:`PlanarArmExplorer` that draws the frames, ``.path`` the (frames, n)
    joint angles of the frames; ``kind=`` is the former name of ``frame``.
    """
    w = PlanarArmExplorer(chain, theta, rates, _frame_or_kind(frame, kind, "space"), static=True, dpi=dpi)
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


# ---------------------------------------------------------------- 2. space vs body columns

class ColumnsExplorer(_Explorer):
    """Space-vs-body columns; see :func:`columns_explorer`."""

    def __init__(self, chain=None, column=3, theta=None, *, static=False, figsize=(6.0, 5.2), dpi=80):
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
        if self.planar:
            ax = fig.add_axes([0.14, 0.1, 0.82, 0.82])
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
        self._last_J = None
        self.changed_space_columns: list = []
        self.changed_body_columns: list = []
        self.last_moved_joint = None
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

    def set(self, theta=None, column=None):
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

    def move_joint(self, joint, value):
        """Move one joint (1-based) to ``value`` rad; records which columns of J_s and J_b changed."""
        self.angle_sliders[int(joint) - 1].value = float(value)
        return self

    def _joint_moved(self, k):
        if self._hold == 0:
            self.last_moved_joint = k + 1
            self.refresh()

    def roles(self, column=None):
        """For column i (1-based): (joints before i, joints after i), 1-based lists."""
        i = self.column if column is None else int(column)
        return list(range(1, i)), list(range(i + 1, self.chain.dof + 1))

    def _compute_and_update(self):
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


def columns_explorer(chain=None, column=3, theta=None, **kw) -> ColumnsExplorer:
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


def columns_explorer_animation(chain=None, column=3, frames=36, dpi=72, interval=150) -> FrameSource:
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
    w.ax.set_position([0.0, 0.04, 0.58, 0.9])
    axm = fig.add_axes([0.66, 0.16, 0.3, 0.66])
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


# ---------------------------------------------------------------- 3. gimbal lock

def _sigma_min_angular(J):
    """Smallest singular value of the angular (ω) rows of geometric Jacobians (..., 6, n)."""
    return np.linalg.svd(np.asarray(J)[..., :3, :], compute_uv=False)[..., -1]


class GimbalLockExplorer(_Explorer):
    """ZYX coordinates of a wrist's tool orientation and their gimbal lock; see :func:`gimbal_lock_explorer`."""

    WRISTS = {"zyz": "ZYZ wrist: only its ZYX coordinates lock", "zyx": "ZYX wrist: both coincide"}

    def __init__(self, angles_deg=(30.0, 60.0, 0.0), wrist="zyz", tool=0.3, *, theta2_range=(-180.0, 180.0),
                 n_grid=241, static=False, figsize=(8.4, 6.0), dpi=80):
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
        ax3 = fig.add_axes([0.0, 0.40, 0.46, 0.56], projection="3d")
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
        axm = fig.add_axes([0.10, 0.03, 0.32, 0.19])
        self.matrix_artist = MatrixArtist(axm, np.eye(3), digits=2, fontsize=fs,
                                          col_labels=[r"$\dot\phi_1$", r"$\dot\phi_2$", r"$\dot\phi_3$"],
                                          row_labels=[r"$\omega_x$", r"$\omega_y$", r"$\omega_z$"])
        axm.tick_params(labelsize=fs)
        axm.xaxis.tick_top()
        self.matrix_title = fig.text(0.26, 0.305, "", ha="center", va="center", fontsize=fs)
        ax_d = fig.add_axes([0.60, 0.60, 0.38, 0.27])
        ax_n = fig.add_axes([0.60, 0.12, 0.38, 0.27], sharex=ax_d)
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
        self._curve_key = None
        self.refresh()

    def _wrist_chain(self, wrist):
        return robots.zyz_wrist(self._tool) if wrist == "zyz" else robots.zyx_wrist(self._tool)

    def _wrist_changed(self, change):
        self.chain = self._wrist_chain(change["new"])
        self.arm.chain = self.chain
        self._changed()

    @property
    def angles_deg(self) -> np.ndarray:
        return np.array([s.value for s in self.angle_sliders])

    @property
    def wrist(self) -> str:
        return self.wrist_dropdown.value

    def set(self, angles_deg=None, theta2_deg=None, wrist=None):
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

    def _curves(self, th):
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

    def _compute_and_update(self):
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


def gimbal_lock_explorer(angles_deg=(30.0, 60.0, 0.0), wrist="zyz", tool=0.3, **kw) -> GimbalLockExplorer:
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


def gimbal_lock_animation(frames=15, dpi=80, interval=250, wrist="zyz", theta1_deg=30.0, theta3_deg=0.0,
                          theta2_deg=(45.0, 135.0)) -> FrameSource:
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


# ---------------------------------------------------------------- 4. resolved-rate motion

def _planar_path(kind, reach, n_steps):
    """Desired tool positions (N, 2) and velocities (N, 2) over t in [0, T] with T = 4 s."""
    T = 4.0
    t = np.linspace(0.0, T, n_steps)
    if kind == "circle":
        c, r = np.array([0.45 * reach, 0.2 * reach]), 0.3 * reach
        w = 2 * np.pi / T
        x = c + r * np.column_stack([np.cos(w * t), np.sin(w * t)])
        v = r * w * np.column_stack([-np.sin(w * t), np.cos(w * t)])
    elif kind == "to full reach":
        a, b = np.array([0.3 * reach, 0.5 * reach]), np.array([reach, 0.0])
        x = a + np.outer(t / T, b - a)
        v = np.tile((b - a) / T, (n_steps, 1))
    elif kind == "close past the base":
        a, b = np.array([0.6 * reach, 0.03 * reach]), np.array([-0.6 * reach, 0.03 * reach])
        x = a + np.outer(t / T, b - a)
        v = np.tile((b - a) / T, (n_steps, 1))
    else:
        raise ValueError(f"Expected path 'circle', 'to full reach' or 'close past the base', got {kind!r}")
    return t, x, v


class ResolvedRateExplorer(_Explorer):
    """Resolved-rate motion; see :func:`resolved_rate_explorer`."""

    PATHS = ("circle", "to full reach", "close past the base")
    RATE_LIMIT = 8.0  # rad/s shown on the rate plot; larger peaks leave the plot and are printed
    GAIN = 2.0  # feedback gain K (1/s) of the controller

    def __init__(self, chain=None, path="close past the base", method="pinv", damping=0.1, *, static=False, n_steps=160,
                 figsize=(9.6, 4.8), dpi=80):
        super().__init__()
        chain = robots.planar_2r() if chain is None else chain
        self.chain = check_planar(chain, "the resolved-rate explorer")
        if path not in self.PATHS:
            raise ValueError(f"Expected path one of {self.PATHS}, got {path!r}")
        if method not in ("pinv", "dls"):
            raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
        self.reach = arm_reach(self.chain)
        self.n_steps = int(n_steps)
        self.path_dropdown = W.Dropdown(options=list(self.PATHS), value=path, description="path",
                                        layout=W.Layout(width="250px"))
        self.method_dropdown = W.Dropdown(options=[("pseudo-inverse", "pinv"), ("damped least squares", "dls")],
                                          value=method, description="method", layout=W.Layout(width="250px"))
        self.damping_slider = W.FloatLogSlider(value=float(damping), base=10, min=-3, max=0, step=0.1,
                                               description="λ (m)", readout_format=".3f", continuous_update=False,
                                               layout=W.Layout(width="330px"), style={"description_width": "70px"})
        self.time_slider = W.IntSlider(value=0, min=0, max=self.n_steps - 1, description="step",
                                       layout=W.Layout(width="330px"), style={"description_width": "70px"})
        self.play = W.Play(value=0, min=0, max=self.n_steps - 1, step=2, interval=60, description="Play")
        W.jslink((self.play, "value"), (self.time_slider, "value"))
        self.status = W.HTML()
        fig = Figure(figsize=figsize, dpi=dpi)
        self._setup(fig, static)
        ax = fig.add_axes([0.07, 0.12, 0.4, 0.78])
        axr = fig.add_axes([0.58, 0.12, 0.4, 0.78])
        self.ax, self.ax_rates = ax, axr
        setup_planar_axes(ax, self.chain, title="tool following the path", margin=0.1)
        (self.des_line,) = ax.plot([], [], "--", color=PALETTE["path"], lw=2.2, label="desired path")
        (self.act_line,) = ax.plot([], [], "-", color=PALETTE["velocity"], lw=1.5, label="actual tool path")
        self.arm = PlanarArmArtist(ax, self.chain, np.zeros(self.chain.dof), show_frames=False, label="arm")
        (self.target,) = ax.plot([], [], "x", color=PALETTE["path"], ms=12, mew=3, zorder=6)
        ax.legend(loc="upper left", fontsize=8.5, framealpha=0.85)
        axr.set_ylim(-self.RATE_LIMIT, self.RATE_LIMIT)  # fixed, so methods compare at a glance
        axr.set_xlabel("time t (s)")
        axr.set_ylabel("joint rate (rad/s)")
        axr.set_title("joint rates from $J_v^{\\#}\\dot x$", fontsize=FONT)
        self.rate_lines = [axr.plot([], [], color=COLUMN_COLORS[i % 7], label=f"$\\dot\\theta_{i + 1}$")[0]
                           for i in range(self.chain.dof)]
        self.cursor = axr.axvline(0.0, color="0.3", lw=1.2)
        self.rate_text = axr.text(0.02, 0.97, "", transform=axr.transAxes, va="top", fontsize=FONT - 1,
                                  bbox=dict(boxstyle="round", fc="white", ec="0.6"))
        axr.legend(loc="lower right", fontsize=9)
        self.blitter.add(self.des_line, self.act_line, self.arm.artists, self.target, self.rate_lines, self.cursor,
                         self.rate_text)
        self._sim_key = None
        for c in (self.path_dropdown, self.method_dropdown, self.damping_slider, self.time_slider):
            c.observe(self._changed, names="value")
        controls = W.VBox([self.path_dropdown, self.method_dropdown, self.damping_slider,
                           W.HBox([self.play]), self.time_slider])
        self.children = [W.HBox([controls, self.status]), self.image]
        self.refresh()

    def set(self, path=None, method=None, damping=None, step=None):
        """Choose the path, the method ('pinv' or 'dls'), the damping λ, and/or the time step shown."""
        with self.hold_updates():
            if path is not None:
                if path not in self.PATHS:
                    raise ValueError(f"Expected path one of {self.PATHS}, got {path!r}")
                self.path_dropdown.value = path
            if method is not None:
                if method not in ("pinv", "dls"):
                    raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
                self.method_dropdown.value = method
            if damping is not None:
                self.damping_slider.value = float(damping)
            if step is not None:
                self.time_slider.value = int(np.clip(step, 0, self.n_steps - 1))
                self.play.value = self.time_slider.value  # keep the linked Play in step
        return self

    def _simulate(self):
        path, method, lam = self.path_dropdown.value, self.method_dropdown.value, self.damping_slider.value
        key = (path, method, lam if method == "dls" else None)
        if key == self._sim_key:
            return False
        t, x_des, v_des = _planar_path(path, self.reach, self.n_steps)
        # start on the path, elbow up: solve for the start by resolved rate from a bent pose
        th0 = self._start_configuration(x_des[0])
        dt = t[1] - t[0]
        self.t, self.x_des, self.v_des = t, x_des, v_des
        # the feed-forward is the path's exact velocity (not the library's default forward differences)
        self.result = _velocity.resolved_rate(self.chain, th0, x_des, dt, method=method, damping=lam,
                                              gain=self.GAIN, target_velocities=v_des)
        r = self.result
        self.thetas, self.rates_hist, self.x_act, self.sigma_hist, self.errors = (
            r.thetas, r.rates, r.positions, r.sigma_min, r.errors)
        self._sim_key = key
        return True

    def _start_configuration(self, x0):
        n = self.chain.dof
        th = np.array([0.3] + [0.9] * (n - 1))[:n]
        for _ in range(200):  # Newton steps with a little damping (1 mm)
            J = geometric_jacobian(self.chain, th)[3:5]
            e = x0 - self.chain.fk(th)[:2, 3]
            if np.linalg.norm(e) < 1e-12:
                break
            th = th + _velocity.dls_rates(J, e, 1e-3)
        return th

    def _compute_and_update(self):
        if self._simulate():
            self.des_line.set_data(self.x_des[:, 0], self.x_des[:, 1])
            for i, ln in enumerate(self.rate_lines):
                ln.set_data(self.t, self.rates_hist[:, i])
            self.ax_rates.set_xlim(0, self.t[-1])
        k = self.time_slider.value
        if self.play.value != k:
            self.play.value = k  # the browser links them; mirror it here so both agree when shown
        self.step = k
        self.arm.update(self.thetas[k])
        self.act_line.set_data(self.x_act[: k + 1, 0], self.x_act[: k + 1, 1])
        self.target.set_data([self.x_des[k, 0]], [self.x_des[k, 1]])
        self.cursor.set_xdata([self.t[k], self.t[k]])
        err = float(self.errors[k])
        s = float(self.sigma_hist[k])
        peak = float(np.abs(self.rates_hist).max())
        self.tracking_error, self.current_sigma_min, self.peak_rate = err, s, peak
        self.rate_text.set_text(f"t = {self.t[k]:.2f} s   σ_min(J_v) = {s:.3f} m\n"
                                f"|θ̇| now {np.linalg.norm(self.rates_hist[k]):.2f} rad/s, peak {peak:.1f} rad/s\n"
                                f"tracking error {1000 * err:.1f} mm")
        level = "bad" if s < 0.02 * self.reach else "warn" if s < 0.1 * self.reach else "ok"
        self.level = level
        meth = "pseudo-inverse" if self.method_dropdown.value == "pinv" else \
            f"damped least squares, λ = {self.damping_slider.value:.3f} m"
        self.status.value = _status_html(
            f"{meth}: smallest singular value of J<sub>v</sub> {s:.3f} m; peak joint rate over the run "
            f"{peak:.1f} rad/s; largest tracking error {1000 * float(self.errors.max()):.1f} mm",
            level)


def resolved_rate_explorer(chain=None, path="close past the base", method="pinv", damping=0.1,
                           **kw) -> ResolvedRateExplorer:
    r"""Resolved-rate motion of a planar arm along a path (chapter 9).

    Paths: ``"circle"`` (well inside the workspace), ``"to full reach"`` (ends
    on the boundary, where the arm is stretched and singular) and ``"close past
    the base"`` (a straight line passing 3 % of the reach from the base: the arm
    must swing joint 1 through about half a turn in a moment). Methods:
    pseudo-inverse, whose joint rates blow up approaching a singularity, or
    damped least squares, whose rates stay bounded at the cost of a tracking
    error. ``.set(path=, method=, damping=, step=)`` drives it. The run is
    :func:`jacobians.velocity.resolved_rate` (gain K = 2/s, the path's own
    velocity as feed-forward), kept as ``.result``; ``.thetas``,
    ``.rates_hist``, ``.x_act``, ``.sigma_hist``, ``.errors`` are its fields, and
    ``.peak_rate``, ``.tracking_error`` what the view reports.
    """
    return ResolvedRateExplorer(chain, path, method, damping, **kw)


def resolved_rate_animation(chain=None, path="close past the base", method="pinv", damping=0.1, frames=36, dpi=72,
                            interval=120) -> FrameSource:
    """The resolved-rate view as a :class:`~jacobians.plotting.FrameSource` over the run.

    ``.explorer`` is the :class:`ResolvedRateExplorer`, ``.path`` the joint angles of the frames.
    """
    w = ResolvedRateExplorer(chain, path, method, damping, static=True, dpi=dpi)
    steps = np.linspace(0, w.n_steps - 1, int(frames)).round().astype(int)

    def draw(k: int) -> list:
        w.set(step=steps[k])
        return []

    draw(0)
    return FrameSource(w.fig, draw, len(steps), interval=interval, render=w.blitter.render_rgba, explorer=w,
                       path=w.thetas[steps].copy())
