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


# ---------------------------------------------------------------- industrial arms against the Robotics Toolbox
# Tolerance: arms of at most 7 links, lengths <= 1.3 m, products of at most 2 * 7 matrices with entries <= 1.3:
# the two libraries' rounding differs by well under 50 * 14 * 1.3 * eps ~ 2e-13; we compare to 1e-11.
RTB_TOL = 1e-11
N_CONFIGS = 200


def _rtb_worst(chain, robot, rng, end=None):
    """Largest difference of T, and of the geometric Jacobian at the tool origin (rows (v, omega) in the Toolbox)."""
    kw = {} if end is None else {"end": end}
    worst_T = worst_J = 0.0
    for q in rng.uniform(-np.pi, np.pi, (N_CONFIGS, chain.dof)) * np.array(
            [1.0 if t == "R" else 0.3 for t in chain.joint_types]):
        T = robot.fkine(q, **kw).A
        J0 = robot.jacob0(q, **kw)
        J = jac.geometric_jacobian(chain, q)
        worst_T = max(worst_T, np.abs(chain.fk(q) - T).max())
        worst_J = max(worst_J, np.abs(np.vstack([J[3:], J[:3]]) - J0).max())
    return worst_T, worst_J


@pytest.mark.parametrize("name, model", [("panda", "Panda"), ("puma560", "Puma560"), ("stanford", "Stanford")])
def test_arms_agree_with_the_toolbox_models(name, model):
    rtb = pytest.importorskip("roboticstoolbox")
    from spatialmath import SE3

    robot = getattr(rtb.models.DH, model)()
    robot.tool = SE3()  # the Toolbox's Panda carries Franka's hand as a tool; ours ends at the flange
    chain = getattr(robots, name)()
    assert chain.dof == robot.n and chain.joint_types == "".join("P" if L.isprismatic else "R" for L in robot.links)
    worst_T, worst_J = _rtb_worst(chain, robot, np.random.default_rng(1))
    assert worst_T < RTB_TOL and worst_J < RTB_TOL


def test_iiwa_agrees_with_the_toolbox_urdf_model_up_to_its_two_cad_offsets():
    """The Toolbox's LBR is ROS-Industrial's iiwa 14 URDF, which puts joints 2 and 4 0.4362 mm off the axis line
    (x = -0.0004362 and +0.0004362) where the data sheet has them on it. Pure translations of two joint frames:
    orientations and axis directions agree exactly; the tool origin moves by at most 2 * 0.4362 mm, and a column
    omega_i x (p - q_i) of the linear rows by at most |dp| + |dq_i| <= 4 * 0.4362 mm."""
    rtb = pytest.importorskip("roboticstoolbox")
    robot = rtb.models.URDF.LBR()
    chain = robots.iiwa14()
    off = 0.0004362
    rng = np.random.default_rng(2)
    worst_R = worst_p = worst_w = worst_v = 0.0
    for q in rng.uniform(-np.pi, np.pi, (N_CONFIGS, 7)):
        T, Tr = chain.fk(q), robot.fkine(q, end="tool0").A
        J, J0 = jac.geometric_jacobian(chain, q), robot.jacob0(q, end="tool0")
        worst_R = max(worst_R, np.abs(T[:3, :3] - Tr[:3, :3]).max())
        worst_p = max(worst_p, np.linalg.norm(T[:3, 3] - Tr[:3, 3]))
        worst_w = max(worst_w, np.abs(J[:3] - J0[3:]).max())
        worst_v = max(worst_v, np.linalg.norm(J[3:] - J0[:3], axis=0).max())
    assert worst_R < RTB_TOL and worst_w < RTB_TOL
    assert worst_p <= 2 * off + RTB_TOL and worst_v <= 4 * off + RTB_TOL
    assert worst_p > 0.5 * off  # the offsets are really there: the comparison sees them


def test_industrial_arms_home_poses_and_jacobians():
    T = robots.panda().fk(np.zeros(7))
    assert np.allclose(T, [[1, 0, 0, 0.088], [0, -1, 0, 0], [0, 0, -1, 0.926], [0, 0, 0, 1]], atol=1e-12)
    assert np.allclose(robots.iiwa14().fk(np.zeros(7)), [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1.306], [0, 0, 0, 1]],
                       atol=1e-12)
    assert robots.stanford().joint_types == "RRPRRR" and robots.puma560().dof == 6
    rng = np.random.default_rng(4)
    for make in (robots.panda, robots.puma560, robots.iiwa14, robots.stanford, robots.puma_like):
        chain = make()
        for q in rng.uniform(-np.pi, np.pi, (5, chain.dof)):
            # central differences of the forward kinematics: error O(h^2) ~ 1e-10 for h = 1e-5 plus rounding
            # eps / h ~ 1e-11 on entries of size 1, so 1e-6 is far above both and far below a wrong column
            dp = jac.numerical_jacobian(lambda t, c=chain: c.fk(t)[:3, 3], q)
            assert np.allclose(jac.geometric_jacobian(chain, q)[3:], dp, atol=1e-6)


def test_puma_like_is_the_arm_of_chapter_11():
    """The chain chapter 11 builds by hand: joint 1 about z at the origin, 2 and 3 about y at height H, the wrist
    x, y, x at p_w = (L1 + L2, 0, H), the tool d6 past p_w."""
    H, L1, L2, d6 = 0.66, 0.43, 0.43, 0.06
    pw = np.array([L1 + L2, 0.0, H])
    axes = [((0, 0, 1), (0, 0, 0)), ((0, 1, 0), (0, 0, H)), ((0, 1, 0), (L1, 0, H)),
            ((1, 0, 0), pw), ((0, 1, 0), pw), ((1, 0, 0), pw)]
    S = np.array([np.concatenate([w, -np.cross(w, q)]) for w, q in axes], dtype=float).T
    M = np.eye(4); M[:3, 3] = pw + [d6, 0, 0]
    arm = robots.puma_like()
    assert np.array_equal(arm.screw_axes, S) and np.array_equal(arm.home, M)
    assert np.allclose(arm.axis_points(), [q for _, q in axes]) and arm.name == "Puma-like"
    with pytest.raises(ValueError, match="positive"):
        robots.puma_like(L1=0.0)


def test_urdf_path():
    for name in robots.URDF_ROBOTS:
        assert robots.urdf_path(name).is_file()
    with pytest.raises(ValueError, match="expected one of"):
        robots.urdf_path("pr2")
    with pytest.raises(TypeError):
        robots.urdf_path(None)
