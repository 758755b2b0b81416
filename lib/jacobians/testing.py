"""Random chains and transforms for tests, exercises and property checks.

>>> import numpy as np
>>> chain = random_chain(np.random.default_rng(0), dof=4)
>>> chain.dof
4
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import positive_int
from .chain import SerialChain
from .lie import _exp_se3, _exp_so3

__all__ = ["random_rotation", "random_transform", "random_chain", "random_theta",
           "EPS", "TOL", "close", "within", "fd_tol", "fd2_tol", "root_tol", "ode_tol",
           "pose_tol"]

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
