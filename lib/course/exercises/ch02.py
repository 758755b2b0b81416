"""Exercises of chapter 2: the space Jacobian."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator

import jacobians as jac
from jacobians import robots
from jacobians.grading import Exercise, Mistake, numeric_exercise, symbolic_exercise
from jacobians.testing import TOL, fd_tol

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import planar_points, planar_trig
from ._kinematics import DEG, Array, adj, body_jac, expS, space_jac
from ._latex import degs, num, vec
from ._mistakes import degrees_mistake, neighbour_columns, sign_mistakes, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._symbolic_2r import SYM_NOTE, describe_arm, draw_arm, draw_shape, numeric_arm, sym_arm, sym_catalogue, sym_names
from ._variants import LAYOUT_TEXT, angles_deg, layout_cases, planar_column, planar_example, worked_example


def _library_ch02_ex1(ex: Exercise) -> None:
    """The column is that column of the library's space Jacobian of the same arm."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    np.testing.assert_allclose(ex.solution(), jac.space_jacobian(arm, th)[:, ex.given["column"] - 1], atol=1e-12)


@register("ch02_ex1", library=_library_ch02_ex1)
def _ch02_ex1(rng: Generator) -> Exercise:
    ls, th_deg, i, S, J_s, J_b, J_s_deg = planar_column(rng, "space", 2, 4)  # joint 2 or 3
    ref = J_s[:, i - 1]
    mistakes = [
        Mistake("home_axis", S[:, i - 1],
                f"This is the screw axis of joint {i} at the home pose. "
                + ("Joint 1 has" if i == 2 else f"Joints 1..{i - 1} have")
                + " moved it: carry it along with the adjoint of the product of their exponentials."),
        Mistake("body_column", J_b[:, i - 1],
                f"This is column {i} of the body Jacobian (seen from the tool frame). The space Jacobian "
                "expresses the joint's screw in the fixed frame {s}."),
        degrees_mistake(J_s_deg[:, i - 1]),
        swap_mistake(ref),
        Mistake("v_sign", np.concatenate([ref[:3], -ref[3:]]),
                f"The linear part has the wrong sign. It is -ω × q with q the current position of "
                f"joint {i}."),
        *neighbour_columns(J_s, i, "space Jacobian"),
    ]
    st = (f"A planar 3R arm (joints about $z$, links along $x$ at home) has link lengths "
          f"$L = {vec(ls, 1)}$ and is at $\\theta = {degs(th_deg)}$. Give column {i} of its space Jacobian, "
          f"$J_{{s{i}}}(\\theta)$, as a 6-vector.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, the joint positions q_i; the column (z, −z × q_i)."""
        th = th_deg * DEG
        Q = planar_points(r, ls, planar_trig(r, th))  # q_i, where joint i is now
        return np.array([0.0, 0.0, 1.0, Q[i - 1][1], -Q[i - 1][0], 0.0])

    return numeric_exercise("One column of the space Jacobian", st,
                    {"lengths": ls, "theta_deg": th_deg, "column": i}, ref, mistakes,
                    what="column", hint=f"The column is (ω, -ω × q_{i}) with q_{i} where joint {i} "
                    "is now.", method=method)


def _jac_catalogue(ref: Array, J_other: Array, other_name: str, other_msg: str, home_msg: str,
                   deg_value: Array | None = None, home: Array | None = None) -> list[Mistake]:
    """The standard catalogue for a full 6xn Jacobian."""
    mistakes = [Mistake(other_name, J_other, other_msg), swap_mistake(ref)]
    if home is not None:
        mistakes.append(Mistake("home_axes", home, "These are the screw axes at the home pose. " + home_msg))
        for j in range(ref.shape[1]):
            W = ref.copy()
            W[:, j] = home[:, j]
            mistakes.append(Mistake(f"home_axis_column_{j + 1}", W,
                                    f"Column {j + 1} is the home screw axis of joint {j + 1}, not the moved one. "
                                    + home_msg))
    if deg_value is not None:
        mistakes.append(degrees_mistake(deg_value))
    mistakes += sign_mistakes(ref)
    return mistakes


def _library_ch02_ex2(ex: Exercise) -> None:
    """The library's space Jacobian, and finite differences of its forward kinematics: [V_s] = Tdot T^-1."""
    g = ex.given
    arm = jac.robots.spatial_rrp(g["h"], g["reach"])
    th = np.array([np.radians(g["theta1_deg"]), np.radians(g["theta2_deg"]), g["d3"]])
    np.testing.assert_allclose(ex.solution(), jac.space_jacobian(arm, th), atol=1e-12)
    T0 = arm.fk(th)
    dT = jac.numerical_jacobian(lambda x: arm.fk(x), th)
    T_inv = np.linalg.inv(T0)
    # Each entry of dT is within fd_tol of ∂T/∂θ_i (truncation h²/6 max|∂³T| plus rounding, from T itself); an
    # entry of W = dT T⁻¹ sums a row of dT against a column of T⁻¹, so its error is at most fd_tol times T⁻¹'s
    # largest column 1-norm, plus the product's and the closed form's rounding, TOL of the terms' size.
    fd_bound = fd_tol(lambda x: arm.fk(x), th) * float(np.abs(T_inv).sum(axis=0).max())
    bound = fd_bound + TOL * size(ex.solution(), np.abs(dT).max() * np.abs(T_inv).sum(axis=0).max())
    for i in range(3):
        W = dT[..., i] @ T_inv
        assert_within([W[2, 1], W[0, 2], W[1, 0], *W[:3, 3]], ex.solution()[:, i], bound, f"column {i + 1}")


@register("ch02_ex2", library=_library_ch02_ex2)
def _ch02_ex2(rng: Generator) -> Exercise:
    h, reach = float(rng.choice([0.5, 1.0, 1.5])), float(rng.choice([0.5, 1.0, 2.0]))
    arm = robots.spatial_rrp(h, reach)
    th_deg = angles_deg(rng, 2, step=30, low=-120, high=120)
    d3 = float(rng.choice([0.25, 0.5, 0.75]))
    th = np.array([th_deg[0] * DEG, th_deg[1] * DEG, d3])
    S = arm.screw_axes
    ref = space_jac(S, th)
    J_b = body_jac(arm.body_axes, th)
    mistakes = _jac_catalogue(
        ref, J_b, "body_for_space",
        "This is the body Jacobian (twists seen from the tool frame). The space Jacobian expresses each "
        "column in the fixed frame {s}.",
        "Each column must be carried by the joints before it: J_si = Ad(e^[S1]θ1 ⋯ e^[S(i-1)]θ(i-1)) S_i.",
        deg_value=space_jac(S, np.array([th_deg[0], th_deg[1], d3])), home=S)
    st = (f"The spatial RRP arm: joint 1 turns about $z$ through the origin, joint 2 about $y$ through "
          f"$(0, 0, {num(h)})$, joint 3 slides along $x$; at home the tool is at $({num(reach)}, 0, {num(h)})$. "
          f"At $\\theta_1 = {int(th_deg[0])}^\\circ$, $\\theta_2 = {int(th_deg[1])}^\\circ$, "
          f"$\\theta_3 = {num(d3)}$ give the space Jacobian $J_s(\\theta)$ ($6\\times3$).")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos and sin of θ1, θ2; column 2: ω2 = R_z(θ1) y, v2 = −ω2 × (0, 0, h); column 3: (0, R_z(θ1)R_y(θ2) x)."""
        c1, s1, c2, s2 = (float(r(f(x * DEG))) for x, f in ((th_deg[0], np.cos), (th_deg[0], np.sin),
                                                            (th_deg[1], np.cos), (th_deg[1], np.sin)))
        w2 = np.array([-s1, c1, 0.0])
        v2 = np.asarray(r(-np.cross(w2, [0.0, 0.0, h])))
        v3 = np.asarray(r(np.array([c1 * c2, s1 * c2, -s2])))
        return np.column_stack([S[:, 0], np.concatenate([w2, v2]), np.concatenate([np.zeros(3), v3])])

    return numeric_exercise("The space Jacobian of an RRP arm", st,
                            {"h": h, "reach": reach, "theta1_deg": th_deg[0], "theta2_deg": th_deg[1], "d3": d3}, ref,
                            mistakes, what="space Jacobian", method=method)


def _library_ch02_ex3(ex: Exercise) -> None:
    """At a point, the reference is the library's space Jacobian of the numeric arm (S, M at those lengths)."""
    ref, chain, th = numeric_arm(ex.reference, ex.given["S"], ex.given["M"], ex.given["symbols"])
    np.testing.assert_allclose(ref, jac.space_jacobian(chain, th), atol=1e-12)


@register("ch02_ex3", library=_library_ch02_ex3)
def _ch02_ex3(rng: Generator) -> Exercise:
    arm, shape = draw_arm(rng), draw_shape(rng)
    syms, S, M, J_s, J_b, B, T = sym_arm(arm, shape)
    mistakes = sym_catalogue(
        J_s, J_b, "body_for_space",
        "This is the body Jacobian. The space Jacobian expresses each column in the fixed frame {s}.",
        S, "Joint 2's screw axis is carried along by joint 1's motion: carry it with the adjoint of e^[S1]θ1.")
    st = (describe_arm(arm, shape) + " Give the space Jacobian $J_s(\\theta_1, \\theta_2)$ as a $6\\times2$ symbolic "
          "matrix in $\\theta_1, \\theta_2, l_1, l_2$. " + SYM_NOTE)
    ex = symbolic_exercise("Symbolic space Jacobian of a planar two-joint arm", st, sym_names(syms), J_s, mistakes,
                           what="space Jacobian")
    ex.hint = ("Column 1 is S1; column 2 is Ad(e^[S1]θ1) S2. Check which column, and within it the angular "
               "rows 1-3 or the linear rows 4-6.")
    ex.given.update({"joints": arm, "shape": shape, "S": S, "M": M})
    return ex


def _space_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    ref = space_jac(S, th)
    mistakes = [
        Mistake("home_axes", S, "Your function returns the screw axes at home: each column must be carried by "
                "the joints before it."),
        Mistake("product_order", space_jac(S, th, order="reverse"),
                "The product of exponentials is multiplied in the wrong order: the transform for column i is "
                "e^[S1]θ1 e^[S2]θ2 ⋯ e^[S(i-1)]θ(i-1), first joint on the left."),
        Mistake("all_joints", _own(S, th),
                "Every column is carried by the product over all the joints: only joints 1..i-1 move axis i."),
        swap_mistake(ref),
    ]
    return (S, th), ref, mistakes


def _own(S: Array, th: Array) -> Array:
    """Every column carried by the product over all joints (wrong)."""
    T = np.eye(4)
    for i in range(S.shape[1]):
        T = T @ expS(S[:, i], th[i])
    return adj(T) @ S


_SPACE_CASES = layout_cases(_space_case)


def _space_example(layout: str) -> Callable[[np.random.Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm of the seed (lengths, angles in tenths of a radian) and the J_s the function must return:
    varies the statement, so that two IDs rarely share one."""
    def build(rng: np.random.Generator) -> tuple[dict[str, Any], Any]:
        _, th, B, M = planar_example(rng)
        S = np.round(adj(M) @ B, 12)
        return {"S": S if layout == "columns" else S.T, "theta": th}, space_jac(S, th)
    return worked_example("my_space_jacobian(S, theta)", build)


def _axes_columns(ex: Exercise, axes: Any) -> Array:
    """The screw axes of a code exercise's test case as columns, whichever layout the variant passes."""
    return np.asarray(axes, dtype=float).T if ex.given["layout"] == "rows" else np.asarray(axes, dtype=float)


def _library_ch02_ex4(ex: Exercise) -> None:
    """On every test case, J_s is the library's body Jacobian carried to {s}: [Ad_T_sb] J_b(θ), T_sb the library's
    forward kinematics (of any home pose: J_s does not depend on it), a route through the joints after each
    column instead of before it. Products of at most 7 exponentials and a 6x6 adjoint: within TOL of the size
    of the terms, |J_b| times max(1, |p|)."""
    for (axes, th), out in reference_runs(ex):
        chain = jac.SerialChain(_axes_columns(ex, axes), np.eye(4))
        T, J_b = chain.fk(th), jac.body_jacobian(chain, th)
        assert_close(out, jac.body_to_space(J_b, T), "space Jacobian", scale=size(J_b) * size(T))


register_code("ch02_ex4", "Code: the space Jacobian", [
    CodeVariant(f"Write `my_space_jacobian(S, theta)`: `S` is {LAYOUT_TEXT[layout]} at home, `theta` a length-$n$ "
                "array of joint values; return $J_s(\\theta)$, $6\\times n$. You may use `jacobians.lie.exp_se3` and "
                "`jacobians.lie.adjoint`, but not `jacobians.space_jacobian`. Set `answer = my_space_jacobian`.",
                space_jac if layout == "columns" else (lambda S, th: space_jac(np.asarray(S).T, th)),
                case, "my_space_jacobian", "space Jacobian", {"layout": layout}, example=_space_example(layout))
    for layout, case in _SPACE_CASES.items()], library=_library_ch02_ex4)
