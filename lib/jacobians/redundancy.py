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
from .velocity import pinv_rates

__all__ = ["manipulability_gradient", "redundant_rates"]


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
