r"""``story`` (chapters 1, 3 and 7): the animations that tell a story, as a live view with a Play button and a
time slider.

The model holds the chain and the motion θ(t) as a formula: θ_i(t) = offset_i + rate_i t + Σ amp sin(freq t +
phase) over the waves of joint i, on ``frames`` instants t_k = t_end k / frames (``closed``: the motion is
periodic, the last instant is t_end (frames - 1)/frames) or t_end k / (frames - 1) (open).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .... import robots
from ....chain import SerialChain
from .._base import LiveView, ViewSpec, chain_model, text

__all__ = ["StoryView", "story_model", "story_times", "story_theta", "story_theta_dot", "STORIES", "SPEC"]

STORIES = ("fixed_axis", "body_columns", "three_velocities")


def _story_motion(offset: Sequence[float], rate: Sequence[float], waves: Sequence[Sequence[Sequence[float]]],
                  t_end: float, frames: int, closed: bool, speed: float) -> dict[str, Any]:
    return {"offset": [float(x) for x in offset], "rate": [float(x) for x in rate],
            "waves": [[[float(v) for v in w] for w in ws] for ws in waves], "t_end": float(t_end),
            "frames": int(frames), "closed": bool(closed), "speed": float(speed), "frame": 0}


def story_model(story: str = "three_velocities") -> dict[str, Any]:
    """The model of ``story``: the chain, the motion θ(t), what is drawn and where (boxes in m).

    >>> m = story_model("fixed_axis")
    >>> m["story"], len(m["S"][0]), m["frames"], m["q"]
    ('fixed_axis', 1, 72, [1.0, 0.6, 0.0])
    """
    if story not in STORIES:
        raise ValueError(f"Expected story one of {', '.join(STORIES)}, got {story!r}")
    if story == "fixed_axis":  # ch01: a body turning at 1 rad/s about the vertical axis through q
        q = np.array([1.0, 0.6, 0.0])
        S = np.r_[0.0, 0.0, 1.0, -np.cross([0.0, 0.0, 1.0], q)].reshape(6, 1)
        M = np.eye(4)
        M[:3, 3] = [1.8, 0.2, 0.0]  # where {b} starts
        chain = SerialChain(S, M, name="a body turning about a fixed axis", joint_points=q.reshape(1, 3))
        return {**chain_model(chain), "story": story, "q": q.tolist(), "theta_dot": [1.0],
                "box": [-0.9, 2.4, -1.4, 2.1], "axis_len": 0.35,
                **_story_motion([0.0], [1.0], [[]], 2 * np.pi, 72, True, 1.0)}
    chain = robots.planar_3r(1.0, 0.8, 0.5)
    if story == "body_columns":  # ch03: a closed path; the columns of J_b in {s} (left) and in {b} (right)
        return {**chain_model(chain), "story": story, "scale": 0.6, "axis_len": 0.4,
                "box": [-1.4, 2.7, -1.0, 2.7], "box_right": [-1.9, 1.1, -0.3, 2.5],
                **_story_motion([0.5, 0.9, -1.0], [0.0, 0.0, 0.0],
                                [[[0.6, 1.0, 0.0]], [[0.5, 2.0, 0.4]], [[0.8, 1.0, np.pi / 2]]],
                                2 * np.pi, 64, True, 0.8)}
    # ch07: constant joint rates; ṗ at the tool, v_s at the origin of {s}, and the numbers
    theta_dot = [0.5, -0.4, 0.9]
    return {**chain_model(chain), "story": story, "theta_dot": theta_dot, "vel_scale": 1.0, "axis_len": 0.4,
            "box": [-1.6, 2.4, -1.2, 2.6],
            **_story_motion([0.2, 0.9, -0.6], theta_dot, [[], [], []], 2 * np.pi / 0.9, 70, False, 1.0)}


def story_times(model: dict[str, Any]) -> NDArray[np.float64]:
    """The instants t_k (s) of the story's frames, as story.js: ``frames`` of them."""
    n, t_end = int(model["frames"]), float(model["t_end"])
    return np.arange(n, dtype=float) * (t_end / n if model["closed"] else t_end / (n - 1))


def story_theta(model: dict[str, Any], t: float | NDArray[np.float64]) -> NDArray[np.float64]:
    """θ(t) of the story's motion (rad): shape (n,) for a number t, (len(t), n) for an array."""
    tt = np.asarray(t, dtype=float)
    out: NDArray[np.float64] = (np.asarray(model["offset"], dtype=float)
                                + np.multiply.outer(tt, np.asarray(model["rate"], dtype=float)))
    for i, waves in enumerate(model["waves"]):
        for amp, freq, phase in waves:
            out[..., i] += amp * np.sin(freq * tt + phase)
    return out


def story_theta_dot(model: dict[str, Any], t: float) -> NDArray[np.float64]:
    """dθ/dt of the story's motion at t (rad/s)."""
    out = np.asarray(model["rate"], dtype=float).copy()
    for i, waves in enumerate(model["waves"]):
        for amp, freq, phase in waves:
            out[i] += amp * freq * np.cos(freq * float(t) + phase)
    return out


class StoryView(LiveView):
    """A story animation as a live view: ``frame`` settable, ``t`` and ``theta`` of the shown frame.

    ``StoryView("body_columns")``; ``w.frame = 10`` shows frame 10, ``w.chain`` is the library's chain.
    """

    def __init__(self, story: str = "three_velocities") -> None:
        model = story_model(story)
        self.chain = SerialChain(np.array(model["S"]), np.array(model["M"]), joint_points=np.array(model["Q"]))
        super().__init__("story", model)

    @property
    def t(self) -> float:
        """The time of the shown frame (s)."""
        return float(story_times(self._model())[int(self.frame)])

    def _model(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in ("frames", "t_end", "closed", "offset", "rate", "waves")}

    @property
    def theta(self) -> NDArray[np.float64]:
        """The joint angles of the shown frame (rad)."""
        return story_theta(self._model(), self.t)


SPEC = ViewSpec(name="story", model=story_model, widget=StoryView, options={"story": text},
                probe=("input.js-time", 10),
                example={"story": "body_columns"},
                folder=Path(__file__).resolve().parent)
