"""Regression checks for the errata of chapters 2 and 3 (and the appendix page).

Each test reads the chapter source and checks that the old wrong text is gone
and the new text is there, and computes with the library (or sympy) the value
that decides who is right, so that it fails on the old page or a wrong value.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import jacobians as jac
from jacobians import lie
from jacobians.testing import close, fd_tol, within

ROOT = Path(__file__).resolve().parents[1]
CH02 = (ROOT / "chapters" / "02_space_jacobian.md").read_text(encoding="utf-8")
CH03 = (ROOT / "chapters" / "03_body_jacobian.md").read_text(encoding="utf-8")
APPENDIX = (ROOT / "chapters" / "appendix_library.md").read_text(encoding="utf-8")
PAGES = {"02": CH02, "03": CH03, "appendix": APPENDIX}


def section(text: str, label: str) -> str:
    """The text from the label ``(label)=`` up to the next ``## `` heading."""
    start = text.index(f"({label})=")
    heading = text.index("\n## ", start)
    nxt = text.find("\n## ", heading + 4)
    return text[start: nxt if nxt != -1 else len(text)]


def flat(text: str) -> str:
    """Prose with line breaks and runs of spaces collapsed, for sentence checks."""
    return " ".join(text.split())


def h2_sections(text: str) -> list[tuple[str, str]]:
    """(heading, body) for every ``## `` section of a page."""
    parts = re.split(r"^## ", text, flags=re.M)[1:]
    return [(p.splitlines()[0], p) for p in parts]


def prf_block(text: str, kind: str, label: str | None = None, after: str | None = None) -> str:
    """The body of the first ``{prf:kind}`` block (with ``:label: label``, or after the string ``after``)."""
    pos = text.index(after) if after else 0
    while True:
        start = text.index("```{prf:" + kind + "}", pos)
        end = text.index("\n```", start + 3)
        block = text[start:end]
        if label is None or f":label: {label}" in block:
            return block
        pos = end


# ---------------------------------------------------------------- chapter 2: the explorer animation

def _explorer_frames(sweep):
    """The 2R arm's J_s and the semi-axes of J_v at 9 poses from (0, 1.2), joint `sweep` (1-based) over [-π, π]."""
    arm = jac.robots.planar_2r(1.0, 1.0)
    path = np.tile([0.0, 1.2], (9, 1))
    path[:, sweep - 1] = np.linspace(-np.pi, np.pi, 9)
    J = np.array([jac.space_jacobian(arm, th) for th in path])
    sig = np.array([jac.analysis.velocity_ellipsoid(jac.geometric_jacobian(arm, th)[3:5])[0] for th in path])
    return arm, J, sig


def test_ch02_explorer_sweeps_joint_1_so_the_J_s_table_changes():
    explore = section(CH02, "ch02-explore")
    assert "sweep=2" not in CH02 and ":sweep: 0" in explore  # the live view's Play turns joint 1
    # the old promises that the figure did not keep
    assert "the formula each column comes from" not in flat(CH02)
    assert "turns red" not in flat(CH02)
    # value: a sweep of θ2 (the old animation) leaves the J_s table constant, a sweep of θ1 does not
    _, J_old, _ = _explorer_frames(sweep=2)
    assert close(J_old, J_old[0])                                  # θ2 enters no column: the same algebra, TOL
    arm, J_new, sig = _explorer_frames(sweep=1)
    assert np.ptp(J_new[:, 3:5, 1], axis=0).min() > 1.5          # column 2 goes round with θ1
    assert np.ptp(J_new[:, :, 0], axis=0).max() == 0              # column 1 stays S_1
    # what the text says about the box: σ_min(J_v) = 0.500 m in every frame of the θ1 sweep
    # a number printed with 3 decimals is within 0.5e-3 of the value; singular values are well-conditioned (Weyl)
    assert "0.500" in explore and within(sig[:, 1], 0.5, 0.5e-3) and close(sig, sig[0])


def test_ch02_the_ellipses_are_said_to_belong_to_J_v_not_J_s():
    explore = flat(section(CH02, "ch02-explore"))
    assert "do not come from $J_s$" in explore and "$J_v$" in explore
    arm, J_s_frames, sig = _explorer_frames(sweep=1)
    th = np.array([0.7, 1.2])
    J_v = jac.geometric_jacobian(arm, th)[3:5]
    J_s_lin = jac.space_jacobian(arm, th)[3:5]
    s_v = np.linalg.svd(J_v, compute_uv=False)
    s_s = np.linalg.svd(J_s_lin, compute_uv=False)
    assert close(sig[0], s_v)                                     # what the explorer draws
    assert np.abs(s_v - s_s).max() > 0.1                          # J_s's rows would give another ellipse


def test_ch02_column_2_of_the_2R_space_jacobian_depends_on_theta1_only():
    t1, t2, L1 = sp.symbols("theta1 theta2 L1", real=True)
    c, s = sp.cos(t1), sp.sin(t1)
    R = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    v2 = R * sp.Matrix([0, -L1, 0])                               # Ad of a rotation about z through 0
    J_s2 = sp.Matrix([0, 0, 1]).col_join(v2)
    assert sp.simplify(J_s2 - sp.Matrix([0, 0, 1, L1 * s, -L1 * c, 0])) == sp.zeros(6, 1)
    assert J_s2.diff(t2) == sp.zeros(6, 1) and J_s2.diff(t1) != sp.zeros(6, 1)
    num = jac.space_jacobian(jac.robots.planar_2r(1.3, 0.7), [0.4, 2.0])[:, 1]
    assert close(num, [0, 0, 1, 1.3 * np.sin(0.4), -1.3 * np.cos(0.4), 0])
    assert "It contains $\\theta_1$ and nothing else" in flat(section(CH02, "ch02-explore"))


# ---------------------------------------------------------------- chapter 2: a notes error now warned

def test_ch02_warns_that_column_3_of_J_s_does_not_depend_on_theta3():
    meaning = flat(section(CH02, "ch02-meaning"))
    assert "**An error in the notes:**" in meaning
    assert "from the current axis (joint 3) to the base" in meaning   # the notes' wrong sentence, quoted
    arm5 = jac.robots.spatial_5r()
    th = np.array([0.4, -0.7, 0.9, 0.3, -0.5])
    dJ = jac.numerical_jacobian(lambda x: jac.space_jacobian(arm5, x), th)
    d = np.linalg.norm(dJ[:, 2, :], axis=0)
    # the notes' "joint 3 counts" is false: ∂J_3/∂θ3 = 0, so its central difference is within fd_tol of 0
    assert within(dJ[:, 2, 2], 0.0, fd_tol(lambda x: jac.space_jacobian(arm5, x), th))
    assert d[0] > 1e-2 and d[1] > 1e-2


# ---------------------------------------------------------------- the benchmark moved to the appendix

def test_benchmark_moved_to_the_appendix():
    assert "perf_counter" not in CH02 and "best_time" not in CH02
    assert "{doc}`appendix_library`" in CH02
    assert "perf_counter" in APPENDIX and "(appendix-library)=" in APPENDIX
    # the appendix asserts only robust facts: the counts of exponentials and the agreement of all methods
    assert "assert close(space_jacobian_naive(S, theta, c_naive), J_lib)" in APPENDIX
    assert "(rec, naive, fd) == (n, n * (n - 1) // 2, (2 * n + 1) * n)" in APPENDIX
    for line in APPENDIX.splitlines():                             # no assert on a time
        assert not (line.lstrip().startswith("assert") and ("t_rec" in line or "t_lib" in line or "t_batch" in line))


# ---------------------------------------------------------------- chapter 3: "Physical meaning" stands alone

def test_ch03_physical_meaning_proof_no_longer_defers_to_chapter_4():
    proof = prf_block(CH03, "proof", after=":label: ch03-prop-meaning")
    assert "04_space_vs_body" not in proof and "worked out in" not in proof
    assert r"T(\theta + te_i)" in proof and "stay still" in proof
    # value: moving joint i alone is the screw motion e^{[J_bi] t} seen from {b} (UR5, every joint)
    ur5 = jac.robots.ur5()
    th = np.array([0.3, -1.1, 0.8, 0.4, -0.6, 1.2])
    T, J_b = ur5.fk(th), jac.body_jacobian(ur5, th)
    for i in range(6):
        e = np.eye(6)[i]
        for t in (0.5, -1.3):
            assert close(ur5.fk(th + t * e), T @ lie.exp_se3(J_b[:, i] * t))     # exact algebra, TOL
        w, v = J_b[:3, i], J_b[3:, i]
        q = np.cross(w, v)                                         # a point of the axis, in {b}
        assert close(ur5.fk(th + 0.9 * e) @ np.r_[q, 1], T @ np.r_[q, 1])    # the axis stays still (rounding only)


# ---------------------------------------------------------------- chapter 3: the four-column box, said once

def test_ch03_four_columns_label_and_a_self_contained_box():
    assert CH03.count("(ch03-four-columns)=") == 1
    after = CH03[CH03.index("(ch03-four-columns)="):]
    box = after[after.index("```{warning}"):after.index("\n```\n", after.index("```{warning}"))]
    assert after.index("```{warning}") < 200                      # the label sits right before the box
    assert box.split("\n", 1)[1].startswith("**An error in the notes:**")
    assert "0 & 0 & 0 & 0" in box                                  # the wrong form
    assert "L_3 + L_2 c_3 + L_1 c_{23} & L_3 + L_2 c_3 & L_3" in box   # the right form
    assert "checked" in box
    assert "Common mistake: a garbled $J_b$ in the lecture slides" not in CH03
    # value: the notes' rows cannot form a matrix; the right J_b is 6 x 3 with angular rows (0,0,0),(0,0,0),(1,1,1)
    with pytest.raises(ValueError):
        sp.Matrix([[0, 0, 0, 0], [0, 0, 0, 0], [1, 1, 1, 1], [1, 2, 0], [3, 4, 5], [0, 0, 0]])
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    th = np.array([0.3, 0.6, -0.9])
    J_b = jac.body_jacobian(arm, th)
    L1, L2, L3 = 1.0, 0.8, 0.5
    s3, c3, s23, c23 = np.sin(th[2]), np.cos(th[2]), np.sin(th[1] + th[2]), np.cos(th[1] + th[2])
    right = np.array([[0, 0, 0], [0, 0, 0], [1, 1, 1], [L2 * s3 + L1 * s23, L2 * s3, 0],
                      [L3 + L2 * c3 + L1 * c23, L3 + L2 * c3, L3], [0, 0, 0]])
    assert J_b.shape == (6, 3) and close(J_b, right)


# ---------------------------------------------------------------- chapter 3: errors of the notes now warned

def test_ch03_warns_the_body_twist_is_not_a_spatial_twist():
    definition = flat(section(CH03, "ch03-definition"))
    assert "**An error in the notes:**" in definition and "the space twist equation" in definition
    ur5 = jac.robots.ur5()
    th, thd, h = np.array([0.3, -1.1, 0.8, 0.4, -0.6, 1.2]), np.array([0.5, -0.2, 0.3, 1.0, -0.7, 0.4]), 1e-6
    T = ur5.fk(th)
    Tdot = (ur5.fk(th + h * thd) - ur5.fk(th - h * thd)) / (2 * h)
    V_b = lie.matrix_to_twist(lie.inverse_transform(T) @ Tdot)
    V_s = lie.matrix_to_twist(Tdot @ lie.inverse_transform(T))
    # Ṫ is a central difference: each entry within fd_tol; a twist entry sums a row or column of it times T⁻¹
    e_V = fd_tol(lambda s: ur5.fk(th + s[0] * thd), np.zeros(1), h) * float(np.abs(lie.inverse_transform(T)).sum())
    assert within(V_b, jac.body_jacobian(ur5, th) @ thd, e_V)
    assert np.linalg.norm(V_b - V_s) > 0.1                          # T⁻¹Ṫ is not the spatial twist
    assert within(V_s, lie.adjoint(T) @ V_b, e_V * (1 + np.abs(lie.adjoint(T)).sum(axis=1).max()))   # both carry e_V


def test_ch03_warns_J_bi_is_a_column_of_J_b_and_free_of_theta_i():
    columns = flat(section(CH03, "ch03-columns"))
    assert columns.count("**An error in the notes:**") == 2
    assert "the $i$-th column of $J_s(\\theta)$" in columns           # the notes' wrong phrase, quoted
    assert "from the current axis to the end effector" in columns
    ur5 = jac.robots.ur5()
    th = np.array([0.3, -1.1, 0.8, 0.4, -0.6, 1.2])
    J_b, J_s = jac.body_jacobian(ur5, th), jac.space_jacobian(ur5, th)
    assert np.all(np.linalg.norm(J_b - J_s, axis=0) > 0.05)
    arm5 = jac.robots.spatial_5r()
    th5 = np.array([0.4, -0.7, 0.9, 0.3, -0.5])
    dJ = jac.numerical_jacobian(lambda x: jac.body_jacobian(arm5, x), th5)
    d = np.linalg.norm(dJ[:, 2, :], axis=0)
    assert within(dJ[:, 2, 2], 0.0, fd_tol(lambda x: jac.body_jacobian(arm5, x), th5))   # FD of 0: within fd_tol
    assert d[3] > 1e-2 and d[4] > 1e-2                              # not θ3, but θ4 and θ5


# ---------------------------------------------------------------- page mechanics (COMMON.md 1-7)

@pytest.mark.parametrize("name", sorted(PAGES))
def test_verified_boxes_replace_checked_prints(name):
    text = PAGES[name]
    assert "✓ checked" not in text and "✓" not in text
    assert "render_markdown_format: myst" in text.split("\n---\n", 1)[0]
    assert "verified = Verified()" in text
    for heading, body in h2_sections(text):
        if "$$" in re.sub(r"\$\$[^$]*\{\?\}[^$]*\$\$", "", body) or re.search(r"```\{prf:(theorem|proposition|lemma|corollary)\}", body):
            cells = re.findall(r"```\{code-cell\}.*?\n```", body, flags=re.S)
            assert cells and cells[-1].rstrip("`").strip().endswith("verified.box()"), heading


@pytest.mark.parametrize("name", sorted(PAGES))
def test_references_come_last(name):
    text = PAGES[name]
    headings = [h for h, _ in h2_sections(text)]
    assert headings[-1] == "References"
    refs = h2_sections(text)[-1][1]
    assert "Lynch & Park, *Modern Robotics*" in refs
    if name == "02":
        assert "§5.1.1" in refs
    if name == "03":
        assert "§5.1.2" in refs and "§8.1.2" in refs


@pytest.mark.parametrize("name", ["02", "03"])
def test_every_animation_has_a_numbered_caption_and_a_readable_size(name):
    text = PAGES[name]
    cells = re.findall(r"```\{code-cell\} ipython3\n(.*?)\n```", text, flags=re.S)
    for cell in cells:
        if "animation_html(" in cell and "def animation_html" not in cell:
            head = cell.split("\n---\n", 1)[0] if cell.startswith("---") else ""
            assert "figure:" in head and f"name: ch{name}-fig-" in head and "caption:" in head
    for w, _h in re.findall(r"figsize=\(([\d.]+), ([\d.]+)\)", text) + re.findall(r"set_size_inches\(([\d.]+), ([\d.]+)\)", text):
        assert float(w) <= 8.5
    for dpi in re.findall(r"dpi=(\d+)", text):
        assert int(dpi) >= 80
    for size in re.findall(r"fontsize=([\d.]+)", text):
        assert float(size) >= 11


def test_ch03_animation_arrows_inside():
    """The old figure drew the column of joint 1 outside the right panel (x down to -1.70 with xlim -1.6).
    The live view (story ``body_columns``) that replaced it has a right panel that holds every arrow."""
    anim = section(CH03, "ch03-animation")
    assert "{live-view} story" in anim and ":story: body_columns" in anim
    from course.stories import story_model, story_theta, story_times

    model = story_model("body_columns")
    xr0 = model["box_right"][0]
    tt = story_times(model)
    traj = story_theta(model, tt)
    vb = jac.body_jacobian(jac.robots.planar_3r(1.0, 0.8, 0.5), traj)[:, 3:5, :]
    assert vb[:, 0, :].min() < -1.6                                # outside the old panel ...
    assert vb[:, 0, :].min() > xr0                                 # ... inside the new one


def test_one_notation_and_no_minus_zero_prints():
    # capital L for link lengths, c_2 shorthand in ch03 prose
    assert '"l1:' not in CH02 and r"(r+\theta_3)\cos\theta_2" not in CH03
    assert r"$c_1 = \cos\theta_1$" in CH02
    # arrays printed on the page go through fmt (np.round(...) + 0.0)
    for name, text in PAGES.items():
        for line in text.splitlines():
            if line.lstrip().startswith("print(") and re.search(r"print\((J_\w*|J_hand|V_b\.round)\)", line.strip()):
                pytest.fail(f"{name}: raw array print {line.strip()}")
    assert (np.round(np.array([-1e-17, -0.0]), 4) + 0.0).tolist() == [0.0, 0.0]
    assert "-0." not in str(np.round(np.array([-1e-17]), 4) + 0.0)
