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


def test_random_chain_is_reproducible_and_valid():
    a = chapter.random_chain(6, np.random.default_rng(3))
    b = chapter.random_chain(6, np.random.default_rng(3))
    assert a.dof == 6 and np.array_equal(a.screw_axes, b.screw_axes) and np.array_equal(a.home, b.home)
    assert set(a.joint_types) <= {"R", "P"}
    for i, kind in enumerate(a.joint_types):
        w, v = a.screw_axes[:3, i], a.screw_axes[3:, i]
        assert np.isclose(np.linalg.norm(w if kind == "R" else v), 1.0)
    with pytest.raises(ValueError, match="positive number of joints"):
        chapter.random_chain(0, np.random.default_rng(0))


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
