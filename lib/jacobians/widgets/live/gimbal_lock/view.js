// @ts-check
// Gimbal lock, live: a spherical wrist, the coordinates φ
// of its tool orientation (ZYX or ZYZ), B(φ) with ω_s = B(φ) φ̇, det B, and the
// analytic Jacobian J_a = diag(B(φ)⁻¹, I) J blowing up next to the geometric J
// as φ nears the lock, while σ_min of J's angular rows says whether the wrist
// itself is singular. In 3-D (the reader turns it): the three joint axes with
// their gimbal rings, the tool frame, and the columns of B(φ), the axes the
// three coordinate angles turn about; at the lock two of them line up. A chart
// gives ‖J_a‖, ‖J‖ and |det B| along θ₂ with θ₁, θ₃ fixed (as the matplotlib
// explorer jacobians.widgets.gimbal did), and a banner says when the view is at
// or near the lock, or at the wrist's own singularity.
//
// anywidget-compatible: `export default { render }`; render({model, el}) reads
// wrists {key: {name, S, M, Q}}, wrist (a key), theta (3, rad), rep ("zyx" | "zyz"),
// limit_deg, step_deg, tool (m), near (|det B| below it: near the lock),
// wrist_singular (σ_min below it: the wrist is singular), palette, column_colors;
// writes theta, wrist and rep back. At the lock J_a is "undefined": never NaN,
// never a throw. _ext/live_views_spatial.py writes the model from the library.

import {
  analyticJacobian, coordinatesFromRotation, evaluate, makeChain, rateToAngularVelocity, singularValues,
} from "../kinematics.js";
import {
  PALETTE, TWIST_ROWS, finishView, fixed, graphic, html, ink, jointSliders, layout, listen, matrixTable, publish, put,
  save, showAngle, startView, sub, svg, text,
} from "../ui.js";
import { CSS as CSS3D, FONT, createView3D, frameItems } from "../view3d.js";

/** @typedef {import("../ui.js").SubText} SubText */
/** @typedef {import("../ui.js").MatrixTable} MatrixTable */
/** @typedef {import("../host.js").Model} Model */
/** @typedef {import("../kinematics.js").Chain} Chain */
/** @typedef {import("../kinematics.js").Evaluation} Evaluation */
/** @typedef {import("../kinematics.js").Representation} Representation */
/** @typedef {import("../linalg.js").Vec} Vec */
/** @typedef {import("../linalg.js").Mat} Mat */
/** @typedef {{name?: string, S: Mat, M: Mat, Q?: Mat | null}} WristModel a wrist of the model's "wrists" */
/**
 * What build and update share: the model's numbers and names.
 * @typedef {{uid: string, tool: number, pal: Record<string, string>, colColors: string[], limitDeg: number,
 *   stepDeg: number, wristModels: Record<string, WristModel>, keys: string[], theta0: number[]}} Options
 */
/** @typedef {ReturnType<typeof buildScene>} Scene */
/** @typedef {ReturnType<typeof buildChart>} Chart */
/** @typedef {ReturnType<typeof buildControls>} Controls */
/**
 * What the view shows (el.jacLive, read by the tests), and the keys of what was last drawn.
 * @typedef {{theta: Vec | null, wrist: string | null, rep: Representation | null, curveKey: string | null,
 *   capKey?: string, statusKey?: string, [more: string]: unknown}} GimbalState
 */
/** @type {Record<Representation, string>} */
const REPS = { zyx: "ZYX (yaw, pitch, roll)", zyz: "ZYZ Euler" };
/** @type {Record<Representation, string>} */
const DET = { zyx: "−cos φ", zyz: "−sin φ" };
const DEFAULT_PALETTE = { analytic: PALETTE.analytic, geometric: PALETTE.geometric, link: PALETTE.link,
  joint: PALETTE.joint, singular: PALETTE.singular, warning: PALETTE.warning, space: PALETTE.space, muted: PALETTE.muted };
const DEFAULT_COLUMNS = ["vermillion", "blue", "green"];
const CHART = { w: 400, h: 190, left: 52, right: 24, top: 12, bottom: 46, lo: -2, hi: 3 }; // log10 range
const N_CURVE = 121; // θ2 every 3°
const LOCK_TOL = 1e-9; // kinematics.analyticJacobian's tol (the library's)
// what this view draws differently from the shared style (ui.js), scoped by its class
const CSS = `
.jac-live.jl-gimbal{contain:content}
.jl-gimbal .jl-side{flex:1 1 280px}
.jl-gimbal table.jl-matrix{table-layout:fixed;width:15em}
.jl-gimbal table.jl-matrix th[scope=col]:first-child{width:2.4em}
.jl-gimbal td,.jl-gimbal th{padding:1px 6px}
.jl-gimbal td{min-width:0}
.jl-gimbal .jl-tables{display:flex;flex-wrap:wrap;column-gap:16px;align-items:flex-start}
.jl-gimbal .jl-chart svg{width:100%;height:auto;display:block;margin-top:8px}
`;

const det3 = (/** @type {Mat} */ A) => A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1])
  - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) + A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
/** The inverse of a 3×3 matrix by its adjugate (B(φ) away from the lock). @param {Mat} A @returns {Mat} */
function inverse3(A) {
  const d = det3(A);
  const C = (/** @type {number} */ i, /** @type {number} */ j) => {
    const r = [0, 1, 2].filter((k) => k !== i), c = [0, 1, 2].filter((k) => k !== j);
    return ((i + j) % 2 ? -1 : 1) * (A[r[0]][c[0]] * A[r[1]][c[1]] - A[r[0]][c[1]] * A[r[1]][c[0]]);
  };
  return [0, 1, 2].map((i) => [0, 1, 2].map((j) => C(j, i) / d));
}
const frob = (/** @type {Mat} */ J) => Math.sqrt(J.reduce((s, row) => s + row.reduce((t, x) => t + x * x, 0), 0));
const deg = (/** @type {number} */ x) => (x * 180) / Math.PI;

/**
 * A number for a table cell: 2 decimals, or 3 significant digits in exponent form when huge; never NaN.
 * @param {number} x @returns {string}
 */
export function cell(x) {
  if (!Number.isFinite(x)) return "—";
  if (Math.abs(x) < 1e4) return fixed(x, 2);
  return x.toExponential(2).replace("-", "\u2212").replace("e+", "e");
}

/**
 * The 3-D drawing of the wrist: its axes, rings, the frames, the columns of B(φ) (build).
 * @param {HTMLElement} plot @param {Options} options
 */
function buildScene(plot, { uid, tool, pal, colColors }) {
  const R0 = 1.55 * tool; // the tool frame stays inside at every pose
  const view = createView3D(plot, {
    id: uid, center: [0, 0, 0], extent: R0, azimuth: -0.95, elevation: 0.4,
    label: "The wrist: joint axes 1 to 3 with their rings, the tool frame {b}, and the axes φ1, φ2, φ3 that the "
      + "coordinate angles turn about (the columns of B(φ))",
  });
  const sFrame = frameItems(view, "{s}", 0.45 * tool, { letters: true, width: 1.5 });
  sFrame.set([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0]);
  const rings = [0, 1, 2].map((i) => view.ring("solid", { stroke: colColors[i], "stroke-width": 3,
    class: `jl-ring jl-ring-${i + 1}` }));
  const axes = [0, 1, 2].map((i) => view.segment("solid", { stroke: colColors[i], "stroke-width": 4,
    class: `jl-axis jl-axis-${i + 1}` }));
  const axisNums = [0, 1, 2].map((i) => view.label("front", String(i + 1), { fill: ink(colColors[i]),
    "font-weight": "bold" }));
  const link = view.segment("solid", { stroke: pal.link, "stroke-width": 6, class: "jl-link" });
  const centre = view.dot("solid", { r: 6, fill: PALETTE.bg, stroke: pal.joint, "stroke-width": 2.5 });
  const bFrame = frameItems(view, "{b}", 0.4 * tool, { letters: true });
  const bCols = [0, 1, 2].map(() => view.arrow("solid", pal.analytic, 3, 12));
  bCols.forEach((a, k) => a.el.setAttribute("class", `jl-bcol jl-bcol-${k + 1}`));
  bCols.forEach((a) => a.el.querySelector("line")?.setAttribute("stroke-dasharray", "7 5"));
  const bLabels = [0, 1, 2].map((k) => view.label("front", `φ${String.fromCharCode(0x2081 + k)}`,
    { fill: ink("plum"), "font-style": "italic" }));

  return { view, rings, axes, axisNums, link, centre, bFrame, bCols, bLabels };
}

/**
 * The chart of ‖J_a‖, ‖J‖ and |det B| along θ2, log scale (build): its scales and the lines update() moves.
 * @param {HTMLElement} plot @param {Options} options
 */
function buildChart(plot, { pal, limitDeg }) {
  const chartBox = html("div", { class: "jl-chart" }, plot);
  const chart = svg("svg", { viewBox: `0 0 ${CHART.w} ${CHART.h}`, role: "img", "font-size": FONT - 2, fill: PALETTE.fg,
    "aria-label": "Along θ2 with θ1 and θ3 fixed: the size of J_a, of J, and |det B|, log scale; a line at the current θ2" },
  chartBox);
  const X = (/** @type {number} */ d) => CHART.left + ((d + limitDeg) / (2 * limitDeg)) * (CHART.w - CHART.left - CHART.right);
  const Y = (/** @type {number} */ v) => {
    const l = Math.log10(Math.max(v, 10 ** (CHART.lo - 0.5)));
    const t = (Math.min(l, CHART.hi + 0.5) - CHART.lo) / (CHART.hi - CHART.lo);
    return CHART.h - CHART.bottom - t * (CHART.h - CHART.top - CHART.bottom);
  };
  const yBottom = CHART.h - CHART.bottom;
  svg("rect", { x: CHART.left, y: CHART.top, width: CHART.w - CHART.left - CHART.right, height: yBottom - CHART.top,
    fill: "none", stroke: PALETTE.border }, chart);
  for (let p = CHART.lo; p <= CHART.hi; p++) {
    svg("line", { x1: CHART.left, x2: CHART.w - CHART.right, y1: Y(10 ** p), y2: Y(10 ** p), stroke: PALETTE.faint }, chart);
    svg("text", { x: CHART.left - 4, y: Y(10 ** p), "text-anchor": "end", "dominant-baseline": "central" }, chart)
      .textContent = p === 0 ? "1" : `10${p < 0 ? "⁻" : ""}${"⁰¹²³⁴⁵⁶⁷⁸⁹"[Math.abs(p)]}`;
  }
  for (const d of [-180, -90, 0, 90, 180]) {
    if (Math.abs(d) > limitDeg) continue;
    svg("text", { x: X(d), y: yBottom + 16, "text-anchor": "middle" }, chart).textContent = `${fixed(d, 0)}°`;
  }
  svg("text", { x: (CHART.left + CHART.w) / 2, y: CHART.h - 6, "text-anchor": "middle" }, chart)
    .textContent = "θ₂ (θ₁, θ₃ fixed)";
  const curveA = svg("polyline", { fill: "none", stroke: pal.analytic, "stroke-width": 2.5, class: "jl-curve-a" }, chart);
  const curveJ = svg("polyline", { fill: "none", stroke: pal.geometric, "stroke-width": 2.5, "stroke-dasharray": "6 4",
    class: "jl-curve-j" }, chart);
  const curveD = svg("polyline", { fill: "none", stroke: PALETTE.fg, "stroke-width": 2, "stroke-dasharray": "2 3",
    class: "jl-curve-d" }, chart);
  const cursor = svg("line", { y1: CHART.top, y2: yBottom, stroke: PALETTE.fg, "stroke-width": 1.2, class: "jl-cursor" },
    chart);
  const legend = html("ul", { class: "jl-legend" }, chartBox);
  /** @type {[string, string, SubText][]} */
  const keys = [[pal.analytic, "", ["‖J", "a‖ (Frobenius), undefined at the lock"]],
    [pal.geometric, "dashed", ["‖J‖, the geometric Jacobian", ""]], [PALETTE.fg, "dotted", ["|det B(φ)|", ""]]];
  for (const [colour, dash, words] of keys) {
    const li = html("li", {}, legend);
    html("span", { class: "jl-key", style: dash ? `border-top:3px ${dash} ${colour};height:0` : `background:${colour}` },
      li);
    sub(li, words);
  }

  return { X, Y, curveA, curveJ, curveD, cursor };
}

/**
 * The selects, the sliders, the banner and status, the tables of B, J and J_a (build).
 * @param {HTMLElement} side @param {Options} options
 */
function buildControls(side, { uid, wristModels, keys, limitDeg, stepDeg, colColors, theta0 }) {
  const wristLabel = html("label", { for: `${uid}-wrist` }, side, "Wrist:");
  const wristSelect = html("select", { id: `${uid}-wrist`, class: "jl-wrist" }, wristLabel);
  for (const k of keys) html("option", { value: k }, wristSelect, wristModels[k].name || k);
  const repLabel = html("label", { for: `${uid}-rep` }, side, "Coordinates φ:");
  const repSelect = html("select", { id: `${uid}-rep`, class: "jl-rep" }, repLabel);
  for (const [k, words] of Object.entries(REPS)) html("option", { value: k }, repSelect, words);
  const { sliders, values } = jointSliders(side, 3, uid, { min: -limitDeg, max: limitDeg, step: stepDeg,
    value: (i) => deg(Number(theta0[i]) || 0), color: (i) => colColors[i] });
  const banner = html("p", { class: "jl-banner", role: "status" }, side);
  const status = html("p", { class: "jl-status", "aria-live": "polite" }, side);
  const tables = html("div", { class: "jl-tables" }, side);
  /** @type {(cls: string, rows: ReadonlyArray<SubText>, cols: ReadonlyArray<SubText>) => MatrixTable} */
  const makeTable = (cls, rows, cols) => matrixTable(tables, cls, rows, cols);
  /** @type {SubText[]} */
  const rateCols = [["φ̇", "1"], ["φ̇", "2"], ["φ̇", "3"]];
  /** @type {SubText[]} */
  const jointCols = [["θ̇", "1"], ["θ̇", "2"], ["θ̇", "3"]];
  const tB = makeTable("jl-B", TWIST_ROWS.slice(0, 3), rateCols);
  const tJ = makeTable("jl-J", TWIST_ROWS, jointCols);
  const tA = makeTable("jl-Ja", [["φ̇", "1"], ["φ̇", "2"], ["φ̇", "3"], ["ṗ", "x"], ["ṗ", "y"], ["ṗ", "z"]], jointCols);
  sub(tJ.caption, ["J", ""]).append("(θ), geometric");
  tB.caption.append("B(φ), ω");
  sub(tB.caption, ["", "s"]).append(" = B(φ) φ̇");

  return { wristSelect, repSelect, sliders, values, banner, status, tB, tJ, tA };
}

// One sweep per point: J from evaluate, φ from its R, then J_a's angular rows B(φ)⁻¹ J_ω
// (the same J_a as analyticJacobian; test_live_gimbal.py reads the curves back against the library).
/**
 * @param {Chain} chain @param {Vec} th @param {Representation} rep @param {number} limitDeg
 * @param {Chart} chart
 */
function curves(chain, th, rep, limitDeg, { X, Y, curveA, curveJ, curveD }) {
  /** @type {string[]} */
  const A = [], G = [], D = [];
  for (let k = 0; k < N_CURVE; k++) {
    const d = -limitDeg + (2 * limitDeg * k) / (N_CURVE - 1);
    const t = [th[0], (d * Math.PI) / 180, th[2]];
    const e = evaluate(chain, t);
    const J = e.Jg;
    const phi = coordinatesFromRotation([e.T[0].slice(0, 3), e.T[1].slice(0, 3), e.T[2].slice(0, 3)], rep);
    const margin = rep === "zyx" ? Math.abs(Math.cos(phi[1])) : Math.abs(Math.sin(phi[1]));
    let lin = 0, ang = 0;
    for (let r = 3; r < 6; r++) for (let c = 0; c < 3; c++) lin += J[r][c] * J[r][c];
    for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) ang += J[r][c] * J[r][c];
    const x = X(d).toFixed(1);
    G.push(`${x},${Y(Math.sqrt(lin + ang)).toFixed(1)}`);
    D.push(`${x},${Y(margin).toFixed(1)}`); // |det B| = the margin, |cos φ2| or |sin φ2|
    if (margin < LOCK_TOL) {
      A.push(`${x},${Y(1e9).toFixed(1)}`); // off the top: undefined at the lock
      continue;
    }
    const B = rateToAngularVelocity(phi, rep);
    const Bi = inverse3(B);
    let sa = 0;
    for (let c = 0; c < 3; c++) {
      for (let i = 0; i < 3; i++) {
        const y = Bi[i][0] * J[0][c] + Bi[i][1] * J[1][c] + Bi[i][2] * J[2][c];
        sa += y * y;
      }
    }
    A.push(`${x},${Y(Math.sqrt(sa + lin)).toFixed(1)}`);
  }
  put(curveA, "points", A.join(" "));
  put(curveJ, "points", G.join(" "));
  put(curveD, "points", D.join(" "));
}

/**
 * Put the wrist's axes, rings, B(φ)'s columns and the frames where e (evaluate) and B say, and redraw (update).
 * @param {Scene} scene @param {Evaluation} e @param {Mat} B @param {number} tool
 */
function drawScene({ view, rings, axes, axisNums, link, centre, bFrame, bCols, bLabels }, e, B, tool) {
  const L = [0.95 * tool, 0.95 * tool, 0.95 * tool];
  const radius = [0.8 * tool, 0.66 * tool, 0.52 * tool];
  for (let i = 0; i < 3; i++) {
    const u = [e.Jg[0][i], e.Jg[1][i], e.Jg[2][i]];
    axes[i].set(u.map((x) => -L[i] * x), u.map((x) => L[i] * x));
    axisNums[i].set(u.map((x) => 1.12 * L[i] * x));
    rings[i].set([0, 0, 0], u, radius[i]);
    const b = [B[0][i], B[1][i], B[2][i]];
    bCols[i].set([0, 0, 0], b.map((x) => 0.75 * tool * x));
    bLabels[i].set(b.map((x) => 0.75 * tool * x), null, 14 * (i - 1), -14);
  }
  const p = [e.T[0][3], e.T[1][3], e.T[2][3]];
  link.set([0, 0, 0], p);
  centre.set([0, 0, 0]);
  bFrame.set([e.T[0].slice(0, 3), e.T[1].slice(0, 3), e.T[2].slice(0, 3)], p);
  view.render();
}

/**
 * The status lines: φ, det B(φ), σ_min of J's ω rows, ‖J‖ and ‖J_a‖ (update; rewritten only when they change).
 * @param {HTMLElement} status @param {GimbalState} state
 * @param {{rep: Representation, phi: Vec, detB: number, sigmaMin: number, wristSing: boolean, normJ: number,
 *   normA: number | null}} numbers
 */
function writeStatus(status, state, { rep, phi, detB, sigmaMin, wristSing, normJ, normA }) {
  const statusKey = [rep, ...phi.map((x) => fixed(deg(x), 1)), fixed(detB, 4), fixed(sigmaMin, 3), wristSing,
    fixed(normJ, 2), normA === null ? "u" : cell(normA)].join("|");
  if (statusKey !== state.statusKey) {
    state.statusKey = statusKey;
    status.textContent = "";
    status.append(`φ (${rep.toUpperCase()}) = (${phi.map((x) => `${fixed(deg(x), 1)}°`).join(", ")})`);
    html("br", {}, status);
    status.append(`det B(φ) = ${DET[rep]}`);
    sub(status, ["", "2"]).append(` = ${fixed(detB, 4)}`);
    html("br", {}, status);
    sub(status, ["σ", "min"]).append(" of J's ω rows = ");
    status.append(`${fixed(sigmaMin, 3)}${wristSing ? " (the wrist is singular)" : ""}`);
    html("br", {}, status);
    status.append(`‖J‖ = ${fixed(normJ, 2)}, ‖J`);
    sub(status, ["", "a"]).append(`‖ = ${normA === null ? "undefined" : cell(normA)}`);
  }
}

/**
 * The reader's input -> the model: a slider sets theta (degrees shown, radians kept), the selects the wrist and the
 * coordinates; a change of the model redraws (bind). Returns the remover of all of it.
 * @param {Model} model
 * @param {{wristSelect: HTMLSelectElement, repSelect: HTMLSelectElement, sliders: HTMLInputElement[]}} controls
 * @param {() => Vec} readTheta @param {() => void} draw @returns {() => void}
 */
function bind(model, { wristSelect, repSelect, sliders }, readTheta, draw) {
  const onInput = (/** @type {Event} */ ev) => {
    const slider = /** @type {HTMLInputElement} */ (ev.target);
    const th = readTheta();
    const i = Number(slider.dataset.joint) - 1;
    const v = Number(slider.value);
    if (!Number.isFinite(v)) return;
    th[i] = (v * Math.PI) / 180;
    save(model, "theta", th);
  };
  return listen(model, ["theta", "wrist", "rep"], draw, [
    ...sliders.map((s) => /** @type {import("../ui.js").Listener} */ ([s, "input", onInput])),
    [wristSelect, "change", () => save(model, "wrist", wristSelect.value)],
    [repSelect, "change", () => save(model, "rep", repSelect.value)],
  ]);
}

/**
 * The model's numbers, checked, with their defaults (what build, update and bind share).
 * @param {Model} model @param {string} uid
 */
function options(model, uid) {
  /** @type {Record<string, WristModel>} */
  const wristModels = model.get("wrists");
  /** @type {Record<string, Chain>} */
  const chains = {};
  for (const [k, w] of Object.entries(wristModels)) chains[k] = makeChain(w.S, w.M, w.Q || null);
  const given = { ...DEFAULT_PALETTE, ...(model.get("palette") || {}) };
  return {
    uid, chains, wristModels, keys: Object.keys(chains),
    // the library's Okabe–Ito colours as the page's mode draws them (palette.js)
    /** @type {Record<string, string>} */
    pal: Object.fromEntries(Object.entries(given).map(([k, c]) => [k, graphic(c)])),
    /** @type {string[]} */
    colColors: (model.get("column_colors") || DEFAULT_COLUMNS).map(graphic),
    limitDeg: Number(model.get("limit_deg")) || 180,
    stepDeg: Number(model.get("step_deg")) || 0.5,
    tool: Number(model.get("tool")) || 0.3,
    near: Number(model.get("near")) || 0.1,
    wristSingular: Number(model.get("wrist_singular")) || 1e-3,
    /** @type {number[]} */
    theta0: model.get("theta"),
  };
}

/** @typedef {ReturnType<typeof options>} Opts */
/** @typedef {{o: Opts, scene: Scene, chart: Chart} & Controls} Parts */

/** The wrist shown (a key of the model's wrists). @param {Model} model @param {string[]} keys @returns {string} */
function readWrist(model, keys) {
  const w = model.get("wrist");
  return keys.includes(w) ? w : keys[0];
}
/** @param {Model} model @returns {Representation} */
function readRep(model) {
  const r = model.get("rep");
  return r in REPS ? r : "zyx";
}
/** θ from the model (rad), within ±limit_deg. @param {Model} model @param {number} limitDeg @returns {Vec} */
function readTheta(model, limitDeg) {
  const th = model.get("theta");
  const lim = (limitDeg * Math.PI) / 180;
  return [0, 1, 2].map((i) => {
    const v = Number(th && th[i]);
    return Number.isFinite(v) ? Math.max(-lim, Math.min(lim, v)) : 0;
  });
}

/**
 * The wrist w at θ in coordinates rep drawn (update): the scene, the chart, the tables, the banner and the status;
 * `state`, what was drawn last, becomes what is drawn now.
 * @param {Parts} parts @param {string} w @param {Representation} rep @param {Vec} th @param {GimbalState} state
 */
function update(parts, w, rep, th, state) {
  const { chains, tool, limitDeg, near, wristSingular, pal } = parts.o;
  const { tB, tJ, tA, banner, status, sliders, values, wristSelect, repSelect } = parts;
  const chain = chains[w];
  const e = evaluate(chain, th);
  const a = analyticJacobian(chain, th, rep);
  const B = rateToAngularVelocity(a.phi, rep);
  const detB = det3(B);
  const sv = singularValues([e.Jg[0], e.Jg[1], e.Jg[2]]);
  const sigmaMin = sv[2];
  const normJ = frob(e.Jg);
  const normA = a.singular || !a.J ? null : frob(a.J);
  drawScene(parts.scene, e, B, tool);
  // chart
  // Along θ2 the three norms do not depend on θ1: joint 1 turns the whole wrist about z, which turns J's
  // columns about z and adds θ1 to φ1 (both ZYX and ZYZ start with a turn about z), and B(φ) = R_z(φ1) B(0, φ2, φ3).
  // So the chart is redone only when θ3, the wrist or the coordinates change (the test checks it at any θ1).
  const key = `${w}|${rep}|${th[2]}`;
  if (key !== state.curveKey) {
    curves(chain, th, rep, limitDeg, parts.chart);
    state.curveKey = key;
  }
  const cx = parts.chart.X(deg(th[1])).toFixed(1);
  put(parts.chart.cursor, "x1", cx);
  put(parts.chart.cursor, "x2", cx);
  // numbers
  for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) text(tB.cells[r][c], cell(B[r][c]));
  for (let r = 0; r < 6; r++) {
    for (let c = 0; c < 3; c++) {
      text(tJ.cells[r][c], cell(e.Jg[r][c]));
      text(tA.cells[r][c], a.singular || !a.J ? "—" : cell(a.J[r][c]));
    }
  }
  const capKey = a.singular ? "lock" : rep;
  if (capKey !== state.capKey) {
    tA.caption.textContent = "";
    sub(tA.caption, ["J", "a"]).append(a.singular ? "(θ): undefined at the lock" : `(θ), ${rep.toUpperCase()}`);
    state.capKey = capKey;
  }
  /** @type {string} */
  let level;
  /** @type {string} */
  let word;
  const margin = a.margin;
  if (a.singular) {
    level = "singular";
    word = `Gimbal lock: det B(φ) = 0, the ${rep.toUpperCase()} angle rates are not defined, Jₐ does not exist`;
  } else if (margin < near) {
    level = "warning";
    word = `Near gimbal lock: |det B(φ)| = ${fixed(margin, 3)}, Jₐ is huge`;
  } else {
    level = "ok";
    word = "";
  }
  const wristSing = sigmaMin < wristSingular;
  if (wristSing) {
    word = `${word ? `${word}. ` : ""}The wrist itself is singular: σₘᵢₙ of J’s ω rows is ${fixed(sigmaMin, 3)}`;
    if (level === "ok") level = "wrist";
  }
  text(banner, word);
  banner.hidden = word === "";
  put(banner, "style", `border-color:${level === "warning" ? pal.warning : pal.singular}`);
  writeStatus(status, state, { rep, phi: a.phi, detB, sigmaMin, wristSing, normJ, normA });
  for (let i = 0; i < 3; i++) showAngle(values[i], sliders[i], th[i], deg(th[i]), 1e-9);
  if (wristSelect.value !== w) wristSelect.value = w;
  if (repSelect.value !== rep) repSelect.value = rep;
  Object.assign(state, { theta: th, wrist: w, rep, phi: a.phi, B, detB, Ja: a.J, J: e.Jg, T: e.T, sigmaMin,
    margin, singular: a.singular, level, normJ, normA });
}

/** @param {{model: Model, el: HTMLElement}} args */
function render({ model, el }) {
  const { uid } = startView(el, { classes: ["jl-gimbal"],
    styles: [["jac-live-style-3d", CSS3D], ["jac-live-style-gimbal", CSS]] });
  const o = options(model, uid);
  const { plot, side } = layout(el);
  /** @type {Parts} */
  const parts = { o, scene: buildScene(plot, o), chart: buildChart(plot, o), ...buildControls(side, o) };
  /** @type {GimbalState} */
  const state = { theta: null, wrist: null, rep: null, curveKey: null };
  const redraw = () => {
    update(parts, readWrist(model, o.keys), readRep(model), readTheta(model, o.limitDeg), state);
    publish(el, { view: "gimbal_lock", theta: /** @type {Vec} */ (state.theta), level: String(state.level),
      wrist: String(state.wrist), rep: String(state.rep) });
  };
  const unlisten = bind(model, parts, () => readTheta(model, o.limitDeg), redraw);
  redraw();
  return finishView(el, state, () => {
    unlisten();
    parts.scene.view.destroy();
  }, { jacView: parts.scene.view });
}

export { render };
export default { render };
