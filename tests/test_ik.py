"""Tests of numerical inverse kinematics (jacobians.ik).

Oracles: the forward kinematics (a converged answer must reach the target), Modern Robotics'
IKinBody / IKinSpace step for step on the UR5, and closed forms on the planar 2R arm.
"""

import numpy as np
import pytest
from fp_bounds import newton_step_bound
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import lie, representations
from jacobians.ik import IKResult, clik, ik, pose_error
from jacobians.testing import (
    EPS,
    TOL,
    clik_step_tol,
    close,
    euler_step_tol,
    pose_tol,
    random_chain,
    random_theta,
    root_tol,
    within,
)

seeds = st.integers(0, 2**32 - 1)


def _ur5_problems(seed, N, spread=0.3):
    rng = np.random.default_rng(seed)
    ur = jac.robots.ur5()
    sol = rng.uniform(-np.pi, np.pi, (N, 6))
    return ur, sol, ur.fk(sol), sol + rng.normal(scale=spread, size=(N, 6))


def _mr_ik(mr, chain, frame, T_d, theta0, eomg, ev, max_iterations=20, iterates=None):
    """MR's IKinBody / IKinSpace written with MR's own functions, counting iterations (MR returns no count).

    ``iterates``, a list, receives (θ_j, J_j, V_j, θ_(j+1)) of every step taken.
    """
    th = np.array(theta0, dtype=float)
    B, S, M = chain.body_axes, chain.screw_axes, chain.home

    def err(th):
        if frame == "body":
            return mr.se3ToVec(mr.MatrixLog6(mr.TransInv(mr.FKinBody(M, B, th)) @ T_d))
        T = mr.FKinSpace(M, S, th)
        return mr.Adjoint(T) @ mr.se3ToVec(mr.MatrixLog6(mr.TransInv(T) @ T_d))

    def far(V):
        return np.linalg.norm(V[:3]) > eomg or np.linalg.norm(V[3:]) > ev

    V = err(th)
    i = 0
    while far(V) and i < max_iterations:
        J = mr.JacobianBody(B, th) if frame == "body" else mr.JacobianSpace(S, th)
        nxt = th + np.linalg.pinv(J) @ V
        if iterates is not None:
            iterates.append((th, J, V, nxt))
        th = nxt
        i += 1
        V = err(th)
    return th, not far(V), i


@pytest.mark.parametrize("frame", ["body", "space"])
def test_same_solutions_as_modern_robotics_on_the_ur5(frame):
    mr = pytest.importorskip("modern_robotics")
    ur, _, T_d, theta0 = _ur5_problems(0, 60)
    eomg, ev = 1e-3, 1e-4
    out = ik(ur, T_d, theta0, frame=frame, eps_omega=eomg, eps_v=ev, max_iterations=20)
    iterates = [[] for _ in range(60)]
    ref = [_mr_ik(mr, ur, frame, T_d[k], theta0[k], eomg, ev, iterates=iterates[k]) for k in range(60)]
    # the counting copy is MR's function, bit for bit
    mr_fn = mr.IKinBody if frame == "body" else mr.IKinSpace
    axes = ur.body_axes if frame == "body" else ur.screw_axes
    for k in range(5):
        th, ok = mr_fn(axes, ur.home, T_d[k], theta0[k], eomg, ev)
        assert np.array_equal(th, ref[k][0]) and ok == ref[k][1]
    ok_mr = np.array([r[1] for r in ref])
    it_mr = np.array([r[2] for r in ref])
    # Step for step from the same state: the library's Newton step from each of MR's iterates θ_j is MR's
    # θ_(j+1), within the bound of that step's conditioning. Two whole runs are not compared: a start that
    # wanders near a singularity amplifies the last bits of each step, and another machine rounds them
    # differently (and a run that ends next to the stopping tolerance may stop one step earlier or later).
    sizes = (lambda T: max(1.0, float(np.abs(T).max())))
    n_steps = 0
    for k in range(60):
        for th, J, V, nxt in iterates[k]:
            if np.linalg.norm(V[:3]) > np.pi - 1e-6:
                continue   # a rotation error of π: the logarithm's axis sign is a tie either side may break its way
            one = ik(ur, T_d[k], th, frame=frame, eps_omega=1e-300, eps_v=1e-300, max_iterations=1)
            assert one.iterations == 1
            step = np.linalg.pinv(J) @ V
            allowed = newton_step_bound(J, V, step, th, sizes(T_d[k]))
            assert np.abs(one.theta - nxt).max() <= max(1e-12, allowed), (k, np.abs(one.theta - nxt).max(), allowed)
            n_steps += 1
    assert n_steps >= 60
    # Where MR converges in a few steps (quadratic convergence, far from the stopping tolerance), so does the library.
    regular = ok_mr & (it_mr <= 8)
    assert regular.sum() >= 50
    assert out.converged[regular].all()
    # and each converged answer does reach the target within the tolerances
    V = pose_error(ur, out.theta, T_d, frame)
    conv = out.converged
    assert (np.linalg.norm(V[conv, :3], axis=-1) <= eomg).all() and (np.linalg.norm(V[conv, 3:], axis=-1) <= ev).all()


@settings(max_examples=30, deadline=None)
@given(seeds, st.sampled_from(["body", "space"]), st.sampled_from(["newton", "dls"]))
def test_converged_means_reached(seed, frame, method):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng, dof=int(rng.integers(6, 8)))
    sol = random_theta(chain, rng)
    T_d = chain.fk(sol)
    out = ik(chain, T_d, sol + 0.1 * rng.normal(size=chain.dof), frame=frame, method=method,
             eps_omega=1e-9, eps_v=1e-9, max_iterations=300, damping=0.01)
    V = pose_error(chain, out.theta, T_d, frame)
    assert close(out.error_omega, np.linalg.norm(V[:3])) and close(out.error_v, np.linalg.norm(V[3:]))   # same formula
    if out.converged:
        # |ω|, |v| <= 1e-9 in the stopping frame; the space error twist is Ad_T of the body one, so in the body
        # frame |ω_b| = |ω_s| and |v_b| <= |v_s| + |p| |ω_s|: pose_tol from those
        p_size = float(np.linalg.norm(chain.fk(out.theta)[:3, 3]))
        e_w, e_v = (1e-9, 1e-9) if frame == "body" else (1e-9, 1e-9 + p_size * 1e-9)
        assert within(chain.fk(out.theta), T_d, pose_tol(T_d, e_w, e_v))
    else:
        assert out.iterations == 300


def test_newton_converges_quadratically():
    ur, sol, T_d, _ = _ur5_problems(1, 1)
    out = ik(ur, T_d[0], sol[0] + 0.05, eps_omega=1e-13, eps_v=1e-13, max_iterations=10, record_history=True)
    assert out.converged
    errs = [np.linalg.norm(pose_error(ur, h, T_d[0])) for h in out.history[: int(out.iterations) + 1]]
    # e_{k+1} <= C e_k^2 while the error is well above rounding
    for a, b in zip(errs, errs[1:], strict=False):
        if a > 1e-6:
            assert b < 10 * a * a


def test_transpose_descends_and_is_slower_than_newton():
    arm = jac.robots.planar_2r()
    T_d = arm.fk([0.3, 1.2])
    starts = np.array([[0.0, 0.5], [1.0, 0.8], [0.6, 1.6]])
    newton = ik(arm, T_d, starts)
    tr = ik(arm, T_d, starts, method="transpose", max_iterations=2000, record_history=True)
    assert newton.converged.all() and tr.converged.all()
    # stopped at |V_b| <= sqrt(2)·1e-6 (the default): within 2|V_b|/σ_min(J_b(θ*)) of θ* (root_tol)
    assert within(tr.theta, [0.3, 1.2], root_tol(jac.body_jacobian(arm, [0.3, 1.2]), np.hypot(1e-6, 1e-6)))
    assert (tr.iterations > 5 * newton.iterations).all()
    errors = np.linalg.norm(pose_error(arm, tr.history, T_d), axis=-1)
    # every step lowers the error: the computed |V| is off by at most 512 EPS times the pose's size (close's model)
    assert (np.diff(errors, axis=0) <= 2 * 512 * EPS * max(1.0, float(np.abs(T_d).max()))).all()
    # on the UR5 too, from starts 0.2 rad off: the error only goes down
    ur, _, T5, th5 = _ur5_problems(0, 5, spread=0.2)
    out = ik(ur, T5, th5, method="transpose", max_iterations=300, record_history=True)
    e5 = np.linalg.norm(pose_error(ur, out.history, T5), axis=-1)
    assert (np.diff(e5, axis=0) <= 2 * 512 * EPS * max(1.0, float(np.abs(T5).max()))).all() and (e5[-1] < 0.05 * e5[0]).all()


def test_dls_converges_on_the_ur5():
    ur, _, T_d, theta0 = _ur5_problems(2, 20, spread=0.2)
    dls = ik(ur, T_d, theta0, method="dls", damping=0.02, eps_omega=1e-6, eps_v=1e-6, max_iterations=500)
    assert dls.converged.all()
    assert within(ur.fk(dls.theta), T_d, pose_tol(T_d, 1e-6, 1e-6))   # body error under the stopping tolerances


def test_dls_stays_bounded_where_newton_jumps():
    """From a singular start (UR5, elbow stretched, σ_min ≈ 1.6e-5) Newton's first step is thousands of
    radians; every DLS step is at most |V|/(2λ) and it lands on the nearby solution."""
    ur = jac.robots.ur5()
    start = np.array([0.3, -0.5, 1e-4, 0.4, 0.8, 0.1])
    assert jac.analysis.singularity_measure(jac.body_jacobian(ur, start)) < 1e-4
    target = np.array([0.5, -0.8, 0.6, 0.5, 0.9, 0.3])
    T_d = ur.fk(target)
    newton = ik(ur, T_d, start, record_history=True)
    lam = 0.05
    dls = ik(ur, T_d, start, method="dls", damping=lam, max_iterations=300, record_history=True)
    steps = np.linalg.norm(np.diff(dls.history, axis=0), axis=-1)
    bounds = np.linalg.norm(pose_error(ur, dls.history[:-1], T_d), axis=-1) / (2 * lam)
    assert (steps <= bounds + 1e-12).all()
    assert np.linalg.norm(newton.history[1] - newton.history[0]) > 1000 * steps.max()
    assert dls.converged and within(dls.theta, target, root_tol(jac.body_jacobian(ur, target), np.hypot(1e-6, 1e-6)))


def test_batches_broadcast_and_stop_on_their_own():
    ur, sol, T_d, theta0 = _ur5_problems(3, 6)
    out = ik(ur, T_d.reshape(2, 3, 4, 4), theta0.reshape(2, 3, 6), record_history=True)
    assert out.theta.shape == (2, 3, 6) and out.converged.shape == (2, 3) and out.iterations.shape == (2, 3)
    assert out.history.shape == (int(out.iterations.max()) + 1, 2, 3, 6)
    for idx in np.ndindex(2, 3):
        one = ik(ur, T_d.reshape(2, 3, 4, 4)[idx], theta0.reshape(2, 3, 6)[idx])
        # both stopped at |V_b| <= sqrt(2)·1e-6: each within root_tol of the solution, so within twice it of each other
        assert within(one.theta, out.theta[idx], 2 * root_tol(jac.body_jacobian(ur, one.theta), np.hypot(1e-6, 1e-6)))
        assert one.iterations == out.iterations[idx]
    # one target, many starts; many targets, one start
    assert ik(ur, T_d[0], theta0).theta.shape == (6, 6)
    assert ik(ur, T_d, theta0[0]).theta.shape == (6, 6)
    # a start that is already a solution takes no step
    done = ik(ur, T_d[0], sol[0])
    assert done.iterations == 0 and done.converged and np.array_equal(done.theta, sol[0])


def test_result_is_frozen_and_readable():
    arm = jac.robots.planar_2r()
    out = ik(arm, arm.fk([0.3, 1.2]), [0.0, 0.5])
    assert isinstance(out, IKResult)
    with pytest.raises(AttributeError):
        out.theta = np.zeros(2)
    assert "converged=True" in repr(out) and "iterations=" in repr(out)
    assert "2 of 2 converged" in repr(ik(arm, arm.fk([0.3, 1.2]), [[0.0, 0.5], [0.1, 0.4]]))


def test_planar_basins():
    """Position-and-orientation targets of the 2R arm have one solution mod 2π: every regular start finds it."""
    arm = jac.robots.planar_2r()
    T_d = arm.fk([0.3, 1.2])
    grid = np.stack(np.meshgrid(np.linspace(-3, 3, 13), np.linspace(-3, 3, 13)), -1).reshape(-1, 2)
    grid = grid[np.abs(np.sin(grid[:, 1])) > 0.05]  # off the singular lines θ2 = 0, ±π
    out = ik(arm, T_d, grid, eps_omega=1e-10, eps_v=1e-10, max_iterations=50)
    wrapped = (out.theta[out.converged] + np.pi) % (2 * np.pi) - np.pi
    assert out.converged.mean() > 0.9
    assert within(wrapped, [0.3, 1.2], root_tol(jac.body_jacobian(arm, [0.3, 1.2]), np.hypot(1e-10, 1e-10)))


def test_pose_error_is_the_log_of_the_relative_pose():
    rng = np.random.default_rng(0)
    chain = random_chain(rng, dof=4)
    th = random_theta(chain, rng)
    T_d = chain.fk(random_theta(chain, rng))
    Vb = pose_error(chain, th, T_d, "body")
    # exp ∘ log is well-conditioned away from a rotation angle of π (where the log's axis is not): TOL (close)
    assert np.linalg.norm(Vb[:3]) < 3.0
    assert close(chain.fk(th) @ lie.exp_se3(Vb), T_d)
    assert close(pose_error(chain, th, T_d, "space"), jac.adjoint(chain.fk(th)) @ Vb)


def test_clik_tracks_a_moving_pose_and_its_error_decays():
    ur = jac.robots.ur5()
    t = np.linspace(0, 2, 201)
    start = np.array([0.3, -0.9, 1.1, 0.2, 0.5, 0.1])
    path = ur.fk(start + np.outer(np.sin(t), [0.4, 0.2, -0.3, 0.1, 0.3, 0.5]))
    out = clik(ur, start, path, dt=0.01, gain=20.0)
    # each step contracts the error by 1 - K dt up to the step's second-order remainder b_k (clik_step_tol,
    # from the arm's curvature and the step's size), so e_k <= B_k, B_{k+1} = (1 - K dt) B_k + b_k, B_0 = e_0
    b = [clik_step_tol(ur, jac.geometric_jacobian(ur, out.thetas[k]), out.thetas[k + 1] - out.thetas[k],
                       out.error_orientation[k], np.linalg.norm(lie.log_so3(path[k + 1, :3, :3] @ path[k, :3, :3].T)),
                       0.2, scale=np.abs(path[:, :3, 3]).max()) for k in range(200)]
    B = np.array([out.error_orientation[0], out.error_position[0]])
    for k in range(200):
        assert out.error_orientation[k + 1] <= 0.8 * out.error_orientation[k] + b[k][0]
        assert out.error_position[k + 1] <= 0.8 * out.error_position[k] + b[k][1]
        B = 0.8 * B + b[k]
        assert out.error_orientation[k + 1] <= B[0] and out.error_position[k + 1] <= B[1]
        assert B.max() < 2e-3                     # hence the tracking error stays under 2e-3 all along the path
    # a fixed target from an offset start: |e_{k+1}| = (1 - K dt)|e_k| up to the step's remainder (clik_step_tol;
    # the feed-forward is 0: the path's increments are exact zeros), checked at every step from the run's own state
    T_d = ur.fk(start)
    off = clik(ur, start + 0.05, np.repeat(T_d[None], 60, axis=0), dt=0.01, gain=20.0)
    e = off.error_orientation + off.error_position
    for k in range(59):
        b_o, b_p = clik_step_tol(ur, jac.geometric_jacobian(ur, off.thetas[k]), off.thetas[k + 1] - off.thetas[k],
                                 off.error_orientation[k], 0.0, 0.2, scale=np.abs(T_d[:3, 3]).max())
        assert abs(e[k + 1] - 0.8 * e[k]) <= b_o + b_p, k
    assert e[-1] < 1e-5 * e[0]                    # 59 steps of at most 0.8 + b_k / e_k (under 0.82): 0.82^59 = 8e-6
    # without the feedback it drifts
    drift = clik(ur, start, path, dt=0.01, gain=0.0)
    assert drift.error_position.max() > 10 * out.error_position.max()


def test_validation():
    arm = jac.robots.planar_2r()
    T = arm.fk([0.1, 0.2])
    with pytest.raises(ValueError, match="method 'newton', 'dls' or 'transpose'"):
        ik(arm, T, [0, 0], method="gauss")
    with pytest.raises(ValueError, match="frame 'space' or 'body'"):
        ik(arm, T, [0, 0], frame="geometric")
    with pytest.raises(ValueError, match="eps_omega"):
        ik(arm, T, [0, 0], eps_omega=0.0)
    with pytest.raises(TypeError, match="integer for max_iterations"):
        ik(arm, T, [0, 0], max_iterations=2.5)
    with pytest.raises(ValueError, match="max_iterations >= 0"):
        ik(arm, T, [0, 0], max_iterations=-1)
    with pytest.raises(ValueError, match=r"theta0 with shape \(\.\.\., 2\)"):
        ik(arm, T, [0, 0, 0])
    with pytest.raises(ValueError, match="do not broadcast"):
        ik(arm, np.stack([T] * 3), np.zeros((2, 2)))
    bad = T.copy()
    bad[:3, :3] *= 2
    with pytest.raises(ValueError, match="rotation"):
        ik(arm, bad, [0, 0])
    with pytest.raises(TypeError, match="record_history"):
        ik(arm, T, [0, 0], record_history="yes")
    with pytest.raises(ValueError, match=r"target_poses with shape \(N, 4, 4\)"):
        clik(arm, [0, 0], T, dt=0.1)
    with pytest.raises(ValueError, match="method 'pinv' or 'dls'"):
        clik(arm, [0, 0], np.stack([T, T]), dt=0.1, method="newton")
    with pytest.raises(ValueError, match=r"target_velocities with shape \(2, 6\)"):
        clik(arm, [0, 0], np.stack([T, T]), dt=0.1, target_velocities=np.zeros((2, 3)))


# ------------------------------------------------------------------ joint limits and wrapping

PLANAR_LIMITS = np.array([[-np.pi, np.pi], [0.0, 2.6], [-2.6, 2.6]])


def test_clamped_iterates_stay_in_the_box_and_can_find_the_other_solution():
    arm = jac.robots.planar_3r()
    T_d = arm.fk([0.2, 1.1, 0.6])                   # elbow up; elbow down is (1.3, -1.1, 1.7)
    free = ik(arm, T_d, [1.2, -0.5, 0.3], eps_omega=1e-9, eps_v=1e-9)
    out = ik(arm, T_d, [1.2, -0.5, 0.3], eps_omega=1e-9, eps_v=1e-9, limits=PLANAR_LIMITS, record_history=True)
    assert free.converged and free.theta[1] < 0
    assert out.converged and within(out.theta, [0.2, 1.1, 0.6],
                                    root_tol(jac.body_jacobian(arm, [0.2, 1.1, 0.6]), np.hypot(1e-9, 1e-9)))
    assert np.all((out.history >= PLANAR_LIMITS[:, 0]) & (out.history <= PLANAR_LIMITS[:, 1]))


def test_clamped_run_stalls_at_a_fixed_point_of_the_clamped_step():
    arm = jac.robots.planar_3r()
    T_d = arm.fk([0.2, 1.1, 0.6])
    out = ik(arm, T_d, [0.9, -0.6, 1.0], eps_omega=1e-9, eps_v=1e-9, limits=PLANAR_LIMITS, max_iterations=30)
    assert not out.converged and out.error_v > 1.0
    # every joint at a limit, and Newton's step there points out of the box (so clipping undoes it)
    step = jac.velocity.pinv_rates(jac.body_jacobian(arm, out.theta), pose_error(arm, out.theta, T_d))
    at_lo, at_hi = out.theta == PLANAR_LIMITS[:, 0], out.theta == PLANAR_LIMITS[:, 1]
    assert np.all((at_lo & (step < 0)) | (at_hi & (step > 0)))


def test_a_wrong_clamp_is_caught():
    """Without the clamp (limits ignored) the same start leaves the box: the box test above is not vacuous."""
    arm = jac.robots.planar_3r()
    out = ik(arm, arm.fk([0.2, 1.1, 0.6]), [1.2, -0.5, 0.3], record_history=True)
    assert np.any(out.history[:, 1] < PLANAR_LIMITS[1, 0])


@pytest.mark.parametrize("seed", range(5))
def test_wrapping_shifts_every_iterate_by_multiples_of_two_pi(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng, dof=6, prismatic_probability=0.3, pitch_probability=0.3)
    S = chain.screw_axes
    # ω·v = 0 exactly for a pure revolute joint (v = -ω × q); computed, up to TOL of the column's size (close)
    pitch_free = np.abs(np.sum(S[:3] * S[3:], axis=0)) <= TOL * np.maximum(1.0, np.abs(S).max(axis=0))
    turns = np.array([c == "R" for c in chain.joint_types]) & pitch_free
    theta = random_theta(chain, rng)
    T_d = chain.fk(theta)
    start = theta + rng.normal(scale=0.3, size=6) + 4 * np.pi * turns
    free = ik(chain, T_d, start, record_history=True, max_iterations=10)
    wrapped = ik(chain, T_d, start, record_history=True, max_iterations=10, wrap=True)
    diff = free.history - wrapped.history
    # plain revolute joints: multiples of 2 pi (rounding of the shift amplified by 10 steps stays far below 1e-6);
    # prismatic and screw joints are never wrapped (a screw joint's pose is not 2 pi-periodic)
    assert np.allclose(jac.ik.wrap_angles(diff[..., turns]), 0, atol=1e-6)
    assert np.allclose(diff[..., ~turns], 0, atol=1e-6)
    assert np.all(np.abs(wrapped.history[1:][..., turns]) <= np.pi)


def test_wrap_angles_range():
    x = np.array([np.pi, -np.pi, 3 * np.pi, 1e-17 - np.pi, 7.0, -7.0, 0.0])
    w = jac.ik.wrap_angles(x)
    assert np.all((w > -np.pi) & (w <= np.pi))
    # w = x - 2πk is off by the rounding of |x| + 2π|k| <= 2·9.5: cos and sin move by no more (close, scale 19)
    assert close(np.cos(w), np.cos(x), scale=19.0) and close(np.sin(w), np.sin(x), scale=19.0)
    with pytest.raises(ValueError, match="finite"):
        jac.ik.wrap_angles([np.nan])


def test_limits_validation():
    arm = jac.robots.planar_3r()
    T_d = arm.fk([0.2, 1.1, 0.6])
    with pytest.raises(ValueError, match=r"limits of shape \(3, 2\)"):
        ik(arm, T_d, [0, 0, 0], limits=[[0, 1], [0, 1]])
    with pytest.raises(ValueError, match="lower <= upper"):
        ik(arm, T_d, [0, 0, 0], limits=[[0, 1], [1, 0], [0, 1]])
    with pytest.raises(ValueError, match="NaN"):
        ik(arm, T_d, [0, 0, 0], limits=[[0, 1], [np.nan, 1], [0, 1]])
    with pytest.raises(TypeError, match="wrap"):
        ik(arm, T_d, [0, 0, 0], wrap="yes")
    # infinite bounds are no limit
    a = ik(arm, T_d, [0.5, 0.5, 0.5], limits=[[-np.inf, np.inf]] * 3)
    b = ik(arm, T_d, [0.5, 0.5, 0.5])
    assert np.array_equal(a.theta, b.theta)


# ------------------------------------------------------------------ Euler-angle CLIK

def test_euler_clik_error_decays_by_one_minus_k_dt_on_a_fixed_target():
    ur = jac.robots.ur5()
    th = np.array([0.3, -0.9, 1.1, 0.2, 0.5, 0.1])
    out = clik(ur, th + 0.02, np.repeat(ur.fk(th)[None], 30, axis=0), dt=0.01, gain=20.0, orientation="zyx")
    e = np.linalg.norm(out.error_angles, axis=-1)
    # |e_{k+1}| = (1 - K dt)|e_k| up to the Taylor remainder of the Euler angles along the step (euler_step_tol:
    # from |Δ|₁ and the pitch's distance to the lock, |cos β|), at every step from the run's own state
    for k in range(29):
        phi = representations.coordinates_from_rotation(ur.fk(out.thetas[k])[:3, :3], "zyx")
        J = jac.geometric_jacobian(ur, out.thetas[k])
        J_A = np.vstack([representations.angular_velocity_to_rate(phi, "zyx") @ J[:3], J[3:]])
        bound = euler_step_tol(out.thetas[k + 1] - out.thetas[k], abs(np.cos(phi[1])), J_A)
        assert abs(e[k + 1] - 0.8 * e[k]) <= bound, k
    assert out.error_orientation[-1] < 0.82 ** 29 * out.error_orientation[0]   # at most 0.82 a step


def test_euler_clik_is_the_axis_angle_law_to_first_order_when_b_is_the_identity():
    """At phi = 0 (the zyx wrist at home) B(0) has columns z, y, x: the first step of both laws agrees to first order."""
    wrist = jac.robots.zyx_wrist()
    target = wrist.fk([0.0, 0.0, 0.0])
    d = 1e-4 * np.array([1.0, -2.0, 0.5])
    a = clik(wrist, d, np.repeat(target[None], 2, axis=0), dt=0.01, gain=5.0)
    b = clik(wrist, d, np.repeat(target[None], 2, axis=0), dt=0.01, gain=5.0, orientation="zyx")
    assert np.allclose(a.rates[0], b.rates[0], atol=1e-6)      # they differ at second order, ~ K |d|^2 = 5e-8


def test_euler_clik_refuses_the_lock_and_bad_orientation():
    wrist = jac.robots.zyx_wrist()
    poses = np.repeat(wrist.fk([0.1, 0.2, 0.3])[None], 3, axis=0)
    with pytest.raises(jac.representations.RepresentationSingularityError, match="axis-angle"):
        clik(wrist, [0.0, np.pi / 2, 0.0], poses, dt=0.01, orientation="zyx")
    lock = np.repeat(wrist.fk([0.0, np.pi / 2, 0.0])[None], 3, axis=0)
    with pytest.raises(jac.representations.RepresentationSingularityError):
        clik(wrist, [0.1, 0.2, 0.3], lock, dt=0.01, orientation="zyx", target_velocities=np.zeros((3, 6)))
    with pytest.raises(ValueError, match="orientation"):
        clik(wrist, [0.1, 0.2, 0.3], poses, dt=0.01, orientation="rpy")
    assert clik(wrist, [0.1, 0.2, 0.3], poses, dt=0.01).error_angles is None
