"""course.stories: the story models (chapters 1, 3, 7) on jacobians.widgets.live.story: their motion θ(t), and StoryView."""

from __future__ import annotations

import json

import numpy as np
import pytest

import jacobians as jac
from course.stories import STORIES, StoryView, story_model, story_theta, story_theta_dot, story_times
from jacobians.testing import close, fd_tol, within
from jacobians.widgets.live import MODELS


@pytest.mark.parametrize("story", STORIES)
def test_model_is_plain_json_and_its_chain_the_librarys(story):
    m = story_model(story)
    json.dumps(m, allow_nan=False)
    assert MODELS["story"] is story_model
    chain = jac.SerialChain(np.array(m["S"]), np.array(m["M"]), joint_points=np.array(m["Q"]))
    if story != "fixed_axis":
        ref = jac.robots.planar_3r(1.0, 0.8, 0.5)
        assert np.array_equal(chain.screw_axes, ref.screw_axes) and np.array_equal(chain.home, ref.home)
    else:  # one revolute joint about z through q: S = (z, -z x q)
        assert close(chain.screw_axes[:, 0], np.r_[0, 0, 1, -np.cross([0, 0, 1], m["q"])])
    t = story_times(m)
    assert len(t) == m["frames"] and t[0] == 0.0
    assert close(t[-1], m["t_end"] * (1 - 1 / m["frames"]) if m["closed"] else m["t_end"])   # a few roundings


@pytest.mark.parametrize("story", STORIES)
def test_theta_dot_is_the_derivative_of_theta(story):
    m = story_model(story)
    h = 1e-6
    for t in np.linspace(-1.0, m["t_end"] + 1.0, 17):
        fd = (story_theta(m, t + h) - story_theta(m, t - h)) / (2 * h)
        # central difference: truncation h²/6·max|θ'''| + rounding (fd_tol, constants from θ(t) itself)
        assert within(story_theta_dot(m, t), fd, fd_tol(lambda s, m=m: story_theta(m, s[0]), np.array([t]), h))
    assert story_theta(m, story_times(m)).shape == (m["frames"], len(m["offset"]))


def test_body_columns_is_the_old_closed_path_and_fixed_axis_turns_once():
    m = story_model("body_columns")
    tt = np.linspace(0, 2 * np.pi, 32, endpoint=False)
    old = np.stack([0.5 + 0.6 * np.sin(tt), 0.9 + 0.5 * np.sin(2 * tt + 0.4), -1.0 + 0.8 * np.cos(tt)], axis=1)
    assert close(story_theta(m, tt), old)                                # the same sums of sines: TOL
    # closed: sin(2t + 0.4) at t = 2π has an argument of size 4π + 0.4, rounded relative to that (close's scale)
    assert close(story_theta(m, m["t_end"]), story_theta(m, 0.0), scale=4 * np.pi + 0.4)
    f = story_model("fixed_axis")
    assert close(story_theta(f, f["t_end"])[0], 2 * np.pi)
    v = story_model("three_velocities")
    assert close(story_theta_dot(v, 1.3), v["theta_dot"])  # constant joint rates


def test_bad_story():
    with pytest.raises(ValueError, match="Expected story one of"):
        story_model("spin")


def test_story_view_widget_frame_and_theta():
    w = StoryView("body_columns")
    m = story_model("body_columns")
    assert w.frame == 0 and w.view == "story" and w.t == 0.0
    w.frame = 10
    assert w.t == story_times(m)[10]
    assert close(w.theta, story_theta(m, story_times(m)[10]))
    assert close(w.chain.fk(w.theta), jac.robots.planar_3r(1.0, 0.8, 0.5).fk(w.theta))


def test_the_library_holds_no_story_and_its_drawings_are_the_views():
    """The stories are the course's: the library registers none; each names a drawing of story/view.js."""
    import re
    from pathlib import Path

    from jacobians.widgets.live.story import DRAWINGS, register_story

    assert {build.__module__ for build in STORIES.values()} == {"course.stories"}  # every story is the course's
    assert sorted(STORIES) == sorted(DRAWINGS)
    view = (Path(__file__).resolve().parents[1] / "lib/jacobians/widgets/live/story/view.js").read_text(encoding="utf-8")
    table = re.search(r"export const DRAWINGS = \{([^}]*)\}", view)
    assert table is not None
    assert sorted(re.findall(r"(\w+):", table.group(1))) == sorted(DRAWINGS)
    with pytest.raises(ValueError, match="Expected a story drawn by story/view.js"):
        register_story("spin")
