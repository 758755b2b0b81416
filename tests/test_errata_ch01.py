"""Regression checks for the errors of chapter 1 fixed in issue 11.

Each test fails on the old text or value: it reads the chapter source and
computes the right value with the library.
"""

import re
from pathlib import Path

import numpy as np
import pytest

import jacobians as jac
from jacobians import lie
from jacobians.testing import close, fd_tol, within

ROOT = Path(__file__).resolve().parents[1]
CH01 = ROOT / "chapters" / "01_twists.md"


def _flat(text: str) -> str:
    """The text with every run of white space made one blank (sentences wrap anywhere)."""
    return re.sub(r"\s+", " ", text)


@pytest.fixture(scope="module")
def ch01() -> str:
    return CH01.read_text(encoding="utf-8")


def _warning(src: str, title_start: str) -> str:
    """The body of the ```{warning} block whose bold title starts with ``title_start``."""
    for block in re.findall(r"```\{warning\}\n(.*?)\n```", src, flags=re.S):
        if _flat(block).startswith(title_start):
            return _flat(block)
    raise AssertionError(f"no warning starting with {title_start!r} in chapter 1")


def _origin_image(w, q):
    """Where the body point at the origin is at time t[0] while the body turns at unit rate about (w, q)."""
    return lambda t: lie.exp_so3(w * t[0]) @ (np.zeros(3) - q) + q


def _origin_velocity(w, q):
    """Velocity of the body point at the origin while the body turns at unit rate about (w, q)."""
    return jac.numerical_jacobian(_origin_image(w, q), np.array([0.0]))[:, 0]


def _origin_velocity_tol(w, q):
    """Bound on the central difference's error (fd_tol); R(-q) + q is a small difference of terms of size |q|."""
    return fd_tol(_origin_image(w, q), np.zeros(1), scale=float(np.abs(q).max()))


# ---------------------------------------------------------------- the sign of v

def test_sign_of_v_box_no_longer_calls_q_cross_w_wrong(ch01):
    flat = _flat(ch01)
    # the old box: "Writing v = w × q (or q × w with the wrong order) flips the linear part"
    assert r"(or $q \times \hat\omega$ with the wrong order)" not in flat
    box = _warning(ch01, r"**Common mistake: the sign of $v$.**")
    assert r"$v = -\hat\omega \times q$" in box
    assert r"same vector as $q \times \hat\omega$" in box
    assert r"The wrong form is $v = \hat\omega \times q$" in box
    assert r"$\mathcal S = (0,0,1,\ 0,-L_1,0)$" in box


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_turning_about_w_q_moves_the_origin_with_q_cross_w(seed):
    rng = np.random.default_rng(seed)
    w = rng.normal(size=3)
    w /= np.linalg.norm(w)
    q = rng.normal(size=3)
    v, bound = _origin_velocity(w, q), _origin_velocity_tol(w, q)
    assert within(v, -np.cross(w, q), bound)
    assert within(v, np.cross(q, w), bound)                      # the form the old box called wrong is right
    assert not within(v, np.cross(w, q), bound)                  # the truly wrong form


def test_example_of_the_box_pivot_on_plus_x():
    L1 = 0.8
    v = _origin_velocity(np.array([0.0, 0.0, 1.0]), np.array([L1, 0.0, 0.0]))
    assert within(v, [0.0, -L1, 0.0], _origin_velocity_tol(np.array([0.0, 0.0, 1.0]), np.array([L1, 0.0, 0.0])))
    assert close(jac.robots.planar_3r(L1, 1.0, 1.0).screw_axes[:, 1], [0, 0, 1, 0, -L1, 0])   # -ω × q, exact algebra


# ---------------------------------------------------------------- the UR5 figure

def _cell(src: str, figure_name: str) -> str:
    for cell in re.findall(r"```\{code-cell\} ipython3\n(.*?)\n```", src, flags=re.S):
        if f"name: {figure_name}" in cell:
            return cell
    raise AssertionError(f"no code cell with figure name {figure_name!r}")


def test_ur5_figure_has_two_views_and_checked_labels(ch01):
    cell = _cell(ch01, "ch01-fig-ur5")
    views = re.search(r"ur5_views = \((.*?)\)\s*#", cell)
    assert views and len(re.findall(r"\(\s*-?\d+\s*,\s*-?\d+\s*\)", views.group(1))) == 2
    assert 'projection="3d"' in cell and "place_labels()" in cell
    assert "fontsize=13" in cell and "dpi=80" in cell
    # the hidden cell after the figure asserts that no number overlaps or is crossed
    assert "assert art.label_problems() == []" in ch01
    # the old figure (one view, numbers at the tips) had numbers crossed by axis 5
    assert "view_init(elev=25, azim=-55)" not in cell


# ---------------------------------------------------------------- the terminology box

def test_terminology_box_is_labelled_and_names_the_four_sources(ch01):
    # the section runs to the next slide or subslide (cells inside it may carry speaker-notes metadata)
    m = re.search(r"\(ch01-terminology-geometric\)=\n### (.*?)\n(.*?)\n\+\+\+ \{\"slideshow\": \{\"slide_type\": \"(?:sub)?slide",
                  ch01, flags=re.S)
    assert m, "the terminology section must carry the label ch01-terminology-geometric"
    body = _flat(m.group(2))
    for source in ("*Modern Robotics*", "SDM5008 lecture (note 003)", "(note 002)", "Siciliano et al., §3.1",
                   "{prf:ref}`ch05-def-geometric`"):
        assert source in body, source


@pytest.mark.parametrize("chain", [jac.robots.ur5(), jac.robots.spatial_rrp()], ids=["ur5", "rrp"])
def test_terminology_mappings(chain):
    rng = np.random.default_rng(7)
    Z3, I3 = np.zeros((3, 3)), np.eye(3)
    swap = np.block([[Z3, I3], [I3, Z3]])
    for th in rng.uniform(-np.pi, np.pi, (3, chain.dof)):
        T = chain.fk(th)
        R, p = T[:3, :3], T[:3, 3]
        J, J_s, J_b = jac.geometric_jacobian(chain, th), jac.space_jacobian(chain, th), jac.body_jacobian(chain, th)
        # Modern Robotics
        assert close(J, np.block([[I3, Z3], [-lie.skew(p), I3]]) @ J_s)         # exact algebra both sides: TOL
        assert close(J, np.block([[R, Z3], [Z3, R]]) @ J_b)
        # note 003: the column formula in {0} builds J_s, which is not J_b
        E, S = np.eye(4), chain.screw_axes
        for i in range(chain.dof):
            assert close(jac.adjoint(E) @ S[:, i], J_s[:, i])
            E = E @ lie.exp_se3(S[:, i] * th[i])
        assert not np.allclose(J_s, J_b, atol=1e-3)
        # note 002 and Siciliano: (pdot, omega), linear first, is our J with its halves swapped
        dp = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, 3], th)
        rev = np.array([c == "R" for c in chain.joint_types])
        P = chain.prefix_transforms(th)
        z = np.array([P[i, :3, :3] @ (S[:3, i] if rev[i] else S[3:, i]) for i in range(chain.dof)]).T
        # the rows dp are central differences: within fd_tol (truncation + rounding); the rows z are exact algebra
        bound = fd_tol(lambda t: chain.fk(t)[:3, 3], th)
        assert within(swap @ J, np.vstack([dp, np.where(rev, z, 0.0)]), bound)
        assert not within(J, np.vstack([dp, np.where(rev, z, 0.0)]), bound)  # the order matters


# ---------------------------------------------------------------- page mechanics

@pytest.mark.parametrize("page", ["01_twists.md", "conventions.md", "intro.md"])
def test_no_checked_prints(page):
    src = (ROOT / "chapters" / page).read_text(encoding="utf-8")
    assert "✓ checked" not in src


def _sections(src: str):
    """(title, body) of each ## section."""
    parts = re.split(r"^## (.*)$", src, flags=re.M)
    return list(zip(parts[1::2], parts[2::2], strict=True))


@pytest.mark.parametrize("page", ["01_twists.md", "conventions.md"])
def test_sections_with_formulas_end_with_a_verified_box(page):
    src = (ROOT / "chapters" / page).read_text(encoding="utf-8")
    assert "render_markdown_format: myst" in src.split("---", 2)[1]
    for title, body in _sections(src):
        needs = "$$" in body or re.search(r"\{prf:(theorem|proposition|lemma|corollary)\}", body)
        if not needs:
            continue
        cells = re.findall(r"```\{code-cell\} ipython3\n(.*?)\n```", body, flags=re.S)
        assert cells and cells[-1].rstrip().endswith("verified.box()"), title


def test_chapter_1_ends_with_references(ch01):
    sections = _sections(ch01)
    title, body = sections[-1]
    assert title.strip() == "References"
    for book in ("*Modern Robotics* (2017)", "*Robotics: Modelling, Planning and Control* (2009)",
                 "*Robotics, Vision and Control*, 2nd ed. (2017)"):
        assert book in body
    # the sections the brief lists, and no others
    for sec in ("§3.2.3", "§3.3.2", "§3.3.3", "§4.1.1", "§4.1.3", "§2.5", "§2.7", "§3.1.1", "§8.1"):
        assert sec in body


@pytest.mark.parametrize("page", ["01_twists.md", "conventions.md"])
def test_no_bracket_swallowed_as_an_optional_argument(page):
    # "\begin{gathered}" or "\\" followed by "[..." reads the bracket as an optional argument,
    # and MathJax silently drops it (it dropped "[\mathcal V_s]" of Definition 3 once)
    src = (ROOT / "chapters" / page).read_text(encoding="utf-8")
    bad = re.findall(r"(?:\\begin\{(?:gathered|aligned)\}|\\\\)\s*\n\s*\[", src)
    assert bad == []
