r"""Live views in JupyterLab: anywidget wrappers of the book's ES modules.

One front-end module per view lives in ``lib/jacobians/widgets/static/live/<view>.js``. The static
book mounts it with the ``{live-view}`` directive (``_ext/live_views.py``) from
a model computed here; in JupyterLab (``make lab``) the same module is the
``_esm`` of an :class:`anywidget.AnyWidget`, so notebook code reads and sets
its state (``w.theta = ...``) and the library computes what the view shows
(``w.J``).

The contract every view module follows: ``export default { render }`` where
``render({model, el})`` draws into ``el`` and returns a cleanup function, and
uses only ``model.get(key)``, ``model.set(key, value)``, ``model.save_changes()``
and ``model.on/off("change:<key>", f)``. The model keys (plain JSON) of a
chain view:

* ``S``: the 6×n screw axes (columns (ω, v)), ``M``: the 4×4 home pose,
  ``Q``: n×3 points on the joint axes at home (where joints are drawn),
  ``name``: the arm's name, ``reach``: its reach in m;
* ``theta``: the n joint values (rad), written back by the view;
* anything else the view documents in its header comment: for
  ``planar_explorer``: ``frame`` (``"space"``, ``"body"``, ``"geometric"``,
  ``"analytic"``), ``sing_tol``, ``vel_scale``, ``force_scale``,
  ``force_clip``, ``sweep``; for ``resolved_rate``: ``path``, ``drawn``,
  ``method``, ``damping``, ``step``, ``n_steps``, ``duration``, ``gain``,
  ``rate_limit``.

:class:`LiveView` hosts ANY ``lib/jacobians/widgets/static/live/<view>.js`` by name: every model key
becomes a synced traitlet. anywidget loads ``_esm`` from a blob: URL, where a
relative import such as ``./kinematics.js`` cannot resolve, so
:func:`module_source` inlines a module's relative imports, recursively, as
``data:`` URL imports.

>>> w = PlanarExplorer(theta=[0.3, 1.2])
>>> w.frame, [round(float(t), 2) for t in w.theta], w.J.shape
('space', [0.3, 1.2], (6, 2))
"""

from __future__ import annotations

import base64
import math
import os
import re
from collections.abc import Callable, Sequence
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .. import robots
from .. import velocity as _velocity
from ..chain import SerialChain
from ..frames import check_frame
from ..jacobian import analytic_jacobian, geometric_jacobian, jacobian
from ..plotting import arm_reach, check_planar

__all__ = ["LiveView", "PlanarExplorer", "ResolvedRate", "module_source", "live_dir", "planar_model",
           "resolved_rate_model", "resample", "planar_path", "start_configuration", "MODELS", "ROBOTS"]

ROBOTS: dict[str, Callable[[], SerialChain]] = {"planar_2r": robots.planar_2r, "planar_3r": robots.planar_3r}
PLANAR_FRAMES = ("space", "body", "geometric", "analytic")
PATHS = ("circle", "to full reach", "close past the base")
SING_TOL = 0.08  # x reach: sigma_min(J_v) below this is "near a singularity" in the planar views
VEL_SCALE = 0.35  # drawn metres per m/s
LIMIT = 3.14  # the views' slider range, rad
_IMPORT = re.compile(r"""(\bfrom\s*|\bimport\s*)(["'])\./([A-Za-z0-9_]+\.js)\2""")


def live_dir() -> Path:
    """The folder of the view modules: ``$JACOBIANS_LIVE_DIR``, else ``static/live`` beside this module.

    The modules ship inside the package (package data, anywidget's layout), so an installed wheel has them;
    the book copies the same folder into ``_static/live``.
    """
    env = os.environ.get("JACOBIANS_LIVE_DIR")
    d = Path(env) if env else Path(__file__).resolve().parent / "static" / "live"
    if not (d / "kinematics.js").is_file():
        raise FileNotFoundError(f"Expected the live view modules (kinematics.js) in {d}: the package was installed "
                                "without its data files (reinstall it) or JACOBIANS_LIVE_DIR names the wrong folder")
    return d


@cache
def _inlined(path: Path, mtime: float) -> str:
    text = path.read_text(encoding="utf-8")

    def sub(m: re.Match[str]) -> str:
        dep = path.parent / m.group(3)
        if not dep.is_file():
            raise FileNotFoundError(f"{path.name} imports ./{m.group(3)}, which is not in {path.parent}")
        code = _inlined(dep, dep.stat().st_mtime)
        url = "data:text/javascript;base64," + base64.b64encode(code.encode("utf-8")).decode("ascii")
        return f"{m.group(1)}{m.group(2)}{url}{m.group(2)}"

    return _IMPORT.sub(sub, text)


def module_source(view: str) -> str:
    """The ES module ``static/live/<view>.js`` as one self-contained text (relative imports as data: URLs)."""
    if not isinstance(view, str) or not re.fullmatch(r"[a-z0-9_]+", view):
        raise ValueError(f"Expected a view name such as 'planar_explorer' (letters, digits, _), got {view!r}")
    path = live_dir() / f"{view}.js"
    if not path.is_file():
        views = sorted(p.stem for p in live_dir().glob("*.js"))
        raise ValueError(f"Expected a view module in {live_dir()}, one of {views}, got {view!r}")
    return _inlined(path, path.stat().st_mtime)


def _chain(robot: str | SerialChain) -> tuple[str, SerialChain]:
    if isinstance(robot, SerialChain):
        return robot.name or "the arm", check_planar(robot, "a planar live view")
    if robot not in ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(ROBOTS)} or a planar SerialChain, got {robot!r}")
    return robot, ROBOTS[robot]()


def _chain_model(chain: SerialChain) -> dict[str, Any]:
    return {"name": chain.name, "S": chain.screw_axes.tolist(), "M": chain.home.tolist(),
            "Q": chain.axis_points().tolist(), "reach": arm_reach(chain)}


def _theta(theta: Sequence[float] | NDArray[np.float64] | None, n: int, robot: str) -> list[float]:
    if theta is None:
        return [0.5, 1.2, -0.8, 0.4, 0.3][:n]  # the matplotlib explorer's default
    th = [float(t) for t in np.asarray(theta, dtype=float).ravel()]
    if len(th) != n:
        raise ValueError(f"Expected theta with {n} angles (rad) for {robot}, got {len(th)}: {list(th)!r}")
    bad = [t for t in th if not math.isfinite(t) or abs(t) > LIMIT]
    if bad:
        raise ValueError(f"Expected theta as finite angles within ±{LIMIT} rad, got {bad!r}")
    return th


def planar_model(robot: str | SerialChain = "planar_2r", theta: Sequence[float] | None = None,
                 frame: str = "space", sweep: int | None = None) -> dict[str, Any]:
    """The model of ``planar_explorer`` for ``robot`` at ``theta`` (rad).

    >>> m = planar_model("planar_2r", [0.3, 1.2], "body")
    >>> len(m["S"]), len(m["S"][0]), m["theta"], m["frame"], round(m["sing_tol"], 3), m["sweep"]
    (6, 2, [0.3, 1.2], 'body', 0.16, 1)
    """
    name, chain = _chain(robot)
    if frame not in PLANAR_FRAMES:
        raise ValueError(f"Expected frame one of {', '.join(PLANAR_FRAMES)}, got {frame!r}")
    n = chain.dof
    sw = n - 1 if sweep is None else sweep
    if not isinstance(sw, int) or not 0 <= sw < n:
        raise ValueError(f"Expected sweep as a joint index 0..{n - 1} (the joint Play turns), got {sweep!r}")
    reach = arm_reach(chain)
    return {**_chain_model(chain), "theta": _theta(theta, n, name), "frame": frame, "sing_tol": SING_TOL * reach,
            "vel_scale": VEL_SCALE, "force_scale": 0.1 * reach ** 2, "force_clip": 1.25 * reach, "sweep": sw}


def resolved_rate_model(robot: str | SerialChain = "planar_2r", path: str = "close past the base",
                        method: str = "pinv", damping: float = 0.1, step: int = 0) -> dict[str, Any]:
    """The model of ``resolved_rate``: a run of 160 steps over 4 s, K = 2/s, along a path of :func:`planar_path`.

    >>> m = resolved_rate_model("planar_2r", "circle", "dls", 0.05)
    >>> m["path"], m["method"], m["damping"], m["n_steps"], m["duration"], m["gain"]
    ('circle', 'dls', 0.05, 160, 4.0, 2.0)
    """
    _, chain = _chain(robot)
    if path not in PATHS:
        raise ValueError(f"Expected path one of {', '.join(PATHS)}, got {path!r}")
    if method not in ("pinv", "dls"):
        raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
    lam = float(damping)
    if not (math.isfinite(lam) and 1e-3 <= lam <= 1.0):
        raise ValueError(f"Expected damping λ in [0.001, 1] m, got {damping!r}")
    return {**_chain_model(chain), "path": path, "drawn": None, "method": method, "damping": lam,
            "step": int(step), "n_steps": 160, "duration": 4.0, "gain": 2.0, "rate_limit": 8.0}


def planar_path(kind: str, reach: float,
                n_steps: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A preset path of the resolved-rate view (resolved_rate.js ``planarPath``): times t (N) over [0, 4 s], desired
    tool positions (N×2) and their exact velocities (N×2), for an arm of reach ``reach``."""
    T = 4.0
    t = np.linspace(0.0, T, n_steps)
    if kind == "circle":
        c, r = np.array([0.45 * reach, 0.2 * reach]), 0.3 * reach
        w = 2 * np.pi / T
        x = c + r * np.column_stack([np.cos(w * t), np.sin(w * t)])
        v = r * w * np.column_stack([-np.sin(w * t), np.cos(w * t)])
    elif kind == "to full reach":
        a, b = np.array([0.3 * reach, 0.5 * reach]), np.array([reach, 0.0])
        x = a + np.outer(t / T, b - a)
        v = np.tile((b - a) / T, (n_steps, 1))
    elif kind == "close past the base":
        a, b = np.array([0.6 * reach, 0.03 * reach]), np.array([-0.6 * reach, 0.03 * reach])
        x = a + np.outer(t / T, b - a)
        v = np.tile((b - a) / T, (n_steps, 1))
    else:
        raise ValueError(f"Expected path 'circle', 'to full reach' or 'close past the base', got {kind!r}")
    return t, x, v


def start_configuration(chain: SerialChain, x0: Sequence[float] | NDArray[np.float64]) -> NDArray[np.float64]:
    """Joint angles that put the tool of a planar arm at ``x0`` (resolved_rate.js ``startConfiguration``): Newton
    steps with 1 mm of damping from (0.3, 0.9, 0.9, ...), until the error is below 1e-12 m or 200 steps."""
    n = chain.dof
    x = np.asarray(x0, dtype=float)
    th = np.array([0.3] + [0.9] * (n - 1))[:n]
    for _ in range(200):
        J = geometric_jacobian(chain, th)[3:5]
        e = x - chain.fk(th)[:2, 3]
        if np.linalg.norm(e) < 1e-12:
            break
        th = th + _velocity.dls_rates(J, e, 1e-3)
    return th


def resample(points: Sequence[Sequence[float]], n: int) -> NDArray[np.float64] | None:
    """A drawn polyline resampled to ``n`` points evenly along its length, as resolved_rate.js (None: no length).

    >>> resample([[0, 0], [1, 0], [1, 1]], 5).tolist()
    [[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 0.5], [1.0, 1.0]]
    """
    P = np.asarray(points, dtype=float).reshape(-1, 2)
    P = P[np.isfinite(P).all(axis=1)]
    if len(P) < 2:
        return None
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(P, axis=0).T))])
    if not s[-1] > 0:
        return None
    out = np.empty((n, 2))
    j = 0
    for k in range(n):
        u = s[-1] * k / (n - 1)
        while j < len(P) - 2 and s[j + 1] < u:
            j += 1
        f = min(1.0, max(0.0, (u - s[j]) / (s[j + 1] - s[j]))) if s[j + 1] > s[j] else 0.0
        out[k] = P[j] + f * (P[j + 1] - P[j])
    return out


#: View name -> function of keyword options returning the view's model (the directive and LiveView use it).
MODELS: dict[str, Callable[..., dict[str, Any]]] = {
    "planar_explorer": planar_model,
    "resolved_rate": resolved_rate_model,
}


def _anywidget() -> Any:
    try:
        import anywidget
    except ImportError as exc:  # pragma: no cover - anywidget is pinned in requirements.txt
        raise ImportError("Expected anywidget (pip install anywidget==0.11.0) for the live views in Jupyter") from exc
    return anywidget


def _base() -> type:
    return _anywidget().AnyWidget  # type: ignore[no-any-return]


class LiveView(_base()):  # type: ignore[misc]
    """Any ``static/live/<view>.js`` as a Jupyter widget: ``LiveView("planar_explorer", **model)``.

    Every key of ``model`` (or, with no model, of ``MODELS[view](**options)``)
    becomes a synced traitlet, read and set as an attribute; the view's
    changes come back to Python. Subclasses add what the library computes.
    """

    def __init__(self, view: str, model: dict[str, Any] | None = None, **options: Any) -> None:
        import traitlets

        if model is None:
            if view not in MODELS:
                raise ValueError(f"Expected a model for view {view!r} (no builder in MODELS: {sorted(MODELS)})")
            model = MODELS[view](**options)
        elif options:
            raise TypeError(f"Expected either a model or options for {view!r}, got both ({sorted(options)})")
        if not isinstance(model, dict) or not all(isinstance(k, str) and k.isidentifier() for k in model):
            raise TypeError(f"Expected the model as a dict with identifier keys, got {type(model).__name__}")
        clash = [k for k in model if hasattr(_base(), k)]
        if clash:
            raise ValueError(f"Expected model keys that are not widget attributes, got {clash}")
        self.add_traits(**{k: traitlets.Any().tag(sync=True) for k in model})
        super().__init__(_esm=module_source(view), **model)
        self.view = view


class PlanarExplorer(LiveView):
    """The live planar arm explorer; ``theta`` and ``frame`` settable, ``J`` from the library.

    ``PlanarExplorer(robot="planar_3r", theta=[...], frame="geometric")``, with
    ``robot`` a name in ``ROBOTS`` or a planar :class:`SerialChain`.
    """

    def __init__(self, robot: str | SerialChain = "planar_2r", theta: Sequence[float] | None = None,
                 frame: str = "space", sweep: int | None = None) -> None:
        _, self.chain = _chain(robot)
        super().__init__("planar_explorer", planar_model(self.chain, theta, frame, sweep))

    @property
    def J(self) -> NDArray[np.float64]:
        """The shown Jacobian at the current ``theta``: 6×n, or for ``"analytic"`` 3×n in (x, y, φ)."""
        th = np.asarray(self.theta, dtype=float)
        if self.frame == "analytic":
            return analytic_jacobian(self.chain, th, "zyx")[[3, 4, 0]]
        return jacobian(self.chain, th, check_frame(self.frame))


class ResolvedRate(LiveView):
    """The live resolved-rate view; ``run`` is the library's run of what it shows (preset paths)."""

    def __init__(self, robot: str | SerialChain = "planar_2r", path: str = "close past the base",
                 method: str = "pinv", damping: float = 0.1) -> None:
        _, self.chain = _chain(robot)
        super().__init__("resolved_rate", resolved_rate_model(self.chain, path, method, damping))

    def target(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None]:
        """The times t (N), desired positions (N×2) and velocities (N×2, None for a drawn path) of the run."""
        n = int(self.n_steps)
        drawn = resample(self.drawn, n) if self.path == "drawn" and self.drawn else None
        if drawn is not None:  # as the view: evenly along the drawn line over the run, forward differences
            return np.linspace(0.0, float(self.duration), n), drawn, None
        return planar_path(self.path if self.path in PATHS else "circle", arm_reach(self.chain), n)

    @property
    def run(self) -> _velocity.ResolvedRateResult:
        """``velocity.resolved_rate`` of the current path, method and λ from the view's start (as the view)."""
        t, x, v = self.target()
        th0 = start_configuration(self.chain, x[0])
        return _velocity.resolved_rate(self.chain, th0, x, t[1] - t[0], method=self.method, damping=self.damping,
                                       gain=self.gain, target_velocities=v)

    @property
    def theta(self) -> NDArray[np.float64]:
        """The joint angles at the shown ``step``."""
        return np.asarray(self.run.thetas[int(self.step)])


# ---------------------------------------------------------------- story views (chapters 1, 3, 7)
# The animations that tell a story, as a live view with a Play button and a time slider
# (lib/jacobians/widgets/static/live/story.js). The model holds the chain and the motion θ(t) as a formula:
# θ_i(t) = offset_i + rate_i t + Σ amp sin(freq t + phase) over the waves of joint i, on
# ``frames`` instants t_k = t_end k / frames (``closed``: the motion is periodic, the last
# instant is t_end (frames - 1)/frames) or t_end k / (frames - 1) (open).

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
        return {**_chain_model(chain), "story": story, "q": q.tolist(), "theta_dot": [1.0],
                "box": [-0.9, 2.4, -1.4, 2.1], "axis_len": 0.35,
                **_story_motion([0.0], [1.0], [[]], 2 * np.pi, 72, True, 1.0)}
    chain = robots.planar_3r(1.0, 0.8, 0.5)
    if story == "body_columns":  # ch03: a closed path; the columns of J_b in {s} (left) and in {b} (right)
        return {**_chain_model(chain), "story": story, "scale": 0.6, "axis_len": 0.4,
                "box": [-1.4, 2.7, -1.0, 2.7], "box_right": [-1.9, 1.1, -0.3, 2.5],
                **_story_motion([0.5, 0.9, -1.0], [0.0, 0.0, 0.0],
                                [[[0.6, 1.0, 0.0]], [[0.5, 2.0, 0.4]], [[0.8, 1.0, np.pi / 2]]],
                                2 * np.pi, 64, True, 0.8)}
    # ch07: constant joint rates; ṗ at the tool, v_s at the origin of {s}, and the numbers
    theta_dot = [0.5, -0.4, 0.9]
    return {**_chain_model(chain), "story": story, "theta_dot": theta_dot, "vel_scale": 1.0, "axis_len": 0.4,
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


MODELS["story"] = story_model


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
