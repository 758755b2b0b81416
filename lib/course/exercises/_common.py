"""Helpers shared by the exercise definitions: random variants, LaTeX, mistake catalogues.

The references are computed with plain numpy formulas here *and* checked
against the :mod:`jacobians` library in ``tests/test_exercises.py``, so a
wrong reference cannot hide behind the code that produced it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike, NDArray

from jacobians import lie, robots
from jacobians.chain import SerialChain
from jacobians.grading import Case, Mistake

Array = NDArray[np.float64]

DEG = np.pi / 180.0


# ----------------------------------------------------------------- formatting

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


# ----------------------------------------------------------------- random variants

def angles_deg(rng: Generator, n: int, step: int = 15, low: int = -150, high: int = 150,
               nonzero: bool = True) -> Array:
    """``n`` angles in degrees, multiples of ``step`` in [low, high] (0 excluded unless ``nonzero`` is False)."""
    choices = np.arange(low, high + 1, step)
    if nonzero:
        choices = choices[choices != 0]
    return rng.choice(choices, size=n).astype(float)


def lengths(rng: Generator, n: int, low: float = 0.5, high: float = 1.5) -> Array:
    """``n`` link lengths with one decimal."""
    return np.round(rng.uniform(low, high, size=n), 1)


def random_rotation(rng: Generator) -> Array:
    """A rotation about a random coordinate-ish axis by a multiple of 30 degrees (nice numbers)."""
    axes = [np.array(a, float) for a in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [0, 1, 1], [1, 0, 1])]
    R = np.eye(3)
    for _ in range(2):
        a = axes[rng.integers(len(axes))]
        a = a / np.linalg.norm(a)
        ang = float(rng.choice([30, 45, 60, 90, 120, -30, -60, -90])) * DEG
        R = R @ lie.exp_so3(a * ang)
    return R


def random_transform(rng: Generator, digits: int = 4) -> Array:
    """A transform with a nice rotation (rounded to ``digits``) and a position in halves."""
    T = np.eye(4)
    T[:3, :3] = np.round(random_rotation(rng), digits)
    T[:3, 3] = rng.integers(-3, 4, size=3) * 0.5
    if not np.any(T[:3, 3]):
        T[0, 3] = 1.0
    return T


def random_chain(rng: Generator, n: int | None = None, prismatic: bool = True) -> tuple[Array, Array, Array]:
    """A random spatial chain (S 6xn, M 4x4): unit axes through random points, maybe a prismatic joint."""
    n = int(rng.integers(2, 7)) if n is None else n
    cols = []
    for _ in range(n):
        w = rng.normal(size=3)
        w /= np.linalg.norm(w)
        if prismatic and rng.random() < 0.2:
            cols.append(np.concatenate([np.zeros(3), w]))
        else:
            q = rng.uniform(-1, 1, size=3)
            cols.append(np.concatenate([w, -np.cross(w, q)]))
    S = np.stack(cols, axis=1)
    M = np.eye(4)
    M[:3, :3] = random_rotation(rng)
    M[:3, 3] = rng.uniform(-1, 1, size=3)
    theta = rng.uniform(-np.pi, np.pi, size=n)
    return S, M, theta


# ----------------------------------------------------------------- kinematics in plain numpy

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


class PlanarPose(NamedTuple):
    """A random planar arm at a random pose: lengths, angles in degrees and radians, the chain."""

    lengths: Array
    theta_deg: Array
    theta: Array
    arm: SerialChain


def planar_pose(rng: Generator, n: int, step: int = 15, low: int = -150, high: int = 150) -> PlanarPose:
    """A planar nR arm (lengths drawn first, then angles, as :func:`lengths` and :func:`angles_deg` draw)."""
    ls = lengths(rng, n)
    th_deg = angles_deg(rng, n, step=step, low=low, high=high)
    return PlanarPose(ls, th_deg, th_deg * DEG, planar_chain(ls))


class SpatialPose(NamedTuple):
    """The spatial 5R arm at a random pose, as a statement shows it (4 digits): the pose, the body,
    geometric and space Jacobians."""

    T: Array
    J_b: Array
    J: Array
    J_s: Array


def spatial_5r_pose(rng: Generator, digits: int = 4) -> SpatialPose:
    """The spatial 5R arm with random dimensions at a random pose, numbers rounded to ``digits``."""
    vals = [float(v) for v in rng.choice([0.3, 0.5, 0.8, 1.0], size=5)]
    arm = robots.spatial_5r(*vals)
    th = angles_deg(rng, 5, step=30, low=-120, high=120) * DEG
    T = fk(arm.screw_axes, arm.home, th)
    T[:3, :] = np.round(T[:3, :], digits)
    J_b = np.round(body_jac(arm.body_axes, th), digits)
    R = T[:3, :3]
    return SpatialPose(T, J_b, blockdiag(R, R) @ J_b, adj(T) @ J_b)


# ----------------------------------------------------------------- test cases of function exercises

CaseBody = Callable[[Array, Array, Array], tuple[tuple[Any, ...], Any, list[Mistake]]]


def chain_case(body: CaseBody) -> Callable[[Generator], Case]:
    """A ``make_case`` for a function exercise on a random chain: ``body(S, M, theta)`` gives the
    arguments, the reference and the mistakes; the case is labelled by the chain's number of joints."""
    def make_case(rng: Generator) -> Case:
        S, M, th = random_chain(rng)
        args, ref, mistakes = body(S, M, th)
        return Case(args, ref, mistakes, f"a random {S.shape[1]}-joint chain")
    make_case.__doc__ = body.__doc__
    return make_case


# ----------------------------------------------------------------- mistake catalogues

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
