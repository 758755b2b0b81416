"""The live views' kinematics (``lib/jacobians/widgets/live/kinematics.js``) give the library's numbers, in Chromium.

For 200 random configurations (seeded) of each teaching arm, the ES module's
forward kinematics, space, body, geometric and analytic Jacobians, B(φ), DLS
and pseudo-inverse steps and ellipse axes are compared with ``jacobians``.

Tolerance: ``|js - lib| <= allowed * max(1, max |lib|)`` over each returned
matrix or vector, i.e. absolute for entries of size up to 1 and relative to
the largest entry beyond. ``allowed`` is ``TOL = 1e-12`` for well-conditioned
quantities (kinematics, Jacobians, B(φ), positions) and, for ill-conditioned
ones, a bound from the conditioning of that very computation, derived in
``fp_bounds.py`` and computed at each configuration: pseudo-inverse and DLS
solves (``solve_bound``: κ of the step), Euler angles and analytic Jacobians
near a representation singularity (``angle_bound``, ``analytic_bound``: 1/cos φ₂),
singular values and ellipse axes (Weyl), ellipse directions (Wedin: 1/gap).
Angles are compared modulo 2π; ellipse directions up to the sign of each column.

The resolved-rate loop is compared one step at a time from the same state
(the library's θ_k for the module's step, the module's θ_k for the library's
step), never as two whole runs: a run through a near-singularity amplifies
the last bits of every step, and another CPU or BLAS kernel rounds them
differently. ``make test-numerics`` runs these tests on other OpenBLAS
kernels and in reverse order.

Needs no built book: it serves the repository on 127.0.0.1 and opens
``tests/browser/live_harness.html``, which imports the module.
"""

from __future__ import annotations

import math
from pathlib import Path
from urllib.parse import urlsplit

import bookcheck
import fp_bounds
import numpy as np
import pytest

import jacobians as jac
from jacobians.plotting import arm_reach

ROOT = Path(__file__).resolve().parents[2]
TOL = 1e-12
N_CONFIGS = 200
LAMBDAS = [0.0, 0.01, 0.1, 1.0]
ARMS = {
    "planar_2r": jac.robots.planar_2r,
    "planar_3r": jac.robots.planar_3r,
    "spatial_5r": jac.robots.spatial_5r,
    "zyz_wrist": jac.robots.zyz_wrist,
    "ur5": jac.robots.ur5,
}
PLANAR = ("planar_2r", "planar_3r")

# Everything the views compute, for every configuration, in one evaluate.
BATCH_JS = """({S, M, Q, thetas, phis, twists, vels, lambdas, planar}) => {
  const K = window.K;
  const chain = K.makeChain(S, M, Q);
  return thetas.map((th, k) => {
    const e = K.evaluate(chain, th);
    const r = {
      T: e.T, Js: e.Js, Jb: e.Jb, Jg: e.Jg, points: e.points, pointsAlone: K.jointPositions(chain, th),
      fk: K.fk(chain, th), space: K.spaceJacobian(chain, th), body: K.bodyJacobian(chain, th),
      geometric: K.geometricJacobian(chain, th), viaFrame: K.jacobian(chain, th, "body"),
      zyx: K.analyticJacobian(chain, th, "zyx"), zyz: K.analyticJacobian(chain, th, "zyz"),
      Bzyx: K.rateToAngularVelocity(phis[k], "zyx"), Bzyz: K.rateToAngularVelocity(phis[k], "zyz"),
      dls: lambdas.map((l) => K.dlsRates(e.Js, twists[k], l)),
      pinv: K.pinvRates(e.Js, twists[k]),
      sv: K.singularValues(e.Js),
    };
    if (planar) {
      const Jv = [e.Jg[3], e.Jg[4]];
      r.vel = K.velocityEllipsoid(Jv);
      r.force = K.forceEllipsoid(Jv);
      r.planarA = K.planarAnalyticJacobian(chain, th);
      r.dlsv = lambdas.map((l) => K.dlsRates(Jv, vels[k], l));
      r.pinvv = K.pinvRates(Jv, vels[k]);
    }
    return r;
  });
}"""

# One bad call per kind of input; each must throw an Error whose message contains the text.
BAD_INPUT = [
    ("K.makeChain(S.slice(0, 5), M)", "Expected S with shape 6×n"),
    ("K.makeChain(S, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])", "Expected M with shape 4×4"),
    ("K.makeChain(S.map((row, r) => r === 2 ? row.map((x) => 2 * x) : row), M)", "unit angular part"),
    ("K.makeChain(S, M, [[0, 0, 0], [0.5, 0.5, 0]])", "Expected jointPoints[1] on the axis"),
    ("K.fk(chain, [0.1])", "Expected theta as an array of 2 numbers"),
    ("K.spaceJacobian(chain, [NaN, 0])", "Expected finite numbers in theta"),
    ("K.bodyJacobian({S, M}, [0, 0])", "makeChain(S, M)"),
    ("K.jacobian(chain, [0, 0], 'world')", "Expected frame"),
    ("K.analyticJacobian(chain, [0, 0], 'exp')", "Unknown representation"),
    ("K.rateToAngularVelocity([0.1, 0.2], 'zyx')", "Expected phi as an array of 3 numbers"),
    ("K.dlsRates([[1, 0], [0, 1]], [1, 2, 3], 0.1)", "Expected V as an array of 2 numbers"),
    ("K.dlsRates([[1, 0], [0, 1]], [1, 2], -1)", "Expected damping as a non-negative"),
    ("K.velocityEllipsoid([1, 2])", "Expected A with shape m×n"),
    ("K.forceEllipsoid([[1, 2], [3]])", "Expected A with shape m×n"),
    ("K.resolvedRate(chain, [0, 1], [[1, 1]], 0.1)", "Expected targetPath with shape N×2 or N×3, N >= 2"),
    ("K.resolvedRateStep(chain, [0, 1], [1, 1], [0, 0], 0.1, 'newton')", 'Expected method "pinv" or "dls"'),
    ("K.planarAnalyticJacobian(K.makeChain(S.map((row, r) => r === 0 ? row.map(() => 1) : r === 2 ? row.map(() => 0)"
     " : row), M), [0, 0])", "Expected a planar arm"),
]


def _err(js, ref) -> float:
    js = np.asarray(js, dtype=float)
    ref = np.asarray(ref, dtype=float)
    assert js.shape == ref.shape, f"shape {js.shape} from the module, {ref.shape} from the library"
    return float(np.max(np.abs(js - ref)) / max(1.0, float(np.max(np.abs(ref)))))


def _angle_err(js, ref) -> float:
    d = np.asarray(js, dtype=float) - np.asarray(ref, dtype=float)
    return float(np.max(np.abs((d + np.pi) % (2 * np.pi) - np.pi)))


def _direction_err(js, ref) -> float:
    js = np.asarray(js, dtype=float)
    ref = np.asarray(ref, dtype=float)
    signs = np.where(np.sum(js * ref, axis=0) < 0, -1.0, 1.0)
    return _err(js * signs, ref)


@pytest.fixture(scope="module")
def kin_page(browser_context):
    with bookcheck.BookServer(ROOT) as server:
        page = browser_context.new_page()
        seen: dict[str, list[str]] = {"console": [], "requests": []}
        page.on("console", lambda m: seen["console"].append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: seen["console"].append(str(e)))
        page.on("request", lambda r: seen["requests"].append(r.url))
        page.goto(server.base + "tests/browser/live_harness.html", wait_until="load")
        page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
        yield page, server.base, seen
        page.close()


def _random_inputs(name: str, n: int):
    rng = np.random.default_rng(sum(map(ord, name)))
    thetas = rng.uniform(-np.pi, np.pi, (N_CONFIGS, n))
    phis = rng.uniform(-np.pi, np.pi, (N_CONFIGS, 3))
    twists = rng.normal(size=(N_CONFIGS, 6))
    vels = rng.normal(size=(N_CONFIGS, 2))
    return thetas, phis, twists, vels


MAX_ERR: dict[str, float] = {}


@pytest.mark.parametrize("name", list(ARMS))
def test_module_matches_library(kin_page, name):
    page = kin_page[0]
    arm = ARMS[name]()
    thetas, phis, twists, vels = _random_inputs(name, arm.dof)
    out = page.evaluate(BATCH_JS, {
        "S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "Q": arm.axis_points().tolist(),
        "thetas": thetas.tolist(), "phis": phis.tolist(),
        "twists": twists.tolist(), "vels": vels.tolist(), "lambdas": LAMBDAS, "planar": name in PLANAR,
    })
    assert len(out) == N_CONFIGS
    T = arm.fk(thetas)
    P = arm.joint_positions(thetas)
    Js = jac.space_jacobian(arm, thetas)
    Jb = jac.body_jacobian(arm, thetas)
    Jg = jac.geometric_jacobian(arm, thetas)
    with np.errstate(invalid="ignore"):  # the library's NaN at a representation singularity
        Ja = {rep: jac.analytic_jacobian(arm, thetas, rep, on_singularity="nan") for rep in ("zyx", "zyz")}
    phi = {rep: jac.pose_coordinates(T, rep)[:, :3] for rep in ("zyx", "zyz")}
    B = {rep: jac.representations.rate_to_angular_velocity(phis, rep) for rep in ("zyx", "zyz")}
    dls = [jac.velocity.dls_rates(Js, twists, lam) for lam in LAMBDAS]
    pinv = jac.velocity.pinv_rates(Js, twists)
    sv = jac.analysis.singular_values(Js)
    errs: dict[str, list[float]] = {}
    over: list[str] = []
    nonsingular = {"zyx": 0, "zyz": 0}
    R = T[:, :3, :3]
    # h: the norm of the two entries of R the first and third angles are atan2 of (cos φ₂ for ZYX, sin φ₂ for ZYZ)
    h = {"zyx": np.hypot(R[:, 0, 0], R[:, 1, 0]), "zyz": np.hypot(R[:, 2, 0], R[:, 2, 1])}

    def note(key: str, value: float, allowed: float = TOL) -> None:
        """Record a difference; it must be within ``allowed`` (TOL, or a bound from fp_bounds stated there)."""
        errs.setdefault(key, []).append(value)
        if not value <= allowed:
            over.append(f"{key} at configuration {k}: {value:.2e} > {allowed:.2e}")

    def solved(key: str, got, J, V, ref, lam: float) -> None:
        """A pseudo-inverse (lam = 0) or DLS solve: fp_bounds.solve_bound, relative to max(1, |ref|)."""
        if lam == 0.0 and fp_bounds.truncation_is_ambiguous(J):
            return
        bound = fp_bounds.solve_bound(J, V, ref, lam) / max(1.0, float(np.abs(ref).max()))
        note(key, _err(got, ref), max(TOL, bound))

    for k, r in enumerate(out):
        for key, ref in (("T", T[k]), ("Js", Js[k]), ("Jb", Jb[k]), ("Jg", Jg[k]), ("fk", T[k]),
                         ("space", Js[k]), ("body", Jb[k]), ("geometric", Jg[k]), ("viaFrame", Jb[k]),
                         ("points", P[k]), ("pointsAlone", P[k]),
                         ("Bzyx", B["zyx"][k]), ("Bzyz", B["zyz"][k])):
            note(key, _err(r[key], ref))
        # singular values: Weyl, |δσ| <= ||δJ|| <= γ σ_max on each side
        note("sv", _err(r["sv"], sv[k]), max(TOL, 2 * fp_bounds.gamma(6, arm.dof) * float(sv[k][0])))
        solved("pinv", r["pinv"], Js[k], twists[k], pinv[k], 0.0)
        for i, lam in enumerate(LAMBDAS):
            solved(f"dls λ={lam}", r["dls"][i], Js[k], twists[k], dls[i][k], lam)
        for rep in ("zyx", "zyz"):
            got = r[rep]
            lib_singular = bool(np.isnan(Ja[rep][k]).any())
            assert got["singular"] is lib_singular, (
                f"{name} θ={thetas[k].tolist()}: {rep} singular flag {got['singular']}, library {lib_singular}")
            # Both sides switch to the lock convention (third angle 0, first a well-conditioned atan2) when
            # h < 1e-12; around that threshold they may take different branches, so no comparison there.
            if h[rep][k] < 1e-13:
                note(f"phi {rep}", _angle_err(got["phi"], phi[rep][k]))
            elif h[rep][k] > 1e-11:
                note(f"phi {rep}", _angle_err(got["phi"], phi[rep][k]), fp_bounds.angle_bound(float(h[rep][k])))
            note(f"margin {rep}", abs(got["margin"] - float(
                jac.representations.representation_singularity_margin(phi[rep][k], rep))))
            if lib_singular:
                assert got["J"] is None
            else:
                nonsingular[rep] += 1
                note(f"Ja {rep}", _err(got["J"], Ja[rep][k]),
                     fp_bounds.analytic_bound(float(h[rep][k]), float(np.abs(Jg[k]).max())))
        if name in PLANAR:
            Jv = Jg[k][3:5]
            axes, dirs = jac.analysis.velocity_ellipsoid(Jv)
            faxes, fdirs = jac.analysis.force_ellipsoid(Jv)
            g2 = fp_bounds.gamma(2, arm.dof)
            note("ellipse axes", _err(r["vel"]["axes"], axes), max(TOL, 2 * g2 * float(axes[0])))
            # a singular vector turns by at most ||δJ|| / gap (Wedin's sin θ theorem); gap = σ₁ - σ₂
            gap = max(float(axes[0] - axes[1]), fp_bounds.EPS)
            note("ellipse directions", _direction_err(r["vel"]["directions"], dirs),
                 max(TOL, 4 * g2 * float(axes[0]) / gap))
            # 1/σ: relative error of σ times 1/σ; the force axes are relative to max(1, 1/σ_min)
            note("force axes", _err(r["force"]["axes"], faxes),
                 max(TOL, 4 * g2 * float(axes[0]) / float(axes[-1]) ** 2 / max(1.0, float(faxes.max()))))
            note("force directions", _direction_err(r["force"]["directions"], fdirs),
                 max(TOL, 4 * g2 * float(axes[0]) / gap))
            for i, lam in enumerate(LAMBDAS):
                solved(f"dls J_v λ={lam}", r["dlsv"][i], Jv, vels[k], jac.velocity.dls_rates(Jv, vels[k], lam), lam)
            solved("pinv J_v", r["pinvv"], Jv, vels[k], jac.velocity.pinv_rates(Jv, vels[k]), 0.0)
            note("Ja planar (x, y, φ)", _err(r["planarA"], Ja["zyx"][k][[3, 4, 0]]))
    # The analytic Jacobian must have been compared, not only flagged: ZYX is
    # never singular for these random draws; ZYZ is singular everywhere for a
    # planar arm (φ₂ = 0), and the flag was checked at each configuration.
    assert nonsingular["zyx"] > 0.95 * N_CONFIGS
    if name not in PLANAR:
        assert nonsingular["zyz"] > 0.95 * N_CONFIGS
    else:
        assert nonsingular["zyz"] == 0
    worst = {key: max(v) for key, v in errs.items()}
    for key, value in worst.items():
        MAX_ERR[f"{name}: {key}"] = value
    print(f"\n{name}: largest difference from the library, per quantity")
    for key, value in worst.items():
        print(f"  {key:22s} {value:.2e}")
    assert not over, f"{name}: differences above what the conditioning allows: {over[:10]}"


def test_representation_singularity_is_a_flag_not_nan(kin_page):
    """The ZYZ wrist at θ₂ = ±π/2, θ₃ = 0 has ZYX pitch ±π/2: the library has no J_a there; the module says so."""
    page = kin_page[0]
    arm = jac.robots.zyz_wrist()
    thetas = [[0.3, math.pi / 2, 0.0], [-1.1, -math.pi / 2, 0.0], [2.0, math.pi / 2, 1e-12]]
    with pytest.raises(jac.RepresentationSingularityError):
        jac.analytic_jacobian(arm, thetas[0], "zyx")
    with np.errstate(invalid="ignore"):
        lib = jac.analytic_jacobian(arm, thetas, "zyx", on_singularity="nan")
    assert np.isnan(lib).all(axis=(1, 2)).all()
    got = page.evaluate("""({S, M, thetas}) => {
      const chain = window.K.makeChain(S, M);
      return thetas.map((th) => window.K.analyticJacobian(chain, th, "zyx"));
    }""", {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "thetas": thetas})
    for th, r in zip(thetas, got, strict=True):
        assert r["singular"] is True and r["J"] is None, (th, r)
        assert r["margin"] < 1e-9 and abs(abs(r["phi"][1]) - math.pi / 2) < 1e-9, (th, r)
        assert all(math.isfinite(x) for x in r["phi"]), (th, r)


def test_singular_arm_gives_no_nan(kin_page):
    """At the stretched-out planar arm (σ_min = 0) every quantity is finite, except the documented ∞ force axis."""
    page = kin_page[0]
    arm = jac.robots.planar_2r()
    got = page.evaluate("""({S, M}) => {
      const K = window.K, chain = K.makeChain(S, M), e = K.evaluate(chain, [0.4, 0]);
      const Jv = [e.Jg[3], e.Jg[4]];
      return {e, Ja: K.analyticJacobian(chain, [0.4, 0]).J, vel: K.velocityEllipsoid(Jv),
              force: K.forceEllipsoid(Jv), dls: K.dlsRates(Jv, [0.3, -0.2], 0.05), pinv: K.pinvRates(Jv, [0.3, -0.2]),
              exp0: K.expSE3([0, 0, 0, 1, 2, 3])};
    }""", {"S": arm.screw_axes.tolist(), "M": arm.home.tolist()})
    flat = np.concatenate([np.ravel(got["e"][k]) for k in ("T", "Js", "Jb", "Jg")]
                          + [np.ravel(got["Ja"]), got["vel"]["axes"], np.ravel(got["vel"]["directions"]),
                             got["dls"], got["pinv"], np.ravel(got["exp0"])])
    assert np.isfinite(flat).all()
    Jv = jac.geometric_jacobian(arm, [0.4, 0.0])[3:5]
    assert _err(got["dls"], jac.velocity.dls_rates(Jv, [0.3, -0.2], 0.05)) <= TOL
    assert _err(got["pinv"], jac.velocity.pinv_rates(Jv, [0.3, -0.2])) <= TOL
    assert got["vel"]["axes"][1] == 0.0 or got["vel"]["axes"][1] < 1e-15
    assert got["force"]["axes"][1] == math.inf and math.isfinite(got["force"]["axes"][0])
    assert _err(got["force"]["axes"][0], jac.analysis.force_ellipsoid(Jv)[0][0]) <= TOL


def test_exp_se3_matches_library_near_and_away_from_zero(kin_page):
    page = kin_page[0]
    rng = np.random.default_rng(13)
    xis = []
    for scale in (0.0, 1e-9, 1e-6, 5e-5, 1e-4, 2e-4, 1e-2, 1.0, 3.0, 6.0):
        for _ in range(20):
            w = rng.normal(size=3)
            w *= scale / np.linalg.norm(w)
            xis.append(np.concatenate([w, rng.normal(size=3)]))
    xis_a = np.array(xis)
    got = page.evaluate("(xis) => xis.map((xi) => window.K.expSE3(xi))", xis_a.tolist())
    ref = jac.lie.exp_se3(xis_a)
    worst = max(_err(g, r) for g, r in zip(got, ref, strict=True))
    print(f"\nexpSE3: largest difference {worst:.2e}")
    assert worst <= TOL


def _paths(arm, name: str):
    """(label, θ0, path, dt, method, damping): a segment, a circle reaching near full stretch, a 3-D one."""
    rng = np.random.default_rng(len(name))
    t = np.linspace(0.0, 1.0, 81)
    dt = float(t[1] - t[0])
    out = []
    for trial in range(3):
        th0 = rng.uniform(-np.pi, np.pi, arm.dof)
        p0 = arm.fk(th0)[:3, 3]
        reach = float(np.linalg.norm(p0[:2]))
        seg = p0[:2] + np.outer(t, rng.normal(size=2) * 0.3)
        ang = 2 * np.pi * t
        centre = p0[:2] * 1.1  # the circle's far side lies beyond the start: near or past full stretch
        circle = centre + (p0[:2] - centre)[None, :] * np.cos(ang)[:, None] \
            + np.array([-(p0[1] - centre[1]), p0[0] - centre[0]])[None, :] * np.sin(ang)[:, None]
        space = p0 + np.outer(t, rng.normal(size=3) * 0.2)
        for method, lam in (("pinv", 0.05), ("dls", 0.05), ("dls", 0.3)):
            out.append((f"segment {trial} {method} {lam}", th0, seg, dt, method, lam))
            out.append((f"circle {trial} r={reach:.2f} {method} {lam}", th0, circle, dt, method, lam))
            out.append((f"3-D {trial} {method} {lam}", th0, space, dt, method, lam))
    return out


# One resolved-rate step of the module from each state θ_k of the library's run: the comparison is of one step
# from the same state, never of two whole runs (a run through a near-singularity amplifies the last bits of
# every step, and the next machine's BLAS kernel rounds them differently). The whole run of the module is
# then tied to its own step function exactly: run.thetas[k + 1] === step(run.thetas[k]).theta.
RR_STEPS_JS = """({S, M, cases}) => {
  const K = window.K, chain = K.makeChain(S, M);
  return cases.map(([th0, path, pdot, dt, method, lam, libThetas]) => {
    const steps = libThetas.map((th, k) => K.resolvedRateStep(chain, th, path[k], pdot[k], dt, method, lam));
    const run = K.resolvedRate(chain, th0, path, dt, method, lam);
    let selfGap = 0;
    for (let k = 0; k + 1 < run.thetas.length; k++) {
      const s = K.resolvedRateStep(chain, run.thetas[k], path[k], pdot[k], dt, method, lam);
      for (let i = 0; i < s.theta.length; i++) selfGap = Math.max(selfGap, Math.abs(s.theta[i] - run.thetas[k + 1][i]));
      for (let i = 0; i < s.rate.length; i++) selfGap = Math.max(selfGap, Math.abs(s.rate[i] - run.rates[k][i]));
    }
    return {steps, selfGap, runLength: run.thetas.length};
  });
}"""


def _forward_differences(P: np.ndarray, dt: float) -> np.ndarray:
    """velocity.resolved_rate's default target velocities (the same IEEE operations as the library and the module)."""
    Pdot = np.zeros_like(P)
    Pdot[:-1] = np.diff(P, axis=0) / dt
    return Pdot


def _check_steps(label: str, arm, reach: float, thetas, path, pdot, dt, method, lam, js_steps, worst, widened,
                 gain: float = 2.0, theta_from_js: bool = False) -> int:
    """Compare step k of the module with the library's step from the same θ_k; return the number of ambiguous steps.

    ``js_steps[k]`` is the module's step from ``thetas[k]`` ({theta, rate, position, sigmaMin}), or, with
    ``theta_from_js``, a module run whose θ_k are ``thetas`` (then θ_{k+1} of the run is compared).
    """
    ambiguous = 0
    for k, th in enumerate(thetas):
        step = fp_bounds.Step(arm, th, path[k], pdot[k], dt, method, lam, gain)
        js = js_steps[k]
        nxt = js["theta"] if not theta_from_js else (thetas[k + 1] if k + 1 < len(thetas) else None)
        diffs = fp_bounds.compare_step(step, reach, js["rate"], js["position"], js["sigmaMin"], th, nxt)
        if not diffs:
            ambiguous += 1
            continue
        for key, (e, allowed) in diffs.items():
            assert e <= allowed, (f"{label}, step {k}: {key} differs by {e:.2e} (relative to max(1, |lib|)); "
                                  f"allowed {allowed:.2e} from the conditioning of this step")
            if allowed > TOL:
                widened[key] = max(widened.get(key, 0.0), allowed)
            worst[key] = max(worst.get(key, 0.0), e)
    return ambiguous


@pytest.mark.parametrize("name", ["planar_2r", "planar_3r", "ur5"])
def test_resolved_rate_matches_library(kin_page, name):
    """The loop of the resolved-rate view, one step at a time from the library's θ_k: θ_(k+1), θ̇, p and σ_min."""
    page = kin_page[0]
    arm = ARMS[name]()
    reach = float(arm_reach(arm))
    cases = _paths(arm, name)
    refs = [jac.velocity.resolved_rate(arm, th0, path, dt, method=method, damping=lam)
            for (_, th0, path, dt, method, lam) in cases]
    pdots = [_forward_differences(np.asarray(c[2], dtype=float), c[3]) for c in cases]
    got = page.evaluate(RR_STEPS_JS, {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "cases": [
        [c[1].tolist(), c[2].tolist(), pd.tolist(), c[3], c[4], c[5], ref.thetas.tolist()]
        for c, pd, ref in zip(cases, pdots, refs, strict=True)]})
    worst: dict[str, float] = {}
    widened: dict[str, float] = {}
    ambiguous = 0
    for (label, _th0, path, dt, method, lam), pdot, ref, r in zip(cases, pdots, refs, got, strict=True):
        assert r["runLength"] == len(path)
        assert r["selfGap"] == 0.0, f"{label}: the module's run is not its own step function repeated ({r['selfGap']})"
        ambiguous += _check_steps(f"{name} {label}", arm, reach, ref.thetas, path, pdot, dt, method, lam,
                                  r["steps"], worst, widened)
    n_steps = sum(len(c[2]) for c in cases)
    assert ambiguous <= 0.01 * n_steps, f"{ambiguous} of {n_steps} steps sat on the pseudo-inverse's cut-off"
    print(f"\nresolved rate {name}, {len(cases)} runs, {n_steps} steps, one step from the library's θ_k; "
          "largest difference: " + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    if widened:
        print("  largest bound above 1e-12 (ill-conditioned steps): "
              + ", ".join(f"{k} {v:.1e}" for k, v in widened.items()))


def test_bad_input_throws_a_clear_error(kin_page):
    page = kin_page[0]
    arm = jac.robots.planar_2r()
    results = page.evaluate("""({S, M, calls}) => {
      const K = window.K, chain = K.makeChain(S, M);
      return calls.map((call) => {
        try { new Function("K", "S", "M", "chain", `return ${call};`)(K, S, M, chain); return {thrown: false}; }
        catch (e) { return {thrown: true, isError: e instanceof Error, message: String(e.message)}; }
      });
    }""", {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "calls": [c for c, _ in BAD_INPUT]})
    for (call, expected), r in zip(BAD_INPUT, results, strict=True):
        assert r["thrown"] and r["isError"], f"{call} did not throw an Error: {r}"
        assert expected in r["message"], f"{call} threw {r['message']!r}, expected it to say {expected!r}"


def test_no_console_error_and_no_foreign_request(kin_page):
    """Runs last in this file (pytest keeps definition order): everything above went through this page."""
    page, base, seen = kin_page
    assert seen["requests"], "the harness page made no request at all"
    host = urlsplit(base).netloc
    foreign = [u for u in seen["requests"] if urlsplit(u).scheme != "data" and urlsplit(u).netloc != host]
    assert not foreign, f"requests to another host: {foreign}"
    assert any(u.endswith("lib/jacobians/widgets/live/kinematics.js") for u in seen["requests"])
    assert not seen["console"], f"console errors: {seen['console']}"


# The resolved-rate view's own functions (lib/jacobians/widgets/live/resolved_rate/view.js): the preset paths, the start
# configuration and the whole run of a preset, against jacobians.widgets.live and velocity.
RR_JS = """({S, M, reach, cases, targets}) => {
  const K = window.K, RR = window.RR, chain = K.makeChain(S, M);
  return {
    paths: RR.PATHS.map((p) => RR.planarPath(p, reach, 160)),
    starts: targets.map((x) => RR.startConfiguration(chain, x)),
    runs: cases.map(([path, method, lam]) => RR.simulate(chain, { path, drawn: null, method, damping: lam,
      nSteps: 160, duration: 4, gain: 2, reach })),
    resampled: RR.resample([[0, 0], [1, 0], [1, 1], [0.4, 1.3]], 17),
  };
}"""


@pytest.mark.parametrize("name", list(PLANAR))
def test_resolved_rate_view_paths_start_and_runs_match_library(kin_page, name):
    from jacobians.widgets.live import PATHS, ResolvedRate, planar_path, resample, start_configuration

    page = kin_page[0]
    arm = ARMS[name]()
    reach = float(arm_reach(arm))
    rng = np.random.default_rng(7)
    # reachable targets: the tool at random configurations
    targets = [arm.fk(th)[:2, 3] for th in rng.uniform(-np.pi, np.pi, (N_CONFIGS, arm.dof))]
    cases = [(p, m, lam) for p in PATHS for m, lam in (("pinv", 0.1), ("dls", 0.02), ("dls", 0.3))]
    got = page.evaluate(RR_JS, {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "reach": reach,
                                "cases": cases, "targets": [t.tolist() for t in targets]})
    worst: dict[str, float] = {}

    def note(key: str, value: float) -> None:
        worst[key] = max(worst.get(key, 0.0), value)

    for p, js in zip(PATHS, got["paths"], strict=True):
        t, x, v = planar_path(p, reach, 160)
        note("path t", _err(js["t"], t))
        note("path x", _err(js["x"], x))
        note("path v", _err(js["v"], v))
    # The start: Newton steps with 1 mm of damping (live.start_configuration, RR.startConfiguration).
    # Each step of the module, from each iterate θ_j of the library's own sequence, is compared with the library's
    # step (a DLS solve: fp_bounds.solve_bound); the two stopping tests (|e| < 1e-12 m) may stop one step apart,
    # so the ends are compared by where the tool is: within 1e-12 m of the target, plus the rounding of fk.
    g = fp_bounds.gamma(2, arm.dof)
    iterates, newton_targets = [], []
    for x0 in targets:
        th = np.array([0.3] + [0.9] * (arm.dof - 1))[:arm.dof]
        for _ in range(200):
            if np.linalg.norm(x0 - arm.fk(th)[:2, 3]) < 1e-12:
                break
            iterates.append(th)
            newton_targets.append(x0)
            th = th + jac.velocity.dls_rates(jac.geometric_jacobian(arm, th)[3:5], x0 - arm.fk(th)[:2, 3], 1e-3)
        lib_start = start_configuration(arm, x0)
        assert np.array_equal(th, lib_start), "the test's copy of the library's Newton loop is not the library's"
    js_newton = page.evaluate("""({S, M, thetas, targets}) => {
      const K = window.K, chain = K.makeChain(S, M);
      return thetas.map((th, j) => {
        const e = K.evaluate(chain, th), err = [targets[j][0] - e.T[0][3], targets[j][1] - e.T[1][3]];
        const d = K.dlsRates([e.Jg[3], e.Jg[4]], err, 1e-3);
        return th.map((t, i) => t + d[i]);
      });
    }""", {"S": arm.screw_axes.tolist(), "M": arm.home.tolist(), "thetas": [t.tolist() for t in iterates],
           "targets": [t.tolist() for t in newton_targets]})
    for th, x0, js_next in zip(iterates, newton_targets, js_newton, strict=True):
        J = jac.geometric_jacobian(arm, th)[3:5]
        e = x0 - arm.fk(th)[:2, 3]
        d = jac.velocity.dls_rates(J, e, 1e-3)
        allowed = max(TOL, (fp_bounds.solve_bound(J, e, d, 1e-3, dv=g * reach) + 2 * fp_bounds.EPS * np.abs(th).max())
                      / max(1.0, np.abs(th + d).max()))
        err = _err(js_next, th + d)
        assert err <= allowed, f"{name}: a Newton step from θ={th.tolist()} differs by {err:.1e}, allowed {allowed:.1e}"
        note("start: one Newton step", err)
    for x0, js in zip(targets, got["starts"], strict=True):
        ref = start_configuration(arm, x0)
        lib_miss = float(np.linalg.norm(arm.fk(ref)[:2, 3] - x0))
        js_miss = float(np.linalg.norm(arm.fk(np.array(js))[:2, 3] - x0))
        assert js_miss <= max(lib_miss, 1e-12) + 2 * g * reach, (x0, js_miss, lib_miss)
    # The runs: from each θ_k of the module's own run, the library's step gives the module's θ_(k+1), θ̇_k, p_k, σ_min.
    widened: dict[str, float] = {}
    ambiguous = 0
    n_steps = 0
    for (p, m, lam), js in zip(cases, got["runs"], strict=True):
        w = ResolvedRate(arm, p, m, lam)
        t, x, v = (np.asarray(a, dtype=float) for a in w.target())
        note("run path", _err(js["xd"], x))
        th0 = start_configuration(arm, x[0])
        # both starts put the tool within 1e-12 m of x[0] (their stopping test), up to the rounding of fk
        start_gap = float(np.abs(arm.fk(np.array(js["theta0"]))[:2, 3] - arm.fk(th0)[:2, 3]).max())
        assert start_gap <= 2e-12 + 2 * g * reach, (p, m, lam, start_gap)
        run = js["run"]
        steps = [{"rate": run["rates"][k], "position": run["positions"][k], "sigmaMin": run["sigmaMin"][k]}
                 for k in range(len(run["thetas"]))]
        js_path = np.asarray(js["xd"], dtype=float)
        js_vel = np.asarray(got["paths"][PATHS.index(p)]["v"], dtype=float)
        ambiguous += _check_steps(f"{name} {p} {m} λ={lam}", arm, reach, np.asarray(run["thetas"], dtype=float),
                                  js_path, js_vel, float(js["t"][1] - js["t"][0]), m, lam, steps,
                                  worst, widened, gain=2.0, theta_from_js=True)
        n_steps += len(run["thetas"])
    assert ambiguous <= 0.01 * n_steps, f"{ambiguous} of {n_steps} steps sat on the pseudo-inverse's cut-off"
    note("resample", _err(got["resampled"], resample([[0, 0], [1, 0], [1, 1], [0.4, 1.3]], 17)))
    if widened:
        print("  largest bound above 1e-12 (ill-conditioned steps): "
              + ", ".join(f"{k} {v:.1e}" for k, v in widened.items()))
    for key, value in worst.items():
        MAX_ERR[f"{name} resolved-rate view: {key}"] = value
    print(f"\n{name}: resolved-rate view, largest difference from the library")
    for key, value in worst.items():
        print(f"  {key:26s} {value:.2e}")
    # every entry of worst was asserted against its own bound above; the well-conditioned ones are at TOL:
    assert all(worst[k] <= TOL for k in worst if k.startswith(("path", "resample", "run path"))), worst
