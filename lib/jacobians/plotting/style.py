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
           "clipped_texts", "text_owners", "texts_in_other_axes", "text_problems"]

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
def drawn_texts(fig: Any) -> Iterator[list[tuple[Any, str, Any]]]:
    """Record every text ``fig`` draws inside the ``with`` block, as (text artist, its words, its box in
    display pixels), in drawing order.

    Only what is drawn counts: a canvas draw, or ``fig.draw_artist`` of the moving artists of a blitted
    frame; hidden texts, empty strings and the tick labels a 3-D axis keeps but does not draw do not.
    Each text is listed once, at its last drawn box.
    """
    from matplotlib.text import Text

    found: dict[int, tuple[Any, str, Any]] = {}
    order: list[int] = []
    original = Text.draw

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
    try:
        yield out
    finally:
        Text.draw = original  # type: ignore[method-assign]
        out.extend(found[i] for i in order)


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
    overlap (:func:`overlapping_texts`), texts cut off at the canvas edge (:func:`clipped_texts`) and texts
    that reach into another plot (:func:`texts_in_other_axes`).

    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 1), dpi=100)
    >>> _ = fig.text(0.1, 0.5, "left"), fig.text(0.12, 0.5, "right"), fig.text(0.95, 0.5, "edge")
    >>> text_problems(fig)
    ["'left' overlaps 'right'", "'edge' is cut off at the edge"]
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    with drawn_texts(fig) as boxes:
        canvas.draw()
    return describe_text_problems(boxes, fig)


def describe_text_problems(boxes: list[tuple[Any, str, Any]], fig: Any,
                           owners: dict[int, Any] | None = None) -> list[str]:
    """:func:`overlapping_texts`, :func:`clipped_texts` and :func:`texts_in_other_axes` of ``boxes`` in words
    (``owners``: :func:`text_owners` of ``fig``, if known)."""
    return ([f"{a!r} overlaps {b!r}" for a, b in overlapping_texts(boxes)]
            + [f"{what!r} is cut off at the edge" for what in clipped_texts(boxes, fig)]
            + [f"{what!r} reaches into plot {i}" for what, i in texts_in_other_axes(boxes, fig, owners=owners)])
