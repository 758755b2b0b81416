r"""Redundancy: the general solution of :math:`J\dot\theta = V`, and the gradient of manipulability.

When a task needs m < n coordinates (a planar 3R arm placing its tip in the
plane: m = 2, n = 3), :math:`J\dot\theta = V` has a family of solutions

.. math:: \dot\theta = J^\dagger V + (I - J^\dagger J)\,z,\qquad z\in\mathbb R^n\ \text{free},

where :math:`I - J^\dagger J` is the orthogonal projector onto the null space
of J (:func:`jacobians.analysis.nullspace_projector`): the second term moves
the joints without moving the task. :func:`redundant_rates` computes it; a
common choice of z is the gradient of a secondary objective, such as
Yoshikawa's manipulability :math:`w(\theta) = \sqrt{\det J J^T}`, whose
gradient :func:`manipulability_gradient` gives in closed form.

**The gradient.** With :math:`A = JJ^T` (invertible where J has full row
rank), :math:`\partial\det A = \det A\ \mathrm{tr}(A^{-1}\partial A)` and
:math:`\partial A = (\partial J)J^T + J(\partial J)^T`, so
:math:`\partial\log\det A = 2\,\mathrm{tr}\big(J^T(JJ^T)^{-1}\partial J\big)
= 2\,\mathrm{tr}(J^\dagger\partial J)`, and

.. math:: \frac{\partial w}{\partial\theta_k} = w\ \mathrm{tr}\Big(J^\dagger\frac{\partial J}{\partial\theta_k}\Big),

with :math:`\partial J/\partial\theta_k` the Jacobian derivative for
:math:`\dot\theta = e_k` (:func:`jacobians.acceleration.jacobian_derivative`).
Written with the SVD :math:`J = \sum_i\sigma_iu_iv_i^T` it is
:math:`\sum_i\big(\prod_{j\ne i}\sigma_j\big)\,u_i^T\frac{\partial J}{\partial\theta_k}v_i`,
which is what is computed (no inverse, finite at a singularity; there w has
a kink, like :math:`|\sigma_{\min}|`, and the value is one of its one-sided slopes).

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()           # w = l1 l2 |sin theta2| for the x, y rows
>>> manipulability_gradient(arm, [0.3, 0.5], rows=[3, 4]).round(12)
array([0.        , 0.87758256])
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_finite, theta_array
from .acceleration import _derivative_and_jacobian
from .analysis import nullspace_projector
from .chain import SerialChain, _as_chain
from .frames import Frame, check_frame
from .velocity import dls_rates, pinv_rates

__all__ = ["manipulability_gradient", "redundant_rates", "task_priority_rates", "weighted_pinv_rates"]


def _rows(rows: Sequence[int] | None) -> list[int]:
    if rows is None:
        return list(range(6))
    if isinstance(rows, (str, bytes)) or not hasattr(rows, "__len__"):
        raise TypeError(f"Expected rows as a sequence of row indices in 0..5, got {type(rows).__name__}")
    out = []
    for r in rows:
        if isinstance(r, bool) or not isinstance(r, (int, np.integer)) or not 0 <= int(r) < 6:
            raise ValueError(f"Expected rows as indices in 0..5 (rows (omega, v) of J), got {list(rows)!r}")
        out.append(int(r))
    if not out or len(set(out)) != len(out):
        raise ValueError(f"Expected distinct row indices, at least one, got {list(rows)!r}")
    return out


def manipulability_gradient(chain: SerialChain, theta: ArrayLike, frame: Frame = "geometric",
                            rows: Sequence[int] | None = None) -> NDArray[np.float64]:
    r"""Gradient :math:`\partial w/\partial\theta` of :math:`w = \sqrt{\det(J_rJ_r^T)}`, shape (..., n).

    Parameters
    ----------
    chain : SerialChain
    theta : array_like, shape (..., n)
    frame : {"space", "body", "geometric"}
        Which Jacobian; default geometric (for a tool-point task take its
        linear rows).
    rows : sequence of int, optional
        The rows :math:`J_r` of the 6-row Jacobian that make the task (e.g.
        ``[3, 4]``: x, y of a planar arm's tool point); default all six. Needs
        ``len(rows) <= n``; :func:`jacobians.analysis.manipulability` of the
        same rows is w.

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm, th = jac.robots.planar_3r(), np.array([0.2, 0.7, -0.4])
    >>> w = lambda t: jac.analysis.manipulability(jac.geometric_jacobian(arm, t)[3:5])
    >>> np.allclose(manipulability_gradient(arm, th, rows=[3, 4]), jac.numerical_jacobian(w, th))
    True
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, ("space", "body", "geometric"))
    r = _rows(rows)
    n = chain.dof
    if len(r) > n:
        raise ValueError(
            f"Expected at most {n} rows for a chain with {n} joints (det J J^T is zero otherwise), got {len(r)}"
        )
    th = theta_array(theta, n)
    # dJ/dθ_k for every k at once: a batch over the unit rates e_k on a new axis.
    eye = np.eye(n)
    dJ, J = _derivative_and_jacobian(chain, np.broadcast_to(th[..., None, :], th.shape[:-1] + (n, n)),
                                     np.broadcast_to(eye, th.shape[:-1] + (n, n)), frame)
    J = J[..., 0, r, :]  # (..., m, n)
    dJ = dJ[..., r, :]  # (..., n_k, m, n)
    U, s, Vt = np.linalg.svd(J, full_matrices=False)  # s: (..., m)
    m = len(r)
    others = np.ones(s.shape)
    for i in range(m):
        for j in range(m):
            if i != j:
                others[..., i] *= s[..., j]
    # u_i^T dJ_k v_i for every k and i
    proj = np.einsum("...ai,...kab,...ib->...ki", U, dJ, Vt)
    grad: NDArray[np.float64] = np.einsum("...ki,...i->...k", proj, others)
    return grad


def redundant_rates(J: ArrayLike, V: ArrayLike, z: ArrayLike, rcond: float = 1e-10) -> NDArray[np.float64]:
    r"""Joint rates :math:`\dot\theta = J^\dagger V + (I - J^\dagger J)z`.

    The first term is the least-norm solution (:func:`jacobians.velocity.pinv_rates`),
    the second the part of z that does not move the task (it is orthogonal to
    the first). Where J has full row rank, :math:`J\dot\theta = V` exactly for every z.

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    V : array_like, shape (..., m)
    z : array_like, shape (..., n)
        A secondary joint velocity, e.g. a gradient step of an objective.
    rcond : float
        As for :func:`jacobians.velocity.pinv_rates` and the projector.

    >>> import numpy as np
    >>> J = np.array([[1.0, 1.0, 0.0]])
    >>> redundant_rates(J, [2.0], [0.0, 0.0, 5.0])      # z moves joint 3 only, which J ignores
    array([1., 1., 5.])
    """
    A = as_float_array(J, "J")
    zz = as_float_array(z, "z")
    if A.ndim < 2 or zz.ndim < 1 or zz.shape[-1] != A.shape[-1]:
        raise ValueError(f"Expected J (..., m, n) and z (..., n) with the same n, got shapes {A.shape} and {zz.shape}")
    check_finite(zz, "z")
    base = pinv_rates(A, V, rcond)
    P = nullspace_projector(A, rtol=rcond)
    out: NDArray[np.float64] = base + (P @ zz[..., :, None])[..., 0]
    return out


def _damped(A: NDArray[np.float64], b: NDArray[np.float64], damping: float) -> NDArray[np.float64]:
    r""":math:`A^\dagger b` for damping 0, else the damped least-squares solution (gains at most 1/(2 damping))."""
    out: NDArray[np.float64] = pinv_rates(A, b) if damping == 0.0 else dls_rates(A, b, damping)
    return out


def task_priority_rates(J1: ArrayLike, V1: ArrayLike, J2: ArrayLike, V2: ArrayLike, damping: float = 0.0,
                        method: str = "nakamura") -> NDArray[np.float64]:
    r"""Joint rates for a primary task :math:`J_1\dot\theta = V_1` and a secondary one :math:`J_2\dot\theta = V_2`.

    ``method="nakamura"`` (Nakamura, Hanafusa and Yoshikawa):
    :math:`\dot\theta = J_1^\dagger V_1 + (J_2P_1)^{\#}(V_2 - J_2J_1^\dagger V_1)` with
    :math:`P_1 = I - J_1^\dagger J_1`. The secondary task is met as well as the
    primary one allows; but where :math:`J_2P_1` loses rank while :math:`J_1` and
    :math:`J_2` do not (an *algorithmic singularity*), :math:`(J_2P_1)^\dagger` has a
    gain :math:`1/\sigma_{\min}(J_2P_1)` and the rates blow up.

    ``method="singularity_robust"`` (Chiaverini):
    :math:`\dot\theta = J_1^\dagger V_1 + P_1J_2^{\#}V_2`. It never inverts :math:`J_2P_1`,
    so it stays bounded at algorithmic singularities; the price is that the
    secondary task is not met exactly even where it could be.

    In both, :math:`A^{\#}` is the pseudo-inverse for ``damping = 0`` and the
    damped least-squares inverse :math:`A^T(AA^T + \lambda^2I)^{-1}` otherwise
    (gains at most :math:`1/(2\lambda)`). The primary task is met exactly
    wherever :math:`J_1` has full row rank: the second term lies in the null space of :math:`J_1`.

    >>> import numpy as np
    >>> J1, J2 = np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 0.0]])
    >>> task_priority_rates(J1, [1.0], J2, [2.0])
    array([1., 2., 0.])
    """
    A1, A2 = as_float_array(J1, "J1"), as_float_array(J2, "J2")
    if A1.ndim < 2 or A2.ndim < 2 or A1.shape[-1] != A2.shape[-1]:
        raise ValueError(f"Expected J1 (..., m1, n) and J2 (..., m2, n) with the same n, "
                         f"got shapes {A1.shape} and {A2.shape}")
    if isinstance(damping, bool) or not isinstance(damping, (int, float, np.floating, np.integer)) \
            or not np.isfinite(damping) or damping < 0:
        raise ValueError(f"Expected damping as a finite number >= 0, got {damping!r}")
    if method not in ("nakamura", "singularity_robust"):
        raise ValueError(f"Expected method 'nakamura' or 'singularity_robust', got {method!r}")
    b1, b2 = as_float_array(V1, "V1"), as_float_array(V2, "V2")
    if b1.shape[-1:] != A1.shape[-2:-1] or b2.shape[-1:] != A2.shape[-2:-1]:
        raise ValueError(f"Expected V1 with {A1.shape[-2]} and V2 with {A2.shape[-2]} entries, "
                         f"got shapes {b1.shape} and {b2.shape}")
    check_finite(b1, "V1")
    check_finite(b2, "V2")
    lam = float(damping)
    first = pinv_rates(A1, b1)
    P1 = nullspace_projector(A1)
    if method == "nakamura":
        A2P1 = A2 @ P1
        rest = b2 - (A2 @ first[..., :, None])[..., 0]
        second = _damped(A2P1, rest, lam)
        # (J2 P1)^# maps into the row space of J2 P1, which P1 fixes: project again so rounding stays out of N(J1)^perp
        second = (P1 @ second[..., :, None])[..., 0]
    else:
        second = (P1 @ _damped(A2, b2, lam)[..., :, None])[..., 0]
    out: NDArray[np.float64] = first + second
    return out


def weighted_pinv_rates(J: ArrayLike, V: ArrayLike, W: ArrayLike) -> NDArray[np.float64]:
    r"""The weighted least-norm rates :math:`\dot\theta = W^{-1}J^T(JW^{-1}J^T)^{-1}V`.

    The minimiser of :math:`\dot\theta^TW\dot\theta` subject to :math:`J\dot\theta = V`, for a
    symmetric positive definite weight W (e.g. larger for joints that should move
    less). Computed as :math:`L^{-T}(JL^{-T})^\dagger V` with :math:`W = LL^T` (Cholesky), which
    is the same where J has full row rank and stays defined where it does not.

    >>> import numpy as np
    >>> weighted_pinv_rates(np.array([[1.0, 1.0]]), [1.0], np.diag([1.0, 3.0]))
    array([0.75, 0.25])
    """
    A = as_float_array(J, "J")
    Wm = as_float_array(W, "W")
    n = A.shape[-1] if A.ndim >= 2 else -1
    if A.ndim < 2 or Wm.shape[-2:] != (n, n):
        raise ValueError(f"Expected J (..., m, n) and W (..., n, n), got shapes {A.shape} and {Wm.shape}")
    check_finite(Wm, "W")
    if not np.allclose(Wm, np.swapaxes(Wm, -1, -2), rtol=1e-12, atol=1e-12 * np.abs(Wm).max()):
        raise ValueError("Expected a symmetric weight W")
    try:
        L = np.linalg.cholesky(Wm)
    except np.linalg.LinAlgError:
        raise ValueError("Expected a positive definite weight W (its Cholesky factorisation failed)") from None
    Linv_T = np.swapaxes(np.linalg.inv(L), -1, -2)
    y = pinv_rates(A @ Linv_T, V)
    out: NDArray[np.float64] = (Linv_T @ y[..., :, None])[..., 0]
    return out
