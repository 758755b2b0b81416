"""Tests of the redundancy helpers (jacobians.redundancy): null-space motion and the gradient of manipulability."""

import numpy as np
import pytest
from fp_bounds import gamma, solve_bound
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians.analysis import manipulability, nullspace_projector
from jacobians.redundancy import manipulability_gradient, redundant_rates
from jacobians.testing import random_chain, random_theta

seeds = st.integers(0, 2**32 - 1)


@settings(max_examples=50, deadline=None)
@given(seeds, st.sampled_from([None, [3, 4], [0, 1, 2], [3, 4, 5]]), st.sampled_from(["space", "body", "geometric"]))
def test_manipulability_gradient_against_finite_differences(seed, rows, frame):
    rng = np.random.default_rng(seed)
    k = 6 if rows is None else len(rows)
    chain = random_chain(rng, dof=int(rng.integers(k, 8)))
    theta = random_theta(chain, rng)
    r = list(range(6)) if rows is None else rows
    w = lambda t: manipulability(jac.jacobian(chain, t, frame)[r])
    if w(theta) < 1e-3:  # w has a kink at a singularity: no derivative to compare with
        return
    fd = jac.numerical_jacobian(w, theta)
    got = manipulability_gradient(chain, theta, frame, rows)
    assert np.allclose(got, fd, atol=1e-6 * max(1.0, np.abs(fd).max())), (got, fd)


def test_planar_closed_forms_and_batch():
    arm = jac.robots.planar_2r(l1=1.0, l2=0.7)
    th = np.array([[0.3, 0.5], [1.0, -2.0]])
    got = manipulability_gradient(arm, th, rows=[3, 4])  # w = l1 l2 |sin θ2|
    assert np.allclose(got, [[0.0, 0.7 * np.cos(0.5)], [0.0, 0.7 * np.sign(np.sin(-2.0)) * np.cos(-2.0)]])
    arm3 = jac.robots.planar_3r()
    batch = random_theta(arm3, 0, size=(2, 3))
    g = manipulability_gradient(arm3, batch, rows=[3, 4])
    assert g.shape == (2, 3, 3)
    for idx in np.ndindex(2, 3):
        assert np.allclose(g[idx], manipulability_gradient(arm3, batch[idx], rows=[3, 4]))
    # joint 1 turns the whole planar arm: w cannot depend on it
    assert np.allclose(g[..., 0], 0, atol=1e-12)


def test_gradient_ascent_in_the_null_space_raises_w_and_keeps_the_tip():
    arm = jac.robots.planar_3r()
    theta = np.array([0.0, 0.3, 2.6])  # a cramped pose: the last link folded back
    tip = arm.fk(theta)[:2, 3]
    w0 = manipulability(jac.geometric_jacobian(arm, theta)[3:5])
    for _ in range(200):
        J = jac.geometric_jacobian(arm, theta)[3:5]
        z = manipulability_gradient(arm, theta, rows=[3, 4])
        theta = theta + 0.01 * redundant_rates(J, np.zeros(2), z)
    w1 = manipulability(jac.geometric_jacobian(arm, theta)[3:5])
    assert w1 > w0 + 0.3
    assert np.allclose(arm.fk(theta)[:2, 3], tip, atol=2e-3)  # only first-order drift of the Euler steps


@settings(max_examples=40, deadline=None)
@given(seeds)
def test_redundant_rates_solve_the_task_for_every_z(seed):
    rng = np.random.default_rng(seed)
    m, n = 2, int(rng.integers(3, 7))
    J, V, z = rng.normal(size=(m, n)), rng.normal(size=m), rng.normal(size=n)
    qd = redundant_rates(J, V, z)
    # Tolerances from the conditioning of a random J (fp_bounds, derived there): the computed qd is exact
    # for J + δJ with |δJ| <= γ|J|, so |J qd - V| <= 2γ (|J| |qd| + |V|); the least-norm part moves by
    # solve_bound (κ = σ_max/σ_min), the projection of z by 2κγ|z| (J⁺J's sensitivity) on each side.
    g = gamma(m, n)
    sigma = np.linalg.svd(J, compute_uv=False)
    kappa = sigma[0] / sigma[-1]
    assert np.linalg.norm(J @ qd - V) <= 2 * g * (sigma[0] * np.linalg.norm(qd) + np.linalg.norm(V))
    base = np.linalg.pinv(J) @ V
    apart = solve_bound(J, V, base) + 8 * kappa * g * np.linalg.norm(z)
    assert np.linalg.norm(qd - (base + (np.eye(n) - np.linalg.pinv(J) @ J) @ z)) <= apart
    # the null-space part is orthogonal to the least-norm part
    assert abs(base @ (qd - base)) <= np.linalg.norm(base) * (apart + 4 * g * np.linalg.norm(qd))
    assert np.allclose(nullspace_projector(J) @ nullspace_projector(J), nullspace_projector(J), atol=1e-12)


def test_validation():
    arm = jac.robots.planar_2r()
    with pytest.raises(ValueError, match="at most 2 rows"):
        manipulability_gradient(arm, [0, 1], rows=[3, 4, 5])
    with pytest.raises(ValueError, match="indices in 0..5"):
        manipulability_gradient(arm, [0, 1], rows=[3, 6])
    with pytest.raises(ValueError, match="distinct"):
        manipulability_gradient(arm, [0, 1], rows=[3, 3])
    with pytest.raises(TypeError, match="sequence of row indices"):
        manipulability_gradient(arm, [0, 1], rows="xy")
    with pytest.raises(ValueError, match="frame 'space', 'body' or 'geometric'"):
        manipulability_gradient(arm, [0, 1], frame="analytic", rows=[3, 4])
    with pytest.raises(ValueError, match="same n"):
        redundant_rates(np.eye(2, 3), [1, 1], [1, 1])
