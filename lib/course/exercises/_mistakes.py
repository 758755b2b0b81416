"""Mistakes met in many exercises: a column with the wrong sign, (v, ω) for (ω, v), degrees for radians."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from jacobians.grading import Mistake

from ._kinematics import swap


def sign_mistakes(ref: ArrayLike, axis_word: str = "joint") -> list[Mistake]:
    """One mistake per column of a 6xn matrix: that column with the opposite sign."""
    ref = np.asarray(ref, float)
    out: list[Mistake] = []
    if ref.ndim != 2:
        return out
    for j in range(ref.shape[1]):
        W = ref.copy()
        W[:, j] *= -1
        out.append(Mistake(f"sign_column_{j + 1}", W,
                           f"Column {j + 1} has the opposite sign of the right one: check the direction of "
                           f"{axis_word} {j + 1}'s axis and the sign in v = -ω × q."))
    return out


def swap_mistake(ref: ArrayLike) -> Mistake:
    """Rows (v, omega) instead of (omega, v)."""
    return Mistake("v_omega_swapped", swap(ref),
                   "Your rows are in the order (v, ω): this course (Modern Robotics) puts the angular part "
                   "first, rows 1-3 ω and rows 4-6 v.")


def degrees_mistake(value: Any) -> Mistake:
    """``value`` is the answer computed with the angles in degrees fed to sin and cos."""
    return Mistake("degrees_for_radians", value,
                   "This is what comes out when the angles in degrees are fed to sin and cos as if they were "
                   "radians: convert degrees to radians first (multiply by π/180).")


def neighbour_columns(J: ArrayLike, i: int, name: str) -> list[Mistake]:
    """Columns i-1 and i+1 (1-based, those that exist) of ``J`` given for column i: the neighbouring column."""
    J = np.asarray(J, float)
    return [Mistake("neighbour_column", J[:, k - 1].copy(),
                    f"This is column {k} of the {name}, the neighbouring column (joint {k}); the exercise asks for "
                    f"column {i}, the one of joint {i}.")
            for k in (i - 1, i + 1) if 1 <= k <= J.shape[1]]
