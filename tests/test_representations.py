"""Tests of the orientation representations and their rate matrices B(phi)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from jacobians import lie
from jacobians import representations as rep
from jacobians.testing import random_rotation

seeds = st.integers(0, 2**32 - 1)


@pytest.mark.parametrize("r", rep.REPRESENTATIONS)
@given(seed=seeds)
def test_round_trip(r, seed):
    R = random_rotation(np.random.default_rng(seed), 5)
    phi = rep.coordinates_from_rotation(R, r)
    assert np.allclose(rep.rotation_from_coordinates(phi, r), R, atol=1e-9)


def test_principal_ranges():
    R = random_rotation(np.random.default_rng(0), 500)
    zyx = rep.coordinates_from_rotation(R, "zyx")
    assert np.all(np.abs(zyx[:, 1]) <= np.pi / 2 + 1e-12) and np.all(np.abs(zyx) <= np.pi + 1e-12)
    zyz = rep.coordinates_from_rotation(R, "zyz")
    assert np.all((zyz[:, 1] >= 0) & (zyz[:, 1] <= np.pi + 1e-12))
    e = rep.coordinates_from_rotation(R, "exp")
    assert np.all(np.linalg.norm(e, axis=-1) <= np.pi + 1e-12)


@pytest.mark.parametrize("r", rep.REPRESENTATIONS)
def test_B_maps_rates_to_spatial_angular_velocity(r):
    rng = np.random.default_rng(1)
    for _ in range(20):
        phi = rng.uniform(-1.2, 1.2, 3)
        if r == "zyz":
            phi[1] = abs(phi[1]) + 0.1
        phidot = rng.normal(size=3)
        h = 1e-6
        R = rep.rotation_from_coordinates(phi, r)
        Rdot = (rep.rotation_from_coordinates(phi + h * phidot, r) - rep.rotation_from_coordinates(phi - h * phidot, r)) / (2 * h)
        w_s = lie.unskew(Rdot @ R.T)
        B = rep.rate_to_angular_velocity(phi, r)
        assert np.allclose(w_s, B @ phidot, atol=1e-7)
        assert np.allclose(rep.angular_velocity_to_rate(phi, r) @ B, np.eye(3), atol=1e-9)


def test_determinants():
    for b in np.linspace(-1.5, 1.5, 7):
        phi = np.array([0.3, b, -0.4])
        assert np.isclose(np.linalg.det(rep.rate_to_angular_velocity(phi, "zyx")), -np.cos(b))
        assert np.isclose(np.linalg.det(rep.rate_to_angular_velocity(phi, "zyz")), -np.sin(b))


def test_gimbal_lock_is_reported():
    with pytest.raises(rep.RepresentationSingularityError, match="gimbal lock"):
        rep.angular_velocity_to_rate([0.1, np.pi / 2, 0.2], "zyx")
    with pytest.raises(rep.RepresentationSingularityError):
        rep.angular_velocity_to_rate([0.1, 0.0, 0.2], "zyz")
    with pytest.raises(rep.RepresentationSingularityError):
        rep.angular_velocity_to_rate([0.0, 0.0, np.pi], "exp")
    assert np.isclose(rep.representation_singularity_margin([0, np.pi / 2, 0], "zyx"), 0.0, atol=1e-15)


def test_locked_rotations_round_trip():
    for r, phi in [("zyx", [0.7, np.pi / 2, 0.0]), ("zyx", [0.7, -np.pi / 2, 0.0]),
                   ("zyz", [0.7, 0.0, 0.0]), ("zyz", [0.7, np.pi, 0.0])]:
        R = rep.rotation_from_coordinates(phi, r)
        back = rep.coordinates_from_rotation(R, r)
        assert np.allclose(rep.rotation_from_coordinates(back, r), R, atol=1e-12)


def test_bad_input():
    with pytest.raises(ValueError, match="Unknown representation"):
        rep.rotation_from_coordinates([0, 0, 0], "xyz")
    with pytest.raises(TypeError):
        rep.rate_to_angular_velocity([0, 0, 0], None)
    with pytest.raises(ValueError, match="shape"):
        rep.rate_to_angular_velocity([0, 0], "zyx")
    with pytest.raises(ValueError, match="rotation"):
        rep.coordinates_from_rotation(np.ones((3, 3)), "zyx")


def test_zyx_order_is_yaw_pitch_roll_the_reverse_of_the_toolbox_and_urdf():
    """'zyx' lists (yaw, pitch, roll); the Toolbox's tr2rpy/rpy2r(order='zyx') and URDF's rpy list (roll, pitch, yaw)."""
    smb = pytest.importorskip("spatialmath.base")
    R = random_rotation(np.random.default_rng(3), 200)
    for Ri in R:
        zyx = rep.coordinates_from_rotation(Ri, "zyx")
        rpy = rep.roll_pitch_yaw(Ri)
        # both sides are atan2 of the same entries: agreement to a few eps of angles of size <= pi
        assert np.allclose(rpy, smb.tr2rpy(Ri, order="zyx"), atol=1e-12)
        assert np.allclose(zyx, rpy[::-1], atol=0)
        assert np.allclose(rep.rotation_from_roll_pitch_yaw(rpy), smb.rpy2r(*rpy, order="zyx"), atol=1e-12)
        yaw, pitch, roll = zyx  # R = Rz(yaw) Ry(pitch) Rx(roll), each about its named axis
        assert np.allclose(lie.rotation_about("z", yaw) @ lie.rotation_about("y", pitch) @ lie.rotation_about("x", roll),
                           Ri, atol=1e-12)
    # a rotation with distinct roll and yaw tells the orders apart: reading the toolbox's vector as 'zyx' is wrong
    phi = np.array([0.3, -0.2, 0.1])
    R1 = rep.rotation_from_coordinates(phi, "zyx")
    assert not np.allclose(rep.rotation_from_coordinates(smb.tr2rpy(R1, order="zyx"), "zyx"), R1, atol=1e-3)
    # batches keep their shape
    assert rep.roll_pitch_yaw(R).shape == (200, 3) and rep.rotation_from_roll_pitch_yaw(np.zeros((4, 3))).shape == (4, 3, 3)


def test_roll_pitch_yaw_bad_input():
    with pytest.raises(ValueError, match="shape"):
        rep.rotation_from_roll_pitch_yaw([0.0, 0.0])
    with pytest.raises(ValueError):
        rep.roll_pitch_yaw(np.eye(4))
