"""Exercises of chapters 4 (space vs body), 5 (geometric Jacobian), 6 (analytic Jacobian)."""

from __future__ import annotations

from typing import Any

import numpy as np
import sympy as sp
from numpy.random import Generator
from numpy.typing import ArrayLike

from jacobians import lie, robots
from jacobians.chain import SerialChain
from jacobians.grading import Exercise, Feedback, Mistake

from ._common import (
    DEG,
    Array,
    adj,
    angles_deg,
    blockdiag,
    bmatrix,
    body_jac,
    chain_case,
    degrees_mistake,
    degs,
    fk,
    inv_T,
    num,
    planar_pose,
    sign_mistakes,
    space_jac,
    spatial_5r_pose,
    swap_mistake,
    vec,
)
from ._registry import register, register_code


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


# =================================================================== chapter 4

def _frame_change(given: str, J: Array, T: Array, ref: Array, mistakes: list[Mistake]) -> Exercise:
    """From J_s to J_b (``given="s"``) or back, at the pose T_sb; (v, omega) swapped is added to the mistakes."""
    target = "b" if given == "s" else "s"
    name = {"s": "space", "b": "body"}
    st = (f"At some configuration an arm has \n\n$$J_{given} = {bmatrix(J, 4)}$$\n\nand "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 4)}.$$\n\nGive its {name[target]} Jacobian $J_{target}$.")
    return Exercise("", f"From the {name[given]} to the {name[target]} Jacobian", st, {f"J_{given}": J, "T_sb": T},
                    "numeric", ref, [*mistakes, swap_mistake(ref)], what=f"{name[target]} Jacobian")


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


def ref_geometric_jacobian(S: ArrayLike, M: ArrayLike, theta: ArrayLike) -> Array:
    """Reference: J = blockdiag(R, R) J_b."""
    T = fk(S, M, theta)
    R = T[:3, :3]
    B = adj(inv_T(M)) @ np.asarray(S, float)
    return blockdiag(R, R) @ body_jac(B, theta)


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
    return Exercise("", "The body twist from joint rates", st,
                    {"lengths": ls, "theta_deg": th_deg, "theta_dot": dth}, "numeric", ref, mistakes,
                    what="body twist")


# =================================================================== chapter 5

def _geo_catalogue(ref: Array, J_b: Array, R: Array, J_s: Array | None = None) -> list[Mistake]:
    ms = [
        Mistake("R_missing", J_b, "This is the body Jacobian J_b: its rows are expressed in the tool frame. The "
                "geometric Jacobian expresses both ω and ṗ in {s}: rotate each half by R_sb."),
        Mistake("only_angular_rotated", blockdiag(R, np.eye(3)) @ J_b,
                "Only the angular half is rotated into {s}; the linear half needs R_sb too."),
        Mistake("only_linear_rotated", blockdiag(np.eye(3), R) @ J_b,
                "Only the linear half is rotated into {s}; the angular half needs R_sb too."),
        Mistake("R_transposed", blockdiag(R.T, R.T) @ J_b,
                "You rotated with R_sbᵀ: to express a vector given in {b} in {s}, multiply by R_sb."),
    ]
    if J_s is not None:
        ms.append(Mistake("space_for_geometric", J_s,
                          "This is the space Jacobian: its linear rows are the velocity of the body point at the "
                          "origin of {s}, not of the tool point p."))
    return ms + [swap_mistake(ref)]


@register("ch05_ex1")
def _ch05_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 2)
    J_b = body_jac(arm.body_axes, th)
    J_s = space_jac(arm.screw_axes, th)
    T = fk(arm.screw_axes, arm.home, th)
    R = T[:3, :3]
    ref = blockdiag(R, R) @ J_b
    deg_T = fk(arm.screw_axes, arm.home, th_deg)
    deg_ref = blockdiag(deg_T[:3, :3], deg_T[:3, :3]) @ body_jac(arm.body_axes, th_deg)
    mistakes = _geo_catalogue(ref, J_b, R, J_s) + [degrees_mistake(deg_ref)] + sign_mistakes(ref)
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give its geometric "
          "Jacobian $J(\\theta)$ ($6\\times2$, rows $(\\omega_s, \\dot p)$, $p$ the tool point).")
    return Exercise("", "Geometric Jacobian of a planar 2R arm", st, {"lengths": ls, "theta_deg": th_deg},
                    "numeric", ref, mistakes, what="geometric Jacobian",
                    hint="Column i is (z_i, z_i × (p - p_i)) with p_i the current position of joint i.")


@register("ch05_ex2")
def _ch05_ex2(rng: Generator) -> Exercise:
    T, J_b, ref, J_s = spatial_5r_pose(rng)
    mistakes = _geo_catalogue(ref, J_b, T[:3, :3], J_s)
    st = (f"A 5-joint arm has body Jacobian \n\n$$J_b = {bmatrix(J_b, 4)}$$\n\nat a pose with "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 4)}.$$\n\nGive its geometric Jacobian $J$ (rows $(\\omega_s, \\dot p)$).")
    return Exercise("", "From the body to the geometric Jacobian", st, {"J_b": J_b, "T_sb": T}, "numeric", ref,
                    mistakes, what="geometric Jacobian")


@register("ch05_ex3")
def _ch05_ex3(rng: Generator) -> Exercise:
    axes = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1], [0, -1, 0]], float)
    z = axes[rng.integers(len(axes))]
    while True:
        p_i = rng.integers(-2, 3, size=3).astype(float)
        p = rng.integers(-2, 3, size=3).astype(float)
        if np.linalg.norm(np.cross(z, p - p_i)) > 0.5 and np.linalg.norm(np.cross(z, p)) > 0.5 \
                and not np.allclose(np.cross(z, p), np.cross(z, p - p_i)):
            break
    ref = np.concatenate([z, np.cross(z, p - p_i)])
    mistakes = [
        Mistake("reversed_difference", np.concatenate([z, np.cross(z, p_i - p)]),
                "The linear part has the wrong sign: it is the velocity of the tool point turning about the "
                "joint axis, so the lever arm points from the joint to the tool."),
        Mistake("no_cross", np.concatenate([z, p - p_i]),
                "The linear part is the lever arm itself; the velocity is the cross product of the axis with "
                "the lever arm."),
        Mistake("lever_from_origin", np.concatenate([z, np.cross(z, p)]),
                "Your lever arm starts at the origin of {s}; it must start at a point of the joint axis."),
        swap_mistake(ref),
    ]
    st = (f"Joint $i$ of an arm is revolute; at the current configuration its axis points along "
          f"$z_i = {vec(z)}$ and passes through $p_i = {vec(p_i)}$, and the tool point is at $p = {vec(p)}$. "
          "Give column $i$ of the geometric Jacobian (6-vector, angular part first).")
    return Exercise("", "A geometric-Jacobian column from the axis", st, {"z_i": z, "p_i": p_i, "p": p},
                    "numeric", ref, mistakes, what="column")


@chain_case
def _geo_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    T = fk(S, M, th)
    B = adj(inv_T(M)) @ S
    J_b = body_jac(B, th)
    R = T[:3, :3]
    ref = blockdiag(R, R) @ J_b
    J_s = space_jac(S, th)
    mistakes = _geo_catalogue(ref, J_b, R, J_s)
    return (S, M, th), ref, mistakes


register_code(
    "ch05_ex4", "Code: the geometric Jacobian",
    "Write `my_geometric_jacobian(S, M, theta)` returning the geometric Jacobian $J(\\theta)$ "
    "(rows $(\\omega_s, \\dot p)$) of the chain with space screw axes `S` ($6\\times n$) and home pose `M`. "
    "You may use `jacobians.space_jacobian`/`body_jacobian` with `jacobians.SerialChain(S, M)`, but not "
    "`geometric_jacobian` or the conversion functions. Set `answer = my_geometric_jacobian`.",
    reference=ref_geometric_jacobian, make_case=_geo_case, fn_name="my_geometric_jacobian", what="geometric Jacobian")


# =================================================================== chapter 6

@register("ch06_ex1")
def _ch06_ex1(rng: Generator) -> Exercise:
    th1, th2, l1, l2 = sp.symbols("theta1 theta2 l1 l2", real=True)
    x = l1 * sp.cos(th1) + l2 * sp.cos(th1 + th2)
    y = l1 * sp.sin(th1) + l2 * sp.sin(th1 + th2)
    ref = sp.Matrix([[sp.diff(x, th1), sp.diff(x, th2)], [sp.diff(y, th1), sp.diff(y, th2)]])
    wrong_sign = sp.Matrix([[-ref[0, 0], -ref[0, 1]], [ref[1, 0], ref[1, 1]]])
    col1_eq_col2 = sp.Matrix([[ref[0, 1], ref[0, 1]], [ref[1, 1], ref[1, 1]]])
    only_l2 = sp.Matrix([[-l1 * sp.sin(th1), -l2 * sp.sin(th2)], [l1 * sp.cos(th1), l2 * sp.cos(th2)]])
    mistakes = [
        Mistake("sign_row_1", wrong_sign, "Row 1 has the wrong sign: differentiate cos carefully."),
        Mistake("column_1_missing_l1", col1_eq_col2,
                "Column 1 is missing the l1 term: joint 1 moves the whole arm, link 1 included."),
        Mistake("relative_angle", only_l2,
                "Link 2's direction is θ1 + θ2 (absolute angle), not θ2 alone."),
    ]
    syms = {"theta1": th1, "theta2": th2, "l1": l1, "l2": l2}
    st = ("The tool point of the planar 2R arm is at $x = l_1\\cos\\theta_1 + l_2\\cos(\\theta_1+\\theta_2)$, "
          "$y = l_1\\sin\\theta_1 + l_2\\sin(\\theta_1+\\theta_2)$. Give the $2\\times2$ analytic (position) "
          "Jacobian $\\partial(x, y)/\\partial(\\theta_1, \\theta_2)$ as a sympy Matrix in "
          "`theta1, theta2, l1, l2` (real symbols).")
    return Exercise("", "Position Jacobian of the planar 2R arm", st, {"symbols": syms}, "symbolic", ref, mistakes,
                    symbols=syms, what="position Jacobian")


def _B(phi: Array, rep: str) -> Array:
    a, b = phi[0], phi[1]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    if rep == "zyx":
        return np.array([[0, -sa, ca * cb], [0, ca, sa * cb], [1, 0, -sb]])
    return np.array([[0, -sa, ca * sb], [0, ca, sa * sb], [1, 0, cb]])


@register("ch06_ex2")
def _ch06_ex2(rng: Generator) -> Exercise:
    rep = "zyx" if rng.random() < 0.5 else "zyz"
    phi_deg = angles_deg(rng, 3, step=15, low=-75, high=75)
    if rep == "zyz":
        phi_deg[1] = abs(phi_deg[1]) + 15
    phi = phi_deg * DEG
    ref = _B(phi, rep)
    mistakes = [
        Mistake("inverse", np.linalg.inv(ref), "This is B(φ)⁻¹ (it maps ω_s to φ̇). The "
                "exercise asks for B, which maps φ̇ to ω_s."),
        degrees_mistake(_B(phi_deg, rep)),
        Mistake("body_frame", _rot(phi, rep).T @ ref,
                "This is the map to the angular velocity in the body frame, Rᵀ B. The exercise wants ω in {s}."),
    ]
    name = {"zyx": "ZYX (yaw-pitch-roll)", "zyz": "ZYZ"}[rep]
    word = {"zyx": r"R = R_z(\phi_1)R_y(\phi_2)R_x(\phi_3)", "zyz": r"R = R_z(\phi_1)R_y(\phi_2)R_z(\phi_3)"}[rep]
    st = (f"For the {name} Euler angles, ${word}$, give the $3\\times3$ matrix $B(\\phi)$ with "
          f"$\\omega_s = B(\\phi)\\dot\\phi$ at $\\phi = {degs(phi_deg)}$.")
    return Exercise("", "From Euler-angle rates to angular velocity", st,
                    {"representation": rep, "phi_deg": phi_deg}, "numeric", ref, mistakes, what="matrix B",
                    hint="Column j of B is the axis of the j-th rotation, carried by the rotations before it.")


def _rot(phi: Array, rep: str) -> Array:
    a, b, c = phi
    last = "x" if rep == "zyx" else "z"
    return lie.rotation_about("z", a) @ lie.rotation_about("y", b) @ lie.rotation_about(last, c)


@register("ch06_ex3")
def _ch06_ex3(rng: Generator) -> Exercise:
    arm = robots.zyx_wrist(float(rng.choice([0.1, 0.2, 0.3])))
    th_deg = angles_deg(rng, 3, step=15, low=-60, high=60)
    th = th_deg * DEG
    T = fk(arm.screw_axes, arm.home, th)
    J = np.round(blockdiag(T[:3, :3], T[:3, :3]) @ body_jac(arm.body_axes, th), 4)
    phi_deg = th_deg  # ZYX coordinates of this wrist are its joint angles
    Binv = np.linalg.inv(_B(phi_deg * DEG, "zyx"))
    ref = blockdiag(Binv, np.eye(3)) @ J
    mistakes = [
        Mistake("B_not_inverted", blockdiag(_B(phi_deg * DEG, "zyx"), np.eye(3)) @ J,
                "You multiplied by B(φ); the analytic Jacobian needs B(φ)⁻¹, the map from ω_s to "
                "the angle rates."),
        Mistake("unchanged", J, "That is the geometric Jacobian unchanged: its angular rows are ω_s, not the "
                "rates of the ZYX angles."),
        Mistake("linear_rows_converted", blockdiag(np.eye(3), Binv) @ J,
                "You converted the linear rows. Only the angular rows change; ṗ stays as it is."),
        degrees_mistake(blockdiag(np.linalg.inv(_B(phi_deg, "zyx")), np.eye(3)) @ J),
        swap_mistake(ref),
    ]
    st = (f"A ZYX wrist (joints about $z$, $y$, $x$ through the origin, tool at distance "
          f"{num(arm.home[0, 3])} along $x$) is at $\\theta = {degs(th_deg)}$, so the ZYX angles of its tool are "
          f"$\\phi = \\theta$. Its geometric Jacobian is \n\n$$J = {bmatrix(J, 4)}.$$\n\nGive the analytic Jacobian "
          "$J_a$ for $x = (\\phi, p)$ (rows: the three ZYX angle rates, then $\\dot p$).")
    return Exercise("", "The analytic Jacobian of a ZYX wrist", st, {"J": J, "phi_deg": phi_deg}, "numeric", ref,
                    mistakes, what="analytic Jacobian")


@register("ch06_ex4")
def _ch06_ex4(rng: Generator) -> Exercise:
    rep = "zyx" if rng.random() < 0.5 else "zyz"
    other = "zyz" if rep == "zyx" else "zyx"

    def margin(x: float, r: str) -> float:
        return float(abs(np.cos(x)) if r == "zyx" else abs(np.sin(x)))

    def predicate(arr: Array) -> Feedback:
        if arr.size != 1:
            return Feedback(False, f"Give one number (the angle φ₂ in radians); you gave {arr.size} values.",
                            mistake="wrong_shape")
        x = float(arr.ravel()[0])
        if margin(x, rep) < 1e-3:
            return Feedback(True, f"Right: at φ₂ = {x:.4g} rad the {rep.upper()} matrix B(φ) is singular "
                            "(gimbal lock: the first and third rotation axes line up).", "correct")
        if abs(x) > 2 * np.pi + 0.01 and margin(x * np.pi / 180, rep) < 1e-3:
            return Feedback(False, "This looks like an angle in degrees; give it in radians.",
                            mistake="degrees_for_radians")
        if margin(x, other) < 1e-3:
            return Feedback(False, f"That is where the {other.upper()} angles lock. For {rep.upper()} look at which "
                            "value of φ₂ lines up the first and third axes (det B = 0).",
                            mistake="other_representation")
        return Feedback(False, f"At φ₂ = {x:.4g} rad, det B(φ) is not zero. Write B(φ) and find "
                        "where its determinant vanishes.", mistake="not_singular")

    ref = np.pi / 2 if rep == "zyx" else np.pi
    st = (f"For the {rep.upper()} Euler angles, give a value of the middle angle $\\phi_2$ (in radians, "
          f"not 0) at which $B(\\phi)$ is singular, so that the angle rates cannot follow some angular "
          "velocities.")
    return Exercise("", "Where Euler angles lock", st, {"representation": rep}, "predicate", ref, [],
                    predicate=predicate, what="angle")


@register("ch06_ex5")
def _ch06_ex5(rng: Generator) -> Exercise:
    th_deg = angles_deg(rng, 3, step=15, low=-60, high=60)
    th = th_deg * DEG
    arm = robots.zyx_wrist(0.2)
    T = fk(arm.screw_axes, arm.home, th)
    J = blockdiag(T[:3, :3], T[:3, :3]) @ body_jac(arm.body_axes, th)
    B = _B(th, "zyx")
    ref = np.linalg.inv(B) @ J[:3]
    mistakes = [
        Mistake("geometric_block", J[:3], "This is the angular block of the geometric Jacobian (ω_s per joint "
                "rate). The analytic one gives the rates of the ZYX angles."),
        Mistake("B_not_inverted", B @ J[:3], "You multiplied by B instead of B⁻¹."),
        degrees_mistake(np.linalg.inv(_B(th_deg, "zyx")) @ J[:3]),
    ]
    st = (f"The ZYX wrist is at $\\theta = {degs(th_deg)}$ (away from gimbal lock). Give the $3\\times3$ angular "
          "block of its analytic Jacobian for ZYX angles, $\\partial\\dot\\phi/\\partial\\dot\\theta$. "
          "Think before you compute.")
    return Exercise("", "Angular block of the wrist's analytic Jacobian", st, {"theta_deg": th_deg}, "numeric", ref,
                    mistakes, what="matrix")
