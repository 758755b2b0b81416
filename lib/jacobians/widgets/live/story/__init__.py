r"""``story``: an animation that tells a story, as a live view with a Play button and a time slider.

The view is generic: a model holds a chain, a motion θ(t) and what is drawn where, and names the drawing
(``story``: one build function of ``view.js`` each, looked up in a table there). Which stories there are is
course content: the course registers each one's model builder with :func:`register_story`
(``course.stories`` holds chapters 1, 3 and 7's); :data:`STORIES` maps each registered name to its builder.
A story asked for by name and not yet registered is looked for in the modules of the entry point group
``jacobians.live_stories`` (the package's metadata names ``course.stories`` there): the library finds the
course's stories without importing the course.

The motion is a formula: θ_i(t) = offset_i + rate_i t + Σ amp sin(freq t + phase) over the waves of joint i,
on ``frames`` instants t_k = t_end k / frames (``closed``: the motion is periodic, the last instant is
t_end (frames - 1)/frames) or t_end k / (frames - 1) (open).
"""

from __future__ import annotations

import importlib.metadata
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ....chain import SerialChain
from ....jacobian import body_jacobian, geometric_jacobian, space_jacobian
from .._base import LiveView, Shown, ViewSpec, chain_model, expect, text

__all__ = ["StoryView", "story_model", "story_view_model", "story_motion", "register_story", "story_times",
           "story_theta", "story_theta_dot", "story_state", "STORIES", "DRAWINGS", "SPEC"]
#: how far the view's numbers may be from the library's, relative to max(1, the largest |number|): both compute
#: θ(t) and the same products of a few 3-joint Jacobians, so they differ by a few roundings of numbers of size
#: at most the reach (1e-15 each); 1e-12 leaves three orders of magnitude to spare
TOL = 1e-12

#: the drawings view.js has (its table ``DRAWINGS``): a story's model names one of them as ``story``
DRAWINGS = ("fixed_axis", "body_columns", "three_velocities")
#: story name -> the builder of its model (no arguments), registered by the course (:func:`register_story`)
STORIES: dict[str, Callable[[], dict[str, Any]]] = {}


def register_story(name: str) -> Callable[[Callable[[], dict[str, Any]]], Callable[[], dict[str, Any]]]:
    """Register a story's model builder under ``name`` (a decorator); the name is also its drawing's."""
    if name not in DRAWINGS:
        raise ValueError(f"Expected a story drawn by story/view.js, one of {', '.join(DRAWINGS)}, got {name!r}")

    def add(build: Callable[[], dict[str, Any]]) -> Callable[[], dict[str, Any]]:
        STORIES[name] = build
        return build

    return add


def story_motion(offset: Sequence[float], rate: Sequence[float], waves: Sequence[Sequence[Sequence[float]]],
                 t_end: float, frames: int, closed: bool, speed: float) -> dict[str, Any]:
    """The model keys of a motion θ(t) (see the module's text), shown from its first frame."""
    return {"offset": [float(x) for x in offset], "rate": [float(x) for x in rate],
            "waves": [[[float(v) for v in w] for w in ws] for ws in waves], "t_end": float(t_end),
            "frames": int(frames), "closed": bool(closed), "speed": float(speed), "frame": 0}


def story_view_model(story: str, chain: SerialChain, motion: dict[str, Any], **drawn: Any) -> dict[str, Any]:
    """A story's model: the chain, the motion (:func:`story_motion`), and what ``story``'s drawing reads
    (``box`` [x0, x1, y0, y1] m, ...: plain JSON)."""
    if story not in DRAWINGS:
        raise ValueError(f"Expected story one of {', '.join(DRAWINGS)}, got {story!r}")
    return {**chain_model(chain), "story": story, **drawn, **motion}


#: the entry point group of the modules that register stories when imported
ENTRY_POINTS = "jacobians.live_stories"


def _load_stories() -> None:
    """Import the modules of the entry point group :data:`ENTRY_POINTS` (each registers its stories)."""
    for entry in importlib.metadata.entry_points(group=ENTRY_POINTS):
        try:
            entry.load()
        except ImportError as exc:  # a provider whose own needs are not installed: its stories stay unknown
            raise ImportError(f"Expected the stories of {entry.value} (entry point {entry.name} of {ENTRY_POINTS}) "
                              f"to load: {exc}") from exc


def story_model(story: str) -> dict[str, Any]:
    """The model of the registered story ``story`` (:data:`STORIES`, filled from :data:`ENTRY_POINTS` when needed)."""
    if story not in STORIES:
        _load_stories()
    if story not in STORIES:
        raise ValueError(f"Expected story one of {', '.join(STORIES) or '(none registered)'}, got {story!r}: "
                         f"the stories are registered by the modules of the entry point group {ENTRY_POINTS}")
    return STORIES[story]()


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


def story_state(model: dict[str, Any], t: float) -> dict[str, NDArray[np.float64]]:
    """What the view draws at time t (story/view.js's ``storyState``), from the library: the pose (θ, the tool
    point p, its axes xb, yb, the joints' points), the linear parts of J_b's columns in {b} (vb) and in {s}
    (vs), and at the motion's joint rates θ̇: the twists' parts ω_s, v_s, ω_b, v_b and the tool point's ṗ."""
    chain = SerialChain(np.array(model["S"]), np.array(model["M"]), joint_points=np.array(model["Q"]))
    th = story_theta(model, t)
    T = chain.fk(th)
    vb = body_jacobian(chain, th)[3:5]
    qd = story_theta_dot(model, t)
    Vs, Vb = space_jacobian(chain, th) @ qd, body_jacobian(chain, th) @ qd
    return {"theta": th, "p": T[:2, 3], "xb": T[:2, 0], "yb": T[:2, 1], "points": chain.joint_positions(th)[:, :2],
            "vb": vb.T, "vs": (T[:2, :2] @ vb).T, "thetaDot": qd, "omegaS": Vs[:3], "vS": Vs[3:],
            "omegaB": Vb[:3], "vB": Vb[3:], "pDot": (geometric_jacobian(chain, th) @ qd)[3:]}


def largest_difference(model: dict[str, Any], state: Shown) -> float:
    """max over the view's numbers (``state``: its ``el.jacLive``) of |view - library| / max(1, max |library|)."""
    worst = 0.0
    for k, v in story_state(model, float(state["t"])).items():
        got = np.asarray(state[k], dtype=float)
        if got.shape != v.shape:
            raise AssertionError(f"story: {k} has shape {got.shape}, the library's {v.shape}")
        worst = max(worst, float(np.abs(got - v).max() / max(1.0, np.abs(v).max())))
    return worst


def check_shown(shown: Shown) -> None:
    """The story shown is the registered one, at a frame's time, and every number it drew is the library's."""
    model, state = shown["model"], shown["state"]
    expect(model == json.loads(json.dumps(story_model(model["story"]))), f"story: not the story {model['story']!r}")
    k = shown["step"]
    expect(state["t"] == story_times(model)[k], f"story: t = {state['t']} is not frame {k}'s")
    expect(list(shown["theta"]) == list(state["theta"]), "story: data-theta is not the θ drawn")
    worst = largest_difference(model, state)
    expect(worst <= TOL, f"story: a number drawn is {worst:.2g} from the library's (relative)")


class StoryView(LiveView):
    """A story animation as a live view: ``frame`` settable, ``t`` and ``theta`` of the shown frame.

    ``StoryView("body_columns")``; ``w.frame = 10`` shows frame 10, ``w.chain`` is the library's chain.
    """

    def __init__(self, story: str) -> None:
        model = story_model(story)  # a registered story (course.stories registers the course's)
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
                folder=Path(__file__).resolve().parent, data_keys=frozenset({"story", "step", "playing"}),
                check=check_shown)
