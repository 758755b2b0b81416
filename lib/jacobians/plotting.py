r"""Figures and animations for the course (matplotlib).

Every drawing helper returns a small *artist* object that keeps the matplotlib
artists it made and has an ``update(...)`` method that moves them with
``set_data`` / ``set_offsets``; nothing is rebuilt. The widgets of
:mod:`jacobians.widgets` and the animations below rely on that.

Colours come from :data:`PALETTE`, the Okabe–Ito palette, which stays
distinguishable under the common colour-vision deficiencies; its semantic keys
(``"space"``, ``"body"``, ``"velocity"``, ...) keep one meaning across the book.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> import jacobians as jac
>>> from jacobians import plotting
>>> arm = jac.robots.planar_2r()
>>> fig, ax = plt.subplots()
>>> art = plotting.draw_planar_arm(ax, arm, [0.3, 0.5])
>>> art.link_line.get_xydata().shape
(3, 2)
>>> plt.close(fig)
"""

from __future__ import annotations

import re

import numpy as np

import matplotlib
import matplotlib.pyplot as plt
from matplotlib import animation as _animation

from ._validation import as_float_array, theta_array
from .chain import _as_chain

__all__ = [
    "PALETTE",
    "COLUMN_COLORS",
    "set_style",
    "check_planar",
    "arm_reach",
    "PlanarArmArtist",
    "draw_planar_arm",
    "planar_arm_animation",
    "animation_html",
    "blit_frames",
    "compact_png",
    "EllipseArtist",
    "draw_ellipse",
    "FrameArtist",
    "draw_frame",
    "TwistArtist",
    "draw_twist",
    "SpatialChainArtist",
    "draw_spatial_chain",
    "matrix_latex",
    "MatrixArtist",
    "draw_matrix",
]

# ---------------------------------------------------------------- colours and style

_OKABE_ITO = {
    "black": "#000000",
    "orange": "#E69F00",
    "sky_blue": "#56B4E9",
    "bluish_green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "reddish_purple": "#CC79A7",
}

#: Okabe–Ito colours by name, plus semantic keys used throughout the book.
PALETTE: dict[str, str] = dict(_OKABE_ITO)
PALETTE.update(
    {
        "link": _OKABE_ITO["blue"],
        "joint": _OKABE_ITO["black"],
        "base": _OKABE_ITO["black"],
        "space": _OKABE_ITO["orange"],
        "body": _OKABE_ITO["sky_blue"],
        "geometric": _OKABE_ITO["bluish_green"],
        "analytic": _OKABE_ITO["reddish_purple"],
        "velocity": _OKABE_ITO["vermillion"],
        "angular": _OKABE_ITO["reddish_purple"],
        "force": _OKABE_ITO["bluish_green"],
        "path": _OKABE_ITO["orange"],
        "singular": _OKABE_ITO["vermillion"],
        "warning": _OKABE_ITO["orange"],
        "ok": _OKABE_ITO["bluish_green"],
        "highlight": _OKABE_ITO["orange"],
        "muted": "#999999",
        "frame_x": _OKABE_ITO["vermillion"],
        "frame_y": _OKABE_ITO["bluish_green"],
        "frame_z": _OKABE_ITO["blue"],
    }
)

#: Colours for Jacobian columns 1, 2, 3, ... (cycled).
COLUMN_COLORS = (
    _OKABE_ITO["vermillion"],
    _OKABE_ITO["blue"],
    _OKABE_ITO["bluish_green"],
    _OKABE_ITO["reddish_purple"],
    _OKABE_ITO["orange"],
    _OKABE_ITO["sky_blue"],
    _OKABE_ITO["black"],
)


def set_style(font_size: float = 14.0) -> None:
    """Lecture-readable matplotlib defaults: large fonts, thick lines, Okabe–Ito colour cycle.

    Changes ``matplotlib.rcParams`` for the running session.
    """
    from cycler import cycler

    s = float(font_size)
    matplotlib.rcParams.update(
        {
            "font.size": s,
            "axes.titlesize": s + 2,
            "axes.labelsize": s + 1,
            "xtick.labelsize": s - 1,
            "ytick.labelsize": s - 1,
            "legend.fontsize": s - 2,
            "lines.linewidth": 2.5,
            "lines.markersize": 8,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "axes.prop_cycle": cycler(color=list(COLUMN_COLORS)),
            "figure.dpi": 100,
            "savefig.dpi": "figure",
            "figure.autolayout": False,
        }
    )


# ---------------------------------------------------------------- helpers

def check_planar(chain, what: str = "this figure"):
    """Return ``chain`` if it moves in the x–y plane of {s}, else raise ``ValueError``.

    Planar means: every revolute axis is parallel to z, every prismatic
    direction lies in the x–y plane, and the home pose of {b} is a rotation about z.
    """
    chain = _as_chain(chain)
    S = chain.screw_axes
    M = chain.home
    bad = []
    for i in range(chain.dof):
        w, v = S[:3, i], S[3:, i]
        if chain.joint_types[i] == "R":
            if abs(abs(w[2]) - 1.0) > 1e-9 or abs(v[2]) > 1e-9:
                bad.append(f"joint {i + 1} turns about {np.round(w, 3).tolist()}, not about z")
        elif abs(v[2]) > 1e-9:
            bad.append(f"joint {i + 1} slides along {np.round(v, 3).tolist()}, out of the x-y plane")
    if abs(M[2, 2] - 1.0) > 1e-9:
        bad.append("the home pose of {b} is not a rotation about z")
    if bad:
        raise ValueError(
            f"Expected a planar chain (joint axes along z, motion in the x-y plane) for {what}, "
            f"got {chain!r}: " + "; ".join(bad)
        )
    return chain


def arm_reach(chain) -> float:
    """How far the joints and tool get from the origin of {s}, for axis limits.

    The largest distance over the home pose and 64 fixed pseudo-random
    configurations (prismatic joints within [-1, 1]).
    """
    chain = _as_chain(chain)
    rng = np.random.default_rng(0)
    th = rng.uniform(-np.pi, np.pi, size=(64, chain.dof))
    th[:, [c == "P" for c in chain.joint_types]] /= np.pi
    th = np.vstack([np.zeros(chain.dof), th])
    r = float(np.linalg.norm(chain.joint_positions(th), axis=-1).max())
    return max(r, 1e-3)


def _clean(v):
    v = np.array(v, dtype=float)
    v[~np.isfinite(v)] = 0.0
    return v


def _is_3d(ax) -> bool:
    return getattr(ax, "name", "") == "3d"


# ---------------------------------------------------------------- 2-D and 3-D frames and arrows

class TwistArtist:
    """Arrows (a quiver in data units) drawn at points; ``update(points, vectors)`` moves them."""

    def __init__(self, ax, points, vectors, *, color=None, label=None, width=0.012, zorder=5, scale=1.0):
        P = np.atleast_2d(_clean(points))[:, :2]
        V = np.atleast_2d(_clean(vectors))[:, :2] * scale
        if color is None:
            color = PALETTE["velocity"]
        self.ax = ax
        self.scale = float(scale)
        self.quiver = ax.quiver(
            P[:, 0], P[:, 1], V[:, 0], V[:, 1], angles="xy", scale_units="xy", scale=1.0,
            color=color, width=width, zorder=zorder, label=label,
        )

    def update(self, points, vectors):
        P = np.atleast_2d(_clean(points))[:, :2]
        V = np.atleast_2d(_clean(vectors))[:, :2] * self.scale
        self.quiver.set_offsets(P)
        self.quiver.set_UVC(V[:, 0], V[:, 1])
        return self

    @property
    def vectors(self) -> np.ndarray:
        """The drawn vectors (already multiplied by ``scale``), shape (k, 2)."""
        return np.column_stack([self.quiver.U, self.quiver.V])

    @property
    def points(self) -> np.ndarray:
        return np.asarray(self.quiver.get_offsets())

    @property
    def artists(self):
        return [self.quiver]


def draw_twist(ax, point, vector, *, color=None, label=None, scale=1.0, width=0.012, zorder=5) -> TwistArtist:
    """Arrow(s) of ``vector`` (x, y parts used) starting at ``point``, in data units.

    ``point`` and ``vector`` have shape (2,) / (3,) for one arrow or (k, 2) / (k, 3)
    for k arrows; ``scale`` multiplies the drawn length. Returns a :class:`TwistArtist`.
    """
    return TwistArtist(ax, point, vector, color=color, label=label, width=width, zorder=zorder, scale=scale)


class FrameArtist:
    """A coordinate frame drawn as its x, y (and z in 3-D) axes, with labels; ``update(T)`` moves it."""

    def __init__(self, ax, T, label, length, fontsize=None, alpha=1.0, lw=2.5):
        self.ax = ax
        self.length = float(length)
        self.label = label
        self.three_d = _is_3d(ax)
        names = "xyz" if self.three_d else "xy"
        self.axis_lines = []
        self.axis_texts = []
        fs = fontsize or matplotlib.rcParams["font.size"]
        for k in names:
            col = PALETTE[f"frame_{k}"]
            if self.three_d:
                (ln,) = ax.plot([0, 0], [0, 0], [0, 0], color=col, lw=lw, alpha=alpha, solid_capstyle="round")
                tx = ax.text(0, 0, 0, "", color=col, fontsize=fs * 0.85)
            else:
                (ln,) = ax.plot([0, 0], [0, 0], color=col, lw=lw, alpha=alpha, solid_capstyle="round", zorder=4)
                tx = ax.text(0, 0, "", color=col, fontsize=fs * 0.85, ha="center", va="center", zorder=6)
            self.axis_lines.append(ln)
            self.axis_texts.append(tx)
        sub = label.strip("{}") if label else ""
        self._sub = sub
        if self.three_d:
            self.name_text = ax.text(0, 0, 0, "", fontsize=fs, color="black")
        else:
            self.name_text = ax.text(0, 0, "", fontsize=fs, color="black", ha="right", va="top", zorder=6)
        self.update(T)

    def update(self, T):
        T = np.asarray(T, dtype=float)
        o = T[:3, 3]
        L = self.length
        for j, (ln, tx) in enumerate(zip(self.axis_lines, self.axis_texts)):
            tip = o + L * T[:3, j]
            lab = f"$\\mathbf{{{'xyz'[j]}}}_{{{self._sub}}}$" if self._sub else ""
            tip_t = o + 1.22 * L * T[:3, j]
            if self.three_d:
                ln.set_data_3d([o[0], tip[0]], [o[1], tip[1]], [o[2], tip[2]])
                tx.set_position((tip_t[0], tip_t[1]))
                tx.set_3d_properties(tip_t[2], None)
            else:
                ln.set_data([o[0], tip[0]], [o[1], tip[1]])
                tx.set_position((tip_t[0], tip_t[1]))
            tx.set_text(lab)
        if self.label:
            off = -0.12 * L * (T[:3, 0] + T[:3, 1])
            if self.three_d:
                self.name_text.set_position((o[0] + off[0], o[1] + off[1]))
                self.name_text.set_3d_properties(o[2], None)
            else:
                self.name_text.set_position((o[0] + off[0], o[1] + off[1]))
            self.name_text.set_text(self.label)
        self.T = T
        return self

    @property
    def artists(self):
        return self.axis_lines + self.axis_texts + [self.name_text]


def draw_frame(ax, T, label="{s}", length=0.3, **kw) -> FrameArtist:
    """Draw frame ``T`` (4x4) on ``ax``: x red-orange, y green, z blue; named ``label``.

    On a 2-D axes only the x and y axes are drawn (projected on the x–y plane);
    on a 3-D axes (``projection="3d"``) all three. Returns a :class:`FrameArtist`.
    """
    T = as_float_array(T, "T")
    if T.shape != (4, 4):
        raise ValueError(f"Expected T with shape (4, 4), got shape {T.shape}")
    return FrameArtist(ax, T, label, length, **kw)


class EllipseArtist:
    """An ellipse drawn as a closed line; ``update(center, semi_axes, directions)``."""

    def __init__(self, ax, center, semi_axes, directions, n_points=90, **kw):
        self.ax = ax
        self._t = np.linspace(0, 2 * np.pi, n_points)
        kw.setdefault("color", PALETTE["velocity"])
        kw.setdefault("lw", 2.0)
        (self.line,) = ax.plot([], [], **kw)
        self.update(center, semi_axes, directions)

    def points(self, center, semi_axes, directions) -> np.ndarray:
        c = _clean(center)[:2]
        s = _clean(semi_axes)[:2]
        D = _clean(directions)[:2, :2]
        circ = np.stack([np.cos(self._t), np.sin(self._t)])
        return (c[:, None] + D @ (s[:, None] * circ)).T

    def update(self, center, semi_axes, directions):
        P = self.points(center, semi_axes, directions)
        self.line.set_data(P[:, 0], P[:, 1])
        return self

    @property
    def artists(self):
        return [self.line]


def draw_ellipse(ax, center, semi_axes, directions, **kw) -> EllipseArtist:
    r"""Draw the ellipse :math:`\{c + D\,\mathrm{diag}(s)\,u : \|u\| = 1\}` on a 2-D axes.

    ``semi_axes`` (2,) are the half-lengths s, ``directions`` (2, 2) holds the
    unit directions as columns (as returned by an SVD: ``U`` and ``sigma`` of
    the 2x2 linear-velocity block give the velocity ellipse). A zero semi-axis
    draws a segment, which is what the ellipse becomes at a singularity.
    Keyword arguments go to ``ax.plot``. Returns an :class:`EllipseArtist`.
    """
    return EllipseArtist(ax, center, semi_axes, directions, **kw)


# ---------------------------------------------------------------- planar arm

class PlanarArmArtist:
    """What :func:`draw_planar_arm` drew; ``update(theta, twist=None)`` moves it in place."""

    def __init__(self, ax, chain, theta, *, show_frames=True, show_joints=True, color=None, alpha=1.0,
                 label=None, twist=None, frame_length=None, twist_scale=1.0, show_base=True):
        self.ax = ax
        self.chain = chain
        self.alpha = alpha
        color = color or PALETTE["link"]
        L = frame_length if frame_length is not None else 0.22 * arm_reach(chain)
        (self.link_line,) = ax.plot([], [], "-", color=color, lw=5, alpha=alpha, solid_capstyle="round",
                                    label=label if label is not None else (chain.name or "arm"), zorder=3)
        self.joint_markers = None
        if show_joints:
            kind_marker = {"R": "o", "P": "s"}
            (self.joint_markers,) = ax.plot([], [], linestyle="none", marker=kind_marker.get(chain.joint_types[0], "o"),
                                            ms=11, mfc="white", mec=PALETTE["joint"], mew=2.2, alpha=alpha, zorder=4)
        (self.tool_marker,) = ax.plot([], [], linestyle="none", marker="o", ms=6, color=PALETTE["joint"],
                                      alpha=alpha, zorder=4)
        self.base = None
        if show_base:
            (self.base,) = ax.plot([0], [0], linestyle="none", marker="^", ms=16, color=PALETTE["muted"],
                                   alpha=alpha, zorder=2)
        self.frames = []
        self.base_frame = self.tool_frame = None
        if show_frames:
            self.base_frame = FrameArtist(ax, np.eye(4), "{s}", L, alpha=alpha)
            self.tool_frame = FrameArtist(ax, chain.home, "{b}", 0.8 * L, alpha=alpha)
            self.frames = [self.base_frame, self.tool_frame]
        self.twist_artist = None
        self.twist_scale = float(twist_scale)
        self._want_twist = twist is not None
        self.update(theta, twist=twist)

    def update(self, theta, twist=None):
        """Move the arm to ``theta``; if given, draw ``twist`` (a space twist V_s, 6-vector) at the tool.

        The arrow is the velocity of the origin of {b},
        :math:`\\dot p = v_s + \\omega_s \\times p`.
        """
        th = theta_array(theta, self.chain.dof)
        pts = self.chain.joint_positions(th)
        self.theta = th
        self.points = pts
        self.link_line.set_data(pts[:, 0], pts[:, 1])
        if self.joint_markers is not None:
            self.joint_markers.set_data(pts[:-1, 0], pts[:-1, 1])
        self.tool_marker.set_data([pts[-1, 0]], [pts[-1, 1]])
        T = None
        if self.tool_frame is not None:
            T = self.chain.fk(th)
            self.tool_frame.update(T)
        if twist is not None:
            V = _clean(twist)
            p = pts[-1]
            pdot = V[3:] + np.cross(V[:3], p)
            if self.twist_artist is None:
                self.twist_artist = TwistArtist(self.ax, p, pdot, color=PALETTE["velocity"],
                                                label=r"$\dot p$ of {b}", scale=self.twist_scale)
            else:
                self.twist_artist.update(p, pdot)
        return self

    @property
    def artists(self):
        out = [self.link_line, self.tool_marker]
        if self.joint_markers is not None:
            out.append(self.joint_markers)
        if self.base is not None:
            out.append(self.base)
        for f in self.frames:
            out += f.artists
        if self.twist_artist is not None:
            out += self.twist_artist.artists
        return out


def setup_planar_axes(ax, chain, *, title=None, margin=0.25):
    """Equal-aspect axes around the arm's reach, labelled x (m), y (m)."""
    r = arm_reach(chain) * (1 + margin)
    ax.set_xlim(-r, r)
    ax.set_ylim(-r, r)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if title:
        ax.set_title(title)
    return ax


def draw_planar_arm(ax, chain, theta, *, show_frames=True, show_joints=True, color=None, alpha=1.0, label=None,
                    twist=None, frame_length=None, twist_scale=1.0, show_base=True, setup_axes=False,
                    title=None) -> PlanarArmArtist:
    r"""Draw a planar arm at ``theta``: links, joints (circles), frames {s} and {b}.

    Parameters
    ----------
    ax : matplotlib Axes (2-D)
    chain : SerialChain
        Must be planar (see :func:`check_planar`); otherwise ``ValueError``.
    theta : array_like, shape (n,)
    twist : array_like, shape (6,), optional
        A space twist :math:`\mathcal V_s = (\omega_s, v_s)`; the velocity of the
        tool point, :math:`\dot p = v_s + \omega_s\times p`, is drawn as an arrow.
    setup_axes : bool
        Also set equal aspect, limits from the reach, and the labels x (m), y (m).

    Returns
    -------
    PlanarArmArtist
        ``.update(theta, twist=None)`` moves every artist with ``set_data``.
    """
    chain = check_planar(chain, "draw_planar_arm")
    if setup_axes:
        setup_planar_axes(ax, chain, title=title)
    return PlanarArmArtist(ax, chain, theta, show_frames=show_frames, show_joints=show_joints, color=color,
                           alpha=alpha, label=label, twist=twist, frame_length=frame_length,
                           twist_scale=twist_scale, show_base=show_base)


_JAC_NAMES = {
    "space": ("J_s", "space"),
    "body": ("J_b", "body"),
    "geometric": ("J", "geometric"),
}


def _jacobian(chain, theta, kind):
    from . import jacobian as _jac

    if kind == "space":
        return _jac.space_jacobian(chain, theta)
    if kind == "body":
        return _jac.body_jacobian(chain, theta)
    if kind == "geometric":
        return _jac.geometric_jacobian(chain, theta)
    raise ValueError(f"Expected jacobian None, 'space', 'body' or 'geometric', got {kind!r}")


def column_arrows(chain, theta, kind):
    """Where and what to draw for the linear parts of the Jacobian columns of a planar arm.

    Returns (points (n, 2), vectors (n, 2)). ``space``: :math:`v_{s,i}` at the origin of
    {s} (the velocity of the point of the moving body at the origin);
    ``body``: :math:`R_{sb} v_{b,i}` at the tool (the body column, turned into
    {s} axes so it can be drawn); ``geometric``: :math:`\\dot p` columns at the tool.
    """
    J = _jacobian(chain, theta, kind)
    n = chain.dof
    if kind == "space":
        P = np.zeros((n, 2))
        V = J[3:5, :].T
    else:
        T = chain.fk(theta)
        P = np.tile(T[:2, 3], (n, 1))
        lin = J[3:6, :]
        if kind == "body":
            lin = T[:3, :3] @ lin
        V = lin[:2, :].T
    return P, V


def planar_arm_animation(chain, thetas, *, jacobian=None, show_columns=True, show_velocity=None, title=None,
                         interval=80, dpi=72, figsize=(5.6, 5.2), show_path=True):
    r"""A FuncAnimation of a planar arm moving through ``thetas``.

    Parameters
    ----------
    chain : SerialChain (planar)
    thetas : array_like, shape (T, n)
        One configuration per frame.
    jacobian : {None, "space", "body", "geometric"}
        If given and ``show_columns``, draw the linear part of each Jacobian column
        as an arrow: for ``"space"`` at the origin of {s}, otherwise at the tool
        (body columns are turned into {s} axes, :math:`R_{sb}v_{b,i}`, to be drawn).
    show_velocity : array_like, shape (n,) or (T, n), optional
        Joint rates; draws the tool velocity :math:`\dot p` (from the geometric Jacobian).
    title : str, optional
    interval : int
        Milliseconds between frames.
    dpi : int
        Resolution of the frames (keep 72–80 for page weight).
    show_path : bool
        Trace the tool path.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        The figure is attached as ``anim._fig``; use :func:`animation_html` to embed it.
    """
    chain = check_planar(chain, "planar_arm_animation")
    th = theta_array(thetas, chain.dof, "thetas")
    if th.ndim != 2:
        raise ValueError(f"Expected thetas with shape (T, {chain.dof}): one row per frame, got shape {th.shape}")
    if jacobian is not None and jacobian not in _JAC_NAMES:
        raise ValueError(f"Expected jacobian None, 'space', 'body' or 'geometric', got {jacobian!r}")
    rates = None
    if show_velocity is not None:
        rates = as_float_array(show_velocity, "show_velocity")
        if rates.shape == (chain.dof,):
            rates = np.tile(rates, (th.shape[0], 1))
        if rates.shape != th.shape:
            raise ValueError(f"Expected show_velocity with shape ({chain.dof},) or {th.shape}, got shape {rates.shape}")

    fig, ax = plt.subplots(figsize=figsize, dpi=dpi)
    setup_planar_axes(ax, chain, title=title or f"{chain.name or 'planar arm'}")
    tips = chain.joint_positions(th)[:, -1, :2]
    if show_path:
        ax.plot(tips[:, 0], tips[:, 1], ":", color=PALETTE["muted"], lw=1.5, label="tool path")
    arm = PlanarArmArtist(ax, chain, th[0])
    cols = None
    if jacobian is not None and show_columns:
        P, V = column_arrows(chain, th[0], jacobian)
        sym = _JAC_NAMES[jacobian][0]
        cols = []
        for i in range(chain.dof):
            lab = f"column {i + 1} of ${sym}$ (linear part)"
            cols.append(TwistArtist(ax, P[i], V[i], color=COLUMN_COLORS[i % len(COLUMN_COLORS)], label=lab,
                                    width=0.01))
    vel = None
    if rates is not None:
        from . import jacobian as _jac

        Jg = _jac.geometric_jacobian(chain, th)
        pdots = np.einsum("tij,tj->ti", Jg[:, 3:5, :], rates)
        vel = TwistArtist(ax, tips[0], pdots[0], color=PALETTE["velocity"], label=r"tool velocity $\dot p$ (m/s)")
    ax.legend(loc="upper left", fontsize=9, framealpha=0.85)
    fig.tight_layout()

    def frame(k):
        arm.update(th[k])
        if cols is not None:
            P, V = column_arrows(chain, th[k], jacobian)
            for i, c in enumerate(cols):
                c.update(P[i], V[i])
        if vel is not None:
            vel.update(tips[k], pdots[k])
        return []

    anim = _animation.FuncAnimation(fig, frame, frames=th.shape[0], interval=interval, blit=False)
    anim._fig = fig
    return anim


# ---------------------------------------------------------------- embedding animations without a CDN

_ICONS = {
    "fa-minus": "&#8722;",  # minus
    "fa-fast-backward": "&#10074;&#9664;&#9664;",  # ❚◀◀ (⏮ is missing from common fonts)
    "fa-step-backward": "&#10074;&#9664;",  # ❚◀
    "fa-play fa-flip-horizontal": "&#9664;",  # ◀
    "fa-pause": "&#10074;&#10074;",  # ❚❚
    "fa-play": "&#9654;",  # ▶
    "fa-step-forward": "&#9654;&#10074;",  # ▶❚
    "fa-fast-forward": "&#9654;&#9654;&#10074;",  # ▶▶❚
    "fa-plus": "+",
}


def _strip_cdn(html: str) -> str:
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html, flags=re.S)

    def icon(m):
        cls = m.group(1).replace("fa ", "", 1).strip()
        sym = _ICONS.get(cls)
        if sym is None:
            return m.group(0)
        return f'<span class="jac-anim-icon" aria-hidden="true">{sym}</span>'

    html = re.sub(r'<i class="(fa [^"]*)"></i>', icon, html)
    style = ("<style>.animation .anim-buttons button{min-width:2.4em;font-size:1.05em;line-height:1.4;"
             "font-family:'DejaVu Sans',system-ui,sans-serif;}.jac-anim-icon{font-style:normal;}</style>")
    return style + html


def compact_png(image, colors: int = 96) -> bytes:
    """PNG bytes of an RGB(A) array or of PNG bytes, reduced to an adaptive palette of ``colors`` colours.

    Line drawings on white need few colours; a palette PNG is 3 to 5 times
    smaller than matplotlib's RGBA PNG and looks the same (no dithering).
    """
    import io

    from PIL import Image

    if isinstance(image, (bytes, bytearray)):
        im = Image.open(io.BytesIO(image)).convert("RGB")
    else:
        im = Image.fromarray(np.asarray(image)[..., :3])
    q = im.quantize(colors=int(colors), method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    buf = io.BytesIO()
    q.save(buf, format="png", optimize=True)
    return buf.getvalue()


class _CompactHTMLWriter(_animation.HTMLWriter):
    """matplotlib's HTMLWriter with palette PNG frames (and a figure's own fast renderer if it has one)."""

    def __init__(self, *args, colors=96, **kwargs):
        kwargs["embed_frames"] = True
        super().__init__(*args, **kwargs)
        self.frame_format = "png"
        self._colors = colors

    def grab_frame(self, **savefig_kwargs):
        import base64
        import io

        if self._hit_limit:
            return
        render = getattr(self.fig, "_jac_render_rgba", None)
        if render is not None:
            data = compact_png(render(), self._colors)
        else:
            f = io.BytesIO()
            self.fig.savefig(f, format="png", dpi=self.dpi, **savefig_kwargs)
            data = compact_png(f.getvalue(), self._colors)
        img64 = base64.encodebytes(data).decode("ascii")
        self._total_bytes += len(img64)
        if self._total_bytes >= self._bytes_limit:
            import warnings

            warnings.warn(f"animation_html: frames beyond {self._bytes_limit / 1e6:.1f} MB were dropped; "
                          "use fewer frames or a lower dpi", stacklevel=2)
            self._hit_limit = True
        else:
            self._saved_frames.append(img64)


def blit_frames(anim, update, n_frames: int, artists) -> None:
    """Make :func:`animation_html` render ``anim`` by blitting only the moving ``artists``.

    The fixed parts of the figure (axes, ticks, labels, legends) are drawn once
    and kept as a bitmap; each frame calls ``update(k)`` and draws ``artists``
    over that bitmap. Several times faster than a full redraw per frame, which
    is what ``FuncAnimation`` does. Every artist that ``update`` changes must be
    in ``artists``; anything else keeps its first state.

    Parameters
    ----------
    anim : matplotlib.animation.FuncAnimation
        The animation (its ``update`` function should be the same as here).
    update : callable
        ``update(k)`` moves the artists to frame ``k``.
    n_frames : int
    artists : iterable of matplotlib artists
    """
    if not isinstance(anim, _animation.Animation):
        raise TypeError(f"Expected a matplotlib Animation, got {type(anim).__name__}")
    if not callable(update):
        raise TypeError(f"Expected a callable update(k), got {type(update).__name__}")
    if isinstance(n_frames, bool) or not isinstance(n_frames, (int, np.integer)) or n_frames < 1:
        raise ValueError(f"Expected a positive number of frames, got {n_frames!r}")
    fig = anim._fig
    artists = list(artists)
    for a in artists:
        a.set_animated(True)
    fig.canvas.draw()
    background = fig.canvas.copy_from_bbox(fig.bbox)

    def render():
        fig.canvas.restore_region(background)
        for a in artists:
            fig.draw_artist(a)
        return np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()

    fig._jac_render_rgba = render
    anim._jac_frames = (update, int(n_frames))


def animation_html(anim, *, default_mode: str = "loop", embed_limit_mb: float = 3.0, colors: int = 96):
    """Embed a matplotlib animation as inline HTML/JS that loads nothing from the internet.

    Matplotlib's ``to_jshtml`` links the font-awesome icon font from a CDN for
    its control buttons. This removes that ``<link>`` and writes the buttons as
    Unicode symbols (▶, ❚❚, ⏮ ...), so the controls show offline. Frames are
    palette PNGs (``colors`` colours, see :func:`compact_png`): about 4x lighter
    than matplotlib's. The figure is closed, so no stray static copy of it
    follows the animation in a notebook.

    Returns
    -------
    IPython.display.HTML
    """
    import tempfile
    from pathlib import Path

    from IPython.display import HTML

    if default_mode not in ("loop", "once", "reflect"):
        raise ValueError(f"Expected default_mode 'loop', 'once' or 'reflect', got {default_mode!r}")
    if not isinstance(anim, _animation.Animation):
        raise TypeError(f"Expected a matplotlib Animation, got {type(anim).__name__}")
    fig = getattr(anim, "_fig", None)
    fps = 1000.0 / getattr(anim, "_interval", 100)
    writer = _CompactHTMLWriter(fps=fps, default_mode=default_mode, embed_limit=float(embed_limit_mb),
                                colors=colors)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp, "anim.html")
            frames = getattr(anim, "_jac_frames", None)
            if frames is not None:
                # our explorers: move the artists and grab, without FuncAnimation's extra full redraws
                func, n = frames
                with writer.saving(fig, str(path), fig.dpi):
                    for k in range(n):
                        func(k)
                        writer.grab_frame()
                anim._draw_was_started = True  # rendered: no "deleted without rendering" warning
            else:
                anim.save(str(path), writer=writer)
            html = path.read_text()
    finally:
        if fig is not None:
            plt.close(fig)
    return HTML(_strip_cdn(html))


# ---------------------------------------------------------------- 3-D chains

def _agg_renderer(fig, draw=True):
    """A renderer for measuring ``fig``'s texts (an Agg canvas is attached if the figure has none
    that can render, e.g. after ``plt.show()`` closed it in a notebook). With ``draw``, or when a
    layout engine only places the axes at draw time, the figure is drawn first."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    if draw or fig.get_layout_engine() is not None:
        fig.canvas.draw()
    return fig.canvas.get_renderer()


class SpatialChainArtist:
    """What :func:`draw_spatial_chain` drew; ``update(theta)`` moves it.

    Each joint axis is a segment of half-length ``axis_length`` centred on the
    joint point, numbered ``1..n``. Where the number sits is ``label_at``: a
    signed position along the axis in units of ``axis_length`` (``1.0``, the
    default, is the tip of the segment; ``-1.6`` is beyond the other tip). A
    number placed beyond a tip is joined to it by a dotted leader in the axis
    colour, so it stays attached to its own axis. :meth:`place_labels` chooses
    these positions for the current view so that the numbers keep clear of
    each other and of the other axes.
    """

    def __init__(self, ax, chain, theta, *, show_axes=True, show_frames=True, color=None, axis_length=None,
                 frame_length=None, label=None, highlight=None, fontsize=None, label_at=None, label_box=False):
        self.ax = ax
        self.chain = chain
        reach = arm_reach(chain)
        self.axis_length = axis_length if axis_length is not None else 0.12 * reach
        self.fontsize = float(fontsize) if fontsize is not None else 11.0
        n = chain.dof
        self._centred = label_at is not None
        self.label_at = self._label_positions(label_at if label_at is not None else 1.0, n)
        color = color or PALETTE["link"]
        (self.link_line,) = ax.plot([], [], [], "-", color=color, lw=4, label=label or chain.name or "arm")
        (self.joint_markers,) = ax.plot([], [], [], linestyle="none", marker="o", ms=8, mfc="white",
                                        mec=PALETTE["joint"], mew=2)
        self.axis_lines = []
        self.axis_texts = []
        self.leader_lines = []
        if show_axes:
            for i in range(n):
                col = COLUMN_COLORS[i % len(COLUMN_COLORS)]
                (ln,) = ax.plot([], [], [], "-", color=col, lw=3)
                (ld,) = ax.plot([], [], [], ":", color=col, lw=1.6)
                kw = {}
                if self._centred:
                    kw.update(ha="center", va="center")
                if label_box:
                    kw["bbox"] = dict(boxstyle="round,pad=0.18", fc="white", ec=col, lw=1.2, alpha=0.9)
                tx = ax.text(0, 0, 0, f"{i + 1}", color=col, fontsize=self.fontsize, fontweight="bold", **kw)
                self.axis_lines.append(ln)
                self.leader_lines.append(ld)
                self.axis_texts.append(tx)
        self.frames = []
        if show_frames:
            Lf = frame_length if frame_length is not None else 0.2 * reach
            fk = dict(fontsize=fontsize) if fontsize is not None else {}
            self.frames = [FrameArtist(ax, np.eye(4), "{s}", Lf, lw=2, **fk),
                           FrameArtist(ax, chain.home, "{b}", 0.7 * Lf, lw=2, **fk)]
        self.update(theta)

    @staticmethod
    def _label_positions(label_at, n):
        t = np.broadcast_to(np.asarray(label_at, dtype=float), (n,)).copy() if np.ndim(label_at) == 0 else \
            np.asarray(label_at, dtype=float)
        if t.shape != (n,) or not np.all(np.isfinite(t)):
            raise ValueError(f"Expected label_at as one finite number or {n} of them (one per joint), got {label_at!r}")
        return t

    def _axis_direction(self, P, i):
        S = self.chain.screw_axes
        if self.chain.joint_types[i] == "R":
            return P[i, :3, :3] @ S[:3, i]
        return P[i, :3, :3] @ S[3:, i]

    def update(self, theta):
        th = theta_array(theta, self.chain.dof)
        P = self.chain.prefix_transforms(th)
        pts = self.chain.joint_positions(th)
        self.theta, self.points = th, pts
        self.link_line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
        self.joint_markers.set_data_3d(pts[:-1, 0], pts[:-1, 1], pts[:-1, 2])
        h = self.axis_length
        for i, (ln, tx, ld) in enumerate(zip(self.axis_lines, self.axis_texts, self.leader_lines)):
            d = self._axis_direction(P, i)
            a, b = pts[i] - h * d, pts[i] + h * d
            ln.set_data_3d([a[0], b[0]], [a[1], b[1]], [a[2], b[2]])
            t = self.label_at[i]
            c = pts[i] + t * h * d
            tx.set_position((c[0], c[1]))
            tx.set_3d_properties(c[2], None)
            if abs(t) > 1.0:
                e = pts[i] + np.sign(t) * h * d
                ld.set_data_3d([e[0], c[0]], [e[1], c[1]], [e[2], c[2]])
            else:
                ld.set_data_3d([], [], [])
        if self.frames:
            self.frames[1].update(self.chain.fk(th))
        return self

    @property
    def artists(self):
        """The artists that :meth:`update` moves (for :func:`blit_frames`)."""
        out = [self.link_line, self.joint_markers, *self.axis_lines, *self.leader_lines, *self.axis_texts]
        if self.frames:
            out += self.frames[1].artists
        return out

    @property
    def axis_directions(self) -> np.ndarray:
        """(n, 3) current unit directions of the drawn joint axes."""
        out = []
        for ln in self.axis_lines:
            x, y, z = ln.get_data_3d()
            d = np.array([x[1] - x[0], y[1] - y[0], z[1] - z[0]])
            out.append(d / np.linalg.norm(d))
        return np.array(out)

    @property
    def label_points(self) -> np.ndarray:
        """(n, 3) where the axis numbers sit, in the coordinates of {s}."""
        return np.array([[t._x, t._y, t._z] for t in self.axis_texts], dtype=float).reshape(-1, 3)

    def _display(self, pts3) -> np.ndarray:
        """Pixel coordinates of 3-D points in the axes' current view."""
        from mpl_toolkits.mplot3d import proj3d

        pts3 = np.asarray(pts3, dtype=float).reshape(-1, 3)
        x, y, _ = proj3d.proj_transform(pts3[:, 0], pts3[:, 1], pts3[:, 2], self.ax.get_proj())
        return self.ax.transData.transform(np.column_stack([x, y]))

    def place_labels(self, candidates=(1.5, -1.5, 1.8, -1.8, 2.1, -2.1, 2.5, -2.5, 2.9, -2.9, 3.3, -3.3, 3.8, -3.8)):
        """Move each axis number along its own axis to where it is clearest, for the current view.

        Call after the view (``view_init``), the limits and the figure layout
        are final. Each number goes to one of the ``candidates`` (signed
        positions along its axis, in units of ``axis_length``; beyond a tip, a
        dotted leader joins it to the segment) inside the axes limits; the
        choice maximises, in pixels, the clearance between the number's box and
        the other numbers, the other texts of the axes (frame labels), the
        other joints' axis segments and the links.
        Returns the chosen ``label_at`` (also stored, and kept by ``update``).
        """
        n = len(self.axis_texts)
        if n == 0:
            return self.label_at
        cands = np.asarray(candidates, dtype=float)
        if cands.ndim != 1 or cands.size == 0 or not np.all(np.isfinite(cands)):
            raise ValueError(f"Expected candidates as a non-empty list of finite numbers, got {candidates!r}")
        if not self._centred:
            for tx in self.axis_texts:
                tx.set_ha("center")
                tx.set_va("center")
            self._centred = True
        self.update(self.theta)
        renderer = _agg_renderer(self.ax.figure, draw=False)
        self.ax.apply_aspect()  # where a draw puts the 3-D axes (their box aspect shrinks them)
        P = self.chain.prefix_transforms(self.theta)
        pts, h = self.points, self.axis_length
        dirs = np.array([self._axis_direction(P, i) for i in range(n)])
        s = np.linspace(0.0, 1.0, 60)[:, None]

        def sampled(a, b):
            a, b = self._display(np.array([a, b]))
            return a + s * (b - a)

        segs = [sampled(pts[i] - h * dirs[i], pts[i] + h * dirs[i]) for i in range(n)]
        link = self._display(pts)
        link_samples = np.vstack([link[k] + s * (link[k + 1] - link[k]) for k in range(len(link) - 1)])
        frame_samples = []
        for f in self.frames:
            for ln in f.axis_lines:
                x, y, z = ln.get_data_3d()
                frame_samples.append(sampled([x[0], y[0], z[0]], [x[-1], y[-1], z[-1]]))
        obstacles_pts = np.vstack([link_samples, *frame_samples]) if frame_samples else link_samples
        texts = [t for t in self.ax.texts if t not in self.axis_texts and t.get_text() and t.get_visible()]
        text_rects = [self._text_box(t, renderer) for t in texts]
        text_rects = [((b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2, b.width / 2, b.height / 2) for b in text_rects]
        half = []
        for tx in self.axis_texts:
            b = self._text_box(tx, renderer)
            half.append((b.width / 2, b.height / 2))
        lims = np.array([self.ax.get_xlim3d(), self.ax.get_ylim3d(), self.ax.get_zlim3d()])

        def point_clearance(c, hw, q):  # signed distance from points q to the box (negative inside)
            dx = np.abs(q[:, 0] - c[0]) - hw[0]
            dy = np.abs(q[:, 1] - c[1]) - hw[1]
            outside = np.hypot(np.maximum(dx, 0), np.maximum(dy, 0))
            inside = np.minimum(np.maximum(dx, dy), 0)
            return float(np.min(outside + inside))

        def rect_clearance(c, hw, r):
            dx = abs(c[0] - r[0]) - hw[0] - r[2]
            dy = abs(c[1] - r[1]) - hw[1] - r[3]
            return float(np.hypot(max(dx, 0), max(dy, 0)) + min(max(dx, dy), 0))

        def leader(i, t):  # sampled dotted leader from the segment's tip to the number (none within the tip)
            if abs(t) <= 1.0:
                return None
            return sampled(pts[i] + np.sign(t) * h * dirs[i], pts[i] + t * h * dirs[i])

        def score(i, t, placed):
            c3 = pts[i] + t * h * dirs[i]
            if np.any(c3 < lims[:, 0]) or np.any(c3 > lims[:, 1]):
                return -np.inf
            c = self._display([c3])[0]
            hw = half[i]
            own = leader(i, t)
            d = [point_clearance(c, hw, obstacles_pts)]
            # margins a little wider than label_problems' (which counts the line widths)
            d += [point_clearance(c, hw, segs[j]) - 4.0 for j in range(n) if j != i]
            d += [rect_clearance(c, hw, r) - 1.0 for r in text_rects]
            for j, (cj, lj) in placed.items():
                if j == i:
                    continue
                d.append(rect_clearance(c, hw, (*cj, *half[j])) - 1.0)
                if lj is not None:  # another number's leader must not cross this number
                    d.append(point_clearance(c, hw, lj) - 3.0)
                if own is not None:  # nor this leader another number
                    d.append(point_clearance(cj, half[j], own) - 3.0)
            return min(d) - 0.5 * abs(t)  # on a tie, the shorter leader

        chosen = self.label_at.copy()
        placed = {}
        for _ in range(4):  # a few sweeps: each number moves to its best spot given the others
            for i in range(n):
                best = max(cands, key=lambda t: score(i, t, placed))
                chosen[i] = best
                placed[i] = (self._display([pts[i] + best * h * dirs[i]])[0], leader(i, best))
        self.label_at = chosen
        self.update(self.theta)
        return chosen


    def _text_box(self, tx, renderer):
        """Pixel bounding box of a 3-D text (and of its background box) as drawn in the current view."""
        from matplotlib.transforms import Bbox

        q = self._display([[tx._x, tx._y, tx._z]])[0]
        x2, y2 = self.ax.transData.inverted().transform(q)
        x3, y3 = tx._x, tx._y
        try:  # where Text3D.draw puts the text: its projected position, in the 2-D data coordinates
            tx._x, tx._y = x2, y2
            bb = tx.get_window_extent(renderer)
        finally:
            tx._x, tx._y = x3, y3
        patch = tx.get_bbox_patch()
        if patch is not None:
            pad = patch.get_boxstyle().pad * tx.get_fontsize() * renderer.points_to_pixels(1.0)
            bb = Bbox.from_extents(bb.x0 - pad, bb.y0 - pad, bb.x1 + pad, bb.y1 + pad)
        return bb

    def label_problems(self) -> list[str]:
        """What makes an axis number hard to read in the current view, as sentences (empty: none).

        Draws the figure, then reports every axis number whose box overlaps
        another number or another text of the axes (frame labels), every joint
        axis segment or leader that crosses or touches (counting its line width)
        the box of another joint's number, and every axis segment that lies, for more than half its length, within
        4 pixels of another one (so it cannot be told apart). Call after the
        view, limits and layout are final.
        """
        renderer = _agg_renderer(self.ax.figure)
        boxes = [self._text_box(tx, renderer) for tx in self.axis_texts]
        others = [t for t in self.ax.texts if t not in self.axis_texts and t.get_text() and t.get_visible()]
        other_boxes = [(t.get_text(), self._text_box(t, renderer)) for t in others]
        out = []
        n = len(boxes)
        for i in range(n):
            for j in range(i + 1, n):
                if boxes[i].overlaps(boxes[j]):
                    out.append(f"number {i + 1} overlaps number {j + 1}")
            for name, bb in other_boxes:
                if boxes[i].overlaps(bb):
                    out.append(f"number {i + 1} overlaps the label {name!r}")
        s = np.linspace(0.0, 1.0, 60)[:, None]
        for j, (ln, ld) in enumerate(zip(self.axis_lines, self.leader_lines)):
            for line in (ln, ld):
                x, y, z = line.get_data_3d()
                if len(x) < 2:
                    continue
                a, b = self._display(np.array([[x[0], y[0], z[0]], [x[-1], y[-1], z[-1]]]))
                samples = a + s * (b - a)
                m = 0.5 * line.get_linewidth() * renderer.points_to_pixels(1.0) + 1.0  # the line's own width
                for i in range(n):
                    bb = boxes[i]
                    inside = ((samples[:, 0] >= bb.x0 - m) & (samples[:, 0] <= bb.x1 + m)
                              & (samples[:, 1] >= bb.y0 - m) & (samples[:, 1] <= bb.y1 + m))
                    if i != j and np.any(inside):
                        out.append(f"{'axis' if line is ln else 'the leader of axis'} {j + 1} crosses number {i + 1}")
        # two joint axes drawn on top of each other: one of them cannot be found
        segs = []
        for ln in self.axis_lines:
            x, y, z = ln.get_data_3d()
            segs.append(self._display(np.array([[x[0], y[0], z[0]], [x[-1], y[-1], z[-1]]])))
        for j in range(len(segs)):
            samples = segs[j][0] + s * (segs[j][1] - segs[j][0])
            for k in range(len(segs)):
                if k == j:
                    continue
                a, b = segs[k]
                ba = b - a
                t = np.clip((samples - a) @ ba / max(ba @ ba, 1e-12), 0.0, 1.0)
                near = np.linalg.norm(samples - (a + t[:, None] * ba), axis=1) < 4.0
                if near.mean() > 0.5:
                    out.append(f"axis {j + 1} is hidden under axis {k + 1}")
        return out


def setup_3d_axes(ax, chain, *, title=None, margin=0.1, fontsize=None):
    """Equal-scale 3-D axes around the chain's reach, labelled in metres.

    ``fontsize`` (points), when given, sizes the tick labels, the axis labels
    (one point larger) and the title (two points larger).
    """
    r = arm_reach(chain) * (1 + margin)
    ax.set_xlim(-r, r)
    ax.set_ylim(-r, r)
    ax.set_zlim(-r, r)
    try:
        ax.set_box_aspect((1, 1, 1))
    except Exception:  # pragma: no cover - very old matplotlib
        pass
    lk = dict(fontsize=fontsize + 1) if fontsize is not None else {}
    ax.set_xlabel("x (m)", **lk)
    ax.set_ylabel("y (m)", **lk)
    ax.set_zlabel("z (m)", **lk)
    if fontsize is not None:
        ax.tick_params(labelsize=fontsize)
    if title:
        ax.set_title(title, **(dict(fontsize=fontsize + 2) if fontsize is not None else {}))
    return ax


def draw_spatial_chain(ax3d, chain, theta, *, show_axes=True, show_frames=True, color=None, axis_length=None,
                       frame_length=None, label=None, setup_axes=False, title=None, fontsize=None, label_at=None,
                       label_box=False, place_labels=False) -> SpatialChainArtist:
    """Draw a spatial chain on a 3-D axes: links through the joint points, each joint axis
    as a short numbered segment (in the column colours), frames {s} and {b}.

    ``fontsize`` sizes the axis numbers and the frame labels (default 11 pt for
    the numbers); ``label_at`` places the numbers along their axes (see
    :class:`SpatialChainArtist`); ``label_box`` puts each number on a white
    box edged in its axis colour; ``place_labels=True`` calls
    :meth:`SpatialChainArtist.place_labels` for the current view (set the view
    and the limits first, or call it yourself afterwards).

    Returns a :class:`SpatialChainArtist` with ``update(theta)``.
    """
    chain = _as_chain(chain)
    if not _is_3d(ax3d):
        raise ValueError("Expected a 3-D axes (fig.add_subplot(projection='3d')) for draw_spatial_chain, "
                         f"got a {type(ax3d).__name__} named {getattr(ax3d, 'name', '?')!r}")
    if setup_axes:
        setup_3d_axes(ax3d, chain, title=title, fontsize=fontsize)
    art = SpatialChainArtist(ax3d, chain, theta, show_axes=show_axes, show_frames=show_frames, color=color,
                             axis_length=axis_length, frame_length=frame_length, label=label, fontsize=fontsize,
                             label_at=label_at, label_box=label_box)
    if place_labels:
        art.place_labels()
    return art


# ---------------------------------------------------------------- matrices

def _fmt(x, digits):
    if not np.isfinite(x):
        return r"\text{undef.}"
    if abs(x) < 0.5 * 10.0 ** (-digits):
        x = 0.0
    s = f"{x:.{digits}f}"
    if s.startswith("-"):
        s = "-" + s[1:]
    return s


def matrix_latex(J, name: str | None = None, digits: int = 3, highlight_columns=(), highlight_color="orange") -> str:
    r"""A LaTeX ``bmatrix`` of a numeric matrix, optionally preceded by ``name =``.

    Entries are rounded to ``digits`` decimals; ``-0`` is shown as ``0``; NaN and
    infinities as "undef.". Columns listed in ``highlight_columns`` (0-based) are
    coloured with ``\color{highlight_color}``.

    >>> matrix_latex([[1, 0.5], [float("nan"), -1e-9]], "A", digits=2)
    'A = \\begin{bmatrix} 1.00 & 0.50 \\\\ \\text{undef.} & 0.00 \\end{bmatrix}'
    """
    A = as_float_array(J, "J")
    if A.ndim == 1:
        A = A[:, None]
    if A.ndim != 2:
        raise ValueError(f"Expected a matrix (2-D array) for J, got shape {A.shape}")
    hl = set(int(c) for c in highlight_columns)
    rows = []
    for r in A:
        cells = []
        for j, x in enumerate(r):
            s = _fmt(x, digits)
            if j in hl:
                s = f"{{\\color{{{highlight_color}}}{s}}}"
            cells.append(s)
        rows.append(" & ".join(cells))
    body = r"\begin{bmatrix} " + r" \\ ".join(rows) + r" \end{bmatrix}"
    return f"{name} = {body}" if name else body


class MatrixArtist:
    """A numeric matrix drawn as a grid of text on an axes; ``update(J)`` changes the numbers."""

    def __init__(self, ax, J, *, digits=2, row_labels=None, col_labels=None, title=None, fontsize=12):
        A = np.atleast_2d(as_float_array(J, "J"))
        self.ax = ax
        self.digits = digits
        self.shape = A.shape
        m, n = A.shape
        ax.set_xlim(-0.5, n - 0.5)
        ax.set_ylim(m - 0.5, -0.5)
        ax.set_xticks(range(n))
        ax.set_yticks(range(m))
        ax.set_xticklabels(col_labels if col_labels is not None else [str(j + 1) for j in range(n)])
        ax.set_yticklabels(row_labels if row_labels is not None else [str(i + 1) for i in range(m)])
        ax.tick_params(length=0)
        ax.grid(False)
        for sp in ax.spines.values():
            sp.set_visible(False)
        if title:
            ax.set_title(title)
        self.texts = [[ax.text(j, i, "", ha="center", va="center", fontsize=fontsize, family="monospace")
                       for j in range(n)] for i in range(m)]
        self.update(A)

    def update(self, J, colors=None):
        A = np.atleast_2d(as_float_array(J, "J"))
        if A.shape != self.shape:
            raise ValueError(f"Expected J with shape {self.shape}, got shape {A.shape}")
        for i in range(self.shape[0]):
            for j in range(self.shape[1]):
                x = A[i, j]
                self.texts[i][j].set_text("undef." if not np.isfinite(x) else f"{(0.0 if abs(x) < 0.5 * 10 ** -self.digits else x):.{self.digits}f}")
                if colors is not None:
                    self.texts[i][j].set_color(colors[j] if np.ndim(colors) == 1 else colors[i][j])
        self.values = A
        return self


def draw_matrix(ax, J, *, digits=2, row_labels=None, col_labels=None, title=None, fontsize=12) -> MatrixArtist:
    """Draw a numeric matrix as text on ``ax`` (no image). Returns a :class:`MatrixArtist`.

    Rows of a Jacobian are usually labelled ``["ωx", "ωy", "ωz", "vx", "vy", "vz"]``.
    """
    return MatrixArtist(ax, J, digits=digits, row_labels=row_labels, col_labels=col_labels, title=title,
                        fontsize=fontsize)
