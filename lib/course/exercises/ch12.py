"""Exercises of chapter 12: the derivative of the Jacobian, tool acceleration and gravity torques."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator

from jacobians import body_jacobian, lie, robots, space_jacobian
from jacobians.acceleration import acceleration, jacobian_derivative
from jacobians.chain import SerialChain
from jacobians.dynamics import gravity_torques, potential_energy
from jacobians.grading import Exercise, Mistake, numeric_exercise
from jacobians.jacobian import numerical_jacobian
from jacobians.testing import fd2_tol, fd_tol

from ._checks import assert_within, size
from ._hand import ad_twist, planar_jv, planar_jv_dot, planar_trig
from ._kinematics import DEG, Array
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake
from ._registry import register
from ._variants import angles_deg, lengths, spatial_5r_pose


def _rates(rng: Generator, n: int) -> Array:
    """Joint rates (rad/s) in steps of 0.5, not all zero."""
    out = rng.integers(-4, 5, size=n).astype(float) / 2
    if not np.any(out):
        out[0] = 1.0
    return out


def _library_ch12_ex1(ex: Exercise) -> None:
    """p̈ is the second derivative of the library's forward kinematics along θ(t) = θ + θ̇ t + θ̈ t²/2, by a
    central second difference at t = 0 (not J θ̈ + J̇ θ̇), within fd2_tol (positions of size Σ L)."""
    g = ex.given
    arm = robots.planar_2r(*g["lengths"])
    th, thd, thdd = np.radians(g["theta_deg"]), g["theta_dot"], g["theta_ddot"]

    def tip(t: float) -> Array:
        return np.asarray(arm.fk(th + thd * t + thdd * t * t / 2)[:2, 3], dtype=float)

    h = 1e-4
    p_ddot = (tip(h) - 2 * tip(0.0) + tip(-h)) / h ** 2
    assert_within(ex.solution(), p_ddot, fd2_tol(tip, 0.0, h=h, scale=float(np.sum(g["lengths"]))),
                  "tool acceleration")


@register("ch12_ex1", library=_library_ch12_ex1)
def _ch12_ex1(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-150, high=150)
    thd, thdd = _rates(rng, 2), _rates(rng, 2)
    arm = robots.planar_2r(*ls)
    th = th_deg * DEG
    ref = acceleration(arm, th, thd, thdd)[3:5]
    J_v = np.array([[-ls[0] * np.sin(th[0]) - ls[1] * np.sin(th.sum()), -ls[1] * np.sin(th.sum())],
                    [ls[0] * np.cos(th[0]) + ls[1] * np.cos(th.sum()), ls[1] * np.cos(th.sum())]])
    Jd_v = jacobian_derivative(arm, th, thd, "geometric")[3:5]
    mistakes = [
        Mistake("no_jdot_term", J_v @ thdd,
                "You kept only J θ̈. The Jacobian changes as the arm moves, and J̇ θ̇ (the centripetal and "
                "Coriolis terms, present even at constant joint rates) must be added."),
        Mistake("only_jdot_term", Jd_v @ thd,
                "You kept only J̇ θ̇: the joint accelerations contribute J θ̈ as well."),
        Mistake("twist_derivative", acceleration(arm, th, thd, thdd, "space")[3:5],
                "This is the linear part of the derivative of the space twist, v̇_s, not the acceleration of the "
                "tool point: p̈ = v̇_s + ω̇ × p + ω × ṗ. Use the position rows of the geometric Jacobian."),
        degrees_mistake(acceleration(arm, th_deg, thd, thdd)[3:5]),
    ]
    st = (f"A planar 2R arm has link lengths $L = {vec(ls, 2)}$ m and is at $\\theta = {degs(th_deg)}$, moving "
          f"with $\\dot\\theta = {vec(thd, 1)}$ rad/s and $\\ddot\\theta = {vec(thdd, 1)}$ rad/s². Give the "
          "acceleration $\\ddot p = (\\ddot x, \\ddot y)$ of its tool point, in m/s².")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, J_v and J̇_v; then J_v θ̈ + J̇_v θ̇."""
        trig = planar_trig(r, th)
        return planar_jv(r, ls, th, trig) @ thdd + planar_jv_dot(r, ls, thd, trig) @ thd

    return numeric_exercise("Tool acceleration of the 2R arm", st,
                            {"lengths": ls, "theta_deg": th_deg, "theta_dot": thd, "theta_ddot": thdd}, ref,
                            mistakes, what="tool acceleration",
                            hint="Differentiate ṗ = J_v θ̇ with the product rule: p̈ = J_v θ̈ + J̇_v θ̇.", method=method)


def _rate_of_columns(axes: Array, thd: Array, frame: str) -> tuple[Array, float]:
    """d/dt of the Jacobian columns ``axes`` as the joints move at ``thd``, by central differences of the library's
    Jacobian, and fd_tol of that. The forward kinematics restarts at the current pose: with θ = θ_c + θ',
    T(θ) = e^[J_s1(θ_c)]θ'1 ··· e^[J_sn(θ_c)]θ'n T(θ_c) = T(θ_c) e^[J_b1(θ_c)]θ'1 ··· e^[J_bn(θ_c)]θ'n, so the
    chain whose axes at home (M = I, where body and space axes agree) are the current columns has these Jacobians
    at θ' = 0, and moves like the arm."""
    chain = SerialChain(axes, np.eye(4))
    jacobian = space_jacobian if frame == "space" else body_jacobian

    def columns(t: Array) -> Array:
        return np.asarray(jacobian(chain, t[0] * thd), dtype=float)

    return numerical_jacobian(columns, np.zeros(1))[..., 0], fd_tol(columns, np.zeros(1), scale=size(axes))


def _library_ch12_ex2(ex: Exercise) -> None:
    """J̇_s by central differences of the library's space Jacobian along the motion (:func:`_rate_of_columns`), not
    the bracket formula; within fd_tol."""
    rate, bound = _rate_of_columns(ex.given["J_s"], ex.given["theta_dot"], "space")
    assert_within(ex.solution(), rate, bound, "J̇_s")


@register("ch12_ex2", library=_library_ch12_ex2)
def _ch12_ex2(rng: Generator) -> Exercise:
    pose = spatial_5r_pose(rng)
    J_s = np.round(pose.J_s[:, :3], 6)
    thd = _rates(rng, 3)
    n = 3

    def columns(order: str) -> Array:
        out = np.zeros((6, n))
        for i in range(n):
            for j in range(n):
                if (order == "before" and j < i) or (order == "after" and j > i):
                    out[:, i] += lie.ad(J_s[:, j]) @ J_s[:, i] * thd[j]
        return out

    ref = columns("before")
    mistakes = [
        Mistake("bracket_order", -ref,
                "Every column has the wrong sign: the bracket is [ad of the earlier joints' twist] applied to "
                "column i, not [ad of column i] applied to them (the bracket is antisymmetric)."),
        Mistake("joints_after", columns("after"),
                "You summed over the joints after i. Column i of J_s is carried by the joints before it "
                "(T_{i-1} = e^{[S_1]θ_1}···e^{[S_{i-1}]θ_{i-1}}): only they change it."),
        Mistake("body_formula", -columns("after"),
                "This is the body Jacobian's formula (joints after i, minus sign). For the space Jacobian the "
                "sum runs over the joints before i, with a plus sign."),
    ]
    st = (f"The first three joints of a spatial arm have, at the current pose, the space Jacobian "
          f"\n\n$$J_s = {bmatrix(J_s, 6)}$$\n\nand move at $\\dot\\theta = {vec(thd, 1)}$ rad/s. "
          "Give $\\dot J_s$ (a $6\\times3$ matrix), the rate of change of these three columns.")
    def method(r: Callable[[Any], Any]) -> Any:
        """the twist of the joints before i, then its bracket with column i."""
        out = np.zeros((6, n))
        for i in range(n):
            V = np.asarray(r(sum((J_s[:, j] * thd[j] for j in range(i)), np.zeros(6))))
            out[:, i] = ad_twist(V) @ J_s[:, i]
        return out

    return numeric_exercise("The derivative of a space Jacobian", st, {"J_s": J_s, "theta_dot": thd}, ref,
                            mistakes, what="matrix J̇_s",
                            hint="Column i changes by the bracket of the twist of the joints before it: "
                                 "J̇_si = [ad of Σ_{j<i} J_sj θ̇_j] J_si; the first column is constant.", method=method)


def _library_ch12_ex3(ex: Exercise) -> None:
    """The holding torques are the gradient of the library's potential energy, ∂P/∂θ, by central differences
    (not Σ J_vᵀ m g), within fd_tol; P sums terms of size g Σm ΣL."""
    g = ex.given
    arm = robots.planar_2r(*g["lengths"])
    th = np.radians(g["theta_deg"])

    def energy(t: Array) -> Array:
        return np.asarray(potential_energy(arm, t, g["masses"], [0.0, -9.81, 0.0]), dtype=float)

    scale = 9.81 * float(np.sum(g["masses"])) * float(np.sum(g["lengths"]))
    assert_within(ex.solution(), numerical_jacobian(energy, th), fd_tol(energy, th, scale=scale), "torques")


@register("ch12_ex3", library=_library_ch12_ex3)
def _ch12_ex3(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-150, high=150)
    while abs(np.cos(th_deg.sum() * DEG)) < 0.2:
        th_deg = angles_deg(rng, 2, step=15, low=-150, high=150)
    m = np.round(rng.uniform(0.5, 4.0, size=2), 1)
    g = 9.81
    arm = robots.planar_2r(*ls)
    th = th_deg * DEG
    ref = gravity_torques(arm, th, m, [0.0, -g, 0.0])
    ends_ref = gravity_torques(arm, th, m, [0.0, -g, 0.0], centres=np.array([[ls[0] / 2, 0, 0], [ls[1] / 2, 0, 0]]))
    c1 = np.cos(th[0])
    mistakes = [
        Mistake("gravity_force", -ref,
                "The sign is flipped: this is gravity's own generalised force. The torques that hold the arm "
                "are τ_g = ∂P/∂θ = −Σ J_{v,c_i}ᵀ m_i g, with g = (0, −9.81)."),
        Mistake("centres_at_link_ends", ends_ref,
                "You put each mass at the end of its link. The centres of mass are at the middle of the links."),
        Mistake("link2_mass_missing_at_joint1", np.array([g * m[0] * ls[0] / 2 * c1, ref[1]]),
                "Joint 1 must hold link 2 as well: its torque has m_2 times the lever arm of link 2's centre, "
                "L_1 c_1 + L_2 c_12 / 2."),
        degrees_mistake(gravity_torques(arm, th_deg, m, [0.0, -g, 0.0])),
    ]
    st = (f"A planar 2R arm moves in a vertical plane, gravity $9.81$ m/s² along $-y$. Its links have lengths "
          f"$L = {vec(ls, 2)}$ m and masses $m = {vec(m, 1)}$ kg, each with its centre of mass at the middle of "
          f"the link. At $\\theta = {degs(th_deg)}$, give the joint torques $\\tau_g$ (N·m) that the motors must "
          "supply to hold the arm still.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos θ1 and cos(θ1 + θ2), the lever arms of the two centres about the joints, then g m times them."""
        C, _ = planar_trig(r, th)
        arms = r(np.array([ls[0] / 2 * C[0], ls[0] * C[0] + ls[1] / 2 * C[1], ls[1] / 2 * C[1]]))
        return g * np.array([m[0] * arms[0] + m[1] * arms[1], m[1] * arms[2]])

    return numeric_exercise("Gravity torques of the 2R arm", st,
                            {"lengths": ls, "masses": m, "theta_deg": th_deg}, ref, mistakes,
                            what="torque vector", method=method,
                            hint="τ_g = −Σ_i J_{v,c_i}ᵀ m_i g, with J_{v,c_i} the position Jacobian of link i's centre "
                                 "of mass (zero column after joint i).")


def _library_ch12_ex4(ex: Exercise) -> None:
    """The rate of the last three body-Jacobian columns by central differences of the library's body Jacobian of
    the chain restarted at the current pose (:func:`_rate_of_columns`; joints 1 and 2 are still, and columns 3-5
    depend only on the joints after them), not the bracket formula; within fd_tol."""
    rate, bound = _rate_of_columns(ex.given["J_b"], ex.given["theta_dot"], "body")
    assert_within(ex.solution(), rate, bound, "J̇_b")


@register("ch12_ex4", library=_library_ch12_ex4)
def _ch12_ex4(rng: Generator) -> Exercise:
    pose = spatial_5r_pose(rng)
    J_b = np.round(pose.J_b[:, 2:], 6)
    thd = _rates(rng, 3)
    n = 3

    def columns(order: str, sign: float) -> Array:
        out = np.zeros((6, n))
        for i in range(n):
            partial = sum((J_b[:, j] * thd[j] for j in range(n) if (j > i if order == "after" else j < i)),
                          np.zeros(6))
            out[:, i] = sign * lie.ad(partial) @ J_b[:, i]
        return out

    ref = columns("after", -1.0)
    mistakes = [
        Mistake("plus_sign", -ref,
                "Every column has the wrong sign. Column i of J_b is carried back by the inverse of the joints "
                "after it, so it turns against their body twist: J̇_bi = −[ad of Σ_{j>i} J_bj θ̇_j] J_bi."),
        Mistake("space_formula", columns("before", 1.0),
                "This is the space Jacobian's formula (joints before i, plus sign). Column i of J_b depends only "
                "on the joints after i; the joints before it move the whole arm, not the view from the tool."),
        Mistake("joints_before_minus", columns("before", -1.0),
                "You summed over the joints before i. In the body Jacobian only the joints after i change "
                "column i; the last column is constant."),
    ]
    st = (f"The last three joints of a spatial arm have, at the current pose, the body Jacobian columns "
          f"\n\n$$\\begin{{bmatrix}}J_{{b3}} & J_{{b4}} & J_{{b5}}\\end{{bmatrix}} = {bmatrix(J_b, 6)}$$\n\n"
          f"and move at $(\\dot\\theta_3, \\dot\\theta_4, \\dot\\theta_5) = {vec(thd, 1)}$ rad/s (joints 1 and 2 "
          "are still). Give the rate of change of these three columns (a $6\\times3$ matrix).")
    def method(r: Callable[[Any], Any]) -> Any:
        """the twist of the joints after i, then minus its bracket with column i."""
        out = np.zeros((6, n))
        for i in range(n):
            V = np.asarray(r(sum((J_b[:, j] * thd[j] for j in range(i + 1, n)), np.zeros(6))))
            out[:, i] = -ad_twist(V) @ J_b[:, i]
        return out

    return numeric_exercise("The derivative of a body Jacobian", st, {"J_b": J_b, "theta_dot": thd}, ref,
                            mistakes, what="matrix J̇_b",
                            hint="Column i changes by minus the bracket of the twist of the joints after it: "
                                 "J̇_bi = −[ad of Σ_{j>i} J_bj θ̇_j] J_bi; the last column is constant.", method=method)
