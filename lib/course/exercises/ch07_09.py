"""Exercises of chapters 7 (conventions), 8 (Jacobians of every link), 9 (using the Jacobian)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

from jacobians.grading import Case, Exercise, Feedback, Mistake

from ._common import (
    DEG,
    Array,
    adj,
    angles_deg,
    blockdiag,
    bmatrix,
    chain_case,
    degrees_mistake,
    degs,
    expS,
    fk,
    inv_T,
    lengths,
    planar_chain,
    planar_pose,
    space_jac,
    spatial_5r_pose,
    swap,
    swap_mistake,
    vec,
)
from ._registry import register, register_code

V_FIRST = ("Rows 1-3 of your answer should be the angular part and rows 4-6 the linear part: Modern Robotics "
           "puts ω first, unlike Siciliano, Corke and Pinocchio.")


def _p_cross(p: Array, J: Array) -> Array:
    """Rows (omega, v + p x omega)."""
    out = J.copy()
    out[3:] = J[3:] + np.cross(p, J[:3].T).T
    return out


# =================================================================== chapter 7

@register("ch07_ex1")
def _ch07_ex1(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_sic = np.round(swap(J), 4)
    ref = swap(J_sic)
    mistakes = [
        Mistake("unchanged", J_sic, "You copied Siciliano's matrix unchanged; its rows are (ṗ, ω). " + V_FIRST),
        Mistake("space_for_geometric", _p_cross(T[:3, 3], ref),
                "You also moved the reference point to the origin of {s}: that is the space Jacobian. The exercise "
                "asks for the geometric Jacobian, which keeps ṗ of the tool point."),
    ]
    st = (f"Siciliano's book writes the geometric Jacobian with rows $(\\dot p, \\omega)$. For a 5-joint arm it "
          f"is \n\n$$J_{{Sic}} = {bmatrix(J_sic, 4)}.$$\n\nGive the same Jacobian in this course's convention, rows "
          "$(\\omega_s, \\dot p)$.")
    return Exercise("", "Siciliano's geometric Jacobian", st, {"J_sic": J_sic}, "numeric", ref, mistakes,
                    what="geometric Jacobian")


@register("ch07_ex2")
def _ch07_ex2(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J0 = np.round(swap(J), 4)          # Corke's jacob0: (v of the tool point, omega) in the world frame
    Jg = swap(J0)
    p = T[:3, 3]
    ref = _p_cross(p, Jg)
    mistakes = [
        Mistake("only_swapped", Jg,
                "You reordered the rows, which gives the geometric Jacobian (velocity of the tool point). "
                "J_s wants the velocity of the body point at the origin of {s}: shift the reference point."),
        Mistake("unchanged", J0, "You copied jacob0 unchanged: its rows are (v, ω). " + V_FIRST),
        Mistake("wrong_shift_sign", _p_cross(-p, Jg),
                "The reference-point shift has the wrong sign: v_s = ṗ - ω × p = ṗ + p × ω."),
        Mistake("shift_not_swapped", swap(_p_cross(p, Jg)),
                "The point shift is right but the rows are (v, ω). " + V_FIRST),
    ]
    st = (f"Robotics Toolbox's `jacob0` returns, for a 5-joint arm, the world-frame Jacobian of the tool point "
          f"with rows $(v, \\omega)$: \n\n$$J_0 = {bmatrix(J0, 4)}.$$\n\n"
          f"The tool pose is \n\n$$T_{{sb}} = {bmatrix(T, 4)}.$$\n\n"
          "Give the space Jacobian $J_s$ of Modern Robotics.")
    return Exercise("", "From Corke's jacob0 to the space Jacobian", st, {"J0": J0, "T_sb": T}, "numeric", ref,
                    mistakes, what="space Jacobian")


@register("ch07_ex3")
def _ch07_ex3(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_lwa = np.round(swap(J), 4)       # Pinocchio LOCAL_WORLD_ALIGNED: (v of the frame origin, omega) in world axes
    R = T[:3, :3]
    Jg = swap(J_lwa)
    ref = blockdiag(R.T, R.T) @ Jg
    mistakes = [
        Mistake("only_swapped", Jg,
                "You reordered the rows only. LOCAL_WORLD_ALIGNED uses the axes of the world frame; J_b needs "
                "both halves expressed in the tool frame."),
        Mistake("R_not_transposed", blockdiag(R, R) @ Jg,
                "You rotated with R_sb; to express world-axis vectors in {b}, multiply by R_sbᵀ."),
        Mistake("only_angular_rotated", blockdiag(R.T, np.eye(3)) @ Jg, "Only the angular half was rotated into {b}."),
        Mistake("only_linear_rotated", blockdiag(np.eye(3), R.T) @ Jg, "Only the linear half was rotated into {b}."),
        Mistake("not_swapped", blockdiag(R.T, R.T) @ J_lwa, "The rotation is right but the rows are (v, ω). "
                + V_FIRST),
    ]
    st = (f"Pinocchio's `getFrameJacobian(..., LOCAL_WORLD_ALIGNED)` gives, for the tool frame of a 5-joint arm, "
          f"rows $(v, \\omega)$ of the frame's origin in world axes: \n\n$$J_{{LWA}} = {bmatrix(J_lwa, 4)},$$\n\nat "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 4)}.$$\n\nGive the body Jacobian $J_b$ of Modern Robotics.")
    return Exercise("", "From Pinocchio's LOCAL_WORLD_ALIGNED to the body Jacobian", st,
                    {"J_lwa": J_lwa, "T_sb": T}, "numeric", ref, mistakes, what="body Jacobian")


def ref_from_pinocchio_world(J_world: ArrayLike) -> Array:
    """Reference: Pinocchio WORLD (v, omega) at the world origin -> MR J_s (omega, v)."""
    return swap(np.asarray(J_world, float))


@chain_case
def _world_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    J_s = space_jac(S, th)
    J_world = swap(J_s)
    T = fk(S, M, th)
    mistakes = [
        Mistake("unchanged", J_world, "Your function returns its input unchanged: WORLD rows are (v, ω). " + V_FIRST),
        Mistake("moved_point", space_jac(S, th) - np.vstack([np.zeros((3, J_s.shape[1])),
                                                            np.cross(T[:3, 3], J_s[:3].T).T]),
                "Your function moves the reference point to the tool. WORLD is already taken at the world origin, "
                "like J_s: only the row order differs."),
    ]
    return (J_world,), J_s, mistakes


register_code(
    "ch07_ex4", "Code: from Pinocchio's WORLD frame",
    "Pinocchio's `WORLD` Jacobian is the space Jacobian with rows $(v, \\omega)$. Write "
    "`from_pinocchio_world(J_world)` returning the Modern Robotics space Jacobian $J_s$ ($6\\times n$, "
    "numpy). Set `answer = from_pinocchio_world`.",
    reference=ref_from_pinocchio_world, make_case=_world_case, fn_name="from_pinocchio_world",
    what="space Jacobian")


# =================================================================== chapter 8

def link_space_jacobians(S: ArrayLike, theta: ArrayLike) -> Array:
    """(n, 6, n): link i's space Jacobian = J_s with the columns after i zeroed."""
    J_s = space_jac(S, theta)
    n = J_s.shape[1]
    return np.stack([J_s * (np.arange(n) <= i) for i in range(n)])


def link_poses(S: Array, link_homes: Array, theta: Array) -> Array:
    """The pose of every link's frame: (n, 4, 4)."""
    n = np.asarray(S).shape[1]
    out = []
    T = np.eye(4)
    for i in range(n):
        T = T @ expS(S[:, i], theta[i])
        out.append(T @ link_homes[i])
    return np.stack(out)


@register("ch08_ex1")
def _ch08_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    J_s = space_jac(arm.screw_axes, th)
    ref = link_space_jacobians(arm.screw_axes, th)[1]
    Tl = link_poses(arm.screw_axes, arm.link_homes, th)[1]
    mistakes = [
        Mistake("not_zeroed", J_s, "Column 3 should be zero: joint 3 comes after link 2 and does not move it."),
        Mistake("zeroed_wrong_side", J_s * (np.arange(3) >= 1),
                "You zeroed the wrong columns: link 2 is moved by joints 1 and 2, not by the joints after it."),
        Mistake("body_link", adj(inv_T(Tl)) @ ref, "This is the body Jacobian of link 2 (expressed in the link's "
                "frame). The exercise asks for its space Jacobian."),
        degrees_mistake(link_space_jacobians(arm.screw_axes, th_deg)[1]),
        swap_mistake(ref),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give the space Jacobian "
          "$J_{s,2}$ of link 2 ($6\\times3$: the map from all three joint rates to the spatial twist of link 2).")
    return Exercise("", "The space Jacobian of a middle link", st, {"lengths": ls, "theta_deg": th_deg}, "numeric",
                    ref, mistakes, what="link Jacobian")


def centre_jacobian(ls: Array, th: Array, link: int = 1) -> Array:
    """Geometric Jacobian (omega_s, pdot of the centre of link `link`, 0-based) of a planar arm."""
    arm = planar_chain(ls)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)[link]
    c = link_poses(S, arm.link_homes, th)[link][:3, 3]
    out = np.array(Jl, dtype=float)
    out[3:] = Jl[3:] - np.cross(c, Jl[:3].T).T
    return out


@register("ch08_ex2")
def _ch08_ex2(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)[1]
    ref = centre_jacobian(ls, th)
    T = fk(S, arm.home, th)
    Jtool = space_jac(S, th)
    Jtool[3:] = Jtool[3:] - np.cross(T[:3, 3], Jtool[:3].T).T
    q2 = fk(S[:, :1], np.eye(4), th[:1]) @ np.array([ls[0], 0, 0, 1.0])
    at_joint = Jl.copy()
    at_joint[3:] = Jl[3:] - np.cross(q2[:3], Jl[:3].T).T
    mistakes = [
        Mistake("tool_point", Jtool, "This is the geometric Jacobian of the tool. Link 2's centre is moved by "
                "joints 1 and 2 only, and its lever arms end at the centre."),
        Mistake("space_link", Jl, "This is the space Jacobian of link 2: its linear rows are the velocity of the "
                "point at the origin of {s}, not of the centre of link 2."),
        Mistake("at_joint_2", at_joint, "This is the velocity of the point at joint 2, not of the centre of link 2."),
        degrees_mistake(centre_jacobian(ls, th_deg)),
        swap_mistake(ref),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ (uniform links, centre of mass at the middle of each link) is "
          f"at $\\theta = {degs(th_deg)}$. Give the geometric Jacobian of the centre of link 2: the $6\\times3$ "
          "matrix with rows $(\\omega_2, \\dot p_{c2})$, both in {s}.")
    return Exercise("", "The geometric Jacobian of a link's centre of mass", st, {"lengths": ls, "theta_deg": th_deg},
                    "numeric", ref, mistakes, what="link Jacobian")


def mass_matrix_2r(ls: Array, ms: Array, th: Array, frame: str = "body", with_rotation: bool = True) -> Array:
    """The mass matrix of a planar 2R arm of uniform rods; the options give the two catalogued mistakes."""
    arm = planar_chain(ls)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)
    Tl = link_poses(S, arm.link_homes, th)
    M = np.zeros((2, 2))
    for i in range(2):
        Irot = np.diag([0.0, 1.0, 1.0]) * ms[i] * ls[i] ** 2 / 12 if with_rotation else np.zeros((3, 3))
        G = blockdiag(Irot, ms[i] * np.eye(3))
        J = adj(inv_T(Tl[i])) @ Jl[i] if frame == "body" else Jl[i]
        M += J.T @ G @ J
    return M


@register("ch08_ex3")
def _ch08_ex3(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    ms = np.round(rng.uniform(1.0, 4.0, size=2), 1)
    th_deg = angles_deg(rng, 2)
    th = th_deg * DEG
    ref = mass_matrix_2r(ls, ms, th)
    mistakes = [
        Mistake("no_rotational_inertia", mass_matrix_2r(ls, ms, th, with_rotation=False),
                "You left out the rotational inertia of the links (the 3x3 block of G_i): a rod spinning about its "
                "centre has kinetic energy too."),
        Mistake("space_jacobians", mass_matrix_2r(ls, ms, th, frame="space"),
                "You used the space Jacobians of the links with inertias G_i written in the link frames: the "
                "Jacobian and G_i must be in the same frame (use the body Jacobian of each link)."),
        degrees_mistake(mass_matrix_2r(ls, ms, th_deg)),
    ]
    st = (f"A planar 2R arm has uniform thin rods: lengths $L = {vec(ls, 1)}$ m, masses $m = {vec(ms, 1)}$ kg, "
          "centre of mass at the middle, rotational inertia $m_i l_i^2/12$ about the centre (about any axis "
          f"perpendicular to the rod). At $\\theta = {degs(th_deg)}$ give the mass matrix "
          "$M(\\theta) = \\sum_i J_{b,i}^T G_i J_{b,i}$ ($2\\times2$, kg m$^2$), with $J_{b,i}$ the body "
          "Jacobian of the frame at the centre of link $i$ and $G_i$ its spatial inertia.")
    return Exercise("", "The mass matrix from link Jacobians", st, {"lengths": ls, "masses": ms, "theta_deg": th_deg},
                    "numeric", ref, mistakes, what="mass matrix")


@chain_case
def _links_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    ref = link_space_jacobians(S, th)
    J_s = space_jac(S, th)
    n = S.shape[1]
    mistakes = [
        Mistake("not_zeroed", np.stack([J_s] * n), "Every link gets the full J_s: the columns of the joints after "
                "link i must be zero."),
        Mistake("zeroed_wrong_side", np.stack([J_s * (np.arange(n) >= i) for i in range(n)]),
                "You zeroed the columns before link i; zero those after it."),
        Mistake("off_by_one", np.stack([J_s * (np.arange(n) < i) for i in range(n)]),
                "Off by one: link i is moved by joints 1..i, including joint i itself."),
    ]
    return (S, th), ref, mistakes


register_code(
    "ch08_ex4", "Code: the Jacobians of every link",
    "Write `my_link_jacobians(S, theta)` returning an array of shape $(n, 6, n)$ whose entry `[i]` is the "
    "space Jacobian of link $i+1$ (0-based `i`). You may call `jacobians.space_jacobian` with "
    "`jacobians.SerialChain(S, np.eye(4))`, but not `link_jacobians`. Set `answer = my_link_jacobians`.",
    reference=link_space_jacobians, make_case=_links_case, fn_name="my_link_jacobians",
    what="stack of link Jacobians")


# =================================================================== chapter 9

@register("ch09_ex1")
def _ch09_ex1(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_b = J_b[:, :3].copy()
    J_s = np.round(adj(T) @ J_b, 4)
    F_b = rng.integers(-3, 4, size=6).astype(float)
    F_b[3:] = F_b[3:] if np.any(F_b[3:]) else np.array([0, 0, 1.0])
    ref = J_b.T @ F_b
    mistakes = [
        Mistake("frame_mismatch", J_s.T @ F_b,
                "You paired the space Jacobian with a wrench given in {b}. Power is FᵀV only when both are in "
                "the same frame: use J_b with F_b (or convert F_b to {s} first)."),
        Mistake("force_moment_swapped", J_b.T @ np.concatenate([F_b[3:], F_b[:3]]),
                "You read the wrench as (f, m). In this course wrenches are (m, f), moment first, matching (ω, v)."),
        Mistake("negated", -ref, "The sign is flipped: τ = JᵀF gives the joint torques that make the tool "
                "apply the wrench F."),
    ]
    st = (f"The first three joints of an arm have, at the current pose, the body Jacobian "
          f"\n\n$$J_b = {bmatrix(J_b, 4)}$$\n\nand the space Jacobian \n\n$$J_s = {bmatrix(J_s, 4)}.$$\n\n"
          "The tool must apply the "
          f"wrench $\\mathcal F_b = {vec(F_b)}$ (moment first, in the tool frame {{b}}). Give the joint torques "
          "$\\tau$ (3-vector).")
    return Exercise("", "Joint torques for a wrench", st, {"J_b": J_b, "J_s": J_s, "F_b": F_b}, "numeric", ref,
                    mistakes, what="torque vector")


def _pos_jac_planar(ls: Array, th: Array) -> Array:
    c = np.cumsum(th)
    x = -np.array([np.sum(ls[i:] * np.sin(c[i:])) for i in range(len(ls))])
    y = np.array([np.sum(ls[i:] * np.cos(c[i:])) for i in range(len(ls))])
    return np.stack([x, y])


@register("ch09_ex2")
def _ch09_ex2(rng: Generator) -> Exercise:
    ls = lengths(rng, 3)
    th_deg = angles_deg(rng, 3, step=30, low=-120, high=120)
    while abs(np.sin(th_deg[1] * DEG)) < 0.3 and abs(np.sin(th_deg[2] * DEG)) < 0.3:
        th_deg = angles_deg(rng, 3, step=30, low=-120, high=120)
    Jv = _pos_jac_planar(ls, th_deg * DEG)
    v = rng.integers(-3, 4, size=2).astype(float) / 2
    if not np.any(v):
        v[0] = 0.5
    ref = np.linalg.pinv(Jv) @ v
    mistakes = [
        Mistake("transpose", Jv.T @ v, "You used Jᵀ instead of the pseudoinverse: Jᵀ maps forces to torques; "
                "it does not invert the velocity map."),
        degrees_mistake(np.linalg.pinv(_pos_jac_planar(ls, th_deg)) @ v),
        Mistake("dls", Jv.T @ np.linalg.solve(Jv @ Jv.T + 0.01 * np.eye(2), v),
                "This is a damped solution; the exercise asks for the exact minimum-norm rates, the pseudoinverse."),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Its tool point must move at "
          f"$\\dot p = {vec(v)}$ (x and y, m/s). Give the joint rates of least norm that do it, "
          "$\\dot\\theta = J_v^{+}\\dot p$, with $J_v$ the $2\\times3$ position Jacobian.")
    return Exercise("", "Least-norm joint rates", st, {"lengths": ls, "theta_deg": th_deg, "p_dot": v}, "numeric",
                    ref, mistakes, what="joint rates")


@register("ch09_ex3")
def _ch09_ex3(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    while abs(np.sin(th_deg[1] * DEG)) < 0.2:
        th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    Jv = _pos_jac_planar(ls, th_deg * DEG)
    ref = np.sqrt(np.linalg.det(Jv @ Jv.T))
    Jd = _pos_jac_planar(ls, th_deg)
    mistakes = [
        Mistake("no_sqrt", np.linalg.det(Jv @ Jv.T), "You gave det(J Jᵀ); the manipulability is its square root."),
        degrees_mistake(np.sqrt(abs(np.linalg.det(Jd @ Jd.T)))),
        Mistake("trace", np.sqrt(np.trace(Jv @ Jv.T)), "You used the trace; the manipulability uses the determinant."),
    ]
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give Yoshikawa's "
          "manipulability $w = \\sqrt{\\det(J_v J_v^T)}$ of its $2\\times2$ position Jacobian $J_v$.")
    return Exercise("", "Manipulability of a 2R arm", st, {"lengths": ls, "theta_deg": th_deg}, "numeric", ref,
                    mistakes, what="manipulability")


def ref_dls_rates(J: ArrayLike, V: ArrayLike, lam: float) -> Array:
    """Damped least squares: J^T (J J^T + lam^2 I)^-1 V."""
    J = np.asarray(J, float)
    return J.T @ np.linalg.solve(J @ J.T + lam ** 2 * np.eye(J.shape[0]), np.asarray(V, float))


def _dls_case(rng: Generator) -> Case:
    m = int(rng.integers(2, 7))
    n = int(rng.integers(2, 8))
    J = rng.normal(size=(m, n))
    if rng.random() < 0.5 and m > 1:
        J[-1] = J[0] * 0.999            # close to singular: where damping matters
    V = rng.normal(size=m)
    lam = float(rng.choice([0.05, 0.1, 0.3]))
    ref = ref_dls_rates(J, V, lam)
    mistakes = [
        Mistake("no_damping", np.linalg.pinv(J) @ V, "Your function returns the pseudoinverse solution: the "
                "damping term is missing."),
        Mistake("lambda_not_squared", ref_dls_rates(J, V, np.sqrt(lam)),
                "The damping enters squared: Jᵀ(J Jᵀ + λ² I)⁻¹V."),
        Mistake("transpose_only", J.T @ V, "Your function returns JᵀV, without the inverse."),
    ]
    return Case((J, V, lam), ref, mistakes, f"a random {m}x{n} J, lambda = {lam}")


register_code(
    "ch09_ex4", "Code: damped least squares",
    "Write `my_dls_rates(J, V, lam)` returning the damped least-squares joint rates "
    "$\\dot\\theta = J^T(JJ^T + \\lambda^2 I)^{-1}\\mathcal V$ for any $m\\times n$ `J`, length-$m$ `V` and "
    "damping `lam` > 0. Set `answer = my_dls_rates`.",
    reference=ref_dls_rates, make_case=_dls_case, fn_name="my_dls_rates", what="joint rates")


@register("ch09_ex5")
def _ch09_ex5(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    while abs(np.sin(th_deg[1] * DEG)) < 0.2:
        th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    Jv = _pos_jac_planar(ls, th_deg * DEG)
    sv = np.linalg.svd(Jv, compute_uv=False)
    ref = sv
    mistakes = [
        Mistake("squared", sv ** 2, "These are the eigenvalues of J Jᵀ; the semi-axes are their square roots."),
        Mistake("ascending", sv[::-1], "Give the semi-axes from the longest to the shortest."),
        Mistake("inverse", 1 / sv, "These are the semi-axes of the force ellipsoid (1/σ); the velocity ellipsoid's "
                "are the singular values σ."),
        degrees_mistake(np.linalg.svd(_pos_jac_planar(ls, th_deg), compute_uv=False)),
    ]
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Unit-norm joint rates map to "
          "an ellipse of tool velocities. Give its two semi-axis lengths, longest first (a 2-vector).")
    return Exercise("", "The velocity ellipse", st, {"lengths": ls, "theta_deg": th_deg}, "numeric", ref, mistakes,
                    what="semi-axes")


@register("ch09_ex6")
def _ch09_ex6(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th1 = float(angles_deg(rng, 1)[0])

    def predicate(arr: Array) -> Feedback:
        if arr.size != 1:
            return Feedback(False, f"Give one number, θ₂ in radians; you gave {arr.size} values.",
                            mistake="wrong_shape")
        x = float(arr.ravel()[0])
        s = abs(np.sin(x))
        if s < 1e-3 and abs(np.cos(x) - 1) < 1e-3:
            return Feedback(False, "θ₂ = 0 (arm stretched) is singular, but the exercise asks for the other "
                            "one in (0, 2π).", mistake="excluded_zero")
        if s < 1e-3:
            return Feedback(True, "Right: with θ₂ = π the arm is folded back and det J_v = l1 l2 sin θ₂ = 0.",
                            "correct")
        if abs(x) > 2 * np.pi + 0.01 and abs(np.sin(x * DEG)) < 1e-3:
            return Feedback(False, "This looks like an angle in degrees; give it in radians.",
                            mistake="degrees_for_radians")
        return Feedback(False, f"At θ₂ = {x:.4g} rad det J_v is not zero: write det J_v as a function of "
                        "θ₂ and find where it vanishes.", mistake="not_singular")

    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ has $\\theta_1 = {int(th1)}^\\circ$. Apart from $\\theta_2 = 0$, "
          "give the value of $\\theta_2$ in radians, between 0 and $2\\pi$, at which its position Jacobian is "
          "singular.")
    return Exercise("", "A singular configuration", st, {"lengths": ls, "theta1_deg": th1}, "predicate", np.pi, [],
                    predicate=predicate, what="angle")
