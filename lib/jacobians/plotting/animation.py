"""Animations for the book: a :class:`FrameSource` and its offline HTML player.

A :class:`FrameSource` is everything needed to make the frames of an
animation: a figure, a number of frames, a ``draw(k)`` that moves the artists
to frame ``k``, the time between frames, and how to render a frame (a full
redraw, blitting only the ``moving`` artists over a kept background, or a
renderer of its own, as the explorers of :mod:`jacobians.widgets` have).
:func:`animation_html` turns it into HTML and JavaScript that load nothing
from the internet, with palette PNG frames (:func:`compact_png`).

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> fig, ax = plt.subplots(figsize=(2, 2), dpi=30)
>>> (dot,) = ax.plot([0.0], [0.0], "o")
>>> source = FrameSource(fig, lambda k: dot.set_data([0.1 * k], [0.0]), 3, interval=200, moving=[dot])
>>> html = animation_html(source).data
>>> html.count("data:image/png;base64"), "https://" in html
(3, False)
"""

from __future__ import annotations

import base64
import functools
import html
import io
import re
import tempfile
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib import animation as _animation
from matplotlib.artist import Artist
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from numpy.typing import ArrayLike, NDArray

from .style import describe_text_problems, drawn_texts, smallest_text_px, text_owners

__all__ = ["FrameSource", "animation_html", "compact_png"]

#: MIME type of an animation's second player, its frames drawn for a projected slide (:func:`set_slide_frames`):
#: the lecture decks' build shows it; the book, JupyterLab and nbconvert show the ``text/html`` player
SLIDE_MIME = "text/vnd.jacobians.slide-html"

# where a slide shows an animation (px of the deck's canvas: width, height) and its smallest text there (px);
# None: no second player (set_slide_frames)
_SLIDE: dict[str, Any] = {"box": None, "text_px": None}


def set_slide_frames(box: tuple[float, float] | None, text_px: float | None = None) -> None:
    """Make :func:`animation_html` also draw each animation's frames for a projected slide (or stop, with None).

    ``box`` is the largest picture a slide shows an animation in (width, height, in px of the deck's
    canvas) and ``text_px`` the smallest text wanted there. An animation whose text, shown as large as
    the box allows, is smaller gets a second player (:data:`SLIDE_MIME`): the same figure drawn at the
    same pixel size, on a smaller canvas at a higher dpi, so that every text, line and marker grows by
    the same factor until the smallest text reaches ``text_px``. Costs a second rendering of every frame,
    so the course turns it on in a notebook kernel only (:func:`course.chapter.start_page`).
    """
    if box is None:
        _SLIDE.update(box=None, text_px=None)
        return
    w, h = (float(v) for v in box)
    if text_px is None or not (w > 0 and h > 0 and float(text_px) > 0):
        raise ValueError(f"Expected a positive box and text size, got {box!r} and {text_px!r}")
    _SLIDE.update(box=(w, h), text_px=float(text_px))



@dataclass(eq=False)
class FrameSource:
    """The frames of an animation, for :func:`animation_html`.

    Parameters
    ----------
    fig : matplotlib Figure
    draw : callable
        ``draw(k)`` moves the artists to frame ``k`` (``0 <= k < n_frames``).
        Like matplotlib's ``FuncAnimation``, it may return the artists it
        changed; the return value is not used.
    n_frames : int
    interval : float
        Milliseconds between frames.
    moving : list of artists, optional
        If given, the fixed part of the figure is drawn once and kept as a
        bitmap, and each frame draws only these artists over it (several times
        faster than a full redraw). Every artist that ``draw`` changes must be
        listed; anything else keeps the state it had at the first render.
    render : callable, optional
        ``render()`` returns the current frame as an (h, w, 3 or 4) array;
        replaces the two ways above (the explorers pass their own blitter).
    explorer : object, optional
        The widget that draws the frames, if any (its fields hold what it shows).
    path : ndarray, optional
        The configurations of the frames, if the maker records them.
    """

    fig: Figure
    draw: Callable[[int], Any]
    n_frames: int
    interval: float = 100.0
    moving: Sequence[Artist] | None = None
    render: Callable[[], ArrayLike] | None = None
    explorer: Any = None
    path: NDArray[np.float64] | None = None
    _background: Any = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.fig, Figure):
            raise TypeError(f"Expected a matplotlib Figure for fig, got {type(self.fig).__name__}")
        if not callable(self.draw):
            raise TypeError(f"Expected a callable draw(k), got {type(self.draw).__name__}")
        n = self.n_frames
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"Expected a positive number of frames, got {n!r}")
        self.n_frames = int(n)
        interval = float(self.interval)
        if not np.isfinite(interval) or interval <= 0:
            raise ValueError(f"Expected a positive interval in milliseconds, got {self.interval!r}")
        self.interval = interval
        if self.render is not None and not callable(self.render):
            raise TypeError(f"Expected a callable render(), got {type(self.render).__name__}")
        if self.moving is not None:
            self.moving = list(self.moving)
            for a in self.moving:
                if not isinstance(a, Artist):
                    raise TypeError(f"Expected matplotlib artists in moving, got {type(a).__name__}")
                a.set_animated(True)

    def _canvas(self) -> FigureCanvasAgg:
        canvas = self.fig.canvas
        if not isinstance(canvas, FigureCanvasAgg):  # e.g. a Figure() made without pyplot
            canvas = FigureCanvasAgg(self.fig)
        return canvas

    def rgba(self) -> NDArray[np.uint8]:
        """The figure as it is now, rendered as this source renders frames: an (h, w, 3) array."""
        if self.render is not None:
            return np.asarray(self.render())[..., :3].copy()
        canvas = self._canvas()
        if self.moving is None:
            canvas.draw()
        else:
            if self._background is None:
                canvas.draw()  # the animated (moving) artists are left out of this one
                self._background = canvas.copy_from_bbox(self.fig.bbox)
            else:
                canvas.restore_region(self._background)
            for a in self.moving:
                self.fig.draw_artist(a)
        return np.asarray(canvas.buffer_rgba())[..., :3].copy()

    def frame(self, k: int) -> NDArray[np.uint8]:
        """Frame ``k`` as an (h, w, 3) array: ``draw(k)``, then render."""
        if not 0 <= int(k) < self.n_frames:
            raise ValueError(f"Expected a frame index between 0 and {self.n_frames - 1}, got {k!r}")
        self.draw(int(k))
        return self.rgba()

    def invalidate(self) -> None:
        """Forget the kept background (call after changing a fixed part of the figure)."""
        self._background = None


def compact_png(image: ArrayLike | bytes, colors: int = 96) -> bytes:
    """PNG bytes of an RGB(A) array or of PNG bytes, reduced to an adaptive palette of ``colors`` colours.

    Line drawings on white need few colours; a palette PNG is 3 to 5 times
    smaller than matplotlib's RGBA PNG and looks the same (no dithering).
    """
    from PIL import Image

    if isinstance(image, (bytes, bytearray)):
        im = Image.open(io.BytesIO(image)).convert("RGB")
    else:
        im = Image.fromarray(np.asarray(image)[..., :3])
    q = im.quantize(colors=int(colors), method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    buf = io.BytesIO()
    q.save(buf, format="png", optimize=True)
    return buf.getvalue()


# ---------------------------------------------------------------- the HTML player

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

# one embedded frame of matplotlib's HTMLWriter (base64 lines joined by "\" + newline)
_FRAME = re.compile(r'frames\[(\d+)\] = "data:image/png;base64,([^"]*)"')


def _strip_cdn(html: str) -> str:
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html, flags=re.S)

    def icon(m: re.Match[str]) -> str:
        cls = m.group(1).replace("fa ", "", 1).strip()
        sym = _ICONS.get(cls)
        if sym is None:
            return m.group(0)
        return f'<span class="jac-anim-icon" aria-hidden="true">{sym}</span>'

    html = re.sub(r'<i class="(fa [^"]*)"></i>', icon, html)
    # the frame slider gets a name a screen reader says ("Animation frame, 12")
    html = re.sub(r'(<input id="_anim_slider[^"]*" type="range" class="anim-slider")',
                  r'\1 aria-label="Animation frame"', html)
    style = ("<style>.animation .anim-buttons button{min-width:2.4em;font-size:1.05em;line-height:1.4;"
             "font-family:'DejaVu Sans',system-ui,sans-serif;}.jac-anim-icon{font-style:normal;}</style>")
    return style + html


def _swap_frames(html: str, frames: Sequence[str]) -> str:
    """Put ``frames`` (base64 PNGs) in place of the frames embedded in matplotlib's player."""
    found = _FRAME.findall(html)
    if len(found) != len(frames):  # matplotlib changed how HTMLWriter embeds frames
        raise RuntimeError(f"Expected {len(frames)} embedded frames in matplotlib's HTML player, "
                           f"found {len(found)} (matplotlib {matplotlib.__version__})")
    return _FRAME.sub(lambda m: f'frames[{m.group(1)}] = "data:image/png;base64,{frames[int(m.group(1))]}"', html)


def _player(frames: Sequence[str], interval: float, default_mode: str) -> str:
    """matplotlib's JavaScript player (HTMLWriter) around the given base64 PNG frames.

    The player is written for a tiny stand-in figure, one grab per frame,
    and the stand-in frames are then replaced by ours: HTMLWriter's public
    interface, no full redraw of the real figure.
    """
    stand_in = Figure(figsize=(1, 1), dpi=2)  # 2 x 2 pixels
    FigureCanvasAgg(stand_in)
    fps: Any = 1000.0 / interval  # a float, as matplotlib uses it (its stubs say int)
    writer = _animation.HTMLWriter(fps=fps, embed_frames=True, default_mode=default_mode)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp, "anim.html")
        with writer.saving(stand_in, str(out), 2):
            for _ in frames:
                writer.grab_frame()
        return _swap_frames(out.read_text(), frames)


def _plain_animation_frames(anim: _animation.Animation, default_mode: str, colors: int) -> tuple[str, list[str]]:
    """A matplotlib Animation not made by us: its own HTML, frames reduced to palette PNGs."""
    with matplotlib.rc_context({"animation.embed_limit": 1e4}):
        html = anim.to_jshtml(embed_frames=True, default_mode=default_mode)
    frames = [base64.b64encode(compact_png(base64.b64decode(b.replace("\\\n", "")), colors)).decode("ascii")
              for _, b in _FRAME.findall(html)]
    return html, frames


def animation_html(anim: FrameSource | _animation.Animation, *, default_mode: str = "loop",
                   embed_limit_mb: float = 3.0, colors: int = 96) -> Any:
    """Embed an animation as inline HTML/JS that loads nothing from the internet.

    ``anim`` is a :class:`FrameSource` (what the course's animation makers
    return), or a matplotlib ``Animation`` (rendered by a full redraw of each
    frame). The player is
    matplotlib's, whose control buttons link the font-awesome icon font from a
    CDN: that ``<link>`` goes and the buttons are written as Unicode symbols
    (▶, ❚❚, ...). Frames are palette PNGs (``colors`` colours, see
    :func:`compact_png`), about 4x lighter than matplotlib's; frames beyond
    ``embed_limit_mb`` are dropped with a warning. The figure of a
    :class:`FrameSource` is closed, so no stray static copy of it follows the
    animation in a notebook. After :func:`set_slide_frames`, a :class:`FrameSource`
    whose text is too small for a projected slide also gets a second player,
    its frames drawn with larger text, under :data:`SLIDE_MIME`.

    Returns
    -------
    IPython.display.HTML
        The book's player (``.data``); displayed, it shows as ``text/html`` and
        carries the slides' player, if any, as :data:`SLIDE_MIME`.
    """
    from IPython.display import HTML

    if default_mode not in ("loop", "once", "reflect"):
        raise ValueError(f"Expected default_mode 'loop', 'once' or 'reflect', got {default_mode!r}")
    if isinstance(anim, _animation.Animation):
        html, reduced = _plain_animation_frames(anim, default_mode, colors)
        return HTML(_strip_cdn(_swap_frames(html, reduced)))
    if not isinstance(anim, FrameSource):
        raise TypeError(f"Expected a FrameSource (or a matplotlib Animation), got {type(anim).__name__}")
    limit = float(embed_limit_mb) * 1024 * 1024
    slides_on = _SLIDE["box"] is not None
    try:
        texts: list[list[tuple[Any, str, Any]]] | None = [] if slides_on else None
        frames = _encoded_frames(anim, colors, limit, "frames", stacklevel=3, texts=texts)
        # the smallest text of the frames, in frame pixels (the decks' tests scale it by the shown width)
        try:
            text_px = f"{smallest_text_px(anim.fig):.2f}"
        except ValueError:  # no text at all
            text_px = "none"
        slide = _slide_player(anim, default_mode, colors, limit)
        # where the slides show the book's own frames, those are checked as the slides' would be
        problems = frame_text_problems(anim, texts) if slides_on and slide is None and texts else None
    finally:
        plt.close(anim.fig)
    return _animation_html_type()(_jac_anim(frames, text_px, anim.interval, default_mode, problems), slide)


def _encoded_frames(anim: FrameSource, colors: int, limit: float, what: str, stacklevel: int,
                    texts: list[list[tuple[Any, str, Any]]] | None = None,
                    lines: list[list[tuple[Any, str, Any]]] | None = None) -> list[str]:
    """``anim``'s frames as base64 palette PNGs, up to ``limit`` bytes in all (the rest dropped, with a warning
    at the caller of :func:`animation_html`). With a list ``texts``, each frame's drawn texts are appended to
    it (:func:`jacobians.plotting.style.drawn_texts`), one list a frame; with ``lines`` as well, each frame's
    drawn plotted lines to that."""
    frames: list[str] = []
    total = 0
    for k in range(anim.n_frames):
        if texts is None:
            image = anim.frame(k)
        else:
            drawn_lines: list[tuple[Any, str, Any]] = []
            with drawn_texts(anim.fig, drawn_lines if lines is not None else None) as drawn:
                image = anim.frame(k)
            texts.append(drawn)
            if lines is not None:
                lines.append(drawn_lines)
        data = base64.b64encode(compact_png(image, colors)).decode("ascii")
        total += len(data)
        if total >= limit:
            warnings.warn(f"animation_html: {what} beyond {limit / 1e6:.1f} MB were dropped; "
                          "use fewer frames or a lower dpi", stacklevel=stacklevel)
            break
        frames.append(data)
    return frames


def frame_text_problems(anim: FrameSource, texts: Sequence[Sequence[tuple[Any, str, Any]]],
                        lines: Sequence[Sequence[tuple[Any, str, Any]]] | None = None) -> list[str]:
    """The texts that overlap, are cut off at the canvas edge, or that a plotted line runs through in any
    frame of ``anim``, each said once with the frames it is seen in (1-based), from the texts (and lines)
    drawn frame by frame (:func:`_encoded_frames`).

    A blitted frame draws only the moving artists over the first frame's picture: the texts and lines of
    the first frame that no later frame draws again are the fixed ones, and belong to every frame. A source
    that renders its frames itself draws no matplotlib text: nothing to check.
    """
    if not texts:
        return []
    lines = lines if lines is not None else [[] for _ in texts]

    def fixed_of(drawn: Sequence[Sequence[tuple[Any, str, Any]]]) -> list[tuple[Any, str, Any]]:
        redrawn = {id(t) for frame in drawn[1:] for t, _, _ in frame}
        return [b for b in drawn[0] if id(b[0]) not in redrawn] if anim.moving is not None else []

    fixed, fixed_lines = fixed_of(texts), fixed_of(lines)
    seen: dict[str, list[int]] = {}
    owners = text_owners(anim.fig)
    for k, (frame, frame_lines) in enumerate(zip(texts, lines, strict=True)):
        boxes = list(frame) if k == 0 else fixed + list(frame)
        drawn = list(frame_lines) if k == 0 else fixed_lines + list(frame_lines)
        for problem in describe_text_problems(boxes, anim.fig, owners, lines=drawn):
            seen.setdefault(problem, []).append(k + 1)
    return [f"{problem} (frame{'s' if len(ks) > 1 else ''} {_ranges(ks)})" for problem, ks in seen.items()]


def _ranges(ks: list[int]) -> str:
    """1, 2, 3, 5 -> "1-3, 5"."""
    out: list[str] = []
    start = prev = ks[0]
    for k in [*ks[1:], None]:
        if k is not None and k == prev + 1:
            prev = k
            continue
        out.append(f"{start}-{prev}" if prev > start else f"{start}")
        if k is not None:
            start = prev = k
    return ", ".join(out)


#: attribute of an animation's player (``div.jac-anim``) drawn for the slides: what is wrong with the text of its
#: frames (:func:`frame_text_problems`), "" when nothing; the decks' tests fail on anything else
TEXT_PROBLEMS_ATTR = "data-text-problems"


def _jac_anim(frames: list[str], text_px: str, interval: float, default_mode: str,
              problems: list[str] | None = None) -> str:
    """The player of ``frames``, marked with its smallest text in frame pixels (read by the decks' tests) and,
    for the slides, what is wrong with its frames' text (:data:`TEXT_PROBLEMS_ATTR`)."""
    player = _strip_cdn(_player(frames, interval, default_mode))
    checked = "" if problems is None else f' {TEXT_PROBLEMS_ATTR}="{html.escape("; ".join(problems), quote=True)}"'
    return f'<div class="jac-anim" data-smallest-text-px="{text_px}"{checked}>{player}</div>'


@functools.cache
def _animation_html_type() -> type:
    """IPython's ``HTML`` (imported when first needed: the plotting extra has no IPython) with a second
    player for the slides."""
    from IPython.display import HTML

    class AnimationHTML(HTML):
        """The book's player (``text/html``), and where one was drawn, the slides' (:data:`SLIDE_MIME`)."""

        def __init__(self, data: str, slide: str | None) -> None:
            super().__init__(data)
            self.slide = slide

        def _repr_mimebundle_(self, include: Any = None, exclude: Any = None) -> dict[str, str]:
            return {SLIDE_MIME: self.slide} if self.slide is not None else {}

    return AnimationHTML


def _moving_text_px(anim: FrameSource) -> float:
    """The smallest text among the moving artists (``canvas.draw`` leaves animated artists out), px."""
    from matplotlib.text import Text

    sizes = [float(a.get_fontsize()) for a in anim.moving or () if isinstance(a, Text)]
    return min(sizes) * float(anim.fig.dpi) / 72.0 if sizes else float("inf")


def _slide_player(anim: FrameSource, default_mode: str, colors: int, limit: float) -> str | None:
    """The slides' player of ``anim`` (:func:`set_slide_frames`), or None (not asked, not needed, or a
    source that renders its frames itself)."""
    box, want = _SLIDE["box"], _SLIDE["text_px"]
    if box is None or anim.render is not None:
        return None
    fig = anim.fig
    try:
        smallest = min(smallest_text_px(fig), _moving_text_px(anim))
    except ValueError:  # no text at all
        return None
    w, h = float(fig.bbox.width), float(fig.bbox.height)
    shown = min(box[0], box[1] * w / h) / w   # the slide's scale of a frame pixel
    if smallest * shown >= want:
        return None   # the book's frames already read from the back row
    # the same pixels, every text, line and marker grown by the same factor (2 % more: rounding of sizes)
    grow = want / (smallest * shown) * 1.02
    width_in, height_in = fig.get_size_inches()
    fig.set_dpi(float(fig.dpi) * grow)
    fig.set_size_inches(width_in / grow, height_in / grow)
    anim.invalidate()
    texts: list[list[tuple[Any, str, Any]]] = []
    frames = _encoded_frames(anim, colors, limit, "slide frames", stacklevel=4, texts=texts)
    text_px = min(smallest_text_px(fig), _moving_text_px(anim))
    problems = frame_text_problems(anim, texts)
    if problems:
        warnings.warn("animation_html: the text of the slides' frames overlaps or is cut off: "
                      + "; ".join(problems), stacklevel=3)
    return _jac_anim(frames, f"{text_px:.2f}", anim.interval, default_mode, problems)
