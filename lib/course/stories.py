"""The story animations of the course (chapters 1, 3 and 7), shown by the live view ``story``.

Each function builds one story's model: the chain, the motion θ(t) and where it is drawn (boxes in m), and
registers it under the name the ``{live-view} story`` directive's ``:story:`` gives (the name of its drawing
in ``jacobians/widgets/live/story/view.js``). Importing this module registers them; the book's extension
(``_ext/live_views.py``) does so. The machinery (the motion's formula, the widget, the view) is the library's
(:mod:`jacobians.widgets.live.story`), re-exported here for the chapters.

>>> m = story_model("fixed_axis")
>>> m["story"], len(m["S"][0]), m["frames"], m["q"]
('fixed_axis', 1, 72, [1.0, 0.6, 0.0])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from jacobians import robots
from jacobians.chain import SerialChain
from jacobians.widgets.live.story import (
    STORIES,
    StoryView,
    register_story,
    story_model,
    story_motion,
    story_theta,
    story_theta_dot,
    story_times,
    story_view_model,
)

__all__ = ["STORIES", "StoryView", "story_model", "story_theta", "story_theta_dot", "story_times",
           "fixed_axis", "body_columns", "three_velocities"]


def _planar_3r() -> SerialChain:
    return robots.planar_3r(1.0, 0.8, 0.5)


@register_story("fixed_axis")
def fixed_axis() -> dict[str, Any]:
    """Chapter 1: a body turning at 1 rad/s about the vertical axis through q."""
    q = np.array([1.0, 0.6, 0.0])
    S = np.r_[0.0, 0.0, 1.0, -np.cross([0.0, 0.0, 1.0], q)].reshape(6, 1)
    M = np.eye(4)
    M[:3, 3] = [1.8, 0.2, 0.0]  # where {b} starts
    chain = SerialChain(S, M, name="a body turning about a fixed axis", joint_points=q.reshape(1, 3))
    return story_view_model("fixed_axis", chain, story_motion([0.0], [1.0], [[]], 2 * np.pi, 72, True, 1.0),
                            q=q.tolist(), theta_dot=[1.0], box=[-0.9, 2.4, -1.4, 2.1], axis_len=0.35)


@register_story("body_columns")
def body_columns() -> dict[str, Any]:
    """Chapter 3: the planar 3R arm along a closed path; the columns of J_b in {s} (left) and in {b} (right)."""
    motion = story_motion([0.5, 0.9, -1.0], [0.0, 0.0, 0.0],
                          [[[0.6, 1.0, 0.0]], [[0.5, 2.0, 0.4]], [[0.8, 1.0, np.pi / 2]]], 2 * np.pi, 64, True, 0.8)
    return story_view_model("body_columns", _planar_3r(), motion, scale=0.6, axis_len=0.4,
                            box=[-1.4, 2.7, -1.0, 2.7], box_right=[-1.9, 1.1, -0.3, 2.5])


@register_story("three_velocities")
def three_velocities() -> dict[str, Any]:
    """Chapter 7: constant joint rates; ṗ at the tool, v_s at the origin of {s}, and the numbers."""
    theta_dot = [0.5, -0.4, 0.9]
    motion = story_motion([0.2, 0.9, -0.6], theta_dot, [[], [], []], 2 * np.pi / 0.9, 70, False, 1.0)
    return story_view_model("three_velocities", _planar_3r(), motion, theta_dot=theta_dot, vel_scale=1.0,
                            axis_len=0.4, box=[-1.6, 2.4, -1.2, 2.6])
