"""Shared by test_live_columns.py and test_live_gimbal.py: the harness page, the camera, fit and offline checks.

The 3-D views draw in SVG units: a world point p goes to
``x = s (p - c)·r``, ``y = -s (p - c)·u`` with ``s = 200 / extent``, c the
centre, r and u the camera's right and up vectors (``lib/jacobians/widgets/live/view3d.js``).
:func:`project` is that map in numpy, so a test can say where the library's
points must be drawn.
"""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import urlsplit

import bookcheck
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
HARNESS = "tests/browser/live_spatial_harness.html"
SVG_DIGITS = 0.006  # coordinates are written with 2 decimals
KEY_STEP = np.radians(5.0)

FIT_JS = """(el) => {
  const box = el.getBoundingClientRect();
  const out = [];
  for (const e of el.querySelectorAll("*")) {
    if (e.closest("svg") && e.tagName !== "svg") continue;  // inside a drawing: clipped by it
    const r = e.getBoundingClientRect();
    if (r.width && (r.right > box.right + 0.5 || r.left < box.left - 0.5)) out.push(e.tagName + "." + e.className);
  }
  const small = [...el.querySelectorAll("label, output, td, th, caption, p, li, option, select, sub")]
    .filter((e) => e.textContent.trim() && parseFloat(getComputedStyle(e).fontSize) < 14)
    .map((e) => e.tagName + ": " + parseFloat(getComputedStyle(e).fontSize));
  // SVG text: its font size in SVG units times the drawing's pixels per unit
  const svgSmall = [];
  for (const s of el.querySelectorAll("svg")) {
    const k = s.getBoundingClientRect().width / s.viewBox.baseVal.width;
    for (const t of s.querySelectorAll("text")) {
      const px = parseFloat(getComputedStyle(t).fontSize) * k;
      if (t.textContent.trim() && t.getAttribute("visibility") !== "hidden" && px < 14) {
        svgSmall.push(t.textContent + ": " + px.toFixed(1));
      }
    }
  }
  return { overflow: out, small, svgSmall, scroll: el.scrollWidth - el.clientWidth, width: box.width,
           page: document.documentElement.scrollWidth - document.documentElement.clientWidth,
           touch: [...el.querySelectorAll("*")].filter((e) => getComputedStyle(e).touchAction === "none")
             .map((e) => e.tagName) };
}"""

CAMERA_JS = "(el) => ({azimuth: el.jacView.camera.azimuth, elevation: el.jacView.camera.elevation})"


def project(points, camera: dict, center, extent: float) -> np.ndarray:
    """World points (..., 3) -> SVG (x, y) of the 3-D view, as view3d.js's project."""
    a, e = camera["azimuth"], camera["elevation"]
    r = np.array([-np.sin(a), np.cos(a), 0.0])
    u = np.array([-np.sin(e) * np.cos(a), -np.sin(e) * np.sin(a), np.cos(e)])
    q = np.asarray(points, dtype=float) - np.asarray(center, dtype=float)
    s = 200.0 / extent
    return np.stack([s * (q @ r), -s * (q @ u)], axis=-1)


def line_ends(el, selector: str) -> np.ndarray:
    """(k, 2, 2): the drawn ends of the <line>s matching ``selector`` inside ``el``, in the order of the
    number their class ends with (``jl-axis-3``): the DOM order is the painter's, back to front."""
    got = el.evaluate("""(el, sel) => [...el.querySelectorAll(sel)]
      .map((l) => [+((l.getAttribute("class") || "").match(/-(\\d+)\\b/) || [0, 0])[1], l])
      .sort((a, b) => a[0] - b[0]).map(([, l]) =>
      [[+l.getAttribute("x1"), +l.getAttribute("y1")], [+l.getAttribute("x2"), +l.getAttribute("y2")]])""", selector)
    return np.array(got, dtype=float)


def number(text: str) -> float:
    """A displayed number ("−0.30", "1.23e5") as a float."""
    return float(text.replace("\u2212", "-"))


def no_negative_zero(cells) -> bool:
    return not any(re.fullmatch(r"[-\u2212]0\.0+", c) for row in cells for c in row)


def open_harness(context):
    """(page, open_view(view, model, width), seen) on the harness page; the caller closes the page."""
    server = bookcheck.BookServer(ROOT)
    server.__enter__()
    page = context.new_page()
    seen: dict[str, list[str]] = {"console": [], "requests": [], "failed": []}
    page.on("console", lambda m: seen["console"].append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: seen["console"].append(str(e)))
    page.on("request", lambda r: seen["requests"].append(r.url))
    page.on("requestfailed", lambda r: seen["failed"].append(r.url))

    def open_view(view: str, model: dict, width: int = 1280):
        page.set_viewport_size({"width": width, "height": 900 if width > 500 else 844})
        page.goto(server.base + HARNESS, wait_until="load")
        page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
        page.evaluate("([v, m]) => window.mountView(v, m)", [view, model])
        return page.wait_for_selector("#host[data-ready='1']", state="attached", timeout=10_000)

    return page, open_view, seen, server


def foreign(requests: list[str], base: str) -> list[str]:
    host = urlsplit(base).netloc
    return [u for u in requests if not u.startswith("data:") and urlsplit(u).netloc != host]


def check_turning(page, el, center, extent, points, selector: str) -> None:
    """Arrow keys on the focused drawing turn it by 5°, a drag turns it; ``points`` (k, 2, 3) are drawn at ``selector``."""
    svg = el.query_selector("svg.jl-3d")
    assert svg.get_attribute("tabindex") == "0" and svg.get_attribute("aria-label")
    assert svg.get_attribute("aria-describedby") and el.query_selector(".jl-help").inner_text().startswith("Turn")
    cam0 = el.evaluate(CAMERA_JS)
    drawn0 = line_ends(el, selector)
    assert np.abs(drawn0 - project(points, cam0, center, extent)).max() < SVG_DIGITS
    svg.focus()
    assert page.evaluate("() => document.activeElement.tagName") == "svg"
    outline = svg.evaluate("(s) => getComputedStyle(s).outlineStyle + ' ' + getComputedStyle(s).outlineWidth")
    assert outline.startswith("solid") and not outline.endswith(" 0px"), outline  # a visible focus ring
    page.keyboard.press("ArrowLeft")
    page.keyboard.press("ArrowUp")
    cam1 = el.evaluate(CAMERA_JS)
    assert abs(cam1["azimuth"] - cam0["azimuth"] - KEY_STEP) < 1e-12
    assert abs(cam1["elevation"] - cam0["elevation"] - KEY_STEP) < 1e-12
    drawn1 = line_ends(el, selector)
    assert np.abs(drawn1 - drawn0).max() > 1.0  # it turned
    assert np.abs(drawn1 - project(points, cam1, center, extent)).max() < SVG_DIGITS
    page.keyboard.press("Home")
    assert el.evaluate(CAMERA_JS) == cam0
    # a drag of 60 px to the left, 20 px down: 0.01 rad per pixel
    box = svg.bounding_box()
    x0, y0 = box["x"] + box["width"] * 0.3, box["y"] + box["height"] * 0.3
    page.mouse.move(x0, y0)
    page.mouse.down()
    page.mouse.move(x0 - 30, y0 + 10)
    page.mouse.move(x0 - 60, y0 + 20)
    page.mouse.up()
    cam2 = el.evaluate(CAMERA_JS)
    assert abs(cam2["azimuth"] - cam0["azimuth"] - 0.6) < 0.02 and abs(cam2["elevation"] - cam0["elevation"] - 0.2) < 0.02
    assert np.abs(line_ends(el, selector) - project(points, cam2, center, extent)).max() < SVG_DIGITS
    page.keyboard.press("Home")
