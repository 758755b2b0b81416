"""The planar arm: its artist, its axes, the arrows of its Jacobian columns, and its animation."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array, theta_array
from ..chain import SerialChain
from ..frames import JACOBIAN_SYMBOLS, Frame, check_frame
from ..jacobian import geometric_jacobian
from ..jacobian import jacobian as _jacobian
from .animation import FrameSource
from .artists import FrameArtist, TwistArtist, _clean, arm_reach, check_planar
from .style import COLUMN_COLORS, PALETTE

__all__ = ["PlanarArmArtist", "setup_planar_axes", "draw_planar_arm", "column_arrows", "planar_arm_animation"]


class PlanarArmArtist:
    """What :func:`draw_planar_arm` drew; ``update(theta, twist=None)`` moves it in place."""

    def __init__(self, ax: Axes, chain: SerialChain, theta: ArrayLike, *, show_frames: bool = True,
                 show_joints: bool = True, color: str | None = None, alpha: float = 1.0, label: str | None = None,
                 twist: ArrayLike | None = None, frame_length: float | None = None, twist_scale: float = 1.0,
                 show_base: bool = True) -> None:
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
        self.twist_artist: TwistArtist | None = None
        self.twist_scale = float(twist_scale)
        self._want_twist = twist is not None
        self.update(theta, twist=twist)

    def update(self, theta: ArrayLike, twist: ArrayLike | None = None) -> PlanarArmArtist:
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
    def artists(self) -> list[Artist]:
        """The artists that :meth:`update` moves."""
        out: list[Artist] = [self.link_line, self.tool_marker]
        if self.joint_markers is not None:
            out.append(self.joint_markers)
        if self.base is not None:
            out.append(self.base)
        for f in self.frames:
            out += f.artists
        if self.twist_artist is not None:
            out += self.twist_artist.artists
        return out


def setup_planar_axes(ax: Axes, chain: SerialChain, *, title: str | None = None, margin: float = 0.25) -> Axes:
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


def draw_planar_arm(ax: Axes, chain: SerialChain, theta: ArrayLike, *, show_frames: bool = True,
                    show_joints: bool = True, color: str | None = None, alpha: float = 1.0, label: str | None = None,
                    twist: ArrayLike | None = None, frame_length: float | None = None, twist_scale: float = 1.0,
                    show_base: bool = True, setup_axes: bool = False, title: str | None = None) -> PlanarArmArtist:
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


#: The frames whose Jacobian columns a planar figure can draw as arrows.
COLUMN_FRAMES: tuple[Frame, ...] = ("space", "body", "geometric")


def column_arrows(chain: SerialChain, theta: ArrayLike,
                  frame: Frame) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Where and what to draw for the linear parts of the Jacobian columns of a planar arm.

    Returns (points (n, 2), vectors (n, 2)). ``space``: :math:`v_{s,i}` at the origin of
    {s} (the velocity of the point of the moving body at the origin);
    ``body``: :math:`R_{sb} v_{b,i}` at the tool (the body column, turned into
    {s} axes so it can be drawn); ``geometric``: :math:`\\dot p` columns at the tool.
    """
    frame = check_frame(frame, COLUMN_FRAMES)
    J = _jacobian(chain, theta, frame)
    n = chain.dof
    if frame == "space":
        P = np.zeros((n, 2))
        V = J[3:5, :].T
    else:
        T = chain.fk(theta)
        P = np.tile(T[:2, 3], (n, 1))
        lin = J[3:6, :]
        if frame == "body":
            lin = T[:3, :3] @ lin
        V = lin[:2, :].T
    return P, V


def planar_arm_animation(chain: SerialChain, thetas: ArrayLike, *, frame: Frame | None = None,
                         show_columns: bool = True, show_velocity: ArrayLike | None = None, title: str | None = None,
                         interval: float = 80, dpi: float = 72, figsize: tuple[float, float] = (5.6, 5.2),
                         show_path: bool = True) -> FrameSource:
    r"""An animation of a planar arm moving through ``thetas``, for :func:`animation_html`.

    Parameters
    ----------
    chain : SerialChain (planar)
    thetas : array_like, shape (T, n)
        One configuration per frame.
    frame : {None, "space", "body", "geometric"}
        If given and ``show_columns``, draw the linear part of each Jacobian column
        as an arrow: for ``"space"`` at the origin of {s}, otherwise at the tool
        (body columns are turned into {s} axes, :math:`R_{sb}v_{b,i}`, to be drawn).
    show_velocity : array_like, shape (n,) or (T, n), optional
        Joint rates; draws the tool velocity :math:`\dot p` (from the geometric Jacobian).
    title : str, optional
    interval : float
        Milliseconds between frames.
    dpi : int
        Resolution of the frames (keep 72–80 for page weight).
    show_path : bool
        Trace the tool path.

    Returns
    -------
    FrameSource
        ``.fig`` is the figure, ``.draw(k)`` moves it to frame k, ``.path`` holds ``thetas``.
    """
    chain = check_planar(chain, "planar_arm_animation")
    th = theta_array(thetas, chain.dof, "thetas")
    if th.ndim != 2:
        raise ValueError(f"Expected thetas with shape (T, {chain.dof}): one row per frame, got shape {th.shape}")
    shown = None if frame is None else check_frame(frame, COLUMN_FRAMES)
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
    if shown is not None and show_columns:
        P, V = column_arrows(chain, th[0], shown)
        sym = JACOBIAN_SYMBOLS[shown]
        cols = []
        for i in range(chain.dof):
            lab = f"column {i + 1} of ${sym}$ (linear part)"
            cols.append(TwistArtist(ax, P[i], V[i], color=COLUMN_COLORS[i % len(COLUMN_COLORS)], label=lab,
                                    width=0.01))
    vel = None
    if rates is not None:
        Jg = geometric_jacobian(chain, th)
        pdots = np.einsum("tij,tj->ti", Jg[:, 3:5, :], rates)
        vel = TwistArtist(ax, tips[0], pdots[0], color=PALETTE["velocity"], label=r"tool velocity $\dot p$ (m/s)")
    ax.legend(loc="upper left", fontsize=9, framealpha=0.85)
    fig.tight_layout()

    def draw(k: int) -> list[Any]:
        arm.update(th[k])
        if cols is not None and shown is not None:
            P, V = column_arrows(chain, th[k], shown)
            for i, c in enumerate(cols):
                c.update(P[i], V[i])
        if vel is not None:
            vel.update(tips[k], pdots[k])
        return []

    return FrameSource(fig, draw, th.shape[0], interval=interval, path=th)
