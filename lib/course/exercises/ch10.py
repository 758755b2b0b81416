"""Exercises of chapter 10: inverse kinematics with the Jacobian (the error twist, Newton and damped steps, the
Newton–Raphson loop)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike, NDArray

from jacobians import body_jacobian, geometric_jacobian, lie, robots, space_jacobian
from jacobians.chain import SerialChain
from jacobians.grading import Case, Exercise, Mistake, numeric_exercise
from jacobians.grading.feedback import verdict
from jacobians.ik import ik
from jacobians.jacobian import numerical_jacobian
from jacobians.testing import EPS, fd_tol, pose_tol
from jacobians.velocity import dls_rates, pinv_rates

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import adjoint_steps, log_se3_steps, planar_jv, planar_tip, planar_trig
from ._kinematics import DEG, Array, adj, inv_T
from ._latex import bmatrix, degs, num, vec
from ._mistakes import IK_MESSAGES, degrees_mistake, ik_mistake, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import angles_deg, example_text, lengths, planar_example, random_chain_data

# ----------------------------------------------------------------- exercise 1: the error twist

#: Cosine and sine pairs with short exact decimals (Pythagorean triples 3-4-5 and 7-24-25), and the quarter turn:
#: the rotations built from them have entries a student can type exactly.
_EXACT_CS = [(0.6, 0.8), (0.8, 0.6), (0.28, 0.96), (0.96, 0.28), (0.0, 1.0)]
_AXES = "xyz"


def _rot(axis: str, c: float, s: float) -> Array:
    """The rotation about a coordinate axis with cosine ``c`` and sine ``s`` (entries exact decimals)."""
    i = _AXES.index(axis)
    j, k = (i + 1) % 3, (i + 2) % 3
    R = np.eye(3)
    R[j, j], R[j, k], R[k, j], R[k, k] = c, -s, s, c
    return R


def _exact_rotation(rng: Generator) -> tuple[Array, str, float]:
    """A rotation about a random coordinate axis by an angle with exact-decimal cosine and sine; the axis and the
    angle (rad) too."""
    axis = _AXES[int(rng.integers(3))]
    c, s = _EXACT_CS[int(rng.integers(len(_EXACT_CS)))]
    s = s * float(rng.choice([-1.0, 1.0]))
    return _rot(axis, c, s), axis, float(np.arctan2(s, c))


def _pose_pair(rng: Generator) -> tuple[Array, Array, Array]:
    """T_sb, T_bd and T_sd = T_sb T_bd, every entry an exact short decimal; T_bd turns by at most 90 degrees
    and moves off its rotation axis (so that the twist's v is not the plain position difference)."""
    R1, _, _ = _exact_rotation(rng)
    quarter = _rot(_AXES[int(rng.integers(3))], 0.0, float(rng.choice([-1.0, 1.0])))
    T_sb = np.eye(4)
    T_sb[:3, :3] = quarter @ R1
    T_sb[:3, 3] = rng.integers(-4, 5, size=3) * 0.5
    R_bd, axis, _ = _exact_rotation(rng)
    p_bd = rng.integers(-2, 3, size=3) * 0.5
    off_axis = [k for k in range(3) if k != _AXES.index(axis)]
    if not np.any(p_bd[off_axis]):
        p_bd[off_axis[int(rng.integers(2))]] = 0.5
    T_bd = np.eye(4)
    T_bd[:3, :3], T_bd[:3, 3] = R_bd, p_bd
    T_sd = np.round(T_sb @ T_bd, 8)  # exact decimals: the rounding only removes binary noise
    return T_sb, T_bd, T_sd


def _library_ch10_ex1(ex: Exercise) -> None:
    """The error twist carries {b} onto {d} in unit time: T_sb e^[V_b] = T_sd, or e^[V_s] T_sb = T_sd, with the
    library's exp_se3 (the reference takes a log). The data are exact short decimals; an exponential and a 4x4
    product: within TOL of |T_sb| |e^[V]|."""
    g = ex.given
    E = lie.exp_se3(ex.solution())
    reached = g["T_sb"] @ E if g["asked"] == "body" else E @ g["T_sb"]
    assert_close(reached, g["T_sd"], "pose reached", scale=size(g["T_sb"]) * size(E))


@register("ch10_ex1", library=_library_ch10_ex1)
def _ch10_ex1(rng: Generator) -> Exercise:
    T_sb, _, T_sd = _pose_pair(rng)
    asked = str(rng.choice(["body", "space"]))
    V_b = lie.log_se3(lie.inverse_transform(T_sb) @ T_sd)
    V_s = adj(T_sb) @ V_b
    R, p = T_sb[:3, :3], T_sb[:3, 3]
    log_Tsd = lie.log_se3(T_sd) if np.linalg.norm(lie.log_so3(T_sd[:3, :3])) < np.pi - 0.2 else None
    if asked == "body":
        ref = V_b
        mistakes = [ik_mistake("space_for_body", V_s), ik_mistake("reversed_order", -V_b)]
        decoupled = np.concatenate([V_b[:3], R.T @ (T_sd[:3, 3] - p)])
    else:
        ref = V_s
        mistakes = [ik_mistake("body_for_space", V_b), ik_mistake("reversed_order", -V_s),
                    ik_mistake("wrong_adjoint", adj(lie.inverse_transform(T_sb)) @ V_b)]
        decoupled = np.concatenate([V_s[:3], T_sd[:3, 3] - p])
    if log_Tsd is not None:
        mistakes.append(ik_mistake("log_of_T_sd", log_Tsd))
    mistakes += [ik_mistake("decoupled_error", decoupled), swap_mistake(ref)]
    frame, sym = ("{b}", "\\mathcal V_b") if asked == "body" else ("{s}", "\\mathcal V_s")
    st = (f"The tool frame {{b}} of an arm is at \n\n$$T_{{sb}} = {bmatrix(T_sb, 6)}$$\n\nand the target pose is "
          f"\n\n$$T_{{sd}} = {bmatrix(T_sd, 6)}$$\n\n(positions in metres). Give the {asked} error twist "
          f"${sym} = (\\omega, v)$: the twist, expressed in {frame}, that carries {{b}} onto {{d}} in unit time "
          "(angular part first, ω in rad, v in m).")
    def method(r: Callable[[Any], Any]) -> Any:
        """T_bd = T_sb⁻¹ T_sd written down, its log step by step (θ, sin θ, ω̂, the coefficient of [ω̂]², v); for
        the space twist, [Ad_T_sb] with its block [p]R written down, times V_b."""
        V = log_se3_steps(r, np.asarray(r(inv_T(T_sb) @ T_sd)))
        return V if asked == "body" else adjoint_steps(r, T_sb) @ V

    return numeric_exercise(f"The {asked} error twist", st, {"T_sb": T_sb, "T_sd": T_sd, "asked": asked}, ref,
                            mistakes, what="error twist", method=method)


# ----------------------------------------------------------------- exercise 2: one Newton step, planar 2R

def _tool_point(arm: SerialChain, theta: ArrayLike) -> Array:
    return np.asarray(arm.fk(theta)[:2, 3], dtype=float)


def _position_jacobian(arm: SerialChain, theta: ArrayLike) -> Array:
    """J_v: the x, y rows of the linear part of the geometric Jacobian (∂p/∂θ of the tool point)."""
    return np.asarray(geometric_jacobian(arm, theta)[3:5], dtype=float)


def _library_ch10_ex2(ex: Exercise) -> None:
    """The step solves the linearised error with J_v by central differences of the library's forward kinematics
    (not its Jacobian): J_fd Δθ = p_d − p(θ_k). J_fd is within ε = fd_tol of J_v entry by entry, so the residual
    is within ε |Δθ|₁, plus the rounding of the reference's solve (TOL cond(J_v) of |J_v| |Δθ| + |e|)."""
    g = ex.given
    arm = robots.planar([float(v) for v in g["lengths"]])
    th = np.radians(g["theta_deg"])

    def tip(t: Array) -> Array:
        return _tool_point(arm, t)

    J_fd = numerical_jacobian(tip, th)
    step, e = ex.solution() - th, g["p_d"] - tip(th)
    bound = (fd_tol(tip, th) * float(np.sum(np.abs(step)))
             + 1e-12 * float(np.linalg.cond(J_fd)) * size(2 * size(J_fd) * size(step), e))
    assert_within(J_fd @ step, e, bound, "linearised position error after the step")


@register("ch10_ex2", library=_library_ch10_ex2)
def _ch10_ex2(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    th_deg = angles_deg(rng, 2, step=15, low=-150, high=150)
    while abs(np.sin(th_deg[1] * DEG)) < 0.4:
        th_deg = angles_deg(rng, 2, step=15, low=-150, high=150)
    arm = robots.planar([float(v) for v in ls])
    th = th_deg * DEG
    while True:  # a target near enough that the step brings the tool closer (Newton's method at work)
        offset = angles_deg(rng, 2, step=5, low=-20, high=20, nonzero=False)
        if not np.any(offset):
            continue
        p_d = np.round(_tool_point(arm, th + offset * DEG), 2)
        e = p_d - _tool_point(arm, th)
        J_v = _position_jacobian(arm, th)
        step = np.linalg.solve(J_v, e)
        ref = th + step
        if np.linalg.norm(p_d - _tool_point(arm, ref)) < 0.5 * np.linalg.norm(e):
            break
    mistakes = [
        ik_mistake("wrong_sign", th - step),
        ik_mistake("step_only", step),
        ik_mistake("answer_in_degrees", np.degrees(ref)),
        ik_mistake("transpose_step", th + J_v.T @ e),
    ]
    J_deg = _position_jacobian(arm, th_deg)  # the angles in degrees fed to sin and cos
    if abs(np.linalg.det(J_deg)) > 1e-2:
        mistakes.append(degrees_mistake(th_deg + np.linalg.solve(J_deg, p_d - _tool_point(arm, th_deg))))
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ m is at $\\theta_k = {degs(th_deg)}$. Its tool point must reach "
          f"$p_d = {vec(p_d, 2)}$ m ($x$, $y$ in {{s}}). Take one Newton–Raphson step on the position error, "
          "$\\theta_{k+1} = \\theta_k + J_v(\\theta_k)^{-1}\\big(p_d - p(\\theta_k)\\big)$, with $J_v$ the "
          "$2\\times2$ Jacobian of the tool point's $(x, y)$. Give $\\theta_{k+1}$ in radians (a 2-vector).")
    def method(r: Callable[[Any], Any]) -> Any:
        """θ_k in radians, cos and sin, p(θ_k), J_v, the error e, the step Δθ, then θ_k + Δθ."""
        t = r(th)
        trig = planar_trig(r, th)
        e = r(p_d - planar_tip(r, ls, th, trig))
        return t + r(np.linalg.solve(planar_jv(r, ls, th, trig), e))

    return numeric_exercise("One Newton–Raphson step", st, {"lengths": ls, "theta_deg": th_deg, "p_d": p_d}, ref,
                            mistakes, what="joint values", method=method)


# ----------------------------------------------------------------- exercise 3: one damped step near a singularity

def _library_ch10_ex3(ex: Exercise) -> None:
    """The step minimises |J Δθ − e|² + λ²|Δθ|²: the gradient J_fdᵀ(J_fd Δθ − e) + λ² Δθ vanishes, J_fd by central
    differences of the library's forward kinematics. With E = J_fd − J (|E_ij| <= ε = fd_tol) the gradient moves by
    Eᵀ(J_fd Δθ − e − E Δθ) + J_fdᵀ E Δθ, at most ε (|J_fd Δθ − e|₁ + ε |Δθ|₁ + max_j |J_fd,j|₁ |Δθ|₁); the reference
    (the library's SVD route, gains <= 1/(2λ)) is off by about 512 EPS |e|/λ, which the gradient multiplies by
    |J|² + λ²."""
    g = ex.given
    arm = robots.planar([float(v) for v in g["lengths"]])
    th, lam = np.radians(g["theta_deg"]), float(g["lam"])

    def tip(t: Array) -> Array:
        return _tool_point(arm, t)

    J, e, d = numerical_jacobian(tip, th), g["p_d"] - tip(th), ex.solution()
    eps = fd_tol(tip, th)
    r = J @ d - e
    d1 = float(np.sum(np.abs(d)))
    bound = (eps * (float(np.sum(np.abs(r))) + eps * d1 + float(np.max(np.sum(np.abs(J), axis=0))) * d1)
             + 512 * EPS * (float(np.linalg.norm(J, 2)) ** 2 + lam ** 2) * float(np.linalg.norm(e)) / lam)
    assert_within(J.T @ r + lam ** 2 * d, np.zeros_like(d), bound, "gradient of the damped cost at the step")


@register("ch10_ex3", library=_library_ch10_ex3)
def _ch10_ex3(rng: Generator) -> Exercise:
    n = int(rng.choice([2, 3]))
    ls = lengths(rng, n)
    th_deg = np.concatenate([angles_deg(rng, 1, step=15, low=-150, high=150),
                             rng.choice([-10.0, -5.0, 5.0, 10.0], size=n - 1)])
    lam = float(rng.choice([0.1, 0.2, 0.3]))
    arm = robots.planar([float(v) for v in ls])
    th = th_deg * DEG
    p = _tool_point(arm, th)
    direction = float(rng.choice(np.arange(30, 360, 30))) * DEG + float(np.sum(th))
    p_d = np.round(p + float(rng.choice([0.2, 0.3, 0.4])) * np.array([np.cos(direction), np.sin(direction)]), 2)
    e = p_d - p
    J_v = _position_jacobian(arm, th)
    ref = dls_rates(J_v, e, lam)
    mistakes = [
        ik_mistake("lambda_not_squared", dls_rates(J_v, e, float(np.sqrt(lam)))),
        ik_mistake("no_damping", pinv_rates(J_v, e)),
        ik_mistake("wrong_sign", -ref),
        ik_mistake("transpose_only", J_v.T @ e),
        ik_mistake("theta_for_step", th + ref),
        ik_mistake("answer_in_degrees", np.degrees(ref)),
    ]
    st = (f"A planar {n}R arm with $L = {vec(ls, 1)}$ m is at $\\theta_k = {degs(th_deg)}$, close to its "
          f"stretched-out singularity. Its tool point must move to $p_d = {vec(p_d, 2)}$ m ($x$, $y$ in {{s}}). "
          f"Take one damped least-squares step with $\\lambda = {num(lam)}$: give "
          "$\\Delta\\theta = (J_v^TJ_v + \\lambda^2I)^{-1}J_v^T\\big(p_d - p(\\theta_k)\\big)$ in radians "
          f"(a {n}-vector), with $J_v$ the $2\\times{n}$ Jacobian of the tool point's $(x, y)$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, p(θ_k), e, J_v, J_vᵀJ_v + λ²I, J_vᵀe; then solve."""
        trig = planar_trig(r, th)
        e = np.asarray(r(p_d - planar_tip(r, ls, th, trig)))
        Jv = planar_jv(r, ls, th, trig)
        A = np.asarray(r(Jv.T @ Jv + lam ** 2 * np.eye(n)))
        return np.linalg.solve(A, np.asarray(r(Jv.T @ e)))

    return numeric_exercise("A damped step near a singularity", st,
                            {"lengths": ls, "theta_deg": th_deg, "p_d": p_d, "lam": lam}, ref, mistakes,
                            what="joint step", method=method)


# ----------------------------------------------------------------- exercise 4: code the Newton–Raphson loop

def _chain(axes: Array, M: Array, frame: str) -> SerialChain:
    S = adj(M) @ axes if frame == "body" else axes
    return SerialChain(S, M)


def ref_ik_body(Blist: ArrayLike, M: ArrayLike, T_sd: ArrayLike, theta0: ArrayLike, eps_omega: float,
                eps_v: float, max_iterations: int) -> Array:
    """IKinBody: the library's ``ik`` in the body frame; returns θ."""
    chain = _chain(np.asarray(Blist, float), np.asarray(M, float), "body")
    return ik(chain, T_sd, theta0, frame="body", eps_omega=eps_omega, eps_v=eps_v,
              max_iterations=max_iterations).theta


def ref_ik_space(Slist: ArrayLike, M: ArrayLike, T_sd: ArrayLike, theta0: ArrayLike, eps_omega: float,
                 eps_v: float, max_iterations: int) -> Array:
    """IKinSpace: the library's ``ik`` in the space frame; returns θ."""
    chain = _chain(np.asarray(Slist, float), np.asarray(M, float), "space")
    return ik(chain, T_sd, theta0, frame="space", eps_omega=eps_omega, eps_v=eps_v,
              max_iterations=max_iterations).theta


class _Kin:
    """Plain-numpy kinematics of one chain for the search of test cases (no input checks: about ten times faster
    than the library's checked functions): the pose, the space and body Jacobians, the error twist, the Newton
    step. Same formulas as the library; the reference itself is always the library's ``ik``, and a case is kept
    only if its results come out the same from a start moved by 1e-11, far more than the two differ by."""

    def __init__(self, chain: SerialChain) -> None:
        self.S = np.asarray(chain.screw_axes, dtype=float)
        self.M = np.asarray(chain.home, dtype=float)
        w, self.v = self.S[:3].T, self.S[3:].T
        n = w.shape[0]
        self.K = np.zeros((n, 3, 3))   # [ω_i] of every joint, and its square
        self.K[:, 0, 1], self.K[:, 0, 2], self.K[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
        self.K[:, 1, 0], self.K[:, 2, 0], self.K[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
        self.K2 = self.K @ self.K
        self.revolute = np.any(w != 0.0, axis=1)

    @staticmethod
    def _skew(w: Array) -> Array:
        return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])

    @staticmethod
    def _adj(T: Array) -> Array:
        R, p = T[:3, :3], T[:3, 3]
        A = np.zeros((6, 6))
        A[:3, :3] = A[3:, 3:] = R
        A[3:, :3] = _Kin._skew(p) @ R
        return A

    def _exps(self, th: Array) -> Array:
        """e^[S_i]θ_i of every joint (n, 4, 4), all at once: Rodrigues for a revolute joint, a shift for a
        prismatic one."""
        s, c = np.sin(th)[:, None, None], np.cos(th)[:, None, None]
        t = th[:, None, None]
        rev = self.revolute[:, None, None]
        R = np.eye(3) + s * self.K + (1.0 - c) * self.K2
        G = t * np.eye(3) + (1.0 - c) * self.K + (t - s) * self.K2
        E = np.zeros((len(th), 4, 4))
        E[:, :3, :3] = np.where(rev, R, np.eye(3))
        E[:, :3, 3] = np.where(rev[:, :, 0], (G @ self.v[:, :, None])[:, :, 0], self.v * th[:, None])
        E[:, 3, 3] = 1.0
        return E

    def pose_jacobian(self, th: Array, frame: str) -> tuple[Array, Array]:
        """T_sb(θ) and the Jacobian of ``frame`` (J_b = [Ad_T⁻¹] J_s)."""
        E = self._exps(np.asarray(th, dtype=float))
        n = self.S.shape[1]
        J = np.empty((6, n))
        T = np.eye(4)
        for i in range(n):
            J[:, i] = self._adj(T) @ self.S[:, i]
            T = T @ E[i]
        T = T @ self.M
        return T, (J if frame == "space" else self._adj(_Kin.inverse(T)) @ J)

    @staticmethod
    def inverse(T: Array) -> Array:
        out = np.eye(4)
        out[:3, :3] = T[:3, :3].T
        out[:3, 3] = -T[:3, :3].T @ T[:3, 3]
        return out

    @staticmethod
    def log(T: Array) -> Array:
        """log(T)^∨ as the library computes it (its branch near θ = π is the library's own)."""
        R, p = T[:3, :3], T[:3, 3]
        c = 0.5 * (np.trace(R) - 1.0)
        if c < -0.99:
            return np.asarray(lie.log_se3(T), dtype=float)
        a = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
        s = float(np.linalg.norm(a))
        theta = float(np.arctan2(s, c))
        small = theta < 1e-4  # the library's switch to the series
        w = a * (1.0 + theta * theta / 6.0 if small else theta / s)
        half = 0.5 * theta
        gamma = (1.0 / 12.0 + theta * theta / 720.0 if small
                 else (1.0 - half * np.cos(half) / np.sin(half)) / (theta * theta))
        K = _Kin._skew(w)
        return np.concatenate([w, (np.eye(3) - 0.5 * K + gamma * (K @ K)) @ p])

    @staticmethod
    def pinv_step(J: Array, V: Array) -> Array:
        """J⁺V from the SVD, singular values below 1e-15 σ_max dropped (the library's ``pinv_rates``)."""
        U, sv, Vt = np.linalg.svd(J, full_matrices=False)
        keep = sv > 1e-15 * sv[0]
        gain = np.where(keep, 1.0 / np.where(keep, sv, 1.0), 0.0)
        out: Array = Vt.T @ (gain * (U.T @ V))
        return out


def newton_loop(chain: SerialChain, T_sd: Array, theta0: Array, eps_omega: float, eps_v: float,
                max_iterations: int, *, jacobian: str = "body", error: str = "body", step: str = "pinv",
                stop: str = "both") -> tuple[Array, list[tuple[float, float]]]:
    """The Newton–Raphson loop written out, with switches that make the chapter's mistakes: the Jacobian
    (``"body"``/``"space"``), the error twist (``"body"``, ``"space"``, ``"reversed"`` = minus the twist of
    ``jacobian``'s frame, ``"log_T_sd"``), the step (``"pinv"``, ``"transpose"``) and the stopping test
    (``"both"``, ``"either"``, ``"norm_omega"``, ``"norm_v"``, ``"never"``: always ``max_iterations`` steps).
    Returns θ and the (‖ω‖, ‖v‖) of every iterate."""
    th = np.array(theta0, dtype=float)
    seen: list[tuple[float, float]] = []
    kin = _Kin(chain)
    log_T_sd = kin.log(T_sd)
    for k in range(max_iterations + 1):
        T, J = kin.pose_jacobian(th, jacobian)
        V_b = kin.log(kin.inverse(T) @ T_sd)
        V_s = kin._adj(T) @ V_b
        own = V_b if jacobian == "body" else V_s
        V = {"body": V_b, "space": V_s, "reversed": -own, "log_T_sd": log_T_sd}[error]
        w, v = float(np.linalg.norm(V[:3])), float(np.linalg.norm(V[3:]))
        seen.append((w, v))
        nrm = float(np.linalg.norm(V))
        done = {"both": w <= eps_omega and v <= eps_v, "either": w <= eps_omega or v <= eps_v,
                "norm_omega": nrm <= eps_omega, "norm_v": nrm <= eps_v, "never": False}[stop]
        if done or k == max_iterations:
            break
        th = th + (kin.pinv_step(J, V) if step == "pinv" else J.T @ V)
        if not np.all(np.isfinite(th)) or np.abs(th).max() > 1e6:
            break
    return th, seen


#: The mistakes of the code exercise that change the iterates (error twist, step): name -> newton_loop's switches,
#: for each form (body, space). The mistakes of the stop test and of the step budget leave the iterates as they are
#: and only stop elsewhere: :data:`_STOP_MISTAKES`.
_ITERATE_MISTAKES: dict[str, dict[str, dict[str, str]]] = {
    "body": {"space_twist_for_body": {"error": "space"}, "reversed_error": {"error": "reversed"},
             "log_of_T_sd": {"error": "log_T_sd"}, "transpose_step": {"step": "transpose"}},
    "space": {"body_twist_for_space": {"error": "body"}, "reversed_error": {"error": "reversed"},
              "log_of_T_sd": {"error": "log_T_sd"}, "transpose_step": {"step": "transpose"}},
}

#: Modern Robotics' fixed number of steps (IKinBody, IKinSpace), which a loop that ignores max_iterations uses.
MR_STEPS = 20


def _close(a: Array, b: Array, scale: float = 1.0) -> bool:
    """Within ``scale`` times the tolerance a function answer is graded to (rtol 1e-6, atol 1e-8)."""
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= scale * (1e-8 + 1e-6 * np.abs(b))))


class _Trail(NamedTuple):
    """The iterates θ_0 .. θ_K of the right loop run without a stop test (K = :data:`MR_STEPS` at most), and the
    (‖ω‖, ‖v‖, ‖V‖) of the error twist at each."""

    thetas: list[Array]
    norms: list[tuple[float, float, float]]


def _trails(chain: SerialChain, T_sd: Array, starts: Array, frame: str, steps: int = MR_STEPS) -> list[_Trail]:
    """The trails from several starts (rows of ``starts``)."""
    return [_trail(chain, T_sd, th0, frame, steps) for th0 in starts]


def _trail(chain: SerialChain, T_sd: Array, th0: Array, frame: str, steps: int = MR_STEPS) -> _Trail:
    """The iterates of the right loop from ``th0`` with no stop test, for ``steps`` steps (:class:`_Kin`); the trail
    ends before an iterate that is not finite or beyond 1e3 rad (the loop blew up)."""
    kin = _Kin(chain)
    th = np.array(th0, dtype=float)
    thetas: list[Array] = []
    norms: list[tuple[float, float, float]] = []
    for k in range(steps + 1):
        T, J = kin.pose_jacobian(th, frame)
        V = kin.log(kin.inverse(T) @ T_sd)
        if frame == "space":
            V = kin._adj(T) @ V
        thetas.append(th)
        norms.append((float(np.linalg.norm(V[:3])), float(np.linalg.norm(V[3:])), float(np.linalg.norm(V))))
        if k == steps:
            break
        if norms[-1][2] < 1e-13:  # converged to rounding: the steps after it move θ by about 1e-16, far below the
            thetas += [th] * (steps - k)   # checker's tolerance (1e-8 + 1e-6 |θ|); they are not computed
            norms += [norms[-1]] * (steps - k)
            break
        th = th + kin.pinv_step(J, V)
        if not np.all(np.isfinite(th)) or np.abs(th).max() > 1e3:
            break
    return _Trail(thetas, norms)


def trail_by_library(chain: SerialChain, T_sd: Array, th0: Array, frame: str, steps: int = MR_STEPS) -> _Trail:
    """The trail of :func:`_trail` computed with the library's checked functions (the tests compare the two)."""
    th = np.array(th0, dtype=float)
    thetas: list[Array] = []
    norms: list[tuple[float, float, float]] = []
    for k in range(steps + 1):
        T = chain.fk(th)
        V = lie.log_se3(lie.inverse_transform(T) @ T_sd)
        if frame == "space":
            V = adj(T) @ V
        thetas.append(th)
        norms.append((float(np.linalg.norm(V[:3])), float(np.linalg.norm(V[3:])), float(np.linalg.norm(V))))
        if k == steps:
            break
        J = body_jacobian(chain, th) if frame == "body" else space_jacobian(chain, th)
        th = th + pinv_rates(J, V, rcond=1e-15)
        if not np.all(np.isfinite(th)) or np.abs(th).max() > 1e3:
            break
    return _Trail(thetas, norms)


def _stop_at(trail: _Trail, rule: str, eps_w: float, eps_v: float, budget: int) -> Array | None:
    """θ where a loop with stop test ``rule`` and at most ``budget`` steps stops on the trail (None if the trail
    is too short: the iterates blew up before)."""
    tests = {"both": lambda w, v, n: w <= eps_w and v <= eps_v, "either": lambda w, v, n: w <= eps_w or v <= eps_v,
             "norm_omega": lambda w, v, n: n <= eps_w, "norm_v": lambda w, v, n: n <= eps_v,
             "never": lambda w, v, n: False}
    for k, (w, v, n) in enumerate(trail.norms):
        if tests[rule](w, v, n) or k == budget:
            return trail.thetas[k]
    return None


#: The mistakes of the stop test and of the step budget: name -> (stop rule, budget from max_iterations k).
_STOP_MISTAKES: dict[str, tuple[str, Callable[[int], int]]] = {
    "stop_on_either": ("either", lambda k: k),
    "stop_on_norm_eps_omega": ("norm_omega", lambda k: k),
    "stop_on_norm_eps_v": ("norm_v", lambda k: k),
    "ignores_max_iterations": ("both", lambda k: MR_STEPS),
    "fixed_steps": ("never", lambda k: MR_STEPS),
    "one_step_short": ("both", lambda k: k - 1),
    "one_step_over": ("both", lambda k: k + 1),
}


def _mistakes_of(chain: SerialChain, T_sd: Array, th0: Array, eps_w: float, eps_v: float, k_max: int, frame: str,
                 ref: Array, rng: Generator) -> list[Mistake] | None:
    """The catalogued mistakes on one test: every named loop's result that differs from the reference and comes
    out the same from a start moved by 1e-11 (a loop that wanders is not reproducible, so it names nothing).
    Two mistakes may give the same result on one test: both are kept, and the checker names one only where the
    tests tell them apart. None if the reference itself is not reproducible (the test is then drawn again)."""
    nudge = 1e-11 * rng.normal(size=len(th0))
    trail, moved = _trails(chain, T_sd, np.stack([th0, th0 + nudge]), frame)
    again = _stop_at(moved, "both", eps_w, eps_v, k_max)
    if again is None or not _close(again, ref, 0.01):
        return None
    mistakes: list[Mistake] = []

    def keep(name: str, val: Array | None, val_moved: Array | None) -> None:
        if val is None or val_moved is None or not np.all(np.isfinite(val)) or np.abs(val).max() > 1e3:
            return
        if not _close(val_moved, val, 0.01) or _close(val, ref, 3.0):  # wanders, or the checker would accept it
            return
        mistakes.append(ik_mistake(name, val))

    for name, switches in _ITERATE_MISTAKES[frame].items():
        kw = {"jacobian": frame, "error": frame, "step": "pinv", "stop": "both", **switches}
        val, _ = newton_loop(chain, T_sd, th0, eps_w, eps_v, k_max, **kw)
        keep(name, val, newton_loop(chain, T_sd, th0 + nudge, eps_w, eps_v, k_max, **kw)[0])
    for name, (rule, budget) in _STOP_MISTAKES.items():
        if budget(k_max) >= 0:
            keep(name, _stop_at(trail, rule, eps_w, eps_v, budget(k_max)),
                 _stop_at(moved, rule, eps_w, eps_v, budget(k_max)))
    return mistakes


def _axes_of(S: Array, M: Array, frame: str) -> Array:
    return S if frame == "space" else adj(lie.inverse_transform(M)) @ S


def _reference_case(S: Array, M: Array, T_sd: Array, th0: Array, eps_w: float, eps_v: float, k_max: int,
                    frame: str, rng: Generator, what: str) -> Case | None:
    chain = SerialChain(S, M)
    axes = _axes_of(S, M, frame)
    ref = (ref_ik_space if frame == "space" else ref_ik_body)(axes, M, T_sd, th0, eps_w, eps_v, k_max)
    mistakes = _mistakes_of(chain, T_sd, th0, eps_w, eps_v, k_max, frame, ref, rng)
    if mistakes is None:
        return None
    label = (f"{what}, a random {S.shape[1]}-joint chain, eps_omega = {eps_w:g}, eps_v = {eps_v:g}, "
             f"max_iterations = {k_max}")
    return Case((axes, M, T_sd, th0, eps_w, eps_v, k_max), ref, mistakes, label)


def _draw_start(rng: Generator, frame: str, prismatic: bool = True, eps: tuple[float, float] | None = None
                ) -> tuple[Array, Array, Array, Array, _Trail, int, float, float]:
    """A random chain, a reachable target, a start 0.05-0.3 rad away and tolerances, whose loop converges in 1 to
    9 steps with no iterate within 5 % of a tolerance (so rounding cannot flip a stop test); the trail and the
    number of steps the loop needs."""
    while True:
        S, M, th_star = random_chain_data(rng, prismatic=prismatic)
        n = S.shape[1]
        T_sd = SerialChain(S, M).fk(th_star)
        th0 = th_star + rng.uniform(0.05, 0.3) * rng.normal(size=n) / np.sqrt(n)
        eps_w = float(rng.choice([1e-2, 1e-3, 1e-6])) if eps is None else eps[0]
        eps_v = float(rng.choice([1e-2, 1e-4, 1e-6])) if eps is None else eps[1]
        trail = _trail(SerialChain(S, M), T_sd, th0, frame, 10)
        stops = [k for k, (w, v, _) in enumerate(trail.norms) if w <= eps_w and v <= eps_v]
        ratios = np.maximum(np.array([[w / eps_w, v / eps_v, x / eps_w, x / eps_v] for w, v, x in trail.norms]),
                            1e-300)
        if stops and 1 <= stops[0] <= 9 and not np.any(np.abs(np.log(ratios[:stops[0] + 1])) < 0.05):
            return S, M, T_sd, th0, trail, stops[0], eps_w, eps_v


def _loop_case(rng: Generator, frame: str) -> Case:
    """A reachable target and a step budget of 0 to 3 more than the loop needs (the loop converges)."""
    while True:
        S, M, T_sd, th0, _, needed, eps_w, eps_v = _draw_start(rng, frame)
        k_max = needed + int(rng.integers(0, 4))
        case = _reference_case(S, M, T_sd, th0, eps_w, eps_v, k_max, frame, rng, "a reachable target")
        if case is not None:
            return case


#: The tolerances a stop-test case may choose from.
_EPS_GRID = [10.0 ** -k * m for k in range(1, 11) for m in (1.0, 2.0, 5.0)]


def _pick_eps(trail: _Trail, rng: Generator) -> tuple[float, float, int, bool] | None:
    """Tolerances under which the right stop test and the three wrong ones stop at four different iterates of
    the trail (the right one after 1 to 9 steps, no norm within 5 % of a tolerance), one of them at random, or
    else tolerances under which each wrong test stops elsewhere than the right one; with the number of steps
    the right loop needs and whether the four are apart. None if there are none."""
    norms = np.array(trail.norms)
    found: list[tuple[float, float, int]] = []
    apart: list[tuple[float, float, int]] = []  # second best: each wrong test stops elsewhere than the right one
    grid = np.array(_EPS_GRID)
    w_ok = norms[None, :, 0] <= grid[:, None]     # (tolerance, iterate)
    v_ok = norms[None, :, 1] <= grid[:, None]
    n_ok = norms[None, :, 2] <= grid[:, None]

    def first(passes: NDArray[np.bool_]) -> NDArray[np.int64]:
        """The first iterate at which a test passes, along the last axis (-1 if none)."""
        return np.where(passes.any(axis=-1), passes.argmax(axis=-1), -1)

    both = first(w_ok[:, None, :] & v_ok[None, :, :])      # (eps_w, eps_v)
    either = first(w_ok[:, None, :] | v_ok[None, :, :])
    on_w, on_v = first(n_ok), first(n_ok)                  # ‖V‖ ≤ eps_omega, ‖V‖ ≤ eps_v
    for a, eps_w in enumerate(_EPS_GRID):
        for c, eps_v in enumerate(_EPS_GRID):
            stops = [int(both[a, c]), int(either[a, c]), int(on_w[a]), int(on_v[c])]
            if -1 in stops or stops[0] in stops[1:] or not 1 <= stops[0] <= 9:
                continue
            thetas = [trail.thetas[k] for k in stops]  # the θ each test stops at must differ, not only the step
            if any(_close(thetas[i], thetas[0], 3.0) for i in (1, 2, 3)):
                continue
            if any(_close(thetas[i], thetas[j], 3.0) for i in (1, 2, 3) for j in (1, 2, 3) if i < j):
                stops = stops[:2] + stops[:2]  # apart from the right one only
            upto = norms[:max(stops) + 1]
            ratios = np.concatenate([upto[:, 0] / eps_w, upto[:, 1] / eps_v, upto[:, 2] / eps_w, upto[:, 2] / eps_v])
            if not np.any(np.abs(np.log(np.maximum(ratios, 1e-300))) < 0.05):
                (found if len(set(stops)) == 4 else apart).append((eps_w, eps_v, stops[0]))
    best = found or apart
    if not best:
        return None
    eps_w, eps_v, needed = best[int(rng.integers(len(best)))]
    return eps_w, eps_v, needed, bool(found)


def _stop_rules_case(rng: Generator, frame: str) -> Case:
    """A reachable target with tolerances under which the right stop test and the three wrong ones stop at four
    different iterates, so each wrong test gives its own θ (tried on 60 starts 0.15-0.7 rad away; else one on
    which each wrong test stops elsewhere than the right one), with a budget that does not bind."""
    fallback: Case | None = None
    for _ in range(60):
        S, M, T_sd, th0, _, _, _, _ = _draw_start(rng, frame)
        th0 = th0 + rng.uniform(0.1, 0.4) * rng.normal(size=len(th0)) / np.sqrt(len(th0))
        trail = _trail(SerialChain(S, M), T_sd, th0, frame, 12)
        picked = _pick_eps(trail, rng)
        if picked is None or (fallback is not None and not picked[3]):
            continue
        eps_w, eps_v, needed, four = picked
        case = _reference_case(S, M, T_sd, th0, eps_w, eps_v, len(trail.norms) - 1, frame, rng,
                               "a reachable target")
        if case is not None and four:
            return case
        fallback = fallback or case
    return fallback if fallback is not None else _loop_case(rng, frame)


def _first(trail: _Trail, rule: str, eps_w: float, eps_v: float) -> int:
    """The first iterate at which the stop test ``rule`` passes (-1 if none)."""
    theta = _stop_at(trail, rule, eps_w, eps_v, len(trail.norms) + 1)
    return next((k for k, t in enumerate(trail.thetas) if t is theta), -1)


def _short_budget_case(rng: Generator, frame: str) -> Case:
    """A reachable target with a step budget short of what the loop needs: it must stop at the cap. Drawn until
    the loop needs 3 or more steps and one step fewer, one step more, no cap (20 steps with the stop test) and
    20 steps without it give four different θ with a budget two short (tried 40 times; else the first draw that
    needs 2 or more steps, with a budget one short)."""
    wanted = ("one_step_short", "one_step_over", "ignores_max_iterations", "fixed_steps")
    fallback: Case | None = None
    attempt = 0
    while attempt < 40 or fallback is None:
        attempt += 1
        S, M, T_sd, th0, _, _, eps_w, eps_v = _draw_start(rng, frame, eps=(1e-3, 1e-3))
        th0 = th0 + rng.uniform(0.1, 0.3) * rng.normal(size=len(th0)) / np.sqrt(len(th0))
        trail = _trail(SerialChain(S, M), T_sd, th0, frame)
        stops = [k for k, (w, v, _) in enumerate(trail.norms[:11]) if w <= eps_w and v <= eps_v]
        needed = stops[0] if stops else 0
        if needed < 2 or (needed < 3 and fallback is not None):
            continue
        if needed >= 3 and fallback is not None:  # the four θ on the trail first (cheap), the whole case after
            if len(trail.thetas) <= MR_STEPS:
                continue
            four = [trail.thetas[k] for k in (needed - 3, needed - 1, needed, MR_STEPS)]
            if any(_close(four[a], four[b], 3.0) for a in range(4) for b in range(a + 1, 4)):
                continue
        case = _reference_case(S, M, T_sd, th0, eps_w, eps_v, needed - 2 if needed >= 3 else 1, frame, rng,
                               "too few steps to converge")
        if case is None:
            continue
        values = {m.name: np.asarray(m.value) for m in case.mistakes if m.name in wanted}
        if len(values) == 4 and not any(_close(values[a], values[b], 3.0) for a in wanted for b in wanted if a < b):
            return case
        fallback = fallback or case
    return fallback


def _unreachable_case(rng: Generator, frame: str) -> Case:
    """A chain of revolute joints only and a target 30 m away, out of its reach (a revolute chain keeps its tool
    within |p_M| + 2 Σ|q_i| <= 23 m of the origin, its joint points q_i and home position p_M being in the unit
    cube): the stop test never passes, and the loop must stop after max_iterations = 2 to 5 steps."""
    while True:
        S, M, T_sd, th0, _, _, eps_w, eps_v = _draw_start(rng, frame, prismatic=False)
        far = T_sd.copy()
        far[:3, 3] = 30.0 * far[:3, 3] / max(float(np.linalg.norm(far[:3, 3])), 1e-9)
        k_max = int(rng.integers(2, 6))
        case = _reference_case(S, M, far, th0, eps_w, eps_v, k_max, frame, rng, "an unreachable target")
        if case is not None and np.all(np.abs(case.reference) < 1e3):
            return case


def converged(args: tuple[object, ...], theta: Array, frame: str) -> bool:
    """Whether the stop test passes at ``theta`` for the test ``args`` (the success a (θ, success) form returns)."""
    axes, M, T_sd, _, eps_w, eps_v, _ = (np.asarray(a, dtype=float) for a in args)
    S = adj(np.asarray(M, float)) @ np.asarray(axes, float) if frame == "body" else np.asarray(axes, float)
    chain = SerialChain(S, np.asarray(M, float))
    T = chain.fk(theta)
    V = lie.log_se3(lie.inverse_transform(T) @ np.asarray(T_sd, float))
    if frame == "space":
        V = adj(T) @ V
    return bool(np.linalg.norm(V[:3]) <= float(eps_w) and np.linalg.norm(V[3:]) <= float(eps_v))


def _loop_statement(frame: str) -> str:
    axes, J, err, mr = (("Blist", "J_b", "\\mathcal V_b = \\log(T_{sb}(\\theta)^{-1}T_{sd})^\\vee", "IKinBody")
                        if frame == "body" else
                        ("Slist", "J_s", "\\mathcal V_s = \\log(T_{sd}T_{sb}(\\theta)^{-1})^\\vee", "IKinSpace"))
    where = "{b}" if frame == "body" else "{s}"
    return (f"Write `my_ik({axes}, M, T_sd, theta0, eps_omega, eps_v, max_iterations)`, Newton–Raphson "
            f"inverse kinematics in the {frame} form (*Modern Robotics*' `{mr}`). `{axes}` is a $6\\times n$ numpy "
            f"array whose columns are the screw axes $(\\omega, v)$ in {where} at home, `M` the home pose of {{b}}, "
            f"`T_sd` the target. Start at `theta0`; at each iterate compute the error twist ${err} = (\\omega, v)$; "
            "stop if $\\|\\omega\\| \\le$ `eps_omega` **and** $\\|v\\| \\le$ `eps_v`; otherwise step "
            f"$\\theta \\leftarrow \\theta + {J}(\\theta)^\\dagger\\,\\mathcal V$ and test again. Take at most "
            "`max_iterations` steps (*Modern Robotics* fixes 20; here the caller says how many): if the test has "
            "not passed after `max_iterations` steps (too few steps, or a target out of reach), stop and return the "
            "last $\\theta$. Return $\\theta$ (a length-$n$ array), or the pair `(theta, success)` as "
            f"`{mr}` does, with `success` true exactly when the stop test passed. It is graded against the "
            "library's `jac.ik.ik` on random chains of 2 to 6 joints (some prismatic): reachable targets with enough "
            "steps, a reachable target with too few steps, and an unreachable target. Set `answer = my_ik`.")


def _case_maker(frame: str) -> Callable[[Generator], Case]:
    def make_case(rng: Generator) -> Case:
        return _loop_case(rng, frame)
    return make_case


def unseparated(cases: list[Case]) -> set[tuple[str, str]]:
    """The pairs (A, B) of catalogued mistakes such that B gives A's result on every test where A's result is wrong:
    a loop making mistake A is then told "either A or B" (the checker names a mistake only where the tests tell it
    from the others). Results are compared to the tolerance code is graded to (:func:`_close`)."""
    names = {m.name for c in cases for m in c.mistakes}
    out: set[tuple[str, str]] = set()
    for a in names:
        fits = set(names) - {a}
        for c in cases:
            values = {m.name: np.asarray(m.value, dtype=float) for m in c.mistakes}
            if a in values:
                fits = {b for b in fits if b in values and _close(values[a], values[b])}
        out |= {(a, b) for b in fits}
    return out


def _separates(case: Case, pairs: set[tuple[str, str]]) -> set[tuple[str, str]]:
    """The pairs (A, B) of ``pairs`` that ``case`` tells apart: A's result is wrong there and B's differs from it."""
    values = {m.name: np.asarray(m.value, dtype=float) for m in case.mistakes}
    return {(a, b) for a, b in pairs if a in values and not (b in values and _close(values[a], values[b]))}


def _more_cases(frame: str) -> Callable[[Generator], list[Case]]:
    """The edge cases after the random ones: tolerances that separate the stop tests, an unreachable target, too
    few steps; then, while two catalogued mistakes give the same result on every test where one of them is wrong
    (a loop making it would be told "either"), a further case of too few steps or of the stop tests that tells
    them apart (up to 8 draws)."""
    def more(rng: Generator) -> list[Case]:
        cases = [_stop_rules_case(rng, frame), _unreachable_case(rng, frame), _short_budget_case(rng, frame)]
        pairs = unseparated(cases)
        for k in range(8):
            if not pairs:
                break
            extra = (_short_budget_case if k % 2 == 0 else _stop_rules_case)(rng, frame)
            if _separates(extra, pairs):
                cases.append(extra)
                pairs = unseparated(cases)
        return cases
    return more


def _adapter(frame: str) -> Callable[[Any, tuple[Any, ...], Any], Any]:
    """θ as it is, or MR's (θ, success): the flag must say whether the stop test passed at the θ returned."""
    def adapt(out: Any, args: tuple[Any, ...], ref: Any) -> Any:
        if not (isinstance(out, (tuple, list)) and len(out) == 2 and isinstance(out[1], (bool, np.bool_))):
            return out
        theta, flag = out
        try:
            th = np.asarray(theta, dtype=float)
        except (TypeError, ValueError):
            return theta
        if th.shape != np.shape(ref) or not np.all(np.isfinite(th)):
            return theta
        want = converged(args, np.asarray(ref, dtype=float), frame)
        if bool(flag) != want:
            return verdict(False, IK_MESSAGES["wrong_success_flag"], mistake="wrong_success_flag")
        return theta
    return adapt


def _ik_example(frame: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm of the seed, a target at other angles and a start near it, with the θ the function must
    return (eps 1e-3, at most 20 steps): varies the statement, so that two IDs rarely share one."""
    def example(rng: Generator) -> tuple[str, dict[str, Any]]:
        _, th, B, M = planar_example(rng, exact=True)
        axes = B if frame == "body" else np.round(adj(M) @ B, 12)
        T_sd = np.round(SerialChain(adj(M) @ B, M).fk(th), 10)  # exact short decimals: a pose as printed
        th0 = np.round(th + rng.choice([-0.2, -0.1, 0.1, 0.2], size=2), 2)
        ref = (ref_ik_body if frame == "body" else ref_ik_space)(axes, M, T_sd, th0, 1e-3, 1e-3, 20)
        name = "Blist" if frame == "body" else "Slist"
        args = {name: axes, "M": M, "T_sd": T_sd, "theta0": th0, "eps_omega": 1e-3, "eps_v": 1e-3,
                "max_iterations": 20}
        text = example_text(f"my_ik({name}, M, T_sd, theta0, eps_omega, eps_v, max_iterations)", args, ref)
        return text, {"example": args}
    return example


def _library_ch10_ex4(ex: Exercise) -> None:
    """On every test case, the loop written out with the library's own pieces (forward kinematics, log, Jacobian,
    pseudo-inverse: :func:`trail_by_library`) stops at the reference's θ, and where its stop test passed, the
    library's forward kinematics puts the tool within pose_tol of T_sd.

    Tolerances. A case is kept only if the loop started 1e-11 away stops within 1e-10 + 1e-8 |θ| of it
    (:func:`_mistakes_of`); two implementations of the loop differ by rounding, about 512 EPS per step, far
    below that start, so they agree within the same 1e-10 + 1e-8 |θ|. The stop test bounds the error twist's
    |ω| and |v|; in the body form T = T_sd e^{−[V_b]} (pose_tol's case), in the space form T = e^{−[V_s]} T_sd,
    whose entries are a row of e^{−[V]} − I times a column of T_sd, bounded the same way."""
    frame = ex.given["frame"]
    for (axes, M, T_sd, th0, eps_w, eps_v, k_max), out in reference_runs(ex):
        chain = _chain(np.asarray(axes, float), np.asarray(M, float), frame)
        trail = trail_by_library(chain, T_sd, th0, frame, steps=k_max)
        k = next((j for j, (w, v, _) in enumerate(trail.norms) if (w <= eps_w and v <= eps_v) or j == k_max), None)
        assert k is not None, "the library's loop blew up before the reference stopped"
        expected = trail.thetas[k]
        beyond = np.maximum(np.abs(np.asarray(out, float) - expected) - 1e-8 * np.abs(expected), 0.0)
        assert_within(beyond, np.zeros_like(expected), 1e-10, "θ where the loop stops (beyond 1e-8 |θ|)")
        w, v, _ = trail.norms[k]
        if w <= eps_w and v <= eps_v:
            assert_within(chain.fk(out), T_sd, pose_tol(T_sd, eps_w, eps_v), "pose reached")


#: Random reachable targets with enough steps, before the edge cases (the cap, an unreachable target, the stop
#: tests): three chains of 2 to 6 joints try the loop itself; the edge cases try what the statement singles out.
IK_RANDOM_CASES = 3

NO_CAP = Mistake("no_iteration_cap", None, IK_MESSAGES["no_iteration_cap"])

register_code("ch10_ex4", "Code: the Newton–Raphson loop", [
    CodeVariant(_loop_statement("body"), ref_ik_body, _case_maker("body"), "my_ik", "joint values",
                {"frame": "body"}, more_cases=_more_cases("body"), on_timeout=NO_CAP, adapt=_adapter("body"),
                example=_ik_example("body"), n_cases=IK_RANDOM_CASES),
    CodeVariant(_loop_statement("space"), ref_ik_space, _case_maker("space"), "my_ik", "joint values",
                {"frame": "space"}, more_cases=_more_cases("space"), on_timeout=NO_CAP, adapt=_adapter("space"),
                example=_ik_example("space"), n_cases=IK_RANDOM_CASES),
], library=_library_ch10_ex4)
