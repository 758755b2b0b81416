// Typeset the math of built book pages once, at build time, with MathJax in Node
// (npm mathjax-full, the same MathJax 3.2.2 as the browser copy), so that no page
// waits for MathJax on the reader's phone.
//
// Usage: node tools/prerender_math.cjs [--fragments <spec.json>] <static-dir> <macros-json> <page.html>...
//
// In each page, every Sphinx math element (<span class="math">\(..\)</span>,
// <div class="math">\[..\]</div> or a bare \begin{env}..\end{env}) gets MathJax's SVG output, with its hidden
// MathML for screen readers (mjx-assistive-mml); the element keeps its TeX in data-tex (the on-demand menu,
// _theme/math_menu.js, typesets it again from there). SVG rather than CommonHTML: a formula drawn with paths needs
// no font, so a page downloads none of MathJax's fonts (on a slow phone the first screen's math no longer waits
// for them). Each formula's SVG is flattened (tools/flatten_math_svg.cjs): its glyphs and rules become one <path>
// in the formula's coordinates, where MathJax writes a <g> per MathML node and a <use> per glyph, so that the
// browser has a tenth of the elements to parse, style and lay out. The shapes are filled with currentColor, so
// they follow the text's colour (dark mode). Sizes are in em of MathJax's font, as the CommonHTML output's were
// (see SVG.prototype.ex below).
// The output's CSS goes into one <style> in the page's head (not MathJax's own id: MathJax in the page, loaded by
// the menu, would replace it). <static-dir> is the site's _static (unused by the SVG output; kept so that the
// callers stay as they were). The page's MathJax configuration and startup.js are removed. A TeX error stops the
// run with the page and the formula.
//
// Fragments (--fragments): {"<page.html>": [{"src", "out", "key"}]}. For each entry, src is a JSON list of HTML
// strings with math in \( \) and \[ \] (HTML-escaped TeX, as the library's statement_html writes it, for the
// exercise pages' statements); string k is typeset (a fragment draws its own glyphs, as every formula does) and
// written to <out>/<k>.js as window.__courseStatements["<key>/<k>"] = "<html>".
//
// Prints one JSON line per page: {"page", "math", "css"} (formulas, fragments' included; CSS bytes).
"use strict";

const fs = require("fs");
const path = require("path");
const { mathjax } = require("mathjax-full/js/mathjax.js");
const { TeX } = require("mathjax-full/js/input/tex.js");
const { SVG } = require("mathjax-full/js/output/svg.js");
const { liteAdaptor } = require("mathjax-full/js/adaptors/liteAdaptor.js");
const { RegisterHTMLHandler } = require("mathjax-full/js/handlers/html.js");
const { AssistiveMmlHandler } = require("mathjax-full/js/a11y/assistive-mml.js");
require("mathjax-full/js/input/tex/AllPackages.js");
const { flattenSvg } = require("./flatten_math_svg.cjs");

// The packages the browser's configuration loads, and those its autoload
// would fetch when a formula uses them (physics is not autoloaded: left out).
const PACKAGES = ["base", "ams", "newcommand", "configmacros", "noundefined", "action", "amscd", "bbox",
  "boldsymbol", "braket", "cancel", "cases", "centernot", "color", "empheq", "enclose", "extpfeil",
  "gensymb", "html", "mathtools", "upgreek", "unicode", "verb"];

// The SVG output gives its sizes in ex of the text around a formula, which MathJax in a browser measures and
// Node cannot (the page's ex is not MathJax's); in em instead (MathJax's font at the text's size, as the
// CommonHTML output drew it), a formula has the same size on the page whatever the page's font.
SVG.prototype.ex = function (m) {
  return Math.abs(m) < 0.001 ? "0" : m.toFixed(3).replace(/\.?0+$/, "") + "em";
};

const adaptor = liteAdaptor();
AssistiveMmlHandler(RegisterHTMLHandler(adaptor));

// Sphinx's math, and myst-nb's text/latex outputs (class "output text_latex math notranslate nohighlight")
// (and any classes an author adds before or after them)
const MATH = /<(span|div)( class="(?:[^"]*\s)?math notranslate nohighlight(?:\s[^"]*)?"[^>]*)>([\s\S]*?)<\/\1>/g;
const EQNO = /^\s*<span class="eqno">[\s\S]*?<\/span>/;
const CONFIG_SCRIPT = /<script>window\.MathJax = [\s\S]*?<\/script>\s*/;
const STARTUP_SCRIPT = /<script defer="defer" src="[^"]*mathjax\/es5\/startup\.js[^"]*"><\/script>\s*/;

function unescapeHtml(s) {
  return s.replace(/&lt;/g, "<").replace(/&gt;/g, ">").replace(/&quot;/g, '"').replace(/&#39;/g, "'")
    .replace(/&amp;/g, "&");
}

function escapeAttr(s) {
  return s.replace(/&/g, "&amp;").replace(/"/g, "&quot;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
}

/** The TeX of a math element's text and whether it is display math. */
function source(tag, text) {
  const t = unescapeHtml(text).trim();
  if (tag === "span" && t.startsWith("\\(") && t.endsWith("\\)")) return [t.slice(2, -2), false];
  if (t.startsWith("\\[") && t.endsWith("\\]")) return [t.slice(2, -2), true];
  if (t.startsWith("$$") && t.endsWith("$$") && t.length > 4) return [t.slice(2, -2), true];
  if (tag === "div") return [t, true];
  return null;
}

// What an earlier run wrote: the typeset formulas (back to their TeX), the page's math CSS and menu settings (and
// the hidden glyph cache of a page typeset with shared glyphs, MathJax's fontCache "global")
const TYPESET = /<(span|div)( class="[^"]*"[^>]*?) data-tex="([^"]*)">(<span class="eqno">[\s\S]*?<\/span>)?<mjx-container[\s\S]*?<\/mjx-container><\/\1>/g;
const OURS = /<style id="course-math-styles">[\s\S]*?<\/style>\n?|<script type="application\/json" id="math-menu-config">[\s\S]*?<\/script>\n?|<svg [^>]*id="MJX-SVG-global-cache"[\s\S]*?<\/svg>\n?/g;

/** The page as Sphinx wrote it, if an earlier run typeset it (so that a page can be typeset again). */
function untypeset(html) {
  return html.replace(OURS, "").replace(TYPESET, (whole, tag, attrs, tex, eqno) => {
    const t = tex.replace(/&quot;/g, '"');  // (escapeAttr's other entities stay: the TeX is HTML text again)
    return `<${tag}${attrs}>${eqno || ""}${tag === "span" ? "\\(" + t + "\\)" : "\\[" + t + "\\]"}</${tag}>`;
  });
}

const PROCESS = /(<div class="(?:[^"]*\s)?mathjax_process(?:\s[^"]*)?"[^>]*>)((?:(?!<div)[\s\S])*?)(<\/div>)/g;
const DELIMITED = /\\\[([\s\S]*?)\\\]|\\\(([\s\S]*?)\\\)/g;

/** The formula `tex` typeset in `doc` (an mjx-container), its SVG flattened (tools/flatten_math_svg.cjs). */
function convert(doc, tex, display) {
  const node = doc.convert(tex, { display });
  const svg = adaptor.childNodes(node).find(c => adaptor.kind(c) === "svg");
  if (svg) flattenSvg(adaptor, svg);
  return node;
}

/** An HTML fragment with its \( \) and \[ \] math typeset in `doc` (as the page's math is). */
function typesetFragment(html, doc, errors) {
  let count = 0;
  const out = html.replace(DELIMITED, (whole, display, inline) => {
    const isDisplay = display !== undefined;
    const tex = unescapeHtml(isDisplay ? display : inline);
    const node = adaptor.outerHTML(convert(doc, tex, isDisplay));
    if (/<mjx-merror|data-mjx-error/.test(node)) errors.push(tex);
    count += 1;
    const tag = isDisplay ? "div" : "span";
    return `<${tag} class="math notranslate nohighlight" data-tex="${escapeAttr(tex)}">${node}</${tag}>`;
  });
  return [out, count];
}

/** Typeset the fragments of a page (see the header) in `doc`; the number of formulas. */
function renderFragments(list, doc, errors) {
  let count = 0;
  for (const { src, out, key } of list) {
    const items = JSON.parse(fs.readFileSync(src, "utf8"));
    fs.mkdirSync(out, { recursive: true });
    items.forEach((html, k) => {
      const [typeset, n] = typesetFragment(html, doc, errors);
      count += n;
      // "</" cannot end a script early: JSON allows "<\/"
      const text = JSON.stringify(typeset).replace(/<\//g, "<\\/");
      fs.writeFileSync(path.join(out, `${k}.js`),
        `(window.__courseStatements=window.__courseStatements||{})[${JSON.stringify(key + "/" + k)}]=${text};\n`);
    });
  }
  return count;
}

/** A MathJax document that typesets as the book does: its packages, the book's macros, SVG glyphs inline. */
function newDocument(macros) {
  return mathjax.document("", {
    InputJax: new TeX({ packages: PACKAGES, macros }),
    OutputJax: new SVG({ fontCache: "none" }),
  });
}

function render(page, macros, fragments) {
  let html = untypeset(fs.readFileSync(page, "utf8"));
  const doc = newDocument(macros);
  let count = 0;
  const errors = [];
  html = html.replace(MATH, (whole, tag, attrs, body) => {
    const eqno = (tag === "div" && EQNO.exec(body)) || [""];  // Sphinx's equation number goes first
    const text = body.slice(eqno[0].length);
    const src = !attrs.includes("data-tex=") && source(tag, text);  // (typeset already: left as it is)
    if (!src) return whole;
    const [tex, display] = src;
    const out = adaptor.outerHTML(convert(doc, tex, display));
    if (/<mjx-merror|data-mjx-error/.test(out)) errors.push(tex);
    count += 1;
    return `<${tag}${attrs} data-tex="${escapeAttr(tex)}">${eqno[0]}${out}</${tag}>`;
  });
  // HTML outputs that ask MathJax to process their text (class mathjax_process: the checker's feedback box in a
  // solution shows the statement with its math in \( \) and \[ \]); their math is typeset here too
  html = html.replace(PROCESS, (whole, open, body, close) => {
    const [out, n] = typesetFragment(body, doc, errors);
    count += n;
    return open + out + close;
  });
  count += renderFragments(fragments || [], doc, errors);
  if (errors.length) {
    throw new Error(`${page}: MathJax could not typeset ${errors.length} formula(s):\n  ` + errors.join("\n  "));
  }
  let css = 0;
  if (count) {
    const style = adaptor.textContent(doc.outputJax.styleSheet(doc));
    css = style.length;
    const menu = JSON.stringify({ macros }).replace(/</g, "\\u003c");
    html = html.replace("</head>", `<style id="course-math-styles">\n${style}</style>\n`
      + `<script type="application/json" id="math-menu-config">${menu}</script>\n</head>`);
  }
  // no page loads MathJax any more: its configuration and loader go (pages without math have neither)
  html = html.replace(CONFIG_SCRIPT, "").replace(STARTUP_SCRIPT, "");
  fs.writeFileSync(page, html);
  return { page, math: count, css };
}

function main(argv) {
  let fragments = {};
  if (argv[0] === "--fragments") {
    fragments = JSON.parse(fs.readFileSync(argv[1], "utf8"));
    argv = argv.slice(2);
  }
  const [staticDir, macrosJson, ...pages] = argv;
  if (!staticDir || !macrosJson) {
    process.stderr.write("usage: node tools/prerender_math.cjs <static-dir> <macros-json> <page.html>...\n");
    return 2;
  }
  const macros = JSON.parse(macrosJson);
  for (const page of pages) process.stdout.write(JSON.stringify(render(page, macros, fragments[page])) + "\n");
  return 0;
}

module.exports = { adaptor, newDocument };

if (require.main === module) process.exitCode = main(process.argv.slice(2));
