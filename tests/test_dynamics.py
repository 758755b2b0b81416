"""Tests of the gravity torques (jacobians.dynamics).

Oracles: finite differences of the potential energy, the sum over link Jacobians written out,
Pinocchio's computeGeneralizedGravity and Modern Robotics' GravityForces on the same masses.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians.dynamics import centres_of_mass, gravity_torques, potential_energy
from jacobians.testing import close, fd_tol, random_chain, random_theta, within

seeds = st.integers(0, 2**32 - 1)


def _problem(rng, chain):
    n = chain.dof
    return rng.uniform(0.1, 3.0, n), 0.3 * rng.normal(size=(n, 3)), rng.normal(size=3) * 5


@settings(max_examples=50, deadline=None)
@given(seeds)
def test_gravity_is_the_gradient_of_potential_energy(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    m, c, g = _problem(rng, chain)
    fd = jac.numerical_jacobian(lambda t: potential_energy(chain, t, m, g, c), theta)
    # central differences: truncation h²/6·max|P'''| + rounding 512·EPS·max|P|/h (fd_tol, constants from P itself)
    bound = fd_tol(lambda t: potential_energy(chain, t, m, g, c), theta)
    assert within(gravity_torques(chain, theta, m, g, c), fd, bound)


@settings(max_examples=30, deadline=None)
@given(seeds)
def test_equals_sum_of_link_jacobian_transposes(seed):
    """τ_g = -Σ J_{v,c_i}ᵀ m_i g with J_{v,c_i} the linear rows of the geometric link Jacobian at the centre."""
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    m, c, g = _problem(rng, chain)
    # move each link frame to its centre of mass, keep its orientation: the link Jacobians of that chain
    homes = chain.link_homes.copy()
    homes[:, :3, 3] += (homes[:, :3, :3] @ c[:, :, None])[..., 0]
    at_com = jac.SerialChain(chain.screw_axes, chain.home, link_homes=homes)
    J = jac.link_jacobians(at_com, theta, "geometric")  # (n, 6, n)
    expected = -sum(J[i, 3:].T @ (m[i] * g) for i in range(chain.dof))
    # two exact sums of the same terms m_i J_iᵀ g: rounding relative to the terms' size, not to τ (which may cancel)
    terms = max(float(np.abs(J[i, 3:].T @ (m[i] * g)).max()) for i in range(chain.dof))
    assert close(gravity_torques(chain, theta, m, g, c), expected, scale=chain.dof * terms)


def test_batched_and_defaults():
    rng = np.random.default_rng(2)
    chain = jac.robots.ur5()
    th = random_theta(chain, rng, size=(2, 3))
    m = rng.uniform(1, 2, 6)
    got = gravity_torques(chain, th, m)
    assert got.shape == (2, 3, 6)
    for idx in np.ndindex(2, 3):
        assert close(got[idx], gravity_torques(chain, th[idx], m, [0, 0, -9.81], np.zeros((6, 3))))   # same sums
    assert centres_of_mass(chain, th).shape == (2, 3, 6, 3)
    assert potential_energy(chain, th, m).shape == (2, 3)
    # planar arm, gravity in its plane: the horizontal arm's torques are m g times the lever arms
    arm = jac.robots.planar_2r(l1=1.0, l2=0.5)
    assert close(gravity_torques(arm, [0, 0], [2.0, 1.0], [0, -10, 0]), [2 * 10 * 0.5 + 10 * 1.25, 10 * 0.25])
    # straight up: the torques are differences of terms m g l of size up to 25 (cos(π/2) ≠ 0 in floats)
    assert close(gravity_torques(arm, [np.pi / 2, 0], [2.0, 1.0], [0, -10, 0]), 0, scale=25.0)


def _pinocchio_model_with_masses(pin, chain, masses, centres):
    from jacobians.interop import to_pinocchio_model

    model, _ = to_pinocchio_model(chain)
    data = model.createData()
    pin.forwardKinematics(model, data, np.zeros(chain.dof))
    for i in range(chain.dof):
        com_home = chain.link_homes[i, :3, :3] @ centres[i] + chain.link_homes[i, :3, 3]
        lever = data.oMi[i + 1].actInv(com_home)  # the centre in joint i's frame, at home
        model.inertias[i + 1] = pin.Inertia(float(masses[i]), lever, 0.01 * np.eye(3))
    return model


def test_against_pinocchio_generalized_gravity():
    pin = pytest.importorskip("pinocchio")
    rng = np.random.default_rng(4)
    chains = [jac.robots.ur5(), jac.robots.scara(), jac.robots.spatial_rrp()] + [
        random_chain(rng, pitch_probability=0.0) for _ in range(5)]
    for chain in chains:
        m, c, _ = _problem(rng, chain)
        model = _pinocchio_model_with_masses(pin, chain, m, c)
        data = model.createData()
        for _ in range(3):
            q = random_theta(chain, rng)
            theirs = pin.computeGeneralizedGravity(model, data, q)  # model.gravity: (0, 0, -9.81)
            # well-conditioned sums of m g |r|: 1e-12 relative to the torques' scale (jacobians.testing.close)
            assert close(theirs, gravity_torques(chain, q, m, centres=c))


def test_against_modern_robotics_gravity_forces():
    mr = pytest.importorskip("modern_robotics")
    rng = np.random.default_rng(5)
    for chain in [jac.robots.ur5(), random_chain(rng, dof=5, pitch_probability=0.0)]:
        m, c, g = _problem(rng, chain)
        F = chain.link_homes.copy()
        F[:, :3, 3] += (F[:, :3, :3] @ c[:, :, None])[..., 0]  # centre-of-mass frames at home
        Mlist = [F[0]] + [np.linalg.inv(F[i - 1]) @ F[i] for i in range(1, chain.dof)] + [np.linalg.inv(F[-1]) @ chain.home]
        Glist = [np.diag([0.01, 0.01, 0.01, mi, mi, mi]) for mi in m]
        for _ in range(3):
            q = random_theta(chain, rng)
            theirs = mr.GravityForces(q, g, Mlist, Glist, chain.screw_axes)
            assert close(theirs, gravity_torques(chain, q, m, g, c))


def test_validation():
    arm = jac.robots.planar_2r()
    with pytest.raises(ValueError, match=r"masses with shape \(2,\)"):
        gravity_torques(arm, [0, 0], [1.0])
    with pytest.raises(ValueError, match="non-negative masses"):
        gravity_torques(arm, [0, 0], [1.0, -1.0])
    with pytest.raises(ValueError, match=r"gravity with shape \(3,\)"):
        gravity_torques(arm, [0, 0], [1.0, 1.0], gravity=[0, -9.81])
    with pytest.raises(ValueError, match=r"centres with shape \(2, 3\)"):
        gravity_torques(arm, [0, 0], [1.0, 1.0], centres=np.zeros((3, 3)))
    with pytest.raises(TypeError, match="real numbers for masses"):
        gravity_torques(arm, [0, 0], "heavy")
    with pytest.raises(TypeError, match="SerialChain"):
        gravity_torques(None, [0, 0], [1.0, 1.0])
