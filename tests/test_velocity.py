"""Tests of jacobians.velocity: pseudo-inverse and damped least squares against
their definitions and numpy, limits in the damping, behaviour at singularities,
resolved-rate tracking."""

from __future__ import annotations

import numpy as np
import pytest
from fp_bounds import solve_bound
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import velocity as vel
from jacobians.testing import chain_curvature, random_chain, random_theta, tracking_tol

RNG = np.random.default_rng(11)


def test_pinv_rates_match_numpy_pinv_batched():
    J = RNG.normal(size=(5, 3, 4))
    V = RNG.normal(size=(5, 3))
    expect = np.einsum("bij,bj->bi", np.linalg.pinv(J), V)
    assert np.allclose(vel.pinv_rates(J, V), expect)
    # broadcasting: one J, many V
    assert np.allclose(vel.pinv_rates(J[0], V), (np.linalg.pinv(J[0]) @ V.T).T)


def test_pinv_rates_exact_for_full_row_rank_and_minimum_norm():
    J = RNG.normal(size=(3, 6))
    V = RNG.normal(size=3)
    qd = vel.pinv_rates(J, V)
    assert np.allclose(J @ qd, V)
    # minimum norm: orthogonal to the null space
    N = jac.analysis.nullspace(J)
    assert np.allclose(N.T @ qd, 0, atol=1e-12)
    # least squares for a tall J
    Jt = RNG.normal(size=(6, 3))
    Vt = RNG.normal(size=6)
    assert np.allclose(vel.pinv_rates(Jt, Vt), np.linalg.lstsq(Jt, Vt, rcond=None)[0])


def test_pinv_rates_planar_2r_by_hand():
    # theta = (0, pi/2), unit links: J_v = [[-1, -1], [1, 0]]; tip up (0, 1) needs (1, -1)
    arm = jac.robots.planar_2r()
    J_v = jac.geometric_jacobian(arm, [0.0, np.pi / 2])[3:5]
    assert np.allclose(J_v, [[-1, -1], [1, 0]], atol=1e-12)
    assert np.allclose(vel.pinv_rates(J_v, [0.0, 1.0]), [1.0, -1.0])
    # the rates really move the tip that way (finite difference of fk)
    qd = vel.pinv_rates(J_v, [0.0, 1.0])
    h = 1e-6
    dp = (arm.fk(np.array([0.0, np.pi / 2]) + h * qd)[:2, 3] - arm.fk(np.array([0.0, np.pi / 2]) - h * qd)[:2, 3]) / (2 * h)
    assert np.allclose(dp, [0.0, 1.0], atol=1e-8)


def test_dls_rates_equal_normal_equations():
    J = RNG.normal(size=(4, 3, 5))
    V = RNG.normal(size=(4, 3))
    lam = 0.3
    n = J.shape[-1]
    JT = np.swapaxes(J, -1, -2)
    expect = np.linalg.solve(JT @ J + lam**2 * np.eye(n), (JT @ V[..., None]))[..., 0]
    assert np.allclose(vel.dls_rates(J, V, lam), expect)
    # the other textbook form J^T (J J^T + lambda^2 I)^-1 V is the same
    expect2 = (JT @ np.linalg.solve(J @ JT + lam**2 * np.eye(3), V[..., None]))[..., 0]
    assert np.allclose(vel.dls_rates(J, V, lam), expect2)


def test_dls_tends_to_pinv_as_damping_goes_to_zero():
    J = RNG.normal(size=(3, 4))
    V = RNG.normal(size=3)
    ref = vel.pinv_rates(J, V)
    errs = [np.linalg.norm(vel.dls_rates(J, V, lam) - ref) for lam in (1e-1, 1e-2, 1e-3, 1e-4)]
    assert all(a > b for a, b in zip(errs[:-1], errs[1:], strict=True))
    # x_λ - x_0 = -Σ λ² / (σ_i (σ_i² + λ²)) (u_i·V) v_i for a full-row-rank J: at most λ² |V| / σ_min³,
    # plus each solve's rounding (solve_bound, from the condition number)
    s_min = np.linalg.svd(J, compute_uv=False)[-1]
    assert errs[-1] <= 1e-8 * np.linalg.norm(V) / s_min**3 + solve_bound(J, V, ref) + solve_bound(J, V, ref, 1e-4)
    assert np.allclose(vel.dls_rates(J, V, 0.0), ref)


def test_dls_bounded_at_a_singularity_while_pinv_blows_up():
    arm = jac.robots.planar_2r()
    V = np.array([1.0, 0.0])  # radial velocity, impossible when stretched along x
    lam = 0.1
    rates_pinv, rates_dls = [], []
    for eps in (1e-1, 1e-3, 1e-5, 1e-7):
        J_v = jac.geometric_jacobian(arm, [0.0, eps])[3:5]
        rates_pinv.append(np.linalg.norm(vel.pinv_rates(J_v, V)))
        qd = vel.dls_rates(J_v, V, lam)
        rates_dls.append(np.linalg.norm(qd))
        assert np.linalg.norm(qd) <= np.linalg.norm(V) / (2 * lam) + 1e-12
    assert rates_pinv[-1] > 1e6 and rates_pinv[-1] > 100 * rates_pinv[0]
    assert max(rates_dls) < 5.0
    # exactly at the singularity: pinv drops the lost direction, DLS too (sigma = 0 gets no rate)
    J0 = jac.geometric_jacobian(arm, [0.0, 0.0])[3:5]
    assert np.allclose(vel.pinv_rates(J0, V), 0, atol=1e-9)
    assert np.allclose(vel.dls_rates(J0, V, lam), 0, atol=1e-9)
    assert np.allclose(vel.dls_rates(np.zeros((2, 2)), V, 0.0), 0)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), batch=st.sampled_from([(), (2,), (3, 2)]),
       lam=st.floats(1e-3, 10.0))
def test_properties_over_random_chains(seed, batch, lam):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng, size=batch)
    J = jac.body_jacobian(chain, theta)
    V = rng.normal(size=batch + (6,))
    qd = vel.pinv_rates(J, V)
    assert qd.shape == batch + (chain.dof,)
    # the residual of the pseudo-inverse solution is orthogonal to the range of J
    res = V - (J @ qd[..., None])[..., 0]
    assert np.allclose((np.swapaxes(J, -1, -2) @ res[..., None])[..., 0], 0, atol=1e-6 * (1 + np.abs(V).max()))
    qd_dls = vel.dls_rates(J, V, lam)
    assert qd_dls.shape == qd.shape
    assert np.all(np.linalg.norm(qd_dls, axis=-1) <= np.linalg.norm(V, axis=-1) / (2 * lam) + 1e-9)
    # DLS never has a larger rate than the pseudo-inverse
    assert np.all(np.linalg.norm(qd_dls, axis=-1) <= np.linalg.norm(qd, axis=-1) + 1e-9)


# ------------------------------------------------------------------ resolved rate

def _circle(arm, theta0, radius, N, dt):
    p0 = arm.fk(theta0)[:2, 3]
    t = np.arange(N) * dt
    w = 2 * np.pi / (t[-1])
    path = p0 + radius * np.stack([np.cos(w * t) - 1, np.sin(w * t)], axis=1)
    vels = radius * w * np.stack([-np.sin(w * t), np.cos(w * t)], axis=1)
    return path, vels


def test_resolved_rate_tracks_a_circle():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    theta0 = np.array([0.2, 0.9, 0.6])
    path, vels = _circle(arm, theta0, 0.3, 200, 0.01)
    out = vel.resolved_rate(arm, theta0, path, dt=0.01, target_velocities=vels)
    assert out.thetas.shape == (200, 3) and out.rates.shape == (200, 3)
    assert out.positions.shape == (200, 2) and out.errors.shape == (200,)
    assert np.allclose(out.thetas[0], theta0)
    # positions are the forward kinematics of the recorded joints
    assert np.allclose(out.positions, arm.fk(out.thetas)[:, :2, 3])
    # the error is the integrator's: with J_v J_v⁺ = I each Euler step gives e' = (1 - K dt) e + r_d - r_p, r_d the
    # path's own Taylor remainder (|p̈_d| dt² / 2 = radius w² dt² / 2) and r_p the arm's (D |Δ|₁² / 2,
    # chain_curvature), so | |e'| - (1 - K dt)|e| | <= b_k at every step, and e_k <= B_k, B_{k+1} = (1 - K dt) B_k + b_k:
    # O(dt), the bound for dt/2 about half the bound for dt
    bounds = []
    for N, dt_, run in ((200, 0.01, out), (399, 0.005, None)):
        path_, vels_ = _circle(arm, theta0, 0.3, N, dt_)
        w = 2 * np.pi / ((N - 1) * dt_)                 # the circle's angular rate (_circle)
        run = run or vel.resolved_rate(arm, theta0, path_, dt=dt_, target_velocities=vels_)
        B = run.errors[0]
        for k in range(N - 1):
            b = 0.3 * w**2 * dt_**2 / 2 + chain_curvature(arm) * np.abs(run.thetas[k + 1] - run.thetas[k]).sum() ** 2 / 2
            assert abs(run.errors[k + 1] - (1 - 2.0 * dt_) * run.errors[k]) <= b + 1e-12 * (1 + np.abs(path_).max())
            B = (1 - 2.0 * dt_) * B + b
            assert run.errors[k + 1] <= B + 1e-12 * (1 + np.abs(path_).max())      # plus the rounding of p (TOL)
        bounds.append(B)
    assert bounds[1] < 0.55 * bounds[0] and bounds[0] < 0.05       # under 5 cm on a circle of radius 30 cm
    # the rates solve J_v qdot = v_d + K e at each step
    k = 50
    J_v = jac.geometric_jacobian(arm, out.thetas[k])[3:5]
    assert np.allclose(J_v @ out.rates[k], vels[k] + 2.0 * (path[k] - out.positions[k]))
    # Euler integration of the recorded rates
    assert np.allclose(out.thetas[1:], out.thetas[:-1] + 0.01 * out.rates[:-1])
    # the feedback matters: without it the error drifts more
    drift = vel.resolved_rate(arm, theta0, path, dt=0.01, target_velocities=vels, gain=0.0)
    assert drift.errors[-1] > out.errors[-1]


def test_resolved_rate_forward_difference_velocities_and_3d():
    arm = jac.robots.spatial_5r()
    theta0 = np.array([0.1, 0.3, -0.5, 0.2, 0.1])
    p0 = arm.fk(theta0)[:3, 3]
    t = np.linspace(0, 1, 51)
    path = p0 + np.outer(t, [-0.2, 0.1, 0.1])  # inwards, away from singularities
    for method in ("pinv", "dls"):
        out = vel.resolved_rate(arm, theta0, path, dt=t[1] - t[0], method=method, damping=0.01)
        assert out.positions.shape == (51, 3)
        assert np.allclose(out.positions, arm.fk(out.thetas)[:, :3, 3])
        # step by step from the run's own state (tracking_tol): the rates solve J_v θ̇ = ṗ_d + K e to the solve's
        # rounding (κ(J_v) TOL), each error vector is the one before plus the path's move minus J_v θ̇ dt within
        # the arm's Taylor remainder D|Δ|₁²/2, and the errors stay under the recursion's bound (O(dt): under 2 cm)
        worst, B = tracking_tol(arm, out.thetas, out.rates, path, t[1] - t[0], 2.0)
        assert worst <= 1 and np.all(out.errors <= B) and B.max() < 2e-2
        assert np.allclose(out.errors, np.linalg.norm(path - out.positions, axis=1), rtol=0, atol=1e-12)
        assert np.allclose(out.thetas[1:], out.thetas[:-1] + (t[1] - t[0]) * out.rates[:-1], rtol=0, atol=1e-12)
        for k in range(50):
            J_v = jac.geometric_jacobian(arm, out.thetas[k])[3:6]
            cmd = (path[k + 1] - path[k]) / (t[1] - t[0]) + 2.0 * (path[k] - out.positions[k])
            ref = np.linalg.pinv(J_v) @ cmd if method == "pinv" else np.linalg.solve(J_v.T @ J_v + 1e-4 * np.eye(5), J_v.T @ cmd)
            assert np.allclose(out.rates[k], ref, rtol=0, atol=1e-12 * np.linalg.cond(J_v) * max(1, np.abs(cmd).max()))
        assert out.sigma_min.min() > 0.2


def test_resolved_rate_near_singularity_pinv_vs_dls():
    # a 2R arm asked to reach past its workspace boundary: pinv rates explode, DLS stays bounded
    arm = jac.robots.planar_2r()
    theta0 = np.array([0.0, 1.0])
    p0 = arm.fk(theta0)[:2, 3]
    t = np.linspace(0, 1, 101)
    target = np.array([2.2, 0.0])
    path = p0 + np.outer(t, target - p0)
    pinv = vel.resolved_rate(arm, theta0, path, dt=0.01, method="pinv")
    dls = vel.resolved_rate(arm, theta0, path, dt=0.01, method="dls", damping=0.1)
    assert np.abs(pinv.rates).max() > 10 * np.abs(dls.rates).max()
    assert np.abs(dls.rates).max() < 20
    assert dls.sigma_min.min() < 0.3  # it does get close to the singularity
    assert dls.errors[-1] > 0.15  # and cannot reach: the target is out of reach (2.2 > 2)


@pytest.mark.parametrize("kwargs, exc, match", [
    (dict(target_path=np.zeros((5, 4))), ValueError, r"\(N, 2\)"),
    (dict(target_path=np.zeros((1, 2))), ValueError, "N >= 2"),
    (dict(target_path="circle"), TypeError, "real numbers"),
    (dict(dt=0.0), ValueError, "positive"),
    (dict(method="newton"), ValueError, "pinv"),
    (dict(damping=-1.0), ValueError, "non-negative"),
    (dict(gain=float("inf")), ValueError, "finite"),
    (dict(theta0=[0.1, 0.2, 0.3]), ValueError, r"\(\.\.\., 2\)"),
    (dict(theta0=[[0.1, 0.2]]), ValueError, r"shape \(2,\)"),
    (dict(target_velocities=np.zeros((3, 2))), ValueError, "shape of target_path"),
    (dict(chain="2R"), TypeError, "SerialChain"),
])
def test_resolved_rate_bad_input(kwargs, exc, match):
    args = dict(chain=jac.robots.planar_2r(), theta0=[0.1, 0.2], target_path=np.zeros((5, 2)), dt=0.1)
    args.update(kwargs)
    with pytest.raises(exc, match=match):
        vel.resolved_rate(**args)


@pytest.mark.parametrize("call, exc, match", [
    (lambda: vel.pinv_rates("J", [1.0]), TypeError, "real numbers"),
    (lambda: vel.pinv_rates([1.0, 2.0], [1.0]), ValueError, r"\(\.\.\., m, n\)"),
    (lambda: vel.pinv_rates(np.eye(3), [1.0, 2.0]), ValueError, r"\(\.\.\., 3\) to match"),
    (lambda: vel.pinv_rates(np.eye(3), [1.0, np.inf, 0.0]), ValueError, "finite"),
    (lambda: vel.pinv_rates(np.ones((2, 3, 3)), np.ones((4, 3))), ValueError, "broadcast"),
    (lambda: vel.pinv_rates(np.eye(2), [1.0, 1.0], rcond=0.0), ValueError, "positive"),
    (lambda: vel.dls_rates(np.eye(2), [1.0, 1.0], damping=-0.1), ValueError, "non-negative"),
    (lambda: vel.dls_rates(np.eye(2), [1.0, 1.0], damping="0.1"), TypeError, "real number"),
    (lambda: vel.dls_rates(np.eye(2), [1.0, 1.0], damping=None), TypeError, "real number"),
])
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
