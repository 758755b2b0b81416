"""Exercises of chapter 9: using the Jacobian (statics, inverse rates, manipulability)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

import jacobians as jac
from jacobians.grading import Case, Exercise, Mistake, numeric_exercise, scalar_exercise
from jacobians.grading.exercise import Interval
from jacobians.testing import EPS

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import pinv_steps, planar_jv
from ._kinematics import DEG, Array, adj
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import angles_deg, example_text, lengths, spatial_5r_pose


def _library_ch09_ex1(ex: Exercise) -> None:
    """The library's statics, τ = J_bᵀ F_b (``statics.joint_torques``): the torque of joint i is the power of F_b
    on the twist J_bi of that joint at unit rate. The data are exact short decimals: within TOL of |J| |F|."""
    J_b, F_b = ex.given["J_b"], ex.given["F_b"]
    assert_close(ex.solution(), jac.statics.joint_torques(J_b, F_b), "torques", scale=6 * size(J_b) * size(F_b))


@register("ch09_ex1", library=_library_ch09_ex1)
def _ch09_ex1(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_b = J_b[:, :3].copy()
    J_s = np.round(adj(T) @ J_b, 6)
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
          f"\n\n$$J_b = {bmatrix(J_b, 6)}$$\n\nand the space Jacobian \n\n$$J_s = {bmatrix(J_s, 6)}.$$\n\n"
          "The tool must apply the "
          f"wrench $\\mathcal F_b = {vec(F_b)}$ (moment first, in the tool frame {{b}}). Give the joint torques "
          "$\\tau$ (3-vector).")
    def method(r: Callable[[Any], Any]) -> Any:
        """J_bᵀ F_b of the printed (exact) data: sums of products, nothing rounded on the way."""
        return J_b.T @ F_b

    return numeric_exercise("Joint torques for a wrench", st, {"J_b": J_b, "J_s": J_s, "F_b": F_b}, ref, mistakes,
                            what="torque vector", method=method)


def _pos_jac_planar(ls: Array, th: Array) -> Array:
    c = np.cumsum(th)
    x = -np.array([np.sum(ls[i:] * np.sin(c[i:])) for i in range(len(ls))])
    y = np.array([np.sum(ls[i:] * np.cos(c[i:])) for i in range(len(ls))])
    return np.stack([x, y])


def _library_ch09_ex2(ex: Exercise) -> None:
    """The rates give the asked tool velocity through the library's J_v."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    J_v, rates = jac.geometric_jacobian(arm, th)[3:5], np.asarray(ex.solution(), dtype=float)
    # a residual: rounding relative to the terms of J_v θ̇ (|J_v| |θ̇|, large when θ̇ is, near a singularity), not to
    # the velocity: the solve's own error, κ(J_v) TOL |θ̇|, leaves the residual at TOL |J_v| |θ̇| (backward stability)
    assert_close(J_v @ rates, ex.given["p_dot"], "J_v θ̇",
                 scale=float(np.linalg.norm(J_v, 2) * np.linalg.norm(rates)) + float(np.abs(ex.given["p_dot"]).max()))


@register("ch09_ex2", library=_library_ch09_ex2)
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
    def method(r: Callable[[Any], Any]) -> Any:
        """J_v, J_v J_vᵀ, its inverse, J_v⁺; then J_v⁺ ṗ."""
        Jv = planar_jv(r, ls, th_deg * DEG)
        return pinv_steps(r, Jv) @ v

    return numeric_exercise("Least-norm joint rates", st, {"lengths": ls, "theta_deg": th_deg, "p_dot": v}, ref,
                            mistakes, what="joint rates", method=method)


def _regular_2r(rng: Generator) -> tuple[Array, Array, Array]:
    """A planar 2R arm away from its singularity (|sin θ2| >= 0.2): lengths, angles in degrees, and its
    2x2 position Jacobian."""
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    while abs(np.sin(th_deg[1] * DEG)) < 0.2:
        th_deg = angles_deg(rng, 2, step=15, low=-165, high=165)
    return ls, th_deg, _pos_jac_planar(ls, th_deg * DEG)


def _library_ch09_ex3(ex: Exercise) -> None:
    """The manipulability of the planar 2R arm is |det J_v| = l1 l2 |sin θ2|, also the library's."""
    L = ex.given["lengths"]
    th = np.radians(ex.given["theta_deg"])
    assert np.isclose(ex.solution(), L[0] * L[1] * abs(np.sin(th[1])))
    assert np.isclose(ex.solution(), abs(np.linalg.det(jac.geometric_jacobian(jac.robots.planar(L), th)[3:5])))


@register("ch09_ex3", library=_library_ch09_ex3)
def _ch09_ex3(rng: Generator) -> Exercise:
    ls, th_deg, Jv = _regular_2r(rng)
    ref = np.sqrt(np.linalg.det(Jv @ Jv.T))
    Jd = _pos_jac_planar(ls, th_deg)
    mistakes = [
        Mistake("no_sqrt", np.linalg.det(Jv @ Jv.T), "You gave det(J Jᵀ); the manipulability is its square root."),
        degrees_mistake(np.sqrt(abs(np.linalg.det(Jd @ Jd.T)))),
        Mistake("trace", np.sqrt(np.trace(Jv @ Jv.T)), "You used the trace; the manipulability uses the determinant."),
        Mistake("theta1_for_theta2", ls[0] * ls[1] * abs(np.sin(th_deg[0] * DEG)),
                "You used θ1 where θ2 belongs: det J_v of a planar 2R arm depends on the elbow angle θ2 only, "
                "not on θ1."),
    ]
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give Yoshikawa's "
          "manipulability $w = \\sqrt{\\det(J_v J_v^T)}$ of its $2\\times2$ position Jacobian $J_v$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """J_v, then |det J_v| (= sqrt(det(J_v J_vᵀ)) for a square J_v)."""
        J = planar_jv(r, ls, th_deg * DEG)
        return abs(J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0])

    return numeric_exercise("Manipulability of a 2R arm", st, {"lengths": ls, "theta_deg": th_deg}, ref, mistakes,
                            what="manipulability", method=method)


def ref_dls_rates(J: ArrayLike, V: ArrayLike, lam: float) -> Array:
    """Damped least squares: J^T (J J^T + lam^2 I)^-1 V."""
    J = np.asarray(J, float)
    return J.T @ np.linalg.solve(J @ J.T + lam ** 2 * np.eye(J.shape[0]), np.asarray(V, float))


def _dls_case(rng: Generator, damping: str) -> Case:
    m = int(rng.integers(2, 7))
    n = int(rng.integers(2, 8))
    J = rng.normal(size=(m, n))
    if rng.random() < 0.5 and m > 1:
        J[-1] = J[0] * 0.999            # close to singular: where damping matters
    V = rng.normal(size=m)
    # Given as mu = lam^2, the damping is drawn larger, so that the mistake of squaring it again
    # (mu^2) cannot pass for no damping at all: the checker can tell the two apart.
    lam = float(rng.choice([0.05, 0.1, 0.3] if damping == "lambda" else [0.3, 0.5, 0.7]))
    ref = ref_dls_rates(J, V, lam)
    mistakes = [
        Mistake("no_damping", np.linalg.pinv(J) @ V, "Your function returns the pseudoinverse solution: the "
                "damping term is missing."),
        Mistake("transpose_only", J.T @ V, "Your function returns JᵀV, without the inverse."),
    ]
    if damping == "lambda":
        mistakes.append(Mistake("lambda_not_squared", ref_dls_rates(J, V, np.sqrt(lam)),
                                "The damping enters squared: Jᵀ(J Jᵀ + λ² I)⁻¹V."))
        return Case((J, V, lam), ref, mistakes, f"a random {m}x{n} J, lam = {lam}")
    mu = lam ** 2
    mistakes.append(Mistake("mu_squared", ref_dls_rates(J, V, mu),
                            "You squared μ: in this variant the argument is already μ = λ², so the matrix to "
                            "invert is J Jᵀ + μ I."))
    return Case((J, V, mu), ref, mistakes, f"a random {m}x{n} J, mu = {mu:g}")


def ref_dls_rates_mu(J: ArrayLike, V: ArrayLike, mu: float) -> Array:
    """Reference of the second variant: the damping given as mu = lambda^2."""
    return ref_dls_rates(J, V, float(np.sqrt(mu)))


def _dls_example(rng: Generator, damping: str) -> tuple[str, dict[str, Any]]:
    """A 2 x 3 J and a V with one-decimal entries and a damping, with the rates the function must return."""
    J = np.round(rng.uniform(-1.0, 1.0, size=(2, 3)), 1)
    V = np.round(rng.uniform(-1.0, 1.0, size=2), 1)
    if damping == "lambda":
        lam = float(rng.choice([0.05, 0.1, 0.2, 0.3]))
        text = example_text("my_dls_rates(J, V, lam)", {"J": J, "V": V, "lam": lam}, ref_dls_rates(J, V, lam))
        return text, {"example_J": J, "example_V": V, "example_lam": lam}
    mu = float(rng.choice([0.04, 0.09, 0.25, 0.49]))
    text = example_text("my_dls_rates(J, V, mu)", {"J": J, "V": V, "mu": mu}, ref_dls_rates_mu(J, V, mu))
    return text, {"example_J": J, "example_V": V, "example_mu": mu}


def _library_ch09_ex4(ex: Exercise) -> None:
    """On every test case, the library's damped rates (``velocity.dls_rates``: gains σ/(σ² + λ²) from the SVD, no
    normal equations) against the reference (a solve with A = J Jᵀ + λ² I). The solve is backward stable, so its
    y = A⁻¹V is off by about κ(A) ops EPS |y| (κ(A) = (σ_max² + λ²)/λ_min(A), up to 1e4 at λ = 0.05), then
    multiplied by Jᵀ; the SVD route's gains are at most 1/(2λ), so its error is about ops EPS |V|/λ. The bound is
    512 EPS κ(A) max(1, |J| |y|, |V|/λ)."""
    for (J, V, d), out in reference_runs(ex):
        lam = float(d) if ex.given["damping"] == "lambda" else float(np.sqrt(d))
        A = J @ J.T + lam ** 2 * np.eye(J.shape[0])
        y = np.linalg.solve(A, V)
        scale = max(1.0, float(np.linalg.norm(J, 2) * np.linalg.norm(y)), float(np.linalg.norm(V)) / lam)
        bound = 512 * EPS * float(np.linalg.cond(A)) * scale
        assert_within(out, jac.velocity.dls_rates(J, V, lam), bound, "damped rates")


register_code("ch09_ex4", "Code: damped least squares", [
    CodeVariant("Write `my_dls_rates(J, V, lam)` returning the damped least-squares joint rates "
                "$\\dot\\theta = J^T(JJ^T + \\lambda^2 I)^{-1}\\mathcal V$ for any $m\\times n$ `J`, length-$m$ "
                "`V` and damping `lam` $= \\lambda > 0$. Set `answer = my_dls_rates`.",
                ref_dls_rates, lambda rng: _dls_case(rng, "lambda"), "my_dls_rates", "joint rates",
                {"damping": "lambda"}, example=lambda rng: _dls_example(rng, "lambda")),
    CodeVariant("Write `my_dls_rates(J, V, mu)` returning the damped least-squares joint rates "
                "$\\dot\\theta = J^T(JJ^T + \\mu I)^{-1}\\mathcal V$ for any $m\\times n$ `J`, length-$m$ "
                "`V` and damping `mu` $= \\mu = \\lambda^2 > 0$ (given already squared). "
                "Set `answer = my_dls_rates`.",
                ref_dls_rates_mu, lambda rng: _dls_case(rng, "mu"), "my_dls_rates", "joint rates",
                {"damping": "mu"}, example=lambda rng: _dls_example(rng, "mu")),
], library=_library_ch09_ex4)


def _library_ch09_ex5(ex: Exercise) -> None:
    """The two semi-axes σ1 >= σ2 >= 0 are fixed by σ1² + σ2² = |J_v|_F² and σ1 σ2 = |det J_v| (J_v the
    library's position rows, not the reference's formula; no SVD); both sides are sums of products of entries of
    size |J|, so within TOL of |J|²."""
    arm = jac.robots.planar(ex.given["lengths"])
    J = jac.geometric_jacobian(arm, np.radians(ex.given["theta_deg"]))[3:5]
    s1, s2 = (float(v) for v in ex.solution())
    assert s1 >= s2 >= 0.0, (s1, s2)
    scale = size(J) ** 2
    assert_close(s1 ** 2 + s2 ** 2, float(np.sum(J ** 2)), "sum of the squared semi-axes", scale=scale)
    assert_close(s1 * s2, abs(float(np.linalg.det(J))), "product of the semi-axes", scale=scale)


@register("ch09_ex5", library=_library_ch09_ex5)
def _ch09_ex5(rng: Generator) -> Exercise:
    ls, th_deg, Jv = _regular_2r(rng)
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
    def method(r: Callable[[Any], Any]) -> Any:
        """J_v, J_v J_vᵀ, its eigenvalues (largest first), their square roots."""
        Jv = planar_jv(r, ls, th_deg * DEG)
        eig = np.asarray(r(np.linalg.eigvalsh(np.asarray(r(Jv @ Jv.T)))[::-1]))
        return np.sqrt(np.maximum(eig, 0.0))

    return numeric_exercise("The velocity ellipse", st, {"lengths": ls, "theta_deg": th_deg}, ref, mistakes,
                            what="semi-axes", method=method)


def _library_ch09_ex6(ex: Exercise) -> None:
    """At θ2 = the answer (θ1 as given), the library's position Jacobian is singular: det J_v = 0 up to the
    rounding of θ2 (EPS |θ2| times |∂det/∂θ2| <= l1 l2) and of the products (TOL (l1 + l2)²); the answer lies in
    (0, 2π)."""
    L = ex.given["lengths"]
    th2 = float(ex.solution())
    assert 0.0 < th2 < 2 * np.pi, th2
    J = jac.geometric_jacobian(jac.robots.planar(L), np.array([np.radians(ex.given["theta1_deg"]), th2]))[3:5]
    assert_close(np.linalg.det(J), 0.0, "det J_v at the answer", scale=float(np.sum(L)) ** 2 * max(1.0, th2))


@register("ch09_ex6", library=_library_ch09_ex6)
def _ch09_ex6(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th1 = float(angles_deg(rng, 1)[0])
    mistakes = [
        Mistake("excluded_zero", 0.0, "θ₂ = 0 (the arm stretched out) is singular, but the statement leaves it "
                "out and asks for the other singular value, in (0, 2π)."),
        Mistake("excluded_two_pi", 2 * np.pi, "θ₂ = 2π is the stretched-out arm again (the same as θ₂ = 0), which "
                "the statement leaves out; the range (0, 2π) excludes it."),
        Mistake("degrees_for_radians", 180.0, "This is the angle in degrees; the exercise asks for radians "
                "(multiply by π/180)."),
    ]
    if abs(np.sin(th1 * DEG)) > 0.05:
        mistakes.append(Mistake("theta1_for_theta2", th1 * DEG, "This is θ₁ (in radians), which the statement gives; "
                                "the exercise asks for θ₂. The singularity depends on θ₂ only."))
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ has $\\theta_1 = {int(th1)}^\\circ$. Apart from $\\theta_2 = 0$, "
          "give the value of $\\theta_2$ in radians, in the range $(0, 2\\pi)$, at which its position Jacobian is "
          "singular.")
    return scalar_exercise("A singular configuration", st, {"lengths": ls, "theta1_deg": th1}, [np.pi], mistakes,
                           interval=Interval(0.0, 2 * np.pi, "(0, 2π)"), outside=[-np.pi, 3 * np.pi, -3 * np.pi],
                           what="angle", decimals=2,
                           hint="Write det J_v as a function of θ₂ (it is l₁ l₂ sin θ₂ for this arm) and find where it "
                           "vanishes in the range asked.")
