"""Numeric matrices as LaTeX (for the pages) and as a grid of text on an axes (for figures)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from numpy.typing import ArrayLike

from .._validation import as_float_array

__all__ = ["matrix_latex", "MatrixArtist", "draw_matrix"]


def _fmt(x: float, digits: int) -> str:
    if not np.isfinite(x):
        return r"\text{undef.}"
    if abs(x) < 0.5 * 10.0 ** (-digits):
        x = 0.0
    s = f"{x:.{digits}f}"
    if s.startswith("-"):
        s = "-" + s[1:]
    return s


def matrix_latex(J: ArrayLike, name: str | None = None, digits: int = 3, highlight_columns: Iterable[int] = (),
                 highlight_color: str = "orange") -> str:
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

    def __init__(self, ax: Axes, J: ArrayLike, *, digits: int = 2, row_labels: Sequence[str] | None = None,
                 col_labels: Sequence[str] | None = None, title: str | None = None, fontsize: float = 12) -> None:
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

    def update(self, J: ArrayLike, colors: Any = None) -> MatrixArtist:
        """Show the numbers of ``J`` (same shape); ``colors``: one per column, or one per entry."""
        A = np.atleast_2d(as_float_array(J, "J"))
        if A.shape != self.shape:
            raise ValueError(f"Expected J with shape {self.shape}, got shape {A.shape}")
        for i in range(self.shape[0]):
            for j in range(self.shape[1]):
                x = A[i, j]
                shown = 0.0 if abs(x) < 0.5 * 10 ** -self.digits else x
                self.texts[i][j].set_text("undef." if not np.isfinite(x) else f"{shown:.{self.digits}f}")
                if colors is not None:
                    self.texts[i][j].set_color(colors[j] if np.ndim(colors) == 1 else colors[i][j])
        self.values = A
        return self


def draw_matrix(ax: Axes, J: ArrayLike, *, digits: int = 2, row_labels: Sequence[str] | None = None,
                col_labels: Sequence[str] | None = None, title: str | None = None,
                fontsize: float = 12) -> MatrixArtist:
    """Draw a numeric matrix as text on ``ax`` (no image). Returns a :class:`MatrixArtist`.

    Rows of a Jacobian are usually labelled ``["ωx", "ωy", "ωz", "vx", "vy", "vz"]``.
    """
    return MatrixArtist(ax, J, digits=digits, row_labels=row_labels, col_labels=col_labels, title=title,
                        fontsize=fontsize)
