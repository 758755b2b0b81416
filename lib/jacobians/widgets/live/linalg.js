// @ts-check
// Small dense linear algebra for the live views: input checks, 3-vectors
// and 3×3 matrices, and a one-sided Jacobi (Hestenes) SVD with the solvers and ellipsoids
// built on it. Split out of kinematics.js, which re-exports the public functions; the
// library counterparts are listed there. Matrices are arrays of rows.

/** @typedef {number[]} Vec a vector */
/** @typedef {number[][]} Mat a matrix, as an array of rows */
/**
 * A thin SVD from one-sided Jacobi: sigma descending; b and w as in `jacobi`; rowsSide tells which side of A.
 * @typedef {{sigma: Vec, b: Vec[], w: Vec[], rowsSide: boolean}} SVD
 */

export const EPS = 2.220446049250313e-16;

// ------------------------------------------------------------ validation

/** An array or a typed array (not a DataView): what a vector or a row may be given as.
 * @param {unknown} x
 * @returns {x is ArrayLike<unknown>}
 */
function isArrayLike(x) {
  return Array.isArray(x) || (ArrayBuffer.isView(x) && !(x instanceof DataView));
}

/** A short description of a value, for error messages.
 * @param {unknown} x
 * @returns {string}
 */
export function describe(x) {
  if (Array.isArray(x)) {
    if (x.length && Array.isArray(x[0])) return `an array of ${x.length} rows of ${x[0].length}`;
    return `an array of length ${x.length}`;
  }
  if (isArrayLike(x)) return `a typed array of length ${x.length}`;
  if (ArrayBuffer.isView(x)) return "a DataView";
  if (x === null) return "null";
  return `${typeof x} ${String(x).slice(0, 60)}`;
}

/** A copy of x as an array of finite numbers (of length len if given), or an error that names it.
 * @param {unknown} x
 * @param {string} name
 * @param {number} [len]
 * @returns {Vec}
 */
export function vector(x, name, len) {
  if (!isArrayLike(x) || (len !== undefined && x.length !== len) || x.length === 0) {
    const want = len === undefined ? "a non-empty array of numbers" : `an array of ${len} numbers`;
    throw new Error(`Expected ${name} as ${want}, got ${describe(x)}`);
  }
  /** @type {Vec} */
  const out = new Array(x.length);
  for (let i = 0; i < x.length; i++) {
    const v = x[i];
    if (typeof v !== "number" || !Number.isFinite(v)) {
      throw new Error(`Expected finite numbers in ${name}, got ${String(v)} at index ${i}`);
    }
    out[i] = v;
  }
  return out;
}

/** A copy of A as rows of finite numbers (rows×cols if given), or an error that names it.
 * @param {unknown} A
 * @param {string} name
 * @param {number} [rows]
 * @param {number} [cols]
 * @returns {Mat}
 */
export function matrix(A, name, rows, cols) {
  const shape = `${rows ?? "m"}×${cols ?? "n"}`;
  if (!Array.isArray(A) || A.length === 0 || (rows !== undefined && A.length !== rows)) {
    throw new Error(`Expected ${name} with shape ${shape} (an array of rows), got ${describe(A)}`);
  }
  /** @type {number | undefined} */
  const c = cols ?? (isArrayLike(A[0]) ? A[0].length : undefined);
  /** @type {Mat} */
  const out = new Array(A.length);
  for (let r = 0; r < A.length; r++) {
    const row = A[r];
    if (!isArrayLike(row) || row.length !== c || c === 0) {
      throw new Error(`Expected ${name} with shape ${shape} (an array of rows), got row ${r} as ${describe(row)}`);
    }
    out[r] = vector(row, `${name}[${r}]`, c);
  }
  return out;
}

/** x if it is a finite number > 0 (>= 0 with allowZero), else an error that names it.
 * @param {unknown} x
 * @param {string} name
 * @param {boolean} allowZero
 * @returns {number}
 */
export function nonNegative(x, name, allowZero) {
  if (typeof x !== "number" || !Number.isFinite(x) || x < 0 || (!allowZero && x === 0)) {
    throw new Error(`Expected ${name} as a ${allowZero ? "non-negative" : "positive"} finite number, got ${String(x)}`);
  }
  return x;
}

// ------------------------------------------------------------ 3-vectors, 3×3

/** @type {(a: Vec, b: Vec) => Vec} */
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
/** R x for a 3×3 R. @type {(R: Mat, x: Vec) => Vec} */
export const mulMv = (R, x) => [
  R[0][0] * x[0] + R[0][1] * x[1] + R[0][2] * x[2],
  R[1][0] * x[0] + R[1][1] * x[1] + R[1][2] * x[2],
  R[2][0] * x[0] + R[2][1] * x[1] + R[2][2] * x[2],
];
/** Rᵀ x for a 3×3 R. @type {(R: Mat, x: Vec) => Vec} */
export const mulMtv = (R, x) => [
  R[0][0] * x[0] + R[1][0] * x[1] + R[2][0] * x[2],
  R[0][1] * x[0] + R[1][1] * x[1] + R[2][1] * x[2],
  R[0][2] * x[0] + R[1][2] * x[1] + R[2][2] * x[2],
];
/** A B for 3×3 matrices.
 * @param {Mat} A
 * @param {Mat} B
 * @returns {Mat}
 */
export function mulMM(A, B) {
  const C = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) C[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  }
  return C;
}
/** [w], the 3×3 skew-symmetric matrix of w. @type {(w: Vec) => Mat} */
export const skew = (w) => [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]];
/** @type {(x: Vec) => number} */
export const norm = (x) => Math.hypot(...x);

/** The 4×4 transform of a rotation R and a position p.
 * @param {Mat} R
 * @param {Vec} p
 * @returns {Mat}
 */
export function transform(R, p) {
  return [[R[0][0], R[0][1], R[0][2], p[0]], [R[1][0], R[1][1], R[1][2], p[1]],
    [R[2][0], R[2][1], R[2][2], p[2]], [0, 0, 0, 1]];
}

// ------------------------------------------------------------ SVD (one-sided Jacobi)

/** (x, y) ← (c x − s y, s x + c y), in place.
 * @param {Vec} x
 * @param {Vec} y
 * @param {number} c
 * @param {number} s
 */
function rotate(x, y, c, s) {
  for (let i = 0; i < x.length; i++) {
    const xi = x[i], yi = y[i];
    x[i] = c * xi - s * yi;
    y[i] = s * xi + c * yi;
  }
}

// Orthogonalise the vectors xs (k vectors of one length) by plane rotations:
// [b_1 … b_k] = [x_1 … x_k] W with W (k×k, columns w_i) orthogonal and the b_i
// mutually orthogonal. σ_i = |b_i|, sorted in descending order.
/**
 * @param {Mat} xs
 * @returns {{sigma: Vec, b: Vec[], w: Vec[]}}
 */
function jacobi(xs) {
  const k = xs.length;
  const b = xs.map((x) => x.slice());
  const W = Array.from({ length: k }, (_, i) => Array.from({ length: k }, (_, j) => (i === j ? 1 : 0)));
  /** @type {(x: Vec, y: Vec) => number} */
  const dot = (x, y) => { let s = 0; for (let i = 0; i < x.length; i++) s += x[i] * y[i]; return s; };
  for (let sweepNo = 0; sweepNo < 60; sweepNo++) {
    let rotated = false;
    for (let p = 0; p < k - 1; p++) {
      for (let q = p + 1; q < k; q++) {
        const alpha = dot(b[p], b[p]), beta = dot(b[q], b[q]), gamma = dot(b[p], b[q]);
        if (gamma === 0 || Math.abs(gamma) <= EPS * Math.sqrt(alpha * beta)) continue;
        rotated = true;
        const zeta = (beta - alpha) / (2 * gamma);
        const t = (zeta >= 0 ? 1 : -1) / (Math.abs(zeta) + Math.hypot(1, zeta));
        const c = 1 / Math.hypot(1, t), s = c * t;
        rotate(b[p], b[q], c, s);
        rotate(W[p], W[q], c, s);
      }
    }
    if (!rotated) break;
  }
  // W is stored by columns: W[i] is w_i.
  /** @type {[number, number][]} */
  const order = b.map((x, i) => /** @type {[number, number]} */ ([norm(x), i])).sort((u, v) => v[0] - u[0]);
  return { sigma: order.map((o) => o[0]), b: order.map((o) => b[o[1]]), w: order.map((o) => W[o[1]]) };
}

// The vectors of the smaller side of A (m×n): its rows if m <= n (then w_i are
// the left singular vectors u_i and b_i = Aᵀ u_i = σ_i v_i), else its columns
// (then w_i are the right singular vectors v_i and b_i = A v_i = σ_i u_i).
/**
 * @param {Mat} A
 * @returns {SVD}
 */
function svd(A) {
  const m = A.length, n = A[0].length;
  if (m <= n) return { rowsSide: true, ...jacobi(A) };
  return { rowsSide: false, ...jacobi(Array.from({ length: n }, (_, j) => A.map((row) => row[j]))) };
}

/** Singular values of A (m×n), min(m, n) of them, descending.
 * @param {unknown} A
 * @returns {Vec}
 */
export function singularValues(A) {
  return svd(matrix(A, "A")).sigma;
}

// θ̇ = Σ_i h(σ_i) ... with h(σ) = gain(σ)/σ; the thin SVD of J, V the wanted velocity.
/**
 * @param {unknown} J
 * @param {unknown} V
 * @param {(sigma: Vec) => Vec} h
 * @returns {Vec}
 */
function svdSolve(J, V, h) {
  const A = matrix(J, "J");
  const b = vector(V, "V", A.length);
  const d = svd(A);
  return apply(d, b, h(d.sigma), A.length, A[0].length);
}

/** Σ_i hs_i (u_iᵀ b) σ_i v_i: the rates of the gains hs from the SVD d of an m×n J.
 * @param {SVD} d
 * @param {Vec} b
 * @param {Vec} hs
 * @param {number} m
 * @param {number} n
 * @returns {Vec}
 */
function apply(d, b, hs, m, n) {
  const out = new Array(n).fill(0);
  for (let i = 0; i < d.sigma.length; i++) {
    if (hs[i] === 0) continue;
    if (d.rowsSide) {
      // J = Σ σ_i u_i v_iᵀ, u_i = w_i, σ_i v_i = b_i
      let uv = 0;
      for (let r = 0; r < m; r++) uv += d.w[i][r] * b[r];
      for (let j = 0; j < n; j++) out[j] += hs[i] * uv * d.b[i][j];
    } else {
      // v_i = w_i, σ_i u_i = b_i
      let uv = 0;
      for (let r = 0; r < m; r++) uv += d.b[i][r] * b[r];
      for (let j = 0; j < n; j++) out[j] += hs[i] * uv * d.w[i][j];
    }
  }
  return out;
}

/** @type {(rcond: number) => (sigma: Vec) => Vec} */
const pinvGain = (rcond) => (sigma) => sigma.map((s) => (s > rcond * sigma[0] ? 1 / (s * s) : 0));
/** @type {(lam2: number) => (sigma: Vec) => Vec} */
const dlsGain = (lam2) => (sigma) => sigma.map((s) => { const den = s * s + lam2; return den > 0 ? 1 / den : 0; });

/**
 * For the resolved-rate loop, on a J and V it built itself (not checked again): one SVD gives
 * {rate: pinvRates(J, V) or dlsRates(J, V, damping), sigma: singularValues(J)}, the same numbers.
 * @param {Mat} J
 * @param {Vec} V
 * @param {string} method "pinv" or "dls"
 * @param {number} damping
 * @returns {{rate: Vec, sigma: Vec}}
 */
export function ratesAndSigma(J, V, method, damping) {
  const d = svd(J);
  const h = method === "pinv" ? pinvGain(1e-10) : dlsGain(damping * damping);
  return { rate: apply(d, V, h(d.sigma), J.length, J[0].length), sigma: d.sigma };
}

/** Damped least squares θ̇ = (JᵀJ + λ²I)⁻¹JᵀV (m×n J, m-vector V), λ = damping >= 0, as velocity.dls_rates.
 * @param {unknown} J
 * @param {unknown} V
 * @param {unknown} damping
 * @returns {Vec}
 */
export function dlsRates(J, V, damping) {
  const lam = nonNegative(damping, "damping", true);
  return svdSolve(J, V, dlsGain(lam * lam));
}

/** Pseudo-inverse rates J⁺V; singular values below rcond·σ_max count as zero (velocity.pinv_rates).
 * @param {unknown} J
 * @param {unknown} V
 * @param {number} [rcond]
 * @returns {Vec}
 */
export function pinvRates(J, V, rcond = 1e-10) {
  nonNegative(rcond, "rcond", false);
  return svdSolve(J, V, pinvGain(rcond));
}

/**
 * @param {unknown} A
 * @returns {{axes: Vec, directions: Mat, k: number, n: number}}
 */
function ellipsoid(A) {
  const a = matrix(A, "A");
  const k = a.length, n = a[0].length;
  const d = jacobi(a); // the rows of A: w_i are its left singular vectors, |b_i| = σ_i
  const axes = d.sigma.map((s, i) => (i < Math.min(k, n) ? s : 0));
  const directions = Array.from({ length: k }, (_, r) => d.w.map((w) => w[r]));
  return { axes, directions, k, n };
}

/**
 * Velocity ellipsoid of a k×n block A (e.g. the x, y rows of the geometric Jacobian):
 * {axes: σ_i descending (k of them, 0 where k > n), directions: k×k, column i the direction of axis i}.
 * @param {unknown} A
 * @returns {{axes: Vec, directions: Mat}}
 */
export function velocityEllipsoid(A) {
  const { axes, directions } = ellipsoid(A);
  return { axes, directions };
}

/**
 * Force ellipsoid: the same directions, semi-axes 1/σ_i, Infinity where σ_i <= rtol·σ_max
 * (default rtol = max(k, n)·ε), as analysis.force_ellipsoid. A view must clip Infinity.
 * @param {unknown} A
 * @param {number | null} [rtol]
 * @returns {{axes: Vec, directions: Mat}}
 */
export function forceEllipsoid(A, rtol = null) {
  const { axes, directions, k, n } = ellipsoid(A);
  const tol = rtol === null ? Math.max(k, n) * EPS : nonNegative(rtol, "rtol", false);
  const smax = axes[0];
  return { axes: axes.map((s) => (s <= tol * smax ? Infinity : 1 / s)), directions };
}
