// @ts-check
// A small orthographic 3-D view in SVG, shared by the spatial live views
// (columns_explorer.js, gimbal_lock.js). No dependencies.
//
// The camera looks at `center` from the direction (cos e cos a, cos e sin a, sin e)
// (a = azimuth, e = elevation, world z up). A point p goes to the screen by
//   x = (p − c)·r,  y = −(p − c)·u   (SVG y points down),  depth = (p − c)·d,
// r = (−sin a, cos a, 0) to the right, u = (−sin e cos a, −sin e sin a, cos e) up,
// d = the direction to the viewer (larger depth = nearer). Orthographic: the
// sphere of radius `extent` about `center` always fits the square viewBox.
//
// The reader turns it by dragging on the drawing (mouse, pen or touch: the SVG
// alone has touch-action none, so the page still scrolls elsewhere) or, once it
// has the keyboard focus, with the arrow keys (5° a press; Home: the first view).
//
// Items keep their world coordinates; render() projects them all, so a camera
// change redraws without recomputing the kinematics. Items in the "solid" layer
// are drawn back to front (painter's order by depth).

import { AXIS_COLORS, PALETTE, html, ink, put, svg } from "./ui.js";

export { AXIS_COLORS };

/** @typedef {import("./ui.js").Attrs} Attrs */
/** @typedef {[number, number, number]} Vec3 a world point or vector */
/** @typedef {ArrayLike<number>} Point a world point (x, y, z) as any array */
/** @typedef {(p: Point) => Vec3} Projector world -> [x, y (SVG units, y down), depth (larger = nearer)] */
/** @typedef {{r: Vec3, u: Vec3, d: Vec3}} Basis the camera's right, up and toward-the-viewer directions */
/** @typedef {{azimuth: number, elevation: number}} Camera */
/** @typedef {"back" | "solid" | "front"} Layer back: under all; solid: painter's order by depth; front: over all */
/**
 * Something drawn in the view: it keeps world data, draw() projects it.
 * @typedef {object} Item
 * @property {SVGElement} el
 * @property {Layer} layer
 * @property {boolean} visible
 * @property {number} depth
 * @property {(pr: Projector, basis: Basis) => void} draw
 * @property {Box} [box] where a label or a dot sits on screen, once drawn: declutter() keeps these apart
 * @property {(x: number, y: number) => void} [moveTo] put it elsewhere on screen (declutter)
 * @property {Item} [anchor] a label drawn on this item (a number on its dot): it moves with it
 */
/** @typedef {{x: number, y: number, hw: number, hh: number}} Box a centre and half sizes, SVG units */
/** @typedef {Item & {p: Point, q: Point, set(p: Point, q: Point): Segment}} Segment */
/** @typedef {Item & {pts: Point[], set(pts: Point[]): Polyline}} Polyline */
/** @typedef {Item & {pts: Point[], set(c: Point, n: Point, radius: number): Ring}} Ring */
/** @typedef {Item & {p: Point, v: Point, set(p: Point, v: Point): Arrow3}} Arrow3 */
/**
 * A text label at a world point, offset (dx, dy) SVG units on screen.
 * @typedef {Item & {el: SVGTextElement, p: Point, dx: number, dy: number,
 *   set(p: Point, t?: string | null, dx?: number, dy?: number): Label}} Label
 */
/** @typedef {Item & {el: SVGCircleElement, p: Point, set(p: Point): Dot}} Dot */
/**
 * @typedef {object} ViewOptions
 * @property {Point} [center] what the camera looks at
 * @property {number} [extent] the world radius about center that must fit
 * @property {number} [azimuth] rad
 * @property {number} [elevation] rad
 * @property {string} [label] the aria-label: what is drawn
 * @property {string} [help] a visible line of how to turn it
 * @property {string} [id] a prefix of the element ids
 */
export const VIEWBOX = 400; // SVG units across; strokes are in screen pixels (non-scaling)
export const FONT = 18; // SVG units: ≥ 14 px when the drawing is ≥ 312 px wide
const KEY_STEP = (5 * Math.PI) / 180;
const DRAG_GAIN = 0.01; // rad per screen pixel
const MAX_ELEVATION = (89 * Math.PI) / 180;

export const CSS = `
.jac-live .jl-view3d{position:relative}
.jac-live .jl-view3d svg{width:100%;height:auto;display:block;touch-action:none;cursor:grab;user-select:none;
  -webkit-user-select:none;border:1px solid var(--jl-border);border-radius:6px;background:var(--jl-paper)}
.jac-live .jl-view3d svg:focus{outline:none}
.jac-live .jl-view3d svg:focus-visible{outline:3px solid var(--jl-blue);outline-offset:2px}
.jac-live .jl-view3d svg.jl-dragging{cursor:grabbing}
.jac-live .jl-help{font-size:14px;margin:4px 0 0;color:var(--jl-soft-text)}
`;

/** @type {(a: Point, b: Point) => Vec3} */
const sub3 = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
/** @type {(a: Point, b: Point) => number} */
const dot3 = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
/** @type {(p: Point) => boolean} */
const finite3 = (p) => Number.isFinite(p[0]) && Number.isFinite(p[1]) && Number.isFinite(p[2]);

/**
 * Labels and dots must not cover each other: in the order they were made (the first keep their place), each
 * that overlaps one already placed moves to the nearest free spot on rings of 4, 8, ... 48 SVG units around
 * where it belongs (12 directions a ring), inside the drawing. A label with an anchor moves with its anchor.
  * @param {Item[]} items
 */
function declutter(items) {
  /** @type {Box[]} */
  const placed = [];
  /** @type {Map<Item, [number, number]>} */
  const moved = new Map();
  const half = VIEWBOX / 2;
  /** @param {Box} b */
  const free = (b) => Math.abs(b.x) + b.hw <= half && Math.abs(b.y) + b.hh <= half
    && placed.every((q) => Math.abs(q.x - b.x) >= q.hw + b.hw || Math.abs(q.y - b.y) >= q.hh + b.hh);
  for (const it of items) {
    const b = it.box;
    if (!it.visible || !b || it.anchor || !it.moveTo) continue;
    let best = b;
    if (!free(b)) {
      search: for (let r = 4; r <= 48; r += 4) {
        for (let k = 0; k < 12; k++) {
          const t = (Math.PI / 6) * k - Math.PI / 4;
          const c = { ...b, x: b.x + r * Math.cos(t), y: b.y + r * Math.sin(t) };
          if (free(c)) {
            best = c;
            break search;
          }
        }
      }
    }
    placed.push(best);
    if (best !== b) {
      it.moveTo(best.x, best.y);
      moved.set(it, [best.x - b.x, best.y - b.y]);
    }
  }
  for (const it of items) {
    const shift = it.anchor && moved.get(it.anchor);
    if (shift && it.box && it.moveTo && it.visible) it.moveTo(it.box.x + shift[0], it.box.y + shift[1]);
  }
}

/**
 * The view's elements in `parent`: a box holding the SVG drawing (its three layers) and the line of help.
 * @param {Element} parent @param {ViewOptions} options
 */
function viewElements(parent, options) {
  const box = html("div", { class: "jl-view3d" }, parent);
  const helpId = `${options.id || "jl3d"}-help`;
  const root = svg("svg", {
    viewBox: `${-VIEWBOX / 2} ${-VIEWBOX / 2} ${VIEWBOX} ${VIEWBOX}`, tabindex: 0, role: "img",
    "aria-roledescription": "turnable 3-D view", "aria-label": options.label || "3-D view",
    "aria-describedby": helpId, class: "jl-3d", "font-size": FONT, "font-family": "inherit", fill: PALETTE.fg,
  }, box);
  /** @type {Record<Layer, SVGGElement>} */
  const layers = { back: svg("g", { class: "jl-back" }, root), solid: svg("g", { class: "jl-solid" }, root),
    front: svg("g", { class: "jl-front" }, root) };
  const help = html("p", { class: "jl-help", id: helpId }, box,
    options.help || "Turn the view: drag it, or focus it (Tab) and press the arrow keys; Home resets.");
  return { box, root, layers, help };
}

/**
 * The camera's basis: r (right), u (up) and d (towards the viewer), world unit vectors.
 * @param {Camera} camera @returns {Basis}
 */
function cameraBasis(camera) {
  const ca = Math.cos(camera.azimuth), sa = Math.sin(camera.azimuth);
  const ce = Math.cos(camera.elevation), se = Math.sin(camera.elevation);
  return { r: [-sa, ca, 0], u: [-se * ca, -se * sa, ce], d: [ce * ca, ce * sa, se] };
}

/**
 * The visible items of the solid layer back to front (the nearest drawn last), moving elements only when the
 * order changed.
 * @param {SVGGElement} layer @param {Item[]} items
 */
function orderSolid(layer, items) {
  const solid = items.filter((it) => it.layer === "solid" && it.visible);
  solid.sort((a, b) => a.depth - b.depth);
  let i = 0;
  let inOrder = true;
  for (const child of layer.children) {
    if (i >= solid.length || child !== solid[i].el) { inOrder = false; break; }
    i++;
  }
  if (!inOrder || i !== solid.length) for (const it of solid) layer.appendChild(it.el);
}

/**
 * The reader turns the view: a drag (a pointer), the arrow keys (Home: back to `home`). Returns the remover.
 * @param {SVGSVGElement} root @param {Camera} camera @param {Camera} home
 * @param {(azimuth: number, elevation: number) => void} setCamera
 */
function bindTurning(root, camera, home, setCamera) {
  /** @type {{x: number, y: number, id: number} | null} */
  let drag = null;
  /** @param {PointerEvent} ev */
  const onDown = (ev) => {
    if (ev.button !== undefined && ev.button !== 0) return;
    drag = { x: ev.clientX, y: ev.clientY, id: ev.pointerId };
    try {
      root.setPointerCapture(ev.pointerId);
    } catch {
      // a synthetic event has no active pointer to capture
    }
    root.classList.add("jl-dragging");
    ev.preventDefault();
  };
  /** @param {PointerEvent} ev */
  const onMove = (ev) => {
    if (!drag) return;
    const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
    drag.x = ev.clientX;
    drag.y = ev.clientY;
    if (!Number.isFinite(dx) || !Number.isFinite(dy)) return;
    setCamera(camera.azimuth - DRAG_GAIN * dx, camera.elevation + DRAG_GAIN * dy);
  };
  const onUp = () => {
    drag = null;
    root.classList.remove("jl-dragging");
  };
  /** @param {KeyboardEvent} ev */
  const onKey = (ev) => {
    const k = ev.key;
    if (k === "ArrowLeft") setCamera(camera.azimuth + KEY_STEP, camera.elevation);
    else if (k === "ArrowRight") setCamera(camera.azimuth - KEY_STEP, camera.elevation);
    else if (k === "ArrowUp") setCamera(camera.azimuth, camera.elevation + KEY_STEP);
    else if (k === "ArrowDown") setCamera(camera.azimuth, camera.elevation - KEY_STEP);
    else if (k === "Home") setCamera(home.azimuth, home.elevation);
    else return;
    ev.preventDefault();
    ev.stopPropagation(); // a deck must not change slides while the view is being turned
  };
  /** @type {[string, (ev: any) => void][]} */
  const handlers = [["pointerdown", onDown], ["pointermove", onMove], ["pointerup", onUp], ["pointercancel", onUp],
    ["keydown", onKey]];
  for (const [type, f] of handlers) root.addEventListener(type, f);
  return () => {
    for (const [type, f] of handlers) root.removeEventListener(type, f);
  };
}

/**
 * The makers of the view's items, each drawn into its layer and kept in `items` (world data; draw() projects it).
 * @param {Record<Layer, SVGGElement>} layers @param {Item[]} items
 */
function itemMakers(layers, items) {
  /**
   * @template {Item} T
   * @param {T} item
   * @returns {T}
   */
  function add(item) {
    items.push(item);
    return item;
  }
  /** @type {(layer: Layer, attrs: Attrs) => Segment} */
  const segment = (layer, attrs) => add(segmentItem(layers[layer], layer, attrs));
  /** @type {(layer: Layer, attrs: Attrs) => Polyline} */
  const polyline = (layer, attrs) => add(polylineItem(layers[layer], layer, attrs));
  /** @type {(layer: Layer, color: string, width?: number, headPx?: number) => Arrow3} */
  const arrow = (layer, color, width, headPx) => add(arrowItem(layers[layer], layer, color, width, headPx));
  /** @type {(layer: Layer, text: string, attrs?: Attrs) => Label} */
  const label = (layer, text, attrs) => add(labelItem(layers[layer], layer, text, attrs));
  /** @type {(layer: Layer, attrs: Attrs) => Dot} */
  const dot = (layer, attrs) => add(dotItem(layers[layer], layer, attrs));
  /** @type {(layer: Layer, attrs: Attrs, segments?: number) => Ring} */
  const ring = (layer, attrs, segments) => add(ringItem(layers[layer], layer, attrs, segments));
  return { segment, polyline, arrow, label, dot, ring };
}

/**
 * An orthographic 3-D view in `parent`.
 * options: center (3), extent (world radius that must fit), azimuth, elevation (rad),
 * label (the aria-label: what is drawn), help (a visible line of how to turn it), id.
 * Returns {svg, layers: {back, solid, front}, camera, project, render, setCamera, items, destroy, onCamera}.
 * @param {Element} parent
 * @param {ViewOptions} options
 */
export function createView3D(parent, options) {
  const center = options.center || [0, 0, 0];
  const extent = options.extent || 1;
  const scale = (0.5 * VIEWBOX) / extent; // SVG units per metre
  /** @type {Camera} */
  const home = { azimuth: options.azimuth ?? -1.0, elevation: options.elevation ?? 0.45 };
  const camera = { ...home };
  const { box, root, layers, help } = viewElements(parent, options);
  let basis = cameraBasis(camera);
  /** World point -> [x, y, depth] in SVG units (y down).
   * @type {Projector}
   */
  function project(p) {
    const q = sub3(p, center);
    return [scale * dot3(q, basis.r), -scale * dot3(q, basis.u), dot3(q, basis.d)];
  }
  /** @type {Item[]} */
  const items = [];
  /** @type {((camera: Camera) => void)[]} */
  const listeners = [];
  function render() {
    for (const it of items) it.draw(project, basis);
    declutter(items);
    orderSolid(layers.solid, items);
  }
  /** @param {number} azimuth @param {number} elevation */
  function setCamera(azimuth, elevation) {
    camera.azimuth = Number.isFinite(azimuth) ? azimuth : camera.azimuth;
    camera.elevation = Math.max(-MAX_ELEVATION, Math.min(MAX_ELEVATION,
      Number.isFinite(elevation) ? elevation : camera.elevation));
    basis = cameraBasis(camera);
    render();
    root.dataset.azimuth = camera.azimuth.toFixed(4);
    root.dataset.elevation = camera.elevation.toFixed(4);
    listeners.forEach((f) => f(camera));
  }
  const unbind = bindTurning(root, camera, home, setCamera);
  root.dataset.azimuth = camera.azimuth.toFixed(4);
  root.dataset.elevation = camera.elevation.toFixed(4);
  return {
    svg: root, box, help, layers, camera, items, project, render, setCamera, ...itemMakers(layers, items), scale,
    /** @param {(camera: Camera) => void} f */
    onCamera(f) { listeners.push(f); },
    destroy() {
      unbind();
      listeners.length = 0;
    },
  };
}


/** A segment p–q (world), stroke in px. set(p, q).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {Attrs} attrs
 * @returns {Segment}
 */
function segmentItem(parent, layer, attrs) {
  const el = svg("line", { "vector-effect": "non-scaling-stroke", "stroke-linecap": "round", ...attrs },
    parent);
  /** @type {Segment} */
  const it = {
    el, layer, visible: true, depth: 0, p: [0, 0, 0], q: [0, 0, 0],
    set(p, q) { this.p = p; this.q = q; this.visible = finite3(p) && finite3(q); return this; },
    draw(pr) {
      put(el, "visibility", this.visible ? "visible" : "hidden");
      if (!this.visible) return;
      const a = pr(this.p), b = pr(this.q);
      put(el, "x1", a[0].toFixed(2)); put(el, "y1", a[1].toFixed(2));
      put(el, "x2", b[0].toFixed(2)); put(el, "y2", b[1].toFixed(2));
      this.depth = 0.5 * (a[2] + b[2]);
    },
  };
  return it;
}
/** A polyline through world points. set(points).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {Attrs} attrs
 * @returns {Polyline}
 */
function polylineItem(parent, layer, attrs) {
  const el = svg("polyline", { fill: "none", "vector-effect": "non-scaling-stroke", "stroke-linejoin": "round",
    "stroke-linecap": "round", ...attrs }, parent);
  /** @type {Polyline} */
  const it = {
    el, layer, visible: true, depth: 0, pts: [],
    set(pts) { this.pts = pts; this.visible = pts.every(finite3); return this; },
    draw(pr) {
      put(el, "visibility", this.visible ? "visible" : "hidden");
      if (!this.visible) return;
      let d = 0;
      put(el, "points", this.pts.map((p) => {
        const a = pr(p);
        d += a[2];
        return `${a[0].toFixed(2)},${a[1].toFixed(2)}`;
      }).join(" "));
      this.depth = d / Math.max(1, this.pts.length);
    },
  };
  return it;
}
/** An arrow from p along the world vector v; its head (px) drawn on screen. set(p, v).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {string} color
 * @param {number} [width]
 * @param {number} [headPx]
 * @returns {Arrow3}
 */
function arrowItem(parent, layer, color, width = 2.5, headPx = 11) {
  const g = svg("g", { fill: color, stroke: color }, parent);
  const line = svg("line", { "stroke-width": width, "vector-effect": "non-scaling-stroke",
    "stroke-linecap": "round" }, g);
  const head = svg("polygon", { stroke: "none" }, g);
  /** @type {Arrow3} */
  const it = {
    el: g, layer, visible: true, depth: 0, p: [0, 0, 0], v: [0, 0, 0],
    set(p, v) { this.p = p; this.v = v; this.visible = finite3(p) && finite3(v); return this; },
    draw(pr) {
      const a = pr(this.p), b = pr([this.p[0] + this.v[0], this.p[1] + this.v[1], this.p[2] + this.v[2]]);
      const dx = b[0] - a[0], dy = b[1] - a[1], L = Math.hypot(dx, dy);
      const show = this.visible && L > 1e-6;
      put(g, "visibility", show ? "visible" : "hidden");
      this.depth = 0.5 * (a[2] + b[2]);
      if (!show) return;
      const ux = dx / L, uy = dy / L, h = Math.min(headPx, 0.5 * L), w = 0.45 * h;
      const bx = b[0] - h * ux, by = b[1] - h * uy;
      put(line, "x1", a[0].toFixed(2)); put(line, "y1", a[1].toFixed(2));
      put(line, "x2", bx.toFixed(2)); put(line, "y2", by.toFixed(2));
      put(head, "points", `${b[0].toFixed(2)},${b[1].toFixed(2)} ${(bx - w * uy).toFixed(2)},`
        + `${(by + w * ux).toFixed(2)} ${(bx + w * uy).toFixed(2)},${(by - w * ux).toFixed(2)}`);
    },
  };
  return it;
}
/** A text label at a world point (offset in SVG units). set(p, text?).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {string} text
 * @param {Attrs} [attrs]
 * @returns {Label}
 */
function labelItem(parent, layer, text, attrs = {}) {
  const el = svg("text", { "text-anchor": "middle", "dominant-baseline": "central", "paint-order": "stroke",
    stroke: PALETTE.bg, "stroke-width": 4, "stroke-linejoin": "round", ...attrs }, parent);
  el.textContent = text;
  let font = 0; // its font size in SVG units, read once it is shown (a deck's style may change it)
  /** @type {Label} */
  const it = {
    el, layer, visible: true, depth: 0, p: [0, 0, 0], dx: 0, dy: 0,
    moveTo(x, y) {
      put(el, "x", x.toFixed(2));
      put(el, "y", y.toFixed(2));
    },
    set(p, t = null, dx = 0, dy = 0) {
      this.p = p; this.dx = dx; this.dy = dy; this.visible = finite3(p);
      if (t !== null && el.textContent !== t) el.textContent = t;
      return this;
    },
    draw(pr) {
      put(el, "visibility", this.visible ? "visible" : "hidden");
      if (!this.visible) return;
      const a = pr(this.p);
      if (!font) font = parseFloat(getComputedStyle(el).fontSize) || FONT;
      // a glyph is about 0.6 em wide; the box is what declutter keeps apart
      this.box = { x: a[0] + this.dx, y: a[1] + this.dy, hw: 0.3 * font * (el.textContent || "").length + 1,
        hh: 0.5 * font };
      this.moveTo?.(this.box.x, this.box.y);
      this.depth = a[2];
    },
  };
  return it;
}
/** A dot (screen radius in SVG units) at a world point. set(p).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {Attrs} attrs
 * @returns {Dot}
 */
function dotItem(parent, layer, attrs) {
  const el = svg("circle", { "vector-effect": "non-scaling-stroke", ...attrs }, parent);
  let r = 0; // its radius in SVG units, read once it is shown (a deck's style may change it)
  /** @type {Dot} */
  const it = {
    el, layer, visible: true, depth: 0, p: [0, 0, 0],
    set(p) { this.p = p; this.visible = finite3(p); return this; },
    moveTo(x, y) {
      put(el, "cx", x.toFixed(2));
      put(el, "cy", y.toFixed(2));
    },
    draw(pr) {
      put(el, "visibility", this.visible ? "visible" : "hidden");
      if (!this.visible) return;
      const a = pr(this.p);
      put(el, "cx", a[0].toFixed(2)); put(el, "cy", a[1].toFixed(2));
      // a dot of the front layer is a key that labels must not cover; a joint of the arm is not
      if (!r) r = parseFloat(getComputedStyle(el).r) || Number(attrs.r) || 0;
      if (layer === "front") this.box = { x: a[0], y: a[1], hw: r, hh: r };
      this.depth = a[2];
    },
  };
  return it;
}
/** A circle of world radius about `c`, in the plane normal to unit `n`, as a closed polyline. set(c, n, radius).
 * @param {Element} parent
 * @param {Layer} layer
 * @param {Attrs} attrs
 * @param {number} [segments]
 * @returns {Ring}
 */
function ringItem(parent, layer, attrs, segments = 40) {
  const line = polylineItem(parent, layer, attrs);
  const base = line.set;
  const it = /** @type {Ring} */ (/** @type {unknown} */ (line));
  /** @param {Point} c @param {Point} n @param {number} radius */
  it.set = function set(c, n, radius) {
    // two unit vectors e1, e2 normal to n
    const a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    const k = dot3(a, n);
    let e1 = [a[0] - k * n[0], a[1] - k * n[1], a[2] - k * n[2]];
    const L = Math.hypot(...e1);
    e1 = e1.map((x) => x / L);
    const e2 = [n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]];
    /** @type {Vec3[]} */
    const pts = [];
    for (let s = 0; s <= segments; s++) {
      const t = (2 * Math.PI * s) / segments, cs = radius * Math.cos(t), sn = radius * Math.sin(t);
      pts.push([c[0] + cs * e1[0] + sn * e2[0], c[1] + cs * e1[1] + sn * e2[1], c[2] + cs * e1[2] + sn * e2[2]]);
    }
    base.call(line, pts);
    return it;
  };
  return it;
}

/**
 * Arrows of a frame and its name ("{s}", placed below its origin); axis letters x, y, z when `letters`.
 * set(R, p, length) with R's columns the axes.
 * @param {View3D} view
 * @param {string} name
 * @param {number} length
 * @param {{letters?: boolean, layer?: Layer, width?: number}} [options]
 */
export function frameItems(view, name, length, { letters = false, layer = "solid", width = 2.5 } = {}) {
  const arrows = AXIS_COLORS.map((c) => view.arrow(layer, c, width));
  const labels = letters ? ["x", "y", "z"].map((a, k) => view.label("front", a, { fill: ink(AXIS_COLORS[k]) })) : [];
  const title = view.label("front", name, { fill: PALETTE.fg });
  return {
    arrows, labels, title,
    /** @param {ArrayLike<ArrayLike<number>>} R @param {Point} p @param {number} [len] */
    set(R, p, len = length) {
      for (let k = 0; k < 3; k++) {
        const v = [R[0][k] * len, R[1][k] * len, R[2][k] * len];
        arrows[k].set(p, v);
        if (labels[k]) labels[k].set([p[0] + 1.25 * v[0], p[1] + 1.25 * v[1], p[2] + 1.25 * v[2]]);
      }
      title.set(p, null, -16, 16);
    },
  };
}

/** A ground grid in the plane z = z0, half-width `half` with `n` cells a side, in the back layer.
 * @param {View3D} view
 * @param {number} half
 * @param {number} n
 * @param {number} [z0]
 */
export function groundGrid(view, half, n, z0 = 0) {
  const step = (2 * half) / n;
  for (let k = 0; k <= n; k++) {
    const t = -half + k * step;
    view.segment("back", { stroke: PALETTE.faint, "stroke-width": 1 }).set([t, -half, z0], [t, half, z0]);
    view.segment("back", { stroke: PALETTE.faint, "stroke-width": 1 }).set([-half, t, z0], [half, t, z0]);
  }
}

/** @typedef {ReturnType<typeof createView3D>} View3D */
