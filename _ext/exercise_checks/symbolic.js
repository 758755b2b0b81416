// Symbolic answers (a formula, or a matrix of formulas in the arm's symbols) read and decided in the page.
//
// The text is laid out as a numeric answer is (parse.js: rows, commas, brackets, NumPy or sympy's Matrix(...)),
// and each entry is parsed by math.js (never evaluated as JavaScript). The verdict is the one of
// SymbolicExercise._grade: the answer is evaluated at the three points the checker uses (drawn at build time,
// stored in the bank with the reference's and every catalogued mistake's values there) and compared at each
// point as compare() does with rtol 1e-6, atol 1e-8 (decide.js's compareNumeric); the first point where it
// differs gives the verdict. An answer without any symbol, where symbols are expected, is told so; a symbol
// the exercise does not define is refused with the message of the checker's as_array.

import { agrees, compareNumeric } from "./decide.js";
import { layout, layoutShape, math, mathText } from "./parse.js";

/** compare() for code and symbolic answers (SymbolicExercise._grade). */
const RTOL = 1e-6;
const ATOL = 1e-8;

/** The names math.js would read as constants, not symbols (sympy's pi and E). */
const CONSTANTS = new Set(["pi", "e", "E", "tau", "NaN", "Infinity"]);

/** The names of the symbols in a parsed formula (function names and constants left out). */
export function symbolsOf(/** @type {any} */ node) {
  /** @type {Set<string>} */
  const out = new Set();
  node.traverse((/** @type {any} */ n, /** @type {string} */ path, /** @type {any} */ parent) => {
    if (n.isSymbolNode && !(parent && parent.isFunctionNode && path === "fn") && !CONSTANTS.has(n.name)) {
      out.add(n.name);
    }
  });
  return out;
}

/**
 * A typed symbolic answer: {shape, nodes} (math.js nodes, row-major) or {kind: "empty"|"invalid", message}.
 * @returns {any}
 */
export function parseFormulas(/** @type {string} */ raw) {
  const lay = layout(raw);
  if ("kind" in lay) return lay;
  const nodes = [];
  for (const text of lay.rows.flat()) {
    try {
      nodes.push(math.parse(mathText(text)));
    } catch {
      return { kind: "invalid", message: `“${text.slice(0, 40)}” could not be read as a formula: write it as in ` +
        "Python, with * for products (l1*cos(theta1)), ** or ^ for powers." };
    }
  }
  return { shape: layoutShape(lay), nodes };
}

const sortNames = (/** @type {Iterable<string>} */ names) => [...names].sort();

/** The checker's verdict on a parsed symbolic answer for variant `v` of `bank`. */
export function decideSymbolic(/** @type {any} */ answer, /** @type {any} */ v, /** @type {any} */ bank) {
  const what = v.what || bank.what;
  /** @type {Set<string>} */
  const free = new Set();
  const perEntry = answer.nodes.map((/** @type {any} */ n) => {
    const names = symbolsOf(n);
    names.forEach((x) => free.add(x));
    return names;
  });
  const wanted = /** @type {string[]} */ (v.wanted);
  const catalogued = new Set(v.mistakes.map((/** @type {any[]} */ m) => m[0]));
  const numbersOnly = {
    correct: false, kind: "wrong", mistake: "numbers_for_symbols",
    message: `Your answer holds numbers only, but this exercise asks for a formula in ${wanted.join(", ")}: define ` +
      "the symbols with sympy.symbols and build your matrix from them (no values substituted).",
  };
  const compiled = answer.nodes.map((/** @type {any} */ n) => n.compile());
  for (let p = 0; p < v.points.length; p++) {
    const point = v.points[p];
    const data = [];
    for (let i = 0; i < compiled.length; i++) {
      const unknown = sortNames([...perEntry[i]].filter((x) => !Object.prototype.hasOwnProperty.call(point, x)));
      if (unknown.length) {
        return { correct: false, kind: "invalid", mistake: null, message: `Your answer uses the symbol(s) ` +
          `${unknown.join(", ")}, which this exercise does not define. Use only: ${sortNames(Object.keys(point)).join(", ")}.` };
      }
      let x;
      try {
        x = compiled[i].evaluate({ ...point });
      } catch {
        x = undefined;
      }
      if (typeof x !== "number") {
        return { correct: false, kind: "invalid", mistake: null, message: "One entry of your answer could not be turned into a number." };
      }
      data.push(x);
    }
    const at = { ref: v.ref[p], mistakes: v.mistakes.map((/** @type {any[]} */ m) => [m[0], m[1][p], m[2]]),
      hint: v.hint, what: v.what, rtol: RTOL, atol: ATOL };
    const result = compareNumeric({ shape: answer.shape, data }, at, bank);
    if (wanted.length && !free.size && (result.correct || !catalogued.has(result.mistake))) return numbersOnly;
    if (!result.correct) {
      const missing = wanted.filter((w) => !free.has(w));
      if (["wrong_entry", "wrong_entries", "wrong_value"].includes(result.mistake || "") && missing.length) {
        result.message += ` Your answer does not depend on ${missing.join(", ")}, but the ${what} does.`;
      }
      return result;
    }
  }
  const verb = agrees(what, "agrees", "agree");
  return { correct: true, kind: "correct", mistake: null,
    message: `Your ${what} ${verb} with the reference at random values of ${v.symbols.join(", ")}.` };
}

const GREEK = new Set(["alpha", "beta", "gamma", "delta", "epsilon", "theta", "lambda", "mu", "phi", "psi", "omega"]);

/** The TeX of an arm's symbol as the statements write it (theta1 -> θ₁, l2 -> l₂); other nodes: math.js's own. */
function symbolTex(/** @type {any} */ node) {
  if (node.type !== "SymbolNode") return undefined;
  const m = /^([A-Za-z]+?)_?(\d+)$/.exec(node.name);
  const base = m ? m[1] : node.name;
  if (!m && !GREEK.has(base)) return undefined;  // pi, e and unknown names: math.js's own TeX
  const tex = GREEK.has(base) ? `\\${base}` : base;
  return m ? `${tex}_{${m[2]}}` : tex;
}

/** A preview of the typed formulas: plain text (math.js's own printing, implicit products shown) and TeX. */
export function preview(/** @type {any} */ answer) {
  const text = answer.nodes.map((/** @type {any} */ n) => n.toString({ implicit: "show" }));
  const tex = answer.nodes.map((/** @type {any} */ n) => n.toTex({ implicit: "show", handler: symbolTex }));
  const [r, c] = answer.shape.length === 2 ? answer.shape : [1, text.length];
  const rows = [];
  for (let i = 0; i < r; i++) rows.push(text.slice(i * c, (i + 1) * c));
  const texRows = [];
  for (let i = 0; i < r; i++) texRows.push(tex.slice(i * c, (i + 1) * c).join(" & "));
  const matrix = answer.shape.length === 0 ? tex[0] : `\\begin{bmatrix}${texRows.join(" \\\\ ")}\\end{bmatrix}`;
  return { rows, tex: matrix };
}
