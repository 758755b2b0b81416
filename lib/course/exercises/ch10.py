"""Exercises of chapter 10: inverse kinematics with the Jacobian (the error twist, Newton and damped steps, the
Newton–Raphson loop)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

from jacobians import body_jacobian, geometric_jacobian, lie, robots, space_jacobian
from jacobians.chain import SerialChain
from jacobians.grading import Case, Exercise, Mistake, numeric_exercise
from jacobians.ik import ik
from jacobians.velocity import dls_rates, pinv_rates

from ._kinematics import DEG, Array, adj
from ._latex import bmatrix, degs, num, vec
from ._mistakes import degrees_mistake, ik_mistake, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import angles_deg, lengths, random_chain

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


@register("ch10_ex1")
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
    return numeric_exercise(f"The {asked} error twist", st, {"T_sb": T_sb, "T_sd": T_sd, "asked": asked}, ref,
                            mistakes, what="error twist")


# ----------------------------------------------------------------- exercise 2: one Newton step, planar 2R

def _tool_point(arm: SerialChain, theta: ArrayLike) -> Array:
    return np.asarray(arm.fk(theta)[:2, 3], dtype=float)


def _position_jacobian(arm: SerialChain, theta: ArrayLike) -> Array:
    """J_v: the x, y rows of the linear part of the geometric Jacobian (∂p/∂θ of the tool point)."""
    return np.asarray(geometric_jacobian(arm, theta)[3:5], dtype=float)


@register("ch10_ex2")
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
    return numeric_exercise("One Newton–Raphson step", st, {"lengths": ls, "theta_deg": th_deg, "p_d": p_d}, ref,
                            mistakes, what="joint values")


# ----------------------------------------------------------------- exercise 3: one damped step near a singularity

@register("ch10_ex3")
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
    return numeric_exercise("A damped step near a singularity", st,
                            {"lengths": ls, "theta_deg": th_deg, "p_d": p_d, "lam": lam}, ref, mistakes,
                            what="joint step")


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


def newton_loop(chain: SerialChain, T_sd: Array, theta0: Array, eps_omega: float, eps_v: float,
                max_iterations: int, *, jacobian: str = "body", error: str = "body", step: str = "pinv",
                stop: str = "both") -> tuple[Array, list[tuple[float, float]]]:
    """The Newton–Raphson loop written out, with switches that make the chapter's mistakes: the Jacobian
    (``"body"``/``"space"``), the error twist (``"body"``, ``"space"``, ``"reversed"`` = minus the twist of
    ``jacobian``'s frame, ``"log_T_sd"``), the step (``"pinv"``, ``"transpose"``) and the stopping test
    (``"both"``, ``"either"``, ``"norm_omega"``, ``"norm_v"``). Returns θ and the (‖ω‖, ‖v‖) of every iterate."""
    th = np.array(theta0, dtype=float)
    seen: list[tuple[float, float]] = []
    log_T_sd = lie.log_se3(T_sd)
    for k in range(max_iterations + 1):
        T = chain.fk(th)
        V_b = lie.log_se3(lie.inverse_transform(T) @ T_sd)
        V_s = adj(T) @ V_b
        own = V_b if jacobian == "body" else V_s
        V = {"body": V_b, "space": V_s, "reversed": -own, "log_T_sd": log_T_sd}[error]
        w, v = float(np.linalg.norm(V[:3])), float(np.linalg.norm(V[3:]))
        seen.append((w, v))
        nrm = float(np.linalg.norm(V))
        done = {"both": w <= eps_omega and v <= eps_v, "either": w <= eps_omega or v <= eps_v,
                "norm_omega": nrm <= eps_omega, "norm_v": nrm <= eps_v}[stop]
        if done or k == max_iterations:
            break
        J = body_jacobian(chain, th) if jacobian == "body" else space_jacobian(chain, th)
        th = th + (pinv_rates(J, V, rcond=1e-15) if step == "pinv" else J.T @ V)
        if not np.all(np.isfinite(th)) or np.abs(th).max() > 1e6:
            break
    return th, seen


#: The mistakes of the code exercise: name -> the loop's switches, for each form (body, space).
_LOOP_MISTAKES: dict[str, dict[str, dict[str, str]]] = {
    "body": {
        "space_twist_for_body": {"error": "space"},
        "reversed_error": {"error": "reversed"},
        "log_of_T_sd": {"error": "log_T_sd"},
        "transpose_step": {"step": "transpose"},
        "stop_on_either": {"stop": "either"},
        "stop_on_norm_eps_omega": {"stop": "norm_omega"},
        "stop_on_norm_eps_v": {"stop": "norm_v"},
    },
    "space": {
        "body_twist_for_space": {"error": "body"},
        "reversed_error": {"error": "reversed"},
        "log_of_T_sd": {"error": "log_T_sd"},
        "transpose_step": {"step": "transpose"},
        "stop_on_either": {"stop": "either"},
        "stop_on_norm_eps_omega": {"stop": "norm_omega"},
        "stop_on_norm_eps_v": {"stop": "norm_v"},
    },
}


def _close(a: Array, b: Array, scale: float = 1.0) -> bool:
    """Within ``scale`` times the tolerance a function answer is graded to (rtol 1e-6, atol 1e-8)."""
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= scale * (1e-8 + 1e-6 * np.abs(b))))


def _loop_case(rng: Generator, frame: str) -> Case:
    """A random chain (2 to 6 joints), a reachable target, a start 0.05-0.3 rad away, tolerances, and a step
    budget of 0 to 3 more than the loop needs. The mistakes kept are those that differ from the reference and
    from each other, and that come out the same from a start moved by 1e-11 (a loop that wanders is not
    reproducible, so it names nothing)."""
    while True:
        S, M, th_star = random_chain(rng)
        n = S.shape[1]
        chain = SerialChain(S, M)
        T_sd = chain.fk(th_star)
        th0 = th_star + rng.uniform(0.05, 0.3) * rng.normal(size=n) / np.sqrt(n)
        eps_w = float(rng.choice([1e-2, 1e-3, 1e-6]))
        eps_v = float(rng.choice([1e-2, 1e-4, 1e-6]))
        _, seen = newton_loop(chain, T_sd, th0, eps_w, eps_v, 30, jacobian=frame, error=frame)
        ratios = np.maximum(np.array([[w / eps_w, v / eps_v] for w, v in seen]), 1e-300)
        converged = seen[-1][0] <= eps_w and seen[-1][1] <= eps_v
        if converged and 2 <= len(seen) <= 10 and not np.any(np.abs(np.log(ratios)) < 0.05):
            break
    k_max = len(seen) - 1 + int(rng.integers(0, 4))
    axes = S if frame == "space" else adj(lie.inverse_transform(M)) @ S
    ref = (ref_ik_space if frame == "space" else ref_ik_body)(axes, M, T_sd, th0, eps_w, eps_v, k_max)
    nudge = 1e-11 * rng.normal(size=n)
    mistakes: list[Mistake] = []
    for name, switches in _LOOP_MISTAKES[frame].items():
        kw = {"jacobian": frame, "error": frame, "step": "pinv", "stop": "both", **switches}
        val, trail = newton_loop(chain, T_sd, th0, eps_w, eps_v, k_max, **kw)
        if not np.all(np.isfinite(val)):
            continue
        if len(trail) > k_max:  # it used the whole budget: keep it only if it is reproducible
            again, _ = newton_loop(chain, T_sd, th0 + nudge, eps_w, eps_v, k_max, **kw)
            if not _close(again, val, 0.01):
                continue
        # (a value the checker would accept names nothing; one too near an earlier mistake would be named as that)
        if _close(val, ref) or any(_close(val, np.asarray(m.value), 2.0) for m in mistakes):
            continue
        mistakes.append(ik_mistake(name, val))
    label = (f"a random {n}-joint chain, eps_omega = {eps_w:g}, eps_v = {eps_v:g}, "
             f"max_iterations = {k_max}")
    return Case((axes, M, T_sd, th0, eps_w, eps_v, k_max), ref, mistakes, label)


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
            "`max_iterations` steps (*Modern Robotics* uses 20). Return $\\theta$ (a length-$n$ array, not a "
            "tuple). It is graded on random chains of 2 to 6 joints (some prismatic) with reachable targets, "
            "against the library's `jac.ik.ik`. Set `answer = my_ik`.")


def _case_maker(frame: str) -> Callable[[Generator], Case]:
    def make_case(rng: Generator) -> Case:
        return _loop_case(rng, frame)
    return make_case


register_code("ch10_ex4", "Code: the Newton–Raphson loop", [
    CodeVariant(_loop_statement("body"), ref_ik_body, _case_maker("body"), "my_ik", "joint values",
                {"frame": "body"}),
    CodeVariant(_loop_statement("space"), ref_ik_space, _case_maker("space"), "my_ik", "joint values",
                {"frame": "space"}),
])
