"""Tests of jacobians.analysis: hand-computed values, SVD from numpy/scipy,
ellipsoid definitions checked by sampling, property tests over random chains and batch shapes."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import analysis as an
from jacobians.testing import random_chain, random_theta

RNG = np.random.default_rng(7)


def _planar_2r_Jv(l1, l2, t1, t2):
    """The 2 x 2 position Jacobian of a planar 2R arm, from the forward kinematics by hand."""
    s1, c1, s12, c12 = np.sin(t1), np.cos(t1), np.sin(t1 + t2), np.cos(t1 + t2)
    return np.array([[-l1 * s1 - l2 * s12, -l2 * s12], [l1 * c1 + l2 * c12, l2 * c12]])


# ------------------------------------------------------------------ hand-computed values

def test_planar_2r_position_rows_match_hand_derivation_and_finite_differences():
    l1, l2 = 0.7, 0.4
    arm = jac.robots.planar_2r(l1, l2)
    for theta in RNG.uniform(-np.pi, np.pi, (5, 2)):
        J_v = an.linear_rows(jac.geometric_jacobian(arm, theta))[:2]
        assert np.allclose(J_v, _planar_2r_Jv(l1, l2, *theta), atol=1e-12)
        fd = jac.numerical_jacobian(lambda th: arm.fk(th)[:2, 3], theta)
        assert np.allclose(J_v, fd, atol=1e-8)


def test_planar_2r_manipulability_is_l1_l2_abs_sin_theta2():
    l1, l2 = 0.7, 0.4
    arm = jac.robots.planar_2r(l1, l2)
    thetas = RNG.uniform(-np.pi, np.pi, (50, 2))
    J_v = jac.geometric_jacobian(arm, thetas)[..., 3:5, :]
    w = an.manipulability(J_v)
    assert w.shape == (50,)
    assert np.allclose(w, l1 * l2 * np.abs(np.sin(thetas[:, 1])), atol=1e-12)
    # and it is Yoshikawa's sqrt(det(J J^T)) for a square or wide matrix
    assert np.allclose(w, np.sqrt(np.linalg.det(J_v @ np.swapaxes(J_v, -1, -2))), atol=1e-12)


def test_manipulability_of_wide_matrix_is_sqrt_det_JJT():
    J = RNG.normal(size=(10, 3, 5))
    assert np.allclose(an.manipulability(J), np.sqrt(np.linalg.det(J @ np.swapaxes(J, -1, -2))))


def test_manipulability_of_tall_matrix_is_sqrt_det_JTJ():
    J = RNG.normal(size=(4, 6, 2))
    assert np.allclose(an.manipulability(J), np.sqrt(np.linalg.det(np.swapaxes(J, -1, -2) @ J)))


def test_condition_number_and_isotropy_by_hand():
    # J_v of a 2R arm with l1 = sqrt(2) l2... pick the textbook isotropic case:
    # l1 = sqrt(2), l2 = 1, theta2 = 3 pi / 4 makes J_v J_v^T a multiple of I
    arm = jac.robots.planar_2r(np.sqrt(2.0), 1.0)
    J_v = jac.geometric_jacobian(arm, [0.3, 3 * np.pi / 4])[3:5]
    JJt = J_v @ J_v.T
    assert np.allclose(JJt, JJt[0, 0] * np.eye(2), atol=1e-12)  # isotropic, checked directly
    assert np.isclose(an.condition_number(J_v), 1.0)
    assert np.isclose(an.isotropy(J_v), 1.0)
    D = np.diag([3.0, 0.5])
    assert np.isclose(an.condition_number(D), 6.0)
    assert np.isclose(an.isotropy(D), 1 / 6)
    assert an.condition_number(np.zeros((2, 2))) == np.inf
    assert an.isotropy(np.zeros((2, 2))) == 0.0
    assert an.condition_number([[1.0, 0.0], [0.0, 0.0]]) == np.inf


def test_condition_number_matches_numpy_cond():
    J = RNG.normal(size=(20, 3, 4))
    assert np.allclose(an.condition_number(J), np.linalg.cond(J))


def test_singular_values_match_scipy():
    for shape in [(6, 3), (3, 6), (6, 6), (2, 2), (1, 4)]:
        A = RNG.normal(size=shape)
        assert np.allclose(an.singular_values(A), scipy.linalg.svdvals(A))


def test_rows_selection():
    J = np.arange(12.0).reshape(6, 2)
    assert np.array_equal(an.angular_rows(J), J[:3])
    assert np.array_equal(an.linear_rows(J), J[3:])
    Jb = np.broadcast_to(J, (4, 6, 2))
    assert an.linear_rows(Jb).shape == (4, 3, 2)
    out = an.linear_rows(J)
    out[0, 0] = 99.0  # a copy, not a view into J
    assert J[3, 0] == 6.0


def test_space_linear_rows_are_not_the_hand_velocity():
    """The docstring's warning, checked: v_s differs from p-dot away from the origin."""
    arm = jac.robots.planar_2r()
    theta = np.array([0.4, 0.9])
    fd = jac.numerical_jacobian(lambda th: arm.fk(th)[:3, 3], theta)
    assert np.allclose(an.linear_rows(jac.geometric_jacobian(arm, theta)), fd, atol=1e-8)
    assert not np.allclose(an.linear_rows(jac.space_jacobian(arm, theta)), fd, atol=1e-3)
    R = arm.fk(theta)[:3, :3]
    assert np.allclose(R @ an.linear_rows(jac.body_jacobian(arm, theta)), fd, atol=1e-8)


# ------------------------------------------------------------------ ellipsoids

def test_velocity_ellipsoid_by_hand():
    axes, U = an.velocity_ellipsoid(np.diag([0.5, 2.0]))
    assert np.allclose(axes, [2.0, 0.5])
    assert np.allclose(np.abs(U), [[0, 1], [1, 0]])


def test_velocity_ellipsoid_is_the_image_of_the_unit_ball():
    """Sample unit joint rates: every image is on the ellipsoid, and the extremes reach the semi-axes."""
    A = RNG.normal(size=(3, 4))
    axes, U = an.velocity_ellipsoid(A)
    assert np.all(np.diff(axes) <= 0)
    assert np.allclose(U.T @ U, np.eye(3))
    q = RNG.normal(size=(4, 20000))
    q /= np.linalg.norm(q, axis=0)
    y = U.T @ (A @ q)  # coordinates along the semi-axes
    # ||qdot|| = 1 maps inside the ellipsoid sum (y_i / a_i)^2 <= 1 (== 1 on the row space)
    assert np.all(np.sum((y / axes[:, None]) ** 2, axis=0) <= 1 + 1e-9)
    # the largest reach along direction i is the semi-axis i
    assert np.allclose(np.abs(y).max(axis=1), axes, rtol=0.05)
    # and A^T u_i / sigma_i is a unit rate reaching exactly sigma_i u_i
    for i in range(3):
        qi = A.T @ U[:, i] / axes[i] ** 2 * axes[i]
        assert np.isclose(np.linalg.norm(qi), 1.0)
        assert np.allclose(A @ qi, axes[i] * U[:, i])


def test_velocity_ellipsoid_flat_when_fewer_joints_than_rows():
    A = RNG.normal(size=(3, 2))
    axes, U = an.velocity_ellipsoid(A)
    assert axes.shape == (3,) and U.shape == (3, 3)
    assert axes[2] == 0.0 and axes[1] > 0
    assert np.allclose(U[:, 2] @ A, 0, atol=1e-12)  # the unreachable direction


def test_force_ellipsoid_is_reciprocal_with_same_directions():
    A = RNG.normal(size=(2, 3))
    v_axes, v_dirs = an.velocity_ellipsoid(A)
    f_axes, f_dirs = an.force_ellipsoid(A)
    assert np.allclose(f_axes, 1 / v_axes)
    assert np.array_equal(f_dirs, v_dirs)
    # definition: a force of size 1/sigma_i along u_i needs a unit torque
    for i in range(2):
        tau = A.T @ (f_axes[i] * f_dirs[:, i])
        assert np.isclose(np.linalg.norm(tau), 1.0)


def test_force_ellipsoid_infinite_along_singular_directions():
    arm = jac.robots.planar_2r()
    J_v = jac.geometric_jacobian(arm, [0.3, 0.0])[3:5]  # stretched out: radial direction lost
    f_axes, dirs = an.force_ellipsoid(J_v)
    assert np.isinf(f_axes[1]) and np.isfinite(f_axes[0])
    radial = np.array([np.cos(0.3), np.sin(0.3)])
    assert np.isclose(abs(dirs[:, 1] @ radial), 1.0)  # the arm resists any radial force with no torque
    assert np.allclose(J_v.T @ radial, 0, atol=1e-12)
    assert np.all(np.isinf(an.force_ellipsoid(np.zeros((2, 3)))[0]))
    # rtol decides what counts as zero
    assert np.isfinite(an.force_ellipsoid(np.diag([1.0, 1e-9]), rtol=1e-12)[0]).all()
    assert np.isinf(an.force_ellipsoid(np.diag([1.0, 1e-9]), rtol=1e-6)[0][1])


# ------------------------------------------------------------------ singularities and null space

def test_is_singular_planar_2r():
    arm = jac.robots.planar_2r()
    thetas = np.array([[0.2, 0.0], [0.2, np.pi], [0.2, 0.5], [1.0, -2.0]])
    J_v = jac.geometric_jacobian(arm, thetas)[..., 3:5, :]
    assert list(an.is_singular(J_v)) == [True, True, False, False]
    assert np.allclose(an.singularity_measure(J_v)[:2], 0, atol=1e-12)
    assert bool(an.is_singular(np.zeros((3, 3))))
    # scale-free: units of length do not matter
    assert not an.is_singular(1e-6 * np.eye(3))


def test_is_singular_tall_and_wide():
    wide = np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0]])  # rank 1 < 2
    tall = wide.T.copy()
    assert an.is_singular(wide) and an.is_singular(tall)
    assert not an.is_singular(np.array([[1.0, 0.0, 3.0], [0.0, 1.0, 0.0]]))


def test_ur5_singularity_wrist_alignment():
    # theta5 = 0 lines up joint axes 4 and 6 of the UR5: the 6 x 6 J_s loses rank
    ur5 = jac.robots.ur5()
    theta = np.array([0.1, -0.7, 1.1, 0.3, 0.0, 0.5])
    assert an.is_singular(jac.space_jacobian(ur5, theta))
    theta[4] = 0.6
    assert not an.is_singular(jac.space_jacobian(ur5, theta))


def test_nullspace_and_projector():
    arm = jac.robots.planar_3r()
    theta = np.array([0.3, 0.8, -0.4])
    J_v = jac.geometric_jacobian(arm, theta)[3:5]
    N = an.nullspace(J_v)
    assert N.shape == (3, 1)
    assert np.allclose(J_v @ N, 0, atol=1e-12)
    assert np.isclose(np.linalg.norm(N), 1.0)
    # a self-motion: moving along N keeps the tip still (first order)
    p0 = arm.fk(theta)[:2, 3]
    p1 = arm.fk(theta + 1e-5 * N[:, 0])[:2, 3]
    assert np.linalg.norm(p1 - p0) < 1e-9
    P = an.nullspace_projector(J_v)
    assert np.allclose(P, N @ N.T, atol=1e-12)
    assert np.allclose(scipy.linalg.null_space(J_v) @ scipy.linalg.null_space(J_v).T, P, atol=1e-12)
    # batched projector, with a singular member (rank drop makes the null space bigger)
    thetas = np.array([[0.3, 0.8, -0.4], [0.3, 0.0, 0.0]])
    Ps = an.nullspace_projector(jac.geometric_jacobian(arm, thetas)[..., 3:5, :])
    assert np.allclose(np.trace(Ps, axis1=-2, axis2=-1), [1.0, 2.0])
    assert an.nullspace(np.eye(3)).shape == (3, 0)
    assert an.nullspace(np.zeros((2, 3))).shape == (3, 3)


# ------------------------------------------------------------------ properties over random chains

@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), batch=st.sampled_from([(), (3,), (2, 4)]))
def test_properties_over_random_chains_and_batches(seed, batch):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng, size=batch)
    J = jac.geometric_jacobian(chain, theta)
    s = an.singular_values(J)
    r = min(6, chain.dof)
    assert s.shape == batch + (r,)
    assert np.all(np.diff(s, axis=-1) <= 1e-12) and np.all(s >= 0)
    # same as numpy's SVD entry by entry
    flat = J.reshape((-1, 6, chain.dof))
    assert np.allclose(s.reshape(-1, r), [np.linalg.svd(j, compute_uv=False) for j in flat])
    # frame changes by a rotation do not change singular values of one kind of rows
    J_b = jac.body_jacobian(chain, theta)
    assert np.allclose(an.singular_values(an.linear_rows(J_b)), an.singular_values(an.linear_rows(J)), atol=1e-9)
    assert np.allclose(an.manipulability(an.angular_rows(J_b)), an.manipulability(an.angular_rows(J)), atol=1e-9)
    # ellipsoid: A A^T = U diag(axes^2) U^T
    A = an.linear_rows(J)
    axes, U = an.velocity_ellipsoid(A)
    assert axes.shape == batch + (3,) and U.shape == batch + (3, 3)
    AAt = A @ np.swapaxes(A, -1, -2)
    assert np.allclose(U @ (axes[..., :, None] ** 2 * np.swapaxes(U, -1, -2)), AAt, atol=1e-9)
    # condition * isotropy = 1 where finite
    k, iso = an.condition_number(J), an.isotropy(J)
    fin = np.isfinite(k)
    assert np.allclose((k * iso)[fin], 1.0)
    assert an.is_singular(J).shape == batch


# ------------------------------------------------------------------ bad input

@pytest.mark.parametrize("call, exc, match", [
    (lambda: an.singular_values("J"), TypeError, "real numbers"),
    (lambda: an.singular_values([1.0, 2.0]), ValueError, r"\(\.\.\., m, n\)"),
    (lambda: an.singular_values(np.zeros((2, 0))), ValueError, "at least one row"),
    (lambda: an.singular_values([[1.0, np.nan]]), ValueError, "finite"),
    (lambda: an.manipulability(np.ones((2, 2)) * 1j), TypeError, "complex"),
    (lambda: an.linear_rows(np.zeros((3, 2))), ValueError, r"\(\.\.\., 6, n\)"),
    (lambda: an.angular_rows(np.zeros((2, 6))), ValueError, "transposed"),
    (lambda: an.is_singular(np.eye(2), tol=-1), ValueError, "positive"),
    (lambda: an.is_singular(np.eye(2), tol="small"), TypeError, "real number"),
    (lambda: an.force_ellipsoid(np.eye(2), rtol=0), ValueError, "positive"),
    (lambda: an.nullspace(np.zeros((2, 2, 3))), ValueError, "nullspace_projector"),
    (lambda: an.velocity_ellipsoid(None), TypeError, "real numbers"),
])
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_reexports_are_the_same_functions():
    assert an.pinv_rates is jac.velocity.pinv_rates
    assert an.dls_rates is jac.velocity.dls_rates
    assert an.joint_torques is jac.statics.joint_torques
