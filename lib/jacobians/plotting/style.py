"""Colours and lecture style: the Okabe–Ito palette and its semantic keys.

Colours come from :data:`PALETTE`, the Okabe–Ito palette, which stays
distinguishable under the common colour-vision deficiencies; its semantic keys
(``"space"``, ``"body"``, ``"velocity"``, ...) keep one meaning across the book.
Importing this module imports matplotlib only when :func:`set_style` runs.

>>> PALETTE["space"] == PALETTE["orange"]
True
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

__all__ = ["PALETTE", "COLUMN_COLORS", "set_style", "smallest_text_px", "drawn_texts", "overlapping_texts",
           "clipped_texts", "text_owners", "texts_in_other_axes", "texts_over_lines", "drawn_line", "text_problems"]

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
    import matplotlib
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


def smallest_text_px(fig: Any) -> float:
    """Size in pixels, at the figure's own dpi, of the smallest text a figure draws.

    The figure is drawn once and every text it draws (title, axis labels,
    the tick labels its locators chose, legend entries, annotations) counts;
    hidden axes and empty strings do not. Mathtext sub- and superscripts are
    drawn smaller than their text's size and are not counted. The lecture
    decks scale this by the width a figure is shown at (``tests/slides``).

    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 2), dpi=144)
    >>> ax = fig.add_subplot()
    >>> ax.tick_params(labelsize=9)
    >>> _ = ax.set_xlabel("x", fontsize=20)
    >>> smallest_text_px(fig)
    18.0
    >>> _ = ax.axis("off")
    >>> smallest_text_px(fig)
    Traceback (most recent call last):
    ...
    ValueError: Expected a figure that draws some text, got none
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.text import Text

    if not isinstance(fig, Figure):
        raise TypeError(f"Expected a matplotlib Figure, got {type(fig).__name__}")
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    sizes: list[float] = []
    original = Text.draw

    def draw(self: Any, renderer: Any) -> Any:
        if self.get_visible() and self.get_text().strip():
            sizes.append(float(self.get_fontsize()))
        return original(self, renderer)

    Text.draw = draw  # type: ignore[method-assign]
    try:
        canvas.draw()
    finally:
        Text.draw = original  # type: ignore[method-assign]
    if not sizes:
        raise ValueError("Expected a figure that draws some text, got none")
    return min(sizes) * float(fig.dpi) / 72.0


@contextlib.contextmanager
def drawn_texts(fig: Any, lines: list[tuple[Any, str, Any]] | None = None) -> Iterator[list[tuple[Any, str, Any]]]:
    """Record every text ``fig`` draws inside the ``with`` block, as (text artist, its words, its box in
    display pixels), in drawing order.

    Only what is drawn counts: a canvas draw, or ``fig.draw_artist`` of the moving artists of a blitted
    frame; hidden texts, empty strings and the tick labels a 3-D axis keeps but does not draw do not.
    Each text is listed once, at its last drawn box. With a list ``lines``, the plotted lines drawn (a
    plot's ``ax.lines``: curves, segments, markers; not its grid, ticks or legend) are appended to it as
    :func:`drawn_line` records them.
    """
    from matplotlib.lines import Line2D
    from matplotlib.text import Text

    found: dict[int, tuple[Any, str, Any]] = {}
    order: list[int] = []
    original = Text.draw
    original_line = Line2D.draw
    seen_lines: dict[int, tuple[Any, str, Any]] = {}
    line_order: list[int] = []

    def draw_line(self: Any, renderer: Any) -> Any:
        done = original_line(self, renderer)
        if self.get_figure(root=True) is fig and self.axes is not None and any(self is ln for ln in self.axes.lines):
            shape = drawn_line(self)
            if shape is not None:
                if id(self) not in seen_lines:
                    line_order.append(id(self))
                seen_lines[id(self)] = shape
        return done

    def draw(self: Any, renderer: Any) -> Any:
        done = original(self, renderer)
        if self.get_figure(root=True) is fig and self.get_visible() and self.get_text().strip():
            try:
                box = self.get_window_extent(renderer)
            except (RuntimeError, ValueError):
                return done
            if box.width > 0 and box.height > 0:
                if id(self) not in found:
                    order.append(id(self))
                found[id(self)] = (self, self.get_text().strip().replace("\n", " ")[:30], box)
        return done

    out: list[tuple[Any, str, Any]] = []
    Text.draw = draw  # type: ignore[method-assign]
    if lines is not None:
        Line2D.draw = draw_line  # type: ignore[method-assign]
    try:
        yield out
    finally:
        Text.draw = original  # type: ignore[method-assign]
        Line2D.draw = original_line  # type: ignore[method-assign]
        out.extend(found[i] for i in order)
        if lines is not None:
            lines.extend(seen_lines[i] for i in line_order)


def drawn_line(line: Any) -> tuple[Any, str, Any] | None:
    """A plotted line as it was last drawn: (the line, its label, (its vertices in display pixels as an
    (n, 2) array or None if no line joins them, the half width of its stroke in pixels, the half size of
    its markers in pixels or 0 if none)); None if it shows nothing. A 3-D plot's line holds its projection
    once drawn, so the same holds for it."""
    import numpy as np

    if not line.get_visible() or (line.get_alpha() is not None and line.get_alpha() == 0):
        return None
    xy = np.asarray(line.get_xydata(), dtype=float)
    if xy.ndim != 2 or len(xy) == 0:
        return None
    pts = line.get_transform().transform(xy)
    pts = pts[np.isfinite(pts).all(axis=1)]
    if len(pts) == 0:
        return None
    px = line.get_figure(root=True).dpi / 72.0
    stroked = line.get_linestyle() not in ("None", "none", " ", "") and line.get_linewidth() > 0
    marker = line.get_marker()
    marked = marker not in (None, "None", "none", " ", "")
    if not stroked and not marked:
        return None
    half_marker = 0.5 * line.get_markersize() * px + 0.5 * line.get_markeredgewidth() * px if marked else 0.0
    name = str(line.get_label())
    if name.startswith("_"):   # matplotlib's name of an unlabelled line
        axes = line.get_figure(root=True).axes
        where = next((i + 1 for i, ax in enumerate(axes) if ax is line.axes), 0)
        name = f"a line of plot {where}"
    return (line, name, (pts, 0.5 * line.get_linewidth() * px if stroked else None, half_marker))


def overlapping_texts(boxes: list[tuple[Any, str, Any]]) -> list[tuple[str, str]]:
    """Pairs of texts (as :func:`drawn_texts` lists them) whose boxes overlap: each at least a third of the
    smaller's height and a tenth of its width, so two lines that merely touch, or a subscript's reach, do
    not count.

    >>> from matplotlib.transforms import Bbox
    >>> overlapping_texts([(None, "a", Bbox([[0, 0], [40, 10]])), (None, "b", Bbox([[30, 2], [70, 12]])),
    ...                    (None, "c", Bbox([[0, 10.5], [40, 20]]))])
    [('a', 'b')]
    """
    found = []
    for i, (_, a, ba) in enumerate(boxes):
        for _, b, bb in boxes[i + 1:]:
            w = min(ba.x1, bb.x1) - max(ba.x0, bb.x0)
            h = min(ba.y1, bb.y1) - max(ba.y0, bb.y0)
            if w > 0.1 * min(ba.width, bb.width) and h > 0.33 * min(ba.height, bb.height):
                found.append((a, b))
    return found


def clipped_texts(boxes: list[tuple[Any, str, Any]], fig: Any, tolerance: float = 1.0) -> list[str]:
    """The texts (as :func:`drawn_texts` lists them) that reach past the edge of ``fig``'s canvas by more
    than ``tolerance`` pixels: cut off in the picture.

    >>> from matplotlib.figure import Figure
    >>> from matplotlib.transforms import Bbox
    >>> fig = Figure(figsize=(1, 1), dpi=100)
    >>> clipped_texts([(None, "in", Bbox([[0, 0], [100, 20]])), (None, "out", Bbox([[90, 0], [110, 20]]))], fig)
    ['out']
    """
    edge = fig.bbox
    return [what for _, what, b in boxes
            if b.x0 < edge.x0 - tolerance or b.y0 < edge.y0 - tolerance
            or b.x1 > edge.x1 + tolerance or b.y1 > edge.y1 + tolerance]


def _segment_hits_box(p: Any, q: Any, x0: float, y0: float, x1: float, y1: float) -> bool:
    """Whether the segment p-q passes through the box [x0, x1] x [y0, y1] (Liang-Barsky clipping)."""
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for step, room in ((-dx, p[0] - x0), (dx, x1 - p[0]), (-dy, p[1] - y0), (dy, y1 - p[1])):
        if step == 0:
            if room < 0:
                return False
            continue
        t = room / step
        if step < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return False
    return True


def texts_over_lines(boxes: list[tuple[Any, str, Any]], lines: list[tuple[Any, str, Any]],
                     inset: float = 0.2) -> list[tuple[str, str]]:
    """Pairs (a text's words, a line's label) where a plotted line (as :func:`drawn_texts` records them with
    ``lines``) runs through a text or one of its markers sits on it: the text's box less ``inset`` of its
    height on each side (the box holds room above and below the letters), grown by half the line's width.
    A text on a box of its own or with a halo (a label drawn over the lines on purpose, readable there) does
    not count.

    >>> import numpy as np
    >>> from matplotlib.transforms import Bbox
    >>> line = (None, "arm", (np.array([[0.0, 5.0], [100.0, 5.0]]), 1.0, 0.0))
    >>> dot = (None, "joint", (np.array([[60.0, 30.0]]), None, 4.0))
    >>> texts_over_lines([(None, "crossed", Bbox([[10, 0], [40, 10]])), (None, "above", Bbox([[10, 8], [40, 18]])),
    ...                   (None, "on a joint", Bbox([[50, 26], [90, 36]]))], [line, dot])
    [('crossed', 'arm'), ('on a joint', 'joint')]
    """
    import numpy as np

    found = []
    for t, what, b in boxes:
        if t is not None and _drawn_on_its_own_box(t):
            continue
        pad = inset * b.height
        for _, name, (pts, half_width, half_marker) in lines:
            hit = False
            if half_width is not None and len(pts) > 1:
                grow = half_width - pad
                x0, y0, x1, y1 = b.x0 - grow, b.y0 - grow, b.x1 + grow, b.y1 + grow
                if x0 < x1 and y0 < y1:
                    lo, hi = np.minimum(pts[:-1], pts[1:]), np.maximum(pts[:-1], pts[1:])
                    near = np.flatnonzero((hi[:, 0] >= x0) & (lo[:, 0] <= x1) & (hi[:, 1] >= y0) & (lo[:, 1] <= y1))
                    hit = any(_segment_hits_box(pts[i], pts[i + 1], x0, y0, x1, y1) for i in near)
            if not hit and half_marker > 0:
                r = half_marker
                hit = bool(np.any((pts[:, 0] + r > b.x0 + pad) & (pts[:, 0] - r < b.x1 - pad)
                                  & (pts[:, 1] + r > b.y0 + pad) & (pts[:, 1] - r < b.y1 - pad)))
            if hit:
                found.append((what, name))
    return found


def _drawn_on_its_own_box(t: Any) -> bool:
    """Whether a text is drawn on a filled box of its own (``bbox=...``) or with a halo (a stroke path
    effect): it reads over the lines it covers."""
    patch = t.get_bbox_patch() if hasattr(t, "get_bbox_patch") else None
    if patch is not None and patch.get_fill() and patch.get_facecolor()[3] > 0.5:
        return True
    return any(type(e).__name__ in ("withStroke", "Stroke") for e in (t.get_path_effects() or []))


def text_owners(fig: Any) -> dict[int, Any]:
    """Each text of ``fig``'s plots (titles, axis and tick labels, legends, annotations) by ``id``, with the
    plot (Axes) it belongs to: a tick label knows its figure, not its plot."""
    from matplotlib.text import Text

    return {id(t): ax for ax in fig.axes for t in ax.findobj(Text)}


def texts_in_other_axes(boxes: list[tuple[Any, str, Any]], fig: Any, margin: float = 2.0,
                        owners: dict[int, Any] | None = None) -> list[tuple[str, int]]:
    """The texts (as :func:`drawn_texts` lists them) of one plot, or of the figure, that reach into the
    drawing area of another 2-D plot of ``fig`` by more than ``margin`` pixels both ways: an axis label or a
    legend over a neighbour's curves. Each as (its words, the number of the plot it enters, 1-based in
    ``fig.axes``). A 3-D plot's area is mostly empty margin and is not counted; a plot's own texts (a
    legend inside it) are its own business.
    """
    owners = text_owners(fig) if owners is None else owners
    found = []
    for t, what, b in boxes:
        owner = owners.get(id(t))
        for i, ax in enumerate(fig.axes):
            if ax is owner or hasattr(ax, "zaxis") or not ax.get_visible() or not ax.axison:
                continue
            # twin or shared plots drawn over the same area are the owner's own area
            if owner is not None and owner.bbox.bounds == ax.bbox.bounds:
                continue
            area = ax.bbox
            w = min(b.x1, area.x1) - max(b.x0, area.x0)
            h = min(b.y1, area.y1) - max(b.y0, area.y0)
            if w > margin and h > margin:
                found.append((what, i + 1))
    return found


def text_problems(fig: Any) -> list[str]:
    """What is wrong with a figure's text on a fixed canvas, as one full draw shows it: pairs of texts that
    overlap (:func:`overlapping_texts`), texts cut off at the canvas edge (:func:`clipped_texts`), texts
    that reach into another plot (:func:`texts_in_other_axes`) and texts that a plotted line runs through
    (:func:`texts_over_lines`).

    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 1), dpi=100)
    >>> _ = fig.text(0.1, 0.5, "left"), fig.text(0.12, 0.5, "right"), fig.text(0.95, 0.5, "edge")
    >>> text_problems(fig)
    ["'left' overlaps 'right'", "'edge' is cut off at the edge"]
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    lines: list[tuple[Any, str, Any]] = []
    with drawn_texts(fig, lines) as boxes:
        canvas.draw()
    return describe_text_problems(boxes, fig, lines=lines)


def describe_text_problems(boxes: list[tuple[Any, str, Any]], fig: Any,
                           owners: dict[int, Any] | None = None,
                           lines: list[tuple[Any, str, Any]] | None = None) -> list[str]:
    """:func:`overlapping_texts`, :func:`clipped_texts`, :func:`texts_in_other_axes` and, given the drawn
    ``lines``, :func:`texts_over_lines` of ``boxes`` in words (``owners``: :func:`text_owners` of ``fig``, if
    known)."""
    return ([f"{a!r} overlaps {b!r}" for a, b in overlapping_texts(boxes)]
            + [f"{what!r} is cut off at the edge" for what in clipped_texts(boxes, fig)]
            + [f"{what!r} reaches into plot {i}" for what, i in texts_in_other_axes(boxes, fig, owners=owners)]
            + [f"{what!r} lies on {name!r}" for what, name in dict.fromkeys(texts_over_lines(boxes, lines or []))])
