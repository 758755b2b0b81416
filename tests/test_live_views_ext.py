"""_ext/live_views.py: the model the {live-view} directive writes, and its errors on bad options."""

from __future__ import annotations

import html
import json
import re

import live_views
import numpy as np
import pytest

import jacobians as jac


@pytest.mark.parametrize("robot,n", [("planar_2r", 2), ("planar_3r", 3)])
def test_planar_model_is_the_library_chain(robot, n):
    chain = getattr(jac.robots, robot)()
    m = live_views.planar_model(robot, [0.3, -1.2, 2.0][:n], "body")
    assert np.array_equal(m["S"], chain.screw_axes) and np.array_equal(m["M"], chain.home)
    assert np.array_equal(m["Q"], chain.axis_points())
    assert m["theta"] == [0.3, -1.2, 2.0][:n] and m["frame"] == "body"
    assert m["reach"] == pytest.approx(float(n)) and m["sing_tol"] == pytest.approx(0.08 * n)
    assert m["vel_scale"] == 0.35
    json.dumps(m, allow_nan=False)  # plain JSON, no NaN


def test_default_theta_is_the_matplotlib_explorers():
    assert live_views.planar_model("planar_3r")["theta"] == [0.5, 1.2, -0.8]
    assert live_views.planar_model("planar_2r")["theta"] == [0.5, 1.2]


@pytest.mark.parametrize("args,message", [
    (("ur5", None, "space"), "Expected robot one of planar_2r, planar_3r, got 'ur5'"),
    (("planar_2r", None, "analytic"), "Expected frame one of space, body, geometric, got 'analytic'"),
    (("planar_2r", [0.1], "space"), "Expected theta with 2 angles (rad) for planar_2r, got 1"),
    (("planar_2r", [0.1, float("nan")], "space"), "Expected theta as finite angles within ±3.14 rad"),
    (("planar_2r", [0.1, 4.0], "space"), "Expected theta as finite angles within ±3.14 rad, got [4.0]"),
])
def test_bad_options_say_what_was_expected(args, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        live_views.planar_model(*args)


def test_angles_option():
    assert live_views._angles("0.3 1.2") == [0.3, 1.2] and live_views._angles("0.3, -1") == [0.3, -1.0]
    with pytest.raises(ValueError, match="Expected :theta: as angles in rad"):
        live_views._angles("0.3 ninety")


@pytest.mark.parametrize("depth,prefix", [(0, "./_static/live"), (1, "../_static/live"), (2, "../../_static/live")])
def test_host_html_paths_follow_the_page_depth(depth, prefix):
    model = live_views.planar_model("planar_2r", [0.0, 1.2])
    out = live_views.host_html("planar_explorer", model, depth, "jac-live-x-0")
    assert f'from "{prefix}/host.js"' in out and f'from "{prefix}/planar_explorer.js"' in out
    assert 'id="jac-live-x-0"' in out and 'getElementById("jac-live-x-0")' in out
    data = re.search(r'data-model="([^"]*)"', out)
    assert data is not None and json.loads(html.unescape(data.group(1))) == model
    assert "http" not in out  # nothing from another host
    with pytest.raises(ValueError, match=r"Expected a live view one of planar_explorer, .*got 'gimbal'"):
        live_views.host_html("gimbal", model, 0, "x")
