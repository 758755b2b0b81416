"""Every live view in light and dark mode: what it draws keeps its contrast on its own ground.

One harness page mounts the five views once (``live_theme_harness.html``);
the test then switches the page between the book's light mode, its dark mode
(``html[data-theme]``, as pydata-sphinx-theme sets it) and a page without a
theme whose reader asks for dark colours (``prefers-color-scheme``, as in a
deck), and reads the computed colours of every drawn element in the browser:

- text (HTML and SVG) at least 4.5:1 against what is behind it (WCAG 1.4.3);
- a number on a coloured dot at least 4.5:1 against the dot;
- lines, arrows, dots and legend keys at least 3:1 against the view's ground
  (WCAG 1.4.11); colours with alpha are blended over the ground first.

Left out, as carrying no meaning: the grid, faint rules and panel borders
(palette.js ``DECOR``), a fill equal to the ground (a hollow joint) and
tints under half opacity (the ring of a drag handle). The ratios of the
palette's table itself are checked without a browser in
``tests/test_live_palette_contrast.py``.
"""

from __future__ import annotations

import math
from pathlib import Path

import bookcheck
import pytest
from live_data import DATA_JS, SHOWN_JS

from jacobians.widgets.live import VIEWS

ROOT = Path(__file__).resolve().parents[2]

#: [host id, view, model]: every registered view, with its spec's example options
MODELS = [[f"v-{name.replace('_', '-')}", name, spec.model_from_options(spec.example)] for name, spec in VIEWS.items()]

CONTRAST_JS = r"""(el) => {
  const parse = (s) => {
    let m = s.match(/rgba?\(([\d.]+),\s*([\d.]+),\s*([\d.]+)(?:,\s*([\d.]+))?\)/);
    if (m) return [+m[1], +m[2], +m[3], m[4] === undefined ? 1 : +m[4]];
    m = s.match(/color\(srgb ([\d.e-]+) ([\d.e-]+) ([\d.e-]+)(?: \/ ([\d.e-]+))?\)/);
    if (m) return [255 * m[1], 255 * m[2], 255 * m[3], m[4] === undefined ? 1 : +m[4]];
    return null;
  };
  const hex = (h) => [1, 3, 5].map((i) => parseInt(h.trim().slice(i, i + 2), 16));
  const lum = (c) => {
    const ch = (v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; };
    return 0.2126 * ch(c[0]) + 0.7152 * ch(c[1]) + 0.0722 * ch(c[2]);
  };
  const ratio = (a, b) => { const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p); return (x + 0.05) / (y + 0.05); };
  const over = (c, bg, alpha) => c.slice(0, 3).map((v, i) => alpha * v + (1 - alpha) * bg[i]);
  const same = (a, b) => Math.max(...[0, 1, 2].map((i) => Math.abs(a[i] - b[i]))) < 1.5;
  const cs = getComputedStyle(el);
  const ground = parse(cs.backgroundColor);
  const decor = ["--jl-grid", "--jl-faint", "--jl-border", "--jl-paper"].map((v) => hex(cs.getPropertyValue(v)));
  const out = { ground, fails: [], checked: 0 };
  const name = (e) => `${e.tagName.toLowerCase()}${e.getAttribute("class") ? "." + e.getAttribute("class").split(" ")[0] : ""}`;
  const seen = (e) => e.checkVisibility({ visibilityProperty: true, opacityProperty: true })
    && !e.closest(".jl-sr, [hidden]");
  const check = (e, what, colour, alpha, need) => {
    const c = parse(colour);
    if (!c) return;
    const a = c[3] * alpha;
    if (a < 0.5) return;  // a tint
    const drawn = over(c, ground, a);
    if (what !== "text" && decor.some((d) => same(d, drawn))) return;
    out.checked++;
    const r = ratio(drawn, ground);
    if (r < need) out.fails.push(`${name(e)} ${what} ${colour} ${r.toFixed(2)}:1 < ${need}`);
  };
  for (const e of el.querySelectorAll("svg *")) {
    if (!seen(e)) continue;
    const s = getComputedStyle(e);
    const alpha = Number(s.opacity);
    if (e.tagName === "text" || e.tagName === "tspan") {
      const dot = e.previousElementSibling;  // a number drawn on a dot (the columns view's axis keys)
      const onDot = dot && dot.classList.contains("jl-axis-key") ? parse(getComputedStyle(dot).fill) : null;
      if (onDot) {
        out.checked++;
        const r = ratio(parse(s.fill), onDot);
        if (r < 4.5) out.fails.push(`${name(e)} on its dot ${s.fill} on ${onDot} ${r.toFixed(2)}:1 < 4.5`);
      } else if (e.textContent.trim()) check(e, "text", s.fill, alpha * Number(s.fillOpacity), 4.5);
    } else if (["line", "polyline", "polygon", "path", "circle", "ellipse", "rect"].includes(e.tagName)) {
      if (s.stroke !== "none" && parseFloat(s.strokeWidth) > 0) check(e, "stroke", s.stroke, alpha * Number(s.strokeOpacity), 3);
      if (s.fill !== "none" && e.tagName !== "line") check(e, "fill", s.fill, alpha * Number(s.fillOpacity), 3);
    }
  }
  for (const e of el.querySelectorAll("*")) {
    if (e.closest("svg") || !seen(e)) continue;
    const s = getComputedStyle(e);
    if (e.classList.contains("jl-key")) {
      const key = parse(s.backgroundColor)[3] > 0 ? s.backgroundColor : s.borderTopColor;
      check(e, "key", key, 1, 3);
      continue;
    }
    if (![...e.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim())) continue;
    let behind = ground;
    for (let p = e; p && p !== el.parentElement; p = p.parentElement) {
      const b = parse(getComputedStyle(p).backgroundColor);
      if (b && b[3] > 0) { behind = over(b, ground, b[3]); break; }
    }
    const c = parse(s.color);
    out.checked++;
    const r = ratio(c, behind);
    if (r < 4.5) out.fails.push(`${name(e)} "${e.textContent.trim().slice(0, 30)}" ${s.color} ${r.toFixed(2)}:1 < 4.5`);
  }
  return out;
}"""


@pytest.fixture(scope="module")
def themed(browser_context):
    with bookcheck.BookServer(ROOT) as server:
        page = browser_context.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.set_viewport_size({"width": 1100, "height": 900})
        page.goto(server.base + "tests/browser/live_theme_harness.html", wait_until="load")
        page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
        page.evaluate("(m) => window.mountAll(m)", MODELS)
        yield page, errors
        page.emulate_media(color_scheme="light")
        page.close()


MODES = {  # the page's theme attribute, the reader's colour scheme, the ground expected
    "book light": ("light", "dark", "light"),
    "book dark": ("dark", "light", "dark"),
    "deck, reader asks dark": (None, "dark", "dark"),
}


@pytest.mark.parametrize("mode", list(MODES))
def test_every_view_keeps_its_contrast(themed, mode):
    page, errors = themed
    theme, scheme, want = MODES[mode]
    page.emulate_media(color_scheme=scheme)  # the book's attribute must win over the reader's scheme
    page.evaluate("(t) => t ? document.documentElement.setAttribute('data-theme', t)"
                  " : document.documentElement.removeAttribute('data-theme')", theme)
    problems = []
    for view_id, view, _ in MODELS:
        got = page.eval_on_selector(f"#{view_id}", CONTRAST_JS)
        dark = sum(got["ground"][:3]) < 3 * 64
        assert dark == (want == "dark"), f"{view}: ground {got['ground']} in {mode}"
        assert got["checked"] > 20, f"{view}: only {got['checked']} colours checked"
        problems += [f"{view}: {f}" for f in got["fails"]]
    assert not problems, "\n".join(problems)
    assert errors == []


def test_every_view_writes_the_same_data_keys(themed):
    """One contract for what a view shows on its host element (AUTHORING.md, "Adding a live view"): the same
    keys in every view, read by every test through live_data.DATA_JS, with each view's own keys beside them."""
    page, errors = themed
    for view_id, view, model in MODELS:
        got = page.eval_on_selector(f"#{view_id}", DATA_JS)
        common = {"view", "ready", "theta", "lmSuppressShortcuts"}
        assert set(got) == common | VIEWS[view].data_keys, f"{view}: {sorted(got)}"  # its own keys: the spec's
        assert got["view"] == view and got["ready"] == 1
        # the joints of the arm shown: the model's screw axes (a view with several arms: the one shown)
        S = model["S"] if "S" in model else model["wrists"][model["wrist"]]["S"]
        n = len(S[0])
        theta = got["theta"]
        assert len(theta) == n and all(isinstance(t, (int, float)) and math.isfinite(t) for t in theta), theta
        assert got.get("level", "ok") in {"ok", "warning", "singular", "wrist"}
        assert got.get("playing", 0) == 0 and isinstance(got.get("step", 0), int)
        check = VIEWS[view].check
        assert check is not None, f"{view}: its spec has no check"
        check(page.eval_on_selector(f"#{view_id}", SHOWN_JS))  # what it shows is the library's (raises if not)
    assert errors == []
