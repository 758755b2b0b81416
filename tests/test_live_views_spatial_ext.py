"""The models of the 3-D live views (jacobians.widgets.live_spatial), and the directive's errors on bad options."""

from __future__ import annotations

import html
import json
import math
import re

import live_views
import numpy as np
import pytest

import jacobians as jac
from jacobians.plotting.style import PALETTE
from jacobians.testing import random_chain
from jacobians.widgets import live_spatial as spatial
from jacobians.widgets.live_spatial import VIEW_MARGIN, reach_bounds

SPATIAL_VIEWS = ("columns_explorer", "gimbal_lock")


def test_columns_model_is_the_library_chain():
    chain = jac.robots.spatial_5r()
    m = spatial.columns_model(theta=[0.1, 0.2, 0.3, 0.4, 0.5], column=2)
    assert np.array_equal(m["S"], chain.screw_axes) and np.array_equal(m["M"], chain.home)
    assert np.array_equal(m["Q"], chain.axis_points())
    assert m["theta"] == [0.1, 0.2, 0.3, 0.4, 0.5] and m["column"] == 2
    assert m["palette"]["space"] == PALETTE["space"] and m["palette"]["body"] == PALETTE["body"]
    # the view's sphere (less the keys' dot) holds the arm, its axes' keys and {b}'s arrows at every pose: random
    # poses, and the stretched ones (every joint at 0 or pi), where a bound is reached if anywhere
    rng = np.random.default_rng(1)
    corners = np.array(np.meshgrid(*[[0.0, np.pi]] * 5)).reshape(5, -1).T
    poses = np.vstack([corners, rng.uniform(-np.pi, np.pi, (4000, 5))])
    P = chain.joint_positions(poses)
    w = np.stack([jac.space_jacobian(chain, th)[:3].T for th in poses])  # each joint's axis direction at the pose
    tips = P[:, :-1] + 1.25 * m["axis_length"] * w
    inside = (1 - VIEW_MARGIN) * m["extent"]
    assert np.linalg.norm(np.concatenate([P, tips], axis=1) - m["center"], axis=-1).max() <= inside
    json.dumps(m, allow_nan=False)


def test_reach_bounds_hold_on_random_arms():
    """A counterexample search for the bound of reach_bounds: random revolute arms at random poses, and the bound
    is reached (within rounding) by the arm stretched away from the fixed point it turns about."""
    rng = np.random.default_rng(7)
    worst = 0.0
    for _ in range(60):
        chain = random_chain(rng, prismatic_probability=0.0, pitch_probability=0.0)
        c, B = reach_bounds(chain)
        P = chain.joint_positions(rng.uniform(-np.pi, np.pi, (400, chain.dof)))
        r = np.linalg.norm(P - c, axis=-1)
        # rounding: distances of a few metres computed through n products of rotations, 1e-12 m is far above it
        assert (r <= B + 1e-12).all(), (chain.name, (r - B).max())
        moving = B > 0  # the fixed points stay at their bound
        worst = max(worst, float((r[:, moving] / B[moving]).max()))
    assert worst > 0.9  # the bound is not loose for nothing: some sampled pose comes near it
    with pytest.raises(ValueError, match="revolute joints with no pitch"):
        reach_bounds(jac.robots.scara())


def test_gimbal_model_holds_both_wrists():
    m = spatial.gimbal_model("zyx_wrist", [0.1, 1.5, -0.2], "zyz")
    assert m["wrist"] == "zyx_wrist" and m["rep"] == "zyz" and m["theta"] == [0.1, 1.5, -0.2]
    for key, make in (("zyz_wrist", jac.robots.zyz_wrist), ("zyx_wrist", jac.robots.zyx_wrist)):
        chain = make(spatial.WRIST_TOOL)
        assert np.array_equal(m["wrists"][key]["S"], chain.screw_axes)
        assert np.array_equal(m["wrists"][key]["M"], chain.home) and m["wrists"][key]["name"] == chain.name
    assert spatial.gimbal_model()["theta"] == pytest.approx([math.radians(30.0), math.radians(60.0), 0.0])
    json.dumps(m, allow_nan=False)


@pytest.mark.parametrize("call,message", [
    (lambda: spatial.columns_model("ur5"), "Expected robot one of spatial_5r, got 'ur5'"),
    (lambda: spatial.columns_model(theta=[0.1]), "Expected theta with 5 angles (rad) for spatial_5r, got 1"),
    (lambda: spatial.columns_model(theta=[0, 0, 0, 0, 4.0]), "Expected theta as finite angles within ±3.14 rad"),
    (lambda: spatial.columns_model(column=6), "Expected column as an integer from 1 to 5, got 6"),
    (lambda: spatial.gimbal_model("puma"), "Expected robot one of zyz_wrist, zyx_wrist, got 'puma'"),
    (lambda: spatial.gimbal_model(rep="exp"), "Expected rep one of zyx, zyz, got 'exp'"),
    (lambda: spatial.gimbal_model(theta=[0.0, float("nan"), 0.0]), "Expected theta as finite angles"),
    (lambda: live_views.model_for("columns_explorer", {"column": "three"}), "Expected a whole number, got 'three'"),
    (lambda: live_views.model_for("columns_explorer", {"rep": "zyx"}), "Expected options robot, theta, column"),
    (lambda: live_views.model_for("gimbal_lock", {"column": "1"}), "Expected options robot, theta, rep"),
    (lambda: live_views.model_for("planar", {}), "Expected a live view one of columns_explorer, gimbal_lock"),
])
def test_bad_options_say_what_was_expected(call, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        call()


@pytest.mark.parametrize("view", SPATIAL_VIEWS)
def test_host_html_loads_the_view_module(view):
    model = live_views.model_for(view, {"theta": "0.1 0.2 0.3" if view == "gimbal_lock" else "0 0 0 0 0"})
    out = live_views.host_html(view, model, 1, "jac-live-x-0")
    assert f'from "../_static/live/{view}/view.js"' in out and "http" not in out
    data = re.search(r'data-model="([^"]*)"', out)
    assert data is not None and json.loads(html.unescape(data.group(1))) == model


def test_the_directive_takes_the_models_from_the_library():
    from jacobians.widgets.live import VIEWS

    assert VIEWS["columns_explorer"].model is spatial.columns_model and VIEWS["gimbal_lock"].model is spatial.gimbal_model
    assert live_views.model_for("columns_explorer", {"theta": "0.1 0.2 0.3 0.4 0.5", "column": "2"}) == \
        spatial.columns_model("spatial_5r", [0.1, 0.2, 0.3, 0.4, 0.5], 2)


def test_columns_widget_state_and_library_values():
    from jacobians.widgets.live import module_source
    from jacobians.widgets.live_spatial import ColumnsExplorer

    chain = jac.robots.spatial_5r()
    w = ColumnsExplorer(theta=[0.1, 0.2, 0.3, 0.4, 0.5], column=2)
    assert w.view == "columns_explorer" and w._esm == module_source("columns_explorer")
    assert w.column == 2 and w.S == chain.screw_axes.tolist()
    w.theta = [-0.3, 1.0, 0.2, -0.7, 2.0]  # as the view writes it back
    assert np.allclose(w.Js, jac.space_jacobian(chain, w.theta), atol=1e-15)
    assert np.allclose(w.Jb, jac.body_jacobian(chain, w.theta), atol=1e-15)
    assert np.array_equal(w.J, w.Js)
    with pytest.raises(ValueError, match=re.escape("Expected column as an integer from 1 to 5, got 0")):
        ColumnsExplorer(column=0)
    with pytest.raises(TypeError, match="Expected theta as 5 numbers"):
        ColumnsExplorer(theta=["a", "b", "c", "d", "e"])


def test_gimbal_widget_state_and_library_values():
    from jacobians import representations as reps
    from jacobians.widgets.live_spatial import GimbalLock

    g = GimbalLock("zyz_wrist", theta=[0.2, 1.2, -0.4], rep="zyz")
    chain = jac.robots.zyz_wrist(spatial.WRIST_TOOL)
    assert np.allclose(g.J, jac.geometric_jacobian(chain, [0.2, 1.2, -0.4]), atol=1e-15)
    assert np.allclose(g.phi, [0.2, 1.2, -0.4], atol=1e-12)  # ZYZ angles of the ZYZ wrist are its joint angles
    assert np.allclose(g.B, reps.rate_to_angular_velocity(g.phi, "zyz"))
    assert g.det_B == pytest.approx(-math.sin(1.2))
    assert np.allclose(g.Ja, jac.analytic_jacobian(chain, [0.2, 1.2, -0.4], "zyz"))
    g.wrist, g.rep, g.theta = "zyx_wrist", "zyx", [0.3, math.pi / 2, 0.0]  # the ZYX wrist at its lock
    assert g.chain.name == jac.robots.zyx_wrist(spatial.WRIST_TOOL).name
    assert np.isnan(g.Ja).all() and abs(g.det_B) < 1e-12
    assert np.allclose(g.J, jac.geometric_jacobian(jac.robots.zyx_wrist(spatial.WRIST_TOOL), g.theta))
