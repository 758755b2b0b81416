// One formula's SVG (MathJax's SVG output with fontCache "none": each glyph a <path> under nested <g>s with
// transforms) drawn with as few elements as it can: every glyph and rule (a fraction's bar, a root's overline: a
// <rect>) is moved into the root's coordinates (npm svgpath applies its ancestors' transforms), and the shapes of
// one paint that are painted one after another become one <path>. A formula of 30 glyphs was about 60 elements in
// the page (a <g> per MathML node, a <use> per glyph, and a hidden copy of each <use>'s glyph); it becomes one
// <path>, or one per run of a colour. On a slow phone, the browser's work on those elements, not their bytes,
// kept the page from showing (chapter 6 had 11,000 SVG elements in its math; 1,090 are left).
//
// What a formula looks like does not change:
// - painting order is kept (only neighbours of one paint merge);
// - under the nonzero fill rule, shapes that overlap add up, because every outline of MathJax's TeX font runs
//   clockwise (tests/js/math_flatten.test.mjs checks each one) and a rule is drawn clockwise too;
// - coordinates are rounded to MathJax's font unit (1/1000 em: 0.016 px at 16 px);
// - where two shapes overlap, one path is antialiased once, where separate ones were blended: a pixel at such an
//   edge may change by at most a quarter of full coverage (tests/browser/test_math_flatten.py compares them).
// Anything else (a <line> of \cancel, a <text> for a character the TeX fonts lack, a link, the nested <svg> that
// stretches a tall delimiter's middle piece and clips it to its place) is kept as it was, under one <g> with its
// ancestors' transforms and paint. A formula with a table of equation numbers (nested <svg>s laid out by the
// browser's width) or an element with an id (a link's target) is left whole.
//
// As a command (the browser test's input): node tools/flatten_math_svg.cjs <in.json> <out.json>, where in.json is
// {"tex": [[<TeX>, <display>], ...], "macros": {...}}: writes, for each formula, MathJax's SVG and the flattened
// one, and the number of SVG elements in each ({"formulas": [{"tex", "display", "mathjax", "flat", "before",
// "after"}], "css"}; "after" is null for a formula left whole).
"use strict";

const svgpath = require("svgpath");

const PAINT = ["fill", "stroke", "stroke-width"];
const GROUP_ATTRS = new Set(["transform", ...PAINT]);

function isData(name) { return name.startsWith("data-"); }

/** The attributes of `node` that are not data-*, as [name, value] pairs. */
function ownAttrs(adaptor, node) {
  return adaptor.allAttributes(node).filter(a => !isData(a.name)).map(a => [a.name, a.value]);
}

function num(v) { return v === undefined || v === null || v === "" ? 0 : Number(v); }

/** Can every element under this root be flattened or kept? (false: leave the formula whole) */
function flattenable(adaptor, node) {
  for (const child of adaptor.childNodes(node)) {
    if (adaptor.kind(child) === "#text" || adaptor.kind(child) === "#comment") continue;
    if (adaptor.getAttribute(child, "id")) return false;
    if (adaptor.kind(child) === "svg"
        && (adaptor.hasAttribute(child, "data-table") || adaptor.hasAttribute(child, "data-labels"))) return false;
    if (!flattenable(adaptor, child)) return false;
  }
  return true;
}

/**
 * Flatten the children of MathJax's root <svg> element `svg` (a LiteElement) in place. Returns the number of
 * elements under the root before and after, or null when the formula is left whole.
 */
function flattenSvg(adaptor, svg) {
  if (!flattenable(adaptor, svg)) return null;
  const items = [];  // in painting order: {paint: {fill, stroke, stroke-width}, d} or {node} (an element kept)
  let before = 0;
  function walk(node, transforms, paint) {
    for (const child of [...adaptor.childNodes(node)]) {  // (a kept element leaves its parent: a copy)
      const kind = adaptor.kind(child);
      if (kind === "#text" || kind === "#comment") continue;
      before += 1;
      const attrs = ownAttrs(adaptor, child);
      const names = attrs.map(([n]) => n);
      const own = adaptor.getAttribute(child, "transform");
      const t = own ? [...transforms, own] : transforms;
      const childPaint = { ...paint };
      for (const [n, v] of attrs) if (PAINT.includes(n)) childPaint[n] = v;
      if (kind === "g" && names.every(n => GROUP_ATTRS.has(n))) {
        walk(child, t, childPaint);
      } else if (kind === "path" && names.every(n => n === "d" || GROUP_ATTRS.has(n))) {
        items.push({ paint: childPaint, d: shape(adaptor.getAttribute(child, "d"), t) });
      } else if (kind === "rect" && names.every(n => ["x", "y", "width", "height", ...GROUP_ATTRS].includes(n))) {
        const [x, y] = [num(adaptor.getAttribute(child, "x")), num(adaptor.getAttribute(child, "y"))];
        const [w, h] = [num(adaptor.getAttribute(child, "width")), num(adaptor.getAttribute(child, "height"))];
        // (clockwise, as every outline of MathJax's TeX font is: under the nonzero rule, a rule that overlaps a
        // glyph, a root's bar and its sign, adds to it rather than cutting a hole)
        items.push({ paint: childPaint, d: shape(`M${x} ${y}V${y + h}H${x + w}V${y}Z`, t) });
      } else {
        items.push({ node: kept(adaptor, child, transforms, paint) });
        before += count(adaptor, child);
      }
    }
  }
  walk(svg, [], {});
  const out = [];
  for (const item of items) {
    const last = out[out.length - 1];
    if (item.d !== undefined && last && last.d !== undefined && same(last.paint, item.paint)) last.d += item.d;
    else out.push({ ...item });
  }
  for (const child of [...adaptor.childNodes(svg)]) adaptor.remove(child);
  for (const item of out) {
    adaptor.append(svg, item.node || adaptor.node("path", { ...paintAttrs(item.paint), d: item.d }));
  }
  return { before, after: count(adaptor, svg) };
}

/** Elements under `node` (not itself). */
function count(adaptor, node) {
  let n = 0;
  for (const child of adaptor.childNodes(node)) {
    if (adaptor.kind(child) === "#text" || adaptor.kind(child) === "#comment") continue;
    n += 1 + count(adaptor, child);
  }
  return n;
}

function same(a, b) {
  return PAINT.every(n => a[n] === b[n]);
}

function paintAttrs(paint) {
  return Object.fromEntries(PAINT.filter(n => paint[n] !== undefined).map(n => [n, paint[n]]));
}

/**
 * A path's data in the root's coordinates. Its first point is absolute; the rest is relative moves, computed with
 * the transforms' translation left out, so that they are the same characters for every copy of a glyph at one
 * size (cached), and the page compresses about as well as one that draws shared glyphs with <use>.
 */
function shape(d, transforms) {
  if (!/[Mm]/.test(d || "")) return "";  // (a space: MathJax writes its glyph with no outline)
  if (!transforms.length) return svgpath(d).rel().round(0).toString().replace(/^m/, "M");  // (svgpath: "M")
  const t = transforms.join(" ");
  const [e, f] = origin(t);
  const key = `${linear(t, e, f)}|${d}`;
  let body = SHAPES.get(key);
  if (body === undefined) {
    const rel = svgpath(d).transform(t).translate(-e, -f).rel().round(0);
    const [, x, y] = rel.segments[0];  // (an outline starts with a move)
    rel.segments = rel.segments.slice(1);
    body = [x, y, rel.toString()];
    SHAPES.set(key, body);
  }
  return `M${round(body[0] + e)} ${round(body[1] + f)}${body[2]}`;
}

const SHAPES = new Map();

/** Where a transform puts the origin. */
function origin(t) {
  let x = 0, y = 0;
  svgpath("M0 0").transform(t).iterate((seg) => { x = seg[1]; y = seg[2]; });
  return [x, y];
}

/** The transform's linear part, as a key: where it puts (1000, 0) and (0, 1000) from the origin. */
function linear(t, e, f) {
  const out = [];
  svgpath("M1000 0L0 1000").transform(t).iterate((seg) => { out.push(round(seg[1] - e), round(seg[2] - f)); });
  return out.join(",");
}

function round(v) {
  const r = Math.round(v);
  return Object.is(r, -0) ? "0" : String(r);
}

/** An element kept as it was, under a <g> with its ancestors' transforms and paint. */
function kept(adaptor, node, transforms, paint) {
  const attrs = paintAttrs(paint);
  if (transforms.length) attrs.transform = transforms.join(" ");
  adaptor.remove(node);
  return adaptor.node("g", attrs, [node]);
}

module.exports = { flattenSvg };

function main(argv) {
  const fs = require("fs");
  const { adaptor, newDocument } = require("./prerender_math.cjs");  // (typeset as the book is)
  if (argv.length !== 2) {
    process.stderr.write("usage: node tools/flatten_math_svg.cjs <in.json> <out.json>\n");
    return 2;
  }
  const { tex, macros } = JSON.parse(fs.readFileSync(argv[0], "utf8"));
  const doc = newDocument(macros || {});
  const formulas = tex.map(([t, display]) => {
    const node = doc.convert(t, { display });
    const mathjaxSvg = adaptor.outerHTML(node);
    const svg = adaptor.childNodes(node).find(c => adaptor.kind(c) === "svg");
    const r = flattenSvg(adaptor, svg);
    return { tex: t, display, mathjax: mathjaxSvg, flat: adaptor.outerHTML(node),
      before: r ? r.before : count(adaptor, svg), after: r ? r.after : null };
  });
  fs.writeFileSync(argv[1], JSON.stringify({ formulas, css: adaptor.textContent(doc.outputJax.styleSheet(doc)) }));
  return 0;
}

if (require.main === module) process.exitCode = main(process.argv.slice(2));
