// @ts-check
// The helpers every live view shares: the palette (palette.js, re-exported), one style sheet
// (text >= 14 px), SVG and HTML element factories, redraws that write only what changed, matrix
// tables, arrows, a polite announcer, and number formatting that never shows NaN.

/** @typedef {Record<string, string | number>} Attrs attributes of a new element */
/** @typedef {string | readonly [string, string]} SubText text, or [base, subscript] (J_s is ["J", "s"]) */
/** @typedef {[number, number]} Point2 a point of a planar drawing, world metres, y up */
/** @typedef {{g: SVGGElement, line: SVGLineElement, head: SVGPolygonElement}} Arrow2 */
/** @typedef {ReturnType<typeof matrixTable>} MatrixTable */

export { AXIS_COLORS, COLUMN_COLORS, PALETTE, columnColor, graphic, ink, tint } from "./palette.js";
import { PALETTE, THEME_CSS } from "./palette.js";

export const SVGNS = "http://www.w3.org/2000/svg";

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
.jac-live input:focus-visible,.jac-live select:focus-visible,.jac-live button:focus-visible{outline:3px solid var(--pst-color-accent,var(--jl-blue));outline-offset:2px}
`;

/** The style every view shares: the palette's custom properties and the layout above. */
export const BASE_CSS = THEME_CSS + CSS;

/**
 * Add a <style id=id> with `css` to the document's head, once (a second view of the same kind finds it).
 * @param {Document} doc
 * @param {string} id
 * @param {string} css
 */
export function injectStyle(doc, id, css) {
  if (doc.getElementById(id)) return;
  const s = doc.createElement("style");
  s.id = id;
  s.textContent = css;
  doc.head.appendChild(s);
}

/** A number with fixed decimals, never "-0.00" (a true minus sign otherwise), "—" if not finite.
 * @param {number} x
 * @param {number} [digits]
 * @returns {string}
 */
export function fixed(x, digits = 2) {
  if (!Number.isFinite(x)) return "—";
  const s = x.toFixed(digits);
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s.replace("-", "\u2212");
}

/**
 * A new SVG element with attributes, appended to `parent` if given.
 * @template {keyof SVGElementTagNameMap} K
 * @param {K} tag
 * @param {Attrs} [attrs]
 * @param {Element | null} [parent]
 * @returns {SVGElementTagNameMap[K]}
 */
export function svg(tag, attrs = {}, parent = null) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (parent) parent.appendChild(e);
  return e;
}

/**
 * A new HTML element with attributes and text, appended to `parent` if given.
 * @template {keyof HTMLElementTagNameMap} K
 * @param {K} tag
 * @param {Attrs} [attrs]
 * @param {Element | null} [parent]
 * @param {string | null} [text]
 * @returns {HTMLElementTagNameMap[K]}
 */
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
 * @param {Element} parent
 * @param {number} [quietMs]
 * @returns {Announcer}
 */
export function announcer(parent, quietMs = 900) {
  const region = html("p", { class: "jl-sr", "aria-live": "polite", "aria-atomic": "true" }, parent);
  /** @type {ReturnType<typeof setTimeout> | null} */
  let timer = null;
  let last = "";
  /** @param {string} text */
  const say = (text) => {
    if (timer !== null) clearTimeout(timer);
    timer = setTimeout(() => {
      timer = null;
      if (text !== last) region.textContent = last = text;
    }, quietMs);
  };
  const cancel = () => {
    if (timer !== null) clearTimeout(timer);
    timer = null;
  };
  return Object.assign(say, { region, cancel });
}
/** @typedef {((text: string) => void) & {region: HTMLParagraphElement, cancel: () => void}} Announcer */

/**
 * el.setAttribute(k, v) only when v differs from what this helper last wrote (a redraw writes little).
 * @param {Element & {jlAttrs?: Record<string, string>}} el
 * @param {string} k
 * @param {string | number} v
 */
export function put(el, k, v) {
  const c = el.jlAttrs || (el.jlAttrs = {});
  const s = String(v);
  if (c[k] !== s) {
    c[k] = s;
    el.setAttribute(k, s);
  }
}

/**
 * el.textContent = s only when it differs.
 * @param {Node & {jlText?: string}} el
 * @param {string} s
 */
export function text(el, s) {
  if (el.jlText !== s) {
    el.jlText = s;
    el.textContent = s;
  }
}

/** Append text, or text with a subscript (["J", "s"] gives J_s), to `parent`; returns parent.
 * @template {Element} E
 * @param {E} parent
 * @param {SubText} label
 * @returns {E}
 */
export function sub(parent, label) {
  if (typeof label === "string") {
    parent.append(label);
    return parent;
  }
  const [base, index] = label;
  parent.append(base);
  if (index) html("sub", {}, parent, index);
  return parent;
}

/** The rows of a twist or of a 6×n Jacobian: ω_x, ω_y, ω_z, v_x, v_y, v_z. */
/** @type {ReadonlyArray<readonly [string, string]>} */
export const TWIST_ROWS = [["ω", "x"], ["ω", "y"], ["ω", "z"], ["v", "x"], ["v", "y"], ["v", "z"]];

/**
 * A table of a matrix in `parent`: an empty caption (the caller writes it), a header row with an empty
 * corner and one head per column, a header cell per row; each label is text or [base, subscript].
 * @param {HTMLElement} parent
 * @param {string} cls its classes besides jl-matrix
 * @param {ReadonlyArray<SubText>} rows
 * @param {ReadonlyArray<SubText>} cols
 * @returns {{table: HTMLTableElement, caption: HTMLTableCaptionElement, heads: HTMLTableCellElement[],
 *   cells: HTMLTableCellElement[][]}} cells[r][c]
 */
export function matrixTable(parent, cls, rows, cols) {
  const table = /** @type {HTMLTableElement} */ (html("table", { class: `jl-matrix ${cls}` }, parent));
  const caption = /** @type {HTMLTableCaptionElement} */ (html("caption", {}, table));
  const hr = html("tr", {}, html("thead", {}, table));
  html("th", { scope: "col" }, hr, "");
  const heads = cols.map((c) => /** @type {HTMLTableCellElement} */ (sub(html("th", { scope: "col" }, hr), c)));
  const tbody = html("tbody", {}, table);
  const cells = rows.map((lab) => {
    const tr = html("tr", {}, tbody);
    sub(html("th", { scope: "row" }, tr), lab);
    return cols.map(() => /** @type {HTMLTableCellElement} */ (html("td", {}, tr, "")));
  });
  return { table, caption, heads, cells };
}

/**
 * An item of a legend: a key of `color` (a bar, or a dashed line), then the parts (text or [base, subscript]).
 * @param {HTMLUListElement} ul
 * @param {string} color
 * @param {ReadonlyArray<SubText>} parts
 * @param {boolean} [dashed]
 * @returns {HTMLLIElement}
 */
export function legendItem(ul, color, parts, dashed = false) {
  const li = html("li", {}, ul);
  const style = dashed ? `border-top:3px dashed ${color};height:0` : `background:${color}`;
  html("span", { class: "jl-key", style }, li);
  for (const p of parts) sub(li, p);
  return li;
}

/** An arrow (shaft + head) in a <g>; setArrow draws it.
 * @param {Element} parent
 * @param {string} color
 * @param {number} width stroke width, screen pixels
 * @returns {Arrow2}
 */
export function makeArrow(parent, color, width) {
  const g = svg("g", { fill: color, stroke: color }, parent);
  const line = svg("line", { "stroke-width": width, "vector-effect": "non-scaling-stroke", "stroke-linecap": "round" }, g);
  const head = svg("polygon", { stroke: "none" }, g);
  return { g, line, head };
}

/** Draw arrow `a` from p along d (world units); hidden when shorter than `tiny`.
 * @param {Arrow2} a
 * @param {ArrayLike<number>} p
 * @param {ArrayLike<number>} d
 * @param {number} headLen
 * @param {number} tiny
 */
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
  a.line.setAttribute("x1", String(p[0]));
  a.line.setAttribute("y1", String(p[1]));
  a.line.setAttribute("x2", String(bx));
  a.line.setAttribute("y2", String(by));
  a.head.setAttribute("points", `${tx},${ty} ${bx - w * uy},${by + w * ux} ${bx + w * uy},${by - w * ux}`);
}

/** An SVG square drawing of half-width R (world metres, y up), a light grid and the base; returns {root, world}.
 * @param {Element} parent
 * @param {number} R
 * @param {number} reach
 * @param {string} label its aria-label
 * @returns {{root: SVGSVGElement, world: SVGGElement}}
 */
export function planarCanvas(parent, R, reach, label) {
  const root = svg("svg", { viewBox: `${-R} ${-R} ${2 * R} ${2 * R}`, role: "img", "aria-label": label,
    fill: PALETTE.fg }, parent);
  const world = svg("g", { transform: "scale(1,-1)" }, root);
  const grid = svg("g", { stroke: PALETTE.grid, "stroke-width": 1 }, world);
  for (let k = -Math.floor(R); k <= Math.floor(R); k++) {
    svg("line", { x1: k, y1: -R, x2: k, y2: R, "vector-effect": "non-scaling-stroke" }, grid);
    svg("line", { x1: -R, y1: k, x2: R, y2: k, "vector-effect": "non-scaling-stroke" }, grid);
  }
  const b = 0.07 * reach;
  svg("polygon", { points: `0,0 ${-b},${-1.6 * b} ${b},${-1.6 * b}`, fill: PALETTE.muted }, world);
  return { root, world };
}

/** Pointer position in the drawing's world coordinates (y up), or null.
 * @param {SVGSVGElement} root
 * @param {{clientX: number, clientY: number}} ev
 * @returns {Point2 | null}
 */
export function toWorld(root, ev) {
  const m = root.getScreenCTM();
  if (!m) return null;
  const q = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(m.inverse());
  return Number.isFinite(q.x) && Number.isFinite(q.y) ? [q.x, -q.y] : null;
}

/** Capture the pointer on `el` (a synthetic event has none to capture).
 * @param {Element} el
 * @param {PointerEvent} ev
 */
export function capture(el, ev) {
  try {
    el.setPointerCapture(ev.pointerId);
  } catch {
    // no active pointer
  }
}

/** Ellipse attributes: centre c, semi-axes a >= b along the unit column u of a 2×2 `directions`.
 * @param {SVGEllipseElement} e
 * @param {ArrayLike<number>} c
 * @param {number} a
 * @param {number} b
 * @param {number[][]} directions
 * @param {number} minAxis
 */
export function setEllipse(e, c, a, b, directions, minAxis) {
  const ang = (Math.atan2(directions[1][0], directions[0][0]) * 180) / Math.PI;
  e.setAttribute("cx", String(c[0]));
  e.setAttribute("cy", String(c[1]));
  e.setAttribute("rx", String(Math.max(a, minAxis)));
  e.setAttribute("ry", String(Math.max(b, minAxis)));
  e.setAttribute("transform", `rotate(${Number.isFinite(ang) ? ang : 0} ${c[0]} ${c[1]})`);
}

/**
 * JupyterLab (Lumino) handles keys before the page does, with bindings whose selectors can match a
 * focused control in an output; the attribute data-lm-suppress-shortcuts on the view and on each of
 * its controls hands the keys to them. A static page ignores it.
 * @param {Element} el
 */
export function suppressShortcuts(el) {
  el.setAttribute("data-lm-suppress-shortcuts", "true");
  for (const c of el.querySelectorAll("input, select, button")) c.setAttribute("data-lm-suppress-shortcuts", "true");
}

/**
 * touch-action on an SVG shape is not honoured (Chromium cancels the pointer once the finger pans):
 * a touch that starts on `el` must not scroll the page, so its touchstart is cancelled. The rest of
 * the drawing still scrolls the page. Returns the listener's remover.
 * @param {Element} el
 * @returns {() => void}
 */
export function holdTouch(el) {
  /** @param {Event} ev */
  const f = (ev) => ev.preventDefault();
  el.addEventListener("touchstart", f, { passive: false });
  return () => el.removeEventListener("touchstart", f);
}

// ---- what every view's render shares: its start (build), its listeners (bind), its end

/** @typedef {import("./host.js").Model} Model */
/** @typedef {[EventTarget, string, (ev: any) => void]} Listener a listener to add: [target, type, handler] */

/**
 * The start of a view's build: the shared style and the view's own (each [id, css], added once to the page),
 * the classes on `el` (jac-live first), and an id prefix for the labels' `for` (unique on the page).
 * @param {HTMLElement} el
 * @param {{classes?: string[], styles?: [string, string][], prefix?: string}} [options]
 * @returns {{doc: Document, uid: string}}
 */
export function startView(el, { classes = [], styles = [], prefix = "jl" } = {}) {
  const doc = el.ownerDocument;
  injectStyle(doc, "jac-live-style", BASE_CSS);
  for (const [id, css] of styles) injectStyle(doc, id, css);
  el.classList.add("jac-live", ...classes);
  return { doc, uid: `${prefix}${Math.random().toString(36).slice(2, 9)}` };
}

/**
 * The common layout: <div class=jl-wrap> with a drawing box and a side box for the controls.
 * @param {HTMLElement} el
 * @param {string} [plotClass]
 * @returns {{wrap: HTMLDivElement, plot: HTMLDivElement, side: HTMLDivElement}}
 */
export function layout(el, plotClass = "jl-plot") {
  const wrap = html("div", { class: "jl-wrap" }, el);
  const plot = html("div", { class: plotClass }, wrap);
  const side = html("div", { class: "jl-side" }, wrap);
  return { wrap, plot, side };
}

/**
 * The joint sliders' range, ±limit rad: the model's `limit`, written by the library (jacobians.widgets.live.LIMIT,
 * the one place it is set). A model without one is an error, not a guess.
 * @param {Model} model
 * @returns {number}
 */
export function sliderLimit(model) {
  const limit = Number(model.get("limit"));
  if (!(limit > 0 && Number.isFinite(limit))) {
    throw new Error(`Expected the model's limit (the sliders' range, rad) as a positive number, got ${JSON.stringify(model.get("limit"))}`);
  }
  return limit;
}

/** θ with the joint's subscript digit: jointName(0) is "θ₁". @param {number} i 0-based @returns {string} */
export const jointName = (i) => `θ${String.fromCharCode(0x2081 + i)}`;

/**
 * One labelled slider a joint, in `parent`: <label for=id>[key] θᵢ = <output></label>, then
 * <input type=range class=jl-theta data-joint=i+1> (its accent the joint's colour when `color` is given).
 * @param {HTMLElement} parent
 * @param {number} n
 * @param {string} uid
 * @param {{min: number, max: number, step: number, value: (i: number) => number, color?: (i: number) => string,
 *   keys?: boolean}} options `keys`: a colour key in each label, coloured by the view
 * @returns {{sliders: HTMLInputElement[], values: HTMLOutputElement[], keys: HTMLSpanElement[]}}
 */
export function jointSliders(parent, n, uid, { min, max, step, value, color, keys = false }) {
  /** @type {HTMLInputElement[]} */
  const sliders = [];
  /** @type {HTMLOutputElement[]} */
  const values = [];
  /** @type {HTMLSpanElement[]} */
  const keyed = [];
  for (let i = 0; i < n; i++) {
    const id = `${uid}-t${i + 1}`;
    const label = html("label", { for: id }, parent);
    if (keys) keyed.push(html("span", { class: "jl-key", "aria-hidden": "true" }, label));
    label.append(`${jointName(i)} = `);
    values.push(html("output", { for: id, class: "jl-value" }, label));
    /** @type {Attrs} */
    const attrs = { type: "range", id, min, max, step, class: "jl-theta", "data-joint": i + 1 };
    if (color) attrs.style = `accent-color:${color(i)}`;
    const s = html("input", attrs, parent);
    s.value = String(value(i));
    sliders.push(s);
  }
  return { sliders, values, keys: keyed };
}

/**
 * A joint's angle shown (update): its output in degrees, the same words for a screen reader (not the slider's
 * radians), and the slider moved to `sliderValue` unless the reader holds it or it is within `tol` already.
 * @param {HTMLOutputElement} out
 * @param {HTMLInputElement} slider
 * @param {number} rad the angle
 * @param {number} sliderValue what the slider holds for it (radians or degrees, as the view's slider)
 * @param {number} [tol]
 */
export function showAngle(out, slider, rad, sliderValue, tol = 0) {
  const d = fixed((rad * 180) / Math.PI, 1);
  text(out, `${d}°`);
  put(slider, "aria-valuetext", `${d} degrees`);
  if (Math.abs(Number(slider.value) - sliderValue) > tol && slider.ownerDocument.activeElement !== slider) {
    slider.value = String(sliderValue);
  }
}

/**
 * Play / Pause on `button` (▶ Play, ❚❚ Pause, aria-pressed): `tick` every `ms` while playing;
 * `onChange(playing)` after each switch.
 * @param {HTMLButtonElement} button
 * @param {() => void} tick
 * @param {number} ms
 * @param {(playing: boolean) => void} [onChange]
 * @returns {{start: () => void, stop: () => void, toggle: () => void, playing: () => boolean}}
 */
export function player(button, tick, ms, onChange = () => {}) {
  /** @type {ReturnType<typeof setInterval> | null} */
  let timer = null;
  const stop = () => {
    if (timer !== null) clearInterval(timer);
    timer = null;
    button.textContent = "▶ Play";
    button.setAttribute("aria-pressed", "false");
    onChange(false);
  };
  const start = () => {
    if (timer !== null) return;
    timer = setInterval(tick, ms);
    button.textContent = "❚❚ Pause";
    button.setAttribute("aria-pressed", "true");
    onChange(true);
  };
  return { start, stop, toggle: () => (timer !== null ? stop() : start()), playing: () => timer !== null };
}

/**
 * Write `value` to the model's `key` and send it (to the kernel, in JupyterLab).
 * @param {Model} model
 * @param {string} key
 * @param {unknown} value
 */
export function save(model, key, value) {
  model.set(key, value);
  model.save_changes();
}

/**
 * Add the listeners, and redraw on a change of the model's `keys` (bind); returns the remover of all of them.
 * @param {Model} model
 * @param {string[]} keys
 * @param {() => void} redraw
 * @param {Listener[]} listeners
 * @returns {() => void}
 */
export function listen(model, keys, redraw, listeners) {
  const names = keys.map((k) => `change:${k}`).join(" ");
  for (const [t, type, f] of listeners) t.addEventListener(type, f);
  model.on(names, redraw);
  return () => {
    model.off(names, redraw);
    for (const [t, type, f] of listeners) t.removeEventListener(type, f);
  };
}

/**
 * What a view shows, for its readers (the tests, the bench, a deck's script), as the host element's data-*
 * attributes: every view writes `view`, and `theta` (the joint angles shown, rad), `level`, `step`, `playing`
 * when it has them; a view's own keys follow. A value is written as JSON, except a string, written bare
 * (data-level="warning", data-theta="[0.5,1.2]", data-step="40"). AUTHORING.md "Adding a live view" lists the keys.
 * @param {HTMLElement} el
 * @param {Record<string, string | number | boolean | readonly number[]>} data camelCase keys, as el.dataset
 */
export function publish(el, data) {
  for (const [k, v] of Object.entries(data)) {
    const s = typeof v === "string" ? v : JSON.stringify(v);
    if (el.dataset[k] !== s) el.dataset[k] = s;
  }
}

/**
 * The end of a view's render: the keys go to its controls in JupyterLab, the state (and the 3-D view) on `el` for
 * the tests, `data-ready`; returns the cleanup, which undoes `unbind` and empties `el`.
 * @param {HTMLElement} el
 * @param {object} state what the view shows (el.jacLive)
 * @param {() => void} unbind
 * @param {Record<string, unknown>} [more] more properties for `el` (jacView)
 * @returns {() => void}
 */
export function finishView(el, state, unbind, more = {}) {
  suppressShortcuts(el); // in JupyterLab a key in a control reaches the control, not a notebook shortcut
  Object.assign(el, { jacLive: state, ...more });
  return () => {
    unbind();
    el.textContent = "";
  };
}
