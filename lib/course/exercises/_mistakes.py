"""Mistakes met in many exercises: a column with the wrong sign, (v, ω) for (ω, v), degrees for radians, and the
mistakes of inverse kinematics (:data:`IK_MESSAGES`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from jacobians.grading import Mistake

from ._kinematics import swap


def sign_mistakes(ref: ArrayLike, axis_word: str = "joint") -> list[Mistake]:
    """One mistake per column of a 6xn matrix: that column with the opposite sign."""
    ref = np.asarray(ref, float)
    out: list[Mistake] = []
    if ref.ndim != 2:
        return out
    for j in range(ref.shape[1]):
        W = ref.copy()
        W[:, j] *= -1
        out.append(Mistake(f"sign_column_{j + 1}", W,
                           f"Column {j + 1} has the opposite sign of the right one: check the direction of "
                           f"{axis_word} {j + 1}'s axis and the sign in v = -ω × q."))
    return out


def swap_mistake(ref: ArrayLike) -> Mistake:
    """Rows (v, omega) instead of (omega, v)."""
    return Mistake("v_omega_swapped", swap(ref),
                   "Your rows are in the order (v, ω): this course (Modern Robotics) puts the angular part "
                   "first, rows 1-3 ω and rows 4-6 v.")


def degrees_mistake(value: Any) -> Mistake:
    """``value`` is the answer computed with the angles in degrees fed to sin and cos."""
    return Mistake("degrees_for_radians", value,
                   "This is what comes out when the angles in degrees are fed to sin and cos as if they were "
                   "radians: convert degrees to radians first (multiply by π/180).")


def neighbour_columns(J: ArrayLike, i: int, name: str) -> list[Mistake]:
    """Columns i-1 and i+1 (1-based, those that exist) of ``J`` given for column i: the neighbouring column."""
    J = np.asarray(J, float)
    return [Mistake("neighbour_column", J[:, k - 1].copy(),
                    f"This is column {k} of the {name}, the neighbouring column (joint {k}); the exercise asks for "
                    f"column {i}, the one of joint {i}.")
            for k in (i - 1, i + 1) if 1 <= k <= J.shape[1]]


#: Mistakes of inverse kinematics (chapter 10), by name: what to look at. Each exercise of chapter 10 names
#: its mistakes from here, so one slip reads the same wherever it is made.
IK_MESSAGES: dict[str, str] = {
    "space_for_body": "This is the space error twist V_s = log(T_sd T_sb⁻¹), the same motion written in {s}. "
                      "The body error twist is log(T_sb⁻¹ T_sd): the inverse of the current pose on the left, so "
                      "that the twist is expressed in {b}.",
    "body_for_space": "This is the body error twist V_b = log(T_sb⁻¹ T_sd), written in {b}. The space error twist "
                      "is the same motion in {s}: V_s = [Ad_T_sb] V_b = log(T_sd T_sb⁻¹).",
    "reversed_order": "Your twist has the opposite sign: it carries {d} onto {b}, not {b} onto {d}. Take the "
                      "logarithm of T_sb⁻¹ T_sd (body) or T_sd T_sb⁻¹ (space), not of T_sd⁻¹ T_sb or T_sb T_sd⁻¹.",
    "log_of_T_sd": "This is the logarithm of the target T_sd alone, the twist from {s} to {d}. The error twist "
                   "starts from the current pose: log(T_sb⁻¹ T_sd), i.e. the log of T_bd.",
    "decoupled_error": "Your ω is right, but v is the plain position difference. The linear part of the error "
                       "twist is not p_d - p: it is the v of the screw motion log(T_sb⁻¹ T_sd), which also depends "
                       "on the rotation (v = G(θ)⁻¹ p_bd).",
    "wrong_adjoint": "You changed frames with Ad of T_sb⁻¹. The body twist goes to {s} with Ad of T_sb: "
                     "V_s = [Ad_T_sb] V_b.",
    "wrong_sign": "The step has the wrong sign: the error e = p_d - p(θ_k) points from the tool to the target, and "
                  "the step solves J Δθ = e, so θ_k+1 = θ_k + Δθ (not minus).",
    "step_only": "This is the step Δθ; the exercise asks for the new joint values θ_k+1 = θ_k + Δθ.",
    "theta_for_step": "This is θ_k + Δθ, the new joint values; the exercise asks for the step Δθ alone.",
    "answer_in_degrees": "These are degrees; the exercise asks for radians (multiply degrees by π/180, or leave "
                         "your result in radians as the computation gives it).",
    "transpose_step": "You stepped along Jᵀe (the Jacobian transpose). Newton's step solves J Δθ = e: use the "
                      "inverse (or pseudo-inverse) of J, not its transpose.",
    "no_damping": "This is the undamped step J⁺e, which is huge near a singularity: the damping term λ²I is "
                  "missing from (JᵀJ + λ²I)⁻¹Jᵀe.",
    "lambda_not_squared": "You added λI; the damping enters squared: (JᵀJ + λ²I)⁻¹Jᵀe.",
    "transpose_only": "This is Jᵀe, without the inverse (JᵀJ + λ²I)⁻¹.",
    "body_twist_for_space": "Your loop pairs J_s with the body error twist log(T_sb⁻¹ T_sd). A Jacobian and an "
                            "error must be in the same frame: with J_s use V_s = log(T_sd T_sb⁻¹).",
    "space_twist_for_body": "Your loop pairs J_b with the space error twist log(T_sd T_sb⁻¹). A Jacobian and an "
                            "error must be in the same frame: with J_b use V_b = log(T_sb⁻¹ T_sd).",
    "reversed_error": "Your loop walks away from the target: its error twist has the wrong sign. Check the order "
                      "of the product in the logarithm (T_sb⁻¹ T_sd in the body form, T_sd T_sb⁻¹ in the space "
                      "form) and that the step is θ + J⁺V, not θ - J⁺V.",
    "stop_on_either": "Your loop stops as soon as ω or v is small. It must go on until both are: "
                      "‖ω‖ ≤ ε_ω and ‖v‖ ≤ ε_v.",
    "stop_on_norm_eps_omega": "Your loop stops on the norm of the whole twist, ‖V‖ ≤ ε_ω. ω (rad) and v (length) "
                              "have different units and tolerances: test ‖ω‖ ≤ ε_ω and ‖v‖ ≤ ε_v separately.",
    "stop_on_norm_eps_v": "Your loop stops on the norm of the whole twist, ‖V‖ ≤ ε_v. ω (rad) and v (length) have "
                          "different units and tolerances: test ‖ω‖ ≤ ε_ω and ‖v‖ ≤ ε_v separately.",
    "ignores_max_iterations": "Your loop takes up to 20 steps whatever max_iterations says (Modern Robotics' fixed "
                              "number): use the argument, so that the caller decides how many steps are allowed.",
    "fixed_steps": "Your loop always takes 20 steps: it must test the error before each step and stop as soon as "
                   "‖ω‖ ≤ ε_ω and ‖v‖ ≤ ε_v, and take at most max_iterations steps.",
    "one_step_short": "Your loop stops one step before the cap: with max_iterations = k it may take k steps "
                      "(it tests the error k + 1 times, before each step and after the last). Check the loop's "
                      "range.",
    "one_step_over": "Your loop takes one step more than max_iterations allows: after k = max_iterations steps it "
                     "must stop, even if the test has not passed. Check the loop's range.",
    "no_iteration_cap": "Your loop does not stop when the target cannot be reached: it must stop after "
                        "max_iterations steps even if the stop test never passes (cap the loop, e.g. "
                        "for k in range(max_iterations + 1)).",
    "wrong_success_flag": "Your θ is right, but the success flag is not: it must be true exactly when the stop test "
                          "‖ω‖ ≤ ε_ω and ‖v‖ ≤ ε_v passed, and false when the loop stopped at the cap.",
}


def ik_mistake(name: str, value: Any) -> Mistake:
    """The catalogued inverse-kinematics mistake ``name`` (a key of :data:`IK_MESSAGES`) with its wrong value."""
    return Mistake(name, value, IK_MESSAGES[name])
