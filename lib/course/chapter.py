r"""What every chapter's hidden set-up cell imports: one place instead of a copy per page.

A chapter starts with one short cell::

    import numpy as np
    import sympy as sp
    import jacobians as jac
    from jacobians import lie, symbolic as sym
    from course.chapter import C, Verified, animation_html, clean, is_zero_matrix, show, start_page

    rng = start_page(seed=2)
    verified = Verified()

:func:`start_page` sets the print options and the figure style and returns the
page's random generator; ``verified`` collects what the page's hidden checks
proved (:mod:`jacobians.verified`).
The rest are the small helpers the pages share: :func:`clean` (round for
printing), :func:`show` (display LaTeX), :func:`trig_shorthand` (write
:math:`\sin(\theta_1+\theta_2)` as :math:`s_{12}`), finite-difference Jacobians
for independent checks, a random chain, and the exact zero tests of
:mod:`jacobians.symbolic`, which the hidden checks assert.
"""

from __future__ import annotations

import html
from collections.abc import Callable, Sequence
from typing import Any

import matplotlib
import numpy as np
import sympy as sp
from IPython.display import Math, display
from matplotlib.axes import Axes
from matplotlib.legend import Legend
from numpy.typing import ArrayLike, NDArray

import jacobians as jac
from jacobians import lie
from jacobians.plotting import COLUMN_COLORS, PALETTE, animation_html, set_style, smallest_text_px
from jacobians.plotting.animation import set_slide_frames
from jacobians.symbolic import is_zero, is_zero_matrix
from jacobians.testing import fd_tol
from jacobians.verified import Verified

__all__ = [
    "C",
    "PALETTE",
    "COLUMN_COLORS",
    "animation_html",
    "Verified",
    "start_page",
    "clean",
    "show",
    "latex_matrix",
    "trig_shorthand",
    "is_zero",
    "is_zero_matrix",
    "fd_space_jacobian",
    "fd_body_jacobian",
    "fd_jacobian_tol",
    "d_dt",
    "d_dt_tol",
    "random_arm",
    "legend_clear",
]

C: dict[str, str] = {
    "black": PALETTE["black"],
    "orange": PALETTE["orange"],
    "sky": PALETTE["sky_blue"],
    "green": PALETTE["bluish_green"],
    "blue": PALETTE["blue"],
    "vermillion": PALETTE["vermillion"],
    "purple": PALETTE["reddish_purple"],
}
"""Short names of the colour-blind-safe (Okabe–Ito) colours of :data:`jacobians.plotting.PALETTE`."""


def start_page(seed: int | None = None, font_size: float | None = None,
               lecture: bool = False) -> np.random.Generator:
    """Print options and figure style for a page; returns the page's random generator.

    Parameters
    ----------
    seed : int, optional
        Seed of the page's random generator (each chapter its own, so its numbers stay put).
    font_size : float, optional
        Readable figures: text of ``font_size`` pt, titles one point larger,
        ticks and legends at least 11 pt. Default: matplotlib's sizes.
    lecture : bool
        The lecture style of :func:`jacobians.plotting.set_style` (large fonts, thick lines) instead.
    """
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int)):
        raise TypeError(f"Expected an int seed, got {type(seed).__name__}")
    if font_size is not None and lecture:
        raise ValueError("Expected either font_size or lecture=True, got both")
    np.set_printoptions(precision=4, suppress=True)
    if lecture:
        set_style()
    elif font_size is not None:
        s = float(font_size)
        small = max(11.0, s - 1)
        matplotlib.rcParams.update({"font.size": s, "axes.titlesize": s + 1, "axes.labelsize": s,
                                    "xtick.labelsize": small, "ytick.labelsize": small,
                                    "legend.fontsize": small, "figure.titlesize": s + 1})
    _png_with_text_size()
    return np.random.default_rng(seed)


#: PNG text key under which a chapter's figures carry their smallest text size (px at natural size)
TEXT_SIZE_KEY = "course:smallest-text-px"


def _png_with_text_size() -> None:
    """In a notebook kernel, draw figures as PNGs that carry their smallest text size (:data:`TEXT_SIZE_KEY`).

    The lecture decks show the book's figures larger than the page does; the
    deck tests read this size from the PNG and scale it by the width the slide
    shows it at (labels of 16 px or more). Outside IPython nothing changes.
    """
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython is a dependency
        return
    ip = get_ipython()
    if ip is None or not hasattr(ip, "display_formatter"):
        return
    import matplotlib.pyplot as plt
    from IPython.core.pylabtools import print_figure
    from matplotlib.figure import Figure

    plt.get_backend()
    if "inline" in str(matplotlib.get_backend()):
        import matplotlib_inline.backend_inline  # noqa: F401  (sets up its formatters first, once)

    def png(fig: Figure) -> str | None:
        try:
            size = f"{smallest_text_px(fig):.2f}"
        except ValueError:
            size = "none"
        data: str | None = print_figure(fig, "png", base64=True, metadata={TEXT_SIZE_KEY: size})
        return data

    def svg(fig: Figure) -> str | None:
        return slide_svg(fig)

    ip.display_formatter.formatters["image/png"].for_type(Figure, png)
    # an animation too gets frames drawn for the slides, where its text would be too small there
    set_slide_frames(SLIDE_ANIMATION_BOX, SLIDE_TEXT_PX)
    # the decks' copy of each figure (the book shows the PNG: _ext/decks.py orders the two)
    ip.display_formatter.formatters["image/svg+xml"].for_type(Figure, svg)


#: where a slide shows a figure, in px of the decks' 1280x720 canvas (``_ext/decks_static/course_decks.css``:
#: an image at most 600 px tall under a heading and a line of text, at most as wide as the slide)
SLIDE_FIGURE_BOX = (1280.0, 600.0)
#: the smallest text of a figure on a slide, in px of the canvas. reveal.js draws the canvas and its 4 %
#: margin into the window: at 1024x768 at 1024/(1.04*1280) = 0.769 of its size, at 1280x720 at
#: 720/(1.04*720) = 0.962. 20 px on a 1024x768 screen is 20/0.769 = 26.0 px of the canvas, 24 px on a 1280x720
#: screen 24/0.962 = 24.96 px; 27 px meets both with a pixel to spare for rounding.
SLIDE_TEXT_PX = 27.0
#: where a slide shows an animation's frames, in px of the canvas (``course_decks.css``: 562 px tall under a line
#: of slide text, 600 px without; the player's buttons under it), at most as wide as the slide
SLIDE_ANIMATION_BOX = (1280.0, 562.0)
#: attribute of a slide figure's ``<svg>`` root: its smallest text, in the SVG's own units (its viewBox)
SVG_TEXT_ATTR = "data-smallest-text"


def _svg_size(svg: str) -> tuple[float, float]:
    import re

    m = re.search(r'<svg[^>]*?\bwidth="([\d.]+)pt"[^>]*?\bheight="([\d.]+)pt"', svg)
    if m is None:
        raise ValueError("Expected matplotlib's SVG with its size in pt")
    return float(m.group(1)), float(m.group(2))


def slide_svg(fig: Any) -> str | None:
    """The figure as the lecture decks show it: SVG (sharp at any projector size), text enlarged to
    :data:`SLIDE_TEXT_PX` at the size the slide shows it (:data:`SLIDE_FIGURE_BOX`).

    A copy of the figure is drawn (the book's PNG is left as the chapter made
    it); every text of the copy grows by the same factor until its smallest
    text, scaled by the width the slide shows the SVG at, reaches the target.
    Glyphs are paths, so the projector's computer needs none of the fonts.
    The smallest text, in the SVG's units, is written on its root
    (:data:`SVG_TEXT_ATTR`): the deck tests scale it by the width as drawn.
    None for a figure that cannot be copied (not picklable).
    """
    import io
    import pickle

    import matplotlib.pyplot as plt
    from matplotlib.text import Text
    from matplotlib.ticker import AutoLocator, MaxNLocator

    try:
        copy = pickle.loads(pickle.dumps(fig))
    except Exception:  # a figure with unpicklable parts keeps its PNG only
        return None
    try:
        with matplotlib.rc_context({"svg.fonttype": "path", "svg.hashsalt": "course-slides"}):
            try:
                base = smallest_text_px(copy) * 72.0 / float(copy.dpi)   # pt: the SVG's units
            except ValueError:
                base = None
            sizes = {id(t): (t, float(t.get_fontsize())) for t in copy.findobj(Text)}
            # a 3-D axis's label sits a fixed distance from its axis, which its rotated tick labels can reach:
            # on a slide it keeps 12 points more
            for ax in copy.axes:
                if hasattr(ax, "zaxis"):
                    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
                        axis.labelpad = float(axis.labelpad) + 12.0
            factor = 1.0
            for _ in range(5):
                buf = io.StringIO()
                copy.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None})
                svg = buf.getvalue()
                if base is None:
                    return svg.replace("<svg ", f'<svg {SVG_TEXT_ATTR}="none" ', 1)
                w, h = _svg_size(svg)
                shown = min(SLIDE_FIGURE_BOX[0], SLIDE_FIGURE_BOX[1] * w / h)
                smallest = smallest_text_px(copy) * 72.0 / float(copy.dpi)
                if smallest * shown / w >= SLIDE_TEXT_PX:
                    break
                # grow every text (tick labels drawn since the last round included) by what is missing
                grow = SLIDE_TEXT_PX / (smallest * shown / w) * 1.02
                factor *= grow
                for t in copy.findobj(Text):
                    t0, s0 = sizes.setdefault(id(t), (t, float(t.get_fontsize()) / (factor / grow)))
                    t.set_fontsize(s0 * factor)
                # axis labels keep their distance from the (larger) tick labels; a 3-D axis puts its label
                # labelpad + 21 points from the axis (mplot3d's fixed offset), so that sum grows
                # (and a 3-D axis, which does not thin its ticks as its labels grow, keeps at most 4 of them)
                for ax in copy.axes:
                    offset = 21.0 if hasattr(ax, "zaxis") else 0.0
                    for axis in (getattr(ax, name, None) for name in ("xaxis", "yaxis", "zaxis")):
                        if axis is not None:
                            axis.labelpad = (float(axis.labelpad) + offset) * grow - offset
                            if offset and isinstance(axis.get_major_locator(), AutoLocator):
                                axis.set_major_locator(MaxNLocator(nbins=4))
            overlaps = "; ".join(f"{a} / {b}" for a, b in text_overlaps(copy))
            attrs = f'{SVG_TEXT_ATTR}="{smallest:.3f}" {SVG_OVERLAP_ATTR}="{html.escape(overlaps, quote=True)}"'
            return svg.replace("<svg ", f"<svg {attrs} ", 1)
    finally:
        plt.close(copy)


#: attribute of a slide figure's ``<svg>`` root: the texts of the figure that overlap, as drawn for the slide
SVG_OVERLAP_ATTR = "data-text-overlaps"


def text_overlaps(fig: Any) -> list[tuple[str, str]]:
    """Pairs of a figure's drawn texts whose boxes overlap (each at least a third of the smaller's height
    and a tenth of its width: two lines that merely touch, or a subscript's reach, do not count). Only
    texts the figure draws count (a 3-D axis keeps tick labels it does not draw): the same rule as the
    animations' slide frames (:func:`jacobians.plotting.style.overlapping_texts`)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from jacobians.plotting.style import drawn_texts, overlapping_texts

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    with drawn_texts(fig) as boxes:
        canvas.draw()
    return overlapping_texts([b for b in boxes if fig.bbox.overlaps(b[2])])


def clean(A: ArrayLike, digits: int = 4) -> NDArray[np.float64]:
    """Round for printing; adding 0.0 turns -0.0 into 0.0, so no "-0." is printed.

    >>> clean([-1e-9, 0.123456])
    array([0.    , 0.1235])
    """
    return np.round(np.asarray(A, dtype=float), digits) + 0.0


def latex_matrix(A: ArrayLike, digits: int = 2) -> str:
    r"""A numeric matrix as a LaTeX ``bmatrix``, each entry rounded to ``digits`` decimals (no "-0.00").

    >>> latex_matrix([[1, -1e-9], [0.5, 2]], 1)
    '\\begin{bmatrix}1.0 & 0.0\\\\0.5 & 2.0\\end{bmatrix}'
    """
    M = np.atleast_2d(clean(A, digits))
    if M.ndim != 2:
        raise ValueError(f"Expected a vector or a matrix, got an array of shape {M.shape}")
    rows = (" & ".join(f"{x:.{digits}f}" for x in row) for row in M)
    return r"\begin{bmatrix}" + r"\\".join(rows) + r"\end{bmatrix}"


def show(latex: str) -> None:
    """Display a LaTeX formula as an output."""
    if not isinstance(latex, str):
        raise TypeError(f"Expected LaTeX as a str, got {type(latex).__name__}")
    display(Math(latex))


def trig_shorthand(expr: sp.Basic, thetas: Sequence[sp.Symbol]) -> sp.Basic:
    r"""Write the sine and cosine of a sum of joint angles as :math:`s_{12}`, :math:`c_{123}`, ... for display.

    Only sums of distinct joint symbols (with coefficient 1) are replaced; the
    index lists the joints in their order.

    >>> t1, t2 = sp.symbols("theta1 theta2")
    >>> trig_shorthand(sp.cos(t1 + t2) + sp.sin(t1), [t1, t2])
    c_{12} + s_{1}
    """
    order = list(thetas)
    if not all(isinstance(t, sp.Symbol) for t in order):
        raise TypeError(f"Expected a sequence of sympy symbols for thetas, got {thetas!r}")

    def index(arg: sp.Expr) -> str | None:
        terms = sp.Add.make_args(arg)
        if len(set(terms)) == len(terms) and all(t in order for t in terms):
            return "".join(str(order.index(t) + 1) for t in sorted(terms, key=order.index))
        return None

    def swap(e: sp.Expr) -> sp.Expr:
        k = index(e.args[0])
        return sp.Symbol(("s" if isinstance(e, sp.sin) else "c") + "_{" + k + "}") if k else e

    return sp.sympify(expr).replace(lambda e: isinstance(e, (sp.sin, sp.cos)), swap)


def _fd_twists(chain: jac.SerialChain, theta: ArrayLike, side: str) -> NDArray[np.float64]:
    th = np.asarray(theta, dtype=float)
    dT = jac.numerical_jacobian(lambda q: chain.fk(q), th)  # (4, 4, n)
    T_inv = lie.inverse_transform(chain.fk(th))
    cols = [dT[..., i] @ T_inv if side == "space" else T_inv @ dT[..., i] for i in range(chain.dof)]
    return np.stack([lie.matrix_to_twist(X) for X in cols], axis=1)


def fd_space_jacobian(chain: jac.SerialChain, theta: ArrayLike) -> NDArray[np.float64]:
    r"""Space Jacobian by finite differences of the forward kinematics, columns
    :math:`(\partial T/\partial\theta_i) T^{-1}`."""
    return _fd_twists(chain, theta, "space")


def fd_body_jacobian(chain: jac.SerialChain, theta: ArrayLike) -> NDArray[np.float64]:
    r"""Body Jacobian by finite differences of the forward kinematics, columns
    :math:`T^{-1}\partial T/\partial\theta_i`."""
    return _fd_twists(chain, theta, "body")


def fd_jacobian_tol(chain: jac.SerialChain, theta: ArrayLike, link: int | None = None) -> float:
    """Bound on each entry's error of :func:`fd_space_jacobian` and :func:`fd_body_jacobian`.

    ``jacobians.testing.fd_tol`` bounds each entry of ``dT/dθ_i`` (truncation
    and rounding of the central difference). A twist entry of
    ``dT/dθ_i T⁻¹`` (or ``T⁻¹ dT/dθ_i``) is a sum over a column (row) of T⁻¹,
    so its error is at most ``sum |T⁻¹|`` times that bound. With ``link=i``
    (0-based), T is the pose of link frame i (``chain.link_poses``) instead
    of the tool's.
    """
    th = np.asarray(theta, dtype=float)

    def pose(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return chain.fk(t) if link is None else chain.link_poses(t)[link]

    return fd_tol(pose, th) * float(np.abs(lie.inverse_transform(pose(th))).sum())


def d_dt(f: Callable[[float], ArrayLike], t0: float = 0.0) -> NDArray[np.float64]:
    """Central finite difference of ``f`` (a function of one number returning an array) at ``t0``."""
    return jac.numerical_jacobian(lambda t: np.asarray(f(t[0])), np.array([t0]))[..., 0]


def d_dt_tol(f: Callable[[float], ArrayLike], t0: float = 0.0) -> float:
    """Bound on each entry's error of :func:`d_dt` (``jacobians.testing.fd_tol`` of the same difference)."""
    return fd_tol(lambda t: np.asarray(f(t[0])), np.array([t0]))


def random_arm(n: int, rng: np.random.Generator) -> jac.SerialChain:
    """A random chain of n joints, about 70 % revolute and 30 % prismatic, with a random home pose."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"Expected a positive number of joints n, got {n!r}")
    cols, types = [], rng.choice(["R", "P"], size=n, p=[0.7, 0.3])
    for t in types:
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        cols.append(np.r_[u, -np.cross(u, rng.normal(size=3))] if t == "R" else np.r_[np.zeros(3), u])
    M = lie.make_transform(lie.exp_so3(rng.normal(size=3)), rng.normal(size=3))
    return jac.SerialChain(np.stack(cols, axis=1), M)


def legend_clear(ax: Axes, legend: Legend, polylines: Sequence[ArrayLike]) -> bool:
    """True if no point of any polyline (each (k, 2), data coordinates of ``ax``) lies under the legend box."""
    ax.figure.canvas.draw()
    box = legend.get_window_extent()
    for polyline in polylines:
        pts = np.asarray(polyline, dtype=float)
        dense = np.concatenate([a + np.linspace(0, 1, 25)[:, None] * (b - a)
                                for a, b in zip(pts[:-1], pts[1:], strict=True)] + [pts])
        xy = ax.transData.transform(dense)
        inside = (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)
        if np.any(inside):
            return False
    return True
