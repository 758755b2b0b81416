"""Kinematics in plain numpy for the exercises' references and mistakes.

The references are computed with these plain formulas *and* checked against
the :mod:`jacobians` library by another route, in each exercise's library check
(``register(..., library=...)``), so a wrong reference cannot hide behind the
code that produced it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from jacobians import lie, robots
from jacobians.chain import SerialChain

Array = NDArray[np.float64]

DEG = np.pi / 180.0


def adj(T: ArrayLike) -> Array:
    """The 6x6 adjoint of a transform, twists (omega, v)."""
    T = np.asarray(T, float)
    R, p = T[:3, :3], T[:3, 3]
    A = np.zeros((6, 6))
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = lie.skew(p) @ R
    return A


def inv_T(T: ArrayLike) -> Array:
    """The inverse of a transform."""
    T = np.asarray(T, float)
    R, p = T[:3, :3], T[:3, 3]
    out = np.eye(4)
    out[:3, :3] = R.T
    out[:3, 3] = -R.T @ p
    return out


def expS(S_col: ArrayLike, th: float) -> Array:
    """exp([S] theta)."""
    return lie.exp_se3(np.asarray(S_col, float) * float(th))


def space_jac(S: ArrayLike, theta: ArrayLike, order: str = "forward") -> Array:
    """The space Jacobian; ``order="reverse"`` multiplies the exponentials the wrong way (a mistake)."""
    S = np.asarray(S, float)
    th = np.asarray(theta, float)
    n = S.shape[1]
    J = np.zeros_like(S)
    T = np.eye(4)
    for i in range(n):
        J[:, i] = adj(T) @ S[:, i]
        E = expS(S[:, i], th[i])
        T = T @ E if order == "forward" else E @ T
    return J


def body_jac(B: ArrayLike, theta: ArrayLike, sign: int = -1) -> Array:
    """The body Jacobian; ``sign=+1`` uses exponents of the wrong sign (a mistake)."""
    B = np.asarray(B, float)
    th = np.asarray(theta, float)
    n = B.shape[1]
    J = np.zeros_like(B)
    T = np.eye(4)
    for i in range(n - 1, -1, -1):
        J[:, i] = adj(T) @ B[:, i]
        T = T @ expS(B[:, i], sign * th[i])
    return J


def fk(S: ArrayLike, M: ArrayLike, theta: ArrayLike) -> Array:
    """Forward kinematics, product of exponentials in the space form."""
    S_, th = np.asarray(S, float), np.asarray(theta, float)
    T = np.eye(4)
    for i in range(S_.shape[1]):
        T = T @ expS(S_[:, i], th[i])
    return np.asarray(T @ np.asarray(M, float), dtype=float)


def swap(J: ArrayLike) -> Array:
    """Rows 4-6 above rows 1-3: (omega, v) <-> (v, omega)."""
    J = np.asarray(J, float)
    return np.concatenate([J[3:], J[:3]], axis=0)


def blockdiag(A: ArrayLike, B: ArrayLike) -> Array:
    """The 6x6 block-diagonal matrix of two 3x3 blocks."""
    out = np.zeros((6, 6))
    out[:3, :3] = A
    out[3:, 3:] = B
    return out


def planar_chain(ls: ArrayLike) -> SerialChain:
    """The planar arm with link lengths ``ls`` (joints about z, links along x at home)."""
    return robots.planar([float(v) for v in np.asarray(ls, dtype=float)])


def nearest_pose(T: ArrayLike) -> Array:
    """A printed pose with its rotation block replaced by the nearest rotation (polar factor of its SVD): the
    library wants an exact rotation, a statement prints 4 digits."""
    out = np.array(T, dtype=float)
    U, _, Vt = np.linalg.svd(out[:3, :3])
    out[:3, :3] = U @ Vt
    return out
