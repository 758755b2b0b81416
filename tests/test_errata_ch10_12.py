"""Regression checks for the errors fixed in chapters 10, 11 and 12.

Each test fails on the old text or on the old value: it reads the chapter source and asserts
that the wrong statement is gone, and it recomputes the right value independently (finite
differences, a series, random arms) and asserts that the wrong one differs from it.
"""

import re
from pathlib import Path

import numpy as np

import jacobians as jac
from jacobians import lie
from jacobians.analysis import singular_values
from jacobians.ik import pose_error
from jacobians.testing import TOL, close, fd_tol, within

ROOT = Path(__file__).resolve().parents[1]
CH10 = ROOT / "chapters" / "10_inverse_kinematics.md"
CH11 = ROOT / "chapters" / "11_redundancy.md"
CH12 = ROOT / "chapters" / "12_jacobian_derivative.md"


def text(path):
    """The chapter source with runs of whitespace collapsed to one space."""
    return re.sub(r"\s+", " ", path.read_text())


# ---------------------------------------------------------------- chapter 10: left, not right, Jacobian

def left_jacobian_se3(V, terms=40):
    """J_l(V) = sum_k [ad_V]^k / (k+1)!, by its series (no exponential, no logarithm)."""
    term, out = np.eye(6), np.eye(6)
    for k in range(1, terms):
        term = term @ lie.ad(V) / (k + 1)
        out = out + term
    return out


def test_ch10_proof_names_the_left_jacobian():
    src = text(CH10)
    assert "inverse of the right Jacobian of $SE(3)$" not in src
    assert "A(F) = J_l(F)^{-1} = J_r(-F)^{-1}" in src


def test_ch10_derivative_of_the_error_is_minus_left_jacobian_inverse_times_jb():
    ur = jac.robots.ur5()
    rng = np.random.default_rng(28)
    goal = rng.uniform(-np.pi, np.pi, 6)
    T_d = ur.fk(goal)
    for _ in range(5):
        th = goal + 0.25 * rng.normal(size=6)
        F = pose_error(ur, th, T_d)
        dF = jac.numerical_jacobian(lambda t: pose_error(ur, t, T_d), th)
        Jb = jac.body_jacobian(ur, th)
        left = -np.linalg.solve(left_jacobian_se3(F), Jb)
        right = -np.linalg.solve(left_jacobian_se3(-F), Jb)
        # central differences within fd_tol (truncation h²/6·max|F'''| + rounding, from F itself); the solve with
        # J_l(F) adds TOL·max(1, |J_b|) times its condition number
        bound = fd_tol(lambda t: pose_error(ur, t, T_d), th) + TOL * max(1.0, np.abs(Jb).max()) * np.linalg.cond(
            left_jacobian_se3(F))
        assert within(dF, left, bound)
        assert np.abs(dF - right).max() > 0.05 * np.linalg.norm(F)       # the old (right) form is wrong at O(|F|)


# ---------------------------------------------------------------- chapter 11: the UR5's wrist axes

def _closest(w_a, q_a, w_b, q_b):
    M = np.array([[w_a @ w_a, -w_a @ w_b], [w_a @ w_b, -w_b @ w_b]])
    s, t = np.linalg.solve(M, [(q_b - q_a) @ w_a, (q_b - q_a) @ w_b])
    return q_a + s * w_a, q_b + t * w_b


def test_ch11_ur5_text_no_longer_says_axes_4_and_6_are_parallel():
    src = text(CH11)
    assert "its axes 4 and 6 are parallel and 95 mm apart" not in src
    assert "and 6 are parallel, 0.095 m apart" not in src                       # the old hidden check's claim
    assert "Its axis 5 meets axis 4 at one point and axis 6 at another" in src


def test_ch11_ur5_axis_5_meets_4_and_6_at_points_0_095_apart_everywhere():
    ur = jac.robots.ur5()
    rng = np.random.default_rng(11)
    for th in rng.uniform(-np.pi, np.pi, (100, 6)):
        J = jac.space_jacobian(ur, th)
        ax = [(J[:3, i], np.cross(J[:3, i], J[3:, i])) for i in (3, 4, 5)]
        A4, A5 = _closest(*ax[0], *ax[1])
        B5, B6 = _closest(*ax[1], *ax[2])
        # axes 4 ⊥ 5 and 5 ⊥ 6 (w_a·w_b = 0): _closest's 2×2 system has condition number 1, the points are
        # well-conditioned: TOL relative to their size (close)
        assert close(A4, A5) and close(B5, B6)
        assert close(np.linalg.norm(A5 - B5), 0.095, scale=float(np.abs(A5).max()))
    # the old reason fails: at the chapter's configuration axes 4 and 6 are 40.11 degrees apart
    J = jac.space_jacobian(ur, [0.5, -0.8, 1.0, 0.3, 0.7, -0.2])
    angle = np.degrees(np.arccos(abs(J[:3, 3] @ J[:3, 5])))
    assert abs(angle - 40.11) < 0.01


# ---------------------------------------------------------------- chapter 11: internal singularities

def test_ch11_summary_no_longer_claims_every_internal_singularity_can_be_left():
    src = text(CH11)
    assert "Internal singularities can be left by self-motion, boundary ones cannot." not in src
    assert ":label: ch11-prop-leave-singularity" in CH11.read_text()


def test_ch11_counterexample_l_211_interior_point_with_only_singular_preimages():
    l = np.array([2.0, 1.0, 1.0])
    arm = jac.robots.planar_3r(*l)
    # the origin is inside the workspace: points of every small radius are reached
    grid = np.linspace(-np.pi, np.pi, 181)
    cfg = np.stack(np.meshgrid([0.0], grid, grid), -1).reshape(-1, 3)
    r = np.linalg.norm(arm.fk(cfg)[:, :2, 3], axis=-1)
    assert r.min() < 0.05 and r.max() > 3.99
    # every configuration reaching the origin: the last link at angle psi, joint 3 at -l3 (cos, sin) psi, which
    # links 1 and 2 reach only folded (|w| = 1 = l1 - l2): theta2 = pi, theta3 = 0, sigma_min = 0
    psi = np.linspace(-np.pi, np.pi, 721)
    w = -l[2] * np.stack([np.cos(psi), np.sin(psi)], -1)
    t1 = np.arctan2(w[:, 1], w[:, 0])
    th = np.stack([t1, np.full_like(t1, np.pi), psi - t1 - np.pi], -1)
    # |p| = 0 exactly: a sum of link vectors of total length 4, computed within TOL of that size (close)
    assert close(arm.fk(th)[:, :2, 3], 0, scale=float(l.sum()))
    smin = singular_values(jac.geometric_jacobian(arm, th)[:, 3:5, :])[:, -1]
    assert close(smin, 0, scale=float(l.sum()))                   # σ_min = 0 exactly; Weyl: within the entries' TOL
    # and no regular configuration reaches it: |p| = 0 needs the flat triangle 2 = 1 + 1
    rng = np.random.default_rng(0)
    th_r = rng.uniform(-np.pi, np.pi, (20000, 3))
    reg = singular_values(jac.geometric_jacobian(arm, th_r)[:, 3:5, :])[:, -1] > 1e-3
    assert np.linalg.norm(arm.fk(th_r[reg])[:, :2, 3], axis=-1).min() > 1e-3


# ---------------------------------------------------------------- chapter 12: omega_{i-1} sums revolute joints

def test_ch12_omega_sums_revolute_joints_only():
    src = text(CH12)
    assert "with $\\omega_{i-1} = \\sum_{j<i}z_j\\dot\\theta_j$ the angular velocity" not in src
    assert "j\\ \\text{revolute}}z_j\\dot\\theta_j" in src


def test_ch12_rpr_chain_z3_dot_by_finite_differences():
    S = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 1, 0, -0.5, 0, 1.0]], dtype=float).T
    M = np.eye(4)
    M[:3, 3] = [1.5, 0, 0.5]
    rpr = jac.SerialChain(S, M)
    rng = np.random.default_rng(5)
    for _ in range(5):
        th, thd = rng.normal(size=(2, 3))
        z3 = lambda t, th=th, thd=thd: jac.space_jacobian(rpr, th + t * thd)[:3, 2]
        h = 1e-6
        z3dot = (z3(h) - z3(-h)) / (2 * h)
        J = jac.space_jacobian(rpr, th)
        right = np.cross(J[:3, 0] * thd[0], J[:3, 2])
        wrong = np.cross(J[:3, 0] * thd[0] + J[3:, 1] * thd[1], J[:3, 2])
        assert within(z3dot, right, fd_tol(lambda t, z3=z3: z3(t[0]), np.zeros(1), h))   # FD truncation + rounding
        assert np.linalg.norm(z3dot - wrong) > 0.05 * abs(thd[1])
