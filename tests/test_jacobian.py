"""Tests of the four Jacobians and their conversions (jacobians.jacobian).

The oracle is finite differences of the forward kinematics: no convention
mistake survives it.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import jacobians as jac
from jacobians import lie
from jacobians.testing import fd_tol, random_chain, random_theta, within

seeds = st.integers(0, 2**32 - 1)
batch_shapes = st.sampled_from([(), (1,), (3,), (2, 2), (2, 1, 3)])
H = 1e-6


def fd_twists(chain, theta):
    """Columns of [V_s] = dT/dθ_i T^-1 and [V_b] = T^-1 dT/dθ_i, by central differences."""
    T = chain.fk(theta)
    Tinv = np.linalg.inv(T)
    Js, Jb = [], []
    for i in range(chain.dof):
        d = np.zeros(chain.dof)
        d[i] = H
        dT = (chain.fk(theta + d) - chain.fk(theta - d)) / (2 * H)
        Js.append(lie.matrix_to_twist(dT @ Tinv))
        Jb.append(lie.matrix_to_twist(Tinv @ dT))
    return np.array(Js).T, np.array(Jb).T


@settings(max_examples=60, deadline=None)
@given(seeds)
def test_space_and_body_against_finite_differences(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    Js_fd, Jb_fd = fd_twists(chain, theta)
    # fd_tol bounds each entry of dT/dθ_i (truncation + rounding); a twist entry sums a column / row of T⁻¹
    e_J = fd_tol(chain.fk, theta, H) * np.abs(np.linalg.inv(chain.fk(theta))).sum()
    assert within(jac.space_jacobian(chain, theta), Js_fd, e_J)
    assert within(jac.body_jacobian(chain, theta), Jb_fd, e_J)


@settings(max_examples=60, deadline=None)
@given(seeds)
def test_geometric_rows_are_omega_s_and_pdot(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    J = jac.geometric_jacobian(chain, theta)
    dp = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, 3], theta)
    e_fd = fd_tol(chain.fk, theta)  # each entry of dp and dR (truncation + rounding of the central difference)
    assert within(J[3:], dp, e_fd)
    R = chain.fk(theta)[:3, :3]
    dR = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, :3], theta)  # (3, 3, n)
    w = np.stack([lie.unskew(dR[..., i] @ R.T) for i in range(chain.dof)], axis=1)
    assert within(J[:3], w, 2 * e_fd)  # dR R^T sums a unit row of R: at most sqrt 3 times e_fd


@settings(max_examples=40, deadline=None)
@given(seeds, batch_shapes)
def test_conversions_hold_on_batches(seed, shape):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng, shape)
    T = chain.fk(theta)
    Js, Jb, J = (jac.space_jacobian(chain, theta), jac.body_jacobian(chain, theta), jac.geometric_jacobian(chain, theta))
    assert Js.shape == shape + (6, chain.dof) and T.shape == shape + (4, 4)
    Ad_sb = jac.adjoint(T)
    Ad_bs = jac.adjoint(np.linalg.inv(T))
    assert np.allclose(Jb, Ad_bs @ Js, atol=1e-9)
    assert np.allclose(Js, Ad_sb @ Jb, atol=1e-9)
    assert np.allclose(jac.space_to_body(Js, T), Jb, atol=1e-9)
    assert np.allclose(jac.body_to_space(Jb, T), Js, atol=1e-9)
    assert np.allclose(jac.body_to_geometric(Jb, T), J, atol=1e-9)
    assert np.allclose(jac.geometric_to_body(J, T), Jb, atol=1e-9)
    assert np.allclose(jac.space_to_geometric(Js, T), J, atol=1e-9)
    assert np.allclose(jac.geometric_to_space(J, T), Js, atol=1e-9)
    R = T[..., :3, :3]
    blk = np.zeros(shape + (6, 6))
    blk[..., :3, :3] = R
    blk[..., 3:, 3:] = R
    assert np.allclose(J, blk @ Jb, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(seeds)
def test_batch_path_equals_single_path(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    thetas = random_theta(chain, rng, 7)
    for f in (jac.space_jacobian, jac.body_jacobian, jac.geometric_jacobian):
        batch = f(chain, thetas)
        single = np.stack([f(chain, t) for t in thetas])
        assert np.allclose(batch, single, atol=1e-12)
    assert np.allclose(chain.fk(thetas), np.stack([chain.fk(t) for t in thetas]), atol=1e-12)


def test_large_batch_crosses_chunks():
    chain = jac.robots.ur5()
    rng = np.random.default_rng(7)
    thetas = random_theta(chain, rng, (3, 3001))  # 9003 > one chunk
    J = jac.body_jacobian(chain, thetas)
    for idx in [(0, 0), (1, 1500), (2, 3000)]:
        assert np.allclose(J[idx], jac.body_jacobian(chain, thetas[idx]), atol=1e-12)


def _ok_for_fd(chain, theta, rep):
    """Away from singularities and from the wrap-around of the angle ranges."""
    phi = jac.pose_coordinates(chain.fk(theta), rep)[:3]
    from jacobians.representations import representation_singularity_margin

    if representation_singularity_margin(phi, rep) < 0.2:
        return False
    if rep in ("zyx", "zyz"):
        ends = [phi[0], phi[2]] if rep == "zyx" else [phi[0], phi[2]]
        return all(abs(abs(a) - np.pi) > 0.2 for a in ends)
    return True


@pytest.mark.parametrize("rep", ["zyx", "zyz", "exp"])
def test_analytic_is_derivative_of_pose_coordinates(rep):
    rng = np.random.default_rng(11)
    checked = 0
    while checked < 25:
        chain = random_chain(rng)
        theta = random_theta(chain, rng)
        if not _ok_for_fd(chain, theta, rep):
            continue
        Ja = jac.analytic_jacobian(chain, theta, rep)
        num = jac.numerical_jacobian(lambda t, chain=chain: jac.pose_coordinates(chain.fk(t), rep), theta)
        assert np.allclose(Ja, num, atol=1e-5), rep
        Jg = jac.geometric_jacobian(chain, theta)
        assert np.allclose(jac.geometric_to_analytic(Jg, chain.fk(theta), rep), Ja, atol=1e-12)
        checked += 1


def test_analytic_reports_gimbal_lock():
    wrist = jac.robots.zyx_wrist()
    theta = np.array([0.3, np.pi / 2, -0.2])
    with pytest.raises(jac.RepresentationSingularityError, match="singular"):
        jac.analytic_jacobian(wrist, theta, "zyx")
    out = jac.analytic_jacobian(wrist, np.stack([theta, [0.3, 0.2, 0.1]]), "zyx", on_singularity="nan")
    assert np.all(np.isnan(out[0])) and np.all(np.isfinite(out[1]))
    # For the ZYX wrist the joint angles are the ZYX coordinates: J_a's angular block is I
    assert np.allclose(jac.analytic_jacobian(wrist, [0.3, 1.5, -0.2], "zyx")[:3], np.eye(3))
    # A ZYZ wrist passes through ZYX gimbal lock at theta2 = pi/2 while it is full rank:
    # near lock J_a is finite and huge, the geometric Jacobian stays well-conditioned
    zyz = jac.robots.zyz_wrist()
    near = jac.analytic_jacobian(zyz, [0.0, np.pi / 2 - 1e-5, 0.0], "zyx")
    assert np.isfinite(near).all() and np.abs(near).max() > 1e4
    Jg = jac.geometric_jacobian(zyz, [0.0, np.pi / 2, 0.0])
    assert np.linalg.svd(Jg[:3], compute_uv=False).min() > 0.5
    with pytest.raises(jac.RepresentationSingularityError):
        jac.analytic_jacobian(zyz, [0.0, np.pi / 2, 0.0], "zyx")
    # ZYZ locks at phi2 = 0; the planar arms have R = Rz, so zyz is singular there
    with pytest.raises(jac.RepresentationSingularityError):
        jac.analytic_jacobian(jac.robots.planar_2r(), [0.1, 0.2], "zyz")
    # exponential coordinates jump at rotation angle pi
    with pytest.raises(jac.RepresentationSingularityError):
        jac.analytic_jacobian(jac.robots.planar_2r(), [np.pi / 2, np.pi / 2], "exp")


def test_wrist_zyx_coordinates_are_joint_angles():
    wrist = jac.robots.zyx_wrist()
    theta = np.array([0.4, -0.7, 1.1])
    assert np.allclose(jac.pose_coordinates(wrist.fk(theta), "zyx")[:3], theta)
    Ja = jac.analytic_jacobian(wrist, theta, "zyx")
    assert np.allclose(Ja[:3], np.eye(3), atol=1e-12)


def test_planar_analytic_equals_geometric_rows():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    theta = np.array([0.3, 0.5, -0.4])  # total angle 0.4: yaw = sum of angles
    Ja = jac.analytic_jacobian(arm, theta, "zyx")
    J = jac.geometric_jacobian(arm, theta)
    assert np.allclose(Ja[0], J[2]) and np.allclose(Ja[3:], J[3:])


# ---------------------------------------------------------------- closed forms of the notes

def test_planar_2r_position_jacobian_closed_form():
    """Note 002 prints entry (2,1) as l1 c1; the correct entry is l1 c1 + l2 c12."""
    l1, l2 = 0.9, 0.6
    arm = jac.robots.planar_2r(l1, l2)
    rng = np.random.default_rng(3)
    for t1, t2 in rng.uniform(-np.pi, np.pi, (20, 2)):
        s1, c1, s12, c12 = np.sin(t1), np.cos(t1), np.sin(t1 + t2), np.cos(t1 + t2)
        Jp = np.array([[-l1 * s1 - l2 * s12, -l2 * s12], [l1 * c1 + l2 * c12, l2 * c12]])
        J = jac.geometric_jacobian(arm, [t1, t2])
        assert np.allclose(J[3:5], Jp)
        wrong = Jp.copy()
        wrong[1, 0] = l1 * c1  # as printed in the notes
        assert not np.allclose(J[3:5], wrong)


def test_planar_3r_closed_forms_of_note_004():
    L1, L2, L3 = 1.0, 0.7, 0.4
    arm = jac.robots.planar_3r(L1, L2, L3)
    rng = np.random.default_rng(4)
    for t1, t2, t3 in rng.uniform(-np.pi, np.pi, (20, 3)):
        s1, c1 = np.sin(t1), np.cos(t1)
        s12, c12 = np.sin(t1 + t2), np.cos(t1 + t2)
        s123, c123 = np.sin(t1 + t2 + t3), np.cos(t1 + t2 + t3)
        s3, c3, s23, c23 = np.sin(t3), np.cos(t3), np.sin(t2 + t3), np.cos(t2 + t3)
        z = [0, 0, 0]
        Js = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, L1 * s1, -L1 * c1, 0],
                       [0, 0, 1, L1 * s1 + L2 * s12, -L1 * c1 - L2 * c12, 0]]).T
        Jb = np.array([[0, 0, 1, L2 * s3 + L1 * s23, L3 + L2 * c3 + L1 * c23, 0],
                       [0, 0, 1, L2 * s3, L3 + L2 * c3, 0], [0, 0, 1, 0, L3, 0]]).T
        J = np.array([[0, 0, 1, -L1 * s1 - L2 * s12 - L3 * s123, L1 * c1 + L2 * c12 + L3 * c123, 0],
                      [0, 0, 1, -L2 * s12 - L3 * s123, L2 * c12 + L3 * c123, 0],
                      [0, 0, 1, -L3 * s123, L3 * c123, 0]]).T
        th = [t1, t2, t3]
        assert np.allclose(jac.space_jacobian(arm, th), Js)
        assert np.allclose(jac.body_jacobian(arm, th), Jb)
        assert np.allclose(jac.geometric_jacobian(arm, th), J)
        del z


# ---------------------------------------------------------------- golden values (Modern Robotics docs)

MR_LIST = np.array([[0, 0, 1, 0, 0.2, 0.2], [1, 0, 0, 2, 0, 3], [0, 1, 0, 0, 2, 1], [1, 0, 0, 0.2, 0.3, 0.4]]).T
MR_THETA = np.array([0.2, 1.1, 0.1, 1.2])


def test_mr_jacobian_space_example():
    chain = jac.SerialChain(MR_LIST, np.eye(4))
    expected = np.array([[0, 0.98006658, -0.09011564, 0.95749426],
                         [0, 0.19866933, 0.4445544, 0.28487557],
                         [1, 0, 0.89120736, -0.04528405],
                         [0, 1.95218638, -2.21635216, -0.51161537],
                         [0.2, 0.43654132, -2.43712573, 2.77535713],
                         [0.2, 2.96026613, 3.23573065, 2.22512443]])
    assert within(jac.space_jacobian(chain, MR_THETA), expected, 5e-9)   # MR prints 8 decimals


def test_mr_jacobian_body_example():
    chain = jac.SerialChain(MR_LIST, np.eye(4))  # M = I: body axes equal the given list
    assert np.allclose(chain.body_axes, MR_LIST)
    expected = np.array([[-0.04528405, 0.99500417, 0, 1],
                         [0.74359313, 0.09304865, 0.36235775, 0],
                         [-0.66709716, 0.03617541, -0.93203909, 0],
                         [2.32586047, 1.66809, 0.56410831, 0.2],
                         [-1.44321167, 2.94561275, 1.43306521, 0.3],
                         [-2.06639565, 1.82881722, -1.58868628, 0.4]])
    assert within(jac.body_jacobian(chain, MR_THETA), expected, 5e-9)    # MR prints 8 decimals


def test_mr_fkin_example():
    M = np.array([[-1, 0, 0, 0], [0, 1, 0, 6], [0, 0, -1, 2], [0, 0, 0, 1]], dtype=float)
    S = np.array([[0, 0, 1, 4, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, -1, -6, 0, -0.1]]).T
    chain = jac.SerialChain(S, M)
    expected = np.array([[0, 1, 0, -5], [1, 0, 0, 4], [0, 0, -1, 1.68584073], [0, 0, 0, 1]])
    assert within(chain.fk([np.pi / 2, 3, np.pi]), expected, 5e-9)   # MR prints 8 decimals
    assert chain.joint_types == "RPR"
    assert np.allclose(chain.body_axes, np.array([[0, 0, -1, 2, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 1, 0, 0, 0.1]]).T)


def test_ur5_against_modern_robotics():
    mr = pytest.importorskip("modern_robotics")
    ur = jac.robots.ur5()
    rng = np.random.default_rng(8)
    for theta in rng.uniform(-np.pi, np.pi, (10, 6)):
        assert np.allclose(jac.space_jacobian(ur, theta), mr.JacobianSpace(ur.screw_axes, theta))
        assert np.allclose(jac.body_jacobian(ur, theta), mr.JacobianBody(ur.body_axes, theta))
        assert np.allclose(ur.fk(theta), mr.FKinBody(ur.home, ur.body_axes, theta))


# ---------------------------------------------------------------- link Jacobians

@settings(max_examples=30, deadline=None)
@given(seeds)
def test_link_jacobians(seed):
    rng = np.random.default_rng(seed)
    chain = random_chain(rng)
    theta = random_theta(chain, rng)
    n = chain.dof
    Js_links = jac.link_jacobians(chain, theta, "space")
    Jb_links = jac.link_jacobians(chain, theta, "body")
    Jg_links = jac.link_jacobians(chain, theta, "geometric")
    assert Js_links.shape == (n, 6, n)
    poses = chain.link_poses(theta)
    for i in range(n):
        assert np.all(Js_links[i][:, i + 1:] == 0) and np.all(Jb_links[i][:, i + 1:] == 0)
        # finite differences of the pose of link frame i
        T = poses[i]
        Tinv = np.linalg.inv(T)
        for k in range(n):
            d = np.zeros(n)
            d[k] = H
            dT = (chain.link_poses(theta + d)[i] - chain.link_poses(theta - d)[i]) / (2 * H)
            assert np.allclose(Js_links[i][:, k], lie.matrix_to_twist(dT @ Tinv), atol=1e-6)
            assert np.allclose(Jb_links[i][:, k], lie.matrix_to_twist(Tinv @ dT), atol=1e-6)
            assert np.allclose(Jg_links[i][3:, k], dT[:3, 3], atol=1e-6)
    # the last link's frame is {b} by default, so its Jacobians are the chain's
    assert np.allclose(Jb_links[-1], jac.body_jacobian(chain, theta), atol=1e-12)


# ---------------------------------------------------------------- bad input

ARM = jac.robots.planar_2r()


@pytest.mark.parametrize(
    "call, error, pattern",
    [
        (lambda: jac.space_jacobian(ARM, [0.1, 0.2, 0.3]), ValueError, r"shape \(\.\.\., 2\)"),
        (lambda: jac.space_jacobian(ARM, np.zeros((5, 3))), ValueError, r"shape \(\.\.\., 2\)"),
        (lambda: jac.space_jacobian(ARM, 0.3), ValueError, "scalar"),
        (lambda: jac.space_jacobian(ARM, [0.1, np.nan]), ValueError, "finite"),
        (lambda: jac.body_jacobian(ARM, [0.1, np.inf]), ValueError, "finite"),
        (lambda: jac.space_jacobian(ARM, "0.1, 0.2"), TypeError, "real numbers"),
        (lambda: jac.space_jacobian(ARM, None), TypeError, "real numbers"),
        (lambda: jac.space_jacobian(ARM, [[0.1, 0.2], [0.3]]), TypeError, "real numbers"),
        (lambda: jac.space_jacobian(np.eye(6), [0.1, 0.2]), TypeError, "SerialChain"),
        (lambda: jac.analytic_jacobian(ARM, [0.1, 0.2], "xyz"), ValueError, "Unknown representation"),
        (lambda: jac.analytic_jacobian(ARM, [0.1, 0.2], 3), TypeError, "representation"),
        (lambda: jac.analytic_jacobian(ARM, [0.1, 0.2], on_singularity="ignore"), ValueError, "on_singularity"),
        (lambda: jac.pose_coordinates(np.eye(4), "euler"), ValueError, "Unknown representation"),
        (lambda: jac.space_to_body(np.zeros((5, 2)), np.eye(4)), ValueError, r"shape \(\.\.\., 6, n\)"),
        (lambda: jac.space_to_body(np.zeros((6, 2)), np.eye(3)), ValueError, r"shape \(\.\.\., 4, 4\)"),
        (lambda: jac.space_to_body(np.zeros((6, 2)), 2 * np.eye(4)), ValueError, "rotation|SE\\(3\\)"),
        (lambda: jac.space_to_body(np.zeros((3, 6, 2)), np.tile(np.eye(4), (4, 1, 1))), ValueError, "batch shapes"),
        (lambda: jac.link_jacobians(ARM, [0.1, 0.2], "world"), ValueError, "frame"),
        (lambda: jac.numerical_jacobian(np.sin, [0.1], eps=-1), ValueError, "positive"),
    ],
)
def test_bad_input(call, error, pattern):
    with pytest.raises(error, match=pattern):
        call()


def test_no_index_or_linalg_errors_on_odd_shapes():
    for bad in [np.zeros((0,)), np.zeros((2, 0)), np.zeros((0, 2, 2))[..., 0]]:
        try:
            jac.space_jacobian(ARM, bad)
        except (ValueError, TypeError):
            pass


# ---------------------------------------------------------------- one entry point: jacobian(chain, theta, frame)

@pytest.mark.parametrize("frame", jac.FRAMES)
def test_jacobian_of_a_frame_is_the_named_function(frame):
    chain = random_chain(3, dof=4)
    theta = random_theta(chain, 4, (5,))
    named = {"space": jac.space_jacobian, "body": jac.body_jacobian, "geometric": jac.geometric_jacobian,
             "analytic": lambda c, t: jac.analytic_jacobian(c, t, "zyx", on_singularity="nan")}[frame]
    np.testing.assert_allclose(jac.jacobian(chain, theta, frame, on_singularity="nan"), named(chain, theta),
                               atol=1e-12)


def test_jacobian_passes_the_analytic_options_on():
    wrist = jac.robots.zyx_wrist()
    lock = [0.3, np.pi / 2, 0.2]
    with pytest.raises(jac.RepresentationSingularityError):
        jac.jacobian(wrist, lock, "analytic")
    assert np.isnan(jac.jacobian(wrist, lock, "analytic", on_singularity="nan")).all()
    np.testing.assert_allclose(jac.jacobian(wrist, [0.3, 0.4, 0.2], "analytic", "zyz"),
                               jac.analytic_jacobian(wrist, [0.3, 0.4, 0.2], "zyz"), atol=1e-12)


@pytest.mark.parametrize("call", [
    lambda: jac.jacobian(jac.robots.planar_2r(), [0, 0], "world"),
    lambda: jac.jacobian(jac.robots.planar_2r(), [0, 0], None),
    lambda: jac.frames.check_frame(3),
])
def test_jacobian_rejects_an_unknown_frame_with_the_one_message(call):
    with pytest.raises(ValueError, match=r"^Expected frame 'space', 'body', 'geometric' or 'analytic', got "):
        call()


def test_every_frame_check_uses_the_one_message():
    arm = jac.robots.planar_2r()
    with pytest.raises(ValueError, match=r"^Expected frame 'space', 'body' or 'geometric', got 'analytic'$"):
        jac.link_jacobians(arm, [0, 0], frame="analytic")
    with pytest.raises(ValueError, match=r"^Expected frame 'space' or 'body', got 'geometric'$"):
        jac.statics.joint_torques_from_wrench(arm, [0, 0], np.zeros(6), frame="geometric")
    assert jac.FRAMES == ("space", "body", "geometric", "analytic")
