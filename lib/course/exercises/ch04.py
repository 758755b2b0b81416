"""Exercises of chapter 4: space and body Jacobians side by side."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

from jacobians import robots
from jacobians.chain import SerialChain
from jacobians.grading import Exercise, Mistake, numeric_exercise

from ._kinematics import DEG, Array, adj, blockdiag, body_jac, fk, inv_T, space_jac
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake, swap_mistake
from ._registry import register, register_code
from ._variants import chain_case, planar_pose


def _rrp_state(rng: Generator, digits: int = 4) -> tuple[SerialChain, Array, Array, Array, Array]:
    h, reach = float(rng.choice([0.5, 1.0])), float(rng.choice([1.0, 1.5]))
    arm = robots.spatial_rrp(h, reach)
    th = np.array([float(rng.choice([-60, -30, 30, 60, 120])) * DEG, float(rng.choice([-45, 30, 60])) * DEG,
                   float(rng.choice([0.2, 0.4, 0.6]))])
    J_s = np.round(space_jac(arm.screw_axes, th), digits)
    T = fk(arm.screw_axes, arm.home, th)
    T[:3, :] = np.round(T[:3, :], digits)
    J_b = np.round(adj(inv_T(T)) @ J_s, digits)
    return arm, th, J_s, J_b, T


def _rotonly(R: Array, J: Array) -> Array:
    return blockdiag(R, R) @ J


def _frame_change(given: str, J: Array, T: Array, ref: Array, mistakes: list[Mistake]) -> Exercise:
    """From J_s to J_b (``given="s"``) or back, at the pose T_sb; (v, omega) swapped is added to the mistakes."""
    target = "b" if given == "s" else "s"
    name = {"s": "space", "b": "body"}
    st = (f"At some configuration an arm has \n\n$$J_{given} = {bmatrix(J, 4)}$$\n\nand "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 4)}.$$\n\nGive its {name[target]} Jacobian $J_{target}$.")
    return numeric_exercise(f"From the {name[given]} to the {name[target]} Jacobian", st, {f"J_{given}": J, "T_sb": T},
                            ref, [*mistakes, swap_mistake(ref)], what=f"{name[target]} Jacobian")


@register("ch04_ex1")
def _ch04_ex1(rng: Generator) -> Exercise:
    arm, th, J_s, J_b, T = _rrp_state(rng)
    R = T[:3, :3]
    ref = adj(inv_T(T)) @ J_s
    mistakes = [
        Mistake("wrong_adjoint", adj(T) @ J_s,
                "You used Ad of T_sb. To go from {s} to {b} you need the transform 'b from s', T_bs = T_sb⁻¹."),
        Mistake("unchanged", J_s, "That is J_s itself: the body Jacobian is the same column twists expressed in {b}."),
        Mistake("rotation_only", _rotonly(R.T, J_s),
                "You only rotated the two halves. The change of reference point also adds a p × ω term to "
                "the linear part."),
    ]
    return _frame_change("s", J_s, T, ref, mistakes)


@register("ch04_ex2")
def _ch04_ex2(rng: Generator) -> Exercise:
    arm, th, J_s, J_b, T = _rrp_state(rng)
    R = T[:3, :3]
    ref = adj(T) @ J_b
    mistakes = [
        Mistake("wrong_adjoint", adj(inv_T(T)) @ J_b,
                "You used Ad of T_bs. To go from {b} to {s} you need the transform 's from b', T_sb."),
        Mistake("unchanged", J_b, "That is J_b itself: the space Jacobian is the same column twists expressed in {s}."),
        Mistake("geometric", _rotonly(R, J_b),
                "You rotated both halves only: that gives the geometric Jacobian (velocity of the tool point), "
                "not the space Jacobian (velocity of the body point at the origin of {s})."),
    ]
    return _frame_change("b", J_b, T, ref, mistakes)


def ref_space_to_body(J_s: ArrayLike, T_sb: ArrayLike) -> Array:
    """Reference: J_b = Ad_{T_bs} J_s."""
    return np.asarray(adj(inv_T(T_sb)) @ np.asarray(J_s, float), dtype=float)


@chain_case
def _s2b_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    J_s = space_jac(S, th)
    T = fk(S, M, th)
    ref = adj(inv_T(T)) @ J_s
    mistakes = [
        Mistake("wrong_adjoint", adj(T) @ J_s, "You used Ad of T_sb; J_b needs Ad of T_bs = T_sb⁻¹."),
        Mistake("unchanged", J_s, "Your function returns J_s unchanged."),
        Mistake("rotation_only", _rotonly(T[:3, :3].T, J_s),
                "Your function only rotates the two halves; the linear part also needs the p × ω term."),
        swap_mistake(ref),
    ]
    return (J_s, T), ref, mistakes


register_code(
    "ch04_ex3", "Code: space to body",
    "Write `my_space_to_body(J_s, T_sb)` returning $J_b$ ($6\\times n$) from $J_s$ ($6\\times n$) and "
    "$T_{sb}$ ($4\\times4$), numpy arrays. Do not call `jacobians.space_to_body`. "
    "Set `answer = my_space_to_body`.",
    reference=ref_space_to_body, make_case=_s2b_case, fn_name="my_space_to_body", what="body Jacobian")


@register("ch04_ex4")
def _ch04_ex4(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    dth = rng.integers(-3, 4, size=3).astype(float) / 2
    if not np.any(dth):
        dth[0] = 1.0
    J_b = body_jac(arm.body_axes, th)
    J_s = space_jac(arm.screw_axes, th)
    ref = J_b @ dth
    mistakes = [
        Mistake("space_twist", J_s @ dth, "This is the spatial twist V_s = J_s θ̇. The body twist uses the "
                "body Jacobian."),
        degrees_mistake(body_jac(arm.body_axes, th_deg) @ dth),
        swap_mistake(ref),
        Mistake("reversed_rates", J_b @ dth[::-1], "The joint rates seem to be taken in the reverse order: "
                "column i of J_b multiplies θ̇_i."),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$ and its joints move at "
          f"$\\dot\\theta = {vec(dth)}$ rad/s. Give the body twist $\\mathcal V_b$ of the tool frame (6-vector).")
    return numeric_exercise("The body twist from joint rates", st,
                            {"lengths": ls, "theta_deg": th_deg, "theta_dot": dth}, ref, mistakes, what="body twist")
