// The page's verdict on an answer, from the bank data the library wrote at build time.
//
// This is the decision of jacobians.grading.compare.compare (numbers, vectors, matrices) and of
// ScalarExercise._grade (one number, several right values, a range), step by step in the same order and
// with the same floating-point operations, so that the page and the notebook give the same verdict, mistake
// name and message. The browser tests (tests/browser/test_exercise_page.py) check the agreement answer by
// answer; a change to the Python comparison must be made here too.
//
// An answer is {shape: number[], data: number[]} (row-major, at most two indices).

/** 10^-k as the correctly rounded literal (Python's 10.0 ** -k is the same double: tests/test_exercise_bank.py). */
const negPow10 = (/** @type {number} */ k) => Number(`1e-${k}`);
const posPow10 = (/** @type {number} */ k) => Number(`1e${k}`);

/** Python's tuple repr of a shape: (), (6,), (6, 3). */
export function shapeText(/** @type {number[]} */ shape) {
  if (shape.length === 0) return "()";
  if (shape.length === 1) return `(${shape[0]},)`;
  return `(${shape.join(", ")})`;
}

/** Python's format(x, f".{p}g"). */
export function formatG(/** @type {number} */ x, /** @type {number} */ p) {
  if (x === 0) return Object.is(x, -0) ? "-0" : "0";
  if (!Number.isFinite(x)) return Number.isNaN(x) ? "nan" : x > 0 ? "inf" : "-inf";
  const [mant, expText] = x.toExponential(p - 1).split("e");
  const exp = Number(expText);
  if (exp >= -4 && exp < p) {
    let s = x.toFixed(Math.max(0, p - 1 - exp));
    if (s.includes(".")) s = s.replace(/0+$/, "").replace(/\.$/, "");
    return s;
  }
  let m = mant;
  if (m.includes(".")) m = m.replace(/0+$/, "").replace(/\.$/, "");
  const sign = exp < 0 ? "-" : "+";
  const digits = String(Math.abs(exp)).padStart(2, "0");
  return `${m}e${sign}${digits}`;
}

/** The verb that agrees with `what` (jacobians.grading.feedback.agrees). */
export function agrees(/** @type {string} */ what, /** @type {string} */ singular, /** @type {string} */ plural) {
  const head = what.split(" of ")[0].split(/\s+/).filter(Boolean);
  const last = head.length ? head[head.length - 1] : what;
  const s = last.endsWith("s") && !(last.endsWith("ss") || last.endsWith("is") || last.endsWith("us"));
  return s ? plural : singular;
}

const sameShape = (/** @type {number[]} */ a, /** @type {number[]} */ b) =>
  a.length === b.length && a.every((v, i) => v === b[i]);

/** A nested list (the bank's JSON) as {shape, data}. */
export function fromNested(/** @type {any} */ x) {
  if (!Array.isArray(x)) return { shape: [], data: [Number(x)] };
  if (x.length && Array.isArray(x[0])) {
    return { shape: [x.length, x[0].length], data: x.flat().map(Number) };
  }
  return { shape: [x.length], data: x.map(Number) };
}

/** |a - b| <= tol entry by entry (tol an array of the shape of b); false for a NaN or another shape. */
function within(/** @type {any} */ a, /** @type {any} */ b, /** @type {number[]} */ tol) {
  if (!sameShape(a.shape, b.shape)) return false;
  for (let i = 0; i < b.data.length; i++) if (!(Math.abs(a.data[i] - b.data[i]) <= tol[i])) return false;
  return true;
}

/** compare.tolerance with decimals: half a unit of the last decimal asked, plus 1e-5 of the value. */
function decimalTol(/** @type {any} */ ref, /** @type {number} */ decimals) {
  const half = 0.5 * negPow10(decimals) * (1 + 1e-6);
  return ref.data.map((/** @type {number} */ v) => half + 1e-5 * Math.abs(v));
}

/** compare.tolerance without decimals: atol + rtol |ref| (symbolic answers, compared tightly). */
function relTol(/** @type {any} */ ref, /** @type {number} */ rtol, /** @type {number} */ atol) {
  return ref.data.map((/** @type {number} */ v) => atol + rtol * Math.abs(v));
}

/** The entry-wise tolerance around `ref`: the stated one, half a unit of the decimals asked, or rtol/atol. */
function tolAround(/** @type {any} */ ref, /** @type {any} */ v) {
  if (v.tol != null) return statedTol(v.tol, ref);
  return v.decimals == null ? relTol(ref, v.rtol, v.atol) : decimalTol(ref, v.decimals);
}

/** compare._stated: the stated tolerance with room for binary noise. */
function statedTol(/** @type {number} */ tol, /** @type {any} */ ref) {
  let m = 0;
  for (const v of ref.data) m = Math.max(m, Math.abs(v));
  const t = tol * (1 + 1e-9) + 1e-12 * (1 + m);
  return ref.data.map(() => t);
}

/** compare.given_decimals: k < most if every entry is a multiple of 10^-k, else null. */
export function givenDecimals(/** @type {number[]} */ data, /** @type {number} */ most) {
  for (let k = 0; k < most; k++) {
    const p = posPow10(k);
    let all = true;
    for (const v of data) {
      const scaled = v * p;
      // numpy rounds half to even, Math.round half up: at a half both are 0.5 away, so the test is the same
      if (!(Math.abs(scaled - Math.round(scaled)) <= 1e-6 * Math.max(1.0, Math.abs(scaled)))) { all = false; break; }
    }
    if (all) return k;
  }
  return null;
}

const verdict = (/** @type {boolean} */ ok, /** @type {string} */ message, /** @type {string|null} */ mistake = null) =>
  ({ correct: ok, kind: ok ? "correct" : "wrong", mistake, message });

function transpose(/** @type {any} */ a) {
  const [r, c] = a.shape;
  const data = new Array(r * c);
  for (let i = 0; i < r; i++) for (let j = 0; j < c; j++) data[j * r + i] = a.data[i * c + j];
  return { shape: [c, r], data };
}

function column(/** @type {any} */ a, /** @type {number} */ j) {
  const [r, c] = a.shape;
  const data = [];
  for (let i = 0; i < r; i++) data.push(a.data[i * c + j]);
  return { shape: [r], data };
}

const TRANSPOSED = "Your matrix is the transpose of the right one: rows and columns are swapped.";

function shapeFeedback(/** @type {any} */ ans, /** @type {any} */ ref, /** @type {number[]} */ tol, /** @type {string} */ what) {
  if (!sameShape(ans.shape, ref.shape)) {
    if (ref.shape.length === 2 && ans.shape.length === 2 && ans.shape[0] === ref.shape[1] &&
        ans.shape[1] === ref.shape[0] && within(transpose(ans), ref, tol)) {
      return verdict(false, TRANSPOSED, "transposed");
    }
    const jacobian = ref.shape.length === 2 && ref.shape[0] === 6 && what.includes("Jacobian");
    const layout = jacobian ? " (6 rows (ω, v), one column per joint)."
      : ": check how many rows and columns the statement asks for.";
    return verdict(false, `Your answer has shape ${shapeText(ans.shape)}, but this ${what} has shape ` +
      `${shapeText(ref.shape)}` + layout, "wrong_shape");
  }
  if (ref.shape.length === 1 && ref.data.length > 1) {
    const order = ref.data.map((/** @type {number} */ _v, /** @type {number} */ i) => i)
      .sort((/** @type {number} */ a, /** @type {number} */ b) => ref.data[a] - ref.data[b] || a - b);
    const sortedAns = [...ans.data].sort((a, b) => a - b);
    const sortedRef = { shape: ref.shape, data: order.map((/** @type {number} */ i) => ref.data[i]) };
    if (within({ shape: ans.shape, data: sortedAns }, sortedRef, order.map((/** @type {number} */ i) => tol[i]))) {
      return verdict(false, "Every value you gave is right, but they are in the wrong order: check the order " +
        "the statement asks for (entry i belongs to joint i, or the order it names, such as largest first).",
      "wrong_order");
    }
  }
  if (ref.shape.length === 2 && ref.shape[0] === ref.shape[1] && within(transpose(ans), ref, tol)) {
    return verdict(false, TRANSPOSED, "transposed");
  }
  if (ref.shape.length === 2 && ref.shape[1] > 1) {
    const cols = ref.shape[1];
    const tolCols = [];
    for (let k = 0; k < cols; k++) tolCols.push(column({ shape: ref.shape, data: tol }, k).data);
    const perm = [];
    for (let j = 0; j < cols; j++) {
      const hits = [];
      for (let k = 0; k < cols; k++) if (within(column(ans, j), column(ref, k), tolCols[k])) hits.push(k);
      perm.push(hits);
    }
    if (perm.every((h) => h.length) && !perm.every((h, j) => h.includes(j))) {
      return verdict(false, "Every column you gave is a right column, but in the wrong place: check the " +
        "order of the columns (column i belongs to joint i).", "column_order");
    }
  }
  if (ref.shape.length === 2 && ref.shape[0] > 1) {
    const [rows, cols] = ref.shape;
    const row = (/** @type {any} */ a, /** @type {number} */ i) => ({ shape: [cols], data: a.data.slice(i * cols, (i + 1) * cols) });
    const perm = [];
    for (let i = 0; i < rows; i++) {
      const hits = [];
      for (let k = 0; k < rows; k++) if (within(row(ans, i), row(ref, k), tol.slice(k * cols, (k + 1) * cols))) hits.push(k);
      perm.push(hits);
    }
    if (perm.every((h) => h.length) && !perm.every((h, i) => h.includes(i))) {
      return verdict(false, "Every row you gave is a right row, but in the wrong place: check the order of " +
        "the rows" + (rows === 6 ? " (ω in rows 1-3, then v in rows 4-6)." : "."), "row_order");
    }
  }
  return null;
}

function rowsText(/** @type {number[]} */ badRows) {
  const ang = badRows.some((r) => r < 3);
  const lin = badRows.some((r) => r >= 3);
  if (ang && lin) return "in both the angular rows 1-3 and the linear rows 4-6";
  return ang ? "in the angular rows 1-3 (ω)" : "in the linear rows 4-6 (v)";
}

function entriesFeedback(/** @type {any} */ ans, /** @type {any} */ ref, /** @type {number[]} */ tol,
  /** @type {string} */ what, /** @type {string} */ entryHint) {
  const bad = ref.data.map((/** @type {number} */ r, /** @type {number} */ i) => !(Math.abs(ans.data[i] - r) <= tol[i]));
  const nbad = bad.filter(Boolean).length;
  const twistRows = ref.shape.length >= 1 && ref.shape[0] === 6;
  if (ref.shape.length === 0) {
    const side = ans.data[0] > ref.data[0] ? "too large" : "too small";
    const hint = entryHint || `Redo the computation step by step and check each quantity that enters your ${what}.`;
    return verdict(false, `Your ${what} ${agrees(what, "is", "are")} ${side}. ${hint}`, "wrong_value");
  }
  const eh = entryHint || "Check the wrong entries' joint, frame and sign against the definition.";
  if (nbad === 1) {
    const i = bad.indexOf(true);
    let where;
    if (ref.shape.length === 1) where = `entry ${i + 1} (counting from 1)`;
    else {
      const c = ref.shape[1];
      where = `the entry in row ${Math.floor(i / c) + 1}, column ${(i % c) + 1} (counting from 1)`;
    }
    return verdict(false, `Almost: ${where} is wrong; every other entry is right. ${eh}`, "wrong_entry");
  }
  if (ref.shape.length === 2) {
    const [r, c] = ref.shape;
    const cols = [];
    const good = [];
    const badRowSet = [];
    for (let j = 0; j < c; j++) {
      let any = false;
      for (let i = 0; i < r; i++) if (bad[i * c + j]) any = true;
      (any ? cols : good).push(j);
    }
    for (let i = 0; i < r; i++) {
      let any = false;
      for (let j = 0; j < c; j++) if (bad[i * c + j]) any = true;
      if (any) badRowSet.push(i);
    }
    let msg = `${nbad} entries are wrong, in column(s) ${cols.map((j) => j + 1).join(", ")}`;
    if (twistRows) msg += " " + rowsText(badRowSet);
    if (good.length) msg += `; column(s) ${good.map((j) => j + 1).join(", ")} are right`;
    return verdict(false, msg + `. ${eh}`, "wrong_entries");
  }
  const rows = [];
  for (let i = 0; i < bad.length; i++) if (bad[i]) rows.push(i);
  const extra = twistRows ? `, ${rowsText(rows)}` : "";
  return verdict(false, `Entries ${rows.map((i) => i + 1).join(", ")} (counting from 1) are wrong${extra}. ${eh}`,
    "wrong_entries");
}

/** compare.precision_message */
export function precisionMessage(/** @type {string} */ what, /** @type {number} */ given, /** @type {number} */ asked) {
  const dec = given === 1 ? "decimal" : "decimals";
  const verb = agrees(what, "agrees", "agree");
  return `Your ${what} ${verb} with the reference to the ${given} ${dec} you gave, but this exercise ` +
    `asks for ${asked} decimals: give more decimals (keep the digits your computation gives, or round ` +
    `to ${asked}).`;
}

function nearMessage(/** @type {string} */ what, /** @type {number} */ tol, /** @type {number} */ worst,
  /** @type {number|null} */ carry) {
  const steps = carry != null ? `rounding every step to ${carry} decimals` : "rounding the answer";
  const verb = agrees(what, "is", "are");
  return `Close: your ${what} ${verb} off by up to ${formatG(worst, 2)}, a little more than the ±${formatG(tol, 6)} ` +
    `that ${steps} can give. Your method looks right; carry more decimals through the steps (keep 4 or 5, or let ` +
    "Python keep them all) and round only the final answer.";
}

/** How many tolerances from the reference an answer gets the message about precision (compare.NEAR). */
const NEAR = 3.0;

/**
 * compare(ans, ref, mistakes, rtol, atol, what, hint, decimals, tol, carry) for a numeric exercise.
 * @param {{shape: number[], data: number[]}} answer
 * @param {any} v one variant of the bank
 * @param {any} bank the exercise's bank (what, messages)
 */
export function compareNumeric(answer, v, bank) {
  const what = v.what || bank.what;
  const ref = fromNested(v.ref);
  let ans = answer;
  const adim = ans.shape.length;
  if (ref.shape.length === 1 && ans.data.length === ref.data.length && adim <= 2 &&
      (adim === 1 || ans.shape.includes(1))) {
    ans = { shape: ref.shape, data: ans.data };
  }
  if (ref.shape.length === 0 && ans.data.length === 1) ans = { shape: [], data: ans.data };
  if (!ans.data.every(Number.isFinite)) {
    return verdict(false, "Your answer contains NaN or inf: check for a division by zero or an unset entry.",
      "not_finite");
  }
  const decimals = v.decimals;
  const stated = v.tol;
  const tolv = tolAround(ref, v);
  if (within(ans, ref, tolv)) {
    return verdict(true, `Your ${what} ${agrees(what, "matches", "match")} the reference` +
      (stated != null ? ` (within ±${formatG(stated, 6)}).` : "."));
  }
  const values = v.mistakes.map((/** @type {any[]} */ m) => [m[0], fromNested(m[1]), bank.messages[m[2]]]);
  for (const [name, mv, message] of values) {
    const mtol = tolAround(mv, v);
    if (sameShape(mv.shape, ans.shape) && within(ans, mv, mtol)) return verdict(false, message, name);
  }
  const k = decimals != null && sameShape(ans.shape, ref.shape) ? givenDecimals(ans.data, decimals) : null;
  if (k !== null && decimals != null && (k > 0 || ans.data.some((/** @type {number} */ x) => x !== 0))) {
    const half = 0.5 * negPow10(k) * (1 + 1e-6);
    if (within(ans, ref, ref.data.map((/** @type {number} */ r) => half + 1e-5 * Math.abs(r)))) {
      return verdict(false, precisionMessage(what, k, decimals), "too_few_decimals");
    }
    for (const [name, mv, message] of values) {
      if (sameShape(mv.shape, ans.shape) && within(ans, mv, mv.data.map((/** @type {number} */ r) => half + 1e-5 * Math.abs(r)))) {
        return verdict(false, message, name);
      }
    }
  }
  if (stated != null && sameShape(ans.shape, ref.shape) && within(ans, ref, tolv.map((t) => NEAR * t))) {
    let worst = 0;
    for (let i = 0; i < ref.data.length; i++) worst = Math.max(worst, Math.abs(ans.data[i] - ref.data[i]));
    return verdict(false, nearMessage(what, stated, worst, v.carry), "imprecise");
  }
  const hint = bank.messages[v.hint] || "";
  return shapeFeedback(ans, ref, tolv, what) || entriesFeedback(ans, ref, tolv, what, hint);
}

/** ScalarExercise._grade: one number, one of several right values, maybe within a range. */
export function compareScalar(/** @type {{shape: number[], data: number[]}} */ answer, /** @type {any} */ v,
  /** @type {any} */ bank) {
  const what = v.what || bank.what;
  const d = v.decimals != null ? v.decimals : 3;
  const hint = bank.messages[v.hint] || "";
  if (answer.data.length !== 1) {
    return verdict(false, `Give one number (the ${what}); you gave ${answer.data.length} values.`, "wrong_shape");
  }
  const x = answer.data[0];
  if (!Number.isFinite(x)) return verdict(false, "Your answer is NaN or inf: check for a division by zero.", "not_finite");
  const tol = 0.5 * negPow10(d) * (1 + 1e-6);
  const k = givenDecimals([x], d);
  const coarse = k !== null ? 0.5 * negPow10(k) * (1 + 1e-6) : tol;
  const near = (/** @type {number[]} */ values, /** @type {number} */ w) => values.some((val) => Math.abs(x - val) <= w);
  if (near(v.accepted, tol)) {
    return verdict(true, `Your ${what} ${agrees(what, "is", "are")} right (to the ${d} decimals asked).`);
  }
  for (const [name, value, m] of v.mistakes) {
    if (near([Number(value)], Math.max(tol, k !== null && k > 0 ? coarse : tol))) {
      return verdict(false, bank.messages[m], name);
    }
  }
  if (v.interval != null && !(v.interval[0] < x && x < v.interval[1])) {
    const msg = `The statement asks for a value in ${v.interval[2]}, and yours lies outside that range.`;
    if (near(v.outside, Math.max(tol, coarse))) {
      return verdict(false, msg + ` It does give the same configuration as the ${what} asked for: add or subtract ` +
        "a multiple of 2π to bring it into the range.", "outside_range");
    }
    return verdict(false, msg + " " + hint, "outside_range");
  }
  if (k !== null && k > 0 && near(v.accepted, coarse)) {
    return verdict(false, precisionMessage(what, k, d), "too_few_decimals");
  }
  return verdict(false, `Your ${what} ${agrees(what, "is", "are")} not right. ${hint}`.trim(), "wrong_value");
}

/** The verdict on an answer already read into numbers ({shape, data}) for variant `v` of `bank` (numbers and one
 * number; a formula is decided by symbolic.js, through compareNumeric at each sample point). */
export function decide(/** @type {{shape: number[], data: number[]}} */ answer, /** @type {any} */ v,
  /** @type {any} */ bank) {
  return bank.kind === "scalar" ? compareScalar(answer, v, bank) : compareNumeric(answer, v, bank);
}
