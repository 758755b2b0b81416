// Small dense linear algebra for the live views (issue #13): input checks, 3-vectors
// and 3×3 matrices, and a one-sided Jacobi (Hestenes) SVD with the solvers and ellipsoids
// built on it. Split out of kinematics.js, which re-exports the public functions; the
// library counterparts are listed there. Matrices are arrays of rows.

export const EPS = 2.220446049250313e-16;

// ------------------------------------------------------------ validation

export function describe(x) {
  if (Array.isArray(x)) {
    if (x.length && Array.isArray(x[0])) return `an array of ${x.length} rows of ${x[0].length}`;
    return `an array of length ${x.length}`;
  }
  if (ArrayBuffer.isView(x)) return `a typed array of length ${x.length}`;
  if (x === null) return "null";
  return `${typeof x} ${String(x).slice(0, 60)}`;
}

export function vector(x, name, len) {
  const ok = Array.isArray(x) || (ArrayBuffer.isView(x) && !(x instanceof DataView));
  if (!ok || (len !== undefined && x.length !== len) || x.length === 0) {
    const want = len === undefined ? "a non-empty array of numbers" : `an array of ${len} numbers`;
    throw new Error(`Expected ${name} as ${want}, got ${describe(x)}`);
  }
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

export function matrix(A, name, rows, cols) {
  const shape = `${rows ?? "m"}×${cols ?? "n"}`;
  if (!Array.isArray(A) || A.length === 0 || (rows !== undefined && A.length !== rows)) {
    throw new Error(`Expected ${name} with shape ${shape} (an array of rows), got ${describe(A)}`);
  }
  const c = cols ?? (A[0] && A[0].length);
  const out = new Array(A.length);
  for (let r = 0; r < A.length; r++) {
    const row = A[r];
    const isRow = Array.isArray(row) || (ArrayBuffer.isView(row) && !(row instanceof DataView));
    if (!isRow || row.length !== c || c === 0) {
      throw new Error(`Expected ${name} with shape ${shape} (an array of rows), got row ${r} as ${describe(row)}`);
    }
    out[r] = vector(row, `${name}[${r}]`, c);
  }
  return out;
}

export function nonNegative(x, name, allowZero) {
  if (typeof x !== "number" || !Number.isFinite(x) || x < 0 || (!allowZero && x === 0)) {
    throw new Error(`Expected ${name} as a ${allowZero ? "non-negative" : "positive"} finite number, got ${String(x)}`);
  }
  return x;
}

// ------------------------------------------------------------ 3-vectors, 3×3

export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const mulMv = (R, x) => [
  R[0][0] * x[0] + R[0][1] * x[1] + R[0][2] * x[2],
  R[1][0] * x[0] + R[1][1] * x[1] + R[1][2] * x[2],
  R[2][0] * x[0] + R[2][1] * x[1] + R[2][2] * x[2],
];
export const mulMtv = (R, x) => [
  R[0][0] * x[0] + R[1][0] * x[1] + R[2][0] * x[2],
  R[0][1] * x[0] + R[1][1] * x[1] + R[2][1] * x[2],
  R[0][2] * x[0] + R[1][2] * x[1] + R[2][2] * x[2],
];
export function mulMM(A, B) {
  const C = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) C[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  }
  return C;
}
export const skew = (w) => [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]];
export const norm = (x) => Math.hypot(...x);

export function transform(R, p) {
  return [[R[0][0], R[0][1], R[0][2], p[0]], [R[1][0], R[1][1], R[1][2], p[1]],
    [R[2][0], R[2][1], R[2][2], p[2]], [0, 0, 0, 1]];
}

// ------------------------------------------------------------ SVD (one-sided Jacobi)

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
function jacobi(xs) {
  const k = xs.length;
  const b = xs.map((x) => x.slice());
  const W = Array.from({ length: k }, (_, i) => Array.from({ length: k }, (_, j) => (i === j ? 1 : 0)));
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
  const order = b.map((x, i) => [norm(x), i]).sort((u, v) => v[0] - u[0]);
  return { sigma: order.map((o) => o[0]), b: order.map((o) => b[o[1]]), w: order.map((o) => W[o[1]]) };
}

// The vectors of the smaller side of A (m×n): its rows if m <= n (then w_i are
// the left singular vectors u_i and b_i = Aᵀ u_i = σ_i v_i), else its columns
// (then w_i are the right singular vectors v_i and b_i = A v_i = σ_i u_i).
function svd(A) {
  const m = A.length, n = A[0].length;
  if (m <= n) return { rowsSide: true, ...jacobi(A) };
  return { rowsSide: false, ...jacobi(Array.from({ length: n }, (_, j) => A.map((row) => row[j]))) };
}

/** Singular values of A (m×n), min(m, n) of them, descending. */
export function singularValues(A) {
  return svd(matrix(A, "A")).sigma;
}

// θ̇ = Σ_i h(σ_i) ... with h(σ) = gain(σ)/σ; the thin SVD of J, V the wanted velocity.
function svdSolve(J, V, h) {
  const A = matrix(J, "J");
  const b = vector(V, "V", A.length);
  const d = svd(A);
  return apply(d, b, h(d.sigma), A.length, A[0].length);
}

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

const pinvGain = (rcond) => (sigma) => sigma.map((s) => (s > rcond * sigma[0] ? 1 / (s * s) : 0));
const dlsGain = (lam2) => (sigma) => sigma.map((s) => { const den = s * s + lam2; return den > 0 ? 1 / den : 0; });

/**
 * For the resolved-rate loop, on a J and V it built itself (not checked again): one SVD gives
 * {rate: pinvRates(J, V) or dlsRates(J, V, damping), sigma: singularValues(J)}, the same numbers.
 */
export function ratesAndSigma(J, V, method, damping) {
  const d = svd(J);
  const h = method === "pinv" ? pinvGain(1e-10) : dlsGain(damping * damping);
  return { rate: apply(d, V, h(d.sigma), J.length, J[0].length), sigma: d.sigma };
}

/** Damped least squares θ̇ = (JᵀJ + λ²I)⁻¹JᵀV (m×n J, m-vector V), λ = damping >= 0, as velocity.dls_rates. */
export function dlsRates(J, V, damping) {
  const lam = nonNegative(damping, "damping", true);
  return svdSolve(J, V, dlsGain(lam * lam));
}

/** Pseudo-inverse rates J⁺V; singular values below rcond·σ_max count as zero (velocity.pinv_rates). */
export function pinvRates(J, V, rcond = 1e-10) {
  nonNegative(rcond, "rcond", false);
  return svdSolve(J, V, pinvGain(rcond));
}

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
 */
export function velocityEllipsoid(A) {
  const { axes, directions } = ellipsoid(A);
  return { axes, directions };
}

/**
 * Force ellipsoid: the same directions, semi-axes 1/σ_i, Infinity where σ_i <= rtol·σ_max
 * (default rtol = max(k, n)·ε), as analysis.force_ellipsoid. A view must clip Infinity.
 */
export function forceEllipsoid(A, rtol = null) {
  const { axes, directions, k, n } = ellipsoid(A);
  const tol = rtol === null ? Math.max(k, n) * EPS : nonNegative(rtol, "rtol", false);
  const smax = axes[0];
  return { axes: axes.map((s) => (s <= tol * smax ? Infinity : 1 / s)), directions };
}
