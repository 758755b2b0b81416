// Pre-compressed copies of the built site's text files, for hosts that serve them
// (nginx gzip_static / brotli_static, Netlify, Cloudflare, Apache with
// mod_rewrite): <file>.gz (gzip, level 9) and <file>.br (brotli, quality 11)
// next to each HTML, CSS, JavaScript, JSON, SVG or XML file of at least 1 KB.
// A host that compresses on the fly (GitHub Pages) ignores them. Copies whose
// original is gone or newer are written again or removed, so the command can
// run after every build.
//
// Usage: node tools/precompress.cjs <site-dir>      (prints a one-line summary)
"use strict";

const fs = require("fs");
const path = require("path");
const zlib = require("zlib");

const TEXT = new Set([".html", ".css", ".js", ".mjs", ".json", ".svg", ".xml", ".txt", ".map"]);
const MIN_BYTES = 1024;

function* files(dir) {
  for (const e of fs.readdirSync(dir, { withFileTypes: true })) {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) yield* files(p);
    else if (e.isFile()) yield p;
  }
}

function main(site) {
  if (!site || !fs.existsSync(path.join(site, "index.html"))) {
    process.stderr.write(`usage: node tools/precompress.cjs <built site> (no index.html in ${site})\n`);
    return 2;
  }
  let written = 0, removed = 0, raw = 0, gz = 0, br = 0;
  const all = [...files(site)];
  for (const f of all) {
    const ext = path.extname(f);
    if (ext === ".gz" || ext === ".br") {
      const original = f.slice(0, -3);
      if (!fs.existsSync(original) || fs.statSync(original).size < MIN_BYTES) { fs.unlinkSync(f); removed += 1; }
      continue;
    }
    if (!TEXT.has(ext)) continue;
    const stat = fs.statSync(f);
    if (stat.size < MIN_BYTES) continue;
    raw += stat.size;
    for (const [suffix, pack] of [
      [".gz", (b) => zlib.gzipSync(b, { level: 9 })],
      [".br", (b) => zlib.brotliCompressSync(b, { params: {
        [zlib.constants.BROTLI_PARAM_QUALITY]: 11, [zlib.constants.BROTLI_PARAM_SIZE_HINT]: b.length } })],
    ]) {
      const out = f + suffix;
      if (!fs.existsSync(out) || fs.statSync(out).mtimeMs < stat.mtimeMs) {
        fs.writeFileSync(out, pack(fs.readFileSync(f)));
        written += 1;
      }
      const size = fs.statSync(out).size;
      if (suffix === ".gz") gz += size; else br += size;
    }
  }
  const mb = (n) => (n / 1e6).toFixed(1);
  process.stdout.write(`precompress: ${written} files written, ${removed} stale removed; text ${mb(raw)} MB `
    + `-> ${mb(gz)} MB gzip, ${mb(br)} MB brotli\n`);
  return 0;
}

process.exitCode = main(process.argv[2]);
