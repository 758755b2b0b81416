"""Exercises of chapter 4: space and body Jacobians side by side."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

import jacobians as jac
from jacobians import robots
from jacobians.chain import SerialChain
from jacobians.grading import Exercise, Mistake, numeric_exercise
from jacobians.testing import TOL, fd_tol

from ._checks import assert_close, assert_within, conjugated_columns, reference_runs, size
from ._hand import adjoint_steps, inverse_adjoint_steps, planar_jv, planar_points, planar_trig
from ._kinematics import Array, adj, blockdiag, body_jac, fk, inv_T, nearest_pose, space_jac
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import chain_case, exact_angle, planar_exact_state, planar_pose, worked_example


def _rrp_state(rng: Generator) -> tuple[SerialChain, Array, Array, Array, Array]:
    """The spatial RRP arm at angles with exact one-decimal cosines and sines: J_s, J_b and T_sb are exact short
    decimals (the rounding to 10 only removes binary noise), so the printed T_sb is a pose and the printed
    Jacobians are the data of the problem."""
    h, reach = float(rng.choice([0.5, 1.0])), float(rng.choice([1.0, 1.5]))
    arm = robots.spatial_rrp(h, reach)
    th = np.array([exact_angle(rng), exact_angle(rng), float(rng.choice([0.2, 0.4, 0.6]))])
    J_s = np.round(space_jac(arm.screw_axes, th), 10)
    T = np.round(fk(arm.screw_axes, arm.home, th), 10)
    J_b = np.round(adj(inv_T(T)) @ J_s, 10)
    return arm, th, J_s, J_b, T


def _rotonly(R: Array, J: Array) -> Array:
    return blockdiag(R, R) @ J


def _frame_change(given: str, J: Array, T: Array, ref: Array, mistakes: list[Mistake]) -> Exercise:
    """From J_s to J_b (``given="s"``) or back, at the pose T_sb; (v, omega) swapped is added to the mistakes.
    The method writes down the adjoint's lower-left block (and −Rᵀp for the inverse), then multiplies."""

    def method(r: Callable[[Any], Any]) -> Any:
        return (inverse_adjoint_steps(r, T) if given == "s" else adjoint_steps(r, T)) @ J

    target = "b" if given == "s" else "s"
    name = {"s": "space", "b": "body"}
    st = (f"At some configuration an arm has \n\n$$J_{given} = {bmatrix(J, 6)}$$\n\nand "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 6)}.$$\n\nGive its {name[target]} Jacobian $J_{target}$.")
    return numeric_exercise(f"From the {name[given]} to the {name[target]} Jacobian", st, {f"J_{given}": J, "T_sb": T},
                            ref, [*mistakes, swap_mistake(ref)], what=f"{name[target]} Jacobian", method=method)


def _library_ch04_ex1(ex: Exercise) -> None:
    """The library's change of frame, on the exact rotation nearest the printed one (the statement prints 4
    digits: the two differ by up to 1e-4 per entry, times |J| <= 2 or so, hence the 2e-3)."""
    key = "J_s" if "J_s" in ex.given else "J_b"
    change = jac.space_to_body if key == "J_s" else jac.body_to_space
    np.testing.assert_allclose(ex.solution(), change(ex.given[key], nearest_pose(ex.given["T_sb"])), atol=2e-3)


@register("ch04_ex1", library=_library_ch04_ex1)
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


def _library_ch04_ex2(ex: Exercise) -> None:
    """Each column of J_s is that column's twist of J_b seen from {s}, T_sb [J_bi] T_sb⁻¹ (4x4 products, not the
    adjoint's blocks); the printed T_sb is an exact pose (short decimals). Exact algebra on terms of size
    |T| |J_b| |T⁻¹|."""
    T, J_b = ex.given["T_sb"], ex.given["J_b"]
    assert_close(ex.solution(), conjugated_columns(T, J_b), "space Jacobian", scale=size(T) ** 2 * size(J_b))


@register("ch04_ex2", library=_library_ch04_ex2)
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


def ref_body_to_space(J_b: ArrayLike, T_sb: ArrayLike) -> Array:
    """Reference of the second variant: J_s = Ad_{T_sb} J_b."""
    return np.asarray(adj(T_sb) @ np.asarray(J_b, float), dtype=float)


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


def _b2s_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    T = fk(S, M, th)
    J_b = adj(inv_T(T)) @ space_jac(S, th)
    ref = adj(T) @ J_b
    mistakes = [
        Mistake("wrong_adjoint", adj(inv_T(T)) @ J_b, "You used Ad of T_bs = T_sb⁻¹; J_s needs Ad of T_sb."),
        Mistake("unchanged", J_b, "Your function returns J_b unchanged."),
        Mistake("rotation_only", _rotonly(T[:3, :3], J_b),
                "Your function only rotates the two halves (that gives the geometric Jacobian); J_s also needs "
                "the p × ω term in the linear part."),
        swap_mistake(ref),
    ]
    return (J_b, T), ref, mistakes


def _change_example(direction: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm of the seed at angles with exact one-decimal cosines and sines: its J_s (or J_b) and
    T_sb, short exact decimals (a pose as printed), and the Jacobian the function must return on them."""
    def build(rng: Generator) -> tuple[dict[str, Any], Any]:
        S, _, th, T = planar_exact_state(rng)
        J_s = np.round(space_jac(S, th), 10)
        J_b = np.round(adj(inv_T(T)) @ J_s, 10)
        return ({"J": J_s, "T_sb": T}, J_b) if direction == "space_to_body" else ({"J": J_b, "T_sb": T}, J_s)
    return worked_example("my_change_frame(J, T_sb)", build)


def _library_ch04_ex3(ex: Exercise) -> None:
    """On every test case, each column seen through T_bs = T_sb⁻¹ (to the body Jacobian) or T_sb (to the space
    one) by conjugation, as in ch04_ex2."""
    to_body = ex.given["direction"] == "space_to_body"
    for (J, T), out in reference_runs(ex):
        expected = conjugated_columns(np.linalg.inv(T) if to_body else T, J)
        assert_close(out, expected, "changed Jacobian", scale=size(T) ** 2 * size(J))


register_code("ch04_ex3", "Code: change the frame of a Jacobian", [
    CodeVariant("Write `my_change_frame(J, T_sb)` that takes the space Jacobian $J_s$ ($6\\times n$) and $T_{sb}$ "
                "($4\\times4$), numpy arrays, and returns the body Jacobian $J_b$. Do not call "
                "`jacobians.space_to_body`. Set `answer = my_change_frame`.",
                ref_space_to_body, chain_case(_s2b_case), "my_change_frame", "body Jacobian",
                {"direction": "space_to_body"}, example=_change_example("space_to_body")),
    CodeVariant("Write `my_change_frame(J, T_sb)` that takes the body Jacobian $J_b$ ($6\\times n$) and $T_{sb}$ "
                "($4\\times4$), numpy arrays, and returns the space Jacobian $J_s$. Do not call "
                "`jacobians.body_to_space`. Set `answer = my_change_frame`.",
                ref_body_to_space, chain_case(_b2s_case), "my_change_frame", "space Jacobian",
                {"direction": "body_to_space"}, example=_change_example("body_to_space")),
], library=_library_ch04_ex3)


#: The velocities ch04_ex4 may ask for: name, symbol, and how it comes from the joint rates.
VELOCITIES = {
    "body": ("the body twist $\\mathcal V_b = J_b\\dot\\theta$ of the tool frame", "body twist"),
    "space": ("the spatial twist $\\mathcal V_s = J_s\\dot\\theta$ of the tool frame", "spatial twist"),
    "geometric": ("the geometric velocity $(\\omega_s, \\dot p) = J\\dot\\theta$ of the tool point ($J$ the "
                  "geometric Jacobian)", "geometric velocity"),
}

#: What each velocity is, for the message naming it when another was asked.
_GIVEN_INSTEAD = {
    "body": "This is the body twist V_b = J_b θ̇ (both halves in the tool frame {b}).",
    "space": ("This is the spatial twist V_s = J_s θ̇: its linear part is the velocity of the body point at the "
              "origin of {s}, not of the tool point."),
    "geometric": ("This is the geometric velocity (ω_s, ṗ) = J θ̇: its linear part is the velocity ṗ of the tool "
                  "point, in {s}."),
}


def _library_ch04_ex4(ex: Exercise) -> None:
    """The asked velocity is the library's Jacobian times the rates; a geometric one's linear part is the tool
    point's velocity by finite differences."""
    g = ex.given
    arm = jac.robots.planar(g["lengths"])
    th = np.radians(g["theta_deg"])
    fn = {"body": jac.body_jacobian, "space": jac.space_jacobian, "geometric": jac.geometric_jacobian}
    np.testing.assert_allclose(ex.solution(), fn[g["asked"]](arm, th) @ g["theta_dot"], atol=1e-12)
    if g["asked"] == "geometric":
        point = lambda x: arm.fk(x)[:3, 3]  # noqa: E731
        J_fd = jac.numerical_jacobian(point, th)
        pdot = J_fd @ g["theta_dot"]
        # each entry of J_fd within fd_tol of ∂p/∂θ (truncation plus rounding, from p itself), so J_fd θ̇ within
        # fd_tol |θ̇|₁; the product and the closed form add TOL of the terms' size
        bound = (fd_tol(point, th) * float(np.abs(g["theta_dot"]).sum())
                 + TOL * size(ex.solution(), np.abs(J_fd).max() * np.abs(g["theta_dot"]).sum()))
        assert_within(ex.solution()[3:], pdot, bound, "linear part")


@register("ch04_ex4", library=_library_ch04_ex4)
def _ch04_ex4(rng: Generator) -> Exercise:
    asked = str(rng.choice(list(VELOCITIES)))
    ls, th_deg, th, arm = planar_pose(rng, 3)
    dth = rng.integers(-3, 4, size=3).astype(float) / 2
    if not np.any(dth):
        dth[0] = 1.0

    def velocities(theta: Array) -> dict[str, Array]:
        J_b = body_jac(arm.body_axes, theta)
        R = fk(arm.screw_axes, arm.home, theta)[:3, :3]
        return {"body": J_b @ dth, "space": space_jac(arm.screw_axes, theta) @ dth,
                "geometric": blockdiag(R, R) @ J_b @ dth}

    vel = velocities(th)
    ref = vel[asked]
    name = VELOCITIES[asked][1]
    mistakes = [Mistake(f"{other}_for_{asked}", v, _GIVEN_INSTEAD[other] + f" The exercise asks for the {name}.")
                for other, v in vel.items() if other != asked]
    J_asked = {"body": body_jac(arm.body_axes, th), "space": space_jac(arm.screw_axes, th)}.get(asked)
    mistakes += [
        degrees_mistake(velocities(th_deg)[asked]),
        swap_mistake(ref),
    ]
    if J_asked is not None:
        mistakes.append(Mistake("reversed_rates", J_asked @ dth[::-1], "The joint rates seem to be taken in the "
                                "reverse order: column i of the Jacobian multiplies θ̇_i."))
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ (tool frame at the end of link 3, oriented like link 3) is at "
          f"$\\theta = {degs(th_deg)}$ and its joints move at $\\dot\\theta = {vec(dth)}$ rad/s. Give "
          f"{VELOCITIES[asked][0]} as a 6-vector, angular part first.")
    hint = {"body": "Both halves are in the tool frame {b}: check the linear rows 4-6 with V_b = J_b θ̇.",
            "space": "The linear rows 4-6 are the velocity of the body point at the origin of {s}: v_s = ṗ - ω × p.",
            "geometric": "The linear rows 4-6 are ṗ, the velocity of the tool point in {s}."}[asked]
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin; ω = (0, 0, Σθ̇). Geometric: ṗ = J_v θ̇. Space: the joint points q_i, v_s = Σ (q_iy, −q_ix) θ̇_i.
        Body: ṗ = J_v θ̇ rotated into the tool frame, v_b = R_sbᵀ ṗ."""
        trig = planar_trig(r, th)
        w = np.array([0.0, 0.0, float(np.sum(dth))])
        if asked == "space":
            Q = planar_points(r, ls, trig)[:3]
            return np.concatenate([w, r(np.array([Q[:, 1] @ dth, -(Q[:, 0] @ dth), 0.0]))])
        p_dot = np.asarray(r(planar_jv(r, ls, th, trig) @ dth))
        if asked == "geometric":
            return np.concatenate([w, p_dot, [0.0]])
        c, s = trig[0][-1], trig[1][-1]
        return np.concatenate([w, r(np.array([c * p_dot[0] + s * p_dot[1], -s * p_dot[0] + c * p_dot[1]])), [0.0]])

    return numeric_exercise(f"The {name} from joint rates", st,
                            {"lengths": ls, "theta_deg": th_deg, "theta_dot": dth, "asked": asked}, ref, mistakes,
                            what=name, hint=hint, method=method)
