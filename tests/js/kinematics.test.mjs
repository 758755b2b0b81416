// node --test: the live views' numeric modules (kinematics.js, linalg.js) against values
// written by the library (tools/js_fixtures.py; `make test-js` writes them first and passes
// their path in JS_FIXTURES). No browser: these modules are plain ES modules.
//
// Bounds. Every comparison allows an error derived a priori from the size of the numbers
// and the conditioning of the problem, never from an error seen once. With ε the unit
// roundoff of IEEE-754 double (2^-52) and n the number of joints:
// - Forward kinematics is a product of n + 1 rigid transforms. Each factor is formed with a
//   relative error of a few ε (sin, cos and a handful of products), and the standard bound
//   for a product of k matrices, |fl(A1⋯Ak) − A1⋯Ak| ≤ γ_{3k} |A1|⋯|Ak| (γ_m = mε/(1 − mε)),
//   with rotations of norm 1 and translations adding up, gives
//   |ΔT| ≤ c (n + 1) ε L, L = 1 + Σ |translations| (the arm's size in metres), c = 32
//   (4 operations per entry of a 4×4 product, a factor 2 for each of the two codes, and
//   the trig functions' ulp).
// - A Jacobian column is Ad(T_{i−1}) S_i: ω carried by a rotation, v = R v_i + p × ω. Its
//   error is that of the prefix pose times the column's size: |ΔJ| ≤ c (n + 1) ε L².
// - Singular values (Weyl): |Δσ_k| ≤ ‖ΔJ‖₂ ≤ ‖ΔJ‖_F, plus the backward error of each SVD,
//   c_svd min(m, n) ε ‖J‖₂ with c_svd = 16 for a one-sided Jacobi sweep (and LAPACK's).
// - Least squares x = J⁺V (perturbation theory of Wedin; Higham, Accuracy and Stability,
//   §20.1): with a backward error δ = c_svd min(m, n) ε on J and V,
//   ‖Δx‖ ≤ δ (κ ‖x‖ + κ² ‖r‖ / ‖J‖₂ + κ ‖V‖ / ‖J‖₂), κ = σ_max / σ_min (over the rank
//   kept), r = V − J x. Damped least squares solves the least-squares problem of [J; λI]
//   with right side [V; 0]: the same bound with σ_k² + λ² in place of σ_k² and the
//   augmented residual.
// Each comparison takes the two codes' results from the same inputs (the JavaScript gets
// the library's J for the solvers), so errors do not carry over between steps.

import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";

import {
  bodyJacobian, dlsRates, expSE3, fk, geometricJacobian, jointPositions, makeChain, pinvRates,
  singularValues, spaceJacobian,
} from "../../lib/jacobians/widgets/live/kinematics.js";
import { EPS, matrix, vector } from "../../lib/jacobians/widgets/live/linalg.js";

const path = process.env.JS_FIXTURES;
if (!path) throw new Error("Set JS_FIXTURES to the file written by `python -m tools.js_fixtures` (make test-js does)");
const data = JSON.parse(readFileSync(path, "utf8"));

const C = 32;
const C_SVD = 16;
const flat = (A) => (Array.isArray(A[0]) ? A.flat() : A);
const maxAbsDiff = (A, B) => {
  const a = flat(A), b = flat(B);
  assert.equal(a.length, b.length, "shapes differ");
  let m = 0;
  for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
};
const norm2 = (x) => Math.hypot(...x);
const matVec = (A, x) => A.map((row) => row.reduce((s, a, j) => s + a * x[j], 0));

// L = 1 + Σ |translation| of the factors: the screw axes' v parts times |θ|, and M's position.
function size(c) {
  let L = 1 + norm2([c.M[0][3], c.M[1][3], c.M[2][3]]);
  for (let i = 0; i < c.theta.length; i++) {
    const v = [c.S[3][i], c.S[4][i], c.S[5][i]];
    L += norm2(v) * Math.max(1, Math.abs(c.theta[i]));
  }
  return L;
}

function within(actual, expected, bound, what) {
  const d = maxAbsDiff(actual, expected);
  assert.ok(d <= bound, `${what}: differs by ${d.toExponential(2)}, bound ${bound.toExponential(2)}`);
}

test("forward kinematics, Jacobians and joint positions equal the library's", () => {
  assert.ok(data.cases.length >= 50, "the fixture holds too few chains");
  for (const [k, c] of data.cases.entries()) {
    const n = c.theta.length;
    const chain = makeChain(c.S, c.M, c.jointPoints);
    const L = size(c);
    const tolT = C * (n + 1) * EPS * L;
    const tolJ = C * (n + 1) * EPS * L * L;
    const what = `case ${k} (${c.name}, n=${n})`;
    within(fk(chain, c.theta), c.fk, tolT, `${what} fk`);
    within(jointPositions(chain, c.theta), c.jointPositions, tolT, `${what} joint positions`);
    within(spaceJacobian(chain, c.theta), c.Js, tolJ, `${what} J_s`);
    within(bodyJacobian(chain, c.theta), c.Jb, tolJ, `${what} J_b`);
    within(geometricJacobian(chain, c.theta), c.Jg, tolJ, `${what} J`);
  }
});

test("exp of a twist equals lie.exp_se3, on both branches of the closed form", () => {
  for (const [k, t] of data.twists.entries()) {
    // one factor: |ΔT| ≤ c ε (1 + |v|θ-scale), the twist's linear part bounds the translation
    const L = 1 + norm2(t.xi.slice(3));
    within(expSE3(t.xi), t.T, C * EPS * L, `twist ${k}`);
  }
});

test("singular values, pseudo-inverse and damped rates equal the library's on its own J", () => {
  for (const [k, c] of data.cases.entries()) {
    const J = c.Jg;
    const m = J.length, n = J[0].length, p = Math.min(m, n);
    const sigma = singularValues(J);
    const smax = c.sigma[0];
    // both SVDs run on the same J: only their backward errors separate them (Weyl)
    const delta = C_SVD * p * EPS;
    within(sigma, c.sigma, 2 * delta * smax, `case ${k} singular values`);

    const V = c.V;
    const normV = norm2(V);
    // pinv keeps σ > rcond σ_max (rcond = 1e-10): the condition number over the kept rank
    const kept = c.sigma.filter((s) => s > 1e-10 * smax);
    const x = c.pinv;
    if (kept.length === p && kept[kept.length - 1] > 1e3 * delta * smax) {
      // a clear rank (the smallest kept σ far above the backward error): Wedin's bound holds
      const kappa = smax / kept[kept.length - 1];
      const r = norm2(matVec(J, x).map((y, i) => V[i] - y));
      const bound = 2 * delta * (kappa * norm2(x) + (kappa * kappa * r + kappa * normV) / smax);
      within(pinvRates(J, V), x, bound, `case ${k} pinv rates (κ = ${kappa.toExponential(1)})`);
    }
    const lam = c.damping;
    // [J; λI] has singular values √(σ_k² + λ²), and λ for the n − p directions J does not see
    const sAug = Math.sqrt(smax * smax + lam * lam);
    const kappaL = sAug / (n > p ? lam : Math.sqrt(c.sigma[p - 1] ** 2 + lam * lam));
    const y = c.dls;
    const rAug = Math.hypot(norm2(matVec(J, y).map((z, i) => V[i] - z)), lam * norm2(y));
    const boundL = 2 * delta * (kappaL * norm2(y) + (kappaL * kappaL * rAug + kappaL * normV) / sAug);
    within(dlsRates(J, V, lam), y, boundL, `case ${k} DLS rates (λ = ${lam.toFixed(3)})`);
  }
});

test("bad input gets an error that says what was expected", () => {
  assert.throws(() => vector([1, NaN], "theta", 2), /Expected finite numbers in theta, got NaN at index 1/);
  assert.throws(() => vector([1, 2], "theta", 3), /Expected theta as an array of 3 numbers, got an array of length 2/);
  assert.throws(() => matrix([[1, 2], [3]], "J"), /Expected J with shape m×n \(an array of rows\), got row 1/);
  const S = [[0], [0], [1], [0], [0], [0]];
  const M = [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]];
  assert.throws(() => makeChain([[0], [0], [2], [0], [0], [0]], M), /unit angular part, got \|ω\| = 2/);
  assert.throws(() => makeChain([[0], [0], [0], [0], [0], [0]], M), /Column 0 of S is zero/);
  assert.throws(() => fk(makeChain(S, M), [0, 1]), /Expected theta as an array of 1 numbers/);
  assert.throws(() => fk({ kind: "other" }, [0]), /Expected a chain made by makeChain/);
  assert.throws(() => dlsRates([[1, 0]], [1], -0.1), /Expected damping as a non-negative finite number, got -0.1/);
  assert.throws(() => pinvRates([[1, 0]], [1], 0), /Expected rcond as a positive finite number, got 0/);
});
