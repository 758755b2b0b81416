"""Exercises of chapter 11: redundancy and the null space (null vector, general solution, units)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator

import jacobians as jac
from jacobians.grading import Exercise, Mistake, numeric_exercise

from ._checks import assert_close, size
from ._hand import pinv_steps, planar_jv
from ._kinematics import DEG, Array
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake
from ._registry import register
from ._variants import angles_deg, lengths


def _pos_jac_planar(ls: Array, th: Array) -> Array:
    """The 2 x n position Jacobian of a planar nR arm (angles in radians): column i is z x (p - q_i)."""
    c = np.cumsum(th)
    x = -np.array([np.sum(ls[i:] * np.sin(c[i:])) for i in range(len(ls))])
    y = np.array([np.sum(ls[i:] * np.cos(c[i:])) for i in range(len(ls))])
    return np.stack([x, y])


def _regular_3r(rng: Generator) -> tuple[Array, Array, Array]:
    """A planar 3R arm away from its singular configurations: lengths, angles in degrees, position Jacobian."""
    while True:
        ls = lengths(rng, 3)
        th_deg = angles_deg(rng, 3, step=15, low=-150, high=150)
        Jv = _pos_jac_planar(ls, th_deg * DEG)
        if np.linalg.svd(Jv, compute_uv=False)[-1] > 0.2:
            return ls, th_deg, Jv


def _position_rows(ex: Exercise) -> Array:
    """The library's position Jacobian (x, y rows of the geometric Jacobian) of the variant's planar arm."""
    return np.asarray(jac.geometric_jacobian(jac.robots.planar(ex.given["lengths"]),
                                             np.radians(ex.given["theta_deg"]))[3:5], dtype=float)


def _library_ch11_ex1(ex: Exercise) -> None:
    """ν is fixed by three facts about the library's position Jacobian J (2x3), none of them the cross product:
    J ν = 0 (it moves no tip), |ν|² = det(J Jᵀ) (Lagrange's identity |r1 × r2|² = |r1|²|r2|² − (r1·r2)²), and
    det[r1; r2; ν] > 0 (right-handed). Sums of products of entries of size |J|: within TOL of |J|³, |J|⁴."""
    J, nu = _position_rows(ex), ex.solution()
    assert_close(J @ nu, np.zeros(2), "J ν", scale=3 * size(J) ** 3)
    assert_close(nu @ nu, np.linalg.det(J @ J.T), "|ν|² against det(J Jᵀ)", scale=9 * size(J) ** 4)
    assert np.linalg.det(np.vstack([J, nu])) > 0, "r1, r2, ν are not right-handed"


@register("ch11_ex1", library=_library_ch11_ex1)
def _ch11_ex1(rng: Generator) -> Exercise:
    ls, th_deg, Jv = _regular_3r(rng)
    ref = np.cross(Jv[0], Jv[1])
    Jd = _pos_jac_planar(ls, th_deg)
    mistakes = [
        Mistake("rows_swapped", -ref, "This is r₂ × r₁: the cross product changes sign when its factors swap. "
                "The exercise asks for ν = r₁ × r₂, first row (ẋ) times second row (ẏ)."),
        degrees_mistake(np.cross(Jd[0], Jd[1])),
        Mistake("columns_for_rows", np.cross(Jv[:, 0].tolist() + [0.0], Jv[:, 1].tolist() + [0.0]),
                "You crossed two columns of J (padded to 3-D); the null vector is the cross product of its two "
                "rows, each a 3-vector over the joints."),
    ]
    st = (f"A planar 3R arm with link lengths $L = {vec(ls, 1)}$ m is at $\\theta = {degs(th_deg)}$. Its task is "
          "the position of the tip, with the $2\\times3$ Jacobian $J$ whose rows $r_1, r_2$ give $\\dot x$ and "
          "$\\dot y$. Give the null vector $\\nu = r_1\\times r_2$ (a 3-vector of joint rates that does not "
          "move the tip).")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, J's entries; then r₁ × r₂."""
        J = planar_jv(r, ls, th_deg * DEG)
        return np.cross(J[0], J[1])

    return numeric_exercise("The null vector of a planar 3R arm", st, {"lengths": ls, "theta_deg": th_deg}, ref,
                            mistakes, what="null vector",
                            hint="J's columns are z × (p − q_i): row 1 holds −(y − y_i), row 2 holds x − x_i, with "
                                 "q_i joint i's position; check them, the angles in radians, then r₁ × r₂ entry by "
                                 "entry.", method=method)


def _library_ch11_ex2(ex: Exercise) -> None:
    """The rates are the solution of J θ̇ = ẋ nearest z: J θ̇ = ẋ, and θ̇ − z has no part in the library's null
    space of J (``analysis.nullspace``). The reference's pseudo-inverse carries cond(J) into the comparison."""
    J, xdot, z = ex.given["J"], ex.given["x_dot"], ex.given["z"]
    thd = ex.solution()
    kappa = float(np.linalg.cond(J))
    assert_close(J @ thd, xdot, "J θ̇", scale=3 * size(J) * size(thd, z), ops=kappa)
    N = jac.analysis.nullspace(J)
    assert_close(N.T @ (thd - z), np.zeros(N.shape[1]), "null-space part of θ̇ − z", scale=3 * size(thd, z),
                 ops=kappa)


@register("ch11_ex2", library=_library_ch11_ex2)
def _ch11_ex2(rng: Generator) -> Exercise:
    _, _, Jv = _regular_3r(rng)
    J = np.round(Jv, 3)
    xdot = rng.integers(-4, 5, size=2).astype(float) / 4
    if not np.any(xdot):
        xdot[1] = 0.5
    z = rng.integers(-2, 3, size=3).astype(float)
    z[int(rng.integers(3))] = float(rng.choice([-3.0, 3.0]))
    Jp = np.linalg.pinv(J)
    P = np.eye(3) - Jp @ J
    ref = Jp @ xdot + P @ z
    mistakes = [
        Mistake("no_projection", Jp @ xdot + z, "You added z itself: only its null-space part (I − J⁺J)z leaves "
                "the tip velocity unchanged. Project z before adding it."),
        Mistake("wrong_projector", Jp @ xdot + Jp @ J @ z, "You projected z with J⁺J, the projector onto the "
                "row space of J; the null-space projector is I − J⁺J."),
        Mistake("least_norm_only", Jp @ xdot, "This is the least-norm solution J⁺ẋ alone: the exercise adds the "
                "null-space part of z to it."),
        Mistake("transpose_for_pinv", J.T @ xdot + P @ z, "You used Jᵀ for the pseudo-inverse J⁺ = Jᵀ(JJᵀ)⁻¹: "
                "Jᵀẋ does not produce the tip velocity ẋ."),
    ]
    st = (f"A redundant arm has the task Jacobian $J = {bmatrix(J, 3)}$. The task must move at "
          f"$\\dot x = {vec(xdot, 2)}$, and a secondary objective asks for the joint rates $z = {vec(z, 0)}$. "
          "Give the joint rates $\\dot\\theta = J^\\dagger\\dot x + (I - J^\\dagger J)z$, which produce "
          "$\\dot x$ exactly and follow $z$ as far as the task allows.")
    def method(r: Callable[[Any], Any]) -> Any:
        """J Jᵀ, its inverse, J⁺, the projector I − J⁺J; then J⁺ẋ + Pz."""
        Jp = pinv_steps(r, J)
        P = np.asarray(r(np.eye(3) - Jp @ J))
        return Jp @ xdot + P @ z

    return numeric_exercise("The general solution", st, {"J": J, "x_dot": xdot, "z": z}, ref, mistakes,
                            what="joint rates",
                            hint="Compute J⁺ = Jᵀ(JJᵀ)⁻¹, then P = I − J⁺J, then J⁺ẋ + Pz; check that J times your "
                                 "answer gives ẋ.", method=method)


def _library_ch11_ex3(ex: Exercise) -> None:
    """The squared singular values are the eigenvalues of the Gram matrix (c J_v)ᵀ(c J_v), largest first (no SVD);
    compared as squares (a square root would amplify the rounding of a small one), within TOL of 3 c² |J_v|²."""
    Jv, c = ex.given["J"][3:], float(ex.given["factor"])
    s = np.asarray(ex.solution(), dtype=float)
    assert np.all(np.diff(s) <= 0) and s[-1] >= 0, s
    eig = np.linalg.eigvalsh((c * Jv).T @ (c * Jv))[::-1]
    assert_close(s ** 2, eig, "squared singular values", scale=3 * c ** 2 * size(Jv) ** 2)


@register("ch11_ex3", library=_library_ch11_ex3)
def _ch11_ex3(rng: Generator) -> Exercise:
    J = np.round(rng.normal(size=(6, 3)), 2)
    J[:3] = np.round(J[:3] / np.linalg.norm(J[:3], axis=0), 2)          # angular rows: unit axes, rad/s
    J[3:] = np.round(J[3:] * rng.uniform(0.04, 0.08), 3)                 # linear rows in m/s (a small arm)
    unit, c = [("centimetres", 100.0), ("inches (1 in = 0.0254 m)", 1 / 0.0254)][int(rng.integers(2))]
    ref = c * np.linalg.svd(J[3:], compute_uv=False)
    mistakes = [
        Mistake("metres", ref / c, f"These are the singular values in metres: in {unit} every length, and so "
                f"every entry of J_v, is {c:.4g} times larger."),
        Mistake("squared", ref * c, "You scaled by the square of the unit factor: J_v is linear in lengths, "
                "so its singular values scale by the factor itself."),
        Mistake("ascending", ref[::-1], "These are the right singular values in the wrong order, smallest first: "
                "the statement asks for them largest first."),
        Mistake("six_d", np.linalg.svd(np.diag([1, 1, 1, c, c, c]) @ J, compute_uv=False),
                "These are singular values of the whole 6×3 Jacobian, which mix rad/s and length/s; the exercise "
                "asks for the linear rows J_v alone."),
    ]
    st = (f"An arm has, in metres, the $6\\times3$ Jacobian with rows $(\\omega, v)$ "
          f"$J = {bmatrix(J, 3)}$. Lengths are now measured in {unit}. Give the singular values of the linear "
          "rows $J_v$ (the last three) in the new unit, largest first (a 3-vector).")
    def method(r: Callable[[Any], Any]) -> Any:
        """J_vᵀJ_v, its eigenvalues (largest first), their square roots times the unit factor."""
        Jv = J[3:]
        eig = np.asarray(r(np.linalg.eigvalsh(np.asarray(r(Jv.T @ Jv)))[::-1]))
        return c * np.sqrt(np.maximum(eig, 0.0))

    return numeric_exercise("Singular values in another unit", st, {"J": J, "unit": unit, "factor": c}, ref,
                            mistakes, what="singular values",
                            hint="Take the last three rows J_v, compute their singular values in metres, then "
                                 "multiply each by the number of new units in a metre.", method=method)


def _library_ch11_ex4(ex: Exercise) -> None:
    """The manipulability is also the product of the singular values of the library's position Jacobian
    (``analysis.singular_values``), not sqrt(det(J Jᵀ)): within TOL of |J|²."""
    J = _position_rows(ex)
    assert_close(ex.solution(), float(np.prod(jac.analysis.singular_values(J))), "manipulability",
                 scale=3 * size(J) ** 2)


@register("ch11_ex4", library=_library_ch11_ex4)
def _ch11_ex4(rng: Generator) -> Exercise:
    ls, th_deg, Jv = _regular_3r(rng)
    ref = float(np.sqrt(np.linalg.det(Jv @ Jv.T)))
    Jd = _pos_jac_planar(ls, th_deg)
    mistakes = [
        Mistake("no_sqrt", float(np.linalg.det(Jv @ Jv.T)), "You gave det(J Jᵀ); the manipulability is its "
                "square root."),
        degrees_mistake(float(np.sqrt(abs(np.linalg.det(Jd @ Jd.T))))),
        Mistake("two_joints_only", float(abs(np.linalg.det(Jv[:, :2]))), "You kept only the first two columns "
                "(|det| of a 2×2 block): with three joints, det(J Jᵀ) sums the squares of all three 2×2 minors."),
        Mistake("transpose_product", float(np.sqrt(abs(np.linalg.det(Jv.T @ Jv)))), "You used JᵀJ (3×3), which "
                "is singular for a 2×3 J; the manipulability of a task Jacobian uses J Jᵀ (2×2)."),
    ]
    st = (f"A planar 3R arm with link lengths $L = {vec(ls, 1)}$ m is at $\\theta = {degs(th_deg)}$, with the tip "
          "position as its task ($J$ is $2\\times3$). Give its manipulability $\\mu_3 = \\sqrt{\\det(JJ^T)}$, which is "
          "also the length of the null vector $r_1\\times r_2$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """J (from rounded cos, sin), its three 2×2 minors, the sum of their squares, its square root."""
        J = planar_jv(r, ls, th_deg * DEG)
        minors = r(np.array([J[0, a] * J[1, b] - J[0, b] * J[1, a] for a, b in ((0, 1), (0, 2), (1, 2))]))
        return np.sqrt(r(np.sum(minors ** 2)))

    return numeric_exercise("Manipulability of a redundant arm", st, {"lengths": ls, "theta_deg": th_deg}, ref,
                            mistakes, what="manipulability", method=method,
                            hint="Build the 2×3 position Jacobian (angles in radians), then det(J Jᵀ) = the sum "
                                 "of the squares of its three 2×2 minors, and take the square root.")
