// How the page reads a typed answer: a number, a vector or a matrix, each entry an expression math.js
// evaluates (fractions, pi, sqrt(2), cos(pi/3), 1e-3). The layout is read first, then each entry is given to
// math.js (the number-only build, with only the functions a hand computation needs: no import, no units):
//   - one number:                    0.5     1/2     -pi/4
//   - a vector:                      0.5, 1, 0     [0.5 1 0]     (0.5, 1, 0)
//   - a matrix as rows, one a line:  1 0 0 / 0 1 0 (lines)
//   - pasted from NumPy:             array([[1., 0.], [0., 1.]])  or its printed form [[1. 0.]\n [0. 1.]]
//   - pasted from MATLAB:            [1 0; 0 1]
// Returns {shape, data} or {kind: "empty"|"invalid", message}.

import {
  create, evaluateDependencies, addDependencies, subtractDependencies, multiplyDependencies,
  divideDependencies, powDependencies, unaryMinusDependencies, unaryPlusDependencies, sqrtDependencies,
  cosDependencies, sinDependencies, tanDependencies, acosDependencies, asinDependencies, atanDependencies,
  atan2Dependencies, expDependencies, logDependencies, absDependencies, piDependencies, tauDependencies,
  eDependencies, NaNDependencies, InfinityDependencies, parseDependencies,
} from "mathjs/number";

const math = create({
  evaluateDependencies, addDependencies, subtractDependencies, multiplyDependencies, divideDependencies,
  powDependencies, unaryMinusDependencies, unaryPlusDependencies, sqrtDependencies, cosDependencies,
  sinDependencies, tanDependencies, acosDependencies, asinDependencies, atanDependencies, atan2Dependencies,
  expDependencies, logDependencies, absDependencies, piDependencies, tauDependencies, eDependencies,
  NaNDependencies, InfinityDependencies, parseDependencies,
});

/** The math.js instance the page reads answers with (numbers only; the functions listed above). */
export { math };

/** An entry's text as math.js reads it: nan, inf and Python's ** spelled its way. */
export const mathText = (/** @type {string} */ text) =>
  text.replace(/\bnan\b/gi, "NaN").replace(/\binf\b/gi, "Infinity").replace(/\*\*/g, "^");

/** Longest answer read, in characters (a 6 x 6 matrix with 10 digits an entry is about 600). */
export const MAX_CHARS = 20000;
/** Most entries read (the checker's own limit is 10 000; no exercise asks for more than 36). */
export const MAX_ENTRIES = 10000;

const invalid = (/** @type {string} */ message) => ({ kind: "invalid", message });

/** One entry's text to a number with math.js. */
function entry(/** @type {string} */ text) {
  const t = mathText(text);
  let value;
  try {
    value = math.evaluate(t, {});
  } catch (err) {
    const msg = String(/** @type {any} */ (err)?.message || err);
    const unknown = /Undefined symbol (\S+)/.exec(msg) || /Undefined function (\S+)/.exec(msg);
    if (unknown) {
      throw new Error(`“${unknown[1]}” is not a number or a function the checker knows: give numbers (fractions, ` +
        "pi, sqrt, sin, cos, tan, exp, log are accepted).", { cause: err });
    }
    throw new Error(`“${text.slice(0, 40)}” could not be read as a number.`, { cause: err });
  }
  if (typeof value !== "number") throw new Error(`“${text.slice(0, 40)}” is not a single real number.`);
  return value;
}

/** Split at the commas outside parentheses (atan2(1, 2) stays one entry). */
function topLevelSplit(/** @type {string} */ text) {
  const out = [];
  let depth = 0;
  let start = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (c === "(") depth++;
    else if (c === ")") depth = Math.max(0, depth - 1);
    else if (c === "," && depth === 0) { out.push(text.slice(start, i)); start = i + 1; }
  }
  out.push(text.slice(start));
  return out;
}

/** The entries of one row: split at commas if there are any, else at spaces (MATLAB, NumPy's print). */
function rowEntries(/** @type {string} */ row) {
  const r = row.replace(/[[\]]/g, " ").trim();
  if (!r) return [];
  const parts = topLevelSplit(r);
  if (parts.length > 1) return parts.map((s) => s.trim()).filter((s, i, all) => s || i < all.length - 1);
  // spaces inside an expression join it: around * / ^, inside brackets, and a - or + with spaces on both sides
  const joined = r.replace(/,\s+/g, ",").replace(/\s*([*/^])\s*/g, "$1").replace(/\(\s*/g, "(").replace(/\s*\)/g, ")")
    .replace(/(\S)\s+([+-])\s+(?=\S)/g, "$1$2");
  return joined.split(/\s+/);
}

/**
 * The layout of a typed answer: its entries' texts, row by row, and whether it was written in brackets; or
 * {kind: "empty"|"invalid", message}.
 * @returns {{rows: string[][], bracketed: boolean, nested: boolean} | {kind: string, message: string}}
 */
export function layout(/** @type {string} */ raw) {
  if (typeof raw !== "string") return invalid("The answer is not text.");
  if (raw.length > MAX_CHARS) return invalid(`Your answer has ${raw.length} characters, far more than this exercise needs.`);
  let text = raw.trim();
  if (!text) return { kind: "empty", message: "Type your answer in the box, then press Check." };
  // NumPy's repr: array([...]) or matrix([...]), maybe with dtype=...; np. in front; sympy's Matrix([...])
  const wrapped = /^(np\.|numpy\.|sp\.|sympy\.)?(array|matrix|asarray|Matrix)\s*\(/.exec(text);
  if (wrapped) {
    text = text.slice(wrapped[0].length).replace(/,\s*dtype\s*=\s*[\w.]+\s*/, "").replace(/\)\s*$/, "").trim();
  }
  // a tuple (1, 2, 3) reads as a list
  if (/^\(.*,.*\)$/s.test(text) && !/^\([^()]*\)\s*[-+*/^]/.test(text)) text = "[" + text.slice(1, -1) + "]";
  const bracketed = text.startsWith("[");
  const nested = /^\[\s*\[/.test(text);  // [[...]]: a matrix, even of one row
  let rows;
  if (/\]\s*[,;]?\s*\[/.test(text)) {
    // nested brackets: a row ends at "]" before the next "["
    rows = text.split(/\]\s*[,;]?\s*\[/);
  } else if (text.includes(";")) {
    rows = text.split(";");
  } else if (!bracketed && /\n/.test(text)) {
    rows = text.split(/\n/);
  } else {
    rows = [text.replace(/\n/g, " ")];
  }
  rows = rows.map((r) => r.replace(/\n/g, " ")).filter((r) => r.replace(/[[\]]/g, "").trim());
  let entries;
  try {
    entries = rows.map((r) => rowEntries(r));
  } catch {
    return invalid("Your answer could not be read: give numbers separated by commas or spaces, one row a line.");
  }
  const count = entries.reduce((a, r) => a + r.length, 0);
  if (count === 0) return { kind: "empty", message: "Type your answer in the box, then press Check." };
  if (count > MAX_ENTRIES) return invalid(`Your answer has ${count} entries, far more than this exercise needs.`);
  if (entries.some((r) => r.length !== entries[0].length)) {
    return invalid("Your rows have different lengths: every row of a matrix needs the same number of entries.");
  }
  if (entries.some((r) => r.some((e) => !e))) return invalid("One entry of your answer is empty (two commas in a row?).");
  return { rows: entries, bracketed, nested };
}

/** The shape of a layout: () for one entry typed without brackets, (n,) for one row, (rows, columns) for several
 * rows or rows in brackets ([[1, 2]] is (1, 2), as numpy reads it). */
export function layoutShape(/** @type {{rows: string[][], bracketed: boolean, nested: boolean}} */ lay) {
  const entries = lay.rows;
  if (entries.length > 1 || lay.nested) return [entries.length, entries[0].length];
  if (entries[0].length === 1 && !lay.bracketed) return [];
  return [entries[0].length];
}

/** Read a typed answer. */
export function parseAnswer(/** @type {string} */ raw) {
  const lay = layout(raw);
  if ("kind" in lay) return lay;
  const entries = lay.rows;
  let data;
  try {
    data = entries.flat().map(entry);
  } catch (err) {
    return invalid(String(/** @type {any} */ (err).message));
  }
  return { shape: layoutShape(lay), data };
}
