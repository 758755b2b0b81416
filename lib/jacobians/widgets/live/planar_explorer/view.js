// @ts-check
// The planar arm explorer, live: a 2R or 3R arm the reader moves
// with one slider per joint, by dragging a joint (it turns the joint before
// it) or the tool (mouse, pen or touch: damped least squares on J_v), or with
// Play, which sweeps one joint; the chosen Jacobian's numbers (space, body,
// geometric, or the analytic Jacobian in (x, y, φ)), the linear parts of its
// columns as arrows, the velocity and force ellipses of J_v (the x, y rows of
// the geometric Jacobian) and σ_min(J_v), with a banner near a singularity.
// The column arrows are drawn as the book's figures draw them
// (jacobians.plotting.planar.column_arrows).
//
// anywidget-compatible: `export default { render }`; render({model, el}) reads
// model.get(key) for S (6×n), M (4×4), Q (n×3 joint axis points), theta (n, rad),
// frame ("space" | "body" | "geometric" | "analytic"), limit (the sliders' range ±limit rad), reach (m), sing_tol (m),
// vel_scale (drawn m per m/s), force_scale (drawn m per N/(N m)), force_clip (m),
// sweep (joint Play turns, 0-based), name; it writes theta and frame back with
// model.set + model.save_changes and redraws on "change:theta" / "change:frame".
// Returns a cleanup function. Never throws at a singularity, never shows NaN.

import { dlsRates, evaluate, forceEllipsoid, makeChain, planarAnalyticJacobian, velocityEllipsoid } from "../kinematics.js";
import {
  PALETTE, TWIST_ROWS, announcer, capture, ink, columnColor, finishView, fixed, html, holdTouch, jointName,
  jointSliders, layout, legendItem, listen, makeArrow, planarCanvas, player, publish, save, setArrow, setEllipse,
  showAngle, sliderLimit, startView, sub, svg, text as setText, toWorld,
} from "../ui.js";

export { fixed };

/** @typedef {import("../host.js").Model} Model */
/** @typedef {import("../kinematics.js").Chain} Chain */
/** @typedef {import("../kinematics.js").Evaluation} Evaluation */
/** @typedef {import("../linalg.js").Vec} Vec */
/** @typedef {import("../linalg.js").Mat} Mat */
/** @typedef {import("../ui.js").Arrow2} Arrow2 */
/** @typedef {import("../ui.js").SubText} SubText */
/** @typedef {"space" | "body" | "geometric" | "analytic"} Frame */
/**
 * What the view shows (el.jacLive, read by the tests).
 * @typedef {{theta: Vec | null, frame: Frame | null, J: Mat | null, sigmaMin: number | null,
 *   level: "ok" | "warning" | "singular" | null, force: "inf" | "clipped" | null}} PlanarState
 */
/** @type {Frame[]} */
export const FRAMES = ["space", "body", "geometric", "analytic"];
/** @type {Record<Frame, SubText>} */
const SYMBOLS = { space: ["J", "s"], body: ["J", "b"], geometric: ["J", ""], analytic: ["J", "a"] };
/** @type {ReadonlyArray<SubText>} */
const ANALYTIC_ROWS = [["ẋ", ""], ["ẏ", ""], ["φ̇", ""]];
const STEP = 0.01; // rad, as the matplotlib explorer's sliders
const MAX_STEP = 0.2; // rad, largest joint change of one DLS iteration of a tool drag
// the slider range ±limit rad (the model's, jacobians.widgets.live.LIMIT) is a multiple of STEP: the initial θ keeps
// its value
const PLAY_STEP = 0.02; // rad per frame of Play: from -limit it passes 0 exactly (the singularity of a stretched arm)
const PLAY_MS = 30;

/** x within ±limit. @param {number} x @param {number} limit */
const clamp = (x, limit) => Math.min(limit, Math.max(-limit, x));

/**
 * The linear parts of the shown Jacobian's columns as arrows: their tails P and vectors V (world, m).
 * @param {Evaluation} e @param {Frame} frame @param {number} n @returns {{P: Vec[], V: Vec[]}}
 */
function linearColumns(e, frame, n) {
  // jacobians.plotting.planar.column_arrows: space at {s}'s origin; body turned into {s} axes; else ṗ columns
  const tip = [e.T[0][3], e.T[1][3]];
  const P = [];
  const V = [];
  for (let i = 0; i < n; i++) {
    if (frame === "space") {
      P.push([0, 0]);
      V.push([e.Js[3][i], e.Js[4][i]]);
    } else if (frame === "body") {
      const v = [e.Jb[3][i], e.Jb[4][i], e.Jb[5][i]];
      P.push(tip);
      V.push([0, 1].map((r) => e.T[r][0] * v[0] + e.T[r][1] * v[1] + e.T[r][2] * v[2]));
    } else {
      P.push(tip);
      V.push([e.Jg[3][i], e.Jg[4][i]]);
    }
  }
  return { P, V };
}


// tool drag: θ moves by damped least-squares steps on J_v towards the pointer (never NaN: DLS is bounded)
/**
 * @param {Chain} chain @param {Vec} th @param {ArrayLike<number>} target @param {number} reach @param {number} limit
 * @returns {Vec}
 */
function solve(chain, th, target, reach, limit) {
  const damping = 0.05 * reach;
  const n = chain.n;
  for (let k = 0; k < 60; k++) {
    const e = evaluate(chain, th);
    const err = [target[0] - e.T[0][3], target[1] - e.T[1][3]];
    if (Math.hypot(err[0], err[1]) < 1e-7 * reach) break;
    const d = dlsRates([e.Jg[3], e.Jg[4]], err, damping);
    const big = Math.max(...d.map(Math.abs));
    const scale = big > MAX_STEP ? MAX_STEP / big : 1; // small steps: the arm follows the pointer continuously
    for (let i = 0; i < n; i++) th[i] = clamp(th[i] + scale * d[i], limit);
  }
  return th;
}
// joint drag: joint k's point turns about joint k-1 towards the pointer (θ_{k-1} changes alone)
/**
 * @param {Chain} chain @param {Vec} th @param {number} k @param {ArrayLike<number>} target @param {number} reach
 * @param {number} limit @returns {Vec}
 */
function turn(chain, th, k, target, reach, limit) {
  const pts = evaluate(chain, th).points;
  const a = pts[k - 1];
  const b = pts[k];
  const d = Math.atan2(target[1] - a[1], target[0] - a[0]) - Math.atan2(b[1] - a[1], b[0] - a[0]);
  if (Math.hypot(target[0] - a[0], target[1] - a[1]) < 1e-6 * reach || !Number.isFinite(d)) return th;
  const wz = chain.joints[k - 1].w[2] < 0 ? -1 : 1;
  let t = th[k - 1] + wz * Math.atan2(Math.sin(d), Math.cos(d));
  if (t > Math.PI) t -= 2 * Math.PI;
  if (t < -Math.PI) t += 2 * Math.PI;
  th[k - 1] = clamp(t, limit);
  return th;
}

/**
 * Dragging the tool's ring or a joint (bind): the pointer's world point sets theta through solve or turn.
 * Returns the remover of the listeners.
 * @param {{root: SVGSVGElement, handle: SVGCircleElement, joints: SVGCircleElement[]}} parts
 * @param {{chain: Chain, reach: number, limit: number, readTheta: () => Vec, setTheta: (th: Vec) => void,
 *   stop: () => void}} run
 * @returns {() => void}
 */
function bindDrags({ root, handle, joints }, { chain, reach, limit, readTheta, setTheta, stop }) {
  /** @type {number | null} */
  let drag = null;
  const onDown = (/** @type {PointerEvent} */ ev) => {
    const h = /** @type {SVGElement} */ (ev.currentTarget);
    const k = h === handle ? -1 : Number(h.dataset.joint) - 1;
    drag = k;
    stop();
    capture(h, ev);
    ev.preventDefault();
  };
  const onMove = (/** @type {PointerEvent} */ ev) => {
    if (drag === null) return;
    const target = toWorld(root, ev);
    if (!target) return;
    setTheta(drag < 0 ? solve(chain, readTheta(), target, reach, limit)
      : turn(chain, readTheta(), drag, target, reach, limit));
  };
  const onUp = (/** @type {PointerEvent} */ ev) => {
    if (drag !== null && ev.type === "pointerup") onMove(ev); // a touch's last move can come only with the lift
    drag = null;
  };
  const draggable = [handle, ...joints.slice(1)];
  const unhold = draggable.map(holdTouch);
  for (const h of draggable) {
    h.addEventListener("pointerdown", onDown);
    h.addEventListener("pointermove", onMove);
    h.addEventListener("pointerup", onUp);
    h.addEventListener("pointercancel", onUp);
  }
  return () => {
    for (const h of draggable) {
      h.removeEventListener("pointerdown", onDown);
      h.removeEventListener("pointermove", onMove);
      h.removeEventListener("pointerup", onUp);
      h.removeEventListener("pointercancel", onUp);
    }
    unhold.forEach((f) => f());
  };
}

/**
 * The model's numbers, checked, with their defaults (what build and update share).
 * @param {Model} model @param {Chain} chain
 */
function options(model, chain) {
  const n = chain.n;
  const reach = Number(model.get("reach")) || 1;
  return {
    chain, n, reach,
    limit: sliderLimit(model),
    singTol: Number(model.get("sing_tol")) || 0.08 * reach,
    velScale: Number(model.get("vel_scale")) || 0.35,
    forceScale: Number(model.get("force_scale")) || 0.1 * reach * reach,
    forceClip: Number(model.get("force_clip")) || 1.25 * reach,
    name: model.get("name") || `planar ${n}R arm`,
    L: 0.22 * reach, // the frames' axes
    head: 0.07 * reach, // arrow heads
    tiny: 1e-9 * reach, // an arrow shorter than this is hidden
  };
}
/** @typedef {ReturnType<typeof options>} Options */

/**
 * The drawing (build): grid, frames, ellipses, the arm, its joints and tool, the column arrows, the drag ring.
 * @param {HTMLElement} plot @param {Options} o
 */
function buildScene(plot, { n, reach, name, L, head, tiny }) {
  const R = 1.3 * reach;
  const { root, world } = planarCanvas(plot, R, reach,
    `${name}: the arm, the linear parts of the Jacobian columns, the velocity and force ellipses`);
  const sx = makeArrow(world, PALETTE.muted, 1.5); // frames {s} and {b} in grey: the colours are the columns'
  const sy = makeArrow(world, PALETTE.muted, 1.5);
  setArrow(sx, [0, 0], [L, 0], head, tiny);
  setArrow(sy, [0, 0], [0, L], head, tiny);
  const ns = { fill: "none", "stroke-width": 2, "vector-effect": "non-scaling-stroke" };
  const ellipse = svg("ellipse", { ...ns, stroke: PALETTE.velocity, class: "jl-ellipse" }, world);
  const force = svg("ellipse", { ...ns, stroke: PALETTE.force, "stroke-dasharray": "6 4", class: "jl-force" }, world);
  const clipLine = svg("polyline", { ...ns, stroke: PALETTE.force, "stroke-dasharray": "2 3", class: "jl-force-clip" },
    world);
  const link = svg("polyline", { fill: "none", stroke: PALETTE.link, "stroke-width": 6, "stroke-linejoin": "round",
    "stroke-linecap": "round", "vector-effect": "non-scaling-stroke", class: "jl-link" }, world);
  const bx = makeArrow(world, PALETTE.muted, 1.5);
  const by = makeArrow(world, PALETTE.muted, 1.5);
  /** @type {SVGCircleElement[]} */
  const joints = [];
  for (let i = 0; i < n; i++) {
    joints.push(svg("circle", { r: 0.045 * reach, fill: PALETTE.bg, stroke: PALETTE.joint, "stroke-width": 2.2,
      "vector-effect": "non-scaling-stroke", class: i ? "jl-joint-handle" : "jl-joint", "data-joint": i + 1 }, world));
    if (i) svg("title", {}, joints[i]).textContent = `drag joint ${i + 1}: turns joint ${i}`;
  }
  const tool = svg("circle", { r: 0.025 * reach, fill: PALETTE.joint }, world);
  /** @type {Arrow2[]} */
  const cols = [];
  for (let i = 0; i < n; i++) cols.push(makeArrow(world, columnColor(i), 3));
  cols.forEach((a, i) => a.g.setAttribute("class", `jl-col jl-col-${i + 1}`));
  const handle = svg("circle", { r: 0.1 * reach, fill: PALETTE.fg, "fill-opacity": 0.06, stroke: PALETTE.joint,
    "stroke-opacity": 0.5, "stroke-dasharray": "3 3", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke",
    class: "jl-handle" }, world);
  svg("title", {}, handle).textContent = "drag the tool (inverse kinematics by damped least squares)";
  return { root, ellipse, force, clipLine, link, bx, by, joints, tool, cols, handle };
}

/**
 * The controls and the numbers (build): a slider a joint, Play and the joint it sweeps, the frame, the Jacobian's
 * table, σ_min, the banner, the legend.
 * @param {HTMLElement} side @param {Options} o @param {Model} model @param {string} uid
 */
function buildControls(side, { n, limit, velScale }, model, uid) {
  const theta0 = model.get("theta");
  const { sliders, values } = jointSliders(side, n, uid, { min: -limit, max: limit, step: STEP,
    value: (i) => theta0[i], color: columnColor });
  const row = html("div", { class: "jl-row" }, side);
  const play = html("button", { type: "button", class: "jl-play", "aria-pressed": "false" }, row, "▶ Play");
  const sweepSel = html("select", { class: "jl-sweep", "aria-label": "joint that Play sweeps" }, row);
  for (let i = 0; i < n; i++) html("option", { value: i }, sweepSel, `sweep ${jointName(i)}`);
  const sweep0 = Number(model.get("sweep"));
  sweepSel.value = String(Number.isInteger(sweep0) && sweep0 >= 0 && sweep0 < n ? sweep0 : n - 1);
  const frameLabel = html("label", { for: `${uid}-frame` }, side, "Jacobian:");
  const select = html("select", { id: `${uid}-frame`, class: "jl-frame" }, frameLabel);
  for (const f of FRAMES) html("option", { value: f }, select, f === "analytic" ? "analytic (x, y, φ)" : f);
  const table = html("table", { class: "jl-matrix" }, side);
  const caption = html("caption", {}, table);
  const thead = html("thead", {}, table);
  const hr = html("tr", {}, thead);
  html("th", { scope: "col" }, hr, "");
  for (let i = 0; i < n; i++) html("th", { scope: "col", style: `color:${ink(columnColor(i))}` }, hr, `col ${i + 1}`);
  const tbody = html("tbody", {}, table);
  // the rows of both kinds, built once: update puts in the tbody those of the Jacobian shown
  const rows = { twist: tableRows(TWIST_ROWS, n), analytic: tableRows(ANALYTIC_ROWS, n) };
  // the caption of each Jacobian, built once: update puts in the caption that of the Jacobian shown
  const captions = Object.fromEntries(FRAMES.map((f) => [f, [...sub(html("span", {}), SYMBOLS[f]).childNodes,
    f === "analytic" ? "(θ), the analytic Jacobian of (x, y, φ), φ the tool's angle" : `(θ), the ${f} Jacobian`]]));
  const status = html("p", { class: "jl-status" }, side);
  const say = announcer(side);  // the key numbers, once the reader stops moving a control
  sub(status, ["σ", "min"]);
  sub(status, ["(J", "v"]);
  const sigmaText = side.ownerDocument.createTextNode("");
  status.append(sigmaText);
  const banner = html("p", { class: "jl-banner", role: "status" }, side);
  const legend = html("ul", { class: "jl-legend" }, side);
  const legendCols = html("li", {}, legend);
  for (let i = 0; i < n; i++) html("span", { class: "jl-key", style: `background:${columnColor(i)}` }, legendCols);
  const legendText = side.ownerDocument.createTextNode("");
  legendCols.append(legendText);
  legendItem(legend, PALETTE.velocity, ["velocity ellipse of J", ["", "v"], `: ‖θ̇‖ = 1 (×${velScale} s)`]);
  const forceItem = legendItem(legend, PALETTE.force, [""], true);
  legendItem(legend, PALETTE.muted, ["axes of {s} and {b}; drag a joint or the dashed ring at the tool"]);
  return { sliders, values, play, sweepSel, select, caption, captions, tbody, rows, sigmaText, say, banner, legendText, forceItem };
}

/** @typedef {ReturnType<typeof buildScene> & ReturnType<typeof buildControls> & {o: Options}} Parts */

/**
 * The table's rows for these labels, not yet in the table (the twist's six, or the analytic Jacobian's three).
 * @param {ReadonlyArray<SubText>} labels @param {number} n
 * @returns {{trs: HTMLTableRowElement[], cells: HTMLTableCellElement[][]}}
 */
function tableRows(labels, n) {
  const trs = labels.map((lab) => {
    const tr = html("tr", {});
    sub(html("th", { scope: "row" }, tr), lab);
    return tr;
  });
  return { trs, cells: trs.map((tr) => Array.from({ length: n }, () => html("td", {}, tr, ""))) };
}

/** θ from the model, a number a joint (0 for what is not one). @param {Model} model @param {number} n @returns {Vec} */
function readTheta(model, n) {
  const th = model.get("theta");
  return Array.from({ length: n }, (_, i) => (Number.isFinite(Number(th && th[i])) ? Number(th[i]) : 0));
}
/** @param {Model} model @returns {Frame} */
function readFrame(model) {
  const f = model.get("frame");
  return FRAMES.includes(f) ? f : "space";
}

/**
 * The force ellipse of J_v at the tool (update): 1/σ_i along the directions of J_v's singular vectors (Infinity at a
 * singularity), drawn ×forceScale and clipped at forceClip, a dotted line where it is clipped, and its legend.
 * Returns "inf", "clipped" or null.
 * @param {Parts} parts @param {number[]} tip @param {number[][]} Jv
 */
function updateForce(parts, tip, Jv) {
  const { reach, forceScale, forceClip } = parts.o;
  const { force, clipLine, forceItem } = parts;
  const f = forceEllipsoid(Jv);
  const drawn = f.axes.map((a) => Math.min(a * forceScale, forceClip));
  const clipped = f.axes.map((a) => !(a * forceScale <= forceClip));
  setEllipse(force, tip, drawn[0], drawn[1], f.directions, 1e-4 * reach);
  /** @type {string[]} */
  const seg = [];
  clipped.forEach((c, i) => {
    if (!c) return;
    const u = [f.directions[0][i], f.directions[1][i]];
    seg.push(`${tip[0] - forceClip * u[0]},${tip[1] - forceClip * u[1]}`, `${tip[0] + forceClip * u[0]},${tip[1] + forceClip * u[1]}`);
  });
  clipLine.setAttribute("points", seg.slice(0, 2).join(" "));
  clipLine.setAttribute("visibility", seg.length ? "visible" : "hidden");
  const forceState = clipped.some((c) => c) ? (f.axes.some((a) => a === Infinity) ? "inf" : "clipped") : null;
  setText(/** @type {ChildNode} */ (forceItem.lastChild), forceState === "inf"
    ? `force ellipse, ‖τ‖ = 1 (×${fixed(forceScale, 2)}): infinite along the dotted line, clipped at ${fixed(forceClip, 2)} m`
    : forceState === "clipped"
      ? `force ellipse, ‖τ‖ = 1 (×${fixed(forceScale, 2)}): longer than drawn along the dotted line`
      : `force ellipse, ‖τ‖ = 1 (×${fixed(forceScale, 2)})`);
  return forceState;
}

/**
 * The table of J, its caption and the legend of the columns (update): the rows and caption of the frame's Jacobian
 * (built in build) put in when the frame changed, then its numbers.
 * @param {Parts} parts @param {Frame} frame @param {Mat} J @param {PlanarState} shown
 */
function updateNumbers(parts, frame, J, shown) {
  const { trs, cells } = frame === "analytic" ? parts.rows.analytic : parts.rows.twist;
  if (frame !== shown.frame) {
    const { caption, captions, legendText, tbody } = parts;
    if (tbody.firstChild !== trs[0]) tbody.replaceChildren(...trs);
    caption.replaceChildren(...captions[frame]);
    setText(legendText, frame === "space" ? "linear parts of the columns, at the origin of {s}"
      : frame === "body" ? "linear parts of the columns, turned into {s} axes, at the tool"
        : "the columns' (ẋ, ẏ), the tool velocity per unit joint rate, at the tool");
  }
  for (let r = 0; r < cells.length; r++) for (let i = 0; i < parts.o.n; i++) setText(cells[r][i], fixed(J[r][i]));
}

/**
 * The picture and the numbers for θ and the frame (update); `shown` is what was drawn last, and becomes this.
 * Returns what the view shows.
 * @param {Parts} parts @param {Vec} th @param {Frame} frame @param {PlanarState} shown
 */
function update(parts, th, frame, shown) {
  const { chain, n, reach, singTol, L, head, tiny } = parts.o;
  const { link, joints, tool, handle, bx, by, cols, ellipse, sigmaText, say, banner } = parts;
  const e = evaluate(chain, th);
  const J = frame === "space" ? e.Js : frame === "body" ? e.Jb : frame === "geometric" ? e.Jg
    : planarAnalyticJacobian(chain, th);
  const pts = e.points;
  link.setAttribute("points", pts.map((p) => `${p[0]},${p[1]}`).join(" "));
  for (let i = 0; i < n; i++) {
    joints[i].setAttribute("cx", String(pts[i][0]));
    joints[i].setAttribute("cy", String(pts[i][1]));
  }
  const tip = [e.T[0][3], e.T[1][3]];
  for (const c of [tool, handle]) {
    c.setAttribute("cx", String(tip[0]));
    c.setAttribute("cy", String(tip[1]));
  }
  setArrow(bx, tip, [0.8 * L * e.T[0][0], 0.8 * L * e.T[1][0]], head, tiny);
  setArrow(by, tip, [0.8 * L * e.T[0][1], 0.8 * L * e.T[1][1]], head, tiny);
  const { P, V } = linearColumns(e, frame, n);
  for (let i = 0; i < n; i++) setArrow(cols[i], P[i], V[i], head, tiny);
  // velocity ellipse of J_v: semi-axes σ_i along the columns of U, drawn ×velScale
  const Jv = [e.Jg[3], e.Jg[4]];
  const { axes, directions } = velocityEllipsoid(Jv);
  setEllipse(ellipse, tip, axes[0] * parts.o.velScale, axes[1] * parts.o.velScale, directions, 1e-4 * reach);
  const forceState = updateForce(parts, tip, Jv); // 1/σ_i along the same directions
  const s = Math.max(axes[1], 0);
  /** @type {"ok" | "warning" | "singular"} */
  let level;
  /** @type {string} */
  let word;
  if (s < 1e-9) {
    level = "singular";
    word = "Singular: the tool cannot move along one direction";
  } else if (s < singTol) {
    level = "warning";
    word = "Near a singularity: the tool barely moves along one direction";
  } else {
    level = "ok";
    word = "";
  }
  link.setAttribute("stroke", level === "ok" ? PALETTE.link : PALETTE[level]);
  setText(sigmaText, `) = ${fixed(s, 3)} m`);
  say(`${th.map((x, i) => `theta ${i + 1} ${fixed((x * 180) / Math.PI, 1)} degrees`).join(", ")}; `
    + `smallest singular value ${fixed(s, 3)} metres${level === "ok" ? "" : `, ${level}`}`);
  if (level !== shown.level) {
    banner.textContent = word;
    banner.hidden = level === "ok";
    banner.style.borderColor = PALETTE[level];
  }
  updateNumbers(parts, frame, J, shown);
  for (let i = 0; i < n; i++) showAngle(parts.values[i], parts.sliders[i], th[i], th[i]);
  if (parts.select.value !== frame) parts.select.value = frame;
  Object.assign(shown, { theta: th, frame, J, sigmaMin: s, level, force: forceState });
}

/**
 * The reader's input -> the model (bind): the sliders, the frame, Play, dragging a joint or the tool.
 * Returns the remover of all of it.
 * @param {Parts} parts @param {Model} model @param {() => void} redraw @param {HTMLElement} el (its data-playing)
 */
function bind(parts, model, redraw, el) {
  const { chain, n, reach, limit } = parts.o;
  const { sliders, select, play, sweepSel } = parts;
  const setTheta = (/** @type {Vec} */ th) => save(model, "theta", th);
  // Play: sweep one joint, PLAY_STEP a frame, up to limit, then from -limit again (on the slider's grid)
  const playing = player(play, () => {
    const th = readTheta(model, n);
    const i = Number(sweepSel.value);
    th[i] = th[i] + PLAY_STEP > limit + 1e-9 ? -limit : Math.round((th[i] + PLAY_STEP) / STEP) * STEP;
    setTheta(th);
  }, PLAY_MS, (p) => publish(el, { playing: p ? 1 : 0 }));
  const onInput = (/** @type {Event} */ ev) => {
    const slider = /** @type {HTMLInputElement} */ (ev.target);
    const th = readTheta(model, n);
    const v = Number(slider.value);
    if (!Number.isFinite(v)) return;
    th[Number(slider.dataset.joint) - 1] = v;
    setTheta(th);
  };
  const unbindDrags = bindDrags(parts, { chain, reach, limit, readTheta: () => readTheta(model, n), setTheta,
    stop: playing.stop });
  const unlisten = listen(model, ["theta", "frame"], redraw, [
    [play, "click", playing.toggle],
    ...sliders.map((s) => /** @type {import("../ui.js").Listener} */ ([s, "input", onInput])),
    [select, "change", () => save(model, "frame", select.value)],
  ]);
  return () => {
    playing.stop();
    unlisten();
    unbindDrags();
  };
}

/** @param {{model: Model, el: HTMLElement}} args */
function render({ model, el }) {
  const { uid } = startView(el);
  const o = options(model, makeChain(model.get("S"), model.get("M"), model.get("Q") || null));
  const { plot, side } = layout(el);
  /** @type {Parts} */
  const parts = { ...buildScene(plot, o), ...buildControls(side, o, model, uid), o };
  /** @type {PlanarState} */
  const state = { theta: null, frame: null, J: null, sigmaMin: null, level: null, force: null };
  const shown = { ...state };
  const redraw = () => {
    update(parts, readTheta(model, o.n), readFrame(model), shown);
    Object.assign(state, { theta: shown.theta, frame: shown.frame, J: shown.J, sigmaMin: shown.sigmaMin,
      level: shown.level, force: shown.force });
    publish(el, { view: "planar_explorer", theta: /** @type {Vec} */ (state.theta),
      level: /** @type {string} */ (state.level), frame: /** @type {Frame} */ (state.frame) });
  };
  const unbind = bind(parts, model, redraw, el);
  redraw();
  publish(el, { playing: 0 });
  return finishView(el, state, unbind);
}

export { render };
export default { render };
