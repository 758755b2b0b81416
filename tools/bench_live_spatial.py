"""How long does one update of the 3-D live views take in headless Chromium? Prints, never asserts.

The real views, mounted on ``tests/browser/live_spatial_harness.html`` from the
models of ``jacobians.widgets.live_spatial``: ``columns_explorer`` (5R arm) and
``gimbal_lock`` (ZYZ wrist). One update is ``model.set(...)`` (what a slider's
input event does: the kinematics, the 3-D items projected and written, the
tables and texts) followed by a forced layout (``getBoundingClientRect`` of the
view and ``offsetHeight``), timed alone with ``performance.now()`` (the page is
served cross-origin isolated, so the clock is fine-grained). Kinds of update:

* columns: one joint angle at a time (random joint, random angle);
* gimbal θ₂: the chart along θ₂ stays, only the cursor moves;
* gimbal θ₃: the chart's 121 points are recomputed too (the worst case; θ₁ leaves the chart as it is);
* a turn of the camera (drag or arrow key): every item projected again.

Budget: median <= 4 ms, worst <= 16 ms. Also prints the bytes of
the modules each page loads.

    .venv/bin/python -m tools.bench_live_spatial [--n 500]
"""

from __future__ import annotations

import argparse
import functools
import http.server
import importlib
import statistics
import sys
import threading
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "_ext")]
spatial: Any = importlib.import_module("jacobians.widgets.live_spatial")  # the 3-D views' model builders

LIVE = ROOT / "lib" / "jacobians" / "widgets" / "live"
HARNESS = "tests/browser/live_spatial_harness.html"
CHROMIUM = "/usr/bin/chromium"
MODULES = {"columns_explorer": ["host.js", "kinematics.js", "view3d.js", "columns_explorer/view.js"],
           "gimbal_lock": ["host.js", "kinematics.js", "view3d.js", "gimbal_lock/view.js"]}

BENCH_JS = """({kind, n, seed}) => {
  const el = document.getElementById("host"), model = window.liveModel;
  let s = seed >>> 0;
  const rand = () => { s = (1664525 * s + 1013904223) >>> 0; return s / 4294967296; };
  const times = [];
  let sink = 0;
  for (let k = 0; k < n; k++) {
    const th = (model.get("theta") || []).slice();
    const t0 = performance.now();
    if (kind === "camera") {
      const v = el.jacView;
      v.setCamera(v.camera.azimuth + 0.05, Math.sin(k / 7));
    } else {
      const i = kind === "joint" ? Math.floor(rand() * th.length) : kind === "theta2" ? 1 : 2;
      th[i] = (2 * rand() - 1) * 3.1;
      model.set("theta", th);
    }
    sink += el.getBoundingClientRect().height + el.offsetHeight;
    times.push(performance.now() - t0);
  }
  return {times, sink};
}"""


class _IsolatedHandler(http.server.SimpleHTTPRequestHandler):
    """Serves the repository with the headers that give performance.now() its fine resolution."""

    def end_headers(self) -> None:
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        super().end_headers()

    def log_message(self, *args: Any) -> None:
        pass


def run(n: int) -> list[tuple[str, list[float]]]:
    from playwright.sync_api import sync_playwright

    handler = functools.partial(_IsolatedHandler, directory=str(ROOT))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{httpd.server_address[1]}/"
    out: list[tuple[str, list[float]]] = []
    cases = [("columns 5R: one joint", "columns_explorer", spatial.columns_model(), "joint"),
             ("columns 5R: turn the camera", "columns_explorer", spatial.columns_model(), "camera"),
             ("gimbal: θ2 (chart kept)", "gimbal_lock", spatial.gimbal_model(), "theta2"),
             ("gimbal: θ3 (chart of 121 points redone)", "gimbal_lock", spatial.gimbal_model(), "theta3"),
             ("gimbal: turn the camera", "gimbal_lock", spatial.gimbal_model(), "camera")]
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            page.goto(base + HARNESS, wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached")
            for label, view, model, kind in cases:
                page.evaluate("([v, m]) => window.mountView(v, m)", [view, model])
                page.evaluate(BENCH_JS, {"kind": kind, "n": 50, "seed": 1})  # warm up the JIT
                got = page.evaluate(BENCH_JS, {"kind": kind, "n": n, "seed": 7})
                out.append((label, got["times"]))
            browser.close()
    finally:
        httpd.shutdown()
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=500, help="updates timed per case")
    args = parser.parse_args(argv)
    print("3-D live views: one update = model.set + redraw + forced layout (ms), headless Chromium")
    print(f"{'case':46s} {'median':>7s} {'p99':>7s} {'worst':>7s}   budget: median <= 4, worst <= 16")
    for label, times in run(args.n):
        t = sorted(times)
        p99 = t[min(len(t) - 1, int(0.99 * len(t)))]
        flag = "" if statistics.median(t) <= 4 and t[-1] <= 16 else "   OVER BUDGET"
        print(f"{label:46s} {statistics.median(t):7.3f} {p99:7.3f} {t[-1]:7.3f}{flag}")
    for view, files in MODULES.items():
        sizes = {f: (LIVE / f).stat().st_size for f in files}
        print(f"modules a {view} page loads: {sum(sizes.values()) / 1000:.1f} KB ("
              + ", ".join(f"{f} {b / 1000:.1f}" for f, b in sizes.items()) + ")")


if __name__ == "__main__":
    main()
