// node --test: tools/flatten_math_svg.cjs, the build's flattening of a formula's SVG into one <path> per paint.
//
// The flattener merges shapes that overlap (a root's sign and its bar, a delimiter's pieces) into one path, filled
// with SVG's default nonzero rule. That draws their union only if every shape winds the same way: a point inside
// two shapes of opposite winding would have winding 0, a hole. Checked here on every glyph of MathJax's TeX font
// (the winding number of each point of a grid over the glyph is never positive: its filled region winds clockwise
// in the font's coordinates, y up) and on the rules the flattener draws. The browser test
// (tests/browser/test_math_flatten.py) compares the book's formulas drawn both ways, pixel by pixel.

import { test } from "node:test";
import assert from "node:assert/strict";
import { createRequire } from "node:module";

const require = createRequire(import.meta.url);
const svgpath = require("svgpath");
const { flattenSvg } = require("../../tools/flatten_math_svg.cjs");
const { TeXFont } = require("mathjax-full/js/output/svg/fonts/tex.js");
const { mathjax } = require("mathjax-full/js/mathjax.js");
const { TeX } = require("mathjax-full/js/input/tex.js");
const { SVG } = require("mathjax-full/js/output/svg.js");
const { liteAdaptor } = require("mathjax-full/js/adaptors/liteAdaptor.js");
const { RegisterHTMLHandler } = require("mathjax-full/js/handlers/html.js");
require("mathjax-full/js/input/tex/AllPackages.js");

const adaptor = liteAdaptor();
RegisterHTMLHandler(adaptor);
const doc = mathjax.document("", {
  InputJax: new TeX({ packages: ["base", "ams", "color", "cancel", "enclose"] }),
  OutputJax: new SVG({ fontCache: "none" }),
});

/** A path's outlines as closed polygons (each curve sampled at 4 points: a chord keeps the outline's direction). */
function polygons(d) {
  const out = [];
  let cur = null;
  let x = 0, y = 0;
  svgpath(d).abs().unshort().unarc().iterate((s) => {
    const cmd = s[0];
    if (cmd === "M") {
      cur = [[s[1], s[2]]];
      out.push(cur);
      [x, y] = [s[1], s[2]];
      return;
    }
    if (cmd === "Z") {
      [x, y] = cur[0];
      return;
    }
    const pts = [];
    if (cmd === "L") pts.push([s[1], s[2]]);
    else if (cmd === "H") pts.push([s[1], y]);
    else if (cmd === "V") pts.push([x, s[1]]);
    else if (cmd === "Q" || cmd === "C") {
      const ctrl = [[x, y]];
      for (let i = 1; i < s.length; i += 2) ctrl.push([s[i], s[i + 1]]);
      for (let k = 1; k <= 4; k++) {
        let p = ctrl.map((c) => c.slice());
        const t = k / 4;
        while (p.length > 1) p = p.slice(1).map((q, i) => [p[i][0] + t * (q[0] - p[i][0]), p[i][1] + t * (q[1] - p[i][1])]);
        pts.push(p[0]);
      }
    } else throw new Error(`unexpected path command ${cmd}`);
    cur.push(...pts);
    [x, y] = pts[pts.length - 1];
  });
  return out;
}

/** The outlines' edges, x1 y1 x2 y2 each, in one array (for winding). */
function edges(polys) {
  const out = [];
  for (const poly of polys) {
    for (let i = 0; i < poly.length; i++) out.push(...poly[i], ...poly[(i + 1) % poly.length]);
  }
  return Float64Array.from(out);
}

/** The winding number of the outlines around (px, py): positive counterclockwise with y up. */
function winding(polys, px, py) {
  const e = polys instanceof Float64Array ? polys : edges(polys);
  let w = 0;
  for (let k = 0; k < e.length; k += 4) {
    const x1 = e[k], y1 = e[k + 1], x2 = e[k + 2], y2 = e[k + 3];
    if (y1 <= py) {
      if (y2 > py && (x2 - x1) * (py - y1) - (px - x1) * (y2 - y1) > 0) w += 1;
    } else if (y2 <= py && (x2 - x1) * (py - y1) - (px - x1) * (y2 - y1) < 0) w -= 1;
  }
  return w;
}

const GRID = 32;

test("every glyph of MathJax's TeX font winds clockwise (no point of it has a positive winding number)", () => {
  const font = new TeXFont();
  let glyphs = 0;
  const wrong = [];
  for (const [variant, v] of Object.entries(font.variant)) {
    for (const [code, data] of Object.entries(v.chars || {})) {
      const d = data && data[3] && data[3].p && "M" + data[3].p;  // (MathJax writes the "M" in front)
      if (!d) continue;
      const polys = polygons(d);
      const e = edges(polys);
      const xs = polys.flat().map((p) => p[0]), ys = polys.flat().map((p) => p[1]);
      const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
      let inside = 0;
      for (let i = 0; i < GRID; i++) {
        for (let j = 0; j < GRID; j++) {
          const w = winding(e, x0 + (x1 - x0) * (i + 0.5) / GRID, y0 + (y1 - y0) * (j + 0.5) / GRID);
          if (w > 0) wrong.push(`${variant} ${code}`);
          if (w !== 0) inside += 1;
        }
      }
      assert.ok(inside > 0, `${variant} ${code}: no grid point inside`);
      glyphs += 1;
    }
  }
  assert.ok(glyphs > 1000, `only ${glyphs} glyphs found`);
  assert.deepEqual([...new Set(wrong)], []);
});

/** A formula's flattened <svg> (and what flattenSvg returned). */
function flat(tex) {
  const node = doc.convert(tex, { display: true });
  const svg = adaptor.childNodes(node).find((c) => adaptor.kind(c) === "svg");
  const result = flattenSvg(adaptor, svg);
  return { svg, result, children: adaptor.childNodes(svg).filter((c) => adaptor.kind(c) !== "#text") };
}

test("a rule that overlaps a glyph adds to it (the rule winds clockwise too)", () => {
  // a clockwise square glyph (as the font's are, y up) and a rule over half of it, under MathJax's y flip
  const svg = adaptor.node("svg", {}, [adaptor.node("g", { fill: "currentColor", transform: "scale(1,-1)" }, [
    adaptor.node("path", { d: "M0 0L0 100L100 100L100 0Z" }),
    adaptor.node("rect", { x: "50", y: "0", width: "100", height: "100" }),
  ])]);
  assert.deepEqual(flattenSvg(adaptor, svg), { before: 3, after: 1 });
  const d = adaptor.getAttribute(adaptor.childNodes(svg)[0], "d");
  const polys = polygons(d);
  for (const [x, y] of [[25, -50], [75, -50], [125, -50]]) {
    // (y flipped: the page's coordinates; the flip reverses both shapes alike, so they still wind one way)
    assert.notEqual(winding(polys, x, y), 0, `(${x}, ${y}) not filled: ${d}`);
    assert.ok(winding(polys, x, y) * winding(polys, 25, -50) > 0);
  }
  assert.equal(winding(polys, 175, -50), 0);
});

test("one path per run of one paint, in painting order", () => {
  const { result, children } = flat("\\textcolor{red}{a} b \\textcolor{red}{c} d");
  assert.equal(result.after, 4);
  assert.deepEqual(children.map((c) => [adaptor.kind(c), adaptor.getAttribute(c, "fill")]),
    [["path", "red"], ["path", "currentColor"], ["path", "red"], ["path", "currentColor"]]);
  assert.ok(result.before >= 10, JSON.stringify(result));
});

test("a line (\\cancel) is kept, under a group with its ancestors' transforms and paint", () => {
  const { children } = flat("a + \\cancel{x}");
  const kinds = children.map((c) => adaptor.kind(c));
  assert.deepEqual(kinds, ["path", "g"]);
  const g = children[1];
  assert.equal(adaptor.kind(adaptor.childNodes(g)[0]), "line");
  assert.match(adaptor.getAttribute(g, "transform"), /^scale\(1,-1\) translate\(/);
  assert.equal(adaptor.getAttribute(g, "stroke"), "currentColor");
});

test("a tall delimiter's stretched middle (a nested svg that clips it) is kept; the rest is one path", () => {
  const { result, children } = flat("J = \\begin{bmatrix}1\\\\0\\\\0\\\\0\\\\1\\\\2\\end{bmatrix}");
  const kept = children.filter((c) => adaptor.kind(c) === "g");
  assert.equal(kept.length, 2);  // the two brackets' middles
  for (const g of kept) {
    const svg = adaptor.childNodes(g)[0];
    assert.equal(adaptor.kind(svg), "svg");
    assert.ok(adaptor.getAttribute(svg, "viewBox"));
  }
  assert.ok(result.before >= 4 * result.after, JSON.stringify(result));
});

test("a formula with a nested svg (an equation number) is left whole", () => {
  const { result, svg } = flat("x = 1 \\tag{3}");
  assert.equal(result, null);
  assert.match(adaptor.outerHTML(svg), /<svg data-table="true"/);
});

test("a glyph drawn again in another place repeats its relative moves (the page compresses)", () => {
  const { children } = flat("x + x");
  const d = adaptor.getAttribute(children[0], "d");
  const glyphs = d.split("M").filter(Boolean).map((g) => g.replace(/^-?[\d.]+[ ,]?-?[\d.]+/, ""));
  assert.equal(glyphs.length, 3, d);  // x, +, x
  assert.equal(glyphs[0], glyphs[2]);
  assert.notEqual(d.split("M")[1], d.split("M")[3]);  // (in two places)
});

/** Every glyph and rule of MathJax's SVG under `node`, its outline's points in the root's coordinates, exact. */
function exactPoints(node, transforms = []) {
  const out = [];
  for (const child of adaptor.childNodes(node)) {
    const kind = adaptor.kind(child);
    if (kind === "#text") continue;
    const own = adaptor.getAttribute(child, "transform");
    const t = own ? [...transforms, own] : transforms;
    if (kind === "path" || kind === "rect") {
      let d = adaptor.getAttribute(child, "d");
      if (kind === "rect") {
        const [x, y, w, h] = ["x", "y", "width", "height"].map((a) => Number(adaptor.getAttribute(child, a) || 0));
        d = `M${x} ${y}V${y + h}H${x + w}V${y}Z`;
      }
      if (!/[Mm]/.test(d)) continue;
      out.push(...endpoints(t.length ? svgpath(d).transform(t.join(" ")) : svgpath(d)));
    } else out.push(...exactPoints(child, t));
  }
  return out;
}

/** The end point of each segment of a path (absolute), in order. */
function endpoints(p) {
  const pts = [];
  p.abs().unshort().iterate((s, _i, x, y) => {
    if (s[0] === "Z") pts.push([x, y]);
    else if (s[0] === "H") pts.push([s[1], y]);
    else if (s[0] === "V") pts.push([x, s[1]]);
    else pts.push([s[s.length - 2], s[s.length - 1]]);
  });
  return pts;
}

test("every point of a flattened formula is within one font unit of where MathJax's transforms put it", () => {
  for (const tex of ["\\frac{x_1^{2}}{\\sqrt{y_{k_j}}} + \\left[\\begin{matrix} a & b \\\\ \\dot\\theta & e^{-x}\\end{matrix}\\right]",
    "\\sum_{i=1}^{n} J_{b}^{\\dagger} \\mathcal{V}_{s} \\overline{q}"]) {
    const node = doc.convert(tex, { display: true });
    const svg = adaptor.childNodes(node).find((c) => adaptor.kind(c) === "svg");
    const exact = exactPoints(svg);
    assert.ok(flattenSvg(adaptor, svg).after === 1);
    const got = endpoints(svgpath(adaptor.getAttribute(adaptor.childNodes(svg)[0], "d")));
    assert.equal(got.length, exact.length, tex);
    let worst = 0;
    got.forEach(([x, y], k) => { worst = Math.max(worst, Math.hypot(x - exact[k][0], y - exact[k][1])); });
    assert.ok(worst <= Math.SQRT2, `${tex}: a point is ${worst} units from its place`);
    assert.ok(exact.length > 100);
  }
});
