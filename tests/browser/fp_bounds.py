"""How far two IEEE-754 computations of the same quantity may differ: bounds from conditioning.

The live views' JavaScript and the library compute the same formulas with
different operation orders (their own SVD, their own sums; numpy's BLAS kernel
depends on the CPU). Each is accurate to a few units of roundoff *backward*:
its result is the exact result for inputs perturbed by a relative amount
``gamma``. How far apart two such results may be is then a matter of the
conditioning of the quantity, not of what one machine happened to give.

Size factor. ``EPS = 2**-52``. Every quantity here is built from the joint
angles by the n matrix exponentials of the product of exponentials, then
inner products of length at most ``m + n`` (a 6×n Jacobian, a thin SVD of an
m×n block: a few sweeps of plane rotations): each step adds a few roundings.
We take ``gamma(m, n) = 32 (m + n) EPS`` as the relative backward error of
either side (about 7e-15 per unit of m + n; Higham, *Accuracy and Stability
of Numerical Algorithms*, 2nd ed., §3.1 and ch. 20: ``gamma_k = k u / (1 - k u)``
for a length-k sum, times a small constant for the SVD's rotations).

Well-conditioned quantities (forward kinematics, Jacobians, singular values,
positions, a tracking error) are compared at ``TOL = 1e-12`` relative to
``max(1, max |reference|)``: their error is a small multiple of ``gamma`` times
their scale (Weyl: ``|δσ_i| <= ||δJ||_2`` for singular values), far below
1e-12 for every m + n <= 12 used here, so 1e-12 holds on any machine.

Ill-conditioned quantities get :func:`solve_bound` (a pseudo-inverse or damped
least-squares solve), :func:`angle_bound` (Euler angles near a representation
singularity) or :func:`analytic_bound` (the analytic Jacobian there).
"""

from __future__ import annotations

import numpy as np

EPS = float(np.finfo(float).eps)  # 2**-52
TOL = 1e-12


def gamma(m: int, n: int) -> float:
    """Relative backward error of one side's computation of an m×n linear-algebra step (module docstring)."""
    return 32.0 * (m + n) * EPS


def scaled_err(js, ref) -> float:
    """max |js - ref| / max(1, max |ref|): absolute for entries up to 1, relative beyond."""
    js = np.asarray(js, dtype=float)
    ref = np.asarray(ref, dtype=float)
    assert js.shape == ref.shape, f"shape {js.shape} from the module, {ref.shape} from the library"
    return float(np.max(np.abs(js - ref)) / max(1.0, float(np.max(np.abs(ref)))))


def solve_bound(J, V, x, damping: float = 0.0, rcond: float = 1e-10, dv: float = 0.0) -> float:
    r"""Bound on ``|x_js - x_lib|_2`` for x = J^# V, J^# the pseudo-inverse (damping 0) or DLS.

    Derivation. DLS, ``x = (JᵀJ + λ²I)⁻¹JᵀV``, is the least-squares solution of
    ``[J; λI] x ≈ [V; 0]``; the pseudo-inverse is the case λ = 0 (minimum-norm
    solution, on the singular values kept above ``rcond σ_max``). Each side
    solves it exactly for ``J + δJ``, ``V + δV`` with ``||δJ|| <= γ ||J||``,
    ``||δV|| <= γ ||V|| + dv`` (``dv``: an absolute error of V's inputs, e.g.
    the gain times the error of a computed position). The first-order
    perturbation bound of a least-squares solution (Wedin 1973; Golub and
    Van Loan, *Matrix Computations*, 4th ed., Thm 5.3.1), for the stacked
    matrix A with singular values ``s_i = sqrt(σ_i² + λ²)`` (and λ on the
    null space of J when J is wide and λ > 0), ``κ = s_max / s_min``, residual
    ``r = [V - Jx; -λx]``:

        ||δx|| <= γ (2κ ||x|| + κ² ||r|| / s_max) + (γ ||V|| + dv) / s_min.

    Each side is within this of the exact solution, so the two differ by at
    most twice it. For a well-conditioned J (κ ~ 1) this is ~1e-14 ||x||; it
    grows like κ near a singularity (like κ² where the residual is not zero).
    """
    J = np.asarray(J, dtype=float)
    V = np.asarray(V, dtype=float)
    x = np.asarray(x, dtype=float)
    m, n = J.shape
    sigma = np.linalg.svd(J, compute_uv=False)
    g = gamma(m, n)
    if damping == 0.0:
        kept = sigma[sigma > rcond * sigma[0]] if sigma[0] > 0 else sigma[:0]
        if kept.size == 0:
            return 0.0 if not np.any(x) else np.inf
        s_max, s_min = float(kept[0]), float(kept[-1])
        r = float(np.linalg.norm(V - J @ x))
    else:
        lam2 = damping * damping
        s = np.sqrt(sigma**2 + lam2)
        s_max = float(s[0])
        s_min = float(damping if n > m else s[-1])
        r = float(np.hypot(np.linalg.norm(V - J @ x), damping * np.linalg.norm(x)))
    kappa = s_max / s_min
    xn, vn = float(np.linalg.norm(x)), float(np.linalg.norm(V))
    return 2.0 * (g * (2.0 * kappa * xn + kappa**2 * r / s_max) + (g * vn + dv) / s_min)


def truncation_is_ambiguous(J, rcond: float = 1e-10, margin: float = 1e-3) -> bool:
    """True if a singular value of J lies within ``margin`` (relative) of the pseudo-inverse's cut-off.

    There the two sides may keep different numbers of singular values: the
    pseudo-inverse is discontinuous, and no tolerance makes sense.
    """
    sigma = np.linalg.svd(np.asarray(J, dtype=float), compute_uv=False)
    cut = rcond * sigma[0]
    return bool(np.any(np.abs(sigma - cut) <= margin * cut))


def angle_bound(h: float, m: int = 3, n: int = 3) -> float:
    """Bound on the difference of ZYX/ZYZ angles from the same rotation R, computed on two sides.

    The first and third angles are ``atan2`` of two entries of R whose norm is
    ``h`` (``cos φ₂`` for ZYX, ``sin φ₂`` for ZYZ); an error δ in those entries
    turns the angle by at most δ / h. R (from the forward kinematics) is
    accurate to ``γ`` in each entry, on each side: ``|Δφ| <= 2 γ / h``. The
    middle angle (``atan2(·, h)``) is well-conditioned. ``TOL`` where h ~ 1.
    """
    return max(TOL, 2.0 * gamma(m, n) / max(h, EPS))


def analytic_bound(h: float, jscale: float, m: int = 6, n: int = 6) -> float:
    """Bound on ``scaled_err`` of an analytic Jacobian ``J_a = diag(B(φ)⁻¹, I) J``-like, computed on two sides.

    ``B(φ)⁻¹`` has entries like ``sin φ₁ / h`` (``h = cos φ₂`` for ZYX, ``sin φ₂``
    for ZYZ, as in :func:`angle_bound`): its derivative in φ₁ or φ₃ is at most
    ~1/h and in φ₂ at most ~1/h². With φ₁, φ₃ accurate to ``2γ/h``, φ₂ and J to
    ``γ`` on each side, an entry of J_a is off by at most about
    ``(1/h² + 2/h² + 1/h) γ |J| <= 4 γ |J| / h²``; twice that for two sides.
    ``jscale = max |J|`` (``scaled_err`` divides by ``max(1, max |J_a|) >= 1``).
    """
    return max(TOL, 8.0 * gamma(m, n) * max(1.0, jscale) / max(h, EPS) ** 2)


class Step:
    """One iteration of ``velocity.resolved_rate`` from a given θ, by the library's own loop."""

    def __init__(self, arm, theta, target, target_velocity, dt, method, damping, gain=2.0):
        import jacobians as jac

        P = np.array([target, target], dtype=float)
        Pdot = np.array([target_velocity, target_velocity], dtype=float)
        out = jac.velocity.resolved_rate(arm, np.asarray(theta, dtype=float), P, dt, method=method, damping=damping,
                                         gain=gain, target_velocities=Pdot)
        self.rate = out.rates[0]
        self.position = out.positions[0]
        self.sigma_min = float(out.sigma_min[0])
        self.theta_next = out.thetas[1]
        d = P.shape[1]
        self.J = jac.geometric_jacobian(arm, np.asarray(theta, dtype=float))[3:3 + d]
        self.V = np.asarray(target_velocity, dtype=float) + gain * (np.asarray(target, dtype=float) - self.position)
        self.gain = gain
        self.method, self.damping, self.dt = method, damping, dt


def compare_step(step: Step, reach: float, js_rate, js_position, js_sigma_min, theta, js_theta_next=None) -> dict:
    """Differences of one resolved-rate step from the same θ, each next to what it may be; ``None`` if ambiguous.

    * position p = fk(θ): well-conditioned, ``TOL`` relative to max(1, |p|);
    * σ_min(J_v): Weyl, ``|δσ| <= ||δJ|| <= γ σ_max`` per side: ``max(TOL, 2 γ σ_max)``;
    * θ̇ = J_v^# (ṗ_d + K (p_d - p)): :func:`solve_bound`, V's inputs off by
      ``dv = K γ reach`` (the gain times the error of the computed position);
      in ``scaled_err`` units: divided by ``max(1, |θ̇|)``;
    * θ_next = θ + θ̇ dt: ``dt`` times the rate bound plus one rounding of each
      entry (``EPS |θ|``), ``TOL`` at least.

    Returns {name: (difference, allowed)}; an empty dict where the pseudo-inverse's cut-off is ambiguous.
    """
    J, V = step.J, step.V
    m, n = J.shape
    if step.method == "pinv" and truncation_is_ambiguous(J):
        return {}
    g = gamma(m, n)
    lam = 0.0 if step.method == "pinv" else step.damping
    rate_abs = solve_bound(J, V, step.rate, lam, dv=step.gain * g * reach)
    rate_scale = max(1.0, float(np.max(np.abs(step.rate))))
    sigma_max = float(np.linalg.svd(J, compute_uv=False)[0])
    out = {
        "positions": (scaled_err(js_position, step.position), TOL),
        "sigma_min": (scaled_err(js_sigma_min, step.sigma_min), max(TOL, 2.0 * g * sigma_max)),
        "rates": (scaled_err(js_rate, step.rate), max(TOL, rate_abs / rate_scale)),
    }
    if js_theta_next is not None:
        theta_scale = max(1.0, float(np.max(np.abs(step.theta_next))))
        allowed = (step.dt * rate_abs + 2.0 * EPS * float(np.max(np.abs(theta)))) / theta_scale
        out["thetas"] = (scaled_err(js_theta_next, step.theta_next), max(TOL, allowed))
    return out


def newton_step_bound(J, V, step, theta, scale):
    """How far the library's and MR's Newton step θ + J⁺V from the same θ may differ (|·|_2).

    J⁺V: the pseudo-inverse solve of a 6×6 system, bound from its condition number
    (:func:`solve_bound`). V = log(T⁻¹T_d) comes from two
    implementations of the matrix logarithm, fed the same T up to γ|T| per entry. For a
    rotation error of angle φ the logarithm's derivative (the inverse of the left Jacobian
    of SO(3), a normal matrix) has norm max(1, φ / (2 sin(φ/2))) <= π/2, and an angle
    computed as arccos((tr R - 1)/2) adds 3γ / sin φ; the translation part
    G⁻¹(ω) p adds as much again times |p| <= scale. So V's inputs make V accurate to
    dv = 2 γ scale (π/2 + 3 / sin φ), and θ + step adds one rounding of each entry.
    """
    g = gamma(6, 6)
    phi = float(np.linalg.norm(V[:3]))
    dv = 2.0 * g * scale * (np.pi / 2 + 3.0 / max(np.sin(phi), EPS))
    return solve_bound(J, V, step, 0.0, rcond=1e-15, dv=dv) + 2 * EPS * float(np.abs(theta).max())
