"""Tests of the Jacobian's time derivative and the end-effector acceleration (jacobians.acceleration).

Oracles: finite differences of the Jacobian along θ(t) = θ + t θ̇, second differences of the
forward kinematics, and Pinocchio's computeJointJacobiansTimeVariation.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import lie
from jacobians.acceleration import acceleration, bracket, jacobian_derivative
from jacobians.testing import close, fd2_tol, fd_tol, random_chain, random_theta, within

seeds = st.integers(0, 2**32 - 1)
FRAMES = ("space", "body", "geometric")
H = 1e-5


def fd_jdot(chain, theta, theta_dot, frame):
    return (jac.jacobian(chain, theta + H * theta_dot, frame) - jac.jacobian(chain, theta - H * theta_dot, frame)) / (2 * H)


@settings(max_examples=60, deadline=None)
@given(seeds)
def test_jdot_is_the_derivative_along_the_motion(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    theta_dot = rng.normal(size=chain.dof)
    for frame in FRAMES:
        got = jacobian_derivative(chain, theta, theta_dot, frame)
        assert got.shape == (6, chain.dof)
        # central difference with step H along θ + sθ̇: truncation H²/6·max|J'''| + rounding (fd_tol, from J itself)
        bound = fd_tol(lambda s, frame=frame: jac.jacobian(chain, theta + s[0] * theta_dot, frame), np.zeros(1), H)
        assert within(got, fd_jdot(chain, theta, theta_dot, frame), bound), frame


def test_column_formulas_written_out_with_lie_ad():
    """Column i of J̇_s is ad(sum_{j<i} J_sj θ̇_j) J_si; of J̇_b, -ad(sum_{j>i} J_bj θ̇_j) J_bi."""
    rng = np.random.default_rng(7)
    chain = jac.robots.ur5()
    theta, thd = random_theta(chain, rng), rng.normal(size=6)
    Js, Jb = jac.space_jacobian(chain, theta), jac.body_jacobian(chain, theta)
    Jds, Jdb = jacobian_derivative(chain, theta, thd, "space"), jacobian_derivative(chain, theta, thd, "body")
    for i in range(6):
        before = sum((Js[:, j] * thd[j] for j in range(i)), np.zeros(6))
        after = sum((Jb[:, j] * thd[j] for j in range(i + 1, 6)), np.zeros(6))
        assert close(Jds[:, i], lie.ad(before) @ Js[:, i])        # the same products, exact algebra
        assert close(Jdb[:, i], -lie.ad(after) @ Jb[:, i])
    assert close(Jds[:, 0], 0) and close(Jdb[:, -1], 0)  # first space / last body column is constant (ad(0) = 0)


def test_bracket_is_lie_ad_columnwise():
    rng = np.random.default_rng(0)
    V, X = rng.normal(size=(6, 4)), rng.normal(size=(6, 4))
    got = bracket(V, X)
    for k in range(4):
        assert close(got[:, k], lie.ad(V[:, k]) @ X[:, k])


def test_linear_in_theta_dot_and_partial_derivatives():
    rng = np.random.default_rng(3)
    chain = random_chain(rng, dof=5)
    theta = random_theta(chain, rng)
    a, b = rng.normal(size=5), rng.normal(size=5)
    for frame in FRAMES:
        lhs = jacobian_derivative(chain, theta, 2.0 * a - 3.0 * b, frame)
        rhs = 2.0 * jacobian_derivative(chain, theta, a, frame) - 3.0 * jacobian_derivative(chain, theta, b, frame)
        # linear in θ̇ exactly; rounding relative to the two terms' size (rhs is a difference of them)
        assert close(lhs, rhs, scale=float(np.abs(2.0 * jacobian_derivative(chain, theta, a, frame)).max()
                                           + np.abs(3.0 * jacobian_derivative(chain, theta, b, frame)).max()))
        k = 2
        dJk = jac.numerical_jacobian(lambda t, frame=frame: jac.jacobian(chain, t, frame), theta)[..., k]
        assert within(jacobian_derivative(chain, theta, np.eye(5)[k], frame), dJk,
                      fd_tol(lambda t, frame=frame: jac.jacobian(chain, t, frame), theta))   # FD bound of ∂J/∂θ


@settings(max_examples=20, deadline=None)
@given(seeds, st.sampled_from([(1,), (3,), (2, 2)]))
def test_batched_equals_loop_and_broadcasts(seed, shape):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng, size=shape)
    thd = rng.normal(size=shape + (chain.dof,))
    for frame in FRAMES:
        got = jacobian_derivative(chain, theta, thd, frame)
        assert got.shape == shape + (6, chain.dof)
        for idx in np.ndindex(*shape):
            assert close(got[idx], jacobian_derivative(chain, theta[idx], thd[idx], frame))
        # one rate for the whole batch broadcasts
        one = jacobian_derivative(chain, theta, thd[(0,) * len(shape)], frame)
        assert one.shape == got.shape


@settings(max_examples=40, deadline=None)
@given(seeds)
def test_acceleration_against_second_differences_of_fk(seed):
    """Geometric: (ω̇_s, p̈); space: d/dt (Ṫ T⁻¹)^∨; body: d/dt (T⁻¹ Ṫ)^∨, along θ(t) = θ + tθ̇ + t²/2 θ̈."""
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    n = chain.dof
    th, thd, thdd = random_theta(chain, rng), rng.normal(size=n), rng.normal(size=n)
    h = 1e-3

    def twist(t, frame):
        # the twist at time t from central differences of the FK in s around t
        e = 1e-5
        T = chain.fk(th + t * thd + 0.5 * t * t * thdd)
        dT = (chain.fk(th + (t + e) * thd + 0.5 * (t + e) ** 2 * thdd)
              - chain.fk(th + (t - e) * thd + 0.5 * (t - e) ** 2 * thdd)) / (2 * e)
        if frame == "space":
            return lie.matrix_to_twist(dT @ np.linalg.inv(T))
        if frame == "body":
            return lie.matrix_to_twist(np.linalg.inv(T) @ dT)
        return np.concatenate([lie.unskew(dT[:3, :3] @ T[:3, :3].T), dT[:3, 3]])

    # The twist is itself a central difference (step 1e-5) of T(t): each entry of dT/dt is within fd_tol of the
    # derivative, a twist entry sums a row or column of dT times T⁻¹ (or Rᵀ): within inner = fd_tol · sum |T⁻¹|.
    # That error is not smooth in t, so the outer difference (step h) may divide it by h; the outer difference of
    # the computed twist adds its own truncation and rounding (fd_tol of twist(t) with step h).
    T0 = chain.fk(th)
    inner = fd_tol(lambda s: chain.fk(th + s[0] * thd + 0.5 * s[0] ** 2 * thdd), np.zeros(1), 1e-5)
    inner *= float(np.abs(np.linalg.inv(T0)).sum())
    for frame in FRAMES:
        fd = (twist(h, frame) - twist(-h, frame)) / (2 * h)
        got = acceleration(chain, th, thd, thdd, frame)
        bound = fd_tol(lambda s, frame=frame: twist(s[0], frame), np.zeros(1), h) + inner / h
        assert within(got, fd, bound), (frame, got, fd, bound)
    # p̈ straight from positions: no twist in between; second difference h²/12·max|p''''| + rounding (fd2_tol)
    p = lambda t: chain.fk(th + t * thd + 0.5 * t * t * thdd)[:3, 3]
    pdd = (p(h) - 2 * p(0.0) + p(-h)) / h**2
    assert within(acceleration(chain, th, thd, thdd)[3:], pdd, fd2_tol(p, 0.0, h))


def test_acceleration_batched():
    rng = np.random.default_rng(5)
    chain = jac.robots.ur5()
    th = random_theta(chain, rng, size=(4,))
    thd, thdd = rng.normal(size=(4, 6)), rng.normal(size=(4, 6))
    got = acceleration(chain, th, thd, thdd, "body")
    assert got.shape == (4, 6)
    for k in range(4):
        assert close(got[k], acceleration(chain, th[k], thd[k], thdd[k], "body"))


def test_against_pinocchio_time_variation():
    pin = pytest.importorskip("pinocchio")
    from jacobians.interop import SWAP, to_pinocchio_model

    rng = np.random.default_rng(11)
    refs = {"space": pin.ReferenceFrame.WORLD, "body": pin.ReferenceFrame.LOCAL,
            "geometric": pin.ReferenceFrame.LOCAL_WORLD_ALIGNED}
    chains = [jac.robots.ur5(), jac.robots.spatial_rrp(), jac.robots.scara()] + [
        random_chain(rng, pitch_probability=0.0) for _ in range(6)]
    for chain in chains:
        model, fid = to_pinocchio_model(chain)
        data = model.createData()
        for _ in range(3):
            q, v = random_theta(chain, rng), rng.normal(size=chain.dof)
            pin.computeJointJacobiansTimeVariation(model, data, q, v)
            pin.updateFramePlacements(model, data)
            for frame, ref in refs.items():
                theirs = SWAP @ np.reshape(pin.getFrameJacobianTimeVariation(model, data, fid, ref), (6, chain.dof))
                # two exact computations of the same well-conditioned products: TOL relative (close)
                assert close(theirs, jacobian_derivative(chain, q, v, frame)), (frame, q, v)


def test_validation():
    arm = jac.robots.planar_2r()
    with pytest.raises(ValueError, match="frame 'space', 'body' or 'geometric'"):
        jacobian_derivative(arm, [0, 0], [1, 0], "analytic")
    with pytest.raises(ValueError, match=r"theta_dot with shape \(\.\.\., 2\)"):
        jacobian_derivative(arm, [0, 0], [1, 0, 0])
    with pytest.raises(ValueError, match="do not broadcast"):
        jacobian_derivative(arm, np.zeros((3, 2)), np.zeros((4, 2)))
    with pytest.raises(TypeError, match="SerialChain"):
        jacobian_derivative("arm", [0, 0], [1, 0])
    with pytest.raises(ValueError, match="finite"):
        acceleration(arm, [0, 0], [1, 0], [np.nan, 0])
    with pytest.raises(ValueError, match="theta_ddot"):
        acceleration(arm, np.zeros((3, 2)), [1, 0], np.zeros((4, 2)))
