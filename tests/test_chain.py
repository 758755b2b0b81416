"""Tests of SerialChain: construction, forward kinematics, DH, validation."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import lie
from jacobians.testing import close, random_chain, random_theta

seeds = st.integers(0, 2**32 - 1)


@settings(max_examples=40, deadline=None)
@given(seeds)
def test_fk_space_and_body_forms_agree(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    T = np.eye(4)
    for i in range(chain.dof):
        T = T @ lie.exp_se3(chain.screw_axes[:, i] * theta[i])
    T_space = T @ chain.home
    T_body = chain.home.copy()
    for i in range(chain.dof):
        T_body = T_body @ lie.exp_se3(chain.body_axes[:, i] * theta[i])
    assert np.allclose(chain.fk(theta), T_space, atol=1e-10)
    assert np.allclose(T_body, T_space, atol=1e-10)
    assert np.allclose(chain.body_axes, jac.adjoint(np.linalg.inv(chain.home)) @ chain.screw_axes)


@settings(max_examples=20, deadline=None)
@given(seeds, st.sampled_from([(2,), (3, 2), (1, 1, 4)]))
def test_fk_batches(seed, shape):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    thetas = random_theta(chain, rng, shape)
    T = chain.fk(thetas)
    assert T.shape == shape + (4, 4)
    flat = thetas.reshape(-1, chain.dof)
    assert np.allclose(T.reshape(-1, 4, 4), np.stack([chain.fk(t) for t in flat]), atol=1e-12)
    P = chain.prefix_transforms(thetas)
    assert P.shape == shape + (chain.dof + 1, 4, 4)
    assert np.allclose(P[..., -1, :, :] @ chain.home, T, atol=1e-10)
    assert chain.link_poses(thetas).shape == shape + (chain.dof, 4, 4)
    assert chain.joint_positions(thetas).shape == shape + (chain.dof + 1, 3)


def test_planar_joint_positions():
    arm = jac.robots.planar_3r(1.0, 0.5, 0.25)
    pts = arm.joint_positions([np.pi / 2, -np.pi / 2, 0.0])
    assert np.allclose(pts, [[0, 0, 0], [0, 1, 0], [0.5, 1, 0], [0.75, 1, 0]], atol=1e-12)


def test_attributes_are_read_only_copies():
    S = jac.robots.planar_2r().screw_axes.copy()
    chain = jac.SerialChain(S, np.eye(4))
    S[0, 0] = 5.0
    assert chain.screw_axes[0, 0] == 0.0
    with pytest.raises(ValueError):
        chain.screw_axes[0, 0] = 1.0
    assert chain.dof == 2 and chain.joint_types == "RR"
    assert "2 joints" in repr(chain)


def test_home_is_reorthonormalised():
    M = np.eye(4)
    M[:3, :3] = lie.rotation_about("z", 0.3)
    M[0, 0] += 1e-8
    chain = jac.SerialChain(jac.robots.planar_2r().screw_axes, M)
    R = chain.home[:3, :3]
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-14)


# ---------------------------------------------------------------- Denavit–Hartenberg

def test_from_dh_planar_2r_matches_screw_description():
    dh = jac.SerialChain.from_dh(a=[1.0, 0.7], alpha=[0, 0], d=[0, 0])
    ref = jac.robots.planar_2r(1.0, 0.7)
    rng = np.random.default_rng(0)
    for th in rng.uniform(-np.pi, np.pi, (10, 2)):
        assert np.allclose(dh.fk(th), ref.fk(th))
        assert np.allclose(jac.space_jacobian(dh, th), jac.space_jacobian(ref, th))


def test_from_dh_link_frames_follow_the_dh_product():
    a, alpha, d = [0.3, 0.5, 0.1], [np.pi / 2, 0.0, -np.pi / 2], [0.4, 0.0, 0.2]
    chain = jac.SerialChain.from_dh(a, alpha, d, offset=[0.1, -0.2, 0.3], joint_types="RRP")
    q = np.array([0.5, -0.3, 0.25])

    def A(theta, di, ai, al):
        Rz = np.eye(4); Rz[:3, :3] = lie.rotation_about("z", theta)
        Tz = np.eye(4); Tz[2, 3] = di
        Tx = np.eye(4); Tx[0, 3] = ai
        Rx = np.eye(4); Rx[:3, :3] = lie.rotation_about("x", al)
        return Rz @ Tz @ Tx @ Rx

    T = np.eye(4)
    frames = []
    off = [0.1, -0.2, 0.3]
    for i in range(3):
        if i < 2:
            T = T @ A(q[i] + off[i], d[i], a[i], alpha[i])
        else:
            T = T @ A(off[i], d[i] + q[i], a[i], alpha[i])  # prismatic: constant angle off[i], length d + q
        frames.append(T)
    assert np.allclose(chain.fk(q), frames[-1], atol=1e-12)
    assert np.allclose(chain.link_poses(q), np.stack(frames), atol=1e-12)


def test_from_dh_modified_matches_classical_for_planar_arm():
    # Craig's frames for the planar 2R of note 002: 0T1 = Rz(t1), 1T2 = Tx(l1) Rz(t2), tool Tx(l2)
    l1, l2 = 0.8, 0.5
    tool = np.eye(4)
    tool[0, 3] = l2
    craig = jac.SerialChain.from_dh(a=[0.0, l1], alpha=[0, 0], d=[0, 0], convention="modified", tool=tool)
    ref = jac.robots.planar_2r(l1, l2)
    for th in np.random.default_rng(1).uniform(-3, 3, (5, 2)):
        assert np.allclose(craig.fk(th), ref.fk(th))


def test_roboticstoolbox_dh_agrees():
    rtb = pytest.importorskip("roboticstoolbox")
    a, alpha, d = [0.0, 0.4318, 0.0203], [np.pi / 2, 0.0, -np.pi / 2], [0.0, 0.0, 0.15]
    robot = rtb.DHRobot([rtb.RevoluteDH(a=a[i], alpha=alpha[i], d=d[i]) for i in range(3)])
    chain = jac.SerialChain.from_dh(a, alpha, d)
    for q in np.random.default_rng(2).uniform(-3, 3, (5, 3)):
        assert close(chain.fk(q), robot.fkine(q).A)   # well-conditioned: 1e-12 relative (jacobians.testing.close)
        J0 = robot.jacob0(q)  # rows (v, omega) of the tool origin in the base frame
        J = jac.geometric_jacobian(chain, q)
        assert close(J0[:3], J[3:]) and close(J0[3:], J[:3])



def _rtb_dh_robot(rtb, a, alpha, d, theta, types, modified):
    """The Robotics Toolbox's robot for a DH table in the from_dh reading: d and theta are the columns at home."""
    links = []
    for i, kind in enumerate(types):
        if kind == "R":
            cls = rtb.RevoluteMDH if modified else rtb.RevoluteDH
            links.append(cls(a=a[i], alpha=alpha[i], d=d[i], offset=theta[i]))
        else:  # the Toolbox's prismatic length is q + offset: its offset is the home length d
            cls = rtb.PrismaticMDH if modified else rtb.PrismaticDH
            links.append(cls(a=a[i], alpha=alpha[i], theta=theta[i], offset=d[i], qlim=[-10, 10]))
    return rtb.DHRobot(links)


def test_from_dh_prismatic_keeps_its_constant_theta_as_in_the_toolbox():
    """The chain of the report: PRPR, with the constant angles 4 and 2 of the prismatic joints in ``offset``."""
    rtb = pytest.importorskip("roboticstoolbox")
    chain = jac.SerialChain.from_dh([0, 2, 0, 0], [0] * 4, [0] * 4, offset=[4, 0, 2, 0], joint_types="PRPR")
    robot = rtb.DHRobot([rtb.PrismaticDH(theta=4, qlim=[-9, 9]), rtb.RevoluteDH(a=2),
                         rtb.PrismaticDH(theta=2, qlim=[-9, 9]), rtb.RevoluteDH()])
    plain = jac.SerialChain.from_dh([0, 2, 0, 0], [0] * 4, [0] * 4, joint_types="PRPR")
    for q in np.random.default_rng(7).uniform(-2, 2, (20, 4)):
        # entries of T are at most |a| + |q| sums of order 10: 1e-12 relative to that scale (close)
        assert close(chain.fk(q), robot.fkine(q).A)
    # the old reading (constant angles dropped) is a different chain: the check above fails on it
    q = np.array([0.5, 0.3, -0.7, 0.2])
    assert np.abs(plain.fk(q) - robot.fkine(q).A).max() > 0.5


@pytest.mark.parametrize("modified", [False, True])
def test_from_dh_matches_the_toolbox_on_random_tables(modified):
    """Random DH tables with random joint types (both conventions): forward kinematics and Jacobians agree."""
    rtb = pytest.importorskip("roboticstoolbox")
    rng = np.random.default_rng(11 + modified)
    for _ in range(40):
        n = int(rng.integers(1, 8))
        types = "".join(rng.choice(["R", "P"], n, p=[0.6, 0.4]))
        a, d, theta = rng.uniform(-1, 1, (3, n))
        alpha = rng.uniform(-np.pi, np.pi, n)
        chain = jac.SerialChain.from_dh(a, alpha, d, offset=theta, joint_types=types,
                                        convention="modified" if modified else "classical")
        robot = _rtb_dh_robot(rtb, a, alpha, d, theta, types, modified)
        assert chain.joint_types == types
        for q in rng.uniform(-np.pi, np.pi, (5, n)) * np.array([1.0 if t == "R" else 0.5 for t in types]):
            T = robot.fkine(q).A
            J0 = robot.jacob0(q)  # rows (v, omega) of the tool origin, in the base frame
            J = jac.geometric_jacobian(chain, q)
            # n <= 7 links of length <= 2.6 (|a| + |d| + |q|): entries <= 20, products of 2n matrices:
            # well-conditioned, 1e-12 relative to max(1, max |entry|) (jacobians.testing.close)
            assert close(chain.fk(q), T)
            assert close(J[3:], J0[:3]) and close(J[:3], J0[3:])


# ---------------------------------------------------------------- bad input

def _col(*v):
    return np.array(v, dtype=float).reshape(6, 1)


@pytest.mark.parametrize(
    "S, M, pattern",
    [
        (np.zeros(6), np.eye(4), "shape \\(6, n\\)"),
        (np.zeros((2, 6)), np.eye(4), "transposed"),
        (np.zeros((6, 0)), np.eye(4), "at least one column"),
        (_col(0, 0, 0, 0, 0, 0), np.eye(4), "zero"),
        (_col(0, 0, 2, 0, 0, 0), np.eye(4), "unit angular part"),
        (_col(0, 0, 0, 0, 0, 3), np.eye(4), "unit linear part"),
        (_col(0, 0, 1, 0, np.nan, 0), np.eye(4), "finite"),
        (_col(0, 0, 1, 0, 0, 0), np.eye(3), "shape \\(4, 4\\)"),
        (_col(0, 0, 1, 0, 0, 0), np.diag([2.0, 1.0, 1.0, 1.0]), "rotation"),
        (_col(0, 0, 1, 0, 0, 0), np.diag([1.0, 1.0, -1.0, 1.0]), "det"),
        (_col(0, 0, 1, 0, 0, 0), np.vstack([np.eye(4)[:3], [0, 0, 1, 1]]), "last row"),
    ],
)
def test_bad_chain(S, M, pattern):
    with pytest.raises(ValueError, match=pattern):
        jac.SerialChain(S, M)


def test_bad_types():
    with pytest.raises(TypeError, match="real numbers"):
        jac.SerialChain("S", np.eye(4))
    with pytest.raises(TypeError, match="real numbers"):
        jac.SerialChain(_col(0, 0, 1, 0, 0, 0), None)
    with pytest.raises(TypeError, match="name"):
        jac.SerialChain(_col(0, 0, 1, 0, 0, 0), np.eye(4), name=3)
    with pytest.raises(ValueError, match="link_homes"):
        jac.SerialChain(_col(0, 0, 1, 0, 0, 0), np.eye(4), link_homes=np.tile(np.eye(4), (2, 1, 1)))
    with pytest.raises(ValueError, match="convention"):
        jac.SerialChain.from_dh([1], [0], [0], convention="craig")
    with pytest.raises(ValueError, match="joint_types"):
        jac.SerialChain.from_dh([1], [0], [0], joint_types="X")
    with pytest.raises(TypeError, match="joint_types"):
        jac.SerialChain.from_dh([1], [0], [0], joint_types=["R"])
    with pytest.raises(ValueError, match=r"alpha with shape \(1\)"):
        jac.SerialChain.from_dh([1], [0, 0], [0])
    with pytest.raises(ValueError, match="theta"):
        jac.robots.planar_2r().fk([1.0])



def test_a_column_of_joint_values_is_refused_with_what_to_pass():
    """(n, 1), as the Robotics Toolbox accepts, is not a batch of n one-joint configurations: say to pass (n,)."""
    arm = jac.robots.ur5()
    col = np.zeros((6, 1))
    for f in (arm.fk, lambda t: jac.space_jacobian(arm, t), lambda t: jac.body_jacobian(arm, t),
              lambda t: jac.jacobian(arm, t, "geometric")):
        with pytest.raises(ValueError, match=r"flat array of shape \(6,\), got a column of shape \(6, 1\)"):
            f(col)
    with pytest.raises(ValueError, match=r"np.ravel"):
        arm.fk(np.zeros((3, 6, 1)))
    # what stays valid: the flat vector, a batch of rows, and for one joint a column of k configurations
    assert arm.fk(col.ravel()).shape == (4, 4) and arm.fk(np.zeros((1, 6))).shape == (1, 4, 4)
    one = jac.SerialChain(_col(0, 0, 1, 0, 0, 0), np.eye(4))
    assert one.fk(np.zeros((5, 1))).shape == (5, 4, 4)
    # a wrong length still gets the length message
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 6\) for a chain with 6 joints, got shape \(5, 1\)"):
        arm.fk(np.zeros((5, 1)))

def test_joint_points_say_where_joints_are_drawn():
    arm = jac.robots.spatial_5r(h=0.5, l1=1.0, l2=1.0, l3=0.5, l4=0.3)
    # joint 4 turns about x through (l1 + l2, 0, h): the point closest to the origin would be (0, 0, h)
    assert np.allclose(arm.axis_points()[3], [2.0, 0, 0.5])
    assert np.allclose(arm.joint_positions(np.zeros(5))[:, :], [[0, 0, 0], [0, 0, 0.5], [1, 0, 0.5], [2, 0, 0.5], [2.5, 0, 0.5], [2.8, 0, 0.5]])
    # the joint points move with the joints before them
    th = np.array([0.3, -0.4, 0.5, 0.2, -0.1])
    P = arm.prefix_transforms(th)
    pts = arm.joint_positions(th)
    for i in range(5):
        assert np.allclose(pts[i], P[i, :3, :3] @ arm.axis_points()[i] + P[i, :3, 3])
    with pytest.raises(ValueError, match="not on the axis"):
        jac.SerialChain(arm.screw_axes, arm.home, joint_points=[[0, 0, 0], [0, 0, 0.5], [1, 0, 0.5], [2, 1, 0.5], [2.5, 0, 0.5]])
    with pytest.raises(ValueError, match="joint_points"):
        jac.SerialChain(arm.screw_axes, arm.home, joint_points=np.zeros((4, 3)))


def test_ur5_joint_points_lie_on_their_axes():
    ur = jac.robots.ur5()
    for i, q in enumerate(ur.axis_points()):
        w, v = ur.screw_axes[:3, i], ur.screw_axes[3:, i]
        assert np.allclose(-np.cross(w, q), v)
