// @ts-check
// Resolved-rate motion of a planar arm, live: the tool follows a
// path the reader picks (the presets of jacobians.widgets.live.planar_path) or
// draws with the pointer, by θ̇ = J_v^# (ṗ_d + K (p_d − p)) with the
// pseudo-inverse or damped least squares (λ on a slider); the joint rates are
// plotted as the run goes. Play, pause and step from the buttons or the keys
// (P or K: play/pause, → or . : one step on, ← or , : one step back, when the
// focus is in the view). The run is velocity.resolved_rate, in kinematics.js.
//
// anywidget-compatible: render({model, el}) reads model.get(key) for S, M, Q,
// reach, name, path ("circle" | "to full reach" | "close past the base" |
// "drawn"), drawn (N×2 points of a drawn path, m), method ("pinv" | "dls"),
// damping (λ, m), step (shown step k), n_steps, duration (s), gain (1/s),
// rate_limit (rad/s, the plot's range); writes path, drawn, method, damping
// and step back and redraws on their "change:" events.

import { dlsRates, evaluate, makeChain, resolvedRate } from "../kinematics.js";
import {
  PALETTE, announcer, capture, columnColor, finishView, fixed, holdTouch, html, listen, planarCanvas, player, publish,
  save, startView, sub, svg, toWorld,
} from "../ui.js";

/** @typedef {import("../ui.js").Point2} Point2 */
/** @typedef {import("../host.js").Model} Model */
/** @typedef {import("../kinematics.js").Chain} Chain */
/** @typedef {import("../kinematics.js").RateMethod} RateMethod */
/** @typedef {import("../kinematics.js").RateRun} RateRun */
/** @typedef {import("../linalg.js").Vec} Vec */
/** @typedef {{t: number[], x: Vec[], v: Vec[]}} PlanarPath times, desired positions, their velocities */
/**
 * What a run depends on (the model's choices, checked).
 * @typedef {{path: string, drawn: Vec[] | null, method: RateMethod, damping: number, nSteps: number,
 *   duration: number, gain: number, reach: number}} RunOptions
 */
/** @typedef {{t: number[], xd: Vec[], theta0: Vec, run: RateRun}} Simulation */
/**
 * What the view shows (el.jacLive, read by the tests).
 * @typedef {{step: number, sim: Simulation | null, level: string | null, sigmaMin?: number, theta?: Vec,
 *   drawn?: Vec[] | null}} RateState
 */

const RUN_HELP = "Keys in the view: P play/pause, → or . one step on, ← or , one step back.";
const PEN_HELP = "Drawing: drag on the picture, or with the picture focused move the pen (+) with the arrow keys "
  + "(Shift: finer), Enter adds a point, Backspace removes one; the button again uses the path, Escape cancels.";
export const PATHS = ["circle", "to full reach", "close past the base"];
const METHODS = { pinv: "pseudo-inverse", dls: "damped least squares" };
const KEYS_ON = new Set(["ArrowRight", "."]);
const KEYS_BACK = new Set(["ArrowLeft", ","]);

/**
 * The preset paths of jacobians.widgets.live.planar_path: {t, x, v} (N times, N×2 positions and velocities).
 * @param {string} kind @param {number} reach @param {number} nSteps @param {number} [duration]
 * @returns {PlanarPath}
 */
export function planarPath(kind, reach, nSteps, duration = 4.0) {
  const T = duration;
  const t = Array.from({ length: nSteps }, (_, k) => (nSteps > 1 ? (T * k) / (nSteps - 1) : 0));
  if (kind === "circle") {
    const c = [0.45 * reach, 0.2 * reach], r = 0.3 * reach, w = (2 * Math.PI) / T;
    return { t, x: t.map((s) => [c[0] + r * Math.cos(w * s), c[1] + r * Math.sin(w * s)]),
      v: t.map((s) => [-r * w * Math.sin(w * s), r * w * Math.cos(w * s)]) };
  }
  /** @type {Record<string, Vec[]>} */
  const presets = { "to full reach": [[0.3 * reach, 0.5 * reach], [reach, 0]],
    "close past the base": [[0.6 * reach, 0.03 * reach], [-0.6 * reach, 0.03 * reach]] };
  const ends = presets[kind];
  if (!ends) throw new Error(`Expected path ${PATHS.map((p) => `"${p}"`).join(", ")}, got ${JSON.stringify(kind)}`);
  const [a, b] = ends;
  const d = [b[0] - a[0], b[1] - a[1]];
  return { t, x: t.map((s) => [a[0] + (s / T) * d[0], a[1] + (s / T) * d[1]]), v: t.map(() => [d[0] / T, d[1] / T]) };
}

/**
 * A drawn polyline resampled to N points evenly spaced along its length (null if it has no length).
 * @param {Vec[]} points @param {number} nSteps @returns {Vec[] | null}
 */
export function resample(points, nSteps) {
  const P = points.filter((p) => Number.isFinite(p[0]) && Number.isFinite(p[1]));
  const s = [0];
  for (let i = 1; i < P.length; i++) s.push(s[i - 1] + Math.hypot(P[i][0] - P[i - 1][0], P[i][1] - P[i - 1][1]));
  const total = s[s.length - 1];
  if (!(P.length >= 2 && total > 0)) return null;
  const out = [];
  let j = 0;
  for (let k = 0; k < nSteps; k++) {
    const u = (total * k) / (nSteps - 1);
    while (j < P.length - 2 && s[j + 1] < u) j++;
    const f = s[j + 1] > s[j] ? Math.min(1, Math.max(0, (u - s[j]) / (s[j + 1] - s[j]))) : 0;
    out.push([P[j][0] + f * (P[j + 1][0] - P[j][0]), P[j][1] + f * (P[j + 1][1] - P[j][1])]);
  }
  return out;
}

/**
 * The run's start, as jacobians.widgets.live.start_configuration: 200 DLS (λ = 1 mm) Newton steps to x0.
 * @param {Chain} chain @param {ArrayLike<number>} x0 @returns {Vec}
 */
export function startConfiguration(chain, x0) {
  const n = chain.n;
  const th = [0.3, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9].slice(0, n);
  for (let k = 0; k < 200; k++) {
    const e = evaluate(chain, th);
    const err = [x0[0] - e.T[0][3], x0[1] - e.T[1][3]];
    if (Math.hypot(err[0], err[1]) < 1e-12) break;
    const d = dlsRates([e.Jg[3], e.Jg[4]], err, 1e-3);
    for (let i = 0; i < n; i++) th[i] += d[i];
  }
  return th;
}

/**
 * The whole run: {t, xd, theta0, run (velocity.resolved_rate's fields)}; presets use their exact velocity.
 * @param {Chain} chain @param {RunOptions} options
 * @param {Map<string, Vec> | null} [starts] the start of each path already computed (filled in)
 * @returns {Simulation}
 */
export function simulate(chain, { path, drawn, method, damping, nSteps, duration, gain, reach }, starts = null) {
  /** @type {number[]} */
  let t = [];
  /** @type {Vec[] | null} */
  let x = null;
  /** @type {Vec[] | null} */
  let v = null;
  if (path === "drawn" && drawn) {
    x = resample(drawn, nSteps);
    t = Array.from({ length: nSteps }, (_, k) => (duration * k) / (nSteps - 1));
    v = null; // forward differences, as the library's default
  }
  if (!x) ({ t, x, v } = planarPath(path === "drawn" ? "circle" : path, reach, nSteps, duration));
  // the start depends on the path only: a change of method or λ reuses it
  const key = `${x[0][0]},${x[0][1]}`;
  const theta0 = (starts && starts.get(key)) || startConfiguration(chain, x[0]);
  if (starts) starts.set(key, theta0);
  const run = resolvedRate(chain, theta0, x, t[1] - t[0], method, damping, gain, v);
  return { t, xd: x, theta0, run };
}

/**
 * @typedef {{root: SVGSVGElement, ink: SVGPolylineElement, pen: SVGPathElement, pad: SVGRectElement,
 *   drawBtn: HTMLButtonElement, help: HTMLElement, say: (text: string) => void, reach: number, R: number}} PadParts
 * @typedef {{tool: () => ArrayLike<number> | null, stop: () => void, use: (pts: Point2[]) => void}} PadRun
 * @typedef {[EventTarget, string, (ev: any) => void]} Listener
 * What the pad holds while the reader draws: whether it is shown, a pointer's stroke (while the pointer is down),
 * the points placed with the keyboard, and where the keyboard's pen is (world m).
 * @typedef {{drawing: boolean, stroke: Point2[] | null, keyed: Point2[], penAt: Point2}} PadState
 */

/**
 * The pad shown or hidden, its ink and pen drawn, and a stroke used as the path.
 * @param {PadParts} parts @param {PadRun} run @param {PadState} st
 */
function padDisplay({ root, ink, pen, pad, drawBtn, help, reach }, run, st) {
  const rootLabel = root.getAttribute("aria-label") || "";
  /** @param {Point2[]} P */
  const inkPoints = (P) => ink.setAttribute("points", P.map((q) => `${q[0]},${q[1]}`).join(" "));
  const showPen = () => {
    const d = 0.05 * reach;
    pen.setAttribute("d", `M${st.penAt[0] - d},${st.penAt[1]} h${2 * d} M${st.penAt[0]},${st.penAt[1] - d} v${2 * d}`);
    inkPoints(st.keyed.length ? [...st.keyed, st.penAt] : []);
  };
  /** @param {boolean} d */
  const setDrawing = (d) => {
    st.drawing = d;
    st.keyed = [];
    pad.setAttribute("visibility", d ? "visible" : "hidden");
    pen.setAttribute("visibility", d ? "visible" : "hidden");
    drawBtn.setAttribute("aria-pressed", String(d));
    drawBtn.textContent = d ? "✎ Use the path drawn" : "✎ Draw a path";
    help.textContent = d ? PEN_HELP : RUN_HELP;
    if (d) {
      const tool = run.tool();
      st.penAt = tool ? [Math.round(tool[0] * 100) / 100, Math.round(tool[1] * 100) / 100] : [0, 0];
      showPen();
      root.setAttribute("tabindex", "0");
      root.setAttribute("aria-label", `${rootLabel}. Drawing pad: the pen starts at the tool. ${PEN_HELP}`);
    } else {
      ink.setAttribute("points", "");
      root.removeAttribute("tabindex");
      root.setAttribute("aria-label", rootLabel);
    }
  };
  /** Use a drawn stroke as the path (at least two distinct points), then stop drawing. @param {Point2[]} pts */
  const commit = (pts) => {
    setDrawing(false);
    if (resample(pts, 2)) run.use(pts);
  };
  return { inkPoints, showPen, setDrawing, commit };
}
/** @typedef {ReturnType<typeof padDisplay>} PadDisplay */

/** @type {Record<string, Point2>} */
const PEN_MOVES = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };

/**
 * The keyboard's pen, with the picture focused: the arrow keys move it (Shift: finer), Enter places a point,
 * Backspace takes one back, Escape cancels.
 * @param {PadParts} parts @param {PadState} st @param {PadDisplay} shown @returns {Listener}
 */
function penKeys({ root, drawBtn, say, reach, R }, st, shown) {
  return [root, "keydown", (/** @type {KeyboardEvent} */ ev) => {
    if (!st.drawing) return;
    const where = () => `(${fixed(st.penAt[0], 2)}, ${fixed(st.penAt[1], 2)}) m`;
    const move = PEN_MOVES[ev.key];
    if (move) {
      const h = ev.shiftKey ? 0.01 * reach : 0.05 * reach;
      st.penAt = /** @type {Point2} */ (st.penAt.map((x, i) => Math.max(-R, Math.min(R, Math.round((x + h * move[i]) * 1e4) / 1e4))));
      say(`pen at ${where()}`);
    } else if (ev.key === "Enter" || ev.key === " ") {
      st.keyed.push(st.penAt);
      say(`point ${st.keyed.length} at ${where()}`);
    } else if (ev.key === "Backspace") {
      st.keyed.pop();
      say(`${st.keyed.length} points`);
    } else if (ev.key === "Escape") {
      shown.setDrawing(false);
      drawBtn.focus();
      say("drawing cancelled");
    } else return;
    if (st.drawing) shown.showPen();
    ev.preventDefault();
    ev.stopPropagation(); // the view's own keys (step, play) and a deck's wait until the drawing ends
  }];
}

/**
 * A pointer's stroke on the pad: down starts it, each move adds a point, up (or cancel) uses it.
 * @param {PadParts} parts @param {PadState} st @param {PadDisplay} shown @returns {Listener[]}
 */
function penStroke({ root, pad }, st, shown) {
  /** @param {PointerEvent} ev */
  const finish = (ev) => {
    if (!st.stroke) return;
    const last = ev.type === "pointerup" && toWorld(root, ev);
    if (last) st.stroke.push(last); // a touch's last move can come only with the lift
    const pts = st.stroke;
    st.stroke = null;
    shown.commit(pts);
  };
  return [
    [pad, "pointerdown", (ev) => {
      const p = toWorld(root, ev);
      if (!p) return;
      capture(pad, ev);
      st.stroke = [p];
      shown.inkPoints(st.stroke);
      ev.preventDefault();
    }],
    [pad, "pointermove", (ev) => {
      const p = st.stroke && toWorld(root, ev);
      if (!p || !st.stroke) return;
      st.stroke.push(p);
      shown.inkPoints(st.stroke);
    }],
    [pad, "pointerup", finish], [pad, "pointercancel", finish],
  ];
}

/**
 * The drawing pad of the path (bind): the Draw button shows a pad over the picture; a drag draws a stroke, or, with
 * the picture focused, the arrow keys move a pen (Shift: finer), Enter places a point, Backspace takes one back, the
 * button uses the points placed, Escape cancels. A stroke of two distinct points or more goes to run.use.
 * Returns the listeners to add, as [target, type, handler].
 * @param {PadParts} parts @param {PadRun} run @returns {Listener[]}
 */
function drawingPad(parts, run) {
  /** @type {PadState} */
  const st = { drawing: false, stroke: null, keyed: [], penAt: [0, 0] };
  const shown = padDisplay(parts, run, st);
  const { root, drawBtn } = parts;
  /** @type {Listener} */
  const button = [drawBtn, "click", () => {
    run.stop();
    if (!st.drawing) {
      shown.setDrawing(true);
      root.focus();
    } else if (st.keyed.length >= 2) shown.commit(st.keyed);
    else shown.setDrawing(false);
  }];
  return [button, penKeys(parts, st, shown), ...penStroke(parts, st, shown)];
}

/**
 * The model's fixed numbers, checked, with their defaults (what build, update and bind share).
 * @param {Model} model
 */
function options(model) {
  const chain = makeChain(model.get("S"), model.get("M"), model.get("Q") || null);
  const n = chain.n;
  const reach = Number(model.get("reach")) || 1;
  const duration = Number(model.get("duration")) || 4;
  const rateLimit = Number(model.get("rate_limit")) || 8;
  // the joint-rate plot: t on [0, duration], rates on [-rateLimit, rateLimit], in a 400 × 300 box
  const X0 = 52, X1 = 392, Y0 = 12, Y1 = 262;
  return {
    chain, n, reach, duration, rateLimit, X0, X1, Y0, Y1,
    nSteps: Math.max(2, Math.round(Number(model.get("n_steps")) || 160)),
    gain: Number.isFinite(Number(model.get("gain"))) ? Number(model.get("gain")) : 2,
    name: model.get("name") || `planar ${n}R arm`,
    R: 1.15 * reach,
    px: (/** @type {number} */ t) => X0 + ((X1 - X0) * t) / duration,
    py: (/** @type {number} */ r) => Y0 + ((Y1 - Y0) * (rateLimit - Math.max(-rateLimit, Math.min(rateLimit, r)))) / (2 * rateLimit),
  };
}
/** @typedef {ReturnType<typeof options>} Options */

/**
 * The arm's drawing (build): the desired and the actual path, the arm, the target, the drawing pad and its pen.
 * @param {HTMLElement} plot @param {Options} o
 */
function buildArm(plot, { n, reach, name, R }) {
  const { root, world } = planarCanvas(plot, R, reach, `${name} following the path; the desired path dashed`);
  const ns = { fill: "none", "vector-effect": "non-scaling-stroke" };
  const desLine = svg("polyline", { ...ns, stroke: PALETTE.path, "stroke-width": 3, "stroke-dasharray": "8 5",
    class: "jr-desired" }, world);
  const actLine = svg("polyline", { ...ns, stroke: PALETTE.velocity, "stroke-width": 2, class: "jr-actual" }, world);
  const link = svg("polyline", { ...ns, stroke: PALETTE.link, "stroke-width": 6, "stroke-linejoin": "round",
    "stroke-linecap": "round", class: "jl-link" }, world);
  const joints = Array.from({ length: n }, () => svg("circle", { r: 0.045 * reach, fill: PALETTE.bg, stroke: PALETTE.joint,
    "stroke-width": 2.2, "vector-effect": "non-scaling-stroke" }, world));
  const target = svg("path", { ...ns, stroke: PALETTE.path, "stroke-width": 3, class: "jr-target" }, world);
  const ink = svg("polyline", { ...ns, stroke: PALETTE.joint, "stroke-width": 2, class: "jr-ink" }, world);
  const pad = svg("rect", { x: -R, y: -R, width: 2 * R, height: 2 * R, fill: "transparent", class: "jl-draw",
    visibility: "hidden" }, world);
  const pen = svg("path", { ...ns, stroke: PALETTE.fg, "stroke-width": 2, class: "jr-pen", visibility: "hidden" }, world);
  return { root, desLine, actLine, link, joints, target, ink, pad, pen };
}

/**
 * The joint-rate plot (build): its axes, a line a joint, the time cursor, the key.
 * @param {HTMLElement} right @param {Options} o
 */
function buildRates(right, { n, duration, rateLimit, X0, X1, Y0, Y1, px, py }) {
  const W = 400, H = 300;
  const rp = svg("svg", { viewBox: `0 0 ${W} ${H}`, role: "img", class: "jr-rates",
    "aria-label": "joint rates against time, as the run goes" }, right);
  const axes = svg("g", { stroke: PALETTE.muted, "stroke-width": 1, "font-size": 16, fill: PALETTE.fg }, rp);
  for (const r of [-rateLimit, -rateLimit / 2, 0, rateLimit / 2, rateLimit]) {
    svg("line", { x1: X0, x2: X1, y1: py(r), y2: py(r), stroke: r === 0 ? PALETTE.muted : PALETTE.faint }, axes);
    svg("text", { x: X0 - 6, y: py(r) + 5, "text-anchor": "end", stroke: "none" }, axes).textContent = fixed(r, 0);
  }
  for (let s = 0; s <= duration + 1e-9; s += 1) {
    svg("text", { x: px(s), y: Y1 + 20, "text-anchor": "middle", stroke: "none" }, axes).textContent = fixed(s, 0);
  }
  svg("text", { x: X1, y: H - 2, "text-anchor": "end", stroke: "none" }, axes).textContent = "t (s)";
  svg("text", { x: X0 + 4, y: Y0 + 14, stroke: "none" }, axes).textContent = "θ̇ (rad/s)";
  const rateLines = Array.from({ length: n }, (_, i) => svg("polyline", { fill: "none", stroke: columnColor(i),
    "stroke-width": 2.5, class: `jr-rate jr-rate-${i + 1}` }, rp));
  const cursor = svg("line", { y1: Y0, y2: Y1, stroke: PALETTE.soft, "stroke-width": 1.5 }, rp);
  const key = html("ul", { class: "jl-legend" }, right);
  for (let i = 0; i < n; i++) {
    const li = html("li", { style: "display:inline-block;margin-right:12px" }, key);
    html("span", { class: "jl-key", style: `background:${columnColor(i)}` }, li);
    li.append(`θ̇${String.fromCharCode(0x2081 + i)}`);
  }
  return { rateLines, cursor };
}

/**
 * The controls (build): path, Draw, method, λ, the step slider, back / Play / on, the help, the status, the banner.
 * @param {HTMLElement} side @param {Options} o @param {string} uid
 */
function buildControls(side, { nSteps }, uid) {
  const row1 = html("div", { class: "jl-row" }, side);
  const pathLabel = html("label", { for: `${uid}-path` }, row1, "Path:");
  const pathSel = html("select", { id: `${uid}-path`, class: "jr-path" }, pathLabel);
  for (const p of [...PATHS, "drawn"]) html("option", { value: p }, pathSel, p === "drawn" ? "drawn by you" : p);
  const drawBtn = html("button", { type: "button", class: "jr-draw", "aria-pressed": "false" }, row1, "✎ Draw a path");
  const methodLabel = html("label", { for: `${uid}-method` }, row1, "Method:");
  const methodSel = html("select", { id: `${uid}-method`, class: "jr-method" }, methodLabel);
  for (const [k, v] of Object.entries(METHODS)) html("option", { value: k }, methodSel, v);
  const lamLabel = html("label", { for: `${uid}-lam` }, side, "damping λ = ");
  const lamOut = html("output", { for: `${uid}-lam` }, lamLabel);
  const lam = html("input", { type: "range", id: `${uid}-lam`, class: "jr-damping", min: -3, max: 0, step: 0.1 }, side);
  const stepLabel = html("label", { for: `${uid}-step` }, side, "step ");
  const stepOut = html("output", { for: `${uid}-step` }, stepLabel);
  const stepIn = html("input", { type: "range", id: `${uid}-step`, class: "jr-step", min: 0, max: nSteps - 1, step: 1 },
    side);
  const row2 = html("div", { class: "jl-row" }, side);
  const back = html("button", { type: "button", class: "jr-back", "aria-label": "one step back" }, row2, "◀ step");
  const play = html("button", { type: "button", class: "jl-play", "aria-pressed": "false" }, row2, "▶ Play");
  const fwd = html("button", { type: "button", class: "jr-fwd", "aria-label": "one step on" }, row2, "step ▶");
  const help = html("p", { class: "jl-status jr-help" }, side, RUN_HELP);
  const status = html("p", { class: "jl-status" }, side);
  const say = announcer(side);  // the key numbers, once a run or a drag has stopped
  const statusT = side.ownerDocument.createTextNode("");
  status.append(statusT);
  sub(status, ["σ", "min"]);
  sub(status, ["(J", "v"]);
  const statusS = side.ownerDocument.createTextNode("");
  status.append(statusS);
  const banner = html("p", { class: "jl-banner", role: "status" }, side);
  return { pathSel, drawBtn, methodSel, lamOut, lam, stepOut, stepIn, back, play, fwd, help, say, statusT, statusS,
    banner };
}

/**
 * The view (build): the arm and the rate plot side by side, the controls below.
 * @param {HTMLElement} el @param {Model} model
 */
function build(el, model) {
  const { uid } = startView(el, { prefix: "jr" });
  const o = options(model);
  el.tabIndex = -1;
  const wrap = html("div", { class: "jl-wrap" }, el);
  const plot = html("div", { class: "jl-plot" }, wrap);
  const right = html("div", { class: "jl-plot" }, wrap);
  const side = html("div", { class: "jl-side" }, el);
  return { o, ...buildArm(plot, o), ...buildRates(right, o), ...buildControls(side, o, uid) };
}
/** @typedef {ReturnType<typeof build>} Parts */

/** The model's choices, checked. @param {Model} model @param {Options} o @returns {RunOptions} */
function readOptions(model, { nSteps, duration, gain, reach }) {
  const get = (/** @type {string} */ k, /** @type {any} */ d) => (model.get(k) === undefined || model.get(k) === null ? d : model.get(k));
  const m = get("method", "pinv");
  const path = get("path", "close past the base");
  const l = Number(get("damping", 0.1));
  return { path: [...PATHS, "drawn"].includes(path) ? path : "circle", drawn: get("drawn", null),
    method: m in METHODS ? m : "pinv", damping: Number.isFinite(l) && l >= 0 ? l : 0.1, nSteps, duration, gain,
    reach };
}
/** The step shown, 0 to n_steps - 1. @param {Model} model @param {number} nSteps @returns {number} */
function readStep(model, nSteps) {
  const s = model.get("step");
  return Math.max(0, Math.min(nSteps - 1, Math.round(Number(s === undefined || s === null ? 0 : s)) || 0));
}

/**
 * Step k of the run drawn (update): the arm, the paths, the rates so far, the numbers, the controls' values.
 * @param {Parts} parts @param {Simulation} sim @param {number} k @param {RunOptions} opts @param {RateState} shown
 */
function update(parts, sim, k, opts, shown) {
  const { n, reach, nSteps, px, py } = parts.o;
  const { link, joints, actLine, target, rateLines, cursor, statusT, statusS, say, banner, lamOut, lam, stepOut,
    stepIn, pathSel, methodSel } = parts;
  const doc = lam.ownerDocument;
  const { run, t, xd } = sim;
  const th = run.thetas[k];
  const pts = evaluate(parts.o.chain, th).points;
  link.setAttribute("points", pts.map((p) => `${p[0]},${p[1]}`).join(" "));
  for (let i = 0; i < n; i++) {
    joints[i].setAttribute("cx", String(pts[i][0]));
    joints[i].setAttribute("cy", String(pts[i][1]));
  }
  actLine.setAttribute("points", run.positions.slice(0, k + 1).map((p) => `${p[0]},${p[1]}`).join(" "));
  const c = xd[k], a = 0.05 * reach;
  target.setAttribute("d", `M${c[0] - a},${c[1] - a}L${c[0] + a},${c[1] + a}M${c[0] - a},${c[1] + a}L${c[0] + a},${c[1] - a}`);
  for (let i = 0; i < n; i++) {
    rateLines[i].setAttribute("points", run.rates.slice(0, k + 1).map((r, j) => `${px(t[j])},${py(r[i])}`).join(" "));
  }
  cursor.setAttribute("x1", String(px(t[k])));
  cursor.setAttribute("x2", String(px(t[k])));
  const s = run.sigmaMin[k];
  const now = Math.hypot(...run.rates[k]);
  let peak = 0;
  for (let j = 0; j <= k; j++) for (const r of run.rates[j]) peak = Math.max(peak, Math.abs(r));
  const level = s < 0.02 * reach ? "singular" : s < 0.1 * reach ? "warning" : "ok";
  statusT.textContent = `t = ${fixed(t[k], 2)} s, `;
  statusS.textContent = `) = ${fixed(s, 3)} m; ‖θ̇‖ = ${fixed(now, 2)} rad/s, `
    + `peak |θ̇ᵢ| so far ${fixed(peak, 1)} rad/s; tracking error ${fixed(1000 * run.errors[k], 1)} mm`;
  say(`time ${fixed(t[k], 2)} seconds; smallest singular value ${fixed(s, 3)} metres; `
    + `peak joint rate so far ${fixed(peak, 1)} radians per second; tracking error ${fixed(1000 * run.errors[k], 1)} millimetres`);
  if (level !== shown.level) {
    banner.hidden = level === "ok";
    banner.textContent = level === "ok" ? "" : level === "singular"
      ? "At a singularity: the tool has almost lost a direction; pseudo-inverse rates blow up, DLS gives up accuracy"
      : "Near a singularity: the joint rates grow";
    banner.style.borderColor = PALETTE[level];
  }
  link.setAttribute("stroke", level === "ok" ? PALETTE.link : PALETTE[level]);
  lamOut.textContent = `${fixed(opts.damping, 3)} m`;
  // the slider moves log10(λ); a screen reader says λ itself, as the label shows it
  lam.setAttribute("aria-valuetext", `λ = ${fixed(opts.damping, 3)} metres`);
  lam.disabled = opts.method !== "dls";
  if (doc.activeElement !== lam) lam.value = String(Math.log10(Math.max(opts.damping, 1e-3)));
  stepOut.textContent = `${k} of ${nSteps - 1}`;
  stepIn.setAttribute("aria-valuetext", `step ${k} of ${nSteps - 1}`);
  if (doc.activeElement !== stepIn || Number(stepIn.value) !== k) stepIn.value = String(k);
  if (pathSel.value !== opts.path) pathSel.value = opts.path;
  if (methodSel.value !== opts.method) methodSel.value = opts.method;
  Object.assign(shown, { step: k, sim, level, sigmaMin: s, theta: th, drawn: opts.drawn });
}

/**
 * The reader's input -> the model (bind): path, method, λ, the step slider, the buttons, the view's keys (P or K
 * play/pause, → or . on, ← or , back, not while a slider or a select has them), the drawing pad.
 * Returns the remover of all of it.
 * @param {Parts} parts @param {Model} model @param {() => void} redraw @param {HTMLElement} el
 * @param {RateState} state
 */
function bind(parts, model, redraw, el, state) {
  const { nSteps, reach, R } = parts.o;
  const { pathSel, methodSel, lam, stepIn, play, back, fwd, root, ink, pen, pad, drawBtn, help, say } = parts;
  const setStep = (/** @type {number} */ k) => save(model, "step", Math.max(0, Math.min(nSteps - 1, k)));
  const playing = player(play, () => {
    if (state.step >= nSteps - 1) return playing.stop();
    return setStep(state.step + 1);
  }, 40, (p) => publish(el, { playing: p ? 1 : 0 }));
  const toggle = () => {
    if (playing.playing()) return playing.stop();
    if (state.step >= nSteps - 1) setStep(0);
    return playing.start();
  };
  const stop = playing.stop;
  const restart = () => {
    stop();
    save(model, "step", 0);
  };
  /** @type {import("../ui.js").Listener[]} */
  const on = [
    [pathSel, "change", () => { save(model, "path", pathSel.value); restart(); }],
    [methodSel, "change", () => { save(model, "method", methodSel.value); restart(); }],
    [lam, "input", () => { save(model, "damping", Math.round(10 ** Number(lam.value) * 1e4) / 1e4); }],
    [stepIn, "input", () => { stop(); setStep(Number(stepIn.value)); }],
    [play, "click", toggle],
    [back, "click", () => { stop(); setStep(state.step - 1); }],
    [fwd, "click", () => { stop(); setStep(state.step + 1); }],
    [el, "keydown", (/** @type {KeyboardEvent & {target: HTMLElement}} */ ev) => {
      const tag = ev.target.tagName;
      if (ev.key === "p" || ev.key === "P" || ev.key === "k" || ev.key === "K") toggle();
      else if (tag !== "INPUT" && tag !== "SELECT" && KEYS_ON.has(ev.key)) { stop(); setStep(state.step + 1); }
      else if (tag !== "INPUT" && tag !== "SELECT" && KEYS_BACK.has(ev.key)) { stop(); setStep(state.step - 1); }
      else return;
      ev.preventDefault();
    }],
  ];
  // drawing a path: press "Draw a path", then drag over the arm's picture, or move a pen with the keys
  on.push(...drawingPad({ root, ink, pen, pad, drawBtn, help, say, reach, R }, {
    tool: () => (state.sim ? state.sim.run.positions[state.step] : null),
    stop,
    use(/** @type {Point2[]} */ pts) {
      model.set("drawn", pts.map((p) => [Math.round(p[0] * 1e4) / 1e4, Math.round(p[1] * 1e4) / 1e4]));
      save(model, "path", "drawn");
      restart();
    },
  }));
  const unlisten = listen(model, ["path", "drawn", "method", "damping", "step"], redraw, on);
  const unhold = holdTouch(pad); // the pad is there only while drawing
  return () => {
    stop();
    unlisten();
    unhold();
  };
}

/** @param {{model: Model, el: HTMLElement}} args */
function render({ model, el }) {
  const parts = build(el, model);
  const { o } = parts;
  /** @type {Simulation | null} */
  let sim = null;
  /** @type {string | null} */
  let simKey = null;
  /** @type {Map<string, Vec>} */
  const starts = new Map();
  /** @type {RateState} */
  const state = { step: 0, sim: null, level: null };
  const redraw = () => {
    const opts = readOptions(model, o);
    // the run is redone only when what it depends on changes
    const k = JSON.stringify([opts.path, opts.path === "drawn" ? opts.drawn : null, opts.method,
      opts.method === "dls" ? opts.damping : 0]);
    if (k !== simKey) {
      sim = simulate(o.chain, opts, starts);
      simKey = k;
      parts.desLine.setAttribute("points", sim.xd.map((p) => `${p[0]},${p[1]}`).join(" "));
    }
    if (!sim) return;
    update(parts, sim, readStep(model, o.nSteps), opts, state);
    publish(el, { view: "resolved_rate", theta: /** @type {Vec} */ (state.theta), level: /** @type {string} */ (state.level),
      step: state.step });
  };
  const unbind = bind(parts, model, redraw, el, state);
  redraw();
  publish(el, { playing: 0 });
  return finishView(el, state, unbind);
}

export { render };
export default { render };
