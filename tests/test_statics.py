"""Tests of jacobians.statics: hand-computed torques, the power balance
tau . theta_dot = F . V in matching frames, wrench frame changes, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import statics as stc
from jacobians.testing import random_chain, random_theta, random_transform

RNG = np.random.default_rng(3)


def test_planar_2r_torques_by_hand():
    """A force f = (fx, fy) at the tip of a 2R arm: tau_i = (p - q_i) x f (z component), derived by hand."""
    l1, l2 = 0.9, 0.6
    arm = jac.robots.planar_2r(l1, l2)
    theta = np.array([0.4, -1.1])
    f = np.array([3.0, -2.0])
    elbow = l1 * np.array([np.cos(0.4), np.sin(0.4)])
    tip = arm.fk(theta)[:2, 3]
    cross = lambda r, f: r[0] * f[1] - r[1] * f[0]
    expect = [cross(tip, f), cross(tip - elbow, f)]
    # in {s}: moment about the origin of {s}, m = p x f
    F_s = np.array([0, 0, cross(tip, f), f[0], f[1], 0])
    assert np.allclose(stc.joint_torques_from_wrench(arm, theta, F_s, frame="space"), expect)
    # the same with J^T F on the x, y rows of the geometric Jacobian
    J_v = jac.geometric_jacobian(arm, theta)[3:5]
    assert np.allclose(stc.joint_torques(J_v, f), expect)
    # in {b}: no moment about the tip, force rotated into {b}
    R = arm.fk(theta)[:3, :3]
    F_b = np.concatenate([[0, 0, 0], R.T @ np.array([f[0], f[1], 0])])
    assert np.allclose(stc.joint_torques_from_wrench(arm, theta, F_b, frame="body"), expect)


def test_stretched_arm_holds_a_radial_force_with_no_torque():
    arm = jac.robots.planar_3r()
    theta = np.array([0.7, 0.0, 0.0])
    radial = np.array([np.cos(0.7), np.sin(0.7), 0.0])
    F_b = np.concatenate([[0, 0, 0], arm.fk(theta)[:3, :3].T @ radial])
    assert np.allclose(stc.joint_torques_from_wrench(arm, theta, F_b, frame="body"), 0, atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), batch=st.sampled_from([(), (3,), (2, 2)]))
def test_power_balance_in_matching_frames(seed, batch):
    """tau . theta_dot == F . V, with (J_s, F_s, V_s) and with (J_b, F_b, V_b); V from finite differences."""
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng, size=batch)
    theta_dot = rng.normal(size=batch + (chain.dof,))
    F_s = rng.normal(size=batch + (6,))
    T = chain.fk(theta)
    F_b = stc.wrench_space_to_body(F_s, T)
    tau_s = stc.joint_torques_from_wrench(chain, theta, F_s, frame="space")
    tau_b = stc.joint_torques_from_wrench(chain, theta, F_b, frame="body")
    assert tau_s.shape == batch + (chain.dof,)
    # the same physical wrench gives the same torques whichever frame it is written in
    assert np.allclose(tau_s, tau_b, atol=1e-9)
    # twists of the motion theta_dot, from finite differences of the forward kinematics
    h = 1e-6
    T_plus, T_minus = chain.fk(theta + h * theta_dot), chain.fk(theta - h * theta_dot)
    T_dot = (T_plus - T_minus) / (2 * h)
    T_inv = np.linalg.inv(T)
    Vs_mat = T_dot @ T_inv
    Vb_mat = T_inv @ T_dot
    def twist(Vm):
        return np.stack([Vm[..., 2, 1], Vm[..., 0, 2], Vm[..., 1, 0], Vm[..., 0, 3], Vm[..., 1, 3], Vm[..., 2, 3]], -1)
    V_s, V_b = twist(Vs_mat), twist(Vb_mat)
    power_joints = np.sum(tau_s * theta_dot, axis=-1)
    scale = 1 + np.abs(power_joints).max()
    assert np.allclose(power_joints, np.sum(F_s * V_s, axis=-1), atol=1e-5 * scale)
    assert np.allclose(power_joints, np.sum(F_b * V_b, axis=-1), atol=1e-5 * scale)


def test_mismatched_frames_give_wrong_torques():
    """Using F_s with J_b (a common mistake) does not give the right torques."""
    arm = jac.robots.spatial_5r()
    theta = np.array([0.3, -0.4, 0.8, 0.2, -0.6])
    F_s = np.array([0.1, 0.2, -0.3, 1.0, -2.0, 0.5])
    right = stc.joint_torques_from_wrench(arm, theta, F_s, frame="space")
    wrong = stc.joint_torques(jac.body_jacobian(arm, theta), F_s)
    assert not np.allclose(right, wrong, atol=1e-3)


def test_wrench_frame_changes_invert_each_other_and_keep_power():
    T = random_transform(RNG, size=(5,))
    F = RNG.normal(size=(5, 6))
    V = RNG.normal(size=(5, 6))
    F_b = stc.wrench_space_to_body(F, T)
    assert np.allclose(stc.wrench_body_to_space(F_b, T), F)
    # power is frame-independent: F_b . V_b = F_s . V_s with V_s = Ad_T V_b
    V_s = (jac.adjoint(T) @ V[..., None])[..., 0]
    assert np.allclose(np.sum(F_b * V, -1), np.sum(F * V_s, -1))
    # by hand: a pure force f at {b}'s origin has moment p x f about {s}
    T1 = np.eye(4)
    T1[:3, 3] = [1.0, 2.0, 3.0]
    f = np.array([0.0, 0.0, 1.0])
    assert np.allclose(stc.wrench_body_to_space(np.r_[0, 0, 0, f], T1), np.r_[np.cross([1.0, 2.0, 3.0], f), f])


def test_joint_torques_broadcasting():
    J = RNG.normal(size=(4, 6, 3))
    F = RNG.normal(size=6)
    assert np.allclose(stc.joint_torques(J, F), np.einsum("bij,i->bj", J, F))
    F2 = RNG.normal(size=(4, 6))
    assert np.allclose(stc.joint_torques(J, F2), np.einsum("bij,bi->bj", J, F2))


@pytest.mark.parametrize("call, exc, match", [
    (lambda: stc.joint_torques("J", [1.0]), TypeError, "real numbers"),
    (lambda: stc.joint_torques([1.0, 2.0], [1.0]), ValueError, r"\(\.\.\., m, n\)"),
    (lambda: stc.joint_torques(np.eye(6), [1.0, 2.0, 3.0]), ValueError, "moment first"),
    (lambda: stc.joint_torques(np.eye(6), [np.nan] * 6), ValueError, "finite"),
    (lambda: stc.joint_torques(np.ones((2, 6, 3)), np.ones((3, 6))), ValueError, "broadcast"),
    (lambda: stc.joint_torques_from_wrench(jac.robots.planar_2r(), [0, 0], np.zeros(6), frame="world"),
     ValueError, "space"),
    (lambda: stc.joint_torques_from_wrench(jac.robots.planar_2r(), [0, 0], np.zeros(3)), ValueError, r"\(\.\.\., 6\)"),
    (lambda: stc.joint_torques_from_wrench(jac.robots.planar_2r(), [0, 0, 0], np.zeros(6)), ValueError, "2 joints"),
    (lambda: stc.joint_torques_from_wrench("arm", [0, 0], np.zeros(6)), TypeError, "SerialChain"),
    (lambda: stc.wrench_space_to_body(np.zeros(6), np.ones((4, 4))), ValueError, "last row"),
    (lambda: stc.wrench_body_to_space(None, np.eye(4)), TypeError, "F_b"),
])
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
