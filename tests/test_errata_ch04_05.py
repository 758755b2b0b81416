"""Regression checks for the errata of chapters 4 and 5.

Each test reads the chapter source and asserts that the old, wrong or repeated
text is gone, and computes with the library the value that shows why it was
wrong, so that the test fails on the old text and on a wrong value alike.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import jacobians as jac
from jacobians import lie
from jacobians.interop import SWAP
from jacobians.testing import close, fd_tol, within

ROOT = Path(__file__).resolve().parents[1]
CH4 = ROOT / "chapters" / "04_space_vs_body.md"
CH5 = ROOT / "chapters" / "05_geometric_jacobian.md"


def _text(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def _flat(text: str) -> str:
    """The text with runs of white space made single spaces (sentences wrap across lines)."""
    return " ".join(text.split())


def _sections(text: str) -> list[tuple[str, str]]:
    """(title, body) of each ``##`` section (code fences skipped when looking for headings)."""
    out, title, body, fence = [], None, [], False
    for line in text.splitlines():
        if line.startswith("```"):
            fence = not fence
        if not fence and line.startswith("## "):
            if title is not None:
                out.append((title, "\n".join(body)))
            title, body = line[3:].strip(), []
        elif title is not None:
            body.append(line)
    if title is not None:
        out.append((title, "\n".join(body)))
    return out


def _code_cells(text: str) -> list[str]:
    """The full text (options and source) of each ``{code-cell}``."""
    return re.findall(r"```\{code-cell\}[^\n]*\n(.*?)\n```(?=\n|$)", text, flags=re.S)


def _omega_columns(chain, th):
    R = chain.fk(th)[:3, :3]
    dR = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, :3], th)
    return np.stack([lie.unskew(0.5 * (W - W.T)) for W in (dR[..., i] @ R.T for i in range(chain.dof))], axis=1)


# ------------------------------------------------------------------ chapter 4: the table vs chapter 7

def test_ch04_no_longer_recommends_J_s_for_resolved_rate_control_towards_a_target():
    text = _flat(_text(CH4))
    assert "resolved-rate control towards a target given in $\\{s\\}$" not in text
    assert "typical use | resolved-rate control" not in text
    # what the page says instead, in agreement with chapter 7: tool-point control uses the geometric J
    assert "use the **geometric Jacobian** $J$" in text and "{ref}`ch07-when`" in text
    ch7 = _flat(_text(ROOT / "chapters" / "07_conversions.md"))
    assert "**Control of the tool point** (resolved rates" in ch7 and "the geometric Jacobian $J$" in ch7


def test_ch04_resolved_rates_with_the_linear_rows_of_J_s_do_not_move_the_tool_as_asked():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    theta = np.deg2rad([30.0, 45.0, -60.0])
    J_s, J = jac.space_jacobian(arm, theta), jac.geometric_jacobian(arm, theta)
    pdot_des = np.array([0.2, -0.1])
    thd_old = np.linalg.pinv(J_s[3:5]) @ pdot_des           # the old table's recipe, read literally
    got = J[3:5] @ thd_old
    assert np.linalg.norm(got - pdot_des) > 0.1              # the tool does not move as asked ...
    assert within(got, [0.11, 0.00], 0.5e-2)                 # ... the number quoted on the page (2 decimals: ±0.005)
    assert "$(0.11, 0.00)$ m/s" in _flat(_text(CH4))
    thd_new = np.linalg.pinv(J[3:5]) @ pdot_des              # the geometric Jacobian does
    # J_v is regular here (σ_min > 0.3): the pseudo-inverse solve is well-conditioned, its residual is rounding (TOL)
    assert np.linalg.svd(J[3:5], compute_uv=False)[-1] > 0.3 and close(J[3:5] @ thd_new, pdot_des)


def test_ch04_v_s_is_the_velocity_of_the_body_point_at_the_origin_not_of_the_tool():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    theta, thd = np.deg2rad([30.0, 45.0, -60.0]), np.array([0.3, -0.5, 0.8])
    T = arm.fk(theta)
    V_s = jac.space_jacobian(arm, theta) @ thd
    pdot = jac.geometric_jacobian(arm, theta)[3:] @ thd
    assert not np.allclose(V_s[3:], pdot, atol=1e-3)
    assert close(pdot, V_s[3:] + np.cross(V_s[:3], T[:3, 3]))     # exact algebra: TOL
    text = _flat(_text(CH4))
    assert "the linear part $v_s$ of the space twist is **not** the velocity of the hand" in text
    assert "$\\dot p = v_s + \\omega_s\\times p$" in text
    assert "$\\mathcal V_s = (\\omega_s,\\ \\dot p - \\omega_s\\times p)$" in text


# ------------------------------------------------------------------ chapter 4: near-duplicate animations

def test_ch04_keeps_one_animation_of_column_3():
    text = _text(CH4)
    cells = _code_cells(text)
    animations = [c for c in cells if "animation_html(" in c]
    assert len(animations) == 1, "chapter 4 should animate the columns once (the bar-chart animation)"
    assert "columns_explorer_animation" not in text          # the near-duplicate widget animation is gone
    assert "```{live-view} columns_explorer" in text         # the live explorer stays, now in the browser (no kernel)


# ------------------------------------------------------------------ "say it once": the four columns

def test_four_columns_correction_is_linked_not_repeated():
    ch4, ch5 = _flat(_text(CH4)), _flat(_text(CH5))
    assert "four entries in the first three rows; the correct $6\\times 3$ matrix" not in ch4
    assert "Garbled matrices in the source slides" not in ch4
    assert "Common mistake: a Jacobian with four columns" not in ch5
    assert "A quick sanity test that catches this kind of slip" not in ch5
    assert "{ref}`ch03-four-columns`" in ch4 and "{ref}`ch03-four-columns`" in ch5
    # the right matrices have one column per joint
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    th = np.array([0.3, -0.4, 1.1])
    assert jac.body_jacobian(arm, th).shape == (6, 3) and jac.geometric_jacobian(arm, th).shape == (6, 3)
    T = arm.fk(th)
    R = T[:3, :3]
    assert close(np.kron(np.eye(2), R) @ jac.body_jacobian(arm, th), jac.geometric_jacobian(arm, th))


# ------------------------------------------------------------------ chapter 5: errors of the notes

def _notes_geometric_jacobian(chain, th):
    """Note 002's J_0 = [dP/dq_i ; z_i] (linear rows first) for every joint, as printed."""
    P = chain.prefix_transforms(th)
    S = chain.screw_axes
    z = np.stack([P[i, :3, :3] @ (S[:3, i] if chain.joint_types[i] == "R" else S[3:, i]) for i in range(chain.dof)],
                 axis=1)
    dP = jac.numerical_jacobian(lambda t: chain.fk(t)[:3, 3], th)
    return np.vstack([dP, z])


@pytest.mark.parametrize("chain", [jac.robots.scara(), jac.robots.spatial_rrp()], ids=["scara", "rrp"])
def test_ch05_warns_that_notes_z_i_rows_hold_for_revolute_joints_only(chain):
    text = _flat(_text(CH5))
    assert "note 002 gives the geometric Jacobian as" in text and "holds only for a **revolute** joint" in text
    rng = np.random.default_rng(1)
    th = rng.uniform(-np.pi, np.pi, chain.dof)
    J0 = _notes_geometric_jacobian(chain, th)
    J = jac.geometric_jacobian(chain, th)
    w = _omega_columns(chain, th)
    k = chain.joint_types.index("P")
    # w: an entry of Ṙ Rᵀ sums 3 entries of the central difference Ṙ (each within fd_tol) times entries of R (<= 1)
    e_w = 3 * fd_tol(lambda t: chain.fk(t)[:3, :3], th)
    e_p = fd_tol(lambda t: chain.fk(t)[:3, 3], th)                   # dP/dq: central differences of the position
    assert close(np.linalg.norm(J0[3:, k]), 1.0) and within(w[:, k], 0, e_w)          # the notes' row fails
    assert close(J[:3, k], 0) and within(J0[:3], J[3:], e_p)                           # dP/dq is right


def test_ch05_row_order_of_note_002_is_a_block_swap():
    text = _flat(_text(CH5))
    assert "**Row order.**" in text and "J_0 = \\begin{bmatrix} 0 & I \\\\ I & 0 \\end{bmatrix} J" in text
    arm = jac.robots.spatial_5r()
    th = np.array([0.3, -0.7, 1.1, 0.4, -0.2])
    J0 = _notes_geometric_jacobian(arm, th)
    J = jac.geometric_jacobian(arm, th)
    e_p = fd_tol(lambda t: arm.fk(t)[:3, 3], th)                     # J0's rows dP/dq are central differences
    assert within(J0, SWAP @ J, e_p) and not within(J0, J, e_p)


def test_ch05_warns_that_note_002_propagation_is_for_revolute_joints_only():
    text = _flat(_text(CH5))
    assert "note 002 gives only the first pair" in text
    assert "+\\,\\dot d_{i+1}\\,\\hat z" in text
    # the prismatic third joint of the SCARA arm turns nothing: the body Jacobian's column has no angular part,
    # while the revolute-only recursion would add the joint rate to the angular velocity (a unit vector)
    scara = jac.robots.scara()
    th = np.array([0.4, -0.8, 0.05, 1.0])
    J_b = jac.body_jacobian(scara, th)
    assert close(J_b[:3, 2], 0) and close(np.linalg.norm(J_b[3:, 2]), 1.0)
    T = scara.fk(th)
    revolute_only = T[:3, :3].T @ np.array([0.0, 0.0, -1.0])   # what adding the rate to omega would give, in {b}
    assert not close(J_b[:3, 2], revolute_only)


def test_ch05_links_the_terminology_box_and_warns_about_note_003_names():
    text = _flat(_text(CH5))
    assert "{ref}`ch01-terminology-geometric`" in text
    assert "special velocities" in text and "*spatial* velocities" in text
    # note 003's columns [Ad(0T_i)] iS_i are the space Jacobian's, not the body Jacobian's
    scara = jac.robots.scara()
    rng = np.random.default_rng(2)
    th = rng.uniform(-np.pi, np.pi, 4)
    P = scara.prefix_transforms(th)
    M = [lie.make_transform(lie.exp_so3(rng.normal(size=3)), rng.normal(size=3)) for _ in range(4)]
    cols = [lie.adjoint(P[i + 1] @ M[i]) @ lie.adjoint(lie.inverse_transform(M[i])) @ scara.screw_axes[:, i]
            for i in range(4)]
    J_note = np.stack(cols, axis=1)
    assert close(J_note, jac.space_jacobian(scara, th))
    assert not close(J_note, jac.body_jacobian(scara, th))


def test_ch05_explorer_path_passes_the_singularities_the_text_promises():
    text = _flat(_text(CH5))
    # the live view sweeps theta_2 (Play) from (0.5, 1.2, 0) with theta_3 held straight
    assert ":theta: 0.5 1.2 0.0" in text and ":sweep: 1" in text and ":robot: planar_3r" in text
    assert "sweeps the elbow of a planar 3R arm through its singular configurations" not in text
    arm = jac.robots.planar_3r()
    sweep = np.linspace(-np.pi, np.pi, 17)

    def smin(th):
        return np.linalg.svd(jac.geometric_jacobian(arm, th)[3:5], compute_uv=False)[-1]

    old = [smin([0.5, t, -0.8]) for t in np.linspace(-np.pi, np.pi, 16)]   # the old animation's path
    assert min(old) > 0.3                                                   # never singular
    new = [smin([0.5, t, 0.0]) for t in sweep]
    # σ_min = 0 exactly at θ2 = -π, 0, π; computed, within TOL of it (Weyl: singular values are well-conditioned)
    assert sum(close(s, 0.0) for s in new) == 3


# ------------------------------------------------------------------ page mechanisms in both chapters

@pytest.mark.parametrize("path", [CH4, CH5], ids=["ch04", "ch05"])
def test_no_check_printouts_and_one_verified_box_per_section(path):
    text = _text(path)
    assert "✓" not in text and "checked:" not in text
    assert "render_markdown_format: myst" in text.split("---", 2)[1]
    for title, body in _sections(text):
        needs_box = "$$" in re.sub(r"\$\$[^$]*\{\?\}[^$]*\$\$", "", body) or re.search(r"```\{prf:(theorem|proposition|lemma|corollary)\}", body)
        cells = _code_cells(body)
        tail = body[body.rfind("verified.box()"):].split("```", 1)[-1] if "verified.box()" in body else ""
        ends_with_box = all(not ln.strip() or ln.startswith("+++") or re.fullmatch(r"\(\S+\)=", ln.strip())
                            for ln in tail.splitlines())   # blank, cell metadata, or the next section's label
        has_box = bool(cells) and cells[-1].rstrip().endswith("verified.box()") and ends_with_box
        if needs_box:
            assert has_box, f"section {title!r} of {path.name} must end with a verified.box() cell"
        if "verified(" in body:
            assert has_box, f"section {title!r} of {path.name} records checks but shows no box"


@pytest.mark.parametrize("path", [CH4, CH5], ids=["ch04", "ch05"])
def test_every_figure_and_animation_has_a_numbered_caption(path):
    text = _text(path)
    for cell in _code_cells(text):
        if "remove-output" in cell:
            continue
        makes_figure = "plt.show()" in cell or "display(fig)" in cell or "animation_html(" in cell
        if makes_figure:
            assert re.search(r"mystnb:\n\s+figure:\n\s+name: ch0[45]-fig-[\w-]+\n\s+caption: \S", cell), cell[:200]
            name = re.search(r"name: (ch0[45]-fig-[\w-]+)", cell).group(1)
            assert f"{{numref}}`{name}`" in text, f"{name} is never referred to in the text"


@pytest.mark.parametrize("path", [CH4, CH5], ids=["ch04", "ch05"])
def test_references_close_the_chapter(path):
    sections = _sections(_text(path))
    title, body = sections[-1]
    assert title == "References"
    assert "Lynch & Park, *Modern Robotics*" in body and "Siciliano" in body and "Corke" in body
    assert "```{code-cell}" not in body


def test_ch05_stanford_table_matches_the_arrays_of_its_cell():
    text = _text(CH5)
    rows = re.findall(r"^\| (\d) \| ([RP]) \| 0 \| (\$[^|]*\$|0) \| ([^|]+) \| ([^|]+) \|$", text, flags=re.M)
    assert len(rows) == 6
    alpha = {"$-\\pi/2$": -np.pi / 2, "$\\pi/2$": np.pi / 2, "0": 0.0}
    d = [0.0, 0.2, 0.5, 0.0, 0.0, 0.1]
    assert "".join(r[1] for r in rows) == "RRPRRR"
    # exact: the dictionary's values are the same float expressions as the list's
    assert np.array_equal([alpha[r[2].strip()] for r in rows], [-np.pi / 2, np.pi / 2, 0, -np.pi / 2, np.pi / 2, 0])
    for (_, kind, _, d_cell, _), d_i in zip(rows, d, strict=True):
        d_cell = d_cell.strip()
        if kind == "P":
            assert d_cell == f"${d_i} + \\theta_3$"
        else:
            assert float(d_cell) == d_i
    assert "d = np.array([0.0, 0.2, 0.5, 0.0, 0.0, 0.1])" in text
    assert "alpha = np.array([-np.pi / 2, np.pi / 2, 0, -np.pi / 2, np.pi / 2, 0])" in text
