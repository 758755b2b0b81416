"""Tests of jacobians.plotting: drawn data equal the library's values, updates move artists in place."""

import html
import os
import re

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

import jacobians as jac
from jacobians import plotting as P


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def test_palette_is_okabe_ito_and_has_semantic_keys():
    okabe_ito = {"#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7"}
    for key in ("link", "joint", "space", "body", "geometric", "analytic", "velocity", "force", "singular", "ok",
                "frame_x", "frame_y", "frame_z"):
        assert P.PALETTE[key] in okabe_ito, key
    assert P.PALETTE["space"] != P.PALETTE["body"]
    assert len({P.PALETTE["frame_x"], P.PALETTE["frame_y"], P.PALETTE["frame_z"]}) == 3


def test_draw_planar_arm_draws_joint_positions_and_updates_in_place():
    arm = jac.robots.planar_3r(1.0, 0.8, 0.5)
    fig, ax = plt.subplots()
    theta = np.array([0.4, 0.6, -0.5])
    art = P.draw_planar_arm(ax, arm, theta, setup_axes=True, title="t")
    pts = arm.joint_positions(theta)
    np.testing.assert_allclose(art.link_line.get_xydata(), pts[:, :2])
    np.testing.assert_allclose(np.column_stack(art.joint_markers.get_data()), pts[:-1, :2])
    n_lines = len(ax.lines)
    theta2 = np.array([-1.0, 2.0, 0.3])
    same_line = art.link_line
    art.update(theta2)
    assert art.link_line is same_line and len(ax.lines) == n_lines
    np.testing.assert_allclose(art.link_line.get_xydata(), arm.joint_positions(theta2)[:, :2])
    # tool frame x axis follows the rotation of T_sb
    T = arm.fk(theta2)
    x_line = art.tool_frame.axis_lines[0]
    xs, ys = x_line.get_data()
    d = np.array([xs[1] - xs[0], ys[1] - ys[0]])
    np.testing.assert_allclose(d / np.linalg.norm(d), T[:2, 0], atol=1e-12)
    np.testing.assert_allclose([xs[0], ys[0]], T[:2, 3], atol=1e-12)
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"


def test_twist_arrow_is_tool_velocity_from_geometric_jacobian():
    arm = jac.robots.planar_2r(1.0, 0.7)
    theta, rates = np.array([0.3, 1.1]), np.array([0.5, -1.2])
    V_s = jac.space_jacobian(arm, theta) @ rates
    fig, ax = plt.subplots()
    art = P.draw_planar_arm(ax, arm, theta, twist=V_s)
    pdot = (jac.geometric_jacobian(arm, theta) @ rates)[3:5]
    np.testing.assert_allclose(art.twist_artist.vectors[0], pdot, atol=1e-12)
    np.testing.assert_allclose(art.twist_artist.points[0], arm.fk(theta)[:2, 3], atol=1e-12)


def test_non_planar_chain_is_refused_with_clear_error():
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match="planar"):
        P.draw_planar_arm(ax, jac.robots.ur5(), np.zeros(6))
    with pytest.raises(ValueError, match="planar"):
        P.planar_arm_animation(jac.robots.spatial_5r(), np.zeros((3, 5)))
    with pytest.raises(TypeError, match="SerialChain"):
        P.draw_planar_arm(ax, "arm", [0, 0])


def test_ellipse_points_lie_on_the_ellipse():
    fig, ax = plt.subplots()
    J = jac.geometric_jacobian(jac.robots.planar_2r(), [0.2, 0.9])[3:5]
    U, s, _ = np.linalg.svd(J)
    e = P.draw_ellipse(ax, [0.5, -0.2], s, U)
    xy = e.line.get_xydata() - [0.5, -0.2]
    # u = diag(1/s) U^T (x - c) has unit norm on the ellipse
    u = (U.T @ xy.T) / s[:, None]
    np.testing.assert_allclose(np.linalg.norm(u, axis=0), 1.0, atol=1e-12)
    # a singular configuration gives a degenerate ellipse, not an error
    Js = jac.geometric_jacobian(jac.robots.planar_2r(), [0.2, 0.0])[3:5]
    U, s, _ = np.linalg.svd(Js)
    e.update([0, 0], s, U)
    assert np.all(np.isfinite(e.line.get_xydata()))


@pytest.mark.parametrize("frame", ["space", "body", "geometric"])
def test_column_arrows_match_jacobian(frame):
    arm = jac.robots.planar_3r()
    theta = np.array([0.3, -0.4, 1.0])
    P_, V = P.column_arrows(arm, theta, frame)
    T = arm.fk(theta)
    if frame == "space":
        np.testing.assert_allclose(V, jac.space_jacobian(arm, theta)[3:5].T, atol=1e-12)
        np.testing.assert_allclose(P_, 0.0)
    else:
        # body columns turned into {s} axes equal the geometric columns' linear parts
        np.testing.assert_allclose(V, jac.geometric_jacobian(arm, theta)[3:5].T, atol=1e-12)
        np.testing.assert_allclose(P_, np.tile(T[:2, 3], (3, 1)), atol=1e-12)


def test_animation_moves_arm_and_columns_and_html_has_no_cdn():
    arm = jac.robots.planar_2r()
    t = np.linspace(0, 1, 4)
    thetas = np.column_stack([t, 1 - t])
    anim = P.planar_arm_animation(arm, thetas, frame="space", show_velocity=[1.0, 0.5], dpi=40)
    assert isinstance(anim, P.FrameSource) and anim.n_frames == 4
    np.testing.assert_allclose(anim.path, thetas)
    fig = anim.fig
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x (m)" and ax.get_title()
    html = P.animation_html(anim).data
    assert "font-awesome" not in html and "https://" not in html and "http://" not in html
    assert "<i class=\"fa" not in html
    assert "&#9654;" in html  # the Play button is labelled
    # the frame slider has a name (WCAG 4.1.2): exactly one slider, labelled
    assert len(re.findall(r'<input id="_anim_slider[^>]*aria-label="Animation frame"', html)) == 1
    assert html.count('type="range"') == 1
    assert html.count("data:image/png;base64") == 4  # one inline PNG per frame
    assert not plt.fignum_exists(fig.number)  # closed: no stray static copy


def test_animation_last_frame_state_matches_library():
    arm = jac.robots.planar_3r()
    thetas = np.array([[0.0, 0.0, 0.0], [0.5, -0.3, 0.8]])
    anim = P.planar_arm_animation(arm, thetas, frame="body", dpi=40)
    anim.draw(1)
    line = [ln for ln in anim.fig.axes[0].lines if ln.get_label() == arm.name][0]
    np.testing.assert_allclose(line.get_xydata(), arm.joint_positions(thetas[1])[:, :2])
    plt.close(anim.fig)


def test_animation_draws_the_columns_of_the_frame_given():
    arm = jac.robots.planar_2r()
    thetas = np.array([[0.0, 0.0], [0.5, -0.3]])
    anim = P.planar_arm_animation(arm, thetas, frame="space", dpi=30)
    arrows = [c for c in anim.fig.axes[0].collections if "column 1" in str(c.get_label())]
    assert len(arrows) == 1
    plt.close(anim.fig)
    with pytest.raises(ValueError, match="got 'spatial'"):
        P.planar_arm_animation(arm, thetas, frame="spatial")
    # the former parameter name jacobian= is gone
    with pytest.raises(TypeError, match="jacobian"):
        P.planar_arm_animation(arm, thetas, jacobian="space")


def test_animation_rejects_bad_input():
    arm = jac.robots.planar_2r()
    with pytest.raises(ValueError, match=r"\(T, 2\)"):
        P.planar_arm_animation(arm, [0.1, 0.2])
    with pytest.raises(ValueError, match="Expected frame 'space', 'body' or 'geometric', got 'analytic'"):
        P.planar_arm_animation(arm, np.zeros((2, 2)), frame="analytic")
    with pytest.raises(TypeError, match="Animation"):
        P.animation_html("not an animation")


def test_spatial_chain_axes_follow_the_joints():
    ur5 = jac.robots.ur5()
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    theta = np.array([0.3, -0.5, 0.8, 0.2, 0.4, 0.1])
    art = P.draw_spatial_chain(ax, ur5, theta, setup_axes=True)
    x, y, z = art.link_line.get_data_3d()
    np.testing.assert_allclose(np.column_stack([x, y, z]), ur5.joint_positions(theta))
    # the current axis of joint i is the angular part of column i of J_s
    J_s = jac.space_jacobian(ur5, theta)
    dots = np.abs(np.sum(art.axis_directions * J_s[:3].T, axis=1))
    np.testing.assert_allclose(dots, 1.0, atol=1e-12)
    fig2, ax2 = plt.subplots()
    with pytest.raises(ValueError, match="3-D axes"):
        P.draw_spatial_chain(ax2, ur5, theta)


def test_frame_3d_and_2d():
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    T = np.eye(4)
    T[:3, :3] = jac.lie.rotation_about("z", 0.5)
    T[:3, 3] = [1, 2, 3]
    f = P.draw_frame(ax, T, "{b}", length=0.5)
    x, y, z = f.axis_lines[2].get_data_3d()
    np.testing.assert_allclose([x[1] - x[0], y[1] - y[0], z[1] - z[0]], 0.5 * T[:3, 2])
    with pytest.raises(ValueError, match=r"\(4, 4\)"):
        P.draw_frame(ax, np.eye(3), "{b}")


def test_matrix_latex_values_and_nan():
    J = jac.space_jacobian(jac.robots.planar_2r(), [0.0, np.pi / 2])
    s = P.matrix_latex(J, "J_s", digits=2)
    assert s.startswith("J_s = \\begin{bmatrix}") and s.endswith("\\end{bmatrix}")
    body = s[len("J_s = \\begin{bmatrix} "):-len(" \\end{bmatrix}")]
    rows = [[float(c) for c in r.split("&")] for r in body.split("\\\\")]
    np.testing.assert_allclose(rows, J.round(2), atol=1e-12)
    assert "-0.00" not in s
    assert "undef" in P.matrix_latex([[np.nan, 1.0]])
    with pytest.raises(ValueError, match="2-D"):
        P.matrix_latex(np.zeros((2, 2, 2)))


def test_draw_matrix_updates_text():
    fig, ax = plt.subplots()
    m = P.draw_matrix(ax, np.eye(2), digits=1)
    m.update([[1.26, -2.0], [np.inf, 0.0]])
    assert [t.get_text() for t in m.texts[0]] == ["1.3", "-2.0"]
    assert m.texts[1][0].get_text() == "undef."
    with pytest.raises(ValueError, match="shape"):
        m.update(np.eye(3))


def test_set_style_sets_readable_fonts():
    with matplotlib.rc_context():
        P.set_style()
        assert matplotlib.rcParams["font.size"] >= 14
        assert matplotlib.rcParams["axes.labelsize"] >= 14


def test_blitting_gives_the_same_frames_as_a_full_redraw():
    import matplotlib.pyplot as plt

    import jacobians as jac
    from jacobians import plotting

    arm = jac.robots.planar_2r()
    thetas = np.linspace([0.0, 0.3], [1.0, 1.5], 5)

    def make():
        fig, ax = plt.subplots(figsize=(3, 3), dpi=50)
        plotting.setup_planar_axes(ax, arm, title="blit test")
        art = plotting.draw_planar_arm(ax, arm, thetas[0], show_frames=False)

        def update(k):
            art.update(thetas[k])
            return []

        return fig, art, update

    fig, art, update = make()
    full = []
    for k in range(len(thetas)):
        update(k)
        fig.canvas.draw()
        full.append(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())
    plt.close(fig)
    # the interface: a FrameSource blitting the moving artists
    fig, art, update = make()
    source = plotting.FrameSource(fig, update, len(thetas), moving=art.artists)
    for k in range(len(thetas)):
        blitted = source.frame(k)
        assert np.mean(np.abs(blitted.astype(int) - full[k].astype(int))) < 1.0
    html = plotting.animation_html(source).data
    assert html.count("frames[") >= len(thetas) and "http" not in html.split("<script")[0]
    # the player says how large its smallest text is, in frame pixels (title, labels or ticks, at dpi 50)
    ticks = matplotlib.rcParams["xtick.labelsize"]
    ticks_pt = ticks if isinstance(ticks, (int, float)) else matplotlib.font_manager.FontProperties(size=ticks).get_size()
    smallest = min(float(ticks_pt), fig.axes[0].title.get_fontsize(), fig.axes[0].xaxis.label.get_fontsize())
    assert f'data-smallest-text-px="{smallest * 50 / 72:.2f}"' in html
    with pytest.raises(ValueError):
        plotting.FrameSource(fig, update, 0, moving=art.artists)
    # a FrameSource rendering whatever state the figure is in (rgba), the background kept across frames
    fig, art, update = make()
    again = plotting.FrameSource(fig, update, len(thetas), interval=50, moving=art.artists)
    assert again.fig is fig and again.n_frames == len(thetas) and again.interval == 50.0
    for k in range(len(thetas)):
        update(k)
        blitted = again.rgba()
        assert np.mean(np.abs(blitted.astype(int) - full[k].astype(int))) < 1.0
    html = plotting.animation_html(again).data
    assert html.count("frames[") >= len(thetas) and "http" not in html.split("<script")[0]
    # FrameSource is the one animation interface (the one before it, on a FuncAnimation, is gone)
    from jacobians.plotting import animation

    assert animation.__all__ == ["FrameSource", "animation_html", "compact_png"]
    assert all(hasattr(plotting, name) for name in animation.__all__)


def _old_ur5_figure():
    """The UR5 figure of chapter 1 before issue 11: one view, numbers at the segment tips."""
    fig = plt.figure(figsize=(6.4, 5.4), dpi=80)
    ax = fig.add_subplot(projection="3d")
    art = P.draw_spatial_chain(ax, jac.robots.ur5(), np.zeros(6), setup_axes=True, title="UR5 at home")
    ax.set_xlim(-0.2, 1.0)
    ax.set_ylim(-0.5, 0.7)
    ax.set_zlim(-0.4, 0.8)
    ax.view_init(elev=25, azim=-55)
    return art


def test_old_ur5_labels_are_reported_and_place_labels_clears_them():
    art = _old_ur5_figure()
    problems = art.label_problems()
    # the defects of the old figure: the wrist's vertical axis 5 runs through numbers 4 and 6
    assert "axis 5 crosses number 4" in problems and "axis 5 crosses number 6" in problems
    art.place_labels()
    assert art.label_problems() == []
    assert np.all(np.abs(art.label_at) > 1.0)  # every number moved beyond its segment, on a leader


@pytest.mark.parametrize("k, elev, azim", [(0, 22, -60), (1, 30, 30)])
def test_place_labels_keeps_each_number_on_its_own_axis(k, elev, azim):
    # the two views of the UR5 figure of chapter 1 (ch01-fig-ur5), as the chapter draws them
    ur5 = jac.robots.ur5()
    fig = plt.figure(figsize=(8.4, 4.6), dpi=80)
    ax = fig.add_axes([0.53 * k, 0.0, 0.47, 0.9], projection="3d")
    ax.set(xlim=(-0.2, 1.0), ylim=(-0.3, 0.4), zlim=(-0.25, 0.35))
    ax.set_box_aspect((1.2, 0.7, 0.6), zoom=(0.95, 1.0)[k])
    ax.view_init(elev=elev, azim=azim)
    art = P.draw_spatial_chain(ax, ur5, np.zeros(6), fontsize=13, label_box=True, axis_length=0.12,
                               frame_length=0.16, place_labels=True)
    assert art.label_problems() == []
    assert all(t.get_fontsize() == 13 for t in art.axis_texts)
    assert art.frames[0].name_text.get_fontsize() == 13
    for theta in (np.zeros(6), np.array([0.3, -0.5, 0.8, 0.2, 0.4, 0.1])):
        art.update(theta)
        pts, d = ur5.joint_positions(theta)[:6], art.axis_directions
        offset = art.label_points - pts
        # the number lies on its own axis line, label_at axis lengths from the joint point
        np.testing.assert_allclose(offset, art.label_at[:, None] * 0.12 * d, atol=1e-12)
        for i, ld in enumerate(art.leader_lines):
            x, y, z = ld.get_data_3d()
            assert len(x) == 2  # every number sits beyond its tip here, so each has a leader
            np.testing.assert_allclose([x[0], y[0], z[0]], pts[i] + np.sign(art.label_at[i]) * 0.12 * d[i])
            np.testing.assert_allclose([x[1], y[1], z[1]], art.label_points[i])


def test_label_problems_finds_overlaps_and_aligned_axes():
    wrist = jac.robots.zyz_wrist()
    fig = plt.figure(figsize=(5, 4), dpi=80)
    ax = fig.add_subplot(projection="3d")
    # all three numbers at the wrist centre: they overlap
    art = P.draw_spatial_chain(ax, wrist, [0.3, 0.9, 0.2], setup_axes=True, axis_length=0.15, label_at=0.0)
    assert "number 1 overlaps number 2" in art.label_problems()
    # at theta_2 = 0 axes 1 and 3 coincide (the wrist's singularity): one hides the other
    fig2 = plt.figure(figsize=(5, 4), dpi=80)
    ax2 = fig2.add_subplot(projection="3d")
    art2 = P.draw_spatial_chain(ax2, wrist, [0.3, 0.0, 0.2], setup_axes=True, axis_length=0.15, show_frames=False)
    assert "axis 3 is hidden under axis 1" in art2.label_problems()
    art2.update([0.3, 0.9, 0.2])
    assert not any("hidden" in p for p in art2.label_problems())


def test_label_positions_default_and_validation():
    ur5 = jac.robots.ur5()
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    art = P.draw_spatial_chain(ax, ur5, np.zeros(6), axis_length=0.1)
    # default: each number at the + tip of its segment, as before, with no leader
    np.testing.assert_allclose(art.label_points, ur5.joint_positions(np.zeros(6))[:6] + 0.1 * art.axis_directions)
    assert all(len(ld.get_data_3d()[0]) == 0 for ld in art.leader_lines)
    with pytest.raises(ValueError, match="one per joint"):
        P.draw_spatial_chain(ax, ur5, np.zeros(6), label_at=[1.0, 2.0])
    with pytest.raises(ValueError, match="candidates"):
        art.place_labels(candidates=[])


# ---------------------------------------------------------------- the animation interface

def _dot_figure():
    fig, ax = plt.subplots(figsize=(2, 2), dpi=30)
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    (dot,) = ax.plot([0.0], [0.0], "o")
    return fig, dot


def test_frame_source_rejects_bad_input_saying_what_came():
    fig, dot = _dot_figure()
    draw = lambda k: dot.set_data([0.1 * k], [0.0])
    with pytest.raises(TypeError, match="Expected a matplotlib Figure for fig, got Line2D"):
        P.FrameSource(dot, draw, 3)
    with pytest.raises(TypeError, match="Expected a callable draw"):
        P.FrameSource(fig, 3, 3)
    with pytest.raises(ValueError, match="positive number of frames, got 2.5"):
        P.FrameSource(fig, draw, 2.5)
    with pytest.raises(ValueError, match="positive interval"):
        P.FrameSource(fig, draw, 3, interval=0)
    with pytest.raises(TypeError, match="artists in moving, got str"):
        P.FrameSource(fig, draw, 3, moving=["dot"])
    with pytest.raises(ValueError, match="between 0 and 2, got 3"):
        P.FrameSource(fig, draw, 3).frame(3)
    with pytest.raises(ValueError, match="default_mode"):
        P.animation_html(P.FrameSource(fig, draw, 3), default_mode="bounce")
    plt.close(fig)


def test_frame_source_frames_move_and_the_player_keeps_the_interval_and_mode():
    fig, dot = _dot_figure()
    seen = []

    def draw(k):
        seen.append(k)
        dot.set_data([-0.8 + 0.8 * k], [0.0])
        return [dot]

    source = P.FrameSource(fig, draw, 3, interval=250, moving=[dot])
    first, last = source.frame(0), source.frame(2)
    assert first.shape == last.shape and first.shape[2] == 3 and not np.array_equal(first, last)
    html = P.animation_html(source, default_mode="reflect").data
    assert seen == [0, 2, 0, 1, 2]  # animation_html draws every frame once, in order
    assert html.count("data:image/png;base64") == 3 and "https://" not in html
    checked = re.findall(r'<input type="radio" name="state" value="(\w+)"[^>]*checked>', html)
    assert checked == ["reflect"]
    assert re.search(r"new Animation\(frames, img_id, slider_id, 250\.0,", html)
    assert not plt.fignum_exists(fig.number)


def test_animation_html_of_a_plain_func_animation_is_offline_with_palette_frames():
    from matplotlib.animation import FuncAnimation

    fig, dot = _dot_figure()
    anim = FuncAnimation(fig, lambda k: dot.set_data([0.3 * k], [0.0]), frames=3, interval=100)
    html = P.animation_html(anim).data
    frames = re.findall(r'frames\[\d+\] = "data:image/png;base64,([^"]*)"', html)
    assert len(frames) == 3 and "font-awesome" not in html and "https://" not in html
    import base64
    import io

    from PIL import Image

    assert Image.open(io.BytesIO(base64.b64decode(frames[1]))).mode == "P"  # palette PNG
    plt.close(fig)


def test_animation_html_drops_frames_beyond_the_limit_with_a_warning():
    fig, dot = _dot_figure()
    source = P.FrameSource(fig, lambda k: dot.set_data([0.1 * k], [0.0]), 4)
    with pytest.warns(UserWarning, match="dropped"):
        html = P.animation_html(source, embed_limit_mb=1e-4).data
    assert html.count("data:image/png;base64") < 4


def test_animation_html_draws_frames_for_the_slides_when_asked_with_text_large_enough():
    from jacobians.plotting import animation

    def source():
        fig, ax = plt.subplots(figsize=(8.0, 5.0), dpi=40, layout="constrained")
        ax.set_xlim(0, 1)
        ax.set_xlabel("x (m)", fontsize=10)
        ax.tick_params(labelsize=9)
        (dot,) = ax.plot([0.0], [0.0], "o")
        label = ax.text(0.1, 0.5, "t = 0", fontsize=8)   # a moving text, the smallest of all

        def draw(k):
            dot.set_data([0.3 * k], [0.0])
            label.set_text(f"t = {k}")
        return P.FrameSource(fig, draw, 3, moving=[dot, label])

    # a chapter's start_page, which other tests in this process may have run, asks for slide frames: start
    # from "not asked"
    animation.set_slide_frames(None)
    book = P.animation_html(source())
    assert book._repr_mimebundle_() == {}   # not asked: the book's player only
    animation.set_slide_frames((1280.0, 562.0), 27.0)
    try:
        both = P.animation_html(source())
        # a target the book's frames already meet asks for no second player
        animation.set_slide_frames((100.0, 50.0), 1.0)
        small = P.animation_html(source())
        with pytest.raises(ValueError):
            animation.set_slide_frames((0.0, 562.0), 27.0)
    finally:
        animation.set_slide_frames(None)
    assert small._repr_mimebundle_() == {}
    slide = both._repr_mimebundle_()[animation.SLIDE_MIME]
    frames = re.compile(r'frames\[\d+\] = "data:image/png;base64,([^"]*)"')
    assert frames.findall(both.data) == frames.findall(book.data)   # the book's player is unchanged
    import base64
    import io

    from PIL import Image

    def first_frame(html):
        data = re.search(r'frames\[0\] = "data:image/png;base64,([^"]*)"', html).group(1).replace("\\\n", "")
        return Image.open(io.BytesIO(base64.b64decode(data)))

    # the same pixels; the smallest text (the moving label, 8 pt) 27 px or more where the slide shows it
    w, h = first_frame(slide).size
    assert abs(w - 320) <= 1 and abs(h - 200) <= 1 and first_frame(book.data).size == (320, 200)
    text_px = float(re.search(r'data-smallest-text-px="([\d.]+)"', slide).group(1))
    shown = min(1280.0, 562.0 * w / h) / w
    assert text_px * shown >= 27.0
    assert float(re.search(r'data-smallest-text-px="([\d.]+)"', book.data).group(1)) * shown < 27.0
    assert slide.count("data:image/png;base64") == 3 and "https://" not in slide


def test_slide_frames_are_checked_for_overlapping_and_cut_off_text_frame_by_frame():
    """The slides' frames of an animation, drawn larger, are checked one by one: a moving text that runs
    into a fixed one in some frames, and a label cut off at the canvas edge, are named with their frames;
    a clean animation carries an empty list."""
    from jacobians.plotting import animation

    def source(crowded):
        fig, ax = plt.subplots(figsize=(6.0, 3.0), dpi=40, layout="constrained")
        ax.set(xlim=(0, 1), ylim=(0, 1))
        ax.set_xlabel("x (m)", fontsize=8)
        ax.tick_params(labelsize=8)
        ax.text(0.5, 0.5, "fixed", fontsize=8)
        label = ax.text(0.05, 0.5, "walker", fontsize=8)
        if crowded:   # a figure text past the right edge: cut off on every frame
            fig.text(0.97, 0.5, "cut off", fontsize=8)
        # the walker reaches the fixed text in the last two frames only (if crowded)
        stops = (0.05, 0.2, 0.45, 0.5) if crowded else (0.05, 0.1, 0.15, 0.2)

        def draw(k):
            label.set_x(stops[k])
        return P.FrameSource(fig, draw, 4, moving=[label])

    animation.set_slide_frames((1280.0, 562.0), 27.0)
    try:
        with pytest.warns(UserWarning, match=r"overlaps or is cut off.*'fixed' overlaps 'walker' \(frames 3-4\)"):
            crowded = P.animation_html(source(True))
        clean = P.animation_html(source(False))
    finally:
        animation.set_slide_frames(None)
    slide = crowded._repr_mimebundle_()[animation.SLIDE_MIME]
    problems = html.unescape(re.search(r'data-text-problems="([^"]*)"', slide).group(1))
    assert problems == "'cut off' is cut off at the edge (frames 1-4); 'fixed' overlaps 'walker' (frames 3-4)"
    assert re.search(r'data-text-problems=""', clean._repr_mimebundle_()[animation.SLIDE_MIME])
    # the book's player, which the slides do not show here, is not marked
    assert "data-text-problems" not in crowded.data


def test_the_text_checks_of_a_figure_see_what_it_draws():
    from jacobians.plotting.style import text_problems

    fig, ax = plt.subplots(figsize=(3.0, 2.0), dpi=100)
    ax.set_ylabel("a long y label that is cut", fontsize=30)
    assert "'a long y label that is cut' is cut off at the edge" in text_problems(fig)
    ax.set_ylabel("y", fontsize=10)
    fig.tight_layout()
    assert text_problems(fig) == []
    plt.close(fig)


def test_a_label_that_reaches_into_the_neighbouring_plot_is_named():
    from jacobians.plotting.style import text_problems

    fig = plt.figure(figsize=(4.0, 2.0), dpi=100)
    left = fig.add_axes([0.1, 0.2, 0.4, 0.7])
    right = fig.add_axes([0.55, 0.2, 0.4, 0.7])
    left.set(xticks=[], yticks=[])
    right.set(xticks=[], yticks=[])
    right.set_ylabel("a label", fontsize=14, labelpad=2)
    assert text_problems(fig) == ["'a label' reaches into plot 1"]
    right.set_ylabel("")
    twin = left.twinx()   # a twin's labels are on its own (shared) area's edge
    twin.set_yticks([])
    assert text_problems(fig) == []
    plt.close(fig)


def test_a_label_that_a_line_of_its_own_plot_runs_through_is_named():
    """A plot's curve through a label, or a marker on it, is found (a label on a box of its own is not:
    it is drawn over the lines on purpose), in a still figure and in an animation's frames."""
    from jacobians.plotting import animation
    from jacobians.plotting.style import text_problems

    fig, ax = plt.subplots(figsize=(3.0, 2.0), dpi=100)
    ax.set(xlim=(0, 10), ylim=(0, 10), xticks=[], yticks=[])
    ax.plot([0, 10], [5, 5], label="the curve")
    crossed = ax.text(5, 5, "crossed", ha="center", va="center")
    ax.plot([2], [8], "o", ms=12, label="a joint")
    on_joint = ax.text(2, 8, "{s}", ha="center", va="center")
    assert text_problems(fig) == ["'crossed' lies on 'the curve'", "'{s}' lies on 'a joint'"]
    crossed.set_bbox({"facecolor": "white", "edgecolor": "none"})   # a label on its own box: readable
    on_joint.set(x=2.6, ha="left")                                   # beside the marker
    assert text_problems(fig) == []
    plt.close(fig)

    # an animation: the label is fixed, the line moves through it in frames 2 and 3 (of 4)
    fig, ax = plt.subplots(figsize=(3.0, 2.0), dpi=100)
    ax.set(xlim=(0, 10), ylim=(0, 10), xticks=[], yticks=[])
    ax.text(5, 5, "fixed", ha="center", va="center")
    (walker,) = ax.plot([0, 10], [0, 0], label="walker")

    def draw(k):
        walker.set_ydata([[0, 5, 5, 9][k]] * 2)
        return [walker]

    source = P.FrameSource(fig, draw, 4, moving=[walker])
    texts, lines = [], []
    animation._encoded_frames(source, 16, 1e9, "frames", 2, texts=texts, lines=lines)
    assert animation.frame_text_problems(source, texts, lines) == ["'fixed' lies on 'walker' (frames 2-3)"]
    plt.close(fig)
