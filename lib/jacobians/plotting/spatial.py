"""Spatial chains on 3-D axes: numbered joint axes, frames, and labels placed clear of each other."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, cast

import numpy as np
from matplotlib.artist import Artist
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from .._validation import theta_array
from ..chain import SerialChain, _as_chain
from .artists import FrameArtist, _is_3d, arm_reach
from .style import COLUMN_COLORS, PALETTE

__all__ = ["SpatialChainArtist", "setup_3d_axes", "draw_spatial_chain"]


def _agg_renderer(fig: Figure, draw: bool = True) -> Any:
    """A renderer for measuring ``fig``'s texts (an Agg canvas is attached if the figure has none
    that can render, e.g. after ``plt.show()`` closed it in a notebook). With ``draw``, or when a
    layout engine only places the axes at draw time, the figure is drawn first."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    if draw or fig.get_layout_engine() is not None:
        fig.canvas.draw()
    return cast(Any, fig.canvas).get_renderer()


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

    def __init__(self, ax: Any, chain: SerialChain, theta: ArrayLike, *, show_axes: bool = True,
                 show_frames: bool = True, color: str | None = None, axis_length: float | None = None,
                 frame_length: float | None = None, label: str | None = None, highlight: Any = None,
                 fontsize: float | None = None, label_at: ArrayLike | None = None, label_box: bool = False) -> None:
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
                kw: dict[str, Any] = {}
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
    def _label_positions(label_at: ArrayLike, n: int) -> NDArray[np.float64]:
        t = np.broadcast_to(np.asarray(label_at, dtype=float), (n,)).copy() if np.ndim(label_at) == 0 else \
            np.asarray(label_at, dtype=float)
        if t.shape != (n,) or not np.all(np.isfinite(t)):
            raise ValueError(f"Expected label_at as one finite number or {n} of them (one per joint), got {label_at!r}")
        return t

    def _axis_direction(self, P: NDArray[np.float64], i: int) -> NDArray[np.float64]:
        S = self.chain.screw_axes
        if self.chain.joint_types[i] == "R":
            return P[i, :3, :3] @ S[:3, i]
        return P[i, :3, :3] @ S[3:, i]

    def update(self, theta: ArrayLike) -> SpatialChainArtist:
        th = theta_array(theta, self.chain.dof)
        P = self.chain.prefix_transforms(th)
        pts = self.chain.joint_positions(th)
        self.theta, self.points = th, pts
        self.link_line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
        self.joint_markers.set_data_3d(pts[:-1, 0], pts[:-1, 1], pts[:-1, 2])
        h = self.axis_length
        for i, (ln, tx, ld) in enumerate(zip(self.axis_lines, self.axis_texts, self.leader_lines, strict=True)):
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
    def artists(self) -> list[Artist]:
        """The artists that :meth:`update` moves (a :class:`~jacobians.plotting.FrameSource`'s ``moving``)."""
        out = [self.link_line, self.joint_markers, *self.axis_lines, *self.leader_lines, *self.axis_texts]
        if self.frames:
            out += self.frames[1].artists
        return out

    @property
    def axis_directions(self) -> NDArray[np.float64]:
        """(n, 3) current unit directions of the drawn joint axes."""
        out = []
        for ln in self.axis_lines:
            x, y, z = ln.get_data_3d()
            d = np.array([x[1] - x[0], y[1] - y[0], z[1] - z[0]])
            out.append(d / np.linalg.norm(d))
        return np.array(out)

    @property
    def label_points(self) -> NDArray[np.float64]:
        """(n, 3) where the axis numbers sit, in the coordinates of {s}."""
        return np.array([t.get_position_3d() for t in self.axis_texts], dtype=float).reshape(-1, 3)

    def _display(self, pts3: ArrayLike) -> NDArray[np.float64]:
        """Pixel coordinates of 3-D points in the axes' current view."""
        from mpl_toolkits.mplot3d import proj3d

        pts3 = np.asarray(pts3, dtype=float).reshape(-1, 3)
        x, y, _ = proj3d.proj_transform(pts3[:, 0], pts3[:, 1], pts3[:, 2], self.ax.get_proj())
        out: NDArray[np.float64] = self.ax.transData.transform(np.column_stack([x, y]))
        return out

    def place_labels(self, candidates: Sequence[float] = (1.5, -1.5, 1.8, -1.8, 2.1, -2.1, 2.5, -2.5, 2.9, -2.9, 3.3,
                                                         -3.3, 3.8, -3.8)) -> NDArray[np.float64]:
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

        def sampled(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
            da, db = self._display(np.array([a, b]))
            out: NDArray[np.float64] = da + s * (db - da)
            return out

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

        def point_clearance(c: Any, hw: Any, q: NDArray[np.float64]) -> float:
            """Signed distance from the points q to the box (negative inside)."""
            dx = np.abs(q[:, 0] - c[0]) - hw[0]
            dy = np.abs(q[:, 1] - c[1]) - hw[1]
            outside = np.hypot(np.maximum(dx, 0), np.maximum(dy, 0))
            inside = np.minimum(np.maximum(dx, dy), 0)
            return float(np.min(outside + inside))

        def rect_clearance(c: Any, hw: Any, r: Any) -> float:
            dx = abs(c[0] - r[0]) - hw[0] - r[2]
            dy = abs(c[1] - r[1]) - hw[1] - r[3]
            return float(np.hypot(max(dx, 0), max(dy, 0)) + min(max(dx, dy), 0))

        def leader(i: int, t: float) -> NDArray[np.float64] | None:
            """The sampled dotted leader from the segment's tip to the number (none within the tip)."""
            if abs(t) <= 1.0:
                return None
            return sampled(pts[i] + np.sign(t) * h * dirs[i], pts[i] + t * h * dirs[i])

        def score(i: int, t: float, placed: dict[int, Any]) -> float:
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
        placed: dict[int, Any] = {}
        for _ in range(4):  # a few sweeps: each number moves to its best spot given the others
            for i in range(n):
                best = max(cands, key=lambda t: score(i, t, placed))
                chosen[i] = best
                placed[i] = (self._display([pts[i] + best * h * dirs[i]])[0], leader(i, best))
        self.label_at = chosen
        self.update(self.theta)
        return chosen

    def _text_box(self, tx: Any, renderer: Any) -> Any:
        """Pixel bounding box of a 3-D text (and of its background box) as drawn in the current view."""
        from matplotlib.transforms import Bbox

        q = self._display([tx.get_position_3d()])[0]
        x2, y2 = self.ax.transData.inverted().transform(q)
        x3, y3 = tx.get_position()
        try:  # where Text3D.draw puts the text: its projected position, in the 2-D data coordinates
            tx.set_position((x2, y2))
            bb = tx.get_window_extent(renderer)
        finally:
            tx.set_position((x3, y3))
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
        for j, (ln, ld) in enumerate(zip(self.axis_lines, self.leader_lines, strict=True)):
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


def setup_3d_axes(ax: Any, chain: SerialChain, *, title: str | None = None, margin: float = 0.1,
                  fontsize: float | None = None) -> Any:
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


def draw_spatial_chain(ax3d: Any, chain: SerialChain, theta: ArrayLike, *, show_axes: bool = True,
                       show_frames: bool = True, color: str | None = None, axis_length: float | None = None,
                       frame_length: float | None = None, label: str | None = None, setup_axes: bool = False,
                       title: str | None = None, fontsize: float | None = None, label_at: ArrayLike | None = None,
                       label_box: bool = False, place_labels: bool = False) -> SpatialChainArtist:
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
