"""Tests of course.chapter, the set-up every chapter imports."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
import sympy as sp

import jacobians as jac
from course import chapter
from jacobians import symbolic as sym
from jacobians.plotting import PALETTE
from jacobians.verified import Verified


@pytest.fixture
def restore_style():
    saved = dict(matplotlib.rcParams)
    printing = np.get_printoptions()
    yield
    matplotlib.rcParams.update(saved)
    np.set_printoptions(**printing)


def test_start_page_returns_a_seeded_generator(restore_style):
    rng = chapter.start_page(seed=4)
    assert rng.uniform() == np.random.default_rng(4).uniform()
    assert chapter.start_page(seed=4) is not rng
    assert chapter.Verified is Verified
    assert np.get_printoptions()["precision"] == 4 and np.get_printoptions()["suppress"] is True


def test_start_page_styles(restore_style):
    before = matplotlib.rcParams["font.size"]
    chapter.start_page()
    assert matplotlib.rcParams["font.size"] == before  # default: matplotlib's own sizes
    chapter.start_page(font_size=12)
    assert (matplotlib.rcParams["font.size"], matplotlib.rcParams["axes.titlesize"],
            matplotlib.rcParams["xtick.labelsize"], matplotlib.rcParams["legend.fontsize"]) == (12, 13, 11, 11)
    chapter.start_page(font_size=11)
    assert (matplotlib.rcParams["axes.labelsize"], matplotlib.rcParams["ytick.labelsize"]) == (11, 11)
    chapter.start_page(lecture=True)
    assert matplotlib.rcParams["font.size"] == 14
    with pytest.raises(ValueError, match="either font_size or lecture"):
        chapter.start_page(font_size=12, lecture=True)
    with pytest.raises(TypeError, match="int seed"):
        chapter.start_page(seed=1.5)  # type: ignore[arg-type]


def test_colours_are_the_library_palette():
    assert chapter.C["vermillion"] == PALETTE["vermillion"] and chapter.C["sky"] == PALETTE["sky_blue"]
    assert set(chapter.C.values()) <= set(PALETTE.values())
    assert len(set(chapter.C.values())) == len(chapter.C)  # seven distinct colours
    assert chapter.PALETTE is PALETTE


def test_clean_rounds_and_removes_negative_zero():
    out = chapter.clean([-1e-9, 0.123456, -2.00004])
    assert out.tolist() == [0.0, 0.1235, -2.0]
    assert not np.signbit(out[0])
    assert chapter.clean([[1.23456]], digits=2).tolist() == [[1.23]]


def test_show_refuses_non_text():
    with pytest.raises(TypeError, match="LaTeX as a str"):
        chapter.show(sp.Symbol("x"))  # type: ignore[arg-type]


def test_trig_shorthand_names_sums_of_joint_angles():
    t1, t2, t3 = sp.symbols("theta1:4", real=True)
    e = sp.cos(t1 + t2) + sp.sin(t1) + sp.sin(t1 + t2 + t3) + sp.cos(2 * t1) + sp.sin(t3 + t1)
    out = chapter.trig_shorthand(e, (t1, t2, t3))
    names = {str(x) for x in out.free_symbols}
    assert names == {"c_{12}", "s_{1}", "s_{123}", "s_{13}", "theta1"}  # cos(2 theta1) is left as it is
    assert out.has(sp.cos(2 * t1))
    # only a renaming: putting sin and cos back gives the expression again
    back = {sp.Symbol("c_{12}"): sp.cos(t1 + t2), sp.Symbol("s_{1}"): sp.sin(t1),
            sp.Symbol("s_{123}"): sp.sin(t1 + t2 + t3), sp.Symbol("s_{13}"): sp.sin(t1 + t3)}
    assert sp.simplify(out.subs(back) - e) == 0
    with pytest.raises(TypeError, match="sympy symbols"):
        chapter.trig_shorthand(e, ["theta1"])  # type: ignore[list-item]


def test_the_zero_tests_are_the_librarys():
    assert chapter.is_zero is sym.is_zero and chapter.is_zero_matrix is sym.is_zero_matrix


@pytest.mark.parametrize("factory", [jac.robots.planar_3r, jac.robots.ur5, jac.robots.spatial_rrp])
def test_finite_difference_jacobians_match_the_library(factory):
    chain = factory()
    theta = np.random.default_rng(7).uniform(-np.pi, np.pi, chain.dof)
    assert np.allclose(chapter.fd_space_jacobian(chain, theta), jac.space_jacobian(chain, theta), atol=1e-6)
    assert np.allclose(chapter.fd_body_jacobian(chain, theta), jac.body_jacobian(chain, theta), atol=1e-6)


def test_d_dt_differentiates():
    assert np.allclose(chapter.d_dt(lambda t: np.array([np.sin(t), t**2]), 0.3), [np.cos(0.3), 0.6], atol=1e-8)


def test_random_arm_is_reproducible_and_valid():
    a = chapter.random_arm(6, np.random.default_rng(3))
    b = chapter.random_arm(6, np.random.default_rng(3))
    assert a.dof == 6 and np.array_equal(a.screw_axes, b.screw_axes) and np.array_equal(a.home, b.home)
    assert set(a.joint_types) <= {"R", "P"}
    for i, kind in enumerate(a.joint_types):
        w, v = a.screw_axes[:3, i], a.screw_axes[3:, i]
        assert np.isclose(np.linalg.norm(w if kind == "R" else v), 1.0)
    with pytest.raises(ValueError, match="positive number of joints"):
        chapter.random_arm(0, np.random.default_rng(0))


def test_legend_clear_sees_a_line_under_the_legend():
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 10)
    ax.plot([0, 1], [0, 1], label="a line")
    legend = ax.legend(loc="upper right")
    try:
        assert chapter.legend_clear(ax, legend, [np.array([[0.0, 0.0], [2.0, 2.0]])])
        fig.canvas.draw()
        box = legend.get_window_extent()
        centre = ax.transData.inverted().transform([(box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2])
        assert not chapter.legend_clear(ax, legend, [np.array([[0.0, 0.0], centre])])  # ends under the legend
    finally:
        plt.close(fig)


def test_every_public_name_is_exported():
    assert set(chapter.__all__) <= set(dir(chapter))
    assert {"start_page", "clean", "show", "trig_shorthand", "is_zero_matrix"} <= set(chapter.__all__)


def test_figures_carry_their_smallest_text_size(restore_style):
    """In a kernel, start_page makes every figure's PNG carry its smallest text (the deck tests read it)."""
    import base64
    import io

    from IPython.core.interactiveshell import InteractiveShell
    from PIL import Image

    ip = InteractiveShell.instance()
    try:
        chapter.start_page(font_size=12)           # ticks and legends 11 pt, labels 12 pt
        fig, ax = plt.subplots(figsize=(3, 2), dpi=80)
        ax.set_xlabel("x (m)")
        data, _ = ip.display_formatter.format(fig)
        png = data["image/png"]
        im = Image.open(io.BytesIO(base64.b64decode(png) if isinstance(png, str) else png))
        assert float(im.text[chapter.TEXT_SIZE_KEY]) == pytest.approx(11 * 80 / 72, abs=0.01)
        ax.tick_params(labelsize=9)                # smaller ticks: the PNG says so
        data, _ = ip.display_formatter.format(fig)
        png = data["image/png"]
        im = Image.open(io.BytesIO(base64.b64decode(png) if isinstance(png, str) else png))
        assert float(im.text[chapter.TEXT_SIZE_KEY]) == pytest.approx(9 * 80 / 72, abs=0.01)
        plt.close(fig)
    finally:
        InteractiveShell.clear_instance()


def _svg_root(svg: str) -> dict[str, str]:
    import re

    head = re.search(r"<svg\b[^>]*>", svg)
    assert head is not None
    return dict(re.findall(r'([\w:-]+)="([^"]*)"', head.group(0)))


def _slide_text_px(svg: str) -> float:
    """The smallest text of a slide SVG in px of the deck's canvas, where the slide shows it."""
    root = _svg_root(svg)
    width, height = float(root["viewBox"].split()[2]), float(root["viewBox"].split()[3])
    box_w, box_h = chapter.SLIDE_FIGURE_BOX
    shown = min(box_w, box_h * width / height)
    return float(root[chapter.SVG_TEXT_ATTR]) * shown / width


@pytest.mark.parametrize("three_d", [False, True], ids=["2-D", "3-D"])
def test_slide_svg_enlarges_a_copy_and_leaves_the_figure(restore_style, three_d):
    """The decks' SVG of a figure: its smallest text reaches SLIDE_TEXT_PX where the slide shows it, glyphs
    are paths, the overlapping texts are listed (none here); the figure itself keeps its sizes."""
    from matplotlib.text import Text

    from jacobians.plotting import smallest_text_px

    fig = plt.figure(figsize=(6, 3.5), dpi=80)
    ax = fig.add_subplot(projection="3d") if three_d else fig.add_subplot()
    ax.plot([0, 1], [0, 1], label="a line")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend()
    before = smallest_text_px(fig)
    sizes = sorted(float(t.get_fontsize()) for t in fig.findobj(Text))
    svg = chapter.slide_svg(fig)
    assert svg is not None
    root = _svg_root(svg)
    assert _slide_text_px(svg) >= chapter.SLIDE_TEXT_PX
    assert root[chapter.SVG_OVERLAP_ATTR] == ""
    assert "<text" not in svg                      # glyphs as paths: no font needed where it is shown
    assert smallest_text_px(fig) == pytest.approx(before)
    assert sorted(float(t.get_fontsize()) for t in fig.findobj(Text)) == pytest.approx(sizes)
    assert plt.fignum_exists(fig.number) and len(plt.get_fignums()) == 1   # the copy is closed
    plt.close(fig)


def test_text_overlaps_names_colliding_labels(restore_style):
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.text(0.5, 0.5, "first label", fontsize=14)
    ax.text(0.52, 0.5, "second label", fontsize=14)
    ax.text(0.1, 0.1, "apart", fontsize=14)
    found = chapter.text_overlaps(fig)
    plt.close(fig)
    assert ("first label", "second label") in found
    assert all("apart" not in pair for pair in found)


def test_latex_matrix_rounds_and_refuses_3d():
    assert chapter.latex_matrix([[1, -1e-9], [0.5, 2]], 1) == r"\begin{bmatrix}1.0 & 0.0\\0.5 & 2.0\end{bmatrix}"
    with pytest.raises(ValueError, match="shape"):
        chapter.latex_matrix(np.zeros((2, 2, 2)))
