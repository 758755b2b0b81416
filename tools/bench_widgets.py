"""How fast do the widgets answer a slider? Prints, never asserts.

For each widget of jacobians.widgets, in one run:
  * one slider change: compute + move artists + draw the moving part + PNG
    (median and worst of N changes);
  * the same change with a full redraw of the figure (no kept background);
  * building the same view from scratch (new widget, first PNG);
and the ratios. Goals (issue 5): an update at least 3x faster than a rebuild,
and at least 10 updates per second.

    MPLBACKEND=Agg .venv/bin/python tools/bench_widgets.py [--n 20]
"""

from __future__ import annotations

import argparse
import functools
import os
import time

os.environ.setdefault("MPLBACKEND", "Agg")

from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

import jacobians as jac
from jacobians import widgets as Wd


def timed(fn: Callable[[int], object], reps: int, cpu: list[float] | None = None) -> np.ndarray:
    """Wall-clock seconds of each call; CPU seconds of this process appended to ``cpu`` if given."""
    out = []
    for k in range(reps):
        t0, c0 = time.perf_counter(), time.process_time()
        fn(k)
        out.append(time.perf_counter() - t0)
        if cpu is not None:
            cpu.append(time.process_time() - c0)
    return np.array(out)


def cases() -> Iterator[tuple[str, Callable[[], Any], Callable[[Any, int], object]]]:
    arm3 = jac.robots.planar_3r(1.0, 0.8, 0.5)
    yield ("explorer 2R", lambda: Wd.planar_arm_explorer(),
           lambda w, k: setattr(w.angle_sliders[1], "value", round(-2.5 + 0.23 * k, 2)))
    yield ("explorer 3R analytic", lambda: Wd.planar_arm_explorer(arm3, frame="analytic"),
           lambda w, k: setattr(w.rate_sliders[0], "value", round(-1.5 + 0.13 * k, 2)))
    yield ("resolved rate: time step", lambda: Wd.resolved_rate_explorer(),
           lambda w, k: setattr(w.time_slider, "value", 5 * k))
    yield ("resolved rate: damping (re-simulates)", lambda: Wd.resolved_rate_explorer(method="dls"),
           lambda w, k: setattr(w.damping_slider, "value", 10 ** (-2.5 + 0.1 * k)))


def _rebuild(make: Callable[[], Any], k: int) -> None:
    make()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=20, help="slider changes per widget")
    ap.add_argument("--builds", type=int, default=3, help="from-scratch builds per widget")
    args = ap.parse_args()
    print(f"{os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.2f} (other work on the machine slows all columns)")
    head = (f"{'widget':40s} {'update med':>10s} {'worst':>8s} {'full redraw':>11s} {'rebuild':>8s} "
            f"{'rebuild/update':>14s} {'updates/s':>9s} {'CPU/update':>10s} {'updates/CPU-s':>13s}")
    print(head)
    print("-" * len(head))
    for name, make, change in cases():
        w = make()
        change(w, 0)  # warm up
        cpu: list[float] = []
        def step(k: int, w: Any = w, change: Callable[[Any, int], object] = change) -> None:
            change(w, k + 1)

        upd = timed(step, args.n, cpu)

        def full(k: int, w: Any = w, change: Callable[[Any, int], object] = change) -> None:
            w.blitter.invalidate()
            change(w, k + 1)

        # full redraw: the same change, with the kept background thrown away first
        fullt = timed(full, max(args.n // 4, 3))
        w.blitter.invalidate()
        rebuild = timed(functools.partial(_rebuild, make), args.builds)
        med = float(np.median(upd))
        print(f"{name:40s} {1000 * med:8.1f}ms {1000 * upd.max():6.1f}ms {1000 * np.median(fullt):9.1f}ms "
              f"{1000 * np.median(rebuild):6.0f}ms {np.median(rebuild) / med:13.1f}x {1 / med:9.1f} "
              f"{1000 * np.median(cpu):8.1f}ms {1 / np.median(cpu):13.1f}")
    print("goals: rebuild/update >= 3x, updates/s >= 10 (a slider change includes the PNG sent to the browser).")
    print("'updates/s' is wall-clock on this machine as loaded now; 'updates/CPU-s' counts only this process's")
    print("CPU time, i.e. what one free core gives.")


if __name__ == "__main__":
    main()
