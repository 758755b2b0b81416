"""Resolved-rate motion of a planar arm along a path (chapter 9): the explorer and its animation."""

from __future__ import annotations

from typing import Any

import ipywidgets as W
import numpy as np
from matplotlib.figure import Figure
from numpy.typing import NDArray

from .. import robots
from .. import velocity as _velocity
from ..chain import SerialChain
from ..jacobian import geometric_jacobian
from ..plotting import (
    COLUMN_COLORS,
    PALETTE,
    FrameSource,
    PlanarArmArtist,
    arm_reach,
    check_planar,
    setup_planar_axes,
)
from .base import (
    FONT,
    _Explorer,
    _status_html,
)

__all__ = ["ResolvedRateExplorer", "resolved_rate_explorer", "resolved_rate_animation"]


def _planar_path(kind: str, reach: float,
                 n_steps: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Desired tool positions (N, 2) and velocities (N, 2) over t in [0, T] with T = 4 s."""
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


class ResolvedRateExplorer(_Explorer):
    """Resolved-rate motion; see :func:`resolved_rate_explorer`."""

    PATHS = ("circle", "to full reach", "close past the base")
    RATE_LIMIT = 8.0  # rad/s shown on the rate plot; larger peaks leave the plot and are printed
    GAIN = 2.0  # feedback gain K (1/s) of the controller

    def __init__(self, chain: SerialChain | None = None, path: str = "close past the base", method: str = "pinv",
                 damping: float = 0.1, *, static: bool = False, n_steps: int = 160,
                 figsize: tuple[float, float] = (9.6, 4.8), dpi: float = 80) -> None:
        super().__init__()
        chain = robots.planar_2r() if chain is None else chain
        self.chain = check_planar(chain, "the resolved-rate explorer")
        if path not in self.PATHS:
            raise ValueError(f"Expected path one of {self.PATHS}, got {path!r}")
        if method not in ("pinv", "dls"):
            raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
        self.reach = arm_reach(self.chain)
        self.n_steps = int(n_steps)
        self.path_dropdown = W.Dropdown(options=list(self.PATHS), value=path, description="path",
                                        layout=W.Layout(width="250px"))
        self.method_dropdown = W.Dropdown(options=[("pseudo-inverse", "pinv"), ("damped least squares", "dls")],
                                          value=method, description="method", layout=W.Layout(width="250px"))
        self.damping_slider = W.FloatLogSlider(value=float(damping), base=10, min=-3, max=0, step=0.1,
                                               description="λ (m)", readout_format=".3f", continuous_update=False,
                                               layout=W.Layout(width="330px"), style={"description_width": "70px"})
        self.time_slider = W.IntSlider(value=0, min=0, max=self.n_steps - 1, description="step",
                                       layout=W.Layout(width="330px"), style={"description_width": "70px"})
        self.play = W.Play(value=0, min=0, max=self.n_steps - 1, step=2, interval=60, description="Play")
        W.jslink((self.play, "value"), (self.time_slider, "value"))
        self.status = W.HTML()
        fig = Figure(figsize=figsize, dpi=dpi)
        self._setup(fig, static)
        ax = fig.add_axes((0.07, 0.12, 0.4, 0.78))
        axr = fig.add_axes((0.58, 0.12, 0.4, 0.78))
        self.ax, self.ax_rates = ax, axr
        setup_planar_axes(ax, self.chain, title="tool following the path", margin=0.1)
        (self.des_line,) = ax.plot([], [], "--", color=PALETTE["path"], lw=2.2, label="desired path")
        (self.act_line,) = ax.plot([], [], "-", color=PALETTE["velocity"], lw=1.5, label="actual tool path")
        self.arm = PlanarArmArtist(ax, self.chain, np.zeros(self.chain.dof), show_frames=False, label="arm")
        (self.target,) = ax.plot([], [], "x", color=PALETTE["path"], ms=12, mew=3, zorder=6)
        ax.legend(loc="upper left", fontsize=8.5, framealpha=0.85)
        axr.set_ylim(-self.RATE_LIMIT, self.RATE_LIMIT)  # fixed, so methods compare at a glance
        axr.set_xlabel("time t (s)")
        axr.set_ylabel("joint rate (rad/s)")
        axr.set_title("joint rates from $J_v^{\\#}\\dot x$", fontsize=FONT)
        self.rate_lines = [axr.plot([], [], color=COLUMN_COLORS[i % 7], label=f"$\\dot\\theta_{i + 1}$")[0]
                           for i in range(self.chain.dof)]
        self.cursor = axr.axvline(0.0, color="0.3", lw=1.2)
        self.rate_text = axr.text(0.02, 0.97, "", transform=axr.transAxes, va="top", fontsize=FONT - 1,
                                  bbox=dict(boxstyle="round", fc="white", ec="0.6"))
        axr.legend(loc="lower right", fontsize=9)
        self.blitter.add(self.des_line, self.act_line, self.arm.artists, self.target, self.rate_lines, self.cursor,
                         self.rate_text)
        self._sim_key: tuple[Any, ...] | None = None
        for c in (self.path_dropdown, self.method_dropdown, self.damping_slider, self.time_slider):
            c.observe(self._changed, names="value")
        controls = W.VBox([self.path_dropdown, self.method_dropdown, self.damping_slider,
                           W.HBox([self.play]), self.time_slider])
        self.children = [W.HBox([controls, self.status]), self.image]
        self.refresh()

    def set(self, path: str | None = None, method: str | None = None, damping: float | None = None,
            step: int | None = None) -> ResolvedRateExplorer:
        """Choose the path, the method ('pinv' or 'dls'), the damping λ, and/or the time step shown."""
        with self.hold_updates():
            if path is not None:
                if path not in self.PATHS:
                    raise ValueError(f"Expected path one of {self.PATHS}, got {path!r}")
                self.path_dropdown.value = path
            if method is not None:
                if method not in ("pinv", "dls"):
                    raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
                self.method_dropdown.value = method
            if damping is not None:
                self.damping_slider.value = float(damping)
            if step is not None:
                self.time_slider.value = int(np.clip(step, 0, self.n_steps - 1))
                self.play.value = self.time_slider.value  # keep the linked Play in step
        return self

    def _simulate(self) -> bool:
        path, method, lam = self.path_dropdown.value, self.method_dropdown.value, self.damping_slider.value
        key = (path, method, lam if method == "dls" else None)
        if key == self._sim_key:
            return False
        t, x_des, v_des = _planar_path(path, self.reach, self.n_steps)
        # start on the path, elbow up: solve for the start by resolved rate from a bent pose
        th0 = self._start_configuration(x_des[0])
        dt = t[1] - t[0]
        self.t, self.x_des, self.v_des = t, x_des, v_des
        # the feed-forward is the path's exact velocity (not the library's default forward differences)
        self.result = _velocity.resolved_rate(self.chain, th0, x_des, dt, method=method, damping=lam,
                                              gain=self.GAIN, target_velocities=v_des)
        r = self.result
        self.thetas, self.rates_hist, self.x_act, self.sigma_hist, self.errors = (
            r.thetas, r.rates, r.positions, r.sigma_min, r.errors)
        self._sim_key = key
        return True

    def _start_configuration(self, x0: NDArray[np.float64]) -> NDArray[np.float64]:
        n = self.chain.dof
        th = np.array([0.3] + [0.9] * (n - 1))[:n]
        for _ in range(200):  # Newton steps with a little damping (1 mm)
            J = geometric_jacobian(self.chain, th)[3:5]
            e = x0 - self.chain.fk(th)[:2, 3]
            if np.linalg.norm(e) < 1e-12:
                break
            th = th + _velocity.dls_rates(J, e, 1e-3)
        return th

    def _compute_and_update(self) -> None:
        if self._simulate():
            self.des_line.set_data(self.x_des[:, 0], self.x_des[:, 1])
            for i, ln in enumerate(self.rate_lines):
                ln.set_data(self.t, self.rates_hist[:, i])
            self.ax_rates.set_xlim(0, self.t[-1])
        k = self.time_slider.value
        if self.play.value != k:
            self.play.value = k  # the browser links them; mirror it here so both agree when shown
        self.step = k
        self.arm.update(self.thetas[k])
        self.act_line.set_data(self.x_act[: k + 1, 0], self.x_act[: k + 1, 1])
        self.target.set_data([self.x_des[k, 0]], [self.x_des[k, 1]])
        self.cursor.set_xdata([self.t[k], self.t[k]])
        err = float(self.errors[k])
        s = float(self.sigma_hist[k])
        peak = float(np.abs(self.rates_hist).max())
        self.tracking_error, self.current_sigma_min, self.peak_rate = err, s, peak
        self.rate_text.set_text(f"t = {self.t[k]:.2f} s   σ_min(J_v) = {s:.3f} m\n"
                                f"|θ̇| now {np.linalg.norm(self.rates_hist[k]):.2f} rad/s, peak {peak:.1f} rad/s\n"
                                f"tracking error {1000 * err:.1f} mm")
        level = "bad" if s < 0.02 * self.reach else "warn" if s < 0.1 * self.reach else "ok"
        self.level = level
        meth = "pseudo-inverse" if self.method_dropdown.value == "pinv" else \
            f"damped least squares, λ = {self.damping_slider.value:.3f} m"
        self.status.value = _status_html(
            f"{meth}: smallest singular value of J<sub>v</sub> {s:.3f} m; peak joint rate over the run "
            f"{peak:.1f} rad/s; largest tracking error {1000 * float(self.errors.max()):.1f} mm",
            level)


def resolved_rate_explorer(chain: SerialChain | None = None, path: str = "close past the base", method: str = "pinv",
                           damping: float = 0.1, **kw: Any) -> ResolvedRateExplorer:
    r"""Resolved-rate motion of a planar arm along a path (chapter 9).

    Paths: ``"circle"`` (well inside the workspace), ``"to full reach"`` (ends
    on the boundary, where the arm is stretched and singular) and ``"close past
    the base"`` (a straight line passing 3 % of the reach from the base: the arm
    must swing joint 1 through about half a turn in a moment). Methods:
    pseudo-inverse, whose joint rates blow up approaching a singularity, or
    damped least squares, whose rates stay bounded at the cost of a tracking
    error. ``.set(path=, method=, damping=, step=)`` drives it. The run is
    :func:`jacobians.velocity.resolved_rate` (gain K = 2/s, the path's own
    velocity as feed-forward), kept as ``.result``; ``.thetas``,
    ``.rates_hist``, ``.x_act``, ``.sigma_hist``, ``.errors`` are its fields, and
    ``.peak_rate``, ``.tracking_error`` what the view reports.
    """
    return ResolvedRateExplorer(chain, path, method, damping, **kw)


def resolved_rate_animation(chain: SerialChain | None = None, path: str = "close past the base", method: str = "pinv",
                            damping: float = 0.1, frames: int = 36, dpi: float = 72,
                            interval: float = 120) -> FrameSource:
    """The resolved-rate view as a :class:`~jacobians.plotting.FrameSource` over the run.

    ``.explorer`` is the :class:`ResolvedRateExplorer`, ``.path`` the joint angles of the frames.
    """
    w = ResolvedRateExplorer(chain, path, method, damping, static=True, dpi=dpi)
    steps = np.linspace(0, w.n_steps - 1, int(frames)).round().astype(int)

    def draw(k: int) -> list:
        w.set(step=steps[k])
        return []

    draw(0)
    return FrameSource(w.fig, draw, len(steps), interval=interval, render=w.blitter.render_rgba, explorer=w,
                       path=w.thetas[steps].copy())
