"""What the exercises' library checks share: a comparison that says what differs, the twist re-expressed by
conjugation (the definition of the adjoint, not its block formula), and the runs of a code exercise's reference
on the variant's own test cases.

Tolerances follow :mod:`jacobians.testing`: two computations of one well-conditioned quantity by exact algebra
agree to ``TOL`` relative to the size of the terms they sum (:func:`~jacobians.testing.close`); a finite
difference to :func:`~jacobians.testing.fd_tol`; a root to :func:`~jacobians.testing.root_tol`; a pose reached by
an iteration to :func:`~jacobians.testing.pose_tol`. Each check says which, and why, where it compares.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from jacobians import lie
from jacobians.grading import Exercise
from jacobians.testing import TOL

Array = NDArray[np.float64]

__all__ = ["assert_close", "assert_within", "conjugated", "conjugated_columns", "reference_runs", "size"]


def size(*arrays: ArrayLike) -> float:
    """The largest entry of the arrays in absolute value, at least 1: the scale of a sum of their products."""
    return max([1.0] + [float(np.max(np.abs(np.asarray(a, dtype=float)), initial=0.0)) for a in arrays])


def assert_within(actual: ArrayLike, expected: ArrayLike, bound: float, what: str) -> None:
    """Raise AssertionError, saying by how much, unless every entry of ``actual`` is within ``bound`` of
    ``expected`` (same shape)."""
    a = np.asarray(actual, dtype=float)
    b = np.asarray(expected, dtype=float)
    if a.shape != b.shape:
        raise AssertionError(f"{what}: shape {a.shape}, the library's {b.shape}")
    diff = float(np.max(np.abs(a - b), initial=0.0))
    if not diff <= bound:  # (a NaN fails too)
        raise AssertionError(f"{what}: off the library's value by {diff:.3g} (allowed {bound:.3g})")


def assert_close(actual: ArrayLike, expected: ArrayLike, what: str, scale: float = 1.0, ops: float = 1.0) -> None:
    """Two computations of one quantity by exact algebra: within ``TOL`` times ``ops`` times the size of their
    terms (``scale``, at least the entries compared; see :func:`jacobians.testing.close`). ``ops`` > 1 counts a
    condition number the comparison carries (a linear solve)."""
    assert_within(actual, expected, TOL * ops * size(actual, expected, scale), what)


def conjugated(T: ArrayLike, V: ArrayLike) -> Array:
    """The twist V seen through the transform T: (T [V] T⁻¹)^∨, products of 4x4 matrices (T inverted as a
    matrix), not the 6x6 adjoint's block formula."""
    T = np.asarray(T, dtype=float)
    return np.asarray(lie.matrix_to_twist(T @ lie.twist_to_matrix(V) @ np.linalg.inv(T)), dtype=float)


def conjugated_columns(T: ArrayLike, J: ArrayLike) -> Array:
    """Every column of J (twists) seen through T (:func:`conjugated`)."""
    J = np.asarray(J, dtype=float)
    return np.column_stack([conjugated(T, J[:, i]) for i in range(J.shape[1])])


def reference_runs(ex: Exercise) -> Iterator[tuple[tuple[Any, ...], Any]]:
    """A code exercise's reference function run on each of the variant's test cases (on a copy of the
    arguments): the arguments and what it returns."""
    for case in ex.cases():  # type: ignore[attr-defined]
        args = copy.deepcopy(case.args)
        yield case.args, ex.reference(*args)
