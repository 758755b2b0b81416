"""What every explorer shares: the blitting renderer, the widget base class, small HTML helpers."""

from __future__ import annotations

import contextlib
import io
from collections.abc import Iterator
from typing import Any

import ipywidgets as W
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from .._validation import theta_array
from ..chain import SerialChain
from ..plotting import (
    PALETTE,
)

__all__: list[str] = []

ROW_LABELS = ["ωx", "ωy", "ωz", "vx", "vy", "vz"]
ROW_LABELS_TEX = [r"\omega_x", r"\omega_y", r"\omega_z", r"v_x", r"v_y", r"v_z"]
FONT = 12


# ---------------------------------------------------------------- drawing machinery

class _Blitter:
    """Draw a figure's fixed part once, then only its moving artists; return PNG bytes."""

    def __init__(self, fig: Figure, live: bool) -> None:
        self.fig = fig
        self.canvas = FigureCanvasAgg(fig)
        self.live = live
        self.dynamic: list[Any] = []
        self._bg: Any = None

    def add(self, *artists: Any) -> None:
        """Draw these artists (nested lists allowed, None skipped) over the kept background."""
        for a in artists:
            if a is None:
                continue
            if isinstance(a, (list, tuple)):
                self.add(*a)
                continue
            if self.live:
                a.set_animated(True)
            self.dynamic.append(a)

    def invalidate(self) -> None:
        """Forget the kept background (after a change of a fixed part)."""
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

    def _setup(self, fig: Figure, static: bool) -> None:
        self.static = bool(static)
        self.fig = fig
        # static (book) figures blit too: their FrameSource renders frames with self.blitter.render_rgba
        self.blitter = _Blitter(fig, live=True)
        self.image = W.Image(format="png", layout=W.Layout(width=f"{int(fig.get_figwidth() * fig.dpi)}px"))
        self.render_count = 0
        self._hold = 0

    @contextlib.contextmanager
    def hold_updates(self) -> Iterator[_Explorer]:
        """Change several controls and redraw once at the end."""
        self._hold += 1
        try:
            yield self
        finally:
            self._hold -= 1
            if self._hold == 0:
                self.refresh()

    def _changed(self, change: object = None) -> None:
        if self._hold == 0:
            self.refresh()

    def refresh(self) -> None:
        """Recompute from the controls, move the artists, and (live) send a new PNG."""
        self._compute_and_update()
        if not self.static:
            self.png = self.blitter.render()
            self.image.value = self.png
        self.render_count += 1

    def _compute_and_update(self) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    def close_figure(self) -> None:
        """Clear the figure (frees its artists)."""
        self.fig.clear()


def _slider(description: str, value: float, lo: float, hi: float, step: float, color: str | None = None,
            readout_format: str = ".2f", width: str = "330px") -> W.FloatSlider:
    style = {"description_width": "70px"}
    if color:
        style["handle_color"] = color
    return W.FloatSlider(value=float(value), min=lo, max=hi, step=step, description=description,
                         continuous_update=True, readout_format=readout_format, style=style,
                         layout=W.Layout(width=width))


def _latex_block(*lines: str) -> str:
    return "".join(f"<div style='margin:2px 0'>$${ln}$$</div>" for ln in lines)


def _status_html(text: str, ok_level: str) -> str:
    colour = {"ok": PALETTE["ok"], "warn": PALETTE["warning"], "bad": PALETTE["singular"]}[ok_level]
    return (f"<div style='padding:4px 8px;border-left:8px solid {colour};font-size:15px'>"
            f"{text}</div>")


def _planar_theta(chain: SerialChain, theta: ArrayLike | None, default: list[float]) -> NDArray[np.float64]:
    n = chain.dof
    if theta is None:
        base: NDArray[np.float64] = np.array(default + [0.4] * n)[:n]
        return base
    return theta_array(theta, n)
