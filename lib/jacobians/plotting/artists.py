"""Small drawing helpers: frames, arrows and ellipses that move in place, and the planar checks.

Each ``draw_*`` returns an *artist* object that keeps the matplotlib artists it
made; its ``update(...)`` moves them with ``set_data`` / ``set_offsets``.
"""

from __future__ import annotations

from typing import Any

import matplotlib
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array
from ..chain import SerialChain, _as_chain
from .style import PALETTE

__all__ = ["check_planar", "arm_reach", "TwistArtist", "draw_twist", "FrameArtist", "draw_frame", "EllipseArtist",
           "draw_ellipse"]


def check_planar(chain: SerialChain, what: str = "this figure") -> SerialChain:
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


def arm_reach(chain: SerialChain) -> float:
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


def _clean(v: ArrayLike) -> NDArray[np.float64]:
    v = np.array(v, dtype=float)
    v[~np.isfinite(v)] = 0.0
    return v


def _is_3d(ax: Any) -> bool:
    return getattr(ax, "name", "") == "3d"


# ---------------------------------------------------------------- 2-D and 3-D frames and arrows

class TwistArtist:
    """Arrows (a quiver in data units) drawn at points; ``update(points, vectors)`` moves them."""

    def __init__(self, ax: Axes, points: ArrayLike, vectors: ArrayLike, *, color: str | None = None,
                 label: str | None = None, width: float = 0.012, zorder: float = 5, scale: float = 1.0) -> None:
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

    def update(self, points: ArrayLike, vectors: ArrayLike) -> TwistArtist:
        P = np.atleast_2d(_clean(points))[:, :2]
        V = np.atleast_2d(_clean(vectors))[:, :2] * self.scale
        self.quiver.set_offsets(P)
        self.quiver.set_UVC(V[:, 0], V[:, 1])
        return self

    @property
    def vectors(self) -> NDArray[np.float64]:
        """The drawn vectors (already multiplied by ``scale``), shape (k, 2)."""
        return np.column_stack([self.quiver.U, self.quiver.V])

    @property
    def points(self) -> NDArray[np.float64]:
        """The arrows' start points, shape (k, 2)."""
        return np.asarray(self.quiver.get_offsets())

    @property
    def artists(self) -> list[Artist]:
        """The artists that :meth:`update` moves."""
        return [self.quiver]


def draw_twist(ax: Axes, point: ArrayLike, vector: ArrayLike, *, color: str | None = None, label: str | None = None,
               scale: float = 1.0, width: float = 0.012, zorder: float = 5) -> TwistArtist:
    """Arrow(s) of ``vector`` (x, y parts used) starting at ``point``, in data units.

    ``point`` and ``vector`` have shape (2,) / (3,) for one arrow or (k, 2) / (k, 3)
    for k arrows; ``scale`` multiplies the drawn length. Returns a :class:`TwistArtist`.
    """
    return TwistArtist(ax, point, vector, color=color, label=label, width=width, zorder=zorder, scale=scale)


class FrameArtist:
    """A coordinate frame drawn as its x, y (and z in 3-D) axes, with labels; ``update(T)`` moves it."""

    def __init__(self, ax: Any, T: ArrayLike, label: str | None, length: float, fontsize: float | None = None,
                 alpha: float = 1.0, lw: float = 2.5) -> None:
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

    def update(self, T: ArrayLike) -> FrameArtist:
        T = np.asarray(T, dtype=float)
        o = T[:3, 3]
        L = self.length
        for j, (ln, tx) in enumerate(zip(self.axis_lines, self.axis_texts, strict=True)):
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
    def artists(self) -> list[Artist]:
        """The artists that :meth:`update` moves."""
        return self.axis_lines + self.axis_texts + [self.name_text]


def draw_frame(ax: Any, T: ArrayLike, label: str | None = "{s}", length: float = 0.3, **kw: Any) -> FrameArtist:
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

    def __init__(self, ax: Axes, center: ArrayLike, semi_axes: ArrayLike, directions: ArrayLike, n_points: int = 90,
                 **kw: Any) -> None:
        self.ax = ax
        self._t = np.linspace(0, 2 * np.pi, n_points)
        kw.setdefault("color", PALETTE["velocity"])
        kw.setdefault("lw", 2.0)
        (self.line,) = ax.plot([], [], **kw)
        self.update(center, semi_axes, directions)

    def points(self, center: ArrayLike, semi_axes: ArrayLike, directions: ArrayLike) -> NDArray[np.float64]:
        """Points of the ellipse, shape (n_points, 2)."""
        c = _clean(center)[:2]
        s = _clean(semi_axes)[:2]
        D = _clean(directions)[:2, :2]
        circ = np.stack([np.cos(self._t), np.sin(self._t)])
        out: NDArray[np.float64] = (c[:, None] + D @ (s[:, None] * circ)).T
        return out

    def update(self, center: ArrayLike, semi_axes: ArrayLike, directions: ArrayLike) -> EllipseArtist:
        P = self.points(center, semi_axes, directions)
        self.line.set_data(P[:, 0], P[:, 1])
        return self

    @property
    def artists(self) -> list[Artist]:
        """The artists that :meth:`update` moves."""
        return [self.line]


def draw_ellipse(ax: Axes, center: ArrayLike, semi_axes: ArrayLike, directions: ArrayLike, **kw: Any) -> EllipseArtist:
    r"""Draw the ellipse :math:`\{c + D\,\mathrm{diag}(s)\,u : \|u\| = 1\}` on a 2-D axes.

    ``semi_axes`` (2,) are the half-lengths s, ``directions`` (2, 2) holds the
    unit directions as columns (as returned by an SVD: ``U`` and ``sigma`` of
    the 2x2 linear-velocity block give the velocity ellipse). A zero semi-axis
    draws a segment, which is what the ellipse becomes at a singularity.
    Keyword arguments go to ``ax.plot``. Returns an :class:`EllipseArtist`.
    """
    return EllipseArtist(ax, center, semi_axes, directions, **kw)
