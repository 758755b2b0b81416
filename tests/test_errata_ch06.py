"""Regression checks for the errors fixed in chapter 6.

Each test fails on the old text or value: it reads the chapter source and asserts the old
wrong statement is gone, and it computes the right value with the library (or sympy) and
asserts that it differs from the old one.
"""

import os
import re
from pathlib import Path

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
import sympy as sp

import jacobians as jac
from jacobians import representations as reps
from jacobians.testing import close

CHAPTER = Path(__file__).resolve().parents[1] / "chapters" / "06_analytic_jacobian.md"


@pytest.fixture(scope="module")
def text():
    return CHAPTER.read_text(encoding="utf-8")


def _markdown(text):
    """The chapter without its code cells (prose, math, warnings)."""
    return re.sub(r"```\{code-cell\}.*?\n```", "", text, flags=re.S)


# ---------------------------------------------------------------- the eigenvalues of B_exp

def _B_exp(theta, axis=(2.0, -1.0, 2.0)):
    w = np.asarray(axis, float) / np.linalg.norm(axis)
    return reps.rate_to_angular_velocity(theta * w, "exp")


def test_B_exp_eigenvalues_old_statement_is_gone(text):
    md = _markdown(text)
    old = r"(1 - \cos\vartheta)/\vartheta^2 \pm i(\vartheta - \sin\vartheta)/\vartheta^2"
    assert old not in md
    assert r"\pm i(\vartheta - \sin\vartheta)" not in md
    # the right pair is stated
    assert r"\lambda_\pm &= \int_0^1 e^{\pm i\sigma\vartheta}\,d\sigma" in md
    assert r"&= \frac{\sin\vartheta}{\vartheta} \pm i\,\frac{1 - \cos\vartheta}{\vartheta}." in md
    assert "Section 3.2.3.3" not in md  # a section number the book does not have for this


@pytest.mark.parametrize("theta", [0.3, 0.99, 2.0, 3.0])
def test_B_exp_eigenvalues_are_sin_over_theta_pm_i_one_minus_cos_over_theta(theta):
    lam = np.linalg.eigvals(_B_exp(theta))
    right = np.array([1.0, np.sin(theta) / theta + 1j * (1 - np.cos(theta)) / theta,
                      np.sin(theta) / theta - 1j * (1 - np.cos(theta)) / theta])
    # B = I + a[ω] + b[ω]² is normal (its terms commute with their transposes): its eigenvalues move by no more than
    # B does (Bauer-Fike with a unitary eigenbasis), so they are well-conditioned: TOL (close)
    assert close(np.sort_complex(lam).view(float), np.sort_complex(right).view(float))
    old = np.array([1.0, (1 - np.cos(theta)) / theta**2 + 1j * (theta - np.sin(theta)) / theta**2,
                    (1 - np.cos(theta)) / theta**2 - 1j * (theta - np.sin(theta)) / theta**2])
    assert not np.allclose(np.sort_complex(lam), np.sort_complex(old), atol=1e-3)
    det = np.linalg.det(_B_exp(theta))
    assert close(det, 2 * (1 - np.cos(theta)) / theta**2)           # a 3×3 determinant of entries <= 1: TOL
    assert close(det, abs(right[1]) ** 2)                             # the right pair gives the determinant
    assert abs(det - abs(old[1]) ** 2) > 0.05                          # the old pair did not


def test_old_pair_product_is_not_the_determinant_symbolically():
    t = sp.symbols("vartheta", positive=True)
    old_product = ((1 - sp.cos(t)) / t**2) ** 2 + ((t - sp.sin(t)) / t**2) ** 2
    new_product = (sp.sin(t) / t) ** 2 + ((1 - sp.cos(t)) / t) ** 2
    det = 2 * (1 - sp.cos(t)) / t**2
    assert sp.simplify(new_product - det) == 0
    assert sp.simplify(old_product - det) != 0
    assert abs(float((old_product - det).subs(t, 0.99))) > 0.5


def test_numbers_quoted_at_0_99(text):
    lam = np.linalg.eigvals(_B_exp(0.99))
    lam = lam[np.argmax(lam.imag)]
    assert (round(lam.real, 3), round(lam.imag, 3)) == (0.844, 0.456)   # 0.84447..., not 0.845
    assert round(np.linalg.det(_B_exp(0.99)), 3) == 0.921
    md = _markdown(text)
    assert r"$\lambda_\pm = 0.844 \pm 0.456\,i$" in md and "0.845" not in md


def test_mr_A_of_r_is_the_body_frame_transpose(text):
    r = np.array([0.4, -0.7, 1.1])
    nr, W = np.linalg.norm(r), jac.lie.skew(r)
    A = np.eye(3) - (1 - np.cos(nr)) / nr**2 * W + (nr - np.sin(nr)) / nr**3 * W @ W
    B = reps.rate_to_angular_velocity(r, "exp")
    R = jac.lie.exp_so3(r)
    assert close(A, R.T @ B)                                          # closed forms, exact algebra: TOL
    assert close(A, B.T)
    assert not np.allclose(A, B, atol=1e-3)
    assert r"A(r) &= R^{\mathsf T} B_{\exp}(r) \\" in text and r"&= B_{\exp}(r)^{\mathsf T} = B_{\exp}(-r)." in text
    assert "§5.1.5" in text


# ---------------------------------------------------------------- the gimbal-lock figure

OLD_PATH_DEG = np.linspace(-90.0, 90.0, 7)  # the old animation swept theta2 over [-90, 90] (theta1 = 30, theta3 = 0)


def _sigma_min_angular(chain, thetas):
    return np.linalg.svd(jac.geometric_jacobian(chain, thetas)[:, :3], compute_uv=False)[:, -1]


def test_old_gimbal_path_crossed_the_wrist_singularity():
    zyz = jac.robots.zyz_wrist(0.3)
    old = np.radians(np.column_stack([np.full(7, 30.0), OLD_PATH_DEG, np.zeros(7)]))
    # θ2 = 0 is on the old path: axes 1 and 3 aligned, σ_min = 0 exactly; computed within TOL (Weyl)
    assert close(_sigma_min_angular(zyz, old).min(), 0.0)


def test_new_gimbal_path_stays_away_from_it(text):
    """The path the page follows (now in the live view of the ZYZ wrist): θ2 from 45° to 135°, θ1 = 30°, θ3 = 0."""
    md = _markdown(text)
    assert "nowhere\nnear a singularity" not in text and "nowhere near a singularity" not in md
    assert "gimbal_lock_animation(frames=14, dpi=60)" not in text
    view = re.search(r"```\{live-view\} gimbal_lock\n(.*?)```", text, flags=re.S).group(1)
    assert ":robot: zyz_wrist" in view and ":rep: zyx" in view
    theta = [float(t) for t in re.search(r":theta: (.*)\n", view).group(1).split()]
    assert close(np.degrees(theta), [30.0, 45.0, 0.0])                    # the view starts the path (17 digits given)
    assert "$\\theta_1 = 30°$, $\\theta_3 = 0$, and $\\theta_2$ from $45°$ to\n$135°$" in text
    zyz = jac.robots.zyz_wrist(0.3)
    path = np.radians(np.column_stack([np.full(241, 30.0), np.linspace(45.0, 135.0, 241), np.zeros(241)]))
    assert _sigma_min_angular(zyz, path).min() >= 0.54
    phi = jac.pose_coordinates(zyz.fk(path), "zyx")[:, :3]
    det_B = np.linalg.det(reps.rate_to_angular_velocity(phi, "zyx"))
    # det B = -cos φ2 = 0 at θ2 = 90°, a point of the path (45 + 120·0.375): computed within TOL of 0
    assert close(np.abs(det_B).min(), 0.0)                # the coordinates lock on the path
    assert np.isnan(jac.analytic_jacobian(zyz, path, "zyx", on_singularity="nan")).any()


# ---------------------------------------------------------------- errors of the notes, warned about

def test_notes_linearisation_missing_delta_q_is_warned(text):
    notes = sorted(Path(__file__).resolve().parents[2].glob("shared/notes/002_*.txt"))
    if notes:  # the notes still contain the slip the page warns about
        assert re.search(r"\\delta \\chi_e \\approx\s+\\frac\{\\partial \\chi_e\(q\)\}\{\\partial q\} = J_\{e\}\(q\)\\delta q",
                         notes[0].read_text(encoding="utf-8"))
    md = _markdown(text)
    assert "**An error in the notes:** the first-order approximation" in md
    chain = jac.robots.spatial_5r()
    th = np.array([0.3, -0.5, 0.9, 0.4, -0.2])
    dq = 1e-3 * np.array([0.7, -0.2, 0.5, 1.1, -0.6])
    J = jac.analytic_jacobian(chain, th, "exp")
    dchi = jac.pose_coordinates(chain.fk(th + dq), "exp") - jac.pose_coordinates(chain.fk(th), "exp")
    assert J.shape != dchi.shape                                            # the notes' middle term
    assert np.linalg.norm(dchi - J @ dq) < 1e-2 * np.linalg.norm(dchi)      # the right one


def test_notes_dimension_name_is_warned(text):
    notes = sorted(Path(__file__).resolve().parents[2].glob("shared/notes/003_*.txt"))
    if notes:
        src = notes[0].read_text(encoding="utf-8")
        assert r"x \in \mathbb{R}^p" in src and r"\mathbb{R}^{n_x\times n}" in src
    md = _markdown(text)
    assert "**An error in the notes:** the size of the analytic Jacobian" in md
    assert r"\partial g/\partial\theta \in \mathbb{R}^{p\times n}" in md
    chain = jac.robots.spatial_5r()
    th = np.zeros(5)
    for p, g in ((2, lambda t: chain.fk(t)[:2, 3]), (3, lambda t: chain.fk(t)[:3, 3])):
        assert jac.numerical_jacobian(g, th).shape == (p, 5)


# ---------------------------------------------------------------- page quality

def test_no_checked_prints_and_one_notation(text):
    assert "✓ checked" not in text
    md = _markdown(text)
    assert "l_1" not in md.replace("(their $l_1 c_1$)", "")      # link lengths are L_1, L_2
    assert "l_2" not in md
    assert md.rstrip().splitlines()[-1].startswith("- Corke")    # References is the last section
    assert "## References" in md
