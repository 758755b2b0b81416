"""The numbers behind the live views, from the library: the Jacobian formulas the planar explorer shows, and the
resolved-rate runs of jacobians.widgets.live (the path presets, the start on the path, pinv against DLS).

What a view draws is compared with these in the browser (tests/browser/test_live_*.py)."""

import numpy as np
import pytest

import jacobians as jac
from jacobians.lie import adjoint, exp_se3
from jacobians.plotting import arm_reach
from jacobians.representations import angular_velocity_to_rate
from jacobians.widgets.live import PATHS, planar_path, start_configuration

# ---------------------------------------------------------------- the formulas the explorer displays

@pytest.mark.parametrize("chain", [jac.robots.planar_3r(1.0, 0.7, 0.4), jac.robots.ur5()], ids=["3R", "UR5"])
def test_displayed_formulas_hold(chain):
    rng = np.random.default_rng(3)
    th = rng.uniform(-np.pi, np.pi, chain.dof)
    S, B = chain.screw_axes, chain.body_axes
    n = chain.dof
    # space: column i = Ad(e^[S1]th1 ... e^[S_{i-1}]th_{i-1}) S_i
    J_s = jac.space_jacobian(chain, th)
    T = np.eye(4)
    for i in range(n):
        np.testing.assert_allclose(J_s[:, i], adjoint(T) @ S[:, i], atol=1e-10)
        T = T @ exp_se3(S[:, i] * th[i])
    # body: column i = Ad(e^-[Bn]thn ... e^-[B_{i+1}]th_{i+1}) B_i
    J_b = jac.body_jacobian(chain, th)
    T = np.eye(4)
    for i in reversed(range(n)):
        np.testing.assert_allclose(J_b[:, i], adjoint(T) @ B[:, i], atol=1e-10)
        T = T @ exp_se3(-B[:, i] * th[i])
    # geometric = diag(R, R) J_b
    R = chain.fk(th)[:3, :3]
    np.testing.assert_allclose(jac.geometric_jacobian(chain, th), np.block([[R, 0 * R], [0 * R, R]]) @ J_b,
                               atol=1e-10)
    # analytic = diag(B(phi)^-1, I) J, and it is d(phi, p)/d theta (finite differences)
    phi = jac.pose_coordinates(chain.fk(th), "zyx")[:3]
    J = jac.geometric_jacobian(chain, th)
    J_a = jac.analytic_jacobian(chain, th, "zyx")
    np.testing.assert_allclose(J_a[:3], angular_velocity_to_rate(phi, "zyx") @ J[:3], atol=1e-9)
    num = jac.numerical_jacobian(lambda q: jac.pose_coordinates(chain.fk(q), "zyx"), th)
    np.testing.assert_allclose(J_a, num, atol=1e-6)


# ---------------------------------------------------------------- the resolved-rate view's runs

GAIN = 2.0  # the view's feedback gain K, 1/s (resolved_rate_model)


def _run(path, method, damping=0.1, n=160):
    """The run the resolved-rate view shows for the 2R arm: a preset path, its exact velocity as feed-forward."""
    chain = jac.robots.planar_2r(1.0, 1.0)
    reach = arm_reach(chain)
    t, x, v = planar_path(path, reach, n)
    th0 = start_configuration(chain, x[0])
    r = jac.velocity.resolved_rate(chain, th0, x, t[1] - t[0], method=method, damping=damping, gain=GAIN,
                                   target_velocities=v)
    return chain, reach, t, x, v, r


def test_resolved_rate_tracks_a_circle_and_rates_match_pinv():
    chain, reach, t, x, v, r = _run("circle", "pinv")
    assert np.linalg.norm(x - r.positions, axis=1).max() < 0.02 * reach  # Euler steps of 25 ms with feedback
    k, dt = 40, t[1] - t[0]
    th = r.thetas[k]
    J_v = jac.geometric_jacobian(chain, th)[3:5]
    np.testing.assert_allclose(r.thetas[k + 1], th + dt * r.rates[k], atol=1e-12)
    # the commanded tool velocity: the path's velocity plus feedback K (x_d - x)
    cmd = v[k] + GAIN * (x[k] - chain.fk(th)[:2, 3])
    np.testing.assert_allclose(r.rates[k], jac.velocity.pinv_rates(J_v, cmd), atol=1e-12)
    np.testing.assert_allclose(J_v @ r.rates[k], cmd, atol=1e-9)  # away from singularities: exact


@pytest.mark.parametrize("method", ["pinv", "dls"])
def test_resolved_rate_start_path_and_steps(method):
    chain, reach, t, x, v, r = _run("close past the base", method)
    # the start is on the path (solved with damped steps), elbow up
    np.testing.assert_allclose(r.positions[0], x[0], atol=1e-9)
    assert r.thetas[0, 1] > 0
    # the path: a straight line 3 % of the reach from the base, from +0.6 to -0.6 reach, in 4 s, its exact velocity
    np.testing.assert_allclose(x[[0, -1]], [[0.6 * reach, 0.03 * reach], [-0.6 * reach, 0.03 * reach]])
    assert t[-1] == pytest.approx(4.0)
    np.testing.assert_allclose(np.diff(x, axis=0) / np.diff(t)[:, None], v[:-1], atol=1e-12)  # a line: exact
    k = 70
    J_v = jac.geometric_jacobian(chain, r.thetas[k])[3:5]
    cmd = v[k] + GAIN * (x[k] - r.positions[k])
    want = jac.velocity.dls_rates(J_v, cmd, 0.1) if method == "dls" else jac.velocity.pinv_rates(J_v, cmd)
    np.testing.assert_allclose(r.rates[k], want, atol=1e-12)
    if method == "dls":  # |J^T (J J^T + λ²I)^-1| <= 1/(2λ): the rate is bounded near the singularity
        assert np.linalg.norm(r.rates[k]) <= np.linalg.norm(cmd) / (2 * 0.1) + 1e-12


def test_resolved_rate_singularity_pinv_blows_up_dls_stays_bounded():
    chain, reach, t, x, v, pinv = _run("to full reach", "pinv")
    assert pinv.sigma_min[-1] < 0.05 * reach
    *_, dls = _run("to full reach", "dls", 0.1)
    assert np.abs(dls.rates).max() < np.abs(pinv.rates).max() / 2
    assert np.linalg.norm(x[-1] - dls.positions[-1]) > 1e-3  # the price: it does not reach the boundary point
    *_, pinv = _run("close past the base", "pinv")
    assert np.all(np.isfinite(pinv.rates))
    *_, dls = _run("close past the base", "dls", 0.1)
    # joint 1 must swing half a turn while the tool passes the base: pinv's peak rate is large, DLS's far less
    assert np.abs(dls.rates).max() < np.abs(pinv.rates).max() / 3
    assert np.linalg.norm(x - dls.positions, axis=1).max() > 0.05 * reach  # DLS cuts the corner
    with pytest.raises(ValueError, match="path"):
        planar_path("spiral", reach, 10)
    assert PATHS == ("circle", "to full reach", "close past the base")
