// The planar arm explorer, live (issue #13): a 2R or 3R arm the reader moves
// with one slider per joint, or by dragging the tool (mouse, pen or touch:
// damped least squares on J_v); the chosen Jacobian's numbers, the linear parts
// of its columns as arrows, the velocity ellipse of J_v (the x, y rows of the
// geometric Jacobian, i.e. the tool point's (ẋ, ẏ)) and σ_min(J_v), with a
// banner near a singularity. What is drawn follows the book's matplotlib
// explorer (jacobians.widgets.planar, jacobians.plotting.planar.column_arrows)
// and its colours (jacobians.plotting.style.PALETTE, COLUMN_COLORS).
//
// anywidget-compatible: `export default { render }`, render({model, el}) reads
// model.get(key) for S (6×n), M (4×4), Q (n×3 joint axis points), theta (n, rad),
// frame ("space" | "body" | "geometric"), reach (m), sing_tol (m), vel_scale,
// name; it writes theta and frame back with model.set + model.save_changes and
// redraws on "change:theta" / "change:frame". On a static page
// _ext/live_views.py writes the model and _theme/live/host.js mounts it.
// Returns a cleanup function. Never throws at a singularity, never shows NaN.

import { dlsRates, evaluate, makeChain, velocityEllipsoid } from "./kinematics.js";

const SVGNS = "http://www.w3.org/2000/svg";
const PALETTE = {
  link: "#0072B2", joint: "#000000", muted: "#999999", velocity: "#D55E00",
  ok: "#009E73", warning: "#E69F00", singular: "#D55E00", frame_x: "#D55E00", frame_y: "#009E73",
};
const COLUMN_COLORS = ["#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"];
export const FRAMES = ["space", "body", "geometric"];
const SYMBOLS = { space: ["J", "s"], body: ["J", "b"], geometric: ["J", ""] };
const ROW_LABELS = [["ω", "x"], ["ω", "y"], ["ω", "z"], ["v", "x"], ["v", "y"], ["v", "z"]];
const DIGITS = 2;
const STEP = 0.01; // rad, as the matplotlib explorer's sliders
const MAX_STEP = 0.2; // rad, largest joint change of one DLS iteration of a tool drag
const LIMIT = 3.14; // slider range ±LIMIT rad (a multiple of STEP: the initial θ keeps its value)
const CSS = `
.jac-live{font-size:16px;line-height:1.35;max-width:100%;box-sizing:border-box;margin:0.5em 0 1.5em}
.jac-live *{box-sizing:border-box}
.jac-live .jl-wrap{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.jac-live .jl-plot{flex:1 1 300px;max-width:460px;min-width:0}
.jac-live .jl-plot svg{width:100%;height:auto;display:block}
.jac-live .jl-handle{cursor:grab;touch-action:none}
.jac-live .jl-side{flex:1 1 260px;min-width:0}
.jac-live label{display:block;font-size:16px}
.jac-live input[type=range]{width:100%;margin:2px 0 8px}
.jac-live select{font-size:16px;margin-left:6px}
.jac-live table{border-collapse:collapse;margin:8px 0;font-size:15px;font-variant-numeric:tabular-nums}
.jac-live td,.jac-live th{padding:1px 8px;text-align:right;border:0}
.jac-live caption{caption-side:top;text-align:left;font-size:15px;white-space:nowrap}
.jac-live sub{font-size:14px;line-height:1}
.jac-live .jl-status{font-size:15px;margin:4px 0}
.jac-live .jl-banner{font-size:16px;font-weight:bold;padding:4px 8px;border:3px solid;border-radius:6px;margin:6px 0}
.jac-live .jl-legend{font-size:14px;margin:4px 0 0;padding:0;list-style:none}
.jac-live .jl-legend li{margin:0}
.jac-live .jl-key{display:inline-block;width:18px;height:4px;vertical-align:middle;margin-right:6px}
`;

function injectStyle(doc) {
  if (doc.getElementById("jac-live-style")) return;
  const s = doc.createElement("style");
  s.id = "jac-live-style";
  s.textContent = CSS;
  doc.head.appendChild(s);
}

/** A number with fixed decimals, never "-0.00" (a true minus sign otherwise). */
export function fixed(x, digits = DIGITS) {
  if (!Number.isFinite(x)) return "—";
  const s = x.toFixed(digits);
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s.replace("-", "\u2212");
}

function svg(tag, attrs = {}, parent = null) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (parent) parent.appendChild(e);
  return e;
}

function html(tag, attrs = {}, parent = null, text = null) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== null) e.textContent = text;
  if (parent) parent.appendChild(e);
  return e;
}

/** Append text with a subscript (e.g. J_s) to `parent`. */
function sub(parent, [base, index]) {
  parent.append(base);
  if (index) html("sub", {}, parent, index);
  return parent;
}

/** An arrow (shaft + head) in a <g>; hidden when shorter than `tiny`. */
function makeArrow(parent, color, width) {
  const g = svg("g", { fill: color, stroke: color }, parent);
  const line = svg("line", { "stroke-width": width, "vector-effect": "non-scaling-stroke", "stroke-linecap": "round" }, g);
  const head = svg("polygon", { stroke: "none" }, g);
  return { g, line, head };
}

function setArrow(a, p, d, headLen, tiny) {
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

function linearColumns(e, frame, n) {
  // jacobians.plotting.planar.column_arrows: space at {s}'s origin; body turned into {s} axes; geometric ṗ columns
  const tip = [e.T[0][3], e.T[1][3]];
  const P = [];
  const V = [];
  for (let i = 0; i < n; i++) {
    if (frame === "space") {
      P.push([0, 0]);
      V.push([e.Js[3][i], e.Js[4][i]]);
    } else if (frame === "body") {
      const v = [e.Jb[3][i], e.Jb[4][i], e.Jb[5][i]];
      const R = e.T;
      P.push(tip);
      V.push([0, 1].map((r) => R[r][0] * v[0] + R[r][1] * v[1] + R[r][2] * v[2]));
    } else {
      P.push(tip);
      V.push([e.Jg[3][i], e.Jg[4][i]]);
    }
  }
  return { P, V };
}

function render({ model, el }) {
  const doc = el.ownerDocument;
  injectStyle(doc);
  el.classList.add("jac-live");
  const chain = makeChain(model.get("S"), model.get("M"), model.get("Q") || null);
  const n = chain.n;
  const reach = Number(model.get("reach")) || 1;
  const singTol = Number(model.get("sing_tol")) || 0.08 * reach;
  const velScale = Number(model.get("vel_scale")) || 0.35;
  const name = model.get("name") || `planar ${n}R arm`;
  const R = 1.3 * reach;
  const uid = `jl${Math.random().toString(36).slice(2, 9)}`;

  const wrap = html("div", { class: "jl-wrap" }, el);
  const plot = html("div", { class: "jl-plot" }, wrap);
  const side = html("div", { class: "jl-side" }, wrap);

  // ---- the drawing: world coordinates in metres, y up
  const root = svg("svg", { viewBox: `${-R} ${-R} ${2 * R} ${2 * R}`, role: "img",
    "aria-label": `${name}: the arm, the linear parts of the Jacobian columns and the velocity ellipse` }, plot);
  const world = svg("g", { transform: "scale(1,-1)" }, root);
  const grid = svg("g", { stroke: "#dddddd", "stroke-width": 1, "vector-effect": "non-scaling-stroke" }, world);
  for (let k = -Math.floor(R); k <= Math.floor(R); k++) {
    svg("line", { x1: k, y1: -R, x2: k, y2: R, "vector-effect": "non-scaling-stroke" }, grid);
    svg("line", { x1: -R, y1: k, x2: R, y2: k, "vector-effect": "non-scaling-stroke" }, grid);
  }
  const b = 0.07 * reach;
  svg("polygon", { points: `0,0 ${-b},${-1.6 * b} ${b},${-1.6 * b}`, fill: PALETTE.muted }, world);
  const L = 0.22 * reach;
  const head = 0.07 * reach;
  const tiny = 1e-9 * reach;
  const sx = makeArrow(world, PALETTE.muted, 1.5); // frames {s} and {b} in grey: the colours are the columns'
  const sy = makeArrow(world, PALETTE.muted, 1.5);
  setArrow(sx, [0, 0], [L, 0], head, tiny);
  setArrow(sy, [0, 0], [0, L], head, tiny);
  const ellipse = svg("ellipse", { fill: "none", stroke: PALETTE.velocity, "stroke-width": 2,
    "vector-effect": "non-scaling-stroke", class: "jl-ellipse" }, world);
  const link = svg("polyline", { fill: "none", stroke: PALETTE.link, "stroke-width": 6, "stroke-linejoin": "round",
    "stroke-linecap": "round", "vector-effect": "non-scaling-stroke", class: "jl-link" }, world);
  const bx = makeArrow(world, PALETTE.muted, 1.5);
  const by = makeArrow(world, PALETTE.muted, 1.5);
  const joints = [];
  for (let i = 0; i < n; i++) {
    joints.push(svg("circle", { r: 0.045 * reach, fill: "white", stroke: PALETTE.joint, "stroke-width": 2.2,
      "vector-effect": "non-scaling-stroke" }, world));
  }
  const tool = svg("circle", { r: 0.025 * reach, fill: PALETTE.joint }, world);
  const cols = [];
  for (let i = 0; i < n; i++) cols.push(makeArrow(world, COLUMN_COLORS[i % COLUMN_COLORS.length], 3));
  cols.forEach((a, i) => a.g.setAttribute("class", `jl-col jl-col-${i + 1}`));
  // drag the tool: damped least squares on J_v (a ring to grab, wider than the dot)
  const handle = svg("circle", { r: 0.1 * reach, fill: "#000000", "fill-opacity": 0.06, stroke: PALETTE.joint,
    "stroke-opacity": 0.5, "stroke-dasharray": "3 3", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke",
    class: "jl-handle" }, world);
  svg("title", {}, handle).textContent = "drag the tool (inverse kinematics by damped least squares)";

  // ---- the controls
  const sliders = [];
  const values = [];
  const theta0 = model.get("theta");
  for (let i = 0; i < n; i++) {
    const id = `${uid}-t${i + 1}`;
    const label = html("label", { for: id }, side);
    label.append(`θ${String.fromCharCode(0x2081 + i)} = `);
    values.push(html("output", { for: id, class: "jl-value" }, label));
    const s = html("input", { type: "range", id, min: -LIMIT, max: LIMIT, step: STEP, class: "jl-theta",
      "data-joint": i + 1, style: `accent-color:${COLUMN_COLORS[i % COLUMN_COLORS.length]}` }, side);
    s.value = String(theta0[i]);
    sliders.push(s);
  }
  const frameLabel = html("label", { for: `${uid}-frame` }, side, "Jacobian:");
  const select = html("select", { id: `${uid}-frame`, class: "jl-frame" }, frameLabel);
  for (const f of FRAMES) html("option", { value: f }, select, f);
  const table = html("table", { class: "jl-matrix" }, side);
  const caption = html("caption", {}, table);
  const thead = html("thead", {}, table);
  const hr = html("tr", {}, thead);
  html("th", { scope: "col" }, hr, "");
  for (let i = 0; i < n; i++) {
    html("th", { scope: "col", style: `color:${COLUMN_COLORS[i % COLUMN_COLORS.length]}` }, hr, `col ${i + 1}`);
  }
  const tbody = html("tbody", {}, table);
  const cells = ROW_LABELS.map((lab) => {
    const tr = html("tr", {}, tbody);
    sub(html("th", { scope: "row" }, tr), lab);
    return Array.from({ length: n }, () => html("td", {}, tr, ""));
  });
  const status = html("p", { class: "jl-status", "aria-live": "polite" }, side);
  const banner = html("p", { class: "jl-banner", role: "status" }, side);
  const legend = html("ul", { class: "jl-legend" }, side);
  const legendCols = html("li", {}, legend);
  const li = html("li", {}, legend);
  html("span", { class: "jl-key", style: `background:${PALETTE.velocity}` }, li);
  sub(li, ["velocity ellipse of J", "v"]).append(`: ‖θ̇‖ = 1 (×${velScale} s)`);
  const li2 = html("li", {}, legend);
  html("span", { class: "jl-key", style: `background:${PALETTE.muted}` }, li2);
  li2.append("axes of {s} and {b}; drag the dashed ring at the tool");

  // ---- state -> picture
  function readTheta() {
    const th = model.get("theta");
    return Array.from({ length: n }, (_, i) => (Number.isFinite(Number(th && th[i])) ? Number(th[i]) : 0));
  }
  function readFrame() {
    const f = model.get("frame");
    return FRAMES.includes(f) ? f : "space";
  }
  const state = { theta: null, frame: null, J: null, sigmaMin: null, level: null };

  function draw() {
    const th = readTheta();
    const frame = readFrame();
    const e = evaluate(chain, th);
    const J = frame === "space" ? e.Js : frame === "body" ? e.Jb : e.Jg;
    const pts = e.points;
    link.setAttribute("points", pts.map((p) => `${p[0]},${p[1]}`).join(" "));
    for (let i = 0; i < n; i++) {
      joints[i].setAttribute("cx", pts[i][0]);
      joints[i].setAttribute("cy", pts[i][1]);
    }
    const tip = [e.T[0][3], e.T[1][3]];
    tool.setAttribute("cx", tip[0]);
    tool.setAttribute("cy", tip[1]);
    handle.setAttribute("cx", tip[0]);
    handle.setAttribute("cy", tip[1]);
    setArrow(bx, tip, [0.8 * L * e.T[0][0], 0.8 * L * e.T[1][0]], head, tiny);
    setArrow(by, tip, [0.8 * L * e.T[0][1], 0.8 * L * e.T[1][1]], head, tiny);
    const { P, V } = linearColumns(e, frame, n);
    for (let i = 0; i < n; i++) setArrow(cols[i], P[i], V[i], head, tiny);
    // velocity ellipse of J_v: semi-axes σ_i along the columns of U, drawn ×velScale
    const Jv = [e.Jg[3], e.Jg[4]];
    const { axes, directions } = velocityEllipsoid(Jv);
    const ang = (Math.atan2(directions[1][0], directions[0][0]) * 180) / Math.PI;
    ellipse.setAttribute("cx", tip[0]);
    ellipse.setAttribute("cy", tip[1]);
    ellipse.setAttribute("rx", Math.max(axes[0], 0) * velScale);
    ellipse.setAttribute("ry", Math.max(axes[1] * velScale, 1e-4 * reach)); // a segment at a singularity
    ellipse.setAttribute("transform", `rotate(${Number.isFinite(ang) ? ang : 0} ${tip[0]} ${tip[1]})`);
    const s = Math.max(axes[1], 0);
    let level;
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
    status.textContent = "";
    sub(status, ["σ", "min"]);
    sub(status, ["(J", "v"]).append(`) = ${fixed(s, 3)} m`);
    banner.textContent = word;
    banner.hidden = level === "ok";
    banner.style.borderColor = PALETTE[level];
    // numbers
    caption.textContent = "";
    sub(caption, SYMBOLS[frame]).append(`(θ), the ${frame} Jacobian`);
    for (let r = 0; r < 6; r++) for (let i = 0; i < n; i++) cells[r][i].textContent = fixed(J[r][i]);
    legendCols.textContent = "";
    for (let i = 0; i < n; i++) {
      html("span", { class: "jl-key", style: `background:${COLUMN_COLORS[i % COLUMN_COLORS.length]}` }, legendCols);
    }
    legendCols.append(frame === "space" ? "linear parts of the columns, at the origin of {s}"
      : frame === "body" ? "linear parts of the columns, turned into {s} axes, at the tool"
        : "linear parts of the columns (ṗ of the tool), at the tool");
    for (let i = 0; i < n; i++) {
      values[i].textContent = `${fixed((th[i] * 180) / Math.PI, 1)}°`;
      if (Number(sliders[i].value) !== th[i] && doc.activeElement !== sliders[i]) sliders[i].value = String(th[i]);
    }
    if (select.value !== frame) select.value = frame;
    Object.assign(state, { theta: th, frame, J, sigmaMin: s, level });
    el.dataset.theta = JSON.stringify(th);
    el.dataset.frame = frame;
    el.dataset.level = level;
  }

  // ---- input -> state
  const onInput = (ev) => {
    const th = readTheta();
    const i = Number(ev.target.dataset.joint) - 1;
    const v = Number(ev.target.value);
    if (!Number.isFinite(v)) return;
    th[i] = v;
    model.set("theta", th);
    model.save_changes();
  };
  const onFrame = () => {
    model.set("frame", select.value);
    model.save_changes();
  };
  // tool drag: θ moves by damped least-squares steps on J_v towards the pointer (never NaN: DLS is bounded)
  const damping = 0.05 * reach;
  function solve(target) {
    const th = readTheta();
    for (let k = 0; k < 60; k++) {
      const e = evaluate(chain, th);
      const err = [target[0] - e.T[0][3], target[1] - e.T[1][3]];
      if (Math.hypot(err[0], err[1]) < 1e-7 * reach) break;
      const d = dlsRates([e.Jg[3], e.Jg[4]], err, damping);
      const big = Math.max(...d.map(Math.abs));
      const scale = big > MAX_STEP ? MAX_STEP / big : 1; // small steps: the arm follows the pointer continuously
      for (let i = 0; i < n; i++) th[i] = Math.min(LIMIT, Math.max(-LIMIT, th[i] + scale * d[i]));
    }
    return th;
  }
  let dragging = false;
  const toWorld = (ev) => {
    const m = root.getScreenCTM();
    if (!m) return null;
    const q = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(m.inverse());
    return [q.x, -q.y];
  };
  const onDown = (ev) => {
    dragging = true;
    try {
      handle.setPointerCapture(ev.pointerId);
    } catch {
      // a synthetic event has no active pointer to capture
    }
    ev.preventDefault();
  };
  const onMove = (ev) => {
    if (!dragging) return;
    const target = toWorld(ev);
    if (!target || !Number.isFinite(target[0]) || !Number.isFinite(target[1])) return;
    model.set("theta", solve(target));
    model.save_changes();
  };
  const onUp = () => {
    dragging = false;
  };
  handle.addEventListener("pointerdown", onDown);
  handle.addEventListener("pointermove", onMove);
  handle.addEventListener("pointerup", onUp);
  handle.addEventListener("pointercancel", onUp);
  sliders.forEach((s) => s.addEventListener("input", onInput));
  select.addEventListener("change", onFrame);
  model.on("change:theta", draw);
  model.on("change:frame", draw);
  draw();
  el.jacLive = state;
  return () => {
    model.off("change:theta", draw);
    model.off("change:frame", draw);
    sliders.forEach((s) => s.removeEventListener("input", onInput));
    handle.removeEventListener("pointerdown", onDown);
    handle.removeEventListener("pointermove", onMove);
    handle.removeEventListener("pointerup", onUp);
    handle.removeEventListener("pointercancel", onUp);
    select.removeEventListener("change", onFrame);
    el.textContent = "";
  };
}

export { render };
export default { render };
