"""How the statements show numbers: LaTeX for numbers, vectors, matrices and angles."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def num(x: float, digits: int = 3) -> str:
    """A number for a statement: at most ``digits`` decimals, no trailing zeros, never ``-0``."""
    x = float(x)
    if abs(x) < 0.5 * 10 ** (-digits):
        x = 0.0
    s = f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def bmatrix(A: ArrayLike, digits: int = 3) -> str:
    """A vector or matrix as a LaTeX ``bmatrix``."""
    A = np.asarray(A, dtype=float)
    if A.ndim == 1:
        A = A[:, None]
    rows = [" & ".join(num(v, digits) for v in row) for row in A]
    return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"


def vec(v: ArrayLike, digits: int = 3) -> str:
    """A vector as ``(a, b, c)``."""
    return "(" + ", ".join(num(x, digits) for x in np.asarray(v, dtype=float).ravel()) + ")"


def degs(theta_deg: ArrayLike) -> str:
    """Angles in degrees as ``(30^\\circ, ...)``."""
    return "(" + ", ".join(f"{int(round(t))}^\\circ" for t in np.asarray(theta_deg).ravel()) + ")"
