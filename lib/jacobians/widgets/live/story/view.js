// @ts-check
// Story animations as a live view: a motion replayed with a Play /
// Pause button and a time slider (a labelled <input>, one frame per arrow
// key), drawn in SVG from the chain and the motion embedded at build time by
// the {live-view} directive (a story of course.stories). The view
// computes in the browser only what it draws, with kinematics.js, at each
// frame; tests/browser/test_live_story.py compares those numbers with the
// library. The view knows no story: it computes the same state at every frame (storyState) and
// draws it with the drawing the model names (`story`, a key of DRAWINGS); three drawings:
//
//   fixed_axis        (chapter 1) a body turning about a fixed vertical axis through q:
//                     v_s at the origin of {s} stays put, ṗ turns with the body.
//   body_columns      (chapter 3) the planar 3R arm along a closed path: left, the linear
//                     parts of J_b's columns turned into {s}, at the tool (the tool velocity per
//                     joint); right, the same vectors in {b}-coordinates.
//   three_velocities  (chapter 7) the planar 3R arm at constant joint rates: ṗ at the tool, v_s
//                     at the origin of {s}, and ω_s, ω_b, ṗ, v_s, v_b in numbers.
//
// anywidget-compatible: `export default { render }`. Model keys: S, M, Q, name, reach, story,
// offset, rate, waves (θ_i(t) = offset_i + rate_i t + Σ amp sin(freq t + phase)), t_end,
// frames, closed, speed (story seconds per second), frame (shown, written back), box
// ([x0, x1, y0, y1] m), box_right, scale, theta_dot, vel_scale, axis_len, q. In a deck,
// course_decks.js presses Play when the slide is shown and Pause when it is left.

import { evaluate, makeChain } from "../kinematics.js";
import {
  PALETTE, columnColor, finishView, fixed, graphic, html, ink, layout, legendItem, listen, makeArrow, player, publish,
  save, setArrow, startView, sub, svg, text as setText,
} from "../ui.js";

/** @typedef {import("../host.js").Model} Model */
/** @typedef {import("../kinematics.js").Chain} Chain */
/** @typedef {import("../linalg.js").Vec} Vec */
/** @typedef {import("../linalg.js").Mat} Mat */
/** @typedef {import("../ui.js").Arrow2} Arrow2 */
/** @typedef {import("../ui.js").SubText} SubText */
/**
 * The story's model (the keys render reads): the motion θ_i(t) = offset_i + rate_i t + Σ amp sin(freq t + phase),
 * its frames, and what is drawn where.
 * @typedef {{story: string, offset: number[], rate: number[], waves: number[][][], t_end: number, frames: number,
 *   closed: boolean, speed: number, box: number[], box_right: number[], scale: number, theta_dot: number[],
 *   vel_scale: number, axis_len: number, q: number[]}} StoryModel
 */
/**
 * Everything a story draws at time t: the pose, and the story's vectors.
 * @typedef {{t: number, theta: Vec, p: Vec, xb: Vec, yb: Vec, points: Vec[], vb?: Vec[], vs?: Vec[],
 *   thetaDot?: Vec, omegaS?: Vec, vS?: Vec, omegaB?: Vec, vB?: Vec, pDot?: Vec}} StoryFrame
 */
/**
 * A drawing of a box (m, y up), with its labels (their size follows the drawn scale).
 * @typedef {{root: SVGSVGElement, world: SVGGElement, font: number, base: number, box: number[],
 *   texts: SVGTextElement[], text: (x: number, y: number, s: string, cls?: string, index?: string) => SVGTextElement}}
 *   Panel
 */
/** @typedef {Record<string, Vec[] | Vec[][]>} Arrows the arrows drawn: [tail, vector] (world m), or a list of them */
/**
 * What a story's build is given: the model, the chain, where it draws, and the legend and the table it fills.
 * @typedef {{m: StoryModel, chain: Chain, n: number, head: number, plot: HTMLElement, legend: HTMLUListElement,
 *   caption: HTMLTableCaptionElement, tableRows: (labels: [string, SubText][], cols: string[],
 *   colColors?: string[] | null) => void, setRow: (key: string, v: number[], d?: number) => void}} StoryContext
 */
/** @typedef {(s: StoryFrame) => Arrows} StoryUpdate a story's redraw at one frame; returns the arrows drawn */

// the palette's colours as the page's mode draws them (palette.js)
const C = { orange: graphic("orange"), blue: graphic("blue"), vermillion: graphic("vermillion"), green: graphic("green"),
  sky: graphic("sky"), black: graphic("ink") };

const CSS = `
.jac-live .js-plot{flex:1 1 300px;max-width:460px;min-width:0;display:flex;flex-wrap:wrap;gap:8px}
.jac-live .js-plot.js-two{flex:1 1 100%;max-width:760px}
.jac-live .js-plot svg{flex:1 1 260px;min-width:0;width:100%;height:auto;display:block}
.jac-live .js-panel-title{font-size:15px;margin:0 0 2px;text-align:center}
.jac-live .js-panel{flex:1 1 260px;min-width:0}
`;

/**
 * The time of frame k (s): closed motions do not repeat t_end (= t_0).
 * @param {{frames: number, closed: boolean, t_end: number}} m @param {number} k @returns {number}
 */
export function frameTime(m, k) {
  const n = m.frames;
  return k * (m.closed ? m.t_end / n : m.t_end / (n - 1));
}

/**
 * θ(t) of the motion (rad).
 * @param {{offset: number[], rate: number[], waves: number[][][]}} m @param {number} t @returns {Vec}
 */
export function storyTheta(m, t) {
  return m.offset.map((o, i) => {
    let x = o + m.rate[i] * t;
    for (const [amp, freq, phase] of m.waves[i] || []) x += amp * Math.sin(freq * t + phase);
    return x;
  });
}

/**
 * dθ/dt of the motion at t (rad/s).
 * @param {{rate: number[], waves: number[][][]}} m @param {number} t @returns {Vec}
 */
export function storyThetaDot(m, t) {
  return m.rate.map((r, i) => {
    let x = r;
    for (const [amp, freq, phase] of m.waves[i] || []) x += amp * freq * Math.cos(freq * t + phase);
    return x;
  });
}

/** Rows `rows` of J times qd. @type {(J: Mat, rows: number[], qd: ArrayLike<number>) => Vec} */
const mulJ = (J, rows, qd) => rows.map((r) => J[r].reduce((s, x, i) => s + x * qd[i], 0));

/**
 * Everything a story draws at time t, from the library's formulas (kinematics.js).
 * @param {Chain} chain @param {StoryModel} m @param {number} t @returns {StoryFrame}
 */
export function storyState(chain, m, t) {
  const theta = storyTheta(m, t);
  const e = evaluate(chain, theta);
  const T = e.T;
  const p = [T[0][3], T[1][3]];
  const R2 = [[T[0][0], T[0][1]], [T[1][0], T[1][1]]];
  /** @type {StoryFrame} */
  const out = { t, theta, p, xb: [R2[0][0], R2[1][0]], yb: [R2[0][1], R2[1][1]], points: e.points.map((q) => [q[0], q[1]]) };
  // the linear parts of J_b's columns, in {b} (vb) and turned into {s} (vs)
  const vb = e.Jb[0].map((_, i) => [e.Jb[3][i], e.Jb[4][i]]);
  out.vb = vb;
  out.vs = vb.map((v) => [R2[0][0] * v[0] + R2[0][1] * v[1], R2[1][0] * v[0] + R2[1][1] * v[1]]);
  // the velocities at the motion's joint rates
  const qd = storyThetaDot(m, t);
  const Vs = mulJ(e.Js, [0, 1, 2, 3, 4, 5], qd);
  const Vb = mulJ(e.Jb, [0, 1, 2, 3, 4, 5], qd);
  out.thetaDot = qd;
  out.omegaS = Vs.slice(0, 3);
  out.vS = Vs.slice(3);
  out.omegaB = Vb.slice(0, 3);
  out.vB = Vb.slice(3);
  out.pDot = mulJ(e.Jg, [3, 4, 5], qd);
  return out;
}

/**
 * An SVG drawing of box [x0, x1, y0, y1] (m, y up): {root, world (y flipped), label(x, y, text)}.
 * @param {Element} parent @param {number[]} box @param {string} label @returns {Panel}
 */
function panel(parent, box, label) {
  const [x0, x1, y0, y1] = box;
  const root = svg("svg", { viewBox: `${x0} ${-y1} ${x1 - x0} ${y1 - y0}`, role: "img", "aria-label": label,
    fill: PALETTE.fg }, parent);
  svg("rect", { x: x0, y: -y1, width: x1 - x0, height: y1 - y0, fill: PALETTE.bg, stroke: PALETTE.border,
    "vector-effect": "non-scaling-stroke" }, root);
  const world = svg("g", { transform: "scale(1,-1)" }, root);
  const grid = svg("g", { stroke: PALETTE.grid, "stroke-width": 1 }, world);
  for (let k = Math.ceil(x0); k <= x1; k++) svg("line", { x1: k, y1: y0, x2: k, y2: y1, "vector-effect": "non-scaling-stroke" }, grid);
  for (let k = Math.ceil(y0); k <= y1; k++) svg("line", { x1: x0, y1: k, x2: x1, y2: k, "vector-effect": "non-scaling-stroke" }, grid);
  const font = 0.045 * (x1 - x0); // ≥ 14 px when the drawing is ≥ 312 px wide
  /** @type {Panel} */
  const P = { root, world, font, base: font, box, texts: [], text: () => { throw new Error("set below"); } };
  P.text = (x, y, s, cls = "", index = "") => {
    const t = svg("text", { x, y: -y, "font-size": P.font, class: cls }, root);
    t.textContent = s;
    if (index) svg("tspan", { "baseline-shift": "sub", "font-size": 0.85 * P.font }, t).textContent = index;
    P.texts.push(t);
    return t;
  };
  Object.assign(root, { jsPanel: P });
  return P;
}

/**
 * Labels at least `--js-label-px` CSS px as shown (a deck sets 24: text on a slide), whatever the
 * drawing's width: the font size in metres follows the drawn scale. True when a size changed.
 * @param {Panel} P @returns {boolean}
 */
function fitLabels(P) {
  const want = parseFloat(getComputedStyle(P.root).getPropertyValue("--js-label-px"));
  const shown = P.root.getBoundingClientRect().width;
  if (!(want > 0) || !(shown > 0)) return false;
  const f = Math.max(P.base, (want * (P.box[1] - P.box[0])) / shown);
  if (Math.abs(f - P.font) <= 1e-9 * f) return false;
  P.font = f;
  for (const t of P.texts) {
    t.setAttribute("font-size", String(f));
    const sub = t.querySelector("tspan");
    if (sub) sub.setAttribute("font-size", String(0.85 * f));
  }
  return true;
}

/**
 * A polyline of the drawing. @param {Element} parent @param {string} color @param {number} width
 * @param {import("../ui.js").Attrs} [extra] @returns {SVGPolylineElement}
 */
function line(parent, color, width, extra = {}) {
  return svg("polyline", { fill: "none", stroke: color, "stroke-width": width, "stroke-linejoin": "round",
    "stroke-linecap": "round", "vector-effect": "non-scaling-stroke", ...extra }, parent);
}

const pts = (/** @type {ArrayLike<number>[]} */ P) => P.map((q) => `${q[0]},${q[1]}`).join(" ");


const vec = (/** @type {number[]} */ v, d = 2) => `(${v.map((x) => fixed(x, d)).join(", ")})`;

const tiny = 1e-9; // an arrow shorter than this (m) is hidden
const arrowsOf = (/** @type {Arrow2} */ a, /** @type {string} */ cls) => a.g.setAttribute("class", cls);

/**
 * Chapter 1's story (build): a body turning about a fixed vertical axis through q; returns its redraw.
 * @param {StoryContext} c @returns {StoryUpdate}
 */
function buildFixedAxis({ m, chain, plot, legend, caption, tableRows, setRow }) {
  const P = panel(plot, m.box, "A body frame {b} turning about a vertical axis through q: v_s at the origin of {s}, ṗ at the origin of {b}");
  const L = 0.4;
  setArrow(makeArrow(P.world, C.black, 1.5), [0, 0], [L, 0], 0.08, tiny);
  setArrow(makeArrow(P.world, C.black, 1.5), [0, 0], [0, L], 0.08, tiny);
  P.text(-0.55, 0.08, "{s}");
  const q = m.q;
  const d = 0.07;
  line(P.world, C.black, 2.5, { points: `${q[0] - d},${q[1] - d} ${q[0] + d},${q[1] + d}` });
  line(P.world, C.black, 2.5, { points: `${q[0] - d},${q[1] + d} ${q[0] + d},${q[1] - d}` });
  P.text(q[0] + 0.1, q[1] + 0.1, "q");
  /** @type {Vec[]} */
  const circle = [];
  for (let k = 0; k <= 96; k++) circle.push(storyState(chain, m, (2 * Math.PI * k) / 96).p); // where {b}'s origin goes
  line(P.world, C.sky, 2, { points: pts(circle), "stroke-dasharray": "2 4", class: "js-path" });
  const bx = makeArrow(P.world, C.vermillion, 2.5);
  const by = makeArrow(P.world, C.green, 2.5);
  arrowsOf(bx, "js-xb");
  arrowsOf(by, "js-yb");
  const blabel = P.text(0, 0, "{b}");
  const vs = makeArrow(P.world, C.orange, 4);
  const pd = makeArrow(P.world, C.blue, 4);
  arrowsOf(vs, "js-vs");
  arrowsOf(pd, "js-pdot");
  legendItem(legend, C.orange, ["v", ["", "s"], ": the body point passing through the origin of {s}"]);
  legendItem(legend, C.blue, ["ṗ: the origin of {b}"]);
  legendItem(legend, C.vermillion, ["x", ["", "b"], " and ", "y", ["", "b"], " (green): the axes of {b}"]);
  legendItem(legend, C.sky, ["where the origin of {b} goes; ✕ the axis through q (ω̂ = ẑ); grid 1 m"], true);
  caption.textContent = "velocities (m/s)";
  tableRows([["vs", ["v", "s"]], ["pd", ["ṗ", ""]]], ["x", "y", "‖·‖"]);
  return (s) => {
    const vS = /** @type {Vec} */ (s.vS), pDot = /** @type {Vec} */ (s.pDot);
    const a = m.axis_len;
    setArrow(bx, s.p, [a * s.xb[0], a * s.xb[1]], 0.07, tiny);
    setArrow(by, s.p, [a * s.yb[0], a * s.yb[1]], 0.07, tiny);
    blabel.setAttribute("x", String(s.p[0] + 0.05));
    blabel.setAttribute("y", String(-(s.p[1] - 0.25)));
    setArrow(vs, [0, 0], [vS[0], vS[1]], 0.12, tiny);
    setArrow(pd, s.p, [pDot[0], pDot[1]], 0.12, tiny);
    setRow("vs", [vS[0], vS[1], Math.hypot(...vS)]);
    setRow("pd", [pDot[0], pDot[1], Math.hypot(...pDot)]);
    return { vs: [[0, 0], [vS[0], vS[1]]], pdot: [s.p, [pDot[0], pDot[1]]] };
  };
}

/**
 * The planar 3R arm of chapters 3 and 7 (build): links, joints (named J1.. when `named`), {s} and the tool's axes,
 * in a panel of its own under an optional title; returns the panel and the arm's redraw.
 * @param {StoryContext} c @param {string} label @param {string | null} title @param {boolean} named
 * @returns {{P: Panel, arm: (s: StoryFrame) => void}}
 */
function buildArm({ m, n, plot }, label, title, named) {
  const left = html("div", { class: "js-panel" }, plot);
  if (title) html("p", { class: "js-panel-title" }, left, title);
  const P = panel(left, m.box, label);
  const L = 0.5;
  setArrow(makeArrow(P.world, C.black, 1.5), [0, 0], [L, 0], 0.08, tiny);
  setArrow(makeArrow(P.world, C.black, 1.5), [0, 0], [0, L], 0.08, tiny);
  P.text(L + 0.02, -P.font * 1.1, "x");
  P.text(-P.font * 0.9, L + 0.02, "y");
  const link = line(P.world, PALETTE.muted, 7, { class: "jl-link" });
  /** @type {SVGCircleElement[]} */
  const joints = [];
  /** @type {SVGTextElement[]} */
  const jl = [];
  for (let i = 0; i < n; i++) {
    joints.push(svg("circle", { r: 0.05, fill: PALETTE.bg, stroke: C.black, "stroke-width": 2, "vector-effect": "non-scaling-stroke" }, P.world));
    if (named) jl.push(P.text(0, 0, `J${i + 1}`));
  }
  const bx = makeArrow(P.world, C.black, 1.5);
  const by = line(P.world, C.black, 1.5, { "stroke-dasharray": "4 3" });
  const xbl = P.text(0, 0, "x", "", "b");
  const ybl = P.text(0, 0, "y", "", "b");
  for (const t of [xbl, ybl]) {
    t.setAttribute("text-anchor", "middle");
    t.setAttribute("dominant-baseline", "middle");
  }
  const arm = (/** @type {StoryFrame} */ s) => {
    link.setAttribute("points", pts(s.points));
    for (let i = 0; i < n; i++) {
      joints[i].setAttribute("cx", String(s.points[i][0]));
      joints[i].setAttribute("cy", String(s.points[i][1]));
      if (jl[i]) {
        jl[i].setAttribute("x", String(s.points[i][0] + 0.08));
        jl[i].setAttribute("y", String(-(s.points[i][1] - 0.28)));
      }
    }
    const a = m.axis_len;
    setArrow(bx, s.p, [a * s.xb[0], a * s.xb[1]], 0.07, tiny);
    by.setAttribute("points", `${s.p[0]},${s.p[1]} ${s.p[0] + a * s.yb[0]},${s.p[1] + a * s.yb[1]}`);
    const r = a + 0.9 * P.font; // the labels just beyond the axes' tips, centred on their line
    xbl.setAttribute("x", String(s.p[0] + r * s.xb[0]));
    xbl.setAttribute("y", String(-(s.p[1] + r * s.xb[1])));
    ybl.setAttribute("x", String(s.p[0] + r * s.yb[0]));
    ybl.setAttribute("y", String(-(s.p[1] + r * s.yb[1])));
  };
  return { P, arm };
}

/**
 * Chapter 3's story (build): the linear parts of J_b's columns at the tool in {s} (left) and in {b} (right).
 * @param {StoryContext} c @returns {StoryUpdate}
 */
function buildBodyColumns(c) {
  const { m, plot, head, legend, caption, tableRows, setRow } = c;
  plot.classList.add("js-two"); // two drawings side by side
  const { P, arm } = buildArm(c, "The planar 3R arm in {s}, with the velocity of the tool point when each joint alone turns at 1 rad/s",
    "the arm in {s}; tool velocity per joint (×0.6)", true);
  const right = html("div", { class: "js-panel" }, plot);
  html("p", { class: "js-panel-title" }, right, "the same vectors in {b} (to scale)");
  const Rp = panel(right, m.box_right, "The linear parts of the columns of J_b, in {b}-coordinates");
  line(Rp.world, PALETTE.muted, 1, { points: `${m.box_right[0]},0 ${m.box_right[1]},0` });
  line(Rp.world, PALETTE.muted, 1, { points: `0,${m.box_right[2]} 0,${m.box_right[3]}` });
  // anchored at the right and top edges, so that a larger font (a slide) grows into the drawing
  Rp.text(m.box_right[1] - 0.3 * Rp.font, -0.3 * Rp.font, "x", "", "b").setAttribute("text-anchor", "end");
  Rp.text(0.08, m.box_right[3] - 0.2 * Rp.font, "y", "", "b").setAttribute("dominant-baseline", "hanging");
  /** @type {Arrow2[]} */
  const colsL = [];
  /** @type {Arrow2[]} */
  const colsR = [];
  for (let i = 0; i < 3; i++) {
    colsL.push(makeArrow(P.world, columnColor(i), 3.5));
    colsR.push(makeArrow(Rp.world, columnColor(i), 3.5));
    arrowsOf(colsL[i], `js-left js-col-${i + 1}`);
    arrowsOf(colsR[i], `js-right js-col-${i + 1}`);
  }
  for (let i = 0; i < 3; i++) legendItem(legend, columnColor(i), ["J", ["", `b${i + 1}`], ` (joint ${i + 1})`]);
  legendItem(legend, C.black, ["x", ["", "b"], " solid, ", "y", ["", "b"], " dashed: the tool axes; grid 1 m (right: 1 m/rad)"]);
  caption.append("linear parts of the columns of J");
  sub(caption, ["", "b"]);
  caption.append(", in {b} (m/rad)");
  tableRows([["x", ["x", "b"]], ["y", ["y", "b"]]], ["col 1", "col 2", "col 3"], [0, 1, 2].map(columnColor));
  return (s) => {
    const vsL = /** @type {Vec[]} */ (s.vs), vbR = /** @type {Vec[]} */ (s.vb);
    arm(s);
    const k = m.scale;
    for (let i = 0; i < 3; i++) {
      setArrow(colsL[i], s.p, [k * vsL[i][0], k * vsL[i][1]], head, tiny);
      setArrow(colsR[i], [0, 0], vbR[i], 0.09, tiny);
    }
    setRow("x", vbR.map((v) => v[0]));
    setRow("y", vbR.map((v) => v[1]));
    return { left: vsL.map((v) => [s.p, [k * v[0], k * v[1]]]), right: vbR.map((v) => [[0, 0], v]) };
  };
}

/**
 * Chapter 7's story (build): ṗ at the tool, v_s at the origin of {s}, and the five velocities in numbers.
 * @param {StoryContext} c @returns {StoryUpdate}
 */
function buildThreeVelocities(c) {
  const { m, head, legend, caption, tableRows, setRow } = c;
  const { P, arm } = buildArm(c, "The planar 3R arm at constant joint rates: ṗ at the tool, v_s at the origin of {s}",
    null, false);
  const pd = makeArrow(P.world, C.green, 4);
  const vs = makeArrow(P.world, C.orange, 4);
  arrowsOf(pd, "js-pdot");
  arrowsOf(vs, "js-vs");
  legendItem(legend, C.green, ["ṗ (geometric J): the tool point's velocity"]);
  legendItem(legend, C.orange, ["v", ["", "s"], " (space J", ["", "s"], "): at the origin of {s}"]);
  legendItem(legend, C.black, ["x", ["", "b"], " solid, ", "y", ["", "b"], " dashed: the tool axes; grid 1 m"]);
  caption.textContent = `θ̇ = ${vec(m.theta_dot, 1)} rad/s`;
  tableRows([["ws", ["ω", "s"]], ["wb", ["ω", "b"]], ["pd", ["ṗ", ""]], ["vs", ["v", "s"]], ["vb", ["v", "b"]]],
    ["x", "y", "z", "‖·‖"]);
  const vsc = m.vel_scale;
  return (s) => {
    const [vS, pDot, omegaS, omegaB, vB] = /** @type {Vec[]} */ ([s.vS, s.pDot, s.omegaS, s.omegaB, s.vB]);
    arm(s);
    setArrow(pd, s.p, [vsc * pDot[0], vsc * pDot[1]], head, tiny);
    setArrow(vs, [0, 0], [vsc * vS[0], vsc * vS[1]], head, tiny);
    const nrm = (/** @type {number[]} */ v) => Math.hypot(...v);
    setRow("ws", [...omegaS, nrm(omegaS)]);
    setRow("wb", [...omegaB, nrm(omegaB)]);
    setRow("pd", [...pDot, nrm(pDot)]);
    setRow("vs", [...vS, nrm(vS)]);
    setRow("vb", [...vB, nrm(vB)]);
    return { pdot: [s.p, [vsc * pDot[0], vsc * pDot[1]]], vs: [[0, 0], [vsc * vS[0], vsc * vS[1]]] };
  };
}

/**
 * The drawings: the model's `story` names the one that draws it (the course's stories, course.stories, name
 * theirs; jacobians.widgets.live.story.DRAWINGS lists these names).
 * @type {Record<string, (c: StoryContext) => StoryUpdate>}
 */
export const DRAWINGS = { fixed_axis: buildFixedAxis, body_columns: buildBodyColumns, three_velocities: buildThreeVelocities };

/** The model's keys a story reads. @param {Model} model @returns {StoryModel} */
function readStory(model) {
  /** @type {Record<string, any>} */
  const keys = {};
  for (const k of ["story", "offset", "rate", "waves", "t_end", "frames", "closed", "speed", "box", "box_right",
    "scale", "theta_dot", "vel_scale", "axis_len", "q"]) keys[k] = model.get(k);
  const m = /** @type {StoryModel} */ (keys);
  if (!Object.keys(DRAWINGS).includes(m.story)) {
    throw new Error(`Expected story one of ${Object.keys(DRAWINGS).join(", ")}, got ${JSON.stringify(m.story)}`);
  }
  return m;
}

/**
 * The view (build): the story's drawing, its numbers and legend, then the time slider, Play and θ.
 * @param {HTMLElement} el @param {Model} model
 */
function build(el, model) {
  const { uid } = startView(el, { styles: [["jac-story-style", CSS]], prefix: "js" });
  const m = readStory(model);
  const chain = makeChain(model.get("S"), model.get("M"), model.get("Q") || null);
  const n = chain.n;
  const reach = Number(model.get("reach")) || 1;
  el.dataset.story = m.story;
  const { plot, side } = layout(el, "js-plot");
  const legend = html("ul", { class: "jl-legend" });
  const table = html("table", { class: "js-numbers" });
  const caption = html("caption", {}, table);
  const tbody = html("tbody", {}, table);
  /** @type {Record<string, HTMLTableCellElement[]>} */
  const rows = {};
  /** @type {StoryContext["tableRows"]} a row per [key, label], a column per name (coloured as colColors) */
  const tableRows = (labels, cols, colColors = null) => {
    const thead = html("thead", {}, table);
    const hr = html("tr", {}, thead);
    table.insertBefore(thead, tbody);
    html("th", { scope: "col" }, hr, "");
    cols.forEach((c, i) => html("th", { scope: "col", style: colColors ? `color:${ink(colColors[i])}` : "" }, hr, c));
    for (const [key, lab] of labels) {
      const tr = html("tr", {}, tbody);
      sub(html("th", { scope: "row" }, tr), lab);
      rows[key] = cols.map(() => html("td", {}, tr, ""));
    }
  };
  /** @type {StoryContext["setRow"]} */
  const setRow = (key, v, d = 2) => v.forEach((x, i) => setText(rows[key][i], fixed(x, d)));
  const drawStory = DRAWINGS[m.story]({ m, chain, n, head: 0.06 * reach, plot, legend, caption, tableRows, setRow });

  // the controls: the time slider, Play / Pause, θ
  const id = `${uid}-time`;
  const label = html("label", { for: id }, side);
  label.append("time ");
  const out = html("output", { for: id, class: "js-time-value" }, label);
  const slider = html("input", { type: "range", id, min: 0, max: m.frames - 1, step: 1, class: "js-time" }, side);
  const row = html("div", { class: "jl-row" }, side);
  const play = html("button", { type: "button", class: "jl-play", "aria-pressed": "false" }, row, "▶ Play");
  const thetaLine = html("p", { class: "jl-status js-theta" }, side);
  side.append(table, legend);
  return { m, chain, drawStory, out, slider, play, thetaLine };
}
/** @typedef {ReturnType<typeof build>} Parts */

/** The frame shown (0 to frames - 1) from the model's. @param {Model} model @param {StoryModel} m */
function readFrame(model, m) {
  const k = Math.round(Number(model.get("frame")));
  return Number.isFinite(k) ? ((k % m.frames) + m.frames) % m.frames : 0;
}

/**
 * Frame k drawn (update); returns what the view shows.
 * @param {Parts} parts @param {number} k
 */
function update({ m, chain, drawStory, out, slider, thetaLine }, k) {
  const s = storyState(chain, m, frameTime(m, k));
  const arrows = drawStory(s);
  setText(out, `t = ${fixed(s.t, 2)} s`);
  setText(thetaLine, `θ = (${s.theta.map((x) => `${fixed((x * 180) / Math.PI, 0)}°`).join(", ")})`);
  if (Number(slider.value) !== k) slider.value = String(k);
  slider.setAttribute("aria-valuetext", `t = ${fixed(s.t, 2)} s, frame ${k + 1} of ${m.frames}`);
  return { frame: k, ...s, arrows };
}

/**
 * The reader's input -> the model (bind): the time slider, Play (a frame every frame's time / speed).
 * Returns the remover and Play's stop.
 * @param {Parts} parts @param {Model} model @param {() => void} redraw @param {(playing: boolean) => void} onPlaying
 */
function bind({ m, slider, play }, model, redraw, onPlaying) {
  const setFrame = (/** @type {number} */ k) => save(model, "frame", k);
  const frameMs = (1000 * m.t_end) / (m.closed ? m.frames : m.frames - 1) / (m.speed || 1);
  const playing = player(play, () => setFrame((readFrame(model, m) + 1) % m.frames), frameMs, onPlaying);
  const unlisten = listen(model, ["frame"], redraw, [
    [play, "click", playing.toggle],
    [slider, "input", () => {
      playing.stop();
      setFrame(Number(slider.value));
    }],
  ]);
  return () => {
    playing.stop();
    unlisten();
  };
}

/** @param {{model: Model, el: HTMLElement}} args */
function render({ model, el }) {
  const parts = build(el, model);
  /** @type {Record<string, unknown>} */
  const state = { frame: null, drawn: null };
  const redraw = () => {
    const shown = update(parts, readFrame(model, parts.m));
    Object.assign(state, shown);
    publish(el, { view: "story", theta: shown.theta, step: shown.frame });
  };
  const unbind = bind(parts, model, redraw, (p) => publish(el, { playing: p ? 1 : 0 }));
  redraw();
  publish(el, { playing: 0 });
  const cleanup = finishView(el, state, unbind);
  // labels at slide size once the drawing has its width (a deck's slide is laid out when shown)
  /** @type {Panel[]} */
  const panels = [...el.querySelectorAll("svg")].map((r) => /** @type {{jsPanel?: Panel}} */ (r).jsPanel)
    .filter((P) => P !== undefined);
  const fit = () => { if (panels.map(fitLabels).some(Boolean)) redraw(); };
  const watch = typeof ResizeObserver === "function" ? new ResizeObserver(fit) : null;
  if (watch) panels.forEach((P) => watch.observe(P.root));
  fit();
  return () => {
    if (watch) watch.disconnect();
    cleanup();
  };
}

export { render };
export default { render };
