#!/usr/bin/env node
// The book's third-party style sheets trimmed to the rules its pages can use (PurgeCSS, npm `purgecss`).
//
// Usage: node tools/purge_css.cjs <site folder>     (_ext/trim_css.py runs it at the end of every HTML build)
//
// The theme (pydata-sphinx-theme, sphinx-book-theme), sphinx-design, myst-nb and Sphinx's basic.css ship rules
// for every component they offer; a page of this book uses a small part of them. Each of those files is
// rewritten in place with only the rules whose selectors name a class, id, element or attribute found in the
// site: in any page (the lecture decks under slides/ excepted: they load their own copies) or in any script
// under _static (the theme's, the live views', the exercise checks', the course's own), since scripts add
// classes at run time (the theme's dropdowns, sidebars and dark mode, the answer boxes' verdicts, the live
// views' states). PurgeCSS's default extractor takes every word of those files as a possible name, so a class
// a script writes as a literal string is kept. What no file spells out whole is kept by the safelist below.
// The course's own style sheets (course.css, the live views', the exercise checks') are left whole.
//
// Prints one JSON line: the bytes of each trimmed file before and after.

"use strict";

const fs = require("node:fs");
const path = require("node:path");
const { PurgeCSS } = require("purgecss");

//: the files trimmed, relative to _static (a pattern for names with a content hash)
const TRIMMED = [/^styles\/pydata-sphinx-theme\.css$/, /^styles\/sphinx-book-theme\.css$/,
  /^sphinx-design\.min\.css$/, /^mystnb\.[0-9a-f]+\.css$/, /^basic\.css$/];

//: kept whatever the pages say: names built from parts at run time, and states no file spells out whole
const SAFELIST = {
  // dark mode (the theme sets <html data-theme="dark"> and data-mode from the reader's choice or system)
  greedy: [/data-theme/, /data-mode/, /data-bs-theme/, /prefers-color-scheme/,
    // MathJax's output and its menu and explorer, loaded on demand (_theme/math_menu.js)
    /^mjx-/, /MathJax/, /^CtxtMenu/,
    // Bootstrap's JS states (collapse, dropdown, modal, tooltip), written by the theme's bundle
    /^show$/, /^showing$/, /^collapsing$/, /^collapse$/, /^fade$/, /^modal/, /^dropdown/, /^tooltip/,
    /^bs-tooltip/, /^popover/, /^bs-popover/],
  standard: ["active", "focus", "disabled", "expanded", "highlighted", "visible", "hidden", "html", "body"],
};

function walk(dir, keep, out = []) {
  for (const entry of fs.readdirSync(dir, { withFileTypes: true })) {
    const full = path.join(dir, entry.name);
    if (entry.isDirectory()) walk(full, keep, out);
    else if (keep(full)) out.push(full);
  }
  return out;
}

async function main() {
  const site = process.argv[2];
  if (!site || !fs.existsSync(path.join(site, "_static"))) {
    console.error("Usage: node tools/purge_css.cjs <built site folder with _static/>");
    process.exit(2);
  }
  const staticDir = path.join(site, "_static");
  const slides = path.join(site, "slides") + path.sep;
  const pages = walk(site, (f) => f.endsWith(".html") && !f.startsWith(slides));
  const scripts = walk(staticDir, (f) => f.endsWith(".js") || f.endsWith(".mjs"));
  const sheets = walk(staticDir, (f) => f.endsWith(".css"))
    .filter((f) => TRIMMED.some((rx) => rx.test(path.relative(staticDir, f).split(path.sep).join("/"))));
  if (!pages.length) {
    console.error(`purge_css: no page under ${site}`);
    process.exit(1);
  }
  const results = await new PurgeCSS().purge({
    content: [...pages, ...scripts],
    css: sheets,
    safelist: SAFELIST,
    // @font-face, @keyframes and custom properties stay: a font or an animation may be named in a rule that
    // stays, and the theme's colours are custom properties read by scripts
    fontFace: false, keyframes: false, variables: false,
  });
  const sizes = {};
  for (const r of results) {
    const before = fs.statSync(r.file).size;
    // the source map described the whole file
    const css = r.css.replace(/\/\*# sourceMappingURL=.*?\*\/\s*$/s, "");
    fs.writeFileSync(r.file, css);
    sizes[path.relative(staticDir, r.file)] = [before, Buffer.byteLength(css)];
  }
  console.log(JSON.stringify({ pages: pages.length, scripts: scripts.length, sizes }));
}

main().catch((e) => {
  console.error(e && e.stack ? e.stack : String(e));
  process.exit(1);
});
