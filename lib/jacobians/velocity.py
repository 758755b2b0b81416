r"""Inverse velocity kinematics: joint rates for a wanted end-effector velocity.

Given a Jacobian J (or a block of its rows) and a wanted velocity V, find
:math:`\dot\theta` with :math:`J\dot\theta \approx V`:

* :func:`pinv_rates`: the Moore-Penrose pseudo-inverse :math:`J^\dagger V`,
  the least-squares solution of smallest norm. Exact where J has full row
  rank; it blows up near a singularity, where :math:`1/\sigma_{\min}` is large.
* :func:`dls_rates`: damped least squares
  :math:`(J^TJ + \lambda^2 I)^{-1}J^TV`, which trades a small tracking error
  for bounded rates: :math:`\|\dot\theta\| \le \|V\|/(2\lambda)`.
* :func:`resolved_rate`: both used in a loop to make the tool point of an arm
  follow a path.

The frames must match: :math:`\mathcal V_s` with :math:`J_s`,
:math:`\mathcal V_b` with :math:`J_b`, :math:`(\omega_s, \dot p)` with the
geometric Jacobian.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()
>>> J_v = jac.geometric_jacobian(arm, [0.0, np.pi / 2])[3:5]   # x, y rows
>>> pinv_rates(J_v, [0.0, 1.0]).round(12) + 0.0             # move the tip up
array([ 1., -1.])
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_finite, positive_float, theta_array
from .chain import SerialChain, _as_chain
from .jacobian import geometric_jacobian

__all__ = ["pinv_rates", "dls_rates", "resolved_rate", "ResolvedRateResult"]


def _system(J: object, V: object) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    A = as_float_array(J, "J")
    if A.ndim < 2 or A.shape[-1] == 0 or A.shape[-2] == 0:
        raise ValueError(f"Expected J with shape (..., m, n), got shape {A.shape}")
    check_finite(A, "J")
    b = as_float_array(V, "V")
    m = A.shape[-2]
    if b.ndim < 1 or b.shape[-1] != m:
        raise ValueError(f"Expected V with shape (..., {m}) to match J with {m} rows, got shape {b.shape}")
    check_finite(b, "V")
    try:
        np.broadcast_shapes(A.shape[:-2], b.shape[:-1])
    except ValueError:
        raise ValueError(
            f"The batch shapes of J {A.shape[:-2]} and V {b.shape[:-1]} do not broadcast"
        ) from None
    return A, b


def _svd_solve(A: NDArray[np.float64], b: NDArray[np.float64],
               gain: Callable[[NDArray[np.float64]], NDArray[np.float64]]) -> NDArray[np.float64]:
    """V_r diag(gain(sigma)) U^T b, with the thin SVD of A."""
    U, s, Vt = np.linalg.svd(A, full_matrices=False)
    Utb = (np.swapaxes(U, -1, -2) @ b[..., :, None])[..., 0]
    out: NDArray[np.float64] = (np.swapaxes(Vt, -1, -2) @ (gain(s) * Utb)[..., :, None])[..., 0]
    return out


def pinv_rates(J: ArrayLike, V: ArrayLike, rcond: float = 1e-10) -> NDArray[np.float64]:
    r"""Joint rates :math:`\dot\theta = J^\dagger V` (Moore-Penrose pseudo-inverse).

    Computed from the SVD :math:`J = U\Sigma V^T`: singular values below
    ``rcond * sigma_max`` are treated as zero (their direction gets no rate,
    as in ``numpy.linalg.pinv``). MR: the :math:`J^\dagger` of Sections 6.2-6.3,
    used in ``IKinSpace`` / ``IKinBody`` (``np.linalg.pinv``).

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    V : array_like, shape (..., m)
        The wanted velocity, in the frame and row order of J.
    rcond : float, positive
        Relative cut-off for small singular values.

    Returns
    -------
    theta_dot : ndarray, shape (..., n)

    >>> import numpy as np
    >>> J = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    >>> pinv_rates(J, [1.0, 1.0])
    array([1. , 0.5, 0. ])
    """
    A, b = _system(J, V)
    rcond = positive_float(rcond, "rcond")

    def gain(s: NDArray[np.float64]) -> NDArray[np.float64]:
        keep = s > rcond * s[..., :1]
        return np.where(keep, 1.0 / np.where(keep, s, 1.0), 0.0)

    return _svd_solve(A, b, gain)


def dls_rates(J: ArrayLike, V: ArrayLike, damping: float) -> NDArray[np.float64]:
    r"""Damped least-squares joint rates :math:`\dot\theta = (J^TJ + \lambda^2 I)^{-1}J^TV`.

    The minimiser of :math:`\|J\dot\theta - V\|^2 + \lambda^2\|\dot\theta\|^2`.
    Computed stably from the SVD as :math:`\sum_i \frac{\sigma_i}{\sigma_i^2 +
    \lambda^2} v_i u_i^T V` (no normal equations are formed, so nothing is
    squared and inverted). Each gain is at most :math:`1/(2\lambda)`, so
    :math:`\|\dot\theta\|\le\|V\|/(2\lambda)` even at a singularity; as
    :math:`\lambda\to 0` it tends to :func:`pinv_rates`. MR: no counterpart in
    MR's code.

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    V : array_like, shape (..., m)
    damping : float, >= 0
        :math:`\lambda`, in the units of J's entries (metres for linear rows).
        0 gives the pseudo-inverse solution (with zero rate along exactly
        singular directions).

    Returns
    -------
    theta_dot : ndarray, shape (..., n)

    >>> import numpy as np
    >>> J = np.array([[1.0, 1.0], [1.0, 1.0]])   # singular
    >>> dls_rates(J, [1.0, 0.0], damping=0.1)
    array([0.24937656, 0.24937656])
    """
    A, b = _system(J, V)
    lam = positive_float(damping, "damping", allow_zero=True)
    lam2 = lam * lam

    def gain(s: NDArray[np.float64]) -> NDArray[np.float64]:
        den = s * s + lam2
        return np.where(den > 0, s / np.where(den > 0, den, 1.0), 0.0)

    return _svd_solve(A, b, gain)


class ResolvedRateResult(NamedTuple):
    """What :func:`resolved_rate` returns; arrays indexed by time step k = 0..N-1."""

    #: (N, n) joint values at each step (row 0 is ``theta0``).
    thetas: np.ndarray
    #: (N, n) joint rates applied from step k to k + 1.
    rates: np.ndarray
    #: (N, d) tool-point positions reached (d = 2 or 3, as the path).
    positions: np.ndarray
    #: (N,) distance from the path point: ``|target_path[k] - positions[k]|``.
    errors: np.ndarray
    #: (N,) smallest singular value of the rows used (distance to a singularity).
    sigma_min: np.ndarray


def resolved_rate(chain: SerialChain, theta0: ArrayLike, target_path: ArrayLike, dt: float, method: str = "pinv",
                  damping: float = 0.05, gain: float = 2.0,
                  target_velocities: ArrayLike | None = None) -> ResolvedRateResult:
    r"""Make the origin of {b} follow a path of points by resolved-rate motion control.

    At each step k, with :math:`p_k` the position of {b}'s origin at
    :math:`\theta_k` and :math:`J_v` the matching linear rows of the geometric
    Jacobian (the x, y rows for a 2-column path, x, y, z for 3 columns):

    .. math:: \dot\theta_k = J_v^{\#}\big(\dot p_{d,k} + K (p_{d,k} - p_k)\big),\qquad
              \theta_{k+1} = \theta_k + \dot\theta_k\,\Delta t,

    with :math:`J_v^{\#}` the pseudo-inverse (``"pinv"``) or damped least
    squares (``"dls"``). The feed-forward :math:`\dot p_{d,k}` comes from
    ``target_velocities`` or, if omitted, from forward differences of the
    path; the feedback gain K removes the drift of the Euler steps. MR:
    the Newton-Raphson step of Section 6.2 (``IKinSpace`` / ``IKinBody``) is
    the same update with :math:`\dot p_d = 0` and :math:`K\Delta t = 1`.

    Parameters
    ----------
    chain : SerialChain
        Any chain; for a planar arm pass a path of (x, y) points.
    theta0 : array_like, shape (n,)
        Start configuration (ideally with the tool at ``target_path[0]``).
    target_path : array_like, shape (N, 2) or (N, 3), N >= 2
        Wanted positions of {b}'s origin in {s} at times 0, dt, 2 dt, ...
    dt : float, positive
        Time step.
    method : {"pinv", "dls"}
    damping : float, >= 0
        :math:`\lambda` for ``"dls"`` (ignored by ``"pinv"``).
    gain : float, >= 0
        K, in 1/s. Stable for :math:`0 \le K\Delta t < 2`.
    target_velocities : array_like, shape (N, d), optional
        :math:`\dot p_d`; default: forward differences of the path (zero at the end).

    Returns
    -------
    ResolvedRateResult
        ``thetas``, ``rates``, ``positions``, ``errors``, ``sigma_min``.

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> t = np.linspace(0, 1, 41)
    >>> start = arm.fk([0.3, 1.2])[:2, 3]
    >>> path = start + np.stack([0.3 * t, 0.2 * t], axis=1)   # a straight segment
    >>> out = resolved_rate(arm, [0.3, 1.2], path, dt=t[1] - t[0])
    >>> out.thetas.shape, bool(out.errors.max() < 1e-2)
    ((41, 2), True)
    """
    chain = _as_chain(chain)
    n = chain.dof
    theta = theta_array(theta0, n)
    if theta.ndim != 1:
        raise ValueError(f"Expected theta0 with shape ({n},), got shape {theta.shape}")
    P = as_float_array(target_path, "target_path")
    if P.ndim != 2 or P.shape[1] not in (2, 3) or P.shape[0] < 2:
        raise ValueError(
            "Expected target_path with shape (N, 2) for (x, y) points or (N, 3) for (x, y, z), N >= 2; "
            f"got shape {P.shape}"
        )
    check_finite(P, "target_path")
    N, d = P.shape
    dt = positive_float(dt, "dt")
    if method not in ("pinv", "dls"):
        raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
    damping = positive_float(damping, "damping", allow_zero=True)
    gain = positive_float(gain, "gain", allow_zero=True)
    if target_velocities is None:
        Pdot = np.zeros_like(P)
        Pdot[:-1] = np.diff(P, axis=0) / dt
    else:
        Pdot = as_float_array(target_velocities, "target_velocities")
        if Pdot.shape != P.shape:
            raise ValueError(f"Expected target_velocities with the shape of target_path {P.shape}, got {Pdot.shape}")
        check_finite(Pdot, "target_velocities")

    thetas = np.empty((N, n))
    rates = np.empty((N, n))
    positions = np.empty((N, d))
    sigma_min = np.empty(N)
    for k in range(N):
        J = geometric_jacobian(chain, theta)
        J_v = J[3:3 + d]
        p = chain.fk(theta)[:d, 3]
        v = Pdot[k] + gain * (P[k] - p)
        if method == "pinv":
            rate = pinv_rates(J_v, v)
        else:
            rate = dls_rates(J_v, v, damping)
        thetas[k], rates[k], positions[k] = theta, rate, p
        sv = np.linalg.svd(J_v, compute_uv=False)
        sigma_min[k] = sv[-1] if sv.size == d else 0.0
        theta = theta + rate * dt
    errors = np.linalg.norm(P - positions, axis=1)
    return ResolvedRateResult(thetas, rates, positions, errors, sigma_min)
