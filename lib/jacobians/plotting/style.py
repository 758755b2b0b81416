"""Colours and lecture style: the Okabe–Ito palette and its semantic keys.

Colours come from :data:`PALETTE`, the Okabe–Ito palette, which stays
distinguishable under the common colour-vision deficiencies; its semantic keys
(``"space"``, ``"body"``, ``"velocity"``, ...) keep one meaning across the book.
Importing this module imports matplotlib only when :func:`set_style` runs.

>>> PALETTE["space"] == PALETTE["orange"]
True
"""

from __future__ import annotations

from typing import Any

__all__ = ["PALETTE", "COLUMN_COLORS", "set_style", "smallest_text_px"]

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
