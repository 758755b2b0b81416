"""The exercises of chapter 10 (inverse kinematics): their references checked by independent routes (the
defining property of the error twist, finite differences of the forward kinematics, Modern Robotics'
IKinBody/IKinSpace), and realistic wrong student code named by its mistake."""

from __future__ import annotations

import modern_robotics as mr
import numpy as np
import pytest

import jacobians as jac
from course import exercises
from course.exercises import ch10
from course.exercises._mistakes import IK_MESSAGES

SEEDS = [*range(20), "s1234567", "maria.garcia@uni.example"]


def _cases(ex, n=None):
    rng = ex._rng(1000)
    return [ex.make_case(rng) for _ in range(n or ex.n_cases)]


# ------------------------------------------------------------------ exercise 1: the error twist

@pytest.mark.parametrize("seed", SEEDS)
def test_error_twist_carries_b_onto_d_and_equals_pose_error(seed):
    ex = exercises.load("ch10_ex1", seed=seed)
    T_sb, T_sd, asked = ex.given["T_sb"], ex.given["T_sd"], ex.given["asked"]
    for T in (T_sb, T_sd):  # the statement's matrices are exact rigid motions (entries typed as shown)
        R = T[:3, :3]
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12) and np.isclose(np.linalg.det(R), 1.0)
        assert np.allclose(T, np.round(T, 6), atol=1e-12) and np.array_equal(T[3], [0, 0, 0, 1])
    V = ex.solution()
    if asked == "body":
        assert np.allclose(T_sb @ jac.lie.exp_se3(V), T_sd, atol=1e-10)      # T_sb e^[V_b] = T_sd
    else:
        assert np.allclose(jac.lie.exp_se3(V) @ T_sb, T_sd, atol=1e-10)      # e^[V_s] T_sb = T_sd
    # the library's pose_error on a chain whose pose at theta = 0 is T_sb
    chain = jac.SerialChain(np.array([[0.0], [0], [1], [0], [0], [0]]), T_sb)
    np.testing.assert_allclose(V, jac.ik.pose_error(chain, [0.0], T_sd, frame=asked), atol=1e-12)
    assert np.linalg.norm(V[:3]) <= np.pi / 2 + 1e-12                        # the relative turn is at most 90°
    assert "to 3 decimals" in ex.statement and "{b}" in ex.statement and "(\\omega, v)" in ex.statement


# ------------------------------------------------------------------ exercise 2: one Newton step

@pytest.mark.parametrize("seed", SEEDS)
def test_newton_step_solves_the_linearised_position_error(seed):
    ex = exercises.load("ch10_ex2", seed=seed)
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    p = lambda t: arm.fk(t)[:2, 3]
    J_fd = jac.numerical_jacobian(p, th)                                       # ∂p/∂θ by central differences
    step = ex.solution() - th
    np.testing.assert_allclose(J_fd @ step, ex.given["p_d"] - p(th), atol=1e-7)
    assert abs(np.linalg.det(J_fd)) > 0.3 * np.prod(ex.given["lengths"])      # away from the singularity
    # the target is near enough for Newton's method to work: the step at least halves the error
    assert np.linalg.norm(ex.given["p_d"] - p(ex.solution())) < 0.5 * np.linalg.norm(ex.given["p_d"] - p(th))
    assert "radians" in ex.statement and "to 3 decimals" in ex.statement


# ------------------------------------------------------------------ exercise 3: one damped step

@pytest.mark.parametrize("seed", SEEDS)
def test_damped_step_minimises_the_damped_cost_near_a_singularity(seed):
    ex = exercises.load("ch10_ex3", seed=seed)
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    lam = ex.given["lam"]
    J = jac.numerical_jacobian(lambda t: arm.fk(t)[:2, 3], th)
    e = ex.given["p_d"] - arm.fk(th)[:2, 3]
    d = ex.solution()
    np.testing.assert_allclose(J.T @ (J @ d - e) + lam ** 2 * d, 0, atol=1e-7)   # gradient of the damped cost
    assert np.linalg.norm(d) <= np.linalg.norm(e) / (2 * lam) + 1e-12
    s = np.linalg.svd(J, compute_uv=False)
    assert s[-1] < 0.2 * s[0]                                                  # near the stretched-out singularity
    names = {m.name for m in ex.mistakes}
    assert {"no_damping", "lambda_not_squared"} <= names
    undamped = next(m.value for m in ex.mistakes if m.name == "no_damping")
    assert np.linalg.norm(undamped) > np.linalg.norm(d)                       # the damping shortens the step


# ------------------------------------------------------------------ exercise 4: the Newton-Raphson loop

@pytest.mark.parametrize("seed", [0, 1, 2])
def test_loop_reference_is_modern_robotics_ikin_and_the_written_out_loop(seed):
    ex = exercises.load("ch10_ex4", seed=seed)
    frame = ex.given["frame"]
    mr_ik = mr.IKinBody if frame == "body" else mr.IKinSpace
    kinds = set()
    for case in ex.cases():
        axes, M, T_sd, th0, eps_w, eps_v, k_max = case.args
        ours = ex.reference(axes, M, T_sd, th0, eps_w, eps_v, k_max)
        S = jac.adjoint(M) @ axes if frame == "body" else axes
        mine, seen = ch10.newton_loop(jac.SerialChain(S, M), T_sd, th0, eps_w, eps_v, k_max, jacobian=frame,
                                      error=frame)
        np.testing.assert_allclose(mine, ours, atol=1e-12)
        met = seen[-1][0] <= eps_w and seen[-1][1] <= eps_v
        assert met == ch10.converged(case.args, ours, frame)
        kinds.add(case.label.split(",")[0])
        if met:  # MR takes up to 20 steps and stops on the same test: the same θ
            theirs, ok = mr_ik(axes, M, T_sd, th0, eps_w, eps_v)
            assert ok and k_max <= 20
            np.testing.assert_allclose(ours, theirs, atol=1e-9)
            assert len(seen) - 1 <= k_max
        else:  # it stopped at the cap, after exactly max_iterations steps
            assert len(seen) - 1 == k_max
    assert kinds == {"a reachable target", "an unreachable target", "too few steps to converge"}, kinds


def _student(frame, *, order="right", jacobian=None, sign=1.0, stop="both", transpose=False):
    """A student's loop, written independently of the checker (Modern Robotics' functions)."""
    def my_ik(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations):
        th = np.array(theta0, dtype=float)
        use = jacobian or frame
        for k in range(max_iterations + 1):
            if frame == "body":
                T = mr.FKinBody(M, axes, th)
                X = mr.TransInv(T) @ T_sd if order == "right" else T_sd @ mr.TransInv(T)
            else:
                T = mr.FKinSpace(M, axes, th)
                X = T_sd @ mr.TransInv(T) if order == "right" else mr.TransInv(T) @ T_sd
            V = mr.se3ToVec(mr.MatrixLog6(X))
            w, v = np.linalg.norm(V[:3]), np.linalg.norm(V[3:])
            done = {"both": w <= eps_omega and v <= eps_v, "either": w <= eps_omega or v <= eps_v,
                    "norm": np.linalg.norm(V) <= eps_omega}[stop]
            if done or k == max_iterations:
                return th
            J = mr.JacobianBody(axes, th) if use == "body" else mr.JacobianSpace(axes, th)
            th = th + sign * (J.T @ V if transpose else np.linalg.pinv(J) @ V)
        return th
    return my_ik


@pytest.mark.parametrize("frame", ["body", "space"])
def test_realistic_student_loops_are_graded_and_their_mistakes_named(frame):
    seed = next(s for s in range(40) if exercises.load("ch10_ex4", seed=s).given["frame"] == frame)
    ex = exercises.load("ch10_ex4", seed=seed)
    assert ex.check(_student(frame)).correct
    other = "space" if frame == "body" else "body"
    fb = ex.check(_student(frame, order="wrong"))
    assert not fb.correct and fb.mistake == f"{other}_twist_for_{frame}", fb
    assert ex.check(_student(frame, sign=-1.0)).mistake == "reversed_error"
    assert ex.check(_student(frame, transpose=True)).mistake == "transpose_step"
    named = set()
    for stop in ("either", "norm"):
        fb = ex.check(_student(frame, stop=stop))
        assert not fb.correct and fb.message.startswith("On test ")
        named.add(fb.mistake)
    assert named <= {"stop_on_either", "stop_on_norm_eps_omega", "ambiguous", "wrong_entries", "wrong_entry"}
    assert named & {"stop_on_either", "stop_on_norm_eps_omega"}, named


def test_a_loop_returning_theta_and_success_like_mr_is_accepted_and_its_flag_checked():
    ex = exercises.load("ch10_ex4", seed=0)
    right = _student(ex.given["frame"])

    def like_mr(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations):
        th = right(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations)
        return th, ch10.converged((axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations), th, ex.given["frame"])

    def always_true(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations):
        return right(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations), True

    assert ex.check(like_mr).correct
    fb = ex.check(always_true)  # the unreachable target is not reached: success must be False there
    assert not fb.correct and fb.mistake == "wrong_success_flag", fb


# ------------------------------------------------------------------ the catalogue of IK mistakes

def test_the_ik_mistakes_of_the_issue_are_all_named_somewhere_in_chapter_10():
    names: set[str] = set()
    for eid in ("ch10_ex1", "ch10_ex2", "ch10_ex3"):
        for seed in range(12):
            names |= {m.name for m in exercises.load(eid, seed=seed).mistakes}
    for seed in range(12):
        ex = exercises.load("ch10_ex4", seed=seed)
        for case in _cases(ex, 3):
            names |= {m.name for m in case.mistakes}
    for required in ("space_for_body", "body_for_space", "reversed_order", "log_of_T_sd",
                     "body_twist_for_space", "space_twist_for_body", "wrong_sign", "no_damping",
                     "lambda_not_squared", "stop_on_either", "reversed_error", "transpose_step"):
        assert required in names, required
    assert names <= set(IK_MESSAGES) | {"v_omega_swapped", "degrees_for_radians"}, names - set(IK_MESSAGES)
