// Drawing helpers shared by the planar live views: the Okabe–Ito
// palette of jacobians.plotting.style, one style sheet (text >= 14 px), SVG and
// HTML element factories, arrows, and number formatting that never shows NaN.

export const SVGNS = "http://www.w3.org/2000/svg";
// Okabe–Ito's orange (#E69F00, 2.2:1 on white) and sky blue (#56B4E9, 2.3:1) are too light for a line
// on the views' white ground (WCAG asks 3:1 of graphics): the views draw them darker, same hue, and
// the grey of the frame axes is #767676 (4.5:1), not #999999 (2.8:1).
const ON_WHITE = { "#E69F00": "#B07800", "#56B4E9": "#3388BB", "#999999": "#767676" };
/** A colour of the palette as a line or fill on white: at least 3:1. */
export const graphic = (c) => ON_WHITE[String(c).toUpperCase()] || c;
// Text in a colour must reach 4.5:1 on white: the darker shade of each hue (same hue, lower lightness).
const INK = { "#D55E00": "#B35000", "#009E73": "#007A5A", "#CC79A7": "#9E5584", "#E69F00": "#9A6700",
  "#56B4E9": "#2A6F9E", "#999999": "#767676" };
/** A colour of the palette as text on white: at least 4.5:1. */
export const ink = (c) => INK[String(c).toUpperCase()] || c;
export const PALETTE = {
  link: "#0072B2", joint: "#000000", muted: graphic("#999999"), velocity: "#D55E00", force: "#009E73",
  path: graphic("#E69F00"), ok: "#009E73", warning: graphic("#E69F00"), singular: "#D55E00",
};
export const COLUMN_COLORS = ["#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"].map(graphic);
export const columnColor = (i) => COLUMN_COLORS[i % COLUMN_COLORS.length];

const CSS = `
.jac-live{font-size:16px;line-height:1.35;max-width:100%;box-sizing:border-box;margin:0.5em 0 1.5em;contain:layout}
.jac-live *{box-sizing:border-box}
.jac-live .jl-wrap{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.jac-live .jl-plot{flex:1 1 300px;max-width:460px;min-width:0}
.jac-live .jl-plot svg{width:100%;height:auto;display:block}
.jac-live .jl-handle,.jac-live .jl-joint-handle{cursor:grab;touch-action:none}
.jac-live .jl-draw{touch-action:none}
.jac-live .jl-side{flex:1 1 260px;min-width:0}
.jac-live label{display:block;font-size:16px}
.jac-live input[type=range]{width:100%;margin:2px 0 8px}
.jac-live select{font-size:16px;margin-left:6px;max-width:100%}
.jac-live button{font-size:16px;margin:2px 6px 6px 0;padding:3px 10px;min-height:32px}
.jac-live table{border-collapse:collapse;margin:8px 0;font-size:15px;font-variant-numeric:tabular-nums}
.jac-live td,.jac-live th{padding:1px 8px;text-align:right;border:0}
.jac-live td{min-width:4.2em}
.jac-live caption{caption-side:top;text-align:left;font-size:15px;white-space:normal}
.jac-live sub{font-size:14px;line-height:1}
.jac-live .jl-status{font-size:15px;margin:4px 0}
.jac-live .jl-banner{font-size:16px;font-weight:bold;padding:4px 8px;border:3px solid;border-radius:6px;margin:6px 0}
.jac-live .jl-legend{font-size:14px;margin:4px 0 0;padding:0;list-style:none}
.jac-live .jl-legend li{margin:0}
.jac-live .jl-key{display:inline-block;width:18px;height:4px;vertical-align:middle;margin-right:6px}
.jac-live .jl-row{display:flex;flex-wrap:wrap;align-items:center;gap:4px}
.jac-live .jl-sr{display:block;width:1px;height:1px;margin:0 0 -1px;padding:0;overflow:hidden;clip-path:inset(50%);white-space:nowrap;border:0}
.jac-live input:focus-visible,.jac-live select:focus-visible,.jac-live button:focus-visible{outline:3px solid var(--pst-color-accent,#0072B2);outline-offset:2px}
`;

export function injectStyle(doc) {
  if (doc.getElementById("jac-live-style")) return;
  const s = doc.createElement("style");
  s.id = "jac-live-style";
  s.textContent = CSS;
  doc.head.appendChild(s);
}

/** A number with fixed decimals, never "-0.00" (a true minus sign otherwise), "—" if not finite. */
export function fixed(x, digits = 2) {
  if (!Number.isFinite(x)) return "—";
  const s = x.toFixed(digits);
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s.replace("-", "\u2212");
}

export function svg(tag, attrs = {}, parent = null) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (parent) parent.appendChild(e);
  return e;
}

export function html(tag, attrs = {}, parent = null, text = null) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== null) e.textContent = text;
  if (parent) parent.appendChild(e);
  return e;
}

/**
 * A polite live region, read by screen readers and hidden from sight, and `say(text)` to fill it.
 * A slider dragged or a run playing changes the numbers many times a second; `say` waits until
 * they have been still for `quietMs` and then announces the last text once (never the same text
 * twice in a row), so a listener hears where the view settled, not every step on the way.
 */
export function announcer(parent, quietMs = 900) {
  const region = html("p", { class: "jl-sr", "aria-live": "polite", "aria-atomic": "true" }, parent);
  let timer = null;
  let last = "";
  const say = (text) => {
    if (timer !== null) clearTimeout(timer);
    timer = setTimeout(() => {
      timer = null;
      if (text !== last) region.textContent = last = text;
    }, quietMs);
  };
  say.region = region;
  say.cancel = () => { if (timer !== null) clearTimeout(timer); timer = null; };
  return say;
}

/** Append text with a subscript (e.g. J_s) to `parent`. */
export function sub(parent, [base, index]) {
  parent.append(base);
  if (index) html("sub", {}, parent, index);
  return parent;
}

/** An arrow (shaft + head) in a <g>; hidden when shorter than `tiny`. */
export function makeArrow(parent, color, width) {
  const g = svg("g", { fill: color, stroke: color }, parent);
  const line = svg("line", { "stroke-width": width, "vector-effect": "non-scaling-stroke", "stroke-linecap": "round" }, g);
  const head = svg("polygon", { stroke: "none" }, g);
  return { g, line, head };
}

export function setArrow(a, p, d, headLen, tiny) {
  const L = Math.hypot(d[0], d[1]);
  if (!(L > tiny)) {
    a.g.setAttribute("visibility", "hidden");
    return;
  }
  a.g.setAttribute("visibility", "visible");
  const ux = d[0] / L;
  const uy = d[1] / L;
  const h = Math.min(headLen, 0.45 * L);
  const tx = p[0] + d[0];
  const ty = p[1] + d[1];
  const bx = tx - h * ux;
  const by = ty - h * uy;
  const w = 0.45 * h;
  a.line.setAttribute("x1", p[0]);
  a.line.setAttribute("y1", p[1]);
  a.line.setAttribute("x2", bx);
  a.line.setAttribute("y2", by);
  a.head.setAttribute("points", `${tx},${ty} ${bx - w * uy},${by + w * ux} ${bx + w * uy},${by - w * ux}`);
}

/** An SVG square drawing of half-width R (world metres, y up), a light grid and the base; returns {root, world}. */
export function planarCanvas(parent, R, reach, label) {
  const root = svg("svg", { viewBox: `${-R} ${-R} ${2 * R} ${2 * R}`, role: "img", "aria-label": label }, parent);
  const world = svg("g", { transform: "scale(1,-1)" }, root);
  const grid = svg("g", { stroke: "#dddddd", "stroke-width": 1 }, world);
  for (let k = -Math.floor(R); k <= Math.floor(R); k++) {
    svg("line", { x1: k, y1: -R, x2: k, y2: R, "vector-effect": "non-scaling-stroke" }, grid);
    svg("line", { x1: -R, y1: k, x2: R, y2: k, "vector-effect": "non-scaling-stroke" }, grid);
  }
  const b = 0.07 * reach;
  svg("polygon", { points: `0,0 ${-b},${-1.6 * b} ${b},${-1.6 * b}`, fill: PALETTE.muted }, world);
  return { root, world };
}

/** Pointer position in the drawing's world coordinates (y up), or null. */
export function toWorld(root, ev) {
  const m = root.getScreenCTM();
  if (!m) return null;
  const q = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(m.inverse());
  return Number.isFinite(q.x) && Number.isFinite(q.y) ? [q.x, -q.y] : null;
}

/** Capture the pointer on `el` (a synthetic event has none to capture). */
export function capture(el, ev) {
  try {
    el.setPointerCapture(ev.pointerId);
  } catch {
    // no active pointer
  }
}

/** Ellipse attributes: centre c, semi-axes a >= b along the unit column u of a 2×2 `directions`. */
export function setEllipse(e, c, a, b, directions, minAxis) {
  const ang = (Math.atan2(directions[1][0], directions[0][0]) * 180) / Math.PI;
  e.setAttribute("cx", c[0]);
  e.setAttribute("cy", c[1]);
  e.setAttribute("rx", Math.max(a, minAxis));
  e.setAttribute("ry", Math.max(b, minAxis));
  e.setAttribute("transform", `rotate(${Number.isFinite(ang) ? ang : 0} ${c[0]} ${c[1]})`);
}

/**
 * JupyterLab (Lumino) handles keys before the page does, with bindings whose selectors can match a
 * focused control in an output; the attribute data-lm-suppress-shortcuts on the view and on each of
 * its controls hands the keys to them. A static page ignores it.
 */
export function suppressShortcuts(el) {
  el.setAttribute("data-lm-suppress-shortcuts", "true");
  for (const c of el.querySelectorAll("input, select, button")) c.setAttribute("data-lm-suppress-shortcuts", "true");
}

/**
 * touch-action on an SVG shape is not honoured (Chromium cancels the pointer once the finger pans):
 * a touch that starts on `el` must not scroll the page, so its touchstart is cancelled. The rest of
 * the drawing still scrolls the page. Returns the listener's remover.
 */
export function holdTouch(el) {
  const f = (ev) => ev.preventDefault();
  el.addEventListener("touchstart", f, { passive: false });
  return () => el.removeEventListener("touchstart", f);
}
