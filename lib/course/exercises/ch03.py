"""Exercises of chapter 3: the body Jacobian."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator

import jacobians as jac
from jacobians import robots
from jacobians.grading import Exercise, Mistake, numeric_exercise, symbolic_exercise

from ._checks import assert_close, reference_runs, size
from ._hand import inverse_adjoint_steps, planar_points, planar_trig
from ._kinematics import DEG, Array, adj, body_jac, inv_T, space_jac
from ._latex import bmatrix, degs, num, vec
from ._mistakes import degrees_mistake, neighbour_columns, sign_mistakes, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._symbolic_2r import SYM_NOTE, describe_arm, draw_arm, draw_shape, numeric_arm, sym_arm, sym_catalogue, sym_names
from ._variants import LAYOUT_TEXT, example_text, layout_cases, planar_column, planar_example


def _library_ch03_ex1(ex: Exercise) -> None:
    """The column is that column of the library's body Jacobian of the same arm."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    np.testing.assert_allclose(ex.solution(), jac.body_jacobian(arm, th)[:, ex.given["column"] - 1], atol=1e-12)


@register("ch03_ex1", library=_library_ch03_ex1)
def _ch03_ex1(rng: Generator) -> Exercise:
    ls, th_deg, i, B, J_b, J_s, J_b_deg = planar_column(rng, "body", 1, 3)  # joint 1 or 2
    ref = J_b[:, i - 1]
    mistakes = [
        Mistake("home_axis", B[:, i - 1],
                f"This is the body screw axis B_{i} at the home pose. Joints {i + 1}..3 move the tool frame relative "
                f"to joint {i}: carry B_{i} with the adjoint of e^-[B3]θ3 ⋯ e^-[B{i + 1}]θ{i + 1}."),
        Mistake("space_column", J_s[:, i - 1],
                f"This is column {i} of the space Jacobian. The body Jacobian expresses the joint's screw in the "
                "tool frame {b}."),
        degrees_mistake(J_b_deg[:, i - 1]),
        swap_mistake(ref),
        Mistake("v_sign", np.concatenate([ref[:3], -ref[3:]]),
                "The linear part has the wrong sign: in {b} it is -ω_b × r with r the position of the joint "
                "axis seen from the tool."),
        *neighbour_columns(J_b, i, "body Jacobian"),
    ]
    st = (f"A planar 3R arm has link lengths $L = {vec(ls, 1)}$ (tool at the end of link 3) and is at "
          f"$\\theta = {degs(th_deg)}$. Give column {i} of its body Jacobian, $J_{{b{i}}}(\\theta)$, as a 6-vector.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, the joint positions, joint i seen from the tool in {s}, then in {b}; (z, −z × r_b)."""
        trig = planar_trig(r, th_deg * DEG)
        Q = planar_points(r, ls, trig)
        d = np.asarray(r(Q[i - 1] - Q[-1]))  # joint i seen from the tool, in {s}
        C, S = trig
        rb = np.asarray(r(np.array([C[-1] * d[0] + S[-1] * d[1], -S[-1] * d[0] + C[-1] * d[1]])))  # in {b}
        return np.array([0.0, 0.0, 1.0, rb[1], -rb[0], 0.0])

    return numeric_exercise("One column of the body Jacobian", st, {"lengths": ls, "theta_deg": th_deg, "column": i},
                            ref, mistakes, what="column", method=method)


def _library_ch03_ex2(ex: Exercise) -> None:
    """The body axes are the library chain's."""
    np.testing.assert_allclose(ex.solution(), jac.SerialChain(ex.given["S"], ex.given["M"]).body_axes, atol=1e-12)


@register("ch03_ex2", library=_library_ch03_ex2)
def _ch03_ex2(rng: Generator) -> Exercise:
    vals = [float(v) for v in rng.choice([0.3, 0.5, 0.8, 1.0, 1.2], size=5)]
    arm = robots.spatial_5r(*vals)
    S, M = arm.screw_axes, arm.home
    ref = adj(inv_T(M)) @ S
    mistakes = [
        Mistake("wrong_adjoint", adj(M) @ S,
                "You used Ad of M instead of Ad of M⁻¹: check which way the adjoint carries the axes "
                "(from {s} to {b} needs T_bs = M⁻¹ at home)."),
        Mistake("unchanged", S, "These are the space screw axes: the body axes are the same axes expressed in the "
                "tool frame at home."),
        swap_mistake(ref),
    ] + sign_mistakes(ref)
    st = (f"The spatial 5R arm has $h = {num(vals[0])}$, $l_1 = {num(vals[1])}$, $l_2 = {num(vals[2])}$, "
          f"$l_3 = {num(vals[3])}$, $l_4 = {num(vals[4])}$; its space screw axes and home pose are "
          f"\n\n$$S = {bmatrix(S)},$$\n\n\n\n$$M = {bmatrix(M)}.$$\n\n"
          "Give its body screw axes $B$ ($6\\times5$, one column per joint).")
    def method(r: Callable[[Any], Any]) -> Any:
        """−Rᵀp and [−Rᵀp]Rᵀ of M⁻¹, then [Ad_M⁻¹] S."""
        return inverse_adjoint_steps(r, M) @ S

    return numeric_exercise("Body screw axes from space screw axes", st, {"S": S, "M": M}, ref, mistakes,
                            what="matrix of body screw axes", method=method)


def _library_ch03_ex3(ex: Exercise) -> None:
    """At a point, the reference is the library's body Jacobian of the numeric arm (S, M at those lengths)."""
    ref, chain, th = numeric_arm(ex.reference, ex.given["S"], ex.given["M"], ex.given["symbols"])
    np.testing.assert_allclose(ref, jac.body_jacobian(chain, th), atol=1e-12)


@register("ch03_ex3", library=_library_ch03_ex3)
def _ch03_ex3(rng: Generator) -> Exercise:
    arm, shape = draw_arm(rng), draw_shape(rng)
    syms, S, M, J_s, J_b, B, T = sym_arm(arm, shape)
    mistakes = sym_catalogue(
        J_b, J_s, "space_for_body",
        "This is the space Jacobian. The body Jacobian expresses each column in the tool frame {b}.",
        B, "Joint 1's axis, seen from the tool, moves when joint 2 moves: carry B1 with the adjoint of "
        "e^-[B2]θ2.")
    st = (describe_arm(arm, shape) + " Give the body Jacobian $J_b(\\theta_1, \\theta_2)$ as a $6\\times2$ symbolic "
          "matrix in $\\theta_1, \\theta_2, l_1, l_2$. " + SYM_NOTE)
    ex = symbolic_exercise("Symbolic body Jacobian of a planar two-joint arm", st, sym_names(syms), J_b, mistakes,
                           what="body Jacobian")
    ex.hint = ("Column 2 is B2; column 1 is Ad(e^-[B2]θ2) B1, with B = Ad(M⁻¹) S. Check which column, and within "
               "it the angular rows 1-3 or the linear rows 4-6.")
    ex.given.update({"joints": arm, "shape": shape, "S": S, "M": M})
    return ex


def _body_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    B = adj(inv_T(M)) @ S
    ref = body_jac(B, th)
    mistakes = [
        Mistake("home_axes", B, "Your function returns the body screw axes at home: each column must be carried "
                "by the joints after it."),
        Mistake("exponent_sign", body_jac(B, th, sign=+1),
                "The exponentials have the wrong sign: the body column i uses e^-[Bn]θn ⋯ e^-[B(i+1)]θ(i+1) "
                "(negative exponents)."),
        Mistake("space_formula", space_jac(B, th),
                "You applied the space-Jacobian recursion (joints before i) to the body axes: in the body "
                "Jacobian column i is moved by the joints after i."),
        swap_mistake(ref),
    ]
    return (B, th), ref, mistakes


def _body_example(layout: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm at a pose of the seed, with the Jacobian the function must return: varies the statement
    (lengths and angles), so that two IDs rarely share one."""
    def example(rng: Generator) -> tuple[str, dict[str, Any]]:
        _, th, B, _ = planar_example(rng)
        given = B if layout == "columns" else B.T
        text = example_text("my_body_jacobian(B, theta)", {"B": given, "theta": th}, body_jac(B, th))
        return text, {"example_B": given, "example_theta": th}
    return example


def _library_ch03_ex4(ex: Exercise) -> None:
    """On every test case, J_b is the library's space Jacobian carried to {b}: [Ad_T_bs] J_s(θ) of the chain
    whose space axes are the given body axes at home M = I (then B = S), a route through the joints before each
    column instead of after it; within TOL of the size of the terms, as in ch02_ex4."""
    for (axes, th), out in reference_runs(ex):
        B = np.asarray(axes, dtype=float).T if ex.given["layout"] == "rows" else np.asarray(axes, dtype=float)
        chain = jac.SerialChain(B, np.eye(4))
        T, J_s = chain.fk(th), jac.space_jacobian(chain, th)
        assert_close(out, jac.space_to_body(J_s, T), "body Jacobian", scale=size(J_s) * size(T))


register_code("ch03_ex4", "Code: the body Jacobian", [
    CodeVariant(f"Write `my_body_jacobian(B, theta)`: `B` is {LAYOUT_TEXT[layout].replace('screw', 'body screw')} "
                "at home, `theta` a length-$n$ array; return $J_b(\\theta)$, $6\\times n$. Do not call "
                "`jacobians.body_jacobian`. Set `answer = my_body_jacobian`.",
                body_jac if layout == "columns" else (lambda B, th: body_jac(np.asarray(B).T, th)),
                case, "my_body_jacobian", "body Jacobian", {"layout": layout}, example=_body_example(layout))
    for layout, case in layout_cases(_body_case).items()], library=_library_ch03_ex4)
