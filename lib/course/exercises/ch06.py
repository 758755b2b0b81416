"""Exercises of chapter 6: the analytic Jacobian."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import sympy as sp
from numpy.random import Generator

import jacobians as jac
from jacobians import lie, robots
from jacobians.grading import Exercise, Mistake, numeric_exercise, scalar_exercise, symbolic_exercise
from jacobians.grading.exercise import Interval
from jacobians.testing import fd_tol

from ._checks import assert_close, assert_within, size
from ._hand import euler_zyx_or_zyz
from ._kinematics import DEG, Array, blockdiag, body_jac, fk
from ._latex import bmatrix, degs, num
from ._mistakes import degrees_mistake, swap_mistake
from ._registry import register
from ._symbolic_2r import (
    describe_arm,
    distinct_sym,
    draw_arm,
    draw_shape,
    numeric_arm,
    sym_arm,
    sym_names,
    theta_mixups,
)
from ._variants import angles_deg


def _library_ch06_ex1(ex: Exercise) -> None:
    """At a point, the reference is finite differences of the library's forward kinematics of the numeric arm."""
    _, S, M, *_ = sym_arm(ex.given["joints"], ex.given["shape"])
    ref, chain, th = numeric_arm(ex.reference, S, M, ex.given["symbols"])
    point = lambda x: chain.fk(x)[:2, 3]  # noqa: E731
    # central differences within fd_tol of ∂p/∂θ (truncation h²/6 max|∂³p| plus rounding, from p itself); the
    # symbolic reference, evaluated to 15 digits, is within the closed form's share of that bound
    assert_within(ref, jac.numerical_jacobian(point, th), fd_tol(point, th), "reference")


@register("ch06_ex1", library=_library_ch06_ex1)
def _ch06_ex1(rng: Generator) -> Exercise:
    arm, shape = draw_arm(rng), draw_shape(rng)
    syms, S, M, J_s, J_b, B, T = sym_arm(arm, shape)
    th1, th2, l1, l2 = syms
    x, y = T[0, 3], T[1, 3]
    ref = sp.Matrix([[sp.diff(x, th1), sp.diff(x, th2)], [sp.diff(y, th1), sp.diff(y, th2)]])
    wrong_sign = sp.Matrix([[-ref[0, 0], -ref[0, 1]], [ref[1, 0], ref[1, 1]]])
    col1_eq_col2 = sp.Matrix([[ref[0, 1], ref[0, 1]], [ref[1, 1], ref[1, 1]]])
    mistakes = [
        Mistake("sign_row_1", wrong_sign, "Row 1 (the derivatives of x) has the wrong sign: differentiate cos "
                "carefully (d cos u = -sin u du)."),
        Mistake("column_1_is_column_2", col1_eq_col2,
                "Your column 1 repeats column 2: joint 1 moves the whole arm, link 1 included, so its column has "
                "a term of its own."),
        *theta_mixups(ref),
    ]
    if arm == ("R+", "R+") and shape == "x":
        only_l2 = sp.Matrix([[-l1 * sp.sin(th1), -l2 * sp.sin(th2)], [l1 * sp.cos(th1), l2 * sp.cos(th2)]])
        mistakes.append(Mistake("relative_angle", only_l2,
                                "Link 2's direction is θ1 + θ2 (absolute angle), not θ2 alone."))
    st = (describe_arm(arm, shape) + f" Its tool point is at $x = {sp.latex(x)}$, $y = {sp.latex(y)}$. Give the "
          "$2\\times2$ analytic (position) Jacobian $\\partial(x, y)/\\partial(\\theta_1, \\theta_2)$ as a sympy "
          "Matrix in `theta1, theta2, l1, l2` (real symbols).")
    ex = symbolic_exercise("Position Jacobian of a planar two-joint arm", st, sym_names(syms), ref,
                           distinct_sym(ref, mistakes), what="position Jacobian")
    ex.hint = "Entry (i, j) is the derivative of coordinate i (x, then y) with respect to θj: check that entry."
    ex.given.update({"joints": arm, "shape": shape, "x": x, "y": y})
    return ex


def _B(phi: Array, rep: str) -> Array:
    a, b = phi[0], phi[1]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    if rep == "zyx":
        return np.array([[0, -sa, ca * cb], [0, ca, sa * cb], [1, 0, -sb]])
    return np.array([[0, -sa, ca * sb], [0, ca, sa * sb], [1, 0, cb]])


def _library_ch06_ex2(ex: Exercise) -> None:
    """The library's map from Euler-angle rates to the angular velocity."""
    phi = np.radians(ex.given["phi_deg"])
    rates = jac.representations.rate_to_angular_velocity(phi, ex.given["representation"])
    np.testing.assert_allclose(ex.solution(), rates, atol=1e-12)


@register("ch06_ex2", library=_library_ch06_ex2)
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
    return numeric_exercise("From Euler-angle rates to angular velocity", st,
                            {"representation": rep, "phi_deg": phi_deg}, ref, mistakes, what="matrix B",
                            method=lambda r: euler_zyx_or_zyz(r, phi, rep),
                            hint="Column j of B is the axis of the j-th rotation, carried by the rotations before it.")


def _rot(phi: Array, rep: str) -> Array:
    a, b, c = phi
    last = "x" if rep == "zyx" else "z"
    return lie.rotation_about("z", a) @ lie.rotation_about("y", b) @ lie.rotation_about(last, c)


def _library_ch06_ex3(ex: Exercise) -> None:
    """The analytic Jacobian's angular rows are the angle rates: the library's B(φ) (ω_s = B φ̇) times them gives
    back the geometric Jacobian's angular rows, and the linear rows are ṗ unchanged. B⁻¹ carries cond(B), so the
    product is within TOL of cond(B) |J|."""
    J = ex.given["J"]
    B = jac.representations.rate_to_angular_velocity(np.radians(ex.given["phi_deg"]), "zyx")
    ref = ex.solution()
    assert_close(B @ ref[:3], J[:3], "angular rows times B", scale=float(np.linalg.cond(B)) * size(J))
    assert_close(ref[3:], J[3:], "linear rows")


@register("ch06_ex3", library=_library_ch06_ex3)
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
    def method(r: Callable[[Any], Any]) -> Any:
        """B(φ) from rounded cosines and sines, its inverse written down, then B⁻¹ times the angular rows."""
        Bi = np.asarray(r(np.linalg.inv(euler_zyx_or_zyz(r, phi_deg * DEG, "zyx"))))
        return np.vstack([r(Bi @ J[:3]), J[3:]])

    return numeric_exercise("The analytic Jacobian of a ZYX wrist", st, {"J": J, "phi_deg": phi_deg}, ref, mistakes,
                            what="analytic Jacobian", method=method)


#: Euler-angle sequences: Tait-Bryan (three different axes) lock at φ2 = ±π/2, proper Euler (first axis =
#: third) at φ2 = 0, π.
TAIT_BRYAN = ("zyx", "xyz", "yzx", "zxy", "xzy", "yxz")
PROPER = ("zyz", "zxz", "xyx", "xzx", "yxy", "yzy")

#: The ranges asked for φ2, per family: (low, high, as the statement writes it). Each holds one lock angle.
RANGES = {
    "tait-bryan": [(0.0, np.pi, "(0, π)"), (np.pi, 2 * np.pi, "(π, 2π)"), (-np.pi, 0.0, "(−π, 0)")],
    "proper": [(np.pi / 2, 3 * np.pi / 2, "(π/2, 3π/2)"), (-3 * np.pi / 2, -np.pi / 2, "(−3π/2, −π/2)"),
               (0.0, 2 * np.pi, "(0, 2π)")],
}


def lock_angles(family: str) -> list[float]:
    """The middle angles in [-4π, 4π] at which B(φ) of the family is singular."""
    base = np.pi / 2 if family == "tait-bryan" else 0.0
    return [base + k * np.pi for k in range(-5, 5) if abs(base + k * np.pi) <= 4 * np.pi + 1e-9]


def _euler_B(rep: str, phi: Array) -> Array:
    """B(φ) of any Euler sequence from its definition, with the library's rotations: column j is the j-th
    rotation's axis carried by the rotations before it (not the lock angles' formula)."""
    unit = {a: np.eye(3)[k] for k, a in enumerate("xyz")}
    cols, R = [], np.eye(3)
    for axis, angle in zip(rep, phi, strict=True):
        cols.append(R @ unit[axis])
        R = R @ lie.rotation_about(axis, angle)
    return np.column_stack(cols)


def _library_ch06_ex4(ex: Exercise) -> None:
    """At φ2 = the answer, B(φ) (of any φ1, φ3) loses rank: its smallest singular value is 0, up to the
    rounding of φ2 itself (EPS |φ2|, and σ_min moves at most at unit rate with φ2, the columns being unit
    vectors turned by φ2) and of the products (TOL); the answer lies in the range asked."""
    rep, (low, high) = ex.given["representation"], ex.given["range"]
    phi2 = float(ex.solution())
    assert low < phi2 < high, f"{phi2} outside ({low}, {high})"
    sigma = np.linalg.svd(_euler_B(rep, np.array([0.3, phi2, -0.2])), compute_uv=False)[-1]
    assert_within(sigma, 0.0, 1e-12 * max(1.0, abs(phi2)), "smallest singular value of B at the answer")


@register("ch06_ex4", library=_library_ch06_ex4)
def _ch06_ex4(rng: Generator) -> Exercise:
    rep = str(rng.choice(TAIT_BRYAN + PROPER))
    family = "tait-bryan" if rep in TAIT_BRYAN else "proper"
    other = "proper" if family == "tait-bryan" else "tait-bryan"
    low, high, text = RANGES[family][int(rng.integers(3))]
    locks = lock_angles(family)
    accepted = [a for a in locks if low < a < high]
    outside = [a for a in locks if not low < a < high]
    mistakes = [
        *[Mistake("degrees_for_radians", a * 180 / np.pi,
                  "This is the angle in degrees; the exercise asks for radians (multiply by π/180).")
          for a in accepted],
        *[Mistake("other_family", a,
                  f"That is where {'proper Euler' if other == 'proper' else 'Tait-Bryan'} angles (like "
                  f"{'ZYZ' if other == 'proper' else 'ZYX'}) lock. The sequence {rep.upper()} "
                  f"{'repeats its first axis' if family == 'proper' else 'has three different axes'}: find where "
                  "its B(φ) loses rank.")
          for a in lock_angles(other) if low < a < high],
    ]
    word = " ".join(f"R_{a}" for a in rep)
    tex = text.replace("π", "\\pi").replace("−", "-")
    st = (f"For the {rep.upper()} Euler angles, $R = R_{rep[0]}(\\phi_1)R_{rep[1]}(\\phi_2)R_{rep[2]}(\\phi_3)$, "
          f"give the value of the middle angle $\\phi_2$ in the range ${tex}$, in radians, at which $B(\\phi)$ "
          "(with $\\omega_s = B(\\phi)\\dot\\phi$) is singular, so that the angle rates cannot follow some "
          "angular velocities.")
    return scalar_exercise("Where Euler angles lock", st, {"representation": rep, "range": (low, high)}, accepted,
                           mistakes, interval=Interval(low, high, text), outside=outside, what="angle", decimals=2,
                           hint=f"Write B(φ) for {word} (its columns are the rotation axes, each carried by the "
                           "rotations before it) and find where det B, a function of φ2 only, vanishes.")


def _library_ch06_ex5(ex: Exercise) -> None:
    """The library's analytic Jacobian of the ZYX wrist (its rotation rows)."""
    th = np.radians(ex.given["theta_deg"])
    wrist = jac.robots.zyx_wrist(0.2)
    # Both are B(φ)⁻¹ J_ω by exact algebra, so they agree to TOL times the condition number of the solve with B;
    # here J_ω = B(θ) (the wrist's axes are the ZYX angles' axes), so κ(B) = κ(J_ω), at most 2 + √3 for |θ2| <= 60°.
    kappa = float(np.linalg.cond(jac.geometric_jacobian(wrist, th)[:3]))
    assert_close(ex.solution(), jac.analytic_jacobian(wrist, th)[:3], "analytic Jacobian", ops=kappa)


@register("ch06_ex5", library=_library_ch06_ex5)
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
    def method(r: Callable[[Any], Any]) -> Any:
        """Thought, not computed: the wrist's angular block of J has columns z, R_z(θ1) y, R_z(θ1)R_y(θ2) x, which
        is B(φ) at φ = θ, so B⁻¹ times it is the identity; nothing is rounded on the way."""
        return np.eye(3)

    return numeric_exercise("Angular block of the wrist's analytic Jacobian", st, {"theta_deg": th_deg}, ref, mistakes,
                            what="matrix", method=method)
