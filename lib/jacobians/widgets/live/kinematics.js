// @ts-check
// Front-end kinematics of the live views: a plain ES module, no
// dependencies, no build step. It mirrors the course library `jacobians`
// (Modern Robotics conventions: twists (ω, v), angular rows first, screw axes
// as the columns of a 6×n matrix). The library is the reference:
// tests/browser/test_live_kinematics.py compares every function below with it
// at 200 random configurations of each teaching arm.
//
// Matrices are plain arrays of rows (S[r][i] is row r, column i; T[r][c]).
// Vectors are arrays (or typed arrays) of numbers. Results are new plain arrays.
//
// Mapping to the library (same argument order; `chain` is makeChain(S, M)):
//   makeChain(S, M, jointPoints)            SerialChain(screw_axes, home, joint_points=...)
//   expSE3(xi)                              lie.exp_se3(twist_theta)
//   fk(chain, theta)                        chain.fk(theta)
//   spaceJacobian(chain, theta)             space_jacobian(chain, theta)
//   bodyJacobian(chain, theta)              body_jacobian(chain, theta)
//   geometricJacobian(chain, theta)         geometric_jacobian(chain, theta)
//   jacobian(chain, theta, frame, rep, tol) jacobian(chain, theta, frame, rep) (analytic: see below)
//   jointPositions(chain, theta)            chain.joint_positions(theta): (n+1)×3, to draw the arm
//   evaluate(chain, theta)                  fk, the three Jacobians above and the joint positions in one sweep
//   analyticJacobian(chain, theta, rep, tol)
//       analytic_jacobian(chain, theta, rep, on_singularity="nan", tol); returns
//       {J, phi, margin, singular}: at a representation singularity J is null and
//       singular is true (never NaN, never a throw).
//   planarAnalyticJacobian(chain, theta)    analytic_jacobian(chain, theta, "zyx")[[3, 4, 0]]: rows ẋ, ẏ, φ̇ of a planar arm
//   coordinatesFromRotation(R, rep)         representations.coordinates_from_rotation
//   rateToAngularVelocity(phi, rep)         representations.rate_to_angular_velocity (B(φ))
//   representationSingularityMargin(phi, rep)  representations.representation_singularity_margin
//   pinvRates(J, V, rcond)                  velocity.pinv_rates
//   dlsRates(J, V, damping)                 velocity.dls_rates
//   singularValues(A)                       analysis.singular_values
//   velocityEllipsoid(A)                    analysis.velocity_ellipsoid -> {axes, directions}
//   forceEllipsoid(A, rtol)                 analysis.force_ellipsoid    -> {axes, directions}
//   resolvedRate(chain, theta0, path, dt, method, damping, gain, targetVelocities)
//                                           velocity.resolved_rate -> {thetas, rates, positions, errors, sigmaMin}
//   resolvedRateStep(chain, theta, target, targetVelocity, dt, method, damping, gain)
//                                           one iteration of its loop (a view steps once per frame)
// Representations: "zyx" and "zyz" ("exp" is not needed by a view: it throws).
// Bad input (wrong shape, non-finite number, unknown name) throws an Error that
// says what was expected and what came. The SVD is a one-sided Jacobi
// (Hestenes) iteration on the smaller side: small matrices, full accuracy.

import {
  cross, describe, matrix, mulMM, mulMtv, mulMv, nonNegative, norm, skew, transform, vector,
  ratesAndSigma,
} from "./linalg.js";

export { dlsRates, forceEllipsoid, pinvRates, singularValues, velocityEllipsoid } from "./linalg.js";

/** @typedef {import("./linalg.js").Vec} Vec */
/** @typedef {import("./linalg.js").Mat} Mat */
/** @typedef {"zyx" | "zyz"} Representation a set of Euler-angle coordinates of a rotation */
/** @typedef {"pinv" | "dls"} RateMethod the pseudo-inverse or damped least squares */
/**
 * One joint, precomputed once: its screw axis (w, v), [w], [w]², [w]v, [w]²v and where it is drawn at home.
 * @typedef {{w: Vec, v: Vec, K: Mat, K2: Mat, Kv: Vec, K2v: Vec, point: Vec}} Joint
 */
/**
 * A chain made by makeChain: n joints, the home orientation R and position p of {b}.
 * @typedef {Readonly<{kind: "chain", n: number, joints: Joint[], R: Mat, p: Vec}>} Chain
 */
/**
 * One forward sweep: {b}'s pose (R, p), the space Jacobian's columns (ws, vs) and the joint points.
 * @typedef {{n: number, R: Mat, p: Vec, ws: Vec[], vs: Vec[], points: Vec[]}} Sweep
 */
/**
 * The analytic Jacobian with the coordinates it is taken in; J is null at a representation singularity.
 * @typedef {{J: Mat | null, phi: Vec, margin: number, singular: boolean}} AnalyticResult
 */
/** @typedef {{theta: Vec, rate: Vec, position: Vec, sigmaMin: number}} RateStep */
/** @typedef {{thetas: Vec[], rates: Vec[], positions: Vec[], errors: number[], sigmaMin: number[]}} RateRun */
/** @typedef {{T: Mat, Js: Mat, Jb: Mat, Jg: Mat, points: Vec[]}} Evaluation */

const SMALL = 1e-4; // lie._SMALL: below this angle the series expansions are used
const UNIT_TOL = 1e-6; // _validation.UNIT_TOL
/** @type {readonly unknown[]} */
const REPRESENTATIONS = ["zyx", "zyz"];
/** @type {readonly unknown[]} */
const FRAMES = ["space", "body", "geometric", "analytic"];

// ------------------------------------------------------------ validation

/**
 * @param {unknown} rep
 * @returns {Representation}
 */
function representation(rep) {
  if (!REPRESENTATIONS.includes(rep)) {
    throw new Error(`Unknown representation ${JSON.stringify(rep)}: expected one of ${REPRESENTATIONS.join(", ")}`);
  }
  return /** @type {Representation} */ (rep);
}

/**
 * @param {unknown} chain
 * @returns {Chain}
 */
function checkChain(chain) {
  if (!chain || typeof chain !== "object" || /** @type {{kind?: unknown}} */ (chain).kind !== "chain") {
    throw new Error(`Expected a chain made by makeChain(S, M), got ${describe(chain)}`);
  }
  return /** @type {Chain} */ (chain);
}

// ------------------------------------------------------------ chain

/**
 * A chain from its screw axes S (6×n, columns (ω, v)) and home pose M (4×4), checked once.
 * jointPoints (n×3, optional): a point on each joint's axis at home, where the view draws
 * the joint; pass the library's chain.axis_points(). Default as SerialChain's: the point of a
 * revolute axis closest to the origin (ω × v), for a prismatic joint the previous such point.
 * @param {unknown} S
 * @param {unknown} M
 * @param {unknown} [jointPoints]
 * @returns {Chain}
 */
export function makeChain(S, M, jointPoints = null) {
  const s = matrix(S, "S", 6);
  const m = matrix(M, "M", 4, 4);
  const n = s[0].length;
  /** @type {Joint[]} */
  const joints = [];
  const q = jointPoints == null ? null : matrix(jointPoints, "jointPoints", n, 3);
  /** @type {Vec} */
  let prev = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    const w = [s[0][i], s[1][i], s[2][i]];
    const v = [s[3][i], s[4][i], s[5][i]];
    const wn = norm(w);
    const vn = norm(v);
    if (wn > UNIT_TOL) {
      if (Math.abs(wn - 1) > UNIT_TOL) {
        throw new Error(`Expected column ${i} of S (a revolute joint) to have a unit angular part, got |ω| = ${wn}`);
      }
    } else if (vn <= UNIT_TOL) {
      throw new Error(`Column ${i} of S is zero: a screw axis must not be zero`);
    } else if (Math.abs(vn - 1) > UNIT_TOL) {
      throw new Error(`Expected column ${i} of S (a prismatic joint, ω = 0) to have a unit linear part, got |v| = ${vn}`);
    }
    let point = wn > UNIT_TOL ? cross(w, v) : prev;
    if (wn > UNIT_TOL) prev = point;
    if (q !== null) {
      const qi = q[i];
      if (wn > UNIT_TOL) {
        const d = w[0] * qi[0] + w[1] * qi[1] + w[2] * qi[2];
        const off = norm([0, 1, 2].map((k) => qi[k] - w[k] * d - point[k]));
        if (off > 1e-6 * Math.max(1, norm(qi))) {
          throw new Error(`Expected jointPoints[${i}] on the axis of revolute joint ${i}, got a point ${off} away from it`);
        }
      }
      point = qi;
    }
    const K = skew(w);
    const K2 = mulMM(K, K);
    joints.push({ w, v, K, K2, Kv: mulMv(K, v), K2v: mulMv(K2, v), point });
  }
  const bottom = m[3];
  const R = [m[0].slice(0, 3), m[1].slice(0, 3), m[2].slice(0, 3)];
  const RtR = mulMM([[R[0][0], R[1][0], R[2][0]], [R[0][1], R[1][1], R[2][1]], [R[0][2], R[1][2], R[2][2]]], R);
  let off = Math.abs(bottom[0]) + Math.abs(bottom[1]) + Math.abs(bottom[2]) + Math.abs(bottom[3] - 1);
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) off = Math.max(off, Math.abs(RtR[i][j] - (i === j ? 1 : 0)));
  if (off > UNIT_TOL) throw new Error("Expected M as a homogeneous transform (R orthonormal, last row 0 0 0 1)");
  return Object.freeze({ kind: /** @type {const} */ ("chain"), n, joints, R, p: [m[0][3], m[1][3], m[2][3]] });
}

/** e^{[ξ]} of a 6-vector ξ = (ω, v)θ, closed form with the series of lie._coefficients near θ = 0.
 * @param {unknown} xi
 * @returns {Mat}
 */
export function expSE3(xi) {
  const x = vector(xi, "xi", 6);
  const w = [x[0], x[1], x[2]];
  const v = [x[3], x[4], x[5]];
  const t = norm(w);
  const t2 = t * t;
  let A, B, C;
  if (t < SMALL) {
    A = 1 - t2 / 6; B = 0.5 - t2 / 24; C = 1 / 6 - t2 / 120;
  } else {
    const s = Math.sin(t), c = Math.cos(t);
    A = s / t; B = (1 - c) / (t * t); C = (t - s) / (t * t * t);
  }
  const K = skew(w);
  const K2 = mulMM(K, K);
  const R = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  const G = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) {
      const d = i === j ? 1 : 0;
      R[i][j] = d + A * K[i][j] + B * K2[i][j];
      G[i][j] = d + B * K[i][j] + C * K2[i][j];
    }
  }
  return transform(R, mulMv(G, v));
}

// One sweep (as _kernels.prefixes_single / space_columns_single): the pose and
// the space Jacobian's columns (ω_s, v_s), one per joint.
/**
 * @param {unknown} chain
 * @param {unknown} theta
 * @returns {Sweep}
 */
function sweep(chain, theta) {
  const c = checkChain(chain);
  const th = vector(theta, "theta", c.n);
  let R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  let p = [0, 0, 0];
  /** @type {Vec[]} */
  const ws = [];
  /** @type {Vec[]} */
  const vs = [];
  /** @type {Vec[]} */
  const points = [];
  for (let i = 0; i < c.n; i++) {
    const j = c.joints[i];
    const pq = mulMv(R, j.point);
    points.push([pq[0] + p[0], pq[1] + p[1], pq[2] + p[2]]);
    const wi = mulMv(R, j.w);
    ws.push(wi);
    const vr = mulMv(R, j.v);
    const pw = cross(p, wi);
    vs.push([vr[0] + pw[0], vr[1] + pw[1], vr[2] + pw[2]]);
    // e^{[S_i]θ_i} for a unit screw: R_i = I + s K + (1-c) K², p_i = θ v + (1-c) K v + (θ-s) K² v
    const t = th[i], s = Math.sin(t), omc = 1 - Math.cos(t), tms = t - s;
    const Ri = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
    for (let a = 0; a < 3; a++) {
      for (let b = 0; b < 3; b++) Ri[a][b] = (a === b ? 1 : 0) + s * j.K[a][b] + omc * j.K2[a][b];
    }
    const pi = [0, 1, 2].map((k) => t * j.v[k] + omc * j.Kv[k] + tms * j.K2v[k]);
    const Rp = mulMv(R, pi);
    p = [Rp[0] + p[0], Rp[1] + p[1], Rp[2] + p[2]];
    R = mulMM(R, Ri);
  }
  const Rsb = mulMM(R, c.R);
  const Rm = mulMv(R, c.p);
  const psb = [Rm[0] + p[0], Rm[1] + p[1], Rm[2] + p[2]];
  points.push(psb);
  return { n: c.n, R: Rsb, p: psb, ws, vs, points };
}

/** @type {(cols: Vec[]) => Mat} */
const columnsToRows = (cols) => [0, 1, 2, 3, 4, 5].map((r) => cols.map((col) => col[r]));

/** @param {Sweep} sw @returns {Mat} */
function spaceRows(sw) {
  return columnsToRows(sw.ws.map((w, i) => [...w, ...sw.vs[i]]));
}

// lin = v_s - p × ω_s: the velocity of the tool point (the geometric Jacobian's linear rows)
/** @param {Sweep} sw @param {number} i @returns {Vec} */
function linear(sw, i) {
  const pw = cross(sw.p, sw.ws[i]);
  const v = sw.vs[i];
  return [v[0] - pw[0], v[1] - pw[1], v[2] - pw[2]];
}

/** @param {Sweep} sw @returns {Mat} */
function geometricRows(sw) {
  return columnsToRows(sw.ws.map((w, i) => [...w, ...linear(sw, i)]));
}

/** @param {Sweep} sw @returns {Mat} */
function bodyRows(sw) {
  return columnsToRows(sw.ws.map((w, i) => [...mulMtv(sw.R, w), ...mulMtv(sw.R, linear(sw, i))]));
}

/** Forward kinematics T_sb(θ) = e^{[S_1]θ_1} ⋯ e^{[S_n]θ_n} M, 4×4.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Mat}
 */
export function fk(chain, theta) {
  const sw = sweep(chain, theta);
  return transform(sw.R, sw.p);
}

/** Space Jacobian J_s (6×n): V_s = J_s θ̇.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Mat}
 */
export function spaceJacobian(chain, theta) {
  return spaceRows(sweep(chain, theta));
}

/** Body Jacobian J_b (6×n) = [Ad_{T_bs}] J_s.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Mat}
 */
export function bodyJacobian(chain, theta) {
  return bodyRows(sweep(chain, theta));
}

/** Geometric Jacobian (6×n): rows (ω_s, ṗ), ṗ the velocity of {b}'s origin in {s}.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Mat}
 */
export function geometricJacobian(chain, theta) {
  return geometricRows(sweep(chain, theta));
}

/** Where each joint's point is at θ (carried by the joints before it), then {b}'s origin: (n+1)×3.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Vec[]}
 */
export function jointPositions(chain, theta) {
  return sweep(chain, theta).points;
}

/** FK, the space, body and geometric Jacobians and the joint positions in one sweep: {T, Js, Jb, Jg, points}.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Evaluation}
 */
export function evaluate(chain, theta) {
  const sw = sweep(chain, theta);
  return { T: transform(sw.R, sw.p), Js: spaceRows(sw), Jb: bodyRows(sw), Jg: geometricRows(sw), points: sw.points };
}

// ------------------------------------------------------------ representations

/** @param {Mat} R @param {Representation} rep @returns {Vec} */
function coords(R, rep) {
  if (rep === "zyx") {
    const h = Math.hypot(R[0][0], R[1][0]);
    const pitch = Math.atan2(-R[2][0], h);
    const lock = h < 1e-12;
    const yaw = lock ? Math.atan2(-R[0][1], R[1][1]) : Math.atan2(R[1][0], R[0][0]);
    const roll = lock ? 0 : Math.atan2(R[2][1], R[2][2]);
    return [yaw + 0, pitch + 0, roll + 0]; // + 0: no -0 for a view to print
  }
  const sb = Math.hypot(R[2][0], R[2][1]);
  const b = Math.atan2(sb, R[2][2]);
  const lock = sb < 1e-12;
  let a = lock ? Math.atan2(R[1][0], R[0][0]) : Math.atan2(R[1][2], R[0][2]);
  const c = lock ? 0 : Math.atan2(R[2][1], -R[2][0]);
  if (lock && R[2][2] < 0) a = Math.atan2(-R[1][0], -R[0][0]);
  return [a + 0, b + 0, c + 0];
}

/** @param {Vec} phi @param {Representation} rep @returns {number} */
function margin(phi, rep) {
  return rep === "zyx" ? Math.abs(Math.cos(phi[1])) : Math.abs(Math.sin(phi[1]));
}

/** Coordinates φ of a rotation (3×3) in "zyx" (yaw, pitch, roll) or "zyz"; at a lock the last angle is 0.
 * @param {unknown} R
 * @param {string} [rep]
 * @returns {Vec}
 */
export function coordinatesFromRotation(R, rep = "zyx") {
  const r = representation(rep);
  return coords(matrix(R, "R", 3, 3), r);
}

/** B(φ) with ω_s = B(φ) φ̇, 3×3. det B = -cos φ_2 (zyx), -sin φ_2 (zyz).
 * @param {unknown} phi
 * @param {string} [rep]
 * @returns {Mat}
 */
export function rateToAngularVelocity(phi, rep = "zyx") {
  representation(rep);
  const f = vector(phi, "phi", 3);
  const ca = Math.cos(f[0]), sa = Math.sin(f[0]), cb = Math.cos(f[1]), sb = Math.sin(f[1]);
  if (rep === "zyx") return [[0, -sa, ca * cb], [0, ca, sa * cb], [1, 0, -sb]];
  return [[0, -sa, ca * sb], [0, ca, sa * sb], [1, 0, cb]];
}

/** Distance from the representation's singularity: |cos φ_2| (zyx), |sin φ_2| (zyz).
 * @param {unknown} phi
 * @param {string} [rep]
 * @returns {number}
 */
export function representationSingularityMargin(phi, rep = "zyx") {
  const r = representation(rep);
  return margin(vector(phi, "phi", 3), r);
}

/** @param {Vec} phi @param {Representation} rep @returns {Mat} */
function Binv(phi, rep) {
  const ca = Math.cos(phi[0]), sa = Math.sin(phi[0]), cb = Math.cos(phi[1]), sb = Math.sin(phi[1]);
  if (rep === "zyx") return [[ca * sb / cb, sa * sb / cb, 1], [-sa, ca, 0], [ca / cb, sa / cb, 0]];
  return [[-ca * cb / sb, -sa * cb / sb, 1], [-sa, ca, 0], [ca / sb, sa / sb, 0]];
}

/**
 * Analytic Jacobian J_a = diag(B(φ)⁻¹, I) J for x = (φ, p), φ the coordinates of R_sb.
 * Returns {J, phi, margin, singular}; where margin < tol, J is null and singular is true.
 * @param {Chain} chain
 * @param {unknown} theta
 * @param {string} [rep]
 * @param {number} [tol]
 * @returns {AnalyticResult}
 */
export function analyticJacobian(chain, theta, rep = "zyx", tol = 1e-9) {
  const r = representation(rep);
  nonNegative(tol, "tol", false);
  const sw = sweep(chain, theta);
  const phi = coords(sw.R, r);
  const m = margin(phi, r);
  if (!(m >= tol)) return { J: null, phi, margin: m, singular: true };
  const J = geometricRows(sw);
  const Bi = Binv(phi, r);
  for (let i = 0; i < sw.n; i++) {
    const w = mulMv(Bi, [J[0][i], J[1][i], J[2][i]]);
    J[0][i] = w[0]; J[1][i] = w[1]; J[2][i] = w[2];
  }
  return { J, phi, margin: m, singular: false };
}

/**
 * The analytic Jacobian of a planar arm (every joint axis along ±z, in the plane z = 0) in the
 * coordinates x = (x, y, φ) of the tool, φ the angle of its x axis: the rows ẋ, ẏ and φ̇ of
 * analyticJacobian(chain, θ, "zyx") (φ is the ZYX yaw; pitch and roll stay 0, so no singularity).
 * Returns a 3×n matrix. Throws on a chain that is not planar.
 * @param {Chain} chain
 * @param {unknown} theta
 * @returns {Mat}
 */
export function planarAnalyticJacobian(chain, theta) {
  const c = checkChain(chain);
  for (let i = 0; i < c.n; i++) {
    const { w, v } = c.joints[i];
    if (Math.abs(w[0]) > UNIT_TOL || Math.abs(w[1]) > UNIT_TOL || Math.abs(v[2]) > UNIT_TOL) {
      throw new Error(`Expected a planar arm (axes along z, in the plane z = 0), got joint ${i} with ω = (${w}), v = (${v})`);
    }
  }
  const J = /** @type {Mat} */ (analyticJacobian(c, theta, "zyx").J); // planar: pitch 0, never singular
  return [J[3], J[4], J[0]];
}

/** The Jacobian in frame "space", "body", "geometric" (a 6×n matrix) or "analytic" (as analyticJacobian).
 * @param {Chain} chain
 * @param {unknown} theta
 * @param {string} frame
 * @param {string} [rep]
 * @param {number} [tol]
 * @returns {Mat | AnalyticResult}
 */
export function jacobian(chain, theta, frame, rep = "zyx", tol = 1e-9) {
  if (!FRAMES.includes(frame)) {
    throw new Error(`Expected frame ${FRAMES.map((f) => `"${f}"`).join(", ")}, got ${JSON.stringify(frame)}`);
  }
  if (frame === "analytic") return analyticJacobian(chain, theta, rep, tol);
  const sw = sweep(chain, theta);
  return frame === "space" ? spaceRows(sw) : frame === "body" ? bodyRows(sw) : geometricRows(sw);
}

// ------------------------------------------------------------ resolved-rate motion

/** @type {readonly unknown[]} */
const METHODS = ["pinv", "dls"];

/**
 * @param {unknown} method
 * @param {unknown} damping
 * @param {unknown} gain
 * @returns {RateMethod}
 */
function rateOptions(method, damping, gain) {
  if (!METHODS.includes(method)) throw new Error(`Expected method "pinv" or "dls", got ${JSON.stringify(method)}`);
  nonNegative(damping, "damping", true);
  nonNegative(gain, "gain", true);
  return /** @type {RateMethod} */ (method);
}

/**
 * @param {Chain} chain
 * @param {Vec} theta
 * @param {Vec} target
 * @param {Vec} targetVelocity
 * @param {number} dt
 * @param {RateMethod} method
 * @param {number} damping
 * @param {number} gain
 * @returns {RateStep}
 */
function step(chain, theta, target, targetVelocity, dt, method, damping, gain) {
  const d = target.length;
  const sw = sweep(chain, theta);
  const J = geometricRows(sw).slice(3, 3 + d);
  const p = sw.p.slice(0, d);
  const v = target.map((x, i) => targetVelocity[i] + gain * (x - p[i]));
  const { rate, sigma: sv } = ratesAndSigma(J, v, method, damping); // = pinvRates/dlsRates and singularValues
  const sigmaMin = sv.length === d ? sv[d - 1] : 0;
  return { theta: theta.map((t, i) => t + rate[i] * dt), rate, position: p, sigmaMin };
}

/**
 * One step of resolved-rate motion of {b}'s origin (as one iteration of velocity.resolved_rate):
 * θ̇ = J_v^# (ṗ_d + K (p_d - p)), θ_next = θ + θ̇ dt, J_v the x, y (d = 2) or x, y, z (d = 3)
 * rows of the geometric Jacobian, # the pseudo-inverse ("pinv") or DLS ("dls", λ = damping).
 * Returns {theta: θ_next, rate, position: p at θ, sigmaMin: σ_min of J_v (0 if n < d)}.
 * @param {Chain} chain
 * @param {unknown} theta
 * @param {unknown} target
 * @param {unknown} targetVelocity
 * @param {number} dt
 * @param {string} [method]
 * @param {number} [damping]
 * @param {number} [gain]
 * @returns {RateStep}
 */
export function resolvedRateStep(chain, theta, target, targetVelocity, dt, method = "pinv", damping = 0.05, gain = 2.0) {
  const c = checkChain(chain);
  const th = vector(theta, "theta", c.n);
  const pd = vector(target, "target");
  if (pd.length !== 2 && pd.length !== 3) throw new Error(`Expected target as (x, y) or (x, y, z), got ${pd.length} numbers`);
  const vd = vector(targetVelocity, "targetVelocity", pd.length);
  nonNegative(dt, "dt", false);
  return step(c, th, pd, vd, dt, rateOptions(method, damping, gain), damping, gain);
}

/**
 * velocity.resolved_rate: follow targetPath (N×2 or N×3, N >= 2) from theta0 with time step dt.
 * targetVelocities (N×d) default: forward differences of the path, zero at the end.
 * Returns {thetas, rates, positions, errors, sigmaMin}, one entry per step.
 * @param {Chain} chain
 * @param {unknown} theta0
 * @param {unknown} targetPath
 * @param {number} dt
 * @param {string} [method]
 * @param {number} [damping]
 * @param {number} [gain]
 * @param {unknown} [targetVelocities]
 * @returns {RateRun}
 */
export function resolvedRate(chain, theta0, targetPath, dt, method = "pinv", damping = 0.05, gain = 2.0,
  targetVelocities = null) {
  const c = checkChain(chain);
  let theta = vector(theta0, "theta0", c.n);
  const P = matrix(targetPath, "targetPath");
  const N = P.length, d = P[0].length;
  if (N < 2 || (d !== 2 && d !== 3)) {
    throw new Error(`Expected targetPath with shape N×2 or N×3, N >= 2, got ${N}×${d}`);
  }
  nonNegative(dt, "dt", false);
  const how = rateOptions(method, damping, gain);
  const Pdot = targetVelocities == null
    ? P.map((row, k) => (k + 1 < N ? row.map((x, i) => (P[k + 1][i] - x) / dt) : row.map(() => 0)))
    : matrix(targetVelocities, "targetVelocities", N, d);
  /** @type {RateRun} */
  const out = { thetas: [], rates: [], positions: [], errors: [], sigmaMin: [] };
  for (let k = 0; k < N; k++) {
    const s = step(c, theta, P[k], Pdot[k], dt, how, damping, gain);
    out.thetas.push(theta); out.rates.push(s.rate); out.positions.push(s.position); out.sigmaMin.push(s.sigmaMin);
    out.errors.push(norm(P[k].map((x, i) => x - s.position[i])));
    theta = s.theta;
  }
  return out;
}
