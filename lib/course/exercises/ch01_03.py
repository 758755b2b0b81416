"""Exercises of chapters 1 (twists, screws, adjoint), 2 (space Jacobian), 3 (body Jacobian)."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import sympy as sp
from numpy.random import Generator

from jacobians import lie, robots
from jacobians.grading import Case, Exercise, Mistake, symbolic_exercise

from ._common import (
    DEG,
    Array,
    adj,
    angles_deg,
    bmatrix,
    body_jac,
    chain_case,
    degrees_mistake,
    degs,
    expS,
    inv_T,
    num,
    planar_pose,
    random_transform,
    sign_mistakes,
    space_jac,
    swap,
    swap_mistake,
    vec,
)
from ._registry import register, register_code

SKEW_HINT = "Recall [p] is the skew matrix with [p]x = p × x."


# =================================================================== chapter 1

@register("ch01_ex1")
def _ch01_ex1(rng: Generator) -> Exercise:
    axes = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], float)
    w = axes[rng.integers(6)]
    while True:
        q = rng.integers(-3, 4, size=3).astype(float)
        if np.linalg.norm(np.cross(w, q)) > 0.5:
            break
    ref = np.concatenate([w, -np.cross(w, q)])
    mistakes = [
        Mistake("v_sign", np.concatenate([w, np.cross(w, q)]),
                "The linear part has the wrong sign. v is the velocity of the point of the body at the origin "
                "of {s}: work out which way that point moves when the body turns about the axis."),
        swap_mistake(ref),
        Mistake("q_as_v", np.concatenate([w, q]),
                "You put the point q itself in the linear part. The linear part is a velocity, built from "
                "ω and q with a cross product."),
    ]
    st = (f"A revolute joint turns about the unit axis $\\hat\\omega = {vec(w)}$ through the point "
          f"$q = {vec(q)}$ (in {{s}}). Give its screw axis $\\mathcal S = (\\omega, v)$ as a 6-vector, "
          "angular part first.")
    return Exercise("", "Screw axis of a revolute joint", st, {"omega": w, "q": q}, "numeric", ref, mistakes,
                    what="screw axis", hint="Check v = -ω × q entry by entry.")


def _adj_mistakes(T: Array) -> list[Mistake]:
    R, p = T[:3, :3], T[:3, 3]
    A = adj(T)
    wrong_order = A.copy()
    wrong_order[3:, :3] = R @ lie.skew(p)
    vfirst = np.zeros((6, 6))
    vfirst[:3, :3] = R
    vfirst[3:, 3:] = R
    vfirst[:3, 3:] = lie.skew(p) @ R
    no_block = A.copy()
    no_block[3:, :3] = 0
    return [
        Mistake("product_order", wrong_order,
                "The lower-left block has its two factors in the wrong order: the skew matrix of p and R do "
                "not commute. " + SKEW_HINT),
        Mistake("v_first_layout", vfirst,
                "This is the adjoint for twists ordered (v, ω). In this course twists are (ω, v), "
                "so the coupling block sits below the diagonal."),
        Mistake("inverse", adj(inv_T(T)),
                "This is the adjoint of the inverse transform. Check which transform the exercise asks about."),
        Mistake("missing_block", no_block,
                "The coupling block is missing: the block-diagonal part alone only rotates, it forgets that the "
                "frames' origins are apart."),
    ]


@register("ch01_ex2")
def _ch01_ex2(rng: Generator) -> Exercise:
    T = random_transform(rng)
    ref = adj(T)
    st = (f"Give the $6\\times 6$ adjoint matrix $[\\mathrm{{Ad}}_T]$ of \n\n$$T = {bmatrix(T, 4)},$$\n\n"
          "for twists ordered $(\\omega, v)$.")
    return Exercise("", "The adjoint of a transform", st, {"T": T}, "numeric", ref, _adj_mistakes(T),
                    what="adjoint matrix", hint="Compare block by block with [[R, 0], [[p]R, R]].")


@register("ch01_ex3")
def _ch01_ex3(rng: Generator) -> Exercise:
    T_ab = random_transform(rng)
    V_b = rng.integers(-3, 4, size=6).astype(float)
    V_b[:3] = V_b[:3] if np.any(V_b[:3]) else np.array([1.0, 0, 0])
    ref = adj(T_ab) @ V_b
    R = T_ab[:3, :3]
    mistakes = [
        Mistake("inverse", adj(inv_T(T_ab)) @ V_b,
                "You used the adjoint of T_ba = T_ab⁻¹. To re-express a twist from {b} in {a}, "
                "use the transform whose subscripts read 'a from b'."),
        swap_mistake(ref),
        Mistake("rotation_only", np.concatenate([R @ V_b[:3], R @ V_b[3:]]),
                "You only rotated both halves. The linear part also picks up p × (R ω) because the "
                "origins of {a} and {b} differ."),
        Mistake("vfirst_input", swap(adj(T_ab) @ swap(V_b)),
                "You read the given twist as (v, ω). It is given angular part first."),
    ]
    st = (f"A body has the twist $\\mathcal V_b = {vec(V_b)}$ expressed in frame {{b}}, and "
          f"\n\n$$T_{{ab}} = {bmatrix(T_ab, 4)}.$$\n\nGive the same twist expressed in {{a}}, $\\mathcal V_a$.")
    return Exercise("", "Changing the frame of a twist", st, {"T_ab": T_ab, "V_b": V_b}, "numeric", ref,
                    mistakes, what="twist")


def _adj_case(rng: Generator) -> Case:
    T = random_transform(rng)
    T[:3, 3] = rng.uniform(-2, 2, size=3)
    return Case((T,), adj(T), _adj_mistakes(T), f"T with p = {vec(T[:3, 3], 2)}")


register_code(
    "ch01_ex4", "Code: the adjoint map",
    "Write a function `my_adjoint(T)` that takes a $4\\times4$ transform (numpy array) and returns its "
    "$6\\times 6$ adjoint $[\\mathrm{Ad}_T]$ for twists ordered $(\\omega, v)$. Set `answer = my_adjoint`. "
    "It is tested on random transforms.",
    reference=adj, make_case=_adj_case, fn_name="my_adjoint", what="adjoint matrix")


# =================================================================== chapter 2

@register("ch02_ex1")
def _ch02_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    i = int(rng.integers(2, 4))  # joint 2 or 3
    S = arm.screw_axes
    J_s = space_jac(S, th)
    J_b = body_jac(arm.body_axes, th)
    ref = J_s[:, i - 1]
    mistakes = [
        Mistake("home_axis", S[:, i - 1],
                f"This is the screw axis of joint {i} at the home pose. Joints 1..{i - 1} have moved it: carry it "
                "along with the adjoint of the product of their exponentials."),
        Mistake("body_column", J_b[:, i - 1],
                f"This is column {i} of the body Jacobian (seen from the tool frame). The space Jacobian "
                "expresses the joint's screw in the fixed frame {s}."),
        degrees_mistake(space_jac(S, th_deg)[:, i - 1]),
        swap_mistake(ref),
        Mistake("v_sign", np.concatenate([ref[:3], -ref[3:]]),
                f"The linear part has the wrong sign. It is -ω × q with q the current position of "
                f"joint {i}."),
    ]
    st = (f"A planar 3R arm (joints about $z$, links along $x$ at home) has link lengths "
          f"$L = {vec(ls, 1)}$ and is at $\\theta = {degs(th_deg)}$. Give column {i} of its space Jacobian, "
          f"$J_{{s{i}}}(\\theta)$, as a 6-vector.")
    return Exercise("", "One column of the space Jacobian", st,
                    {"lengths": ls, "theta_deg": th_deg, "column": i}, "numeric", ref, mistakes,
                    what="column", hint=f"The column is (ω, -ω × q_{i}) with q_{i} where joint {i} "
                    "is now.")


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


@register("ch02_ex2")
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
    return Exercise("", "The space Jacobian of an RRP arm", st,
                    {"h": h, "reach": reach, "theta1_deg": th_deg[0], "theta2_deg": th_deg[1], "d3": d3},
                    "numeric", ref, mistakes, what="space Jacobian")


def _sym_names(syms: tuple[Any, ...]) -> dict[str, Any]:
    return dict(zip(("theta1", "theta2", "l1", "l2"), syms, strict=True))


def _sym_2r() -> tuple[Any, Any, Any, Any]:
    th1, th2, l1, l2 = sp.symbols("theta1 theta2 l1 l2", real=True)
    return th1, th2, l1, l2


def _sym_exp(S: Any, th: Any) -> Any:
    """exp([S] th) for a planar revolute screw (about z), sympy."""
    w = S[:3, 0]
    v = S[3:, 0]
    c, s = sp.cos(th), sp.sin(th)
    R = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]]) if w[2] == 1 else None
    W = sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G = sp.eye(3) * th + (1 - c) * W + (th - s) * W * W
    p = G * v
    T = sp.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def _sym_adj(T: Any) -> Any:
    R, p = T[:3, :3], T[:3, 3]
    P = sp.Matrix([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    A = sp.zeros(6, 6)
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = P * R
    return A


@functools.lru_cache(maxsize=1)
def _sym_planar_2r() -> tuple[tuple[Any, Any, Any, Any], Any, Any, Any, Any, Any, Any]:
    """Symbolic S, M, J_s, J_b, B of the planar 2R arm, built from exponentials and adjoints (cached)."""
    th1, th2, l1, l2 = _sym_2r()
    S1 = sp.Matrix([0, 0, 1, 0, 0, 0])
    S2 = sp.Matrix([0, 0, 1, 0, -l1, 0])
    E1 = _sym_exp(S1, th1)
    E2 = _sym_exp(S2, th2)
    M = sp.eye(4)
    M[0, 3] = l1 + l2

    def tidy(A: Any) -> Any:
        return A.applyfunc(lambda e: sp.trigsimp(sp.expand(sp.expand_trig(e))))

    J_s = tidy(sp.Matrix.hstack(S1, _sym_adj(E1) * S2))
    Minv = sp.eye(4)
    Minv[0, 3] = -(l1 + l2)
    B = tidy(_sym_adj(Minv) * sp.Matrix.hstack(S1, S2))
    # Body recursion: J_b2 = B2, J_b1 = Ad(e^{-[B2] theta2}) B1.
    J_b = tidy(sp.Matrix.hstack(_sym_adj(_sym_exp(B[:, 1], -th2)) * B[:, 0], B[:, 1]))
    T = E1 * E2 * M
    return (th1, th2, l1, l2), sp.Matrix.hstack(S1, S2), M, J_s, J_b, B, T


def _sym_catalogue(ref: Any, other: Any, other_name: str, other_msg: str, home: Any, home_msg: str) -> list[Mistake]:
    def neg_col(A: Any, j: int) -> Any:
        W = A.copy()
        W[:, j] = -W[:, j]
        return W
    sw = sp.Matrix.vstack(ref[3:, :], ref[:3, :])
    return [
        Mistake(other_name, other, other_msg),
        Mistake("v_omega_swapped", sw, "Your rows are in the order (v, ω): this course puts the angular part "
                "first, rows 1-3 ω and rows 4-6 v."),
        Mistake("home_axes", home, "These are the screw axes at the home pose. " + home_msg),
        Mistake("sign_column_1", neg_col(ref, 0), "Column 1 has the opposite sign: check the direction of "
                "joint 1's axis and the sign in v = -ω × q."),
        Mistake("sign_column_2", neg_col(ref, 1), "Column 2 has the opposite sign: check the direction of "
                "joint 2's axis and the sign in v = -ω × q."),
    ]


SYM_NOTE = ("Use sympy: `theta1, theta2, l1, l2 = sympy.symbols('theta1 theta2 l1 l2', real=True)` and give a "
            "`sympy.Matrix`.")


@register("ch02_ex3")
def _ch02_ex3(rng: Generator) -> Exercise:
    syms, S, M, J_s, J_b, B, T = _sym_planar_2r()
    mistakes = _sym_catalogue(
        J_s, J_b, "body_for_space",
        "This is the body Jacobian. The space Jacobian expresses each column in the fixed frame {s}.",
        S, "Joint 2's axis moves when joint 1 turns: carry it with the adjoint of e^[S1]θ1.")
    st = ("For the planar 2R arm with link lengths $l_1, l_2$ (joint 1 about $z$ at the origin, joint 2 about "
          "$z$ through $(l_1, 0, 0)$ at home), give the space Jacobian $J_s(\\theta_1, \\theta_2)$ as a "
          "$6\\times2$ symbolic matrix. " + SYM_NOTE)
    return symbolic_exercise("Symbolic space Jacobian of the planar 2R arm", st, _sym_names(syms), J_s, mistakes,
                             what="space Jacobian")


@chain_case
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


register_code(
    "ch02_ex4", "Code: the space Jacobian",
    ("Write `my_space_jacobian(S, theta)`: `S` is a $6\\times n$ numpy array whose columns are the screw "
     "axes $(\\omega, v)$ at home, `theta` a length-$n$ array of joint values; return $J_s(\\theta)$, "
     "$6\\times n$. You may use `jacobians.lie.exp_se3` and `jacobians.lie.adjoint`, but not "
     "`jacobians.space_jacobian`. Set `answer = my_space_jacobian`."),
    reference=space_jac, make_case=_space_case, fn_name="my_space_jacobian", what="space Jacobian")


# =================================================================== chapter 3

@register("ch03_ex1")
def _ch03_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    i = int(rng.integers(1, 3))  # joint 1 or 2
    B = arm.body_axes
    J_b = body_jac(B, th)
    J_s = space_jac(arm.screw_axes, th)
    ref = J_b[:, i - 1]
    mistakes = [
        Mistake("home_axis", B[:, i - 1],
                f"This is the body screw axis B_{i} at the home pose. Joints {i + 1}..3 move the tool frame relative "
                f"to joint {i}: carry B_{i} with the adjoint of e^-[B3]θ3 ⋯ e^-[B{i + 1}]θ{i + 1}."),
        Mistake("space_column", J_s[:, i - 1],
                f"This is column {i} of the space Jacobian. The body Jacobian expresses the joint's screw in the "
                "tool frame {b}."),
        degrees_mistake(body_jac(B, th_deg)[:, i - 1]),
        swap_mistake(ref),
        Mistake("v_sign", np.concatenate([ref[:3], -ref[3:]]),
                "The linear part has the wrong sign: in {b} it is -ω_b × r with r the position of the joint "
                "axis seen from the tool."),
    ]
    st = (f"A planar 3R arm has link lengths $L = {vec(ls, 1)}$ (tool at the end of link 3) and is at "
          f"$\\theta = {degs(th_deg)}$. Give column {i} of its body Jacobian, $J_{{b{i}}}(\\theta)$, as a 6-vector.")
    return Exercise("", "One column of the body Jacobian", st,
                    {"lengths": ls, "theta_deg": th_deg, "column": i}, "numeric", ref, mistakes, what="column")


@register("ch03_ex2")
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
    return Exercise("", "Body screw axes from space screw axes", st, {"S": S, "M": M}, "numeric", ref, mistakes,
                    what="matrix of body screw axes")


@register("ch03_ex3")
def _ch03_ex3(rng: Generator) -> Exercise:
    syms, S, M, J_s, J_b, B, T = _sym_planar_2r()
    mistakes = _sym_catalogue(
        J_b, J_s, "space_for_body",
        "This is the space Jacobian. The body Jacobian expresses each column in the tool frame {b}.",
        B, "Joint 1's axis, seen from the tool, moves when joint 2 turns: carry B1 with the adjoint of "
        "e^-[B2]θ2.")
    st = ("For the planar 2R arm with link lengths $l_1, l_2$ (tool frame at the end of link 2, oriented like "
          "{s} at home), give the body Jacobian $J_b(\\theta_1, \\theta_2)$ as a $6\\times2$ symbolic matrix. "
          + SYM_NOTE)
    return symbolic_exercise("Symbolic body Jacobian of the planar 2R arm", st, _sym_names(syms), J_b, mistakes,
                             what="body Jacobian")


@chain_case
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


register_code(
    "ch03_ex4", "Code: the body Jacobian",
    ("Write `my_body_jacobian(B, theta)`: `B` is $6\\times n$ (body screw axes at home, $(\\omega, v)$), "
     "`theta` length $n$; return $J_b(\\theta)$. Do not call `jacobians.body_jacobian`. "
     "Set `answer = my_body_jacobian`."),
    reference=body_jac, make_case=_body_case, fn_name="my_body_jacobian", what="body Jacobian")
