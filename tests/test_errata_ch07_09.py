"""Regression checks for the errors fixed in chapters 7, 8 and 9.

Each test fails on the old text or the old value: it reads the chapter source
and asserts that the wrong statement is gone (or that the missing warning is
there), and it recomputes the right value with the library (or sympy) and
asserts that it differs from the wrong one.
"""

import re
from pathlib import Path

import numpy as np
import pytest

import jacobians as jac
from jacobians import analysis, lie
from jacobians.testing import TOL, close, fd_tol, within

ROOT = Path(__file__).resolve().parents[1]
CH07 = ROOT / "chapters" / "07_conversions.md"
CH08 = ROOT / "chapters" / "08_link_jacobians.md"
CH09 = ROOT / "chapters" / "09_using_the_jacobian.md"


def text(path):
    """The chapter source with runs of whitespace collapsed to one space."""
    return re.sub(r"\s+", " ", path.read_text())


def block(path, label):
    """The source of the exercise ``label`` and its solution, whitespace collapsed."""
    src = path.read_text()
    start = src.index(f":label: {label}")
    end = src.index("```{solution-end}", start)
    return re.sub(r"\s+", " ", src[start:end])


def product_of_exponentials(chain, theta, i):
    E = np.eye(4)
    for k in range(i):
        E = E @ lie.exp_se3(chain.screw_axes[:, k] * theta[k])
    return E


# ---------------------------------------------------------------- chapter 7, exercise 4

def test_ch07_ex4_old_false_statement_is_gone():
    ex = block(CH07, "ch07-ex-D")
    assert "overlooked in the statement" not in ex
    assert "equal only when the origin of $\\{b\\}$ is at the origin of $\\{s\\}$ or every column's angular part is zero" not in ex
    assert "if and only if $\\omega_{s,i}\\times p = 0$ for every $i$" in ex


def test_ch07_ex4_counterexample_to_old_statement_and_new_condition():
    # joint 1 revolute about z, joint 2 prismatic along z, tool on the z axis: p != 0, a revolute joint,
    # and yet J_s = J, which the old statement ("only when p = 0 or every angular part is zero") denied
    S = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 0, 0, 0, 1]], dtype=float).T
    M = np.eye(4)
    M[2, 3] = 0.5
    chain = jac.SerialChain(S, M)
    q = np.array([0.7, 0.2])
    p = chain.fk(q)[:3, 3]
    J_s, J = jac.space_jacobian(chain, q), jac.geometric_jacobian(chain, q)
    assert np.linalg.norm(p) > 0.5 and np.linalg.norm(J_s[:3]) > 0.5       # old condition false
    assert close(J_s, J)                                                   # ... and the rows are equal (exact algebra)
    assert close(np.cross(J_s[:3].T, p), 0, scale=float(np.abs(p).max()))  # the new condition holds (terms of size |p|)
    # where the new condition fails, the linear rows differ by omega x p
    arm = jac.robots.planar_3r()
    q = np.array([0.3, -0.8, 1.1])
    p = arm.fk(q)[:3, 3]
    J_s, J = jac.space_jacobian(arm, q), jac.geometric_jacobian(arm, q)
    assert close(J[3:] - J_s[3:], np.cross(J_s[:3].T, p).T, scale=float(np.abs(J).max() + np.abs(J_s).max()))
    assert not close(J[3:], J_s[3:])


# ---------------------------------------------------------------- chapter 8, the mass matrix

def _mass_matrix(chain, theta, inertias):
    J_b = jac.link_jacobians(chain, theta, "body")
    return sum(J_b[i].T @ inertias[i] @ J_b[i] for i in range(chain.dof)), J_b


def test_ch08_old_definiteness_claim_is_gone_and_the_rank_condition_is_stated():
    src = text(CH08)
    assert "positive semi-definite at worst, and definite as soon as every joint moves some mass" not in src
    assert "a symmetric positive-definite $n\\times n$ matrix" not in src
    assert ":label: ch08-prop-definite" in CH08.read_text()
    assert "full column rank $n$" in src


def test_ch08_coaxial_counterexample_has_a_singular_mass_matrix():
    S = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, 0, 0]], dtype=float).T
    homes = np.array([np.eye(4), lie.make_transform(np.eye(3), [0.5, 0, 0])])
    chain = jac.SerialChain(S, lie.make_transform(np.eye(3), [1.0, 0, 0]), link_homes=homes)
    rod = np.diag([0.0, 1 / 12, 1 / 12, 1.0, 1.0, 1.0])
    M, J_b = _mass_matrix(chain, np.array([0.4, -1.1]), [np.zeros((6, 6)), rod])
    # every joint moves some mass (the old sufficient condition) ...
    assert M[0, 0] > 0.1 and M[1, 1] > 0.1
    # ... yet M is singular, with null vector (1, -1), and the stacked weighted Jacobian has rank 1
    # λ_min = 0 exactly; computed, off by the rounding of M's entries (Weyl): TOL relative to max |M| (close)
    assert close(np.linalg.eigvalsh(M)[0], 0.0, scale=float(np.abs(M).max()))
    assert close(M @ [1.0, -1.0], 0, scale=float(np.abs(M).max()))
    A = np.vstack([np.zeros((6, 2)), np.diag(np.sqrt(np.diag(rod))) @ J_b[1]])
    assert np.linalg.matrix_rank(A) == 1 and close(M, A.T @ A)


def test_ch08_generic_arm_has_full_rank_and_positive_definite_mass_matrix():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    G = [np.diag([m * l**2 / 12] * 3 + [m] * 3) for m, l in zip([2.0, 1.5, 1.0], [1.0, 0.8, 0.5], strict=True)]
    M, J_b = _mass_matrix(arm, np.array([0.3, -1.0, 0.6]), G)
    A = np.vstack([np.sqrt(G[i]) @ J_b[i] for i in range(3)])
    assert np.linalg.matrix_rank(A) == 3 and np.linalg.eigvalsh(M)[0] > 1e-6
    assert close(M, A.T @ A)


def test_ch08_last_link_frame_is_not_always_the_end_effector():
    # old text: "The end-effector frame is the case i = n, M_n = M", false for the planar arms
    assert "The end-effector frame is the case $i = n$, $M_n = M$." not in text(CH08)
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    assert not close(arm.link_homes[-1], arm.home)
    ur5 = jac.robots.ur5()
    assert close(ur5.link_homes[-1], ur5.home)


# ---------------------------------------------------------------- chapter 8, errors of the notes

def test_ch08_warns_about_four_more_errors_of_the_notes():
    src = text(CH08)
    assert src.count("**An error in the notes:**") >= 4
    assert "\\mathbf 0_{n\\times(n-i)}" in src and "0_{6\\times(n-i)}" in src          # notes 001, zero block
    assert "notes 003" in src and "e^{[\\mathcal S_i]\\theta_i}\\,M_i" in src           # notes 003, eq. (2)
    assert "[\\hat\\xi_k]" in src and "[\\hat\\xi_1]\\dot\\theta_1" in src               # notes 001, index slips


def test_notes_zero_block_has_six_rows():
    arm = jac.robots.planar_3r()
    theta = np.array([0.2, 0.5, -0.4])
    J_s = jac.space_jacobian(arm, theta)
    with pytest.raises(ValueError):
        np.hstack([J_s[:, :1], np.zeros((3, 2))])                 # 0_{n x (n-i)}, n = 3, i = 1
    assert close(np.hstack([J_s[:, :1], np.zeros((6, 2))]), jac.link_jacobians(arm, theta, "space")[0])


def test_notes_003_pose_of_frame_i_needs_M_i():
    for chain in (jac.robots.ur5(), jac.robots.planar_3r(1.0, 0.8, 0.5)):
        theta = np.random.default_rng(2).uniform(-np.pi, np.pi, chain.dof)
        J_s = jac.space_jacobian(chain, theta)
        wrong = 0
        for i in range(chain.dof):
            E = product_of_exponentials(chain, theta, i + 1)
            S_in_i = jac.adjoint(np.linalg.inv(chain.link_homes[i])) @ chain.screw_axes[:, i]
            assert close(jac.adjoint(E @ chain.link_homes[i]) @ S_in_i, J_s[:, i])
            wrong += not close(jac.adjoint(E @ chain.home) @ S_in_i, J_s[:, i])   # closed forms: equal up to TOL, or not
        assert wrong >= chain.dof - 1


def test_notes_index_slips_give_wrong_columns():
    chain = jac.robots.ur5()
    theta = np.random.default_rng(4).uniform(-np.pi, np.pi, 6)
    i = 2
    T = chain.link_poses(theta)[i]
    dT = jac.numerical_jacobian(lambda t: chain.link_poses(t)[i], theta)[..., i]
    fd_s = lie.matrix_to_twist(dT @ np.linalg.inv(T))
    fd_b = lie.matrix_to_twist(np.linalg.inv(T) @ dT)
    E_prev = product_of_exponentials(chain, theta, i)
    G = lie.exp_se3(chain.screw_axes[:, i] * theta[i]) @ chain.link_homes[i]
    # each entry of dT within fd_tol (truncation + rounding); a twist entry sums a row (column) of it times T⁻¹
    bound = fd_tol(lambda t: chain.link_poses(t)[i], theta) * float(np.abs(np.linalg.inv(T)).sum())
    assert within(jac.adjoint(E_prev) @ chain.screw_axes[:, i], fd_s, bound)
    assert not within(jac.adjoint(E_prev) @ chain.screw_axes[:, 0], fd_s, bound)
    assert within(jac.adjoint(np.linalg.inv(G)) @ chain.screw_axes[:, i], fd_b, bound)
    assert not within(jac.adjoint(np.linalg.inv(G)) @ chain.screw_axes[:, 0], fd_b, bound)


# ---------------------------------------------------------------- chapter 9, exercise 3

def test_ch09_ex3_says_which_force_the_sensor_reads_and_negates_it():
    ex = block(CH09, "ch09-ex-C")
    assert "measures the force that the environment exerts **on the tool**" in ex
    assert "F_b = -F_measured" in ex


def test_ch09_ex3_torques_by_virtual_work_are_the_negated_old_value():
    arm = jac.robots.planar_2r()
    theta = np.array([0.3, 1.2])
    F_measured = np.array([0, 0, 0, 10.0, 0, 0])
    old = jac.body_jacobian(arm, theta).T @ F_measured            # the old solution, J_b^T times the reading
    f_s = arm.fk(theta)[:3, :3] @ F_measured[3:]
    J_v = jac.numerical_jacobian(lambda t: arm.fk(t)[:3, 3], theta)
    tau = -J_v.T @ f_s                                            # motors cancel the environment's generalised force
    # J_v's entries are central differences (within fd_tol); τ sums a column of them times f_s
    bound = fd_tol(lambda t: arm.fk(t)[:3, 3], theta) * float(np.abs(f_s).sum())
    assert within(tau, -old, bound)
    assert not within(tau, old, bound)


# ---------------------------------------------------------------- chapter 9, other fixes

def test_ch09_determinant_is_the_product_of_singular_values_only_up_to_sign():
    assert "$\\det J = \\prod_i \\sigma_i = 0$" not in text(CH09)
    assert "$|\\det J| = \\prod_i \\sigma_i$" in text(CH09)
    J = jac.geometric_jacobian(jac.robots.planar_2r(1.0, 0.8), [0.2, -1.0])[3:5]
    s = np.linalg.svd(J, compute_uv=False)
    assert np.linalg.det(J) < 0 and not close(np.linalg.det(J), np.prod(s))
    assert close(abs(np.linalg.det(J)), np.prod(s))                 # a 2×2 of entries <= 2: well-conditioned, TOL


def test_ch09_ellipse_figure_has_one_pose_per_panel_and_nothing_clipped():
    src = CH09.read_text()
    assert 'for ax, kind in zip(axes, ("velocity", "force"))' not in src      # the old two-panel overlay
    assert "name: ch09-fig-ellipses" in src and "plt.subplots(2, 2" in src
    # the old figure: common limits +-1.25 reach, force ellipse x 0.25 at theta_2 = 0.35 left the axes
    arm = jac.robots.planar_2r(1.0, 0.8)
    from jacobians.plotting import arm_reach

    r = arm_reach(arm) * 1.25
    th = np.array([0.2, 0.35])
    A = analysis.linear_rows(jac.geometric_jacobian(arm, th))[:2]
    semi, dirs = analysis.force_ellipsoid(A)
    c = arm.fk(th)[:2, 3]
    u = np.stack([np.cos(np.linspace(0, 2 * np.pi, 181)), np.sin(np.linspace(0, 2 * np.pi, 181))])
    pts = c[:, None] + dirs @ (0.25 * semi[:, None] * u)
    assert np.abs(pts).max() > r


def test_ch09_ur5_third_singular_family_is_the_shoulder_plane_condition():
    assert "wrist centre above the shoulder axis" not in text(CH09)
    from scipy.optimize import brentq

    ur5 = jac.robots.ur5()
    base = np.array([0.3, -1.1, 1.4, -0.6, 1.1, 0.4])
    t2 = brentq(lambda x: np.linalg.det(jac.space_jacobian(ur5, np.r_[base[0], x, base[2:]])), 0.5, 1.0)
    theta = np.r_[base[0], t2, base[2:]]
    J_s = jac.space_jacobian(ur5, theta)
    # brentq stops within xtol + 4 EPS |t2| (2e-12 + 4 EPS |t2|) of the root of det; there det J_s is at most
    # |d det/dθ2| times that (twice the difference quotient, for its variation) plus rounding, and
    # σ_min = |det| / (σ_1 ... σ_5); Weyl adds TOL σ_1
    s_ur = np.linalg.svd(J_s, compute_uv=False)
    ddet = (np.linalg.det(jac.space_jacobian(ur5, np.r_[base[0], t2 + 1e-6, base[2:]]))
            - np.linalg.det(jac.space_jacobian(ur5, np.r_[base[0], t2 - 1e-6, base[2:]]))) / 2e-6
    det_bound = 2 * abs(ddet) * (2e-12 + 4 * np.finfo(float).eps * abs(t2)) + TOL * float(np.prod(s_ur[:-1])) * s_ur[0]
    assert s_ur[-1] <= det_bound / float(np.prod(s_ur[:-1])) + TOL * s_ur[0]
    q5, q6 = np.cross(J_s[:3, 4], J_s[3:, 4]), np.cross(J_s[:3, 5], J_s[3:, 5])
    a = np.linalg.lstsq(np.stack([J_s[:3, 4], -J_s[:3, 5]], axis=1), q6 - q5, rcond=None)[0][0]
    wrist = q5 + a * J_s[:3, 4]
    normal = np.cross(J_s[:3, 0], J_s[:3, 1])
    assert abs(normal @ wrist) < 1e-9                 # axes 1 and 2 pass through (0, 0, H1); normal is horizontal
    assert np.isclose(np.hypot(wrist[0], wrist[1]), 0.109)


# ---------------------------------------------------------------- all three chapters

@pytest.mark.parametrize("path", [CH07, CH08, CH09], ids=lambda p: p.stem)
def test_checks_are_recorded_in_verified_boxes(path):
    src = path.read_text()
    assert "✓" not in src and "checked:" not in src
    assert "render_markdown_format: myst" in src.split("---", 2)[1]
    sections = re.split(r"\n(?=## )", src)[1:]
    for sec in sections:
        title = sec.splitlines()[0]
        if "$$" in sec or re.search(r"```\{prf:(theorem|proposition|lemma|corollary)\}", sec):
            cells = re.findall(r"```\{code-cell\} ipython3\n(.*?)```", sec, flags=re.S)
            assert cells and cells[-1].strip().endswith("verified.box()"), title
    assert sections[-1].startswith("## References")
