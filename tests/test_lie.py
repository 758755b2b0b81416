"""Tests of jacobians.lie: exp/log, adjoint, small ad, batching."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from jacobians import lie
from jacobians.testing import TOL, close, random_rotation, random_transform

seeds = st.integers(0, 2**32 - 1)
batch_shapes = st.sampled_from([(), (1,), (4,), (2, 3), (3, 1, 2)])


def test_skew_matches_cross_product():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(2, 5, 3))
    assert np.allclose(lie.skew(a) @ b[..., None], np.cross(a, b)[..., None])
    assert np.allclose(lie.unskew(lie.skew(a)), a)
    assert np.allclose(lie.skew(a), -np.swapaxes(lie.skew(a), -1, -2))


@given(seeds, batch_shapes)
def test_exp_log_so3_round_trip(seed, shape):
    rng = np.random.default_rng(seed)
    R = random_rotation(rng, shape)
    w = lie.log_so3(R)
    assert w.shape == shape + (3,)
    assert np.all(np.linalg.norm(w, axis=-1) <= np.pi + 1e-12)
    assert np.allclose(lie.exp_so3(w), R, atol=1e-10)


@pytest.mark.parametrize("angle", [0.0, 1e-12, 1e-8, 1e-5, 1e-3, 0.5, 3.0, np.pi - 1e-3, np.pi - 1e-7, np.pi])
def test_exp_log_so3_near_zero_and_pi(angle):
    rng = np.random.default_rng(1)
    for _ in range(20):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        R = lie.exp_so3(axis * angle)
        w = lie.log_so3(R)
        assert np.allclose(lie.exp_so3(w), R, atol=1e-9)
        assert np.isclose(np.linalg.norm(w), angle, atol=1e-7)
        if angle < np.pi - 1e-2:
            assert np.allclose(w, axis * angle, atol=1e-9)


@given(seeds, batch_shapes)
def test_exp_log_se3_round_trip(seed, shape):
    T = random_transform(np.random.default_rng(seed), shape)
    xi = lie.log_se3(T)
    assert xi.shape == shape + (6,)
    assert np.allclose(lie.exp_se3(xi), T, atol=1e-9)


@pytest.mark.parametrize("angle", [0.0, 1e-9, 1e-4, 1.0, np.pi - 1e-6, np.pi])
def test_exp_log_se3_near_zero_and_pi(angle):
    rng = np.random.default_rng(2)
    for _ in range(10):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        T = lie.exp_se3(np.concatenate([axis * angle, rng.normal(size=3)]))
        assert np.allclose(lie.exp_se3(lie.log_se3(T)), T, atol=1e-8)


def test_exp_se3_is_the_matrix_exponential():
    from scipy.linalg import expm

    rng = np.random.default_rng(3)
    for _ in range(20):
        xi = rng.normal(size=6) * rng.uniform(0, 2)
        assert np.allclose(lie.exp_se3(xi), expm(lie.twist_to_matrix(xi)), atol=1e-10)
    xi = np.array([0, 0, 0, 1.0, -2.0, 0.5])  # pure translation
    assert np.allclose(lie.exp_se3(xi)[:3, 3], xi[3:])


@given(seeds)
def test_adjoint_properties(seed):
    rng = np.random.default_rng(seed)
    T1, T2 = random_transform(rng, 2)
    V = rng.normal(size=6)
    # Ad_T V is the twist T [V] T^-1
    lhs = lie.twist_to_matrix(lie.adjoint(T1) @ V)
    rhs = T1 @ lie.twist_to_matrix(V) @ np.linalg.inv(T1)
    assert np.allclose(lhs, rhs, atol=1e-10)
    # homomorphism and inverse
    assert np.allclose(lie.adjoint(T1 @ T2), lie.adjoint(T1) @ lie.adjoint(T2), atol=1e-10)
    assert np.allclose(lie.adjoint(lie.inverse_transform(T1)), np.linalg.inv(lie.adjoint(T1)), atol=1e-9)


@given(seeds)
def test_small_ad_is_the_lie_bracket(seed):
    rng = np.random.default_rng(seed)
    V1, V2 = rng.normal(size=(2, 6))
    A, B = lie.twist_to_matrix(V1), lie.twist_to_matrix(V2)
    assert np.allclose(lie.twist_to_matrix(lie.ad(V1) @ V2), A @ B - B @ A, atol=1e-10)
    # d/dt Ad_{exp(t V1)} at t = 0 equals ad_{V1}
    h = 1e-6
    D = (lie.adjoint(lie.exp_se3(h * V1)) - lie.adjoint(lie.exp_se3(-h * V1))) / (2 * h)
    assert np.allclose(D, lie.ad(V1), atol=1e-6)


def test_left_jacobian_and_inverse():
    rng = np.random.default_rng(4)
    for r in [rng.normal(size=3), np.array([1e-9, 0, 0]), np.array([0, 0, np.pi - 1e-4])]:
        Jl, Jinv = lie.left_jacobian_so3(r), lie.left_jacobian_so3_inverse(r)
        assert np.allclose(Jl @ Jinv, np.eye(3), atol=1e-8)
        # omega_s = J_l(r) r_dot: compare with finite differences of exp
        rdot = rng.normal(size=3)
        h = 1e-6
        Rdot = (lie.exp_so3(r + h * rdot) - lie.exp_so3(r - h * rdot)) / (2 * h)
        w_s = lie.unskew(Rdot @ lie.exp_so3(r).T)
        assert np.allclose(w_s, Jl @ rdot, atol=1e-7)


def test_mr_golden_values():
    # Modern Robotics library documentation, Adjoint / MatrixLog6 / MatrixExp6 examples
    T = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 3], [0, 0, 0, 1]], dtype=float)
    expected = np.array([[1, 0, 0, 0, 0, 0], [0, 0, -1, 0, 0, 0], [0, 1, 0, 0, 0, 0],
                         [0, 0, 3, 1, 0, 0], [3, 0, 0, 0, 0, -1], [0, 0, 0, 0, 1, 0]], dtype=float)
    assert np.allclose(lie.adjoint(T), expected)
    assert np.allclose(lie.log_se3(T), [1.57079633, 0, 0, 0, 2.35619449, 2.35619449], atol=1e-8)
    assert np.allclose(lie.exp_se3([1.57079632, 0, 0, 0, 2.35619449, 2.35619449]), T, atol=1e-7)


def test_against_modern_robotics_random():
    mr = pytest.importorskip("modern_robotics")
    rng = np.random.default_rng(5)
    for _ in range(20):
        T = random_transform(rng)
        assert close(lie.adjoint(T), mr.Adjoint(T))
        # log: ω̂ = vee(R - R^T) / (2 sin θ), so an error TOL in R's entries moves θ ω̂ by up to π TOL / sin θ
        theta = np.arccos(np.clip((np.trace(T[:3, :3]) - 1) / 2, -1, 1))
        assert close(lie.twist_to_matrix(lie.log_se3(T)), mr.MatrixLog6(T), TOL * np.pi / np.sin(theta))
        xi = rng.normal(size=6)
        assert close(lie.exp_se3(xi), mr.MatrixExp6(mr.VecTose3(xi)))


@pytest.mark.parametrize(
    "call, error",
    [
        (lambda: lie.skew([1, 2]), ValueError),
        (lambda: lie.skew("abc"), TypeError),
        (lambda: lie.skew(None), TypeError),
        (lambda: lie.skew([1, np.nan, 2]), ValueError),
        (lambda: lie.exp_se3(np.zeros(5)), ValueError),
        (lambda: lie.log_so3(np.ones((3, 3))), ValueError),
        (lambda: lie.log_so3(np.diag([1.0, 1.0, -1.0])), ValueError),
        (lambda: lie.adjoint(np.eye(3)), ValueError),
        (lambda: lie.adjoint(np.zeros((4, 4))), ValueError),
        (lambda: lie.inverse_transform([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]), ValueError),
        (lambda: lie.matrix_to_twist(np.ones((4, 4))), ValueError),
        (lambda: lie.rotation_about("w", 1.0), ValueError),
        (lambda: lie.exp_so3([1 + 1j, 0, 0]), TypeError),
        (lambda: lie.skew([[1, 2, 3], [4, 5]]), TypeError),
    ],
)
def test_bad_input(call, error):
    with pytest.raises(error, match=r"(?i)expected|got|rotation|finite|se\(3\)"):
        call()
