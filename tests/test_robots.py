"""Tests of the teaching robots."""

import numpy as np
import pytest

import jacobians as jac
from jacobians import robots


def test_planar_contract():
    arm = robots.planar_2r(l1=2.0, l2=0.5)
    assert np.allclose(arm.screw_axes.T, [[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -2.0, 0]])
    assert np.allclose(arm.home[:3, 3], [2.5, 0, 0])
    arm3 = robots.planar_3r(1.0, 2.0, 3.0)
    assert np.allclose(arm3.axis_points(), [[0, 0, 0], [1, 0, 0], [3, 0, 0]])
    assert np.allclose(arm3.home[:3, 3], [6, 0, 0])
    assert np.allclose(arm3.link_homes[:, :3, 3], [[0.5, 0, 0], [2.0, 0, 0], [4.5, 0, 0]])


def test_ur5_home_and_known_pose():
    ur = robots.ur5()
    assert np.allclose(ur.fk(np.zeros(6)), ur.home)
    # MR Example 4.5: theta2 = -pi/2, theta5 = pi/2
    T = ur.fk([0, -np.pi / 2, 0, 0, np.pi / 2, 0])
    expected = np.array([[0, -1, 0, 0.095], [1, 0, 0, 0.109], [0, 0, 1, 0.988], [0, 0, 0, 1]])
    assert np.allclose(T, expected, atol=1e-12)


@pytest.mark.parametrize("make", [robots.spatial_rrp, robots.scara, robots.spatial_5r, robots.zyx_wrist, robots.zyz_wrist, robots.ur5])
def test_every_robot_is_consistent(make):
    chain = make()
    theta = np.random.default_rng(0).uniform(-1, 1, chain.dof)
    Js = jac.space_jacobian(chain, theta)
    dp = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, 3], theta)
    assert np.allclose(jac.geometric_jacobian(chain, theta)[3:], dp, atol=1e-6)
    assert np.allclose(jac.space_to_body(Js, chain.fk(theta)), jac.body_jacobian(chain, theta))


def test_joint_types():
    assert robots.spatial_rrp().joint_types == "RRP"
    assert robots.scara().joint_types == "RRPR"


def test_bad_lengths():
    with pytest.raises(ValueError, match="positive"):
        robots.planar_2r(l1=-1.0)
    with pytest.raises(TypeError, match="real number"):
        robots.planar_3r(l1="1")
    with pytest.raises(TypeError, match="sequence"):
        robots.planar(3)
    with pytest.raises(ValueError, match="at least one"):
        robots.planar([])
