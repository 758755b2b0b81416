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


# ---------------------------------------------------------------- task priority and the weighted pseudo-inverse

from jacobians.redundancy import task_priority_rates, weighted_pinv_rates  # noqa: E402


@settings(max_examples=40, deadline=None)
@given(seeds)
def test_task_priority_primary_exact_and_secondary_least_squares(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 8))
    m1 = int(rng.integers(1, n))
    m2 = int(rng.integers(1, n + 1))
    J1, J2 = rng.normal(size=(m1, n)), rng.normal(size=(m2, n))
    x1, x2 = rng.normal(size=m1), rng.normal(size=m2)
    P1 = nullspace_projector(J1)
    base = np.linalg.pinv(J1) @ x1
    z_best = np.linalg.lstsq(J2 @ P1, x2 - J2 @ base, rcond=1e-10)[0]        # J2 P1 has rank <= n - m1: drop rounding
    best = np.linalg.norm(J2 @ (base + P1 @ z_best) - x2)
    for method in ("nakamura", "singularity_robust"):
        qd = task_priority_rates(J1, x1, J2, x2, method=method)
        assert np.allclose(J1 @ qd, x1, atol=1e-9)                               # primary exact
        assert np.allclose(qd - base, P1 @ (qd - base), atol=1e-9)               # the rest is in N(J1)
    qd = task_priority_rates(J1, x1, J2, x2)
    assert np.isclose(np.linalg.norm(J2 @ qd - x2), best, atol=1e-8)             # secondary: the least error
    if m2 <= n - m1:                                                             # J2 P1 full row rank (generic)
        assert np.allclose(J2 @ qd, x2, atol=1e-8)


def test_rank_of_j2p1_is_the_rank_the_stacked_rows_add():
    """rank(J2 P1) = rank [J1; J2] - rank J1: an algorithmic singularity is a dependence between the two tasks."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        n = int(rng.integers(3, 7))
        m1, m2 = int(rng.integers(1, n)), int(rng.integers(1, n))
        J1, J2 = rng.normal(size=(m1, n)), rng.normal(size=(m2, n))
        if rng.random() < 0.5:                                                   # make a row of J2 depend on J1
            J2[0] = rng.normal(size=m1) @ J1 + (rng.normal(size=m2 - 1) @ J2[1:] if m2 > 1 else 0)
        r = np.linalg.matrix_rank
        assert r(J2 @ nullspace_projector(J1), tol=1e-8) == r(np.vstack([J1, J2]), tol=1e-8) - r(J1, tol=1e-8)


def test_algorithmic_singularity_blows_up_nakamura_and_not_the_robust_forms():
    """Planar 3R: tip (primary) and last-link angle (secondary). J1, J2 full rank; J2 P1 singular at theta2 = 0."""
    arm = jac.robots.planar_3r()
    x1, x2 = np.array([0.1, 0.0]), np.array([0.5])
    norms = {}
    for t2 in (1e-1, 1e-2, 1e-3, 1e-4):
        th = np.array([0.3, t2, 1.2])
        J = jac.geometric_jacobian(arm, th)
        J1, J2 = J[3:5], J[2:3]
        assert manipulability(J1) > 0.5 and np.allclose(J2, 1.0)                # neither task is singular
        nak = task_priority_rates(J1, x1, J2, x2)
        sr = task_priority_rates(J1, x1, J2, x2, method="singularity_robust")
        dmp = task_priority_rates(J1, x1, J2, x2, damping=0.1)
        norms[t2] = np.linalg.norm(nak)
        base = np.linalg.pinv(J1) @ x1
        assert np.linalg.norm(sr) <= np.linalg.norm(base) + np.linalg.norm(np.linalg.pinv(J2) @ x2) + 1e-12
        rest = x2 - J2 @ base
        assert np.linalg.norm(dmp) <= np.linalg.norm(base) + np.linalg.norm(rest) / (2 * 0.1) + 1e-12
        for qd in (nak, sr, dmp):
            assert np.allclose(J1 @ qd, x1, atol=1e-8)
    # sigma(J2 P1) = |P1 (1,1,1)| is proportional to |sin theta2| near 0: the undamped rates grow like 1/theta2
    assert 8 < norms[1e-2] / norms[1e-1] < 12 and 8 < norms[1e-4] / norms[1e-3] < 12


def test_task_priority_bad_input():
    J1, J2 = np.eye(2, 3), np.ones((1, 3))
    with pytest.raises(ValueError, match="same n"):
        task_priority_rates(J1, [1, 1], np.ones((1, 4)), [1])
    with pytest.raises(ValueError, match="damping"):
        task_priority_rates(J1, [1, 1], J2, [1], damping=-1.0)
    with pytest.raises(ValueError, match="method"):
        task_priority_rates(J1, [1, 1], J2, [1], method="chiaverini-ish")
    with pytest.raises(ValueError, match="V1"):
        task_priority_rates(J1, [1, 1, 1], J2, [1])


@settings(max_examples=40, deadline=None)
@given(seeds)
def test_weighted_pinv_is_the_weighted_least_norm_solution(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    m = int(rng.integers(1, n + 1))
    J, V = rng.normal(size=(m, n)), rng.normal(size=m)
    A = rng.normal(size=(n, n))
    W = A @ A.T + 0.1 * np.eye(n)
    qd = weighted_pinv_rates(J, V, W)
    # KKT system of: minimise qd^T W qd / 2 subject to J qd = V
    K = np.block([[W, J.T], [J, np.zeros((m, m))]])
    assert np.allclose(qd, np.linalg.solve(K, np.r_[np.zeros(n), V])[:n], atol=1e-7 * max(1, np.abs(qd).max()))
    assert np.allclose(weighted_pinv_rates(J, V, np.eye(n)), np.linalg.pinv(J) @ V)


def test_weighted_pinv_bad_weight():
    J = np.ones((1, 2))
    with pytest.raises(ValueError, match="symmetric"):
        weighted_pinv_rates(J, [1.0], [[1.0, 1.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match="positive definite"):
        weighted_pinv_rates(J, [1.0], [[1.0, 0.0], [0.0, -1.0]])
    with pytest.raises(ValueError, match="shapes"):
        weighted_pinv_rates(J, [1.0], np.eye(3))
