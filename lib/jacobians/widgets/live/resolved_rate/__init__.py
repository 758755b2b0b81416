r"""``resolved_rate`` (chapter 9): a planar arm following a preset or drawn path with the pseudo-inverse or
damped least squares, its joint rates plotted.

The model: the chain's keys, ``path``, ``drawn``, ``method``, ``damping``, ``step``, ``n_steps``,
``duration``, ``gain``, ``rate_limit``. :class:`ResolvedRate` gives the library's run of what it shows.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .... import velocity as _velocity
from ....chain import SerialChain
from ....jacobian import geometric_jacobian
from ....plotting import arm_reach
from .._base import LiveView, Shown, ViewSpec, chain_model, expect, number, planar_chain, text

__all__ = ["ResolvedRate", "resolved_rate_model", "planar_path", "start_configuration", "resample", "PATHS", "SPEC"]

PATHS = ("circle", "to full reach", "close past the base")


def resolved_rate_model(robot: str | SerialChain = "planar_2r", path: str = "close past the base",
                        method: str = "pinv", damping: float = 0.1, step: int = 0) -> dict[str, Any]:
    """The model of ``resolved_rate``: a run of 160 steps over 4 s, K = 2/s, along a path of :func:`planar_path`.

    >>> m = resolved_rate_model("planar_2r", "circle", "dls", 0.05)
    >>> m["path"], m["method"], m["damping"], m["n_steps"], m["duration"], m["gain"]
    ('circle', 'dls', 0.05, 160, 4.0, 2.0)
    """
    _, chain = planar_chain(robot)
    if path not in PATHS:
        raise ValueError(f"Expected path one of {', '.join(PATHS)}, got {path!r}")
    if method not in ("pinv", "dls"):
        raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
    lam = float(damping)
    if not (math.isfinite(lam) and 1e-3 <= lam <= 1.0):
        raise ValueError(f"Expected damping λ in [0.001, 1] m, got {damping!r}")
    return {**chain_model(chain), "path": path, "drawn": None, "method": method, "damping": lam,
            "step": int(step), "n_steps": 160, "duration": 4.0, "gain": 2.0, "rate_limit": 8.0}


def planar_path(kind: str, reach: float,
                n_steps: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A preset path of the resolved-rate view (view.js ``planarPath``): times t (N) over [0, 4 s], desired
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
    """Joint angles that put the tool of a planar arm at ``x0`` (view.js ``startConfiguration``): Newton
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
    """A drawn polyline resampled to ``n`` points evenly along its length, as view.js (None: no length).

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


class ResolvedRate(LiveView):
    """The live resolved-rate view; ``run`` is the library's run of what it shows (preset paths)."""

    def __init__(self, robot: str | SerialChain = "planar_2r", path: str = "close past the base",
                 method: str = "pinv", damping: float = 0.1) -> None:
        _, self.chain = planar_chain(robot)
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


def check_shown(shown: Shown) -> None:
    """The arm drawn, the time and σ_min(J_v) shown are the library's run's at the step shown."""
    m = shown["model"]
    robot = {2: "planar_2r", 3: "planar_3r"}[len(m["S"][0])]
    w = ResolvedRate(robot, path=m["path"], method=m["method"], damping=m["damping"])
    run, k = w.run, shown["step"]
    # the view integrates the same steps in the same order: only the last bits of the joint angles differ
    expect(np.allclose(shown["theta"], run.thetas[k], atol=1e-9), f"resolved_rate: θ at step {k} is not the run's")
    t = np.linspace(0.0, w.duration, w.n_steps)[k]
    for want in (f"t = {t:.2f} s", f"(Jv) = {float(run.sigma_min[k]):.3f} m"):
        expect(want in shown["text"], f"resolved_rate: {want!r} not shown at step {k}")


SPEC = ViewSpec(name="resolved_rate", model=resolved_rate_model, widget=ResolvedRate,
                options={"robot": text, "path": text, "method": text, "damping": number},
                probe=("input.jr-step", 80),
                example={"robot": "planar_3r", "path": "circle", "method": "dls", "damping": "0.05"},
                folder=Path(__file__).resolve().parent, data_keys=frozenset({"step", "playing", "level"}),
                check=check_shown)
