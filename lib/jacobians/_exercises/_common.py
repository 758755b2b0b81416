"""Helpers shared by the exercise definitions: random variants, LaTeX, mistake catalogues.

The references are computed with plain numpy formulas here *and* checked
against the :mod:`jacobians` library in ``tests/test_exercises.py``, so a
wrong reference cannot hide behind the code that produced it.
"""

from __future__ import annotations

import numpy as np

from .. import lie
from ..chain import SerialChain
from ..grading import Mistake

DEG = np.pi / 180.0


# ----------------------------------------------------------------- formatting

def num(x, digits: int = 3) -> str:
    x = float(x)
    if abs(x) < 0.5 * 10 ** (-digits):
        x = 0.0
    s = f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def bmatrix(A, digits: int = 3) -> str:
    A = np.asarray(A, dtype=float)
    if A.ndim == 1:
        A = A[:, None]
    rows = [" & ".join(num(v, digits) for v in row) for row in A]
    return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"


def vec(v, digits: int = 3) -> str:
    return "(" + ", ".join(num(x, digits) for x in np.asarray(v, dtype=float).ravel()) + ")"


def degs(theta_deg) -> str:
    return "(" + ", ".join(f"{int(round(t))}^\\circ" for t in np.asarray(theta_deg).ravel()) + ")"


# ----------------------------------------------------------------- random variants

def angles_deg(rng, n, step=15, low=-150, high=150, nonzero=True):
    choices = np.arange(low, high + 1, step)
    if nonzero:
        choices = choices[choices != 0]
    return rng.choice(choices, size=n).astype(float)


def lengths(rng, n, low=0.5, high=1.5):
    return np.round(rng.uniform(low, high, size=n), 1)


def random_rotation(rng):
    """A rotation about a random coordinate-ish axis by a multiple of 30 degrees (nice numbers)."""
    axes = [np.array(a, float) for a in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [0, 1, 1], [1, 0, 1])]
    R = np.eye(3)
    for _ in range(2):
        a = axes[rng.integers(len(axes))]
        a = a / np.linalg.norm(a)
        ang = float(rng.choice([30, 45, 60, 90, 120, -30, -60, -90])) * DEG
        R = R @ lie.exp_so3(a * ang)
    return R


def random_transform(rng, digits=4):
    T = np.eye(4)
    T[:3, :3] = np.round(random_rotation(rng), digits)
    T[:3, 3] = rng.integers(-3, 4, size=3) * 0.5
    if not np.any(T[:3, 3]):
        T[0, 3] = 1.0
    return T


def random_chain(rng, n=None, prismatic=True):
    """A random spatial chain (S 6xn, M 4x4): unit axes through random points, maybe a prismatic joint."""
    n = int(rng.integers(2, 7)) if n is None else n
    cols = []
    for i in range(n):
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

def adj(T):
    T = np.asarray(T, float)
    R, p = T[:3, :3], T[:3, 3]
    A = np.zeros((6, 6))
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = lie.skew(p) @ R
    return A


def inv_T(T):
    T = np.asarray(T, float)
    R, p = T[:3, :3], T[:3, 3]
    out = np.eye(4)
    out[:3, :3] = R.T
    out[:3, 3] = -R.T @ p
    return out


def expS(S_col, th):
    return lie.exp_se3(np.asarray(S_col, float) * float(th))


def space_jac(S, theta, order="forward"):
    S = np.asarray(S, float)
    n = S.shape[1]
    J = np.zeros_like(S)
    T = np.eye(4)
    for i in range(n):
        J[:, i] = adj(T) @ S[:, i]
        E = expS(S[:, i], theta[i])
        T = T @ E if order == "forward" else E @ T
    return J


def body_jac(B, theta, sign=-1):
    B = np.asarray(B, float)
    n = B.shape[1]
    J = np.zeros_like(B)
    T = np.eye(4)
    for i in range(n - 1, -1, -1):
        J[:, i] = adj(T) @ B[:, i]
        T = T @ expS(B[:, i], sign * theta[i])
    return J


def fk(S, M, theta):
    T = np.eye(4)
    for i in range(np.asarray(S).shape[1]):
        T = T @ expS(S[:, i], theta[i])
    return T @ M


def swap(J):
    J = np.asarray(J, float)
    return np.concatenate([J[3:], J[:3]], axis=0)


def blockdiag(A, B):
    out = np.zeros((6, 6))
    out[:3, :3] = A
    out[3:, 3:] = B
    return out


def planar_chain(ls):
    from .. import robots
    return robots.planar([float(v) for v in ls])


def chain(S, M) -> SerialChain:
    return SerialChain(S, M)


# ----------------------------------------------------------------- mistake catalogues

def sign_mistakes(ref, axis_word="joint"):
    ref = np.asarray(ref, float)
    out = []
    if ref.ndim != 2:
        return out
    for j in range(ref.shape[1]):
        W = ref.copy()
        W[:, j] *= -1
        out.append(Mistake(f"sign_column_{j + 1}", W,
                           f"Column {j + 1} has the opposite sign of the right one: check the direction of "
                           f"{axis_word} {j + 1}'s axis and the sign in v = -\u03c9 \u00d7 q."))
    return out


def swap_mistake(ref, name="(\u03c9, v)"):
    return Mistake("v_omega_swapped", swap(ref),
                   "Your rows are in the order (v, \u03c9): this course (Modern Robotics) puts the angular part "
                   "first, rows 1-3 \u03c9 and rows 4-6 v.")


def degrees_mistake(value):
    return Mistake("degrees_for_radians", value,
                   "This is what comes out when the angles in degrees are fed to sin and cos as if they were "
                   "radians: convert degrees to radians first (multiply by \u03c0/180).")
