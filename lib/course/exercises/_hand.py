"""The intended methods of the exercises, as a student works them by hand: every number written down passes
through ``r`` (see :mod:`jacobians.grading.rounding`), so the checker can derive how far right hand-work with
rounded steps may land from the exact answer. Each method gives the reference when ``r`` keeps every digit.

>>> import numpy as np
>>> J = planar_jv(lambda x: x, np.array([1.0, 1.0]), np.array([0.0, np.pi / 2]))
>>> np.round(J, 12).tolist()
[[-1.0, -1.0], [1.0, 0.0]]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ._kinematics import Array

#: The ``r`` of a method: an intermediate in, the number written down out.
R = Callable[[Any], Any]


def planar_trig(r: R, th: Array) -> tuple[Array, Array]:
    """Cosines and sines of the cumulative angles θ1, θ1+θ2, ... (angles in radians), as written down."""
    c = np.cumsum(th)
    return np.asarray(r(np.cos(c))), np.asarray(r(np.sin(c)))


def planar_jv(r: R, ls: Array, th: Array, trig: tuple[Array, Array] | None = None) -> Array:
    """The 2 x n position Jacobian of a planar nR arm from rounded cosines and sines (``trig``, written down
    once for the whole exercise, or here); its entries written down.
    Column i is z × (p − q_i): (−(y − y_i), x − x_i), sums of L_k sin and L_k cos over the links k ≥ i."""
    C, S = planar_trig(r, th) if trig is None else trig
    n = len(ls)
    x = -np.array([np.sum(ls[i:] * S[i:]) for i in range(n)])
    y = np.array([np.sum(ls[i:] * C[i:]) for i in range(n)])
    return np.asarray(r(np.stack([x, y])))


def planar_tip(r: R, ls: Array, th: Array, trig: tuple[Array, Array] | None = None) -> Array:
    """The tool point (x, y) of a planar nR arm from rounded cosines and sines; written down."""
    C, S = planar_trig(r, th) if trig is None else trig
    return np.asarray(r(np.array([np.sum(ls * C), np.sum(ls * S)])))


def planar_points(r: R, ls: Array, trig: tuple[Array, Array]) -> Array:
    """The joint positions q_1 = 0, q_2, ..., q_n and the tip p (rows, (x, y)) from rounded cosines and sines;
    written down."""
    C, S = trig
    steps = np.stack([ls * C, ls * S], axis=1)
    return np.asarray(r(np.vstack([np.zeros(2), np.cumsum(steps, axis=0)])))


def planar_jv_dot(r: R, ls: Array, th_dot: Array, trig: tuple[Array, Array]) -> Array:
    """The time derivative of the 2 x n position Jacobian at the rates ``th_dot``: each L_k sin φ_k becomes
    L_k cos φ_k φ̇_k and each L_k cos φ_k becomes −L_k sin φ_k φ̇_k, with φ̇_k the sum of the rates up to k;
    written down."""
    C, S = trig
    rates = np.cumsum(th_dot)
    n = len(ls)
    x = -np.array([np.sum(ls[i:] * C[i:] * rates[i:]) for i in range(n)])
    y = -np.array([np.sum(ls[i:] * S[i:] * rates[i:]) for i in range(n)])
    return np.asarray(r(np.stack([x, y])))


def pinv_steps(r: R, J: Array) -> Array:
    """J⁺ = Jᵀ(J Jᵀ)⁻¹ of a wide J, as written down: J Jᵀ, its inverse, then the product."""
    A = np.asarray(r(J @ J.T))
    return np.asarray(r(J.T @ np.asarray(r(np.linalg.inv(A)))))


def skew3(p: Array) -> Array:
    """[p], the 3 x 3 skew matrix of p."""
    return np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])


def adjoint_steps(r: R, T: Array) -> Array:
    """[Ad_T] with its lower-left block [p]R written down (R and p are given)."""
    Rm, p = T[:3, :3], T[:3, 3]
    out = np.zeros((6, 6))
    out[:3, :3] = out[3:, 3:] = Rm
    out[3:, :3] = r(skew3(p) @ Rm)
    return out


def inverse_adjoint_steps(r: R, T: Array) -> Array:
    """[Ad_T⁻¹] with −Rᵀp and the block [−Rᵀp]Rᵀ written down."""
    Rm, p = T[:3, :3], T[:3, 3]
    q = np.asarray(r(-Rm.T @ p))
    out = np.zeros((6, 6))
    out[:3, :3] = out[3:, 3:] = Rm.T
    out[3:, :3] = r(skew3(q) @ Rm.T)
    return out


def ad_twist(V: Array) -> Array:
    """[ad_V] = [[ω], 0; [v], [ω]] of a twist (ω, v)."""
    out = np.zeros((6, 6))
    out[:3, :3] = out[3:, 3:] = skew3(V[:3])
    out[3:, :3] = skew3(V[3:])
    return out


def rotate_halves(r: R, Rm: Array, J: Array) -> Array:
    """diag(R, R) J: each half of the 6-row matrix (or vector) rotated, written down."""
    return np.concatenate([np.asarray(r(Rm @ J[:3])), np.asarray(r(Rm @ J[3:]))])


def euler_zyx_or_zyz(r: R, phi: Array, rep: str) -> Array:
    """B(φ) of the ZYX or ZYZ angles (ω_s = B φ̇) from rounded cosines and sines of φ1, φ2, its products
    written down."""
    ca, sa, cb, sb = (float(r(f(x))) for x, f in ((phi[0], np.cos), (phi[0], np.sin), (phi[1], np.cos),
                                                    (phi[1], np.sin)))
    if rep == "zyx":
        return np.array([[0.0, -sa, float(r(ca * cb))], [0.0, ca, float(r(sa * cb))], [1.0, 0.0, -sb]])
    return np.array([[0.0, -sa, float(r(ca * sb))], [0.0, ca, float(r(sa * sb))], [1.0, 0.0, cb]])


def log_se3_steps(r: R, T: Array) -> Array:
    """The twist V = log(T)^∨ = (ω̂θ, G⁻¹(θ)p θ) of a pose turning by 0 < θ < π, as written down: θ from the
    trace, sin θ, the unit axis ω̂ from R − Rᵀ, the coefficient 1 − (θ/2)cot(θ/2), then
    v = (I − (θ/2)[ω̂] + (1 − (θ/2)cot(θ/2))[ω̂]²) p."""
    Rm, p = T[:3, :3], T[:3, 3]
    th = float(r(np.arccos(np.clip((np.trace(Rm) - 1.0) / 2.0, -1.0, 1.0))))
    s = float(r(np.sin(th)))
    w = np.asarray(r(np.array([Rm[2, 1] - Rm[1, 2], Rm[0, 2] - Rm[2, 0], Rm[1, 0] - Rm[0, 1]]) / (2.0 * s)))
    k = float(r(1.0 - th / 2.0 / np.tan(th / 2.0)))
    W = skew3(w)
    v = np.asarray(r(p - th / 2.0 * (W @ p) + k * (W @ (W @ p))))
    return np.concatenate([np.asarray(r(w * th)), v])
