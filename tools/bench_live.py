"""How fast is one update of a live view's kinematics in headless Chromium? Prints, never asserts.

One update of a planar 3R arm: forward kinematics, the geometric Jacobian (with
the other two in the same sweep) and the velocity and force ellipse axes of its
x, y rows, by ``lib/jacobians/widgets/live/kinematics.js``. Timed over 2000 random
configurations (seeded), each one alone with ``performance.now()`` (the page
is cross-origin isolated, so the clock is fine-grained), in two forms:

* compute only;
* compute plus a stand-in redraw: an SVG with the three links and the ellipse,
  and the 6×3 matrix written as text, then a forced layout
  (``getBoundingClientRect``). The real views draw more.

Then the real views, mounted on ``tests/browser/live_view_harness.html`` from
the directive's models, one update at a time, each followed by a forced layout
(``getBoundingClientRect`` of the view): the planar explorer (2R and 3R) on a
slider input and on a tool drag (``pointermove``: up to 60 DLS iterations),
the resolved-rate view on a step (a Play frame) and on a damping change (the
whole 160-step run again), the story views of chapters 1, 3 and 7 on a time
slider input (one frame of the replay).

Also prints the size of every module under ``lib/jacobians/widgets/live/`` and the modules
each view's page loads (its import graph). Budgets: one update,
compute plus redraw with forced layout, median <= 4 ms and worst <= 16 ms;
live modules <= 150 KB per page.

    .venv/bin/python -m tools.bench_live [--n 2000]
"""

from __future__ import annotations

import argparse
import functools
import http.server
import os
import re
import shutil
import statistics
import tempfile
import threading
from pathlib import Path
from typing import Any

import jacobians as jac

ROOT = Path(__file__).resolve().parent.parent
LIVE = ROOT / "lib" / "jacobians" / "widgets" / "live"
HARNESS = "tests/browser/live_harness.html"
VIEW_HARNESS = "tests/browser/live_view_harness.html"
CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]

BENCH_JS = """({S, M, n, seed, redraw}) => {
  const K = window.K, chain = K.makeChain(S, M);
  let s = seed >>> 0;
  const rand = () => { s = (1664525 * s + 1013904223) >>> 0; return s / 4294967296; };
  const NS = "http://www.w3.org/2000/svg";
  let svg, links, ell, pre;
  if (redraw) {
    svg = document.createElementNS(NS, "svg");
    svg.setAttribute("viewBox", "-3.5 -3.5 7 7"); svg.setAttribute("width", "400"); svg.setAttribute("height", "400");
    links = [0, 1, 2].map(() => { const l = document.createElementNS(NS, "polyline"); svg.append(l); return l; });
    ell = document.createElementNS(NS, "ellipse"); svg.append(ell);
    pre = document.createElement("pre");
    document.body.append(svg, pre);
  }
  const times = [];
  let sink = 0;
  for (let k = 0; k < n; k++) {
    const th = [0, 1, 2].map(() => (2 * rand() - 1) * Math.PI);
    const t0 = performance.now();
    const e = K.evaluate(chain, th);
    const Jv = [e.Jg[3], e.Jg[4]];
    const vel = K.velocityEllipsoid(Jv);
    const force = K.forceEllipsoid(Jv);
    if (redraw) {
      let x = 0, y = 0, a = 0;
      for (let i = 0; i < 3; i++) {
        a += th[i];
        const x2 = x + Math.cos(a), y2 = y + Math.sin(a);
        links[i].setAttribute("points", `${x},${-y} ${x2},${-y2}`);
        x = x2; y = y2;
      }
      const d = vel.directions;
      ell.setAttribute("cx", e.T[0][3]); ell.setAttribute("cy", -e.T[1][3]);
      ell.setAttribute("rx", vel.axes[0]); ell.setAttribute("ry", vel.axes[1]);
      const deg = -Math.atan2(d[1][0], d[0][0]) * 180 / Math.PI;
      ell.setAttribute("transform", `rotate(${deg} ${e.T[0][3]} ${-e.T[1][3]})`);
      pre.textContent = e.Jg.map((row) => row.map((v) => v.toFixed(3)).join("  ")).join("\\n");
      sink += svg.getBoundingClientRect().width + pre.getBoundingClientRect().height;
    }
    sink += force.axes[0];
    times.push(performance.now() - t0);
  }
  if (redraw) { svg.remove(); pre.remove(); }
  let a = performance.now(), b = a;
  while (b === a) b = performance.now();
  return {times, sink, resolution: b - a};
}"""


VIEW_JS = """async ({view, model, n, kind, seed}) => {
  await window.mountView(view, model);
  const el = document.getElementById("host");
  let s = seed >>> 0;
  const rand = () => { s = (1664525 * s + 1013904223) >>> 0; return s / 4294967296; };
  const sliders = el.querySelectorAll("input.jl-theta");
  const handle = el.querySelector("circle.jl-handle");
  const box = el.querySelector("svg").getBoundingClientRect();
  if (kind === "drag") handle.dispatchEvent(new PointerEvent("pointerdown", {bubbles: true, pointerId: 1}));
  const times = [];
  let sink = 0;
  for (let k = 0; k < n; k++) {
    const t0 = performance.now();
    if (kind === "slider") {
      const sl = sliders[k % sliders.length];
      sl.value = ((2 * rand() - 1) * Number(sl.max)).toFixed(2);  // the slider's own range (the model's limit)
      sl.dispatchEvent(new Event("input", {bubbles: true}));
    } else if (kind === "drag") {
      handle.dispatchEvent(new PointerEvent("pointermove", {bubbles: true, pointerId: 1,
        clientX: box.left + box.width * (0.1 + 0.8 * rand()), clientY: box.top + box.height * (0.1 + 0.8 * rand())}));
    } else if (kind === "story") {
      const st = el.querySelector("input.js-time");
      st.value = String(Math.floor(rand() * (+st.max + 1)));
      st.dispatchEvent(new Event("input", {bubbles: true}));
    } else if (kind === "step") {
      const st = el.querySelector("input.jr-step");
      st.value = String(k % 160);
      st.dispatchEvent(new Event("input", {bubbles: true}));
    } else {
      const lam = el.querySelector("input.jr-damping");
      lam.value = (-3 + 0.1 * (k % 31)).toFixed(1);
      lam.dispatchEvent(new Event("input", {bubbles: true}));
    }
    sink += el.getBoundingClientRect().height + el.offsetWidth;  // forced style and layout
    times.push(performance.now() - t0);
  }
  if (kind === "drag") handle.dispatchEvent(new PointerEvent("pointerup", {bubbles: true, pointerId: 1}));
  return {times, sink};
}"""

_IMPORT = re.compile(r"""(?:\bfrom|\bimport)\s*["']((?:\.\.?/)[A-Za-z0-9_]+\.js)["']""")


def page_modules(view: str) -> dict[str, int]:
    """The modules a page with ``view`` loads: host.js and the view's import graph, with their bytes."""
    seen: dict[str, int] = {}
    todo = ["host.js", f"{view}/view.js"]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        text = (LIVE / name).read_text(encoding="utf-8")
        seen[name] = len(text.encode("utf-8"))
        here = (LIVE / name).parent
        todo.extend((here / dep).resolve().relative_to(LIVE.resolve()).as_posix() for dep in _IMPORT.findall(text))
    return seen


class _IsolatedHandler(http.server.SimpleHTTPRequestHandler):
    """Serves the repository with the headers that give performance.now() its fine resolution."""

    def end_headers(self) -> None:
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        super().end_headers()

    def log_message(self, *args: Any) -> None:
        pass


def module_sizes() -> dict[str, int]:
    """Bytes of each ES module under lib/jacobians/widgets/live/."""
    return {p.relative_to(LIVE).as_posix(): p.stat().st_size for p in sorted(LIVE.rglob("*.js"))}


def run(n: int) -> dict[str, Any]:
    """Time n updates, compute only and with the stand-in redraw; the module sizes."""
    from playwright.sync_api import sync_playwright

    arm = jac.robots.planar_3r()
    handler = functools.partial(_IsolatedHandler, directory=str(ROOT))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    profile = tempfile.mkdtemp(prefix="bench-live-")
    out: dict[str, Any] = {}
    try:
        with sync_playwright() as p:
            context = p.chromium.launch_persistent_context(
                profile, executable_path=CHROMIUM, args=ARGS, headless=True,
                viewport={"width": 1280, "height": 900})
            page = context.new_page()
            page.goto(f"http://127.0.0.1:{httpd.server_port}/{HARNESS}", wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            out["isolated"] = page.evaluate("() => self.crossOriginIsolated")
            args = {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "n": n, "seed": 13}
            page.evaluate(BENCH_JS, {**args, "n": 200, "redraw": True})  # warm up the JIT
            for label, redraw in (("compute", False), ("compute + redraw", True)):
                r = page.evaluate(BENCH_JS, {**args, "redraw": redraw})
                out[label] = r["times"]
                out["resolution"] = r["resolution"]
            from jacobians.widgets.live import planar_model, resolved_rate_model

            page.goto(f"http://127.0.0.1:{httpd.server_port}/{VIEW_HARNESS}", wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            out["views"] = {}
            cases = [("planar_explorer 2R: slider", "planar_explorer", planar_model("planar_2r"), "slider"),
                     ("planar_explorer 3R: slider", "planar_explorer", planar_model("planar_3r"), "slider"),
                     ("planar_explorer 3R: tool drag", "planar_explorer", planar_model("planar_3r"), "drag"),
                     ("resolved_rate: step", "resolved_rate", resolved_rate_model(), "step"),
                     ("resolved_rate: damping (new run)", "resolved_rate",
                      resolved_rate_model(method="dls"), "damping")]
            from course.stories import STORIES, story_model

            cases += [(f"story {s}: time slider", "story", story_model(s), "story") for s in STORIES]
            for label, view, model, kind in cases:
                m = max(50, n // 10) if kind in ("drag", "damping") else n
                page.evaluate(VIEW_JS, {"view": view, "model": model, "n": 50, "kind": kind, "seed": 1})  # warm up
                out["views"][label] = page.evaluate(VIEW_JS, {"view": view, "model": model, "n": m, "kind": kind,
                                                              "seed": 17})["times"]
            context.close()
    finally:
        httpd.shutdown()
        httpd.server_close()
        shutil.rmtree(profile, ignore_errors=True)
    out["sizes"] = module_sizes()
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--n", type=int, default=2000, help="random configurations (default 2000)")
    opts = parser.parse_args(argv)
    out = run(opts.n)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"Live kinematics, planar 3R, {opts.n} random configurations, headless Chromium "
          f"(cross-origin isolated: {out['isolated']}, clock step {out['resolution'] * 1000:.1f} µs, "
          f"load average {load:.1f} on {os.cpu_count()} cores)")
    for label in ("compute", "compute + redraw"):
        t = out[label]
        print(f"  {label:18s} median {statistics.median(t):.4f} ms   mean {statistics.fmean(t):.4f} ms   "
              f"p99 {sorted(t)[int(0.99 * len(t))]:.3f} ms   worst {max(t):.3f} ms   "
              f"over 4 ms: {sum(x > 4 for x in t)}, over 16 ms: {sum(x > 16 for x in t)}")
    print("Live views, one update with forced layout (budget: median <= 4 ms, worst <= 16 ms):")
    for label, t in out["views"].items():
        ok = statistics.median(t) <= 4 and max(t) <= 16
        print(f"  {label:34s} n {len(t):5d}  median {statistics.median(t):.3f} ms   "
              f"p99 {sorted(t)[int(0.99 * len(t))]:.3f} ms   worst {max(t):.3f} ms   "
              f"over 16 ms: {sum(x > 16 for x in t)}   {'within' if ok else 'OVER'} budget")
    for view in ("planar_explorer", "resolved_rate", "story"):
        mods = page_modules(view)
        print(f"  a page with {view} loads {', '.join(f'{k} {v / 1024:.1f} KB' for k, v in mods.items())}: "
              f"{sum(mods.values()) / 1024:.1f} KB (budget 150 KB)")
    total = sum(out["sizes"].values())
    sizes = ", ".join(f"{k} {v / 1024:.1f} KB" for k, v in out["sizes"].items())
    print(f"  modules under lib/jacobians/widgets/live/: {sizes}; total {total / 1024:.1f} KB")
    print("  budgets: median <= 4 ms, worst <= 16 ms with redraw; <= 150 KB of live modules per page")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
