"""Random chains and transforms for tests, exercises and property checks.

>>> import numpy as np
>>> chain = random_chain(np.random.default_rng(0), dof=4)
>>> chain.dof
4
"""

from __future__ import annotations

from collections.abc import Callable
from math import comb, factorial
from typing import Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import positive_int
from .chain import SerialChain
from .lie import _exp_se3, _exp_so3

__all__ = ["random_rotation", "random_transform", "random_chain", "random_theta",
           "EPS", "TOL", "close", "within", "fd_tol", "fd2_tol", "root_tol", "ode_tol",
           "pose_tol", "chain_curvature", "clik_step_tol", "euler_step_tol", "taylor_tol",
           "tracking_tol", "resolved_rate_tol"]

#: What the ``rng`` arguments accept: a generator, a seed, or None for a fresh one.
RngLike: TypeAlias = "np.random.Generator | int | None"
#: A batch shape: ``()`` for one sample, an int or a tuple of ints.
Size: TypeAlias = "int | tuple[int, ...]"


def _rng(rng: RngLike) -> np.random.Generator:
    if isinstance(rng, np.random.Generator):
        return rng
    return np.random.default_rng(rng)


def random_rotation(rng: RngLike = None, size: Size = ()) -> NDArray[np.float64]:
    """Rotations from exponential coordinates drawn in a ball of radius pi."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    w = rng.normal(size=size + (3,))
    w /= np.linalg.norm(w, axis=-1, keepdims=True)
    return _exp_so3(w * rng.uniform(0, np.pi, size=size + (1,)))


def random_transform(rng: RngLike = None, size: Size = (), scale: float = 1.0) -> NDArray[np.float64]:
    """Random rigid transforms with translations of about ``scale``."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    return _exp_se3(np.concatenate([rng.normal(size=size + (3,)), scale * rng.normal(size=size + (3,))], -1))


def random_chain(rng: RngLike = None, dof: int | None = None, prismatic_probability: float = 0.25,
                 pitch_probability: float = 0.1) -> SerialChain:
    """A random chain: revolute joints (some with a pitch), prismatic joints, a random home pose."""
    rng = _rng(rng)
    n = int(rng.integers(1, 8)) if dof is None else positive_int(dof, "dof")
    if n < 1:
        raise ValueError(f"Expected dof >= 1, got {n}")
    S = np.zeros((6, n))
    for i in range(n):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        if rng.uniform() < prismatic_probability:
            S[3:, i] = axis
        else:
            q = rng.normal(size=3)
            S[:3, i] = axis
            S[3:, i] = -np.cross(axis, q)
            if rng.uniform() < pitch_probability:
                S[3:, i] += rng.normal() * axis
    return SerialChain(S, random_transform(rng))


def random_theta(chain: SerialChain, rng: RngLike = None, size: Size = ()) -> NDArray[np.float64]:
    """Joint values in [-pi, pi] (revolute) or [-1, 1] (prismatic), shape size + (n,)."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    scale: NDArray[np.float64] = np.array([np.pi if t == "R" else 1.0 for t in chain.joint_types])
    return rng.uniform(-1, 1, size=size + (chain.dof,)) * scale


# ---------------------------------------------------------------- tolerances derived from the computation

#: Unit roundoff of IEEE-754 double precision (2**-52, the gap from 1 to the next double).
EPS: float = float(np.finfo(float).eps)
#: Relative tolerance of a well-conditioned quantity computed two ways (see :func:`close`).
TOL: float = 1e-12


def close(a: ArrayLike, b: ArrayLike, tol: float = TOL, scale: float | None = None) -> bool:
    """True if ``max |a - b| <= tol * max(1, scale)``, ``scale = max(|a|, |b|)`` unless given.

    For two computations of the same well-conditioned quantity by exact
    algebra (a product of exponentials against its closed form, an adjoint
    against a matrix product, a symbolic formula evaluated in floats). Each
    side is the exact value for inputs perturbed by a relative amount of a
    few hundred units of roundoff at most: the chapters' quantities come from
    at most ~10 matrix exponentials and products of 6×6 (or smaller)
    matrices, and each step adds a few roundings relative to the largest
    entry (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
    §3.1: a length-k inner product is off by ``k EPS / (1 - k EPS)`` of
    ``|a||b|``). With a condition number of order 1, the two sides differ by
    a few hundred EPS (~1e-13) of their scale. ``TOL = 1e-12`` holds with a
    margin on any IEEE-754 machine, BLAS kernel and summation order, and is
    still ten orders of magnitude below any error of a formula.

    Entries up to 1 are compared absolutely, larger ones relative to the
    largest (``max(1, scale)``). Pass ``scale`` when the compared values are
    small differences of large terms (a residual ``w · v`` of vectors of size
    10 has the scale 10, not its own size); a zero ``b`` is compared this way
    too.

    >>> close(np.sin(np.pi / 6), 0.5)
    True
    >>> close([1.0, 2.0], [1.0, 2.0 + 1e-9])
    False
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    diff = float(np.max(np.abs(a - b), initial=0.0))
    if scale is None:
        scale = max(float(np.max(np.abs(a), initial=0.0)), float(np.max(np.abs(b), initial=0.0)))
    return bool(diff <= tol * max(1.0, float(scale)))


def within(a: ArrayLike, b: ArrayLike, bound: float) -> bool:
    """True if ``max |a - b| <= bound``: for a bound derived elsewhere (e.g. :func:`fd_tol`)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return bool(float(np.max(np.abs(a - b), initial=0.0)) <= float(bound))


def fd_tol(f: Callable[[NDArray[np.float64]], ArrayLike], x: ArrayLike, h: float = 1e-6,
           scale: float = 1.0, ops: float = 512.0) -> float:
    """Bound on ``max |numerical_jacobian(f, x, h) - Df(x)|``: truncation plus rounding.

    ``numerical_jacobian`` takes central differences ``(f(x + h e_i) - f(x - h e_i)) / 2h``.
    Its error in each entry is at most (Taylor's theorem with remainder; the
    second-order terms cancel)

    * truncation ``h² / 6 · M3``, ``M3 = max |∂³f / ∂x_i³|`` near x;
    * rounding of f: each value is off by at most ``δ = ops · EPS · F``,
      ``F = max(scale, max |f|)`` on the stencil, so their difference over 2h
      by ``δ / h``. Rounding is relative to the terms f is computed from:
      ``scale`` (default 1, as in :func:`close`) must be their size when f is
      a small difference of large terms (``q - R q`` near R = I is tiny, its
      rounding is that of ``|q|``);
    * rounding of the step: ``x ± h`` is stored to within ``EPS |x ± h| / 2``, so
      the actual step is ``2h (1 + e)``, ``|e| <= EPS (|x| + h) / 2h``: an error
      ``|e| · M1``, ``M1 = max |∂f/∂x_i|``; and the final subtraction and
      division, ``2 EPS M1``;
    * the closed form it is compared with, computed by exact algebra, is
      accurate to ``ops · EPS · M1`` (as in :func:`close`).

    ``ops = 512`` (relative accuracy of f about 1.1e-13 of its largest entry)
    covers a product of up to ~10 matrix exponentials, their inverses and
    4×4 or 6×6 products, as in the chapters (the model of
    ``tests/browser/fp_bounds.py``: 32 roundings per unit of size, size 16).

    The constants come from the quantity, not from an observed error: F from
    the stencil's values, M1 from the difference quotient itself, M3 from
    the third central difference with the wider step ``H = 0.05``,
    ``(f(x+2H) - 2f(x+H) + 2f(x-H) - f(x-2H)) / 2H³``, taken twice (its own
    error is ``H²/4 · M5``, under 1 % of M3 for the chapters' motions, whose
    rates are a few rad per unit of x; the third derivative varies by
    ``h M4`` within the stencil). f must be smooth on ``[x - 2H, x + 2H]``:
    across a jump (an angle wrapped at ±π) M3 only becomes larger, so the
    bound stays a bound.

    >>> from jacobians.jacobian import numerical_jacobian
    >>> x = np.array([0.3])
    >>> bound = fd_tol(np.sin, x, ops=4)     # sin: a few roundings
    >>> round(bound / 1e-10)                 # 4 EPS / h: 8.9e-10, the truncation 1.5e-14
    9
    >>> within(numerical_jacobian(np.sin, x), np.cos(x), bound)
    True
    """
    x = np.asarray(x, dtype=float)
    h = float(h)
    H = 0.05

    def val(y: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(f(y), dtype=float)

    F = max(float(scale), float(np.max(np.abs(val(x)), initial=0.0)))
    M1 = M3 = 0.0
    for i in range(x.shape[-1]):
        e = np.zeros_like(x)
        e[..., i] = 1.0
        lo, hi = val(x - h * e), val(x + h * e)
        F = max(F, float(np.max(np.abs(lo), initial=0.0)), float(np.max(np.abs(hi), initial=0.0)))
        M1 = max(M1, float(np.max(np.abs(hi - lo), initial=0.0)) / (2 * h))
        d3 = (val(x + 2 * H * e) - 2 * val(x + H * e) + 2 * val(x - H * e) - val(x - 2 * H * e)) / (2 * H**3)
        M3 = max(M3, 2.0 * float(np.max(np.abs(d3), initial=0.0)))
    xmax = float(np.max(np.abs(x), initial=0.0))
    truncation = h * h / 6.0 * M3
    rounding = ops * EPS * F / h + EPS * (xmax + h) / (2 * h) * M1 + (2 + ops) * EPS * M1
    return truncation + rounding


def fd2_tol(f: Callable[[float], ArrayLike], t: float, h: float = 1e-4, scale: float = 1.0,
            ops: float = 512.0) -> float:
    """Bound on ``max |(f(t+h) - 2 f(t) + f(t-h)) / h² - f″(t)|``: truncation plus rounding.

    Taylor's theorem (the odd terms cancel): the truncation is at most
    ``h² / 12 · M4``, ``M4 = max |f⁗|`` near t. Each value of f is off by at
    most ``δ = ops · EPS · F`` (``F = max(scale, max |f|)`` on the stencil, as
    in :func:`fd_tol`), so the combination by ``4 δ / h²``; the closed form
    it is compared with is accurate to ``ops · EPS · M2``. M4 comes from the
    fourth central difference with the wider step ``H = 0.05``, taken twice
    (as M3 in :func:`fd_tol`), M2 from the second difference itself.

    >>> bound = fd2_tol(np.sin, 0.3, ops=4)
    >>> within((np.sin(0.3 + 1e-4) - 2 * np.sin(0.3) + np.sin(0.3 - 1e-4)) / 1e-8, -np.sin(0.3), bound)
    True
    >>> round(bound / 1e-7, 1)                # 4 · 4 EPS / h²: the rounding dominates
    3.6
    """
    t, h = float(t), float(h)
    H = 0.05

    def val(s: float) -> NDArray[np.float64]:
        return np.asarray(f(s), dtype=float)

    stencil = [val(t - h), val(t), val(t + h)]
    F = max([float(scale)] + [float(np.max(np.abs(v), initial=0.0)) for v in stencil])
    M2 = float(np.max(np.abs(stencil[2] - 2 * stencil[1] + stencil[0]), initial=0.0)) / h**2
    d4 = (val(t + 2 * H) - 4 * val(t + H) + 6 * val(t) - 4 * val(t - H) + val(t - 2 * H)) / H**4
    M4 = 2.0 * float(np.max(np.abs(d4), initial=0.0))
    return h * h / 12.0 * M4 + 4.0 * ops * EPS * F / (h * h) + (2 + ops) * EPS * M2


def root_tol(J: ArrayLike, residual: float, scale: float = 1.0, ops: float = 512.0) -> float:
    """Bound on ``|x - x*|`` for an iterate x of a root finder stopped at ``|F(x)| <= residual``, F(x*) = 0.

    ``J = DF(x*)`` (m×n, m >= n, full column rank, smallest singular value
    σ). Taylor: ``F(x) = J (x - x*) + r``, ``|r| <= M2 |x - x*|² / 2``, so
    ``σ |x - x*| <= |F(x)| + M2 |x - x*|² / 2``. Where Newton's method has
    converged, the second-order term is below half the first
    (``M2 |x - x*| <= σ``: quadratic convergence holds there), hence
    ``|x - x*| <= 2 |F(x)| / σ``: the stopping residual times the condition
    of the Jacobian at the solution, not an observed error. The residual
    was computed, so the true one is larger by up to ``δ = ops · EPS · scale``
    (the rounding of F's terms, as in :func:`fd_tol`); the closed form x* it
    is compared with is off by ``δ / σ`` (the same conditioning). In all,
    ``(2 residual + 3 δ) / σ``. A singular J gives ``inf``: there is no bound.

    >>> round(root_tol(np.eye(2), 1e-9) / 1e-9, 3)
    2.0
    >>> root_tol([[1.0, 0.0], [0.0, 0.0]], 1e-9)
    inf
    """
    sigma = float(np.linalg.svd(np.asarray(J, dtype=float), compute_uv=False)[-1])
    delta = ops * EPS * float(scale)
    return float("inf") if sigma <= 0.0 else (2.0 * float(residual) + 3.0 * delta) / sigma


def ode_tol(sol: Any, rtol: float, atol: float, growth: float = 1.0) -> float:
    """Bound on ``max |y_computed(t) - y(t)|`` for a ``scipy.integrate.solve_ivp`` result ``sol``.

    The solver keeps each step's local error estimate under
    ``atol + rtol |y|`` in the root mean square over the n components, so
    each component's under ``sqrt(n) (atol + rtol max |y|)``; the dense
    output (``sol.sol``) interpolates to the same order: twice that at an
    interpolated time. The global error is the sum over the steps of the
    local errors, each carried to t by the flow: at most
    ``growth = max ||∂y(t)/∂y(s)||`` times that sum (1 for a contracting
    flow; the caller derives it, e.g. ``max_t ||e^{At}||`` for a linear
    error dynamics ``ė = A e``). The steps are counted from the dense
    output's breakpoints (``sol.sol.ts``), else bounded by ``sol.nfev``
    (each step takes at least one evaluation). The local error estimate is the
    embedded pair's (asymptotically exact; the solution carried on is of
    the higher order), which holds for the smooth right-hand sides used here.

    >>> from scipy.integrate import solve_ivp
    >>> sol = solve_ivp(lambda t, y: -y, (0, 2), [1.0], rtol=1e-8, atol=1e-10, dense_output=True)
    >>> bound = ode_tol(sol, 1e-8, 1e-10)          # y' = -y contracts: growth 1
    >>> t = np.linspace(0, 2, 9)
    >>> within(sol.sol(t)[0], np.exp(-t), bound), within(sol.sol(t)[0], np.exp(-1.001 * t), bound)
    (True, False)
    """
    y = np.asarray(sol.y, dtype=float)
    dense = getattr(sol, "sol", None)
    steps = len(dense.ts) - 1 if dense is not None else int(sol.nfev)
    local = float(np.sqrt(y.shape[0])) * (float(atol) + float(rtol) * float(np.max(np.abs(y), initial=0.0)))
    return 2.0 * float(growth) * steps * local


def pose_tol(T_d: ArrayLike, eps_omega: float, eps_v: float) -> float:
    """Bound on ``max |T - T_d|`` for a pose T whose body error twist ``log(T⁻¹ T_d)^∨ = (ω, v)`` has
    ``|ω| <= eps_omega``, ``|v| <= eps_v`` (the stopping test of ``ik.ik``).

    ``T = T_d e^{-[V]}``, so ``T - T_d = T_d (e^{-[V]} - I)``. An entry is a row
    of T_d (norm at most ``sqrt(1 + |p_d|²)``) times a column of
    ``e^{-[V]} - I`` (norm at most ``‖[V]‖ e^{‖[V]‖}``, with
    ``‖[V]‖₂ <= |ω| + |v|``). The forward kinematics that gives T adds its
    rounding, ``TOL`` relative to ``max(1, max |T_d|)`` (:func:`close`).

    >>> T_d = np.eye(4); T_d[:3, 3] = [3.0, 0.0, 4.0]
    >>> round(pose_tol(T_d, 1e-9, 1e-9) / 1e-9, 2)     # sqrt(26) · 2e-9 + 4e-12
    10.2
    """
    T_d = np.asarray(T_d, dtype=float)
    size = float(eps_omega) + float(eps_v)
    row = float(np.sqrt(1.0 + np.sum(T_d[..., :3, 3] ** 2, axis=-1).max()))
    return row * size * float(np.exp(size)) + TOL * max(1.0, float(np.max(np.abs(T_d))))


def chain_curvature(chain: SerialChain) -> float:
    """D with ``|∂²p/∂θ_i∂θ_j| <= D`` for the tool point p of a revolute chain, at every configuration.

    With the screw axes ``S_j'`` at θ (space frame), ``∂p/∂θ_j = [S_j'] p̃`` and, for
    ``i <= j``, ``∂²p/∂θ_i∂θ_j = [S_i'][S_j'] p̃``: ``[S_j'] p̃`` is the free vector
    ``w_j = ω_j × (p - q_j) + h_j ω_j`` (q_j on axis j, pitch h_j), and ``[S_i']`` turns
    it into ``ω_i × w_j``, no longer than ``|w_j| <= |p - q_j| + |h_j|``. The
    distance ``|p - q_j|`` is at most ``|q_{j+1} - q_j| + ... + |q_n - q_{n-1}| + |p - q_n|``,
    and each term joins two points of one link (the axis points ``q_k``, ``q_{k+1}``
    of link k, the tool and ``q_n`` of the last link), so it is the same at every
    configuration: D is the largest of these sums plus the pitch, from the home
    pose. Along a step Δ, ``|d²p/ds²| = |Σ Δ_i Δ_j ∂²p/∂θ_i∂θ_j| <= D |Δ|₁²``. A
    prismatic joint stretches its link, so D would depend on θ: it is refused.

    >>> import jacobians as jac
    >>> chain_curvature(jac.robots.planar_2r(1.0, 0.5))      # the tip is 1.5 from the first axis
    1.5
    """
    S = np.asarray(chain.screw_axes, dtype=float)
    if any(t != "R" for t in chain.joint_types):
        raise ValueError(f"chain_curvature needs revolute joints only, got {chain.joint_types!r}")
    w, v = S[:3].T, S[3:].T
    q = np.cross(w, v)                                   # the point of each axis nearest the origin, at home
    pitch = np.abs(np.sum(w * v, axis=1))
    tip = np.asarray(chain.home, dtype=float)[:3, 3]
    hops = np.r_[np.linalg.norm(np.diff(q, axis=0), axis=1), np.linalg.norm(tip - q[-1])]
    reach = np.cumsum(hops[::-1])[::-1]                  # reach[j] = |q_{j+1} - q_j| + ... + |p - q_n|
    return float(np.max(reach + pitch))


def clik_step_tol(chain: SerialChain, J: ArrayLike, delta: ArrayLike, e_o: float, w_d: float, k_dt: float,
                  scale: float = 1.0, ops: float = 512.0) -> tuple[float, float]:
    """Bounds ``(b_o, b_p)`` on how far one axis-angle CLIK step leaves the ideal ``(1 - K dt)`` contraction.

    One step of ``ik.clik`` (pseudo-inverse, J the 6×n geometric Jacobian of full row
    rank, so ``J Δ = (R R_dᵀ w_d + K dt e_o, Δp_d + K dt e_p)`` with ``w_d = log(R_{d,k+1} R_{d,k}ᵀ)``,
    ``Δp_d = p_{d,k+1} - p_{d,k}`` the path's own increments, the default feed-forward
    times dt) gives

    * position: ``e_p' = p_d' - p(θ + Δ) = (1 - K dt) e_p - r_p``, r_p the Taylor remainder of
      p along Δ: ``|r_p| <= D |Δ|₁² / 2`` (:func:`chain_curvature`);
    * orientation: the joints turn the tool by ``Q = exp([J_ω Δ + c])``; the angular velocity
      along the step varies by ``|ω'(s)| = |Σ_{i<j} Δ_iΔ_j ω_i × ω_j| <= |Δ|₁² / 2``, so
      ``|c| <= |Δ|₁² / 4`` to second order. With ``X = R_d Rᵀ = exp([e_o])``,
      ``X' = exp([w_d]) X exp(-[Xᵀw_d + K dt e_o + c]) = exp([w_d]) exp(-[w_d + K dt e_o + Xc]) X``,
      and BCH gives ``X' = exp(-[K dt e_o + Xc + w_d × K dt e_o / 2 + ...]) exp([e_o])``. The
      part along e_o leaves ``exp([(1 - K dt) e_o])`` exactly; the rest, of size
      ``|c| + |w_d| K dt |e_o| / 2``, moves the log by at most ``(θ/2)/sin(θ/2)`` times
      itself (the norm of the inverse Jacobian of SO(3)'s log at angle θ, here
      ``θ = |e_o| + |Δ|₁ + |w_d|``).

    The terms left out are of third order (``|Δ|₁³``, ``|w_d|² K dt |e_o|``); for
    ``|Δ|₁, |w_d|, |e_o| <= 1/2`` they are below the second-order ones, so twice the
    second-order bound holds (as in :func:`root_tol`); the position's bound is exact
    Taylor, D holding at every configuration. Rounding: the errors are
    computed to ``ops · EPS · max(1, scale)`` (scale: the size of the positions), and
    the pseudo-inverse solve to ``κ(J)`` times that. Hence, in norms,
    ``| |e_o'| - (1 - K dt)|e_o| | <= b_o`` and likewise for e_p with ``b_p``.

    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r(1.0, 0.5)
    >>> b_o, b_p = clik_step_tol(arm, jac.geometric_jacobian(arm, [0.3, 1.0]), [0.01, -0.02], 0.0, 0.0, 0.2)
    >>> round(b_p / 1e-4, 6)                       # 1.5 · 0.03² / 2: the rounding is 1e-12 of it
    6.75
    """
    J = np.asarray(J, dtype=float)
    d1 = float(np.sum(np.abs(np.asarray(delta, dtype=float))))
    e_o, w_d, k_dt = abs(float(e_o)), abs(float(w_d)), float(k_dt)
    if max(d1, w_d, e_o) > 0.5:
        raise ValueError(f"clik_step_tol holds for steps, path increments and errors up to 0.5, got "
                         f"|Δ|₁ = {d1:.3g}, |w_d| = {w_d:.3g}, |e_o| = {e_o:.3g}")
    s = np.linalg.svd(J, compute_uv=False)
    kappa = float(s[0] / s[-1]) if s[-1] > 0 else float("inf")
    rounding = ops * EPS * (1.0 + kappa) * max(1.0, float(scale))
    theta = e_o + d1 + w_d
    log_gain = 1.0 if theta == 0 else (theta / 2) / np.sin(theta / 2)
    b_p = chain_curvature(chain) * d1 * d1 / 2.0 + rounding
    b_o = 2.0 * log_gain * (d1 * d1 / 4.0 + w_d * k_dt * e_o / 2.0) + rounding
    return float(b_o), float(b_p)


def euler_step_tol(delta: ArrayLike, margin: float, J_A: ArrayLike, ops: float = 512.0) -> float:
    """Bound on ``| |e_φ'| - (1 - K dt)|e_φ| |`` for one Euler-angle CLIK step on a fixed target.

    ``ik.clik(..., orientation="zyx" or "zyz")`` steps ``J_A Δ = K dt (e_φ, e_p)``, J_A the
    analytic Jacobian (6×6, regular), and ``∂φ/∂θ = B(φ)⁻¹ J_ω`` is its first block, so
    ``e_φ' = (1 - K dt) e_φ - r``, r the Taylor remainder of φ along Δ:
    ``φ'' = ∂B⁻¹[φ'] ω + B⁻¹ ω'`` with ``|ω| <= |Δ|₁`` (unit axes), ``|ω'| <= |Δ|₁² / 2``
    (:func:`clik_step_tol`). For ZYX (margin ``m = |cos β|``, β the pitch) and ZYZ
    (``m = |sin β|``, β the middle angle) every row of B⁻¹ is ``(c_α t, s_α t, 1)``,
    ``(-s_α, c_α, 0)`` or ``(c_α, s_α, 0) / m`` with ``|t| <= 1/m``: ``‖B⁻¹‖ <= b = sqrt(1 + 2/m²)``,
    and its derivatives in α and β have Frobenius norms ``sqrt(2)/m`` and ``sqrt(2)/m²``:
    ``‖∂B⁻¹‖ <= b' = 2/m²``. So ``|r| <= (b b' + b/2) |Δ|₁² / 2``, with m the smallest margin
    along the step: the margin is 1-Lipschitz in β and β moves by at most ``b |Δ|₁``, so
    ``m >= m₀ - b(m₀/2) |Δ|₁`` as long as that is at least ``m₀/2`` (else ValueError). The
    solve adds ``ops · EPS · κ(J_A)`` (the angles are of order 1).

    >>> round(euler_step_tol([0.01, 0.0, 0.0], 1.0, np.eye(6)) / 1e-4, 3)    # m = 1 - b(1/2) · 0.01 = 0.97
    2.321
    """
    d1 = float(np.sum(np.abs(np.asarray(delta, dtype=float))))
    m0 = float(margin)

    def b_of(m: float) -> float:
        return float(np.sqrt(1.0 + 2.0 / m**2))

    m = m0 - b_of(m0 / 2) * d1
    if not m >= m0 / 2:
        raise ValueError(f"euler_step_tol: the step |Δ|₁ = {d1:.3g} may take the angles to their singularity "
                         f"(margin {m0:.3g})")
    b, db = b_of(m), 2.0 / m**2
    s = np.linalg.svd(np.asarray(J_A, dtype=float), compute_uv=False)
    kappa = float(s[0] / s[-1]) if s[-1] > 0 else float("inf")
    return float((b * db + b / 2) * d1 * d1 / 2 + ops * EPS * (1.0 + kappa))


def taylor_tol(g: Callable[[float], ArrayLike], h: float, order: int = 2, scale: float = 1.0,
               ops: float = 512.0) -> float:
    """Bound on ``max |g(h) - 2^k g(h/2)|`` for a g that vanishes to order k at 0 (a Taylor remainder).

    If ``g(0) = g'(0) = ... = g^(k-1)(0) = 0``, Taylor's theorem gives
    ``g(s) = s^k g_k + R(s)``, ``|R(s)| <= M s^(k+1) / (k+1)!``, ``M = max |g^(k+1)|`` on [0, h]; the
    k-th order terms cancel in ``g(h) - 2^k g(h/2)``, which is at most
    ``M h^(k+1) / (k+1)! · (1 + 2^k / 2^(k+1)) = 1.5 M h^(k+1) / (k+1)!``. This is the
    check that a remainder is of order k, with the window derived instead of "the ratio of
    two remainders is 2^k ± 10 %": a remainder of order k - 1 (a wrong first-order term)
    leaves ``h^(k-1) |g_(k-1)| (1 - 2^k / 2^(k-1))``, far outside for any h where the bound is
    small. M comes from the (k+1)-th central difference with the wider step ``H = 0.05``
    at 0, h/2 and h, taken twice (as M3 in :func:`fd_tol`); each value of g is off by
    ``ops · EPS · max(scale, |g|)`` (scale: the size of the terms g is a difference of),
    so the combination by ``(1 + 2^k)`` times that.

    >>> g = lambda s: np.sin(s) - s                          # of order 3 at 0
    >>> bound = taylor_tol(g, 1e-2, order=3)               # 1.5 M 1e-8 / 24 + 9 · 512 EPS, M ~ max |sin| near 0
    >>> g_bug = lambda s: g(s) + 1e-6 * s**2               # a second-order term of 1e-6: off by 1e-10
    >>> within(g(1e-2), 8 * g(5e-3), bound), within(g_bug(1e-2), 8 * g_bug(5e-3), bound)
    (True, False)
    >>> within(np.sin(1e-2), 8 * np.sin(5e-3), taylor_tol(np.sin, 1e-2, order=3))   # sin is of order 1
    False
    """
    h, k, H = float(h), int(order), 0.05
    if k < 1:
        raise ValueError(f"Expected order >= 1, got {order}")

    def val(t: float) -> NDArray[np.float64]:
        return np.asarray(g(t), dtype=float)

    M = 0.0
    for c in (0.0, h / 2, h):
        # the (k+1)-th central difference: sum_j (-1)^j C(k+1, j) g(c + ((k+1)/2 - j) H) / H^(k+1)
        d = sum((-1.0) ** j * comb(k + 1, j) * val(c + ((k + 1) / 2 - j) * H) for j in range(k + 2)) / H ** (k + 1)
        M = max(M, 2.0 * float(np.max(np.abs(d), initial=0.0)))
    F = max(float(scale), float(np.max(np.abs(val(h)), initial=0.0)), float(np.max(np.abs(val(h / 2)), initial=0.0)))
    return float(1.5 * M * h ** (k + 1) / factorial(k + 1) + (1 + 2**k) * ops * EPS * F)


def _target_velocities(path: np.ndarray, dt: float, given: ArrayLike | None) -> np.ndarray:
    """The path's velocities as a resolved-rate run feeds them forward: ``given``, or the forward differences of
    the path (the last one zero)."""
    if given is not None:
        return np.asarray(given, dtype=float)
    pdot = np.zeros_like(path)
    pdot[:-1] = np.diff(path, axis=0) / dt
    return pdot


def tracking_tol(chain: SerialChain, thetas: ArrayLike, rates: ArrayLike, path: ArrayLike, dt: float,
                 gain: float, target_velocities: ArrayLike | None = None) -> tuple[float, NDArray[np.float64]]:
    """Check a resolved-rate run step by step; return ``(worst, B)``: ``worst <= 1`` when every step is right,
    ``B[k]`` a bound on its tracking error ``|p_{d,k} - p(θ_k)|`` derived from those steps.

    One step of ``velocity.resolved_rate`` (rates ``θ̇_k``, feed-forward ``ṗ_{d,k}``, command
    ``c_k = ṗ_{d,k} + K e_k``, ``θ_{k+1} = θ_k + θ̇_k dt``) moves the tool point by
    ``p(θ_{k+1}) - p(θ_k) = J_v θ̇_k dt + r_p``, with ``|r_p| <= D |Δ|₁² / 2`` (Taylor along the step
    ``Δ = θ_{k+1} - θ_k``, D from :func:`chain_curvature`). So, exactly,
    ``e_{k+1} = e_k + (p_{d,k+1} - p_{d,k}) - J_v θ̇_k dt - r_p``: the run's own states predict each
    error vector to within ``b_k = D |Δ|₁² / 2`` plus rounding (``TOL`` of the positions for each of
    the four positions in it, and of ``|J_v| |Δ|₁`` for the product). ``worst`` is the largest
    ``|e_{k+1} - prediction| / b_k``: a step that is not ``θ̇_k dt`` moves the prediction to first
    order in Δ, above 1 once that exceeds ``D |Δ|₁² / 2`` (a time step 20 % off does here; a few % off,
    or rates a few % off, do not: check the rates against the law itself, from the same state). Rearranged,
    ``e_{k+1} = (1 - K dt) e_k + s_k - r_p`` with the step's shortfall
    ``s_k = dt (c_k - J_v θ̇_k) + (p_{d,k+1} - p_{d,k} - ṗ_{d,k} dt)`` (what the solve leaves out
    of the command, zero for the pseudo-inverse of a J_v of full row rank, ``λ² (J_v J_vᵀ + λ²)⁻¹ c_k dt``
    for DLS, plus the path's own Taylor remainder), so for ``0 <= K dt <= 1``,
    ``|e_k| <= B_k``, ``B_0 = |e_0|``, ``B_{k+1} = (1 - K dt) B_k + |s_k| + b_k``: O(dt) for a
    smooth path away from singularities, and not an observed error. Planar chains (paths of 2
    columns) use J_v's rows x, y; spatial ones all three.

    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r(1.0, 1.0)
    >>> path = arm.fk([-0.9, 1.8])[:2, 3] + np.outer(np.linspace(0, 0.5, 50), [1.0, 0.5])
    >>> out = jac.velocity.resolved_rate(arm, [-0.9, 1.8], path, 0.02, gain=2.0)
    >>> worst, B = tracking_tol(arm, out.thetas, out.rates, path, 0.02, 2.0)
    >>> bool(worst <= 1), bool(np.all(out.errors <= B)), bool(B.max() < 0.05)
    (True, True, True)
    >>> wrong = np.cumsum(np.r_[out.thetas[:1], 1.2 * 0.02 * out.rates[:-1]], axis=0)    # steps of 1.2 dt
    >>> bool(tracking_tol(arm, wrong, out.rates, path, 0.02, 2.0)[0] > 1)
    True
    """
    from .jacobian import geometric_jacobian

    thetas, rates, path = (np.asarray(a, dtype=float) for a in (thetas, rates, path))
    dt, K = float(dt), float(gain)
    if not 0.0 <= K * dt <= 1.0:
        raise ValueError(f"tracking_tol needs 0 <= K dt <= 1, got {K * dt:.3g}")
    pdot = _target_velocities(path, dt, target_velocities)
    dim = path.shape[1]
    D = chain_curvature(chain)
    e = path - np.asarray(chain.fk(thetas), dtype=float)[:, :dim, 3]
    scale = max(1.0, float(np.max(np.abs(path))))
    B = np.empty(len(path))
    B[0] = float(np.linalg.norm(e[0]))
    worst = 0.0
    for k in range(len(path) - 1):
        J_v = np.asarray(geometric_jacobian(chain, thetas[k]), dtype=float)[3:3 + dim]
        d1 = float(np.sum(np.abs(thetas[k + 1] - thetas[k])))
        b = D * d1 * d1 / 2.0 + TOL * (4.0 * scale + float(np.linalg.norm(J_v, 2)) * d1)
        moved = J_v @ rates[k] * dt
        worst = max(worst, float(np.linalg.norm(e[k + 1] - (e[k] + path[k + 1] - path[k] - moved))) / b)
        shortfall = dt * (pdot[k] + K * e[k]) - moved + (path[k + 1] - path[k] - pdot[k] * dt)
        B[k + 1] = (1.0 - K * dt) * B[k] + float(np.linalg.norm(shortfall)) + b
    return worst, B


def resolved_rate_tol(chain: SerialChain, thetas: ArrayLike, rates: ArrayLike, path: ArrayLike, dt: float,
                      gain: float, damping: float = 0.0, target_velocities: ArrayLike | None = None,
                      e0: float = 0.0, ops: float = 512.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """How far a resolved-rate run may be from the same run in exact arithmetic: ``(E, R)``, per step.

    ``E[k]`` bounds ``|θ_k - θ*_k|`` and ``R[k]`` bounds ``|θ̇_k - θ̇*_k|``, θ* the run of
    ``velocity.resolved_rate`` computed exactly from any start within ``e0`` of ``thetas[0]``;
    ``inf`` from the step where the argument no longer holds. Any machine's run of the same law
    is within its own E of θ*, so a claim about the run shown (a rate above a threshold, a small
    singular value) holds on every IEEE-754 machine when it holds with the margin that E and R give.

    One step is ``θ_{k+1} = f(θ_k) = θ_k + dt θ̇(θ_k)``, ``θ̇ = J^# c``, ``c = ṗ_{d,k} + K (p_{d,k} - p(θ))``,
    ``J^# = Jᵀ W``, ``W = (J Jᵀ + λ²)⁻¹`` (J = J_v, m×n, m <= n for the pseudo-inverse, λ = 0). Its
    derivative along δ is ``(I - J^# J) DJ[δ]ᵀ W c - J^# DJ[δ] θ̇ - K J^# J δ``, where ``DJ[δ]``'s column
    j is ``Σ_i δ_i ∂²p/∂θ_i∂θ_j``, of norm at most ``D |δ|₁`` (:func:`chain_curvature`), so
    ``‖DJ[δ]‖ <= n D |δ|`` and ``|DJ[δ] θ̇| <= n D |δ| |θ̇|``. With ``‖I - J^# J‖ <= 1``,
    ``‖J^#‖ <= g = min(1/(2λ), 1/σ)``, ``|W c| <= |c| / (σ² + λ²)`` (the first term vanishes for the
    pseudo-inverse of a square J) and ``‖J^# J‖ <= 1``, the rate is Lipschitz with
    ``L = n D (|c| / (σ² + λ²) + g |θ̇|) + K``, and the step map with
    ``‖I - K dt J^# J‖ + dt n D (|c| / (σ² + λ²) + g |θ̇|)``, where
    ``‖I - K dt J^# J‖ = 1 - K dt σ² / (σ² + λ²)`` for a square J (else 1). Every quantity is taken
    at its worst over the ball of radius ``e = E[k]`` around θ_k: σ (the smallest singular value)
    at least ``σ_k - n D e`` (Weyl: ``‖J(θ) - J(θ_k)‖ <= n D e``), ``|c|`` at most
    ``|c_k| + K (σ_max + n D e) e``, ``|θ̇|`` at most ``(|θ̇_k| + ρ + (n D |c| / (σ² + λ²) + K) e) / (1 - n D g e)``
    (the rate's own Lipschitz bound solved for its largest value, valid while ``2 n D g e <= 1``).
    Rounding: the SVD solve is backward stable (J off by ``ops · EPS · σ_max``, c by ``ops · EPS`` of the
    positions' size), so ``ρ = ops · EPS · (σ_max (|c| / (σ² + λ²) + g |θ̇_k|) + g · scale)``, and the
    sum ``θ_k + dt θ̇_k`` adds ``EPS |θ_{k+1}|``. Hence ``E[k+1] = ‖Df‖ E[k] + dt ρ + EPS |θ_{k+1}|``,
    ``R[k] = L E[k] + ρ``. The bound is first order in ``ops · EPS`` and assumes nothing else;
    it is loose (each step's worst direction), so it runs out where the run passes close to a
    singularity with large rates: there claims need another argument.

    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r(1.0, 1.0)
    >>> path = arm.fk([-0.9, 1.8])[:2, 3] + np.outer(np.linspace(0, 0.5, 50), [1.0, 0.5])
    >>> out = jac.velocity.resolved_rate(arm, [-0.9, 1.8], path, 0.02, gain=2.0)
    >>> E, R = resolved_rate_tol(arm, out.thetas, out.rates, path, 0.02, 2.0)
    >>> bool(E.max() < 1e-10)                   # 50 steps' rounding, each amplified by the steps after it
    True
    >>> moved = jac.velocity.resolved_rate(arm, [-0.9 + 1e-9, 1.8], path, 0.02, gain=2.0)   # a start 1e-9 off
    >>> E9 = resolved_rate_tol(arm, out.thetas, out.rates, path, 0.02, 2.0, e0=1e-9)[0]
    >>> bool(np.all(np.linalg.norm(moved.thetas - out.thetas, axis=1) <= E9))
    True
    >>> slow = jac.velocity.resolved_rate(arm, [-0.9, 1.8], path, 0.0201, gain=2.0)          # steps 0.5 % long
    >>> bool(np.all(np.linalg.norm(slow.thetas - out.thetas, axis=1) <= 2 * E))
    False
    """
    from .jacobian import geometric_jacobian

    thetas, rates, path = (np.asarray(a, dtype=float) for a in (thetas, rates, path))
    dt, K, lam = float(dt), float(gain), float(damping)
    N, dim = path.shape
    n = thetas.shape[1]
    if lam == 0.0 and dim > n:
        raise ValueError(f"resolved_rate_tol: the pseudo-inverse needs J_v of full row rank, m <= n; got m = {dim}, "
                         f"n = {n}")
    if not 0.0 <= K * dt <= 1.0:
        raise ValueError(f"resolved_rate_tol needs 0 <= K dt <= 1, got {K * dt:.3g}")
    pdot = _target_velocities(path, dt, target_velocities)
    nD = n * chain_curvature(chain)
    scale = max(1.0, float(np.max(np.abs(path))))
    square = dim == n
    E = np.full(N, np.inf)
    R = np.full(N, np.inf)
    E[0] = float(e0)
    for k in range(N):
        e = float(E[k])
        J = np.asarray(geometric_jacobian(chain, thetas[k]), dtype=float)[3:3 + dim]
        sv = np.linalg.svd(J, compute_uv=False)
        s_max, sig = float(sv[0]), (float(sv[-1]) if sv.size == dim else 0.0)
        c = float(np.linalg.norm(pdot[k] + K * (path[k] - np.asarray(chain.fk(thetas[k]))[:dim, 3])))
        sig_b = sig - nD * e
        c_b = c + K * (s_max + nD * e) * e
        if lam == 0.0 and sig_b <= 0.0:
            break

        def gains(sg: float, cc: float) -> tuple[float, float]:
            """(g, |W c|) for a smallest singular value of at least sg."""
            g = 1.0 / (2.0 * lam) if sg <= 0.0 else (1.0 / sg if lam == 0.0 else min(1.0 / (2.0 * lam), 1.0 / sg))
            w = 0.0 if (lam == 0.0 and square) else cc / (max(sg, 0.0) ** 2 + lam**2)
            return g, w

        g, w = gains(sig, c)
        g_b, w_b = gains(sig_b, c_b)
        if 2.0 * nD * g_b * e > 1.0:
            break
        rate_k = float(np.linalg.norm(rates[k]))
        rho = ops * EPS * (s_max * (w + g * rate_k) + g * scale)
        rate_b = (rate_k + rho + (nD * w_b + K) * e) / (1.0 - nD * g_b * e)
        contract = 1.0 - K * dt * (sig_b**2 / (sig_b**2 + lam**2) if square and sig_b > 0.0 else 0.0)
        R[k] = (nD * (w_b + g_b * rate_b) + K) * e + rho
        if k + 1 < N:
            E[k + 1] = ((contract + dt * nD * (w_b + g_b * rate_b)) * e + dt * rho
                        + EPS * float(np.linalg.norm(thetas[k + 1])))
    return E, R
