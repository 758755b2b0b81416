"""Tests of jacobians.widgets: drive each widget programmatically and compare what it shows with the library."""

import os
import re

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

import jacobians as jac
from jacobians import widgets as Wd
from jacobians.lie import adjoint, exp_se3
from jacobians.representations import angular_velocity_to_rate


def parse_bmatrix(tex):
    """Numbers of the first bmatrix in a LaTeX string (NaN for 'undef.')."""
    body = re.search(r"\\begin\{bmatrix\}(.*?)\\end\{bmatrix\}", tex).group(1)
    rows = []
    body = re.sub(r"\\color\{[^}]*\}", "", body)
    for r in body.split(r"\\"):
        rows.append([np.nan if "undef" in c else float(re.sub(r"[^0-9eE.+-]", "", c)) for c in r.split("&")])
    return np.array(rows)


# ---------------------------------------------------------------- the formulas the explorer displays

@pytest.mark.parametrize("chain", [jac.robots.planar_3r(1.0, 0.7, 0.4), jac.robots.ur5()], ids=["3R", "UR5"])
def test_displayed_formulas_hold(chain):
    rng = np.random.default_rng(3)
    th = rng.uniform(-np.pi, np.pi, chain.dof)
    S, B = chain.screw_axes, chain.body_axes
    n = chain.dof
    # space: column i = Ad(e^[S1]th1 ... e^[S_{i-1}]th_{i-1}) S_i
    J_s = jac.space_jacobian(chain, th)
    T = np.eye(4)
    for i in range(n):
        np.testing.assert_allclose(J_s[:, i], adjoint(T) @ S[:, i], atol=1e-10)
        T = T @ exp_se3(S[:, i] * th[i])
    # body: column i = Ad(e^-[Bn]thn ... e^-[B_{i+1}]th_{i+1}) B_i
    J_b = jac.body_jacobian(chain, th)
    T = np.eye(4)
    for i in reversed(range(n)):
        np.testing.assert_allclose(J_b[:, i], adjoint(T) @ B[:, i], atol=1e-10)
        T = T @ exp_se3(-B[:, i] * th[i])
    # geometric = diag(R, R) J_b
    R = chain.fk(th)[:3, :3]
    np.testing.assert_allclose(jac.geometric_jacobian(chain, th), np.block([[R, 0 * R], [0 * R, R]]) @ J_b,
                               atol=1e-10)
    # analytic = diag(B(phi)^-1, I) J, and it is d(phi, p)/d theta (finite differences)
    phi = jac.pose_coordinates(chain.fk(th), "zyx")[:3]
    J = jac.geometric_jacobian(chain, th)
    J_a = jac.analytic_jacobian(chain, th, "zyx")
    np.testing.assert_allclose(J_a[:3], angular_velocity_to_rate(phi, "zyx") @ J[:3], atol=1e-9)
    num = jac.numerical_jacobian(lambda q: jac.pose_coordinates(chain.fk(q), "zyx"), th)
    np.testing.assert_allclose(J_a, num, atol=1e-6)


def test_drawn_ellipses_are_the_library_ellipses():
    """The outlines drawn are the images of |qdot| = 1 and the forces with |J_v^T f| = 1 (library axes)."""
    w = Wd.planar_arm_explorer(jac.robots.planar_3r(1.0, 0.8, 0.5), theta=[0.3, 0.8, -0.6])
    J_v = jac.geometric_jacobian(w.chain, w.theta)[3:5]
    tip = w.chain.fk(w.theta)[:2, 3]
    axes_v, U = jac.analysis.velocity_ellipsoid(J_v)
    axes_f, _ = jac.analysis.force_ellipsoid(J_v)
    np.testing.assert_allclose(w.sigma, axes_v, atol=1e-12)
    np.testing.assert_allclose(w.force_semi_axes, 1.0 / np.linalg.svd(J_v, compute_uv=False), rtol=1e-12)
    np.testing.assert_allclose(w.force_semi_axes, axes_f, rtol=1e-12)
    assert w.force_state is None and not w.force_clipped.any()
    # velocity outline: points U diag(s) u with |u| = 1 are images J_v qdot with |qdot| = 1
    pts = (w.vel_ellipse.line.get_xydata() - tip) / w.vel_scale
    qdot = np.linalg.pinv(J_v) @ pts.T
    np.testing.assert_allclose(np.linalg.norm(qdot, axis=0), 1.0, atol=1e-9)
    # force outline: every drawn point f has |J_v^T f| = 1 (unit joint torque)
    f = (w.force_ellipse.line.get_xydata() - tip) / w.force_scale
    np.testing.assert_allclose(np.linalg.norm(J_v.T @ f.T, axis=0), 1.0, atol=1e-9)
    assert w.force_ellipse.line.get_linestyle() == "--" and not w.force_clip_line.get_visible()


def test_force_ellipse_clipped_and_marked_near_and_at_a_singularity():
    w = Wd.planar_arm_explorer(jac.robots.planar_2r(1.0, 1.0))
    legend = lambda: [t.get_text() for t in w.legend.get_texts()]
    # at the singularity the library reports an infinite semi-axis along the arm
    w.set(theta=[0.3, 0.0])
    J_v = jac.geometric_jacobian(w.chain, w.theta)[3:5]
    axes_f, U = jac.analysis.force_ellipsoid(J_v)
    assert np.isinf(axes_f[1]) and np.isinf(w.force_semi_axes[1]) and np.isfinite(w.force_semi_axes[0])
    np.testing.assert_allclose(np.abs(U[:, 1]), [np.cos(0.3), np.sin(0.3)], atol=1e-12)  # along the links
    assert w.force_state == "inf" and list(w.force_clipped) == [False, True]
    np.testing.assert_allclose(w.force_drawn_semi_axes, [w.force_scale * axes_f[0], w.force_clip], rtol=1e-12)
    assert w.force_clip == pytest.approx(1.25 * w.reach)
    xy = w.force_ellipse.line.get_xydata()
    assert np.all(np.isfinite(xy))
    tip = w.chain.fk(w.theta)[:2, 3]
    along = (xy - tip) @ U[:, 1]
    assert along.max() == pytest.approx(w.force_clip, rel=1e-3)  # drawn to the clip length, no further
    assert w.force_ellipse.line.get_linestyle() == ":"
    line = w.force_clip_line.get_xydata()
    assert w.force_clip_line.get_visible()
    np.testing.assert_allclose(line[:2], [tip - w.force_clip * U[:, 1], tip + w.force_clip * U[:, 1]], atol=1e-12)
    assert any(r"\infty" in t and "clipped" in t for t in legend())
    assert any("force ellipse" in t and "clipped" in t for t in legend())
    # near it: finite, but longer than the view: clipped, marked, not called infinite
    w.set(theta=[0.3, 0.05])
    assert w.force_state == "clipped" and np.all(np.isfinite(w.force_semi_axes))
    assert w.force_semi_axes[1] * w.force_scale > w.force_clip
    assert w.force_drawn_semi_axes[1] == w.force_clip and w.force_clip_line.get_visible()
    assert not any(r"\infty" in t for t in legend()) and any("longer than drawn" in t for t in legend())
    # away from it: the plain dashed ellipse and legend again
    w.set(theta=[0.3, 1.5])
    assert w.force_state is None and not w.force_clip_line.get_visible()
    assert w.force_ellipse.line.get_linestyle() == "--"
    assert not any("clipped" in t for t in legend())
    np.testing.assert_allclose(w.force_drawn_semi_axes, w.force_scale * w.force_semi_axes, rtol=1e-12)
    # ellipses hidden: no clip mark drawn or listed
    w.set(theta=[0.3, 0.0])
    w.ellipse_checkbox.value = False
    assert not w.force_clip_line.get_visible() and not any(r"\infty" in t for t in legend())


# ---------------------------------------------------------------- 1. explorer

@pytest.fixture(scope="module")
def explorer3():
    return Wd.planar_arm_explorer(jac.robots.planar_3r(1.0, 0.8, 0.5))


@pytest.mark.parametrize("frame", ["space", "body", "geometric", "analytic"])
def test_explorer_shows_library_jacobian(explorer3, frame):
    w = explorer3
    arm = w.chain
    th, rates = np.array([0.4, -0.9, 1.3]), np.array([0.5, -1.0, 0.25])
    before = w.render_count
    w.set(theta=th, rates=rates, frame=frame)
    assert w.render_count == before + 1  # one redraw for three changes
    ref = {"space": jac.space_jacobian, "body": jac.body_jacobian, "geometric": jac.geometric_jacobian,
           "analytic": lambda c, t: jac.analytic_jacobian(c, t, "zyx")}[frame](arm, th)
    np.testing.assert_allclose(w.jacobian, ref, atol=1e-12)
    np.testing.assert_allclose(parse_bmatrix(w.matrix_latex), ref.round(3), atol=1.1e-3)
    assert parse_bmatrix(w.matrix_latex).shape == (6, 3)
    np.testing.assert_allclose(w.twist, ref @ rates, atol=1e-12)
    assert "$$" in w.matrix_html.value and Wd.JACOBIAN_SYMBOLS[frame] in w.matrix_html.value
    # drawn arm and tool-velocity arrow
    np.testing.assert_allclose(w.arm.link_line.get_xydata(), arm.joint_positions(th)[:, :2], atol=1e-12)
    pdot = (jac.geometric_jacobian(arm, th) @ rates)[3:5]
    np.testing.assert_allclose(w.pdot_arrow.vectors[0], pdot * w.vel_scale, atol=1e-12)
    np.testing.assert_allclose(w.pdot_arrow.points[0], arm.fk(th)[:2, 3], atol=1e-12)
    if frame == "space":
        V_s = jac.space_jacobian(arm, th) @ rates
        np.testing.assert_allclose(w.vs_arrow.vectors[0], V_s[3:5] * w.vel_scale, atol=1e-12)
    assert w.png[:8] == b"\x89PNG\r\n\x1a\n" and w.image.value == w.png


def test_explorer_slider_drives_redraw_and_ellipse(explorer3):
    w = explorer3
    w.set(theta=[0.2, 0.5, 0.5], rates=[1, 1, 1], frame="geometric")
    png0 = w.png
    w.angle_sliders[1].value = -0.7
    th = w.theta
    assert th[1] == pytest.approx(-0.7)
    np.testing.assert_allclose(w.arm.link_line.get_xydata(), w.chain.joint_positions(th)[:, :2], atol=1e-12)
    assert w.png != png0
    J_v = jac.geometric_jacobian(w.chain, th)[3:5]
    sig = np.linalg.svd(J_v, compute_uv=False)
    np.testing.assert_allclose(w.sigma, sig, atol=1e-12)
    xy = w.vel_ellipse.line.get_xydata()
    U = np.linalg.svd(J_v)[0]
    u = (U.T @ (xy - w.chain.fk(th)[:2, 3]).T) / (sig * w.vel_scale)[:, None]
    np.testing.assert_allclose(np.linalg.norm(u, axis=0), 1.0, atol=1e-9)  # on the ellipse U diag(s) u, |u| = 1
    np.testing.assert_allclose(np.abs(u).max(axis=1), 1.0, atol=1e-3)  # reaches both semi-axes (90 samples)


def test_explorer_singular_and_extreme_values_do_not_raise():
    w = Wd.planar_arm_explorer(jac.robots.planar_2r(1.0, 1.0))
    w.set(theta=[0.3, 0.0], rates=[2.0, -2.0])
    assert w.sigma_min < 1e-12 and w.level == "bad"
    assert "SINGULAR" in w.status.value
    assert np.all(np.isfinite(w.force_ellipse.line.get_xydata()))
    w.set(theta=[np.pi, -np.pi], frame="analytic")
    assert np.all(np.isfinite(w.jacobian))  # planar arm: ZYX pitch stays 0
    w.set(theta=[0.3, 0.05])
    assert w.level == "warn"
    w.set(theta=[0.3, 1.5])
    assert w.level == "ok"
    assert w.arm.link_line.get_color() == Wd.PALETTE["link"]
    with pytest.raises(ValueError, match="Expected frame 'space', 'body', 'geometric' or 'analytic', got 'spatial'"):
        w.set(frame="spatial")


def test_explorer_takes_the_frame_shown():
    w = Wd.planar_arm_explorer(jac.robots.planar_2r(1.0, 1.0), frame="body")
    assert w.frame == "body"
    np.testing.assert_allclose(w.jacobian, jac.body_jacobian(w.chain, w.theta), atol=1e-12)
    w.set(frame="geometric")
    assert w.frame == "geometric"
    np.testing.assert_allclose(w.jacobian, jac.geometric_jacobian(w.chain, w.theta), atol=1e-12)
    with pytest.raises(ValueError, match="got 'spatial'"):
        Wd.planar_arm_explorer(frame="spatial")
    # the former parameter name "kind" (and the property of that name) are gone
    former = {"kind": "body"}
    with pytest.raises(TypeError, match="kind"):
        Wd.planar_arm_explorer(**former)
    with pytest.raises(TypeError, match="kind"):
        w.set(**former)
    with pytest.raises(TypeError, match="kind"):
        Wd.planar_arm_explorer_animation(frames=2, dpi=30, **former)
    assert w.frame == "geometric" and not hasattr(w, "kind")


def test_explorer_play_sweeps_the_chosen_joint():
    w = Wd.planar_arm_explorer()
    w.sweep_dropdown.value = 0
    w.play.value = w.play.max // 2
    assert w.theta[0] == pytest.approx(0.0, abs=0.01)
    w.play.value = w.play.max
    assert w.theta[0] == pytest.approx(np.pi, abs=0.01)


def test_non_planar_chains_are_refused():
    with pytest.raises(ValueError, match="planar"):
        Wd.planar_arm_explorer(jac.robots.ur5())
    with pytest.raises(ValueError, match="planar"):
        Wd.resolved_rate_explorer(jac.robots.spatial_5r())
    with pytest.raises(TypeError, match="SerialChain"):
        Wd.planar_arm_explorer("2R")
    with pytest.raises(ValueError, match=r"\(\.\.\., 2\)"):
        Wd.planar_arm_explorer(theta=[1, 2, 3])


# ---------------------------------------------------------------- 4. resolved rate

def test_resolved_rate_tracks_a_circle_and_rates_match_pinv():
    w = Wd.resolved_rate_explorer(path="circle", method="pinv")
    err = np.linalg.norm(w.x_des - w.x_act, axis=1).max()
    assert err < 0.02 * w.reach  # Euler steps of 25 ms with feedback
    k = 40
    w.set(step=k)
    th = w.thetas[k]
    np.testing.assert_allclose(w.arm.link_line.get_xydata(), w.chain.joint_positions(th)[:, :2], atol=1e-12)
    J_v = jac.geometric_jacobian(w.chain, th)[3:5]
    dt = w.t[1] - w.t[0]
    np.testing.assert_allclose(w.thetas[k + 1], th + dt * w.rates_hist[k], atol=1e-12)
    xdot = np.linalg.lstsq(J_v, J_v @ w.rates_hist[k], rcond=None)[0]
    np.testing.assert_allclose(w.rates_hist[k], xdot, atol=1e-9)  # minimum-norm solution
    # the commanded tool velocity: the path's velocity plus feedback K (x_d - x), K = 2/s
    cmd = w.v_des[k] + 2.0 * (w.x_des[k] - w.chain.fk(th)[:2, 3])
    np.testing.assert_allclose(w.rates_hist[k], jac.velocity.pinv_rates(J_v, cmd), atol=1e-12)
    np.testing.assert_allclose(J_v @ w.rates_hist[k], cmd, atol=1e-9)  # away from singularities: exact
    xs, ys = w.rate_lines[0].get_data()
    np.testing.assert_allclose(ys, w.rates_hist[:, 0])
    assert w.tracking_error == pytest.approx(np.linalg.norm(w.x_des[k] - w.x_act[k]), abs=1e-15)


@pytest.mark.parametrize("method", ["pinv", "dls"])
def test_resolved_rate_run_is_the_library_run(method):
    w = Wd.resolved_rate_explorer(path="close past the base", method=method, damping=0.1)
    assert isinstance(w.result, jac.velocity.ResolvedRateResult)
    dt = w.t[1] - w.t[0]
    ref = jac.velocity.resolved_rate(w.chain, w.thetas[0], w.x_des, dt, method=method, damping=0.1, gain=2.0,
                                     target_velocities=w.v_des)
    for got, want in zip(w.result, ref, strict=True):
        np.testing.assert_allclose(got, want, atol=1e-12)
    np.testing.assert_allclose(w.errors, np.linalg.norm(w.x_des - w.x_act, axis=1), atol=1e-15)
    np.testing.assert_allclose(w.sigma_hist, np.linalg.svd(
        jac.geometric_jacobian(w.chain, w.thetas)[:, 3:5], compute_uv=False)[:, -1], atol=1e-12)
    # the start is on the path (solved with damped steps), elbow up
    np.testing.assert_allclose(w.x_act[0], w.x_des[0], atol=1e-9)
    assert w.thetas[0, 1] > 0
    # a step of DLS: the library's dls_rates of the commanded velocity
    k = 70
    J_v = jac.geometric_jacobian(w.chain, w.thetas[k])[3:5]
    cmd = w.v_des[k] + 2.0 * (w.x_des[k] - w.x_act[k])
    want = (jac.velocity.dls_rates(J_v, cmd, 0.1) if method == "dls" else jac.velocity.pinv_rates(J_v, cmd))
    np.testing.assert_allclose(w.rates_hist[k], want, atol=1e-12)
    if method == "dls":
        assert np.linalg.norm(w.rates_hist[k]) <= np.linalg.norm(cmd) / (2 * 0.1) + 1e-12
    # the path: a straight line 3 % of the reach from the base, from +0.6 to -0.6 reach, in 4 s
    np.testing.assert_allclose(w.x_des[[0, -1]], [[0.6 * w.reach, 0.03 * w.reach], [-0.6 * w.reach, 0.03 * w.reach]])
    assert w.t[-1] == pytest.approx(4.0)
    assert not hasattr(Wd, "resolved_rate") and not hasattr(Wd, "velocity_force_ellipses")


def test_resolved_rate_singularity_pinv_blows_up_dls_stays_bounded():
    w = Wd.resolved_rate_explorer(path="to full reach", method="pinv")
    peak_pinv = w.peak_rate
    assert w.sigma_hist[-1] < 0.05 * w.reach
    w.set(method="dls", damping=0.1)
    peak_dls = w.peak_rate
    assert peak_dls < peak_pinv / 2
    err_dls = np.linalg.norm(w.x_des[-1] - w.x_act[-1])
    assert err_dls > 1e-3  # the price: it does not reach the boundary point
    w.set(path="close past the base", method="pinv", step=10_000)
    assert w.step == w.n_steps - 1 and np.all(np.isfinite(w.rates_hist))
    assert w.play.value == w.step  # the linked Play shows the same step
    peak_pinv = w.peak_rate  # joint 1 must swing half a turn while the tool passes the base
    w.set(method="dls", damping=0.1)
    assert w.peak_rate < peak_pinv / 3
    assert np.linalg.norm(w.x_des - w.x_act, axis=1).max() > 0.05 * w.reach  # DLS cuts the corner
    with pytest.raises(ValueError, match="method"):
        w.set(method="jacobian transpose")


# ---------------------------------------------------------------- static counterparts

@pytest.mark.parametrize("make", [
    lambda: Wd.planar_arm_explorer_animation(frames=3, dpi=40),
    lambda: Wd.resolved_rate_animation(frames=3, dpi=40),
], ids=["explorer", "resolved_rate"])
def test_static_animations_embed_without_cdn(make):
    from jacobians.plotting import animation_html

    anim = make()
    n_frames = anim.n_frames
    assert anim.explorer.fig is anim.fig and len(anim.path) == n_frames
    html = animation_html(anim).data
    assert "http://" not in html and "https://" not in html
    assert html.count("data:image/png;base64") >= 3
    assert html.count("data:image/png;base64") == n_frames


def test_static_explorer_animation_panel_shows_jacobian():
    anim = Wd.planar_arm_explorer_animation(frame="body", frames=4, dpi=40, sweep=1)
    w = anim.explorer
    anim.draw(2)
    np.testing.assert_allclose(w.matrix_artist.values, jac.body_jacobian(w.chain, w.theta), atol=1e-12)
    assert w.theta[0] == pytest.approx(np.linspace(-np.pi, np.pi, 4)[2])
    np.testing.assert_allclose(anim.path[2], w.theta, atol=1e-12)
    with pytest.raises(ValueError, match="sweep"):
        Wd.planar_arm_explorer_animation(sweep=3)
    assert Wd.planar_arm_explorer_animation(frame="geometric", frames=2, dpi=30).explorer.frame == "geometric"
