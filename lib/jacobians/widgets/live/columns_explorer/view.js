// @ts-check
// The columns explorer, live: which joints move which
// column of J_s and of J_b, on the spatial 5R arm of the notes. One slider per
// joint; the arm and its joint (screw) axes in a 3-D view the reader turns;
// J_s and J_b with their current numbers. After a joint moves, the columns whose
// numbers changed are coloured and listed: moving θ_k changes the columns of J_s
// after k and the columns of J_b before k. A watched column i colours the axes
// by role: the joints before i (they move column i of J_s), joint i, the joints
// after i (they move column i of J_b), as jacobians.widgets.columns did.
//
// anywidget-compatible: `export default { render }`; render({model, el}) reads
// S (6×n), M (4×4), Q (n×3 joint axis points), theta (n, rad), column (1-based),
// name, limit (slider range ±limit rad), step (rad), reach, center (3), extent,
// axis_length (m), palette {space, body, link, joint, muted}; it writes theta and
// column back (model.set + save_changes) and redraws on "change:theta" /
// "change:column". _ext/live_views_spatial.py writes the model from the library.
// Never throws on a reachable input, never shows NaN.

import { evaluate, makeChain } from "../kinematics.js";
import {
  PALETTE, TWIST_ROWS, finishView, fixed, graphic, html, jointSliders, layout, listen, matrixTable, publish, put,
  save, showAngle, sliderLimit, startView, sub, text, tint,
} from "../ui.js";
import { CSS as CSS3D, createView3D, frameItems, groundGrid } from "../view3d.js";

/** @typedef {import("../host.js").Model} Model */
/** @typedef {import("../linalg.js").Mat} Mat */
/** @typedef {import("../ui.js").SubText} SubText */
/** @typedef {import("../ui.js").MatrixTable} MatrixTable */
/** @typedef {import("../view3d.js").Segment} Segment */
/** @typedef {import("../view3d.js").Dot} Dot */
/** @typedef {import("../view3d.js").Label} Label */
/**
 * What the view shows, and what changed when a joint last moved (el.jacLive, read by the tests).
 * @typedef {object} ColumnsState
 * @property {number[] | null} theta
 * @property {number | null} column 1-based
 * @property {Mat | null} Js
 * @property {Mat | null} Jb
 * @property {number[]} moved the joints (1-based) that moved
 * @property {number[]} changedS the columns of J_s that changed
 * @property {number[]} changedB the columns of J_b that changed
 * @property {string | null} changeKey
 * @property {Mat} [T]
 * @property {number[][]} [points]
 */

const CHANGE_TOL = 1e-12; // as jacobians.widgets.columns: a column "changed" if an entry moved by more
const DEFAULT_PALETTE = { space: PALETTE.space, body: PALETTE.body, link: PALETTE.link, joint: PALETTE.joint,
  muted: PALETTE.muted };
// what this view draws differently from the shared style (ui.js), scoped by its class
const CSS = `
.jac-live.jl-columns{contain:content}
.jl-columns .jl-side{flex:1 1 280px}
.jl-columns select{max-width:none}
.jl-columns table.jl-matrix{table-layout:fixed;width:21.4em}
.jl-columns table.jl-matrix th[scope=col]:first-child{width:2.4em}
.jl-columns td,.jl-columns th{padding:1px 6px}
.jl-columns td{min-width:0}
.jl-columns .jl-key{width:14px;height:14px;border-radius:50%;vertical-align:-2px;border:1px solid var(--jl-ink)}
.jl-columns .jl-changes{font-size:15px;margin:6px 0;min-height:2.7em}
.jl-columns .jl-tables{display:flex;flex-wrap:wrap;column-gap:16px;align-items:flex-start}
.jl-columns td.jl-watch,.jl-columns th.jl-watch{outline:2px solid var(--jl-ink);outline-offset:-2px}
`;

/**
 * The model's numbers, checked, with their defaults (what build, update and bind share).
 * @param {Model} model
 */
function options(model) {
  const chain = makeChain(model.get("S"), model.get("M"), model.get("Q") || null);
  const n = chain.n;
  const given = { ...DEFAULT_PALETTE, ...(model.get("palette") || {}) };
  const reach = Number(model.get("reach")) || 1;
  return {
    chain, n, reach,
    // the library's Okabe–Ito colours as the page's mode draws them (palette.js)
    pal: Object.fromEntries(Object.entries(given).map(([k, c]) => [k, graphic(c)])),
    limit: sliderLimit(model),
    step: Number(model.get("step")) || 0.01,
    axisLen: Number(model.get("axis_length")) || 0.15 * reach,
    name: model.get("name") || `${n}-joint arm`,
  };
}
/** @typedef {ReturnType<typeof options>} Options */

/**
 * The 3-D drawing (build): ground, {s}, the links, the joint axes, the joints, {b}, the axes' numbered dots.
 * @param {HTMLElement} plot @param {Options} o @param {Model} model @param {string} uid
 */
function buildScene(plot, { n, reach, pal, name }, model, uid) {
  const view = createView3D(plot, {
    id: uid, center: model.get("center") || [0, 0, 0], extent: Number(model.get("extent")) || 1.3 * reach,
    azimuth: -1.05, elevation: 0.5,
    label: `${name}: the arm, its joint axes numbered 1 to ${n} (coloured by which column of J_s or J_b they move), `
      + "the frames {s} and {b}",
  });
  groundGrid(view, 0.75 * reach, 6);
  const sFrame = frameItems(view, "{s}", 0.35 * reach / 2, { letters: true });
  const eye = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  sFrame.set(eye, [0, 0, 0]);
  /** @type {Segment[]} */
  const links = [];
  for (let k = 0; k < n; k++) {
    links.push(view.segment("solid", { stroke: pal.link, "stroke-width": 7, class: `jl-link jl-link-${k + 1}` }));
  }
  /** @type {Segment[]} */
  const axes = [];
  for (let i = 0; i < n; i++) axes.push(view.segment("solid", { "stroke-width": 4, class: `jl-axis jl-axis-${i + 1}` }));
  /** @type {Dot[]} */
  const joints = [];
  for (let i = 0; i < n; i++) {
    joints.push(view.dot("solid", { r: 7, fill: PALETTE.bg, stroke: pal.joint, "stroke-width": 2.5 }));
  }
  const bFrame = frameItems(view, "{b}", 0.35 * reach / 2);
  /** @type {Dot[]} */
  const axisDots = [];
  /** @type {Label[]} */
  const axisNums = [];
  for (let i = 0; i < n; i++) {
    axisDots.push(view.dot("front", { r: 13, stroke: PALETTE.fg, "stroke-width": 1.5, class: "jl-axis-key" }));
    axisNums.push(view.label("front", String(i + 1), { "font-weight": "bold", stroke: "none", class: "jl-axis-num" }));
    axisNums[i].anchor = axisDots[i]; // the number sits on its dot
  }
  return { view, links, axes, joints, bFrame, axisDots, axisNums };
}

/**
 * The controls and the numbers (build): the watched column, a slider a joint, the legend, what changed, J_s and J_b.
 * @param {HTMLElement} side @param {Options} o @param {Model} model @param {string} uid
 */
function buildControls(side, { n, limit, step }, model, uid) {
  const colLabel = html("label", { for: `${uid}-col` }, side, "Watch column");
  const select = html("select", { id: `${uid}-col`, class: "jl-column" }, colLabel);
  for (let i = 1; i <= n; i++) html("option", { value: i }, select, `${i}`);
  const theta0 = model.get("theta");
  const { sliders, values, keys } = jointSliders(side, n, uid, { min: -limit, max: limit, step, value: (i) => theta0[i],
    keys: true });
  const legend = html("ul", { class: "jl-legend" }, side);
  const changes = html("p", { class: "jl-changes", "aria-live": "polite" }, side);
  const tables = html("div", { class: "jl-tables" }, side);
  /** @param {SubText} symbol @param {string} cls @param {string} words */
  function makeTable(symbol, cls, words) {
    const t = matrixTable(tables, cls, TWIST_ROWS, Array.from({ length: n }, (_, i) => `${i + 1}`));
    sub(t.caption, symbol).append(`(θ), ${words}`);
    return t;
  }
  const tS = makeTable(["J", "s"], "jl-space", "space Jacobian");
  const tB = makeTable(["J", "b"], "jl-body", "body Jacobian");
  return { select, sliders, values, keys, legend, changes, tS, tB };
}
/** @typedef {ReturnType<typeof buildScene> & ReturnType<typeof buildControls> & {o: Options}} Parts */

/** θ from the model, in the sliders' range (0 for what is not a number). @param {Model} model @param {Options} o */
function readTheta(model, { n, limit }) {
  const th = model.get("theta");
  return Array.from({ length: n }, (_, i) => {
    const v = Number(th && th[i]);
    return Number.isFinite(v) ? Math.max(-limit, Math.min(limit, v)) : 0;
  });
}
/** The watched column, 1 to n. @param {Model} model @param {number} n */
function readColumn(model, n) {
  const c = Math.round(Number(model.get("column")));
  return c >= 1 && c <= n ? c : 1;
}

/** @param {Mat | null} A @param {Mat} B @param {number} n @returns {number[]} the columns (1-based) that differ */
function changedColumns(A, B, n) {
  /** @type {number[]} */
  const out = [];
  if (!A || !B) return out;
  for (let c = 0; c < n; c++) {
    let d = 0;
    for (let r = 0; r < 6; r++) d = Math.max(d, Math.abs(A[r][c] - B[r][c]));
    if (d > CHANGE_TOL) out.push(c + 1);
  }
  return out;
}
/** @param {number[]} xs */
const list = (xs) => (xs.length ? xs.join(", ") : "none");

/** The legend for watched column `col` (update). @param {HTMLUListElement} legend @param {Options} o @param {number} col */
function legendFor(legend, { n, pal }, col) {
  const before = Array.from({ length: col - 1 }, (_, k) => k + 1);
  const after = Array.from({ length: n - col }, (_, k) => col + k + 1);
  legend.textContent = "";
  const l1 = html("li", {}, legend);
  html("span", { class: "jl-key", style: `background:${pal.space}` }, l1);
  l1.append(`axes ${list(before)} (before ${col}): they move column ${col} of `);
  sub(l1, ["J", "s"]);
  const l2 = html("li", {}, legend);
  html("span", { class: "jl-key", style: `background:${pal.body}` }, l2);
  l2.append(`axes ${list(after)} (after ${col}): they move column ${col} of `);
  sub(l2, ["J", "b"]);
  const l3 = html("li", {}, legend);
  html("span", { class: "jl-key", style: `background:${PALETTE.bg}` }, l3);
  l3.append(`axis ${col}, outlined in the tables: it moves neither`);
}

/** The sentence of what changed (update). @param {HTMLElement} changes @param {ColumnsState} state */
function describeChanges(changes, state) {
  changes.textContent = "";
  if (state.moved.length === 1) {
    const k = state.moved[0];
    changes.append(`You moved θ${String.fromCharCode(0x2080 + k)}: columns of `);
    sub(changes, ["J", "s"]).append(` that changed: ${list(state.changedS)} (after ${k}); of `);
    sub(changes, ["J", "b"]).append(`: ${list(state.changedB)} (before ${k}).`);
  } else if (state.moved.length > 1) {
    changes.append(`Joints ${state.moved.join(", ")} moved: columns of `);
    sub(changes, ["J", "s"]).append(` that changed: ${list(state.changedS)}; of `);
    sub(changes, ["J", "b"]).append(`: ${list(state.changedB)}.`);
  } else {
    changes.append("Move one joint and watch which columns change (coloured).");
  }
}

/**
 * The arm, the axes coloured by role, the tables with what changed (update); `state`, what was drawn last, becomes
 * what is drawn now.
 * @param {Parts} parts @param {number[]} th @param {number} col @param {ColumnsState} state
 */
function update(parts, th, col, state) {
  const { chain, n, pal, axisLen } = parts.o;
  const { view, links, axes, joints, bFrame, axisDots, axisNums, keys, sliders, values, tS, tB } = parts;
  const e = evaluate(chain, th);
  const pts = e.points;
  // what changed since the last drawing
  const last = state.theta;
  const moved = last ? th.map((t, k) => (t !== last[k] ? k + 1 : 0)).filter(Boolean) : [];
  if (moved.length) {
    state.changedS = changedColumns(state.Js, e.Js, n);
    state.changedB = changedColumns(state.Jb, e.Jb, n);
    state.moved = moved;
  }
  /** @type {(k: number, i: number) => string} the colour of axis k when column i is watched */
  const roleColor = (k, i) => (k < i ? pal.space : k > i ? pal.body : PALETTE.fg);
  // the arm
  for (let k = 0; k < n; k++) links[k].set(pts[k], pts[k + 1]);
  for (let i = 0; i < n; i++) {
    const c = roleColor(i + 1, col);
    const w = [e.Js[0][i], e.Js[1][i], e.Js[2][i]]; // ω_s,i: axis i's direction in {s}
    const q = pts[i];
    axes[i].set([q[0] - axisLen * w[0], q[1] - axisLen * w[1], q[2] - axisLen * w[2]],
      [q[0] + axisLen * w[0], q[1] + axisLen * w[1], q[2] + axisLen * w[2]]);
    put(axes[i].el, "stroke", c);
    put(axes[i].el, "stroke-width", i + 1 === col ? 6 : 4);
    joints[i].set(q);
    const tip = [q[0] + 1.25 * axisLen * w[0], q[1] + 1.25 * axisLen * w[1], q[2] + 1.25 * axisLen * w[2]];
    axisDots[i].set(tip);
    put(axisDots[i].el, "fill", i + 1 === col ? PALETTE.bg : c);
    axisNums[i].set(tip);
    put(axisNums[i].el, "fill", i + 1 === col ? PALETTE.fg : PALETTE.onColour);
    put(keys[i], "style", `background:${i + 1 === col ? PALETTE.bg : c}`);
    put(sliders[i], "style", `accent-color:${i + 1 === col ? PALETTE.fg : c}`);
  }
  const R = [e.T[0].slice(0, 3), e.T[1].slice(0, 3), e.T[2].slice(0, 3)];
  bFrame.set(R, pts[n]);
  view.render();
  // numbers
  /** @type {[MatrixTable, Mat, number[], string][]} */
  const shown = [[tS, e.Js, state.changedS, pal.space], [tB, e.Jb, state.changedB, pal.body]];
  for (const [t, J, changed, colour] of shown) {
    for (let c = 0; c < n; c++) {
      const isChanged = changed.includes(c + 1);
      const isWatched = c + 1 === col;
      const style = isChanged ? `background:${tint(colour, 0.35)}` : "";
      const cls = `${isWatched ? "jl-watch" : ""}${isChanged ? " jl-changed" : ""}`.trim();
      put(t.heads[c], "class", cls);
      put(t.heads[c], "style", style);
      for (let r = 0; r < 6; r++) {
        const cell = t.cells[r][c];
        text(cell, fixed(J[r][c]));
        put(cell, "class", cls);
        put(cell, "style", style);
      }
    }
  }
  if (col !== state.column) legendFor(parts.legend, parts.o, col);
  const changeKey = `${state.moved}|${state.changedS}|${state.changedB}`;
  if (changeKey !== state.changeKey) describeChanges(parts.changes, state);
  state.changeKey = changeKey;
  for (let i = 0; i < n; i++) showAngle(values[i], sliders[i], th[i], th[i]);
  if (Number(parts.select.value) !== col) parts.select.value = String(col);
  Object.assign(state, { theta: th, column: col, Js: e.Js, Jb: e.Jb, T: e.T, points: pts });
}

/**
 * The reader's input -> the model (bind): a slider sets its joint, the select the watched column.
 * @param {Parts} parts @param {Model} model @param {() => void} redraw @returns {() => void}
 */
function bind({ o, sliders, select }, model, redraw) {
  /** @param {Event} ev */
  const onInput = (ev) => {
    const th = readTheta(model, o);
    const target = /** @type {HTMLInputElement} */ (ev.target);
    const i = Number(target.dataset.joint) - 1;
    const v = Number(target.value);
    if (!Number.isFinite(v)) return;
    th[i] = v;
    save(model, "theta", th);
  };
  return listen(model, ["theta", "column"], redraw, [
    ...sliders.map((s) => /** @type {import("../ui.js").Listener} */ ([s, "input", onInput])),
    [select, "change", () => save(model, "column", Number(select.value))],
  ]);
}

/** @param {{model: Model, el: HTMLElement}} args */
function render({ model, el }) {
  const { uid } = startView(el, { classes: ["jl-columns"],
    styles: [["jac-live-style-3d", CSS3D], ["jac-live-style-columns", CSS]] });
  const o = options(model);
  const { plot, side } = layout(el);
  /** @type {Parts} */
  const parts = { ...buildScene(plot, o, model, uid), ...buildControls(side, o, model, uid), o };
  /** @type {ColumnsState} */
  const state = { theta: null, column: null, Js: null, Jb: null, moved: [], changedS: [], changedB: [], changeKey: null };
  const redraw = () => {
    update(parts, readTheta(model, o), readColumn(model, o.n), state);
    publish(el, { view: "columns_explorer", theta: /** @type {number[]} */ (state.theta),
      column: /** @type {number} */ (state.column), moved: state.moved, changedS: state.changedS,
      changedB: state.changedB });
  };
  const unlisten = bind(parts, model, redraw);
  redraw();
  return finishView(el, state, () => {
    unlisten();
    parts.view.destroy();
  }, { jacView: parts.view });
}

export { render };
export default { render };
