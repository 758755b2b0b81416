r"""What a Jacobian says about a configuration: singular values, manipulability,
ellipsoids, singularities, null spaces.

All functions take a Jacobian, or a block of its rows, with shape (..., m, n)
(m task rows, n joints) and broadcast over the leading dimensions. The
singular value decomposition :math:`A = U\Sigma V^T` is the single tool:
the joint-rate ball :math:`\|\dot\theta\| \le 1` is mapped by A onto an
ellipsoid whose semi-axes are the singular values :math:`\sigma_i` along the
columns of U.

**Which rows?** Ellipsoids mix nothing: build them from rows of one kind,
angular rows (:func:`angular_rows`) or linear rows (:func:`linear_rows`).
For the velocity of the hand, take the linear rows of the *geometric* or
*body* Jacobian. The linear rows of the space Jacobian are
:math:`v_s`, the velocity of the (imaginary) body point at the origin of
{s}, not of the hand.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r(l1=1.0, l2=1.0)
>>> J_v = linear_rows(jac.geometric_jacobian(arm, [0.0, np.pi / 2]))[:2]
>>> round(float(manipulability(J_v)), 12)   # l1 l2 |sin theta2|
1.0

For convenience the inverse-velocity and statics helpers are re-exported
here: :func:`~jacobians.velocity.pinv_rates`,
:func:`~jacobians.velocity.dls_rates` and
:func:`~jacobians.statics.joint_torques`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_finite, positive_float
from .statics import joint_torques
from .velocity import dls_rates, pinv_rates

__all__ = [
    "singular_values",
    "manipulability",
    "condition_number",
    "isotropy",
    "linear_rows",
    "angular_rows",
    "velocity_ellipsoid",
    "force_ellipsoid",
    "is_singular",
    "singularity_measure",
    "nullspace",
    "nullspace_projector",
    "pinv_rates",
    "dls_rates",
    "joint_torques",
]


def _matrix(J: object, name: str = "J") -> NDArray[np.float64]:
    """A finite float array with at least two dimensions (..., m, n), m, n >= 1."""
    A = as_float_array(J, name)
    if A.ndim < 2:
        raise ValueError(
            f"Expected {name} with shape (..., m, n) (a matrix, or a batch of them), got shape {A.shape}; "
            "a single row must be passed as a 1 x n matrix"
        )
    if A.shape[-1] == 0 or A.shape[-2] == 0:
        raise ValueError(f"Expected {name} with at least one row and one column, got shape {A.shape}")
    return check_finite(A, name)


def _six_rows(J: object, name: str = "J") -> NDArray[np.float64]:
    A = _matrix(J, name)
    if A.shape[-2] != 6:
        hint = " (it looks transposed)" if A.shape[-1] == 6 else ""
        raise ValueError(f"Expected {name} with shape (..., 6, n), rows (omega, v), got shape {A.shape}{hint}")
    return A


def _rtol(value: object, A: NDArray[np.float64]) -> float:
    if value is None:
        return float(max(A.shape[-2:]) * np.finfo(float).eps)
    return positive_float(value, "rtol")


def singular_values(J: ArrayLike) -> NDArray[np.float64]:
    r"""Singular values :math:`\sigma_1 \ge \dots \ge \sigma_r \ge 0`, :math:`r = \min(m, n)`.

    Parameters
    ----------
    J : array_like, shape (..., m, n)

    Returns
    -------
    ndarray, shape (..., min(m, n)), in descending order

    >>> singular_values([[3.0, 0.0], [0.0, -4.0]])
    array([4., 3.])
    """
    return np.asarray(np.linalg.svd(_matrix(J), compute_uv=False), dtype=np.float64)


def manipulability(J: ArrayLike) -> NDArray[np.float64]:
    r"""Yoshikawa's manipulability :math:`w = \sqrt{\det(J J^T)} = \sigma_1\cdots\sigma_m`.

    The volume of the velocity ellipsoid, up to the volume of the unit ball.
    For m <= n (at least as many joints as task rows) this is Yoshikawa's
    measure, the product of the singular values, zero exactly at a singularity.
    For m > n, :math:`\det(JJ^T)` is always zero; this function then returns
    the product of the n singular values, :math:`\sqrt{\det(J^TJ)}`. Choose
    the rows that matter first (:func:`linear_rows`, or the x, y rows of a
    planar arm): the number depends on that choice. MR: :math:`\mu_3(A)
    = \sqrt{\lambda_1\cdots\lambda_m}` of Section 5.4 (eigenvalues of
    :math:`AA^T`); MR's code has no function for it.

    Parameters
    ----------
    J : array_like, shape (..., m, n)

    Returns
    -------
    ndarray, shape (...)

    >>> import numpy as np
    >>> round(float(manipulability([[1.0, 2.0], [3.0, 4.0]])), 12)   # |det| = 2
    2.0
    """
    w: NDArray[np.float64] = np.prod(singular_values(J), axis=-1)
    return w


def condition_number(J: ArrayLike) -> NDArray[np.float64]:
    r"""Condition number :math:`\kappa = \sigma_{\max} / \sigma_{\min}` (over the min(m, n) singular values).

    1 for an isotropic configuration; ``inf`` where :math:`\sigma_{\min} = 0`
    (including the zero matrix). Near a singularity it is large but finite:
    test singularity with :func:`is_singular`. MR: :math:`\mu_1 =
    \sqrt{\lambda_{\max}/\lambda_{\min}}` of Section 5.4 (eigenvalues of
    :math:`JJ^T`); MR's :math:`\mu_2` is its square.

    Returns
    -------
    ndarray, shape (...), in :math:`[1, \infty]`

    >>> float(condition_number([[2.0, 0.0], [0.0, 0.5]]))
    4.0
    """
    s = singular_values(J)
    big, small = s[..., 0], s[..., -1]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(small > 0, big / np.where(small > 0, small, 1.0), np.inf)


def isotropy(J: ArrayLike) -> NDArray[np.float64]:
    r"""Inverse condition number :math:`\sigma_{\min}/\sigma_{\max}` in [0, 1] (0 at a singularity and for J = 0).

    MR: :math:`1/\mu_1` (Section 5.4).

    >>> float(isotropy([[2.0, 0.0], [0.0, 0.5]]))
    0.25
    """
    s = singular_values(J)
    big, small = s[..., 0], s[..., -1]
    return np.where(big > 0, small / np.where(big > 0, big, 1.0), 0.0)


def linear_rows(J: ArrayLike) -> NDArray[np.float64]:
    r"""Rows 3:6 of a 6-row Jacobian (the v or :math:`\dot p` part; twists are angular first).

    Which linear rows you want depends on the Jacobian:

    * geometric Jacobian: :math:`\dot p`, the velocity of the origin of {b}
      expressed in {s} -- the hand's velocity, for the ellipsoid drawn at the hand;
    * body Jacobian: :math:`v_b`, the same velocity expressed in {b};
    * space Jacobian: :math:`v_s`, the velocity of the body point that is
      momentarily at the origin of {s}. This is **not** the hand's velocity;
      an ellipsoid built from it is wrong for the hand.

    MR: :math:`J_v` of Section 5.4, the linear block of :math:`J_b`.

    Parameters
    ----------
    J : array_like, shape (..., 6, n)

    Returns
    -------
    ndarray, shape (..., 3, n)

    >>> import jacobians as jac
    >>> linear_rows(jac.geometric_jacobian(jac.robots.planar_2r(), [0.0, 0.0]))
    array([[0., 0.],
           [2., 1.],
           [0., 0.]])
    """
    return _six_rows(J)[..., 3:6, :].copy()


def angular_rows(J: ArrayLike) -> NDArray[np.float64]:
    r"""Rows 0:3 of a 6-row Jacobian, the angular velocity part :math:`\omega`.

    The same for the space and geometric Jacobians (:math:`\omega_s`);
    :math:`\omega_b = R^T\omega_s` for the body Jacobian. MR: :math:`J_\omega`
    of Section 5.4.

    >>> import jacobians as jac
    >>> angular_rows(jac.space_jacobian(jac.robots.planar_2r(), [0.3, 0.2]))
    array([[0., 0.],
           [0., 0.],
           [1., 1.]])
    """
    return _six_rows(J)[..., 0:3, :].copy()


def velocity_ellipsoid(A: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    r"""The image of the unit ball of joint rates: semi-axes and their directions.

    With :math:`A = U\Sigma V^T`, the set :math:`\{A\dot\theta : \|\dot\theta\|\le 1\}`
    is the ellipsoid with semi-axis :math:`\sigma_i` along column i of U
    (MR Section 5.4, the manipulability ellipsoid, whose semi-axes are
    :math:`\sqrt{\lambda_i}` of :math:`AA^T`).

    Parameters
    ----------
    A : array_like, shape (..., k, n)
        Rows of one kind (:func:`linear_rows` of the geometric or body
        Jacobian, or :func:`angular_rows`), or the x, y rows of a planar arm.

    Returns
    -------
    semi_axes : ndarray, shape (..., k)
        In descending order; zero for the k - n directions A cannot reach
        when k > n (the ellipsoid is flat).
    directions : ndarray, shape (..., k, k)
        Orthonormal columns: column i is the direction of semi-axis i.

    >>> import numpy as np
    >>> axes, dirs = velocity_ellipsoid([[0.0, 1.0], [2.0, 0.0]])
    >>> axes
    array([2., 1.])
    >>> np.abs(dirs)
    array([[0., 1.],
           [1., 0.]])
    """
    A = _matrix(A, "A")
    k, n = A.shape[-2:]
    U, s, _ = np.linalg.svd(A, full_matrices=True)
    axes = np.zeros(A.shape[:-2] + (k,))
    axes[..., : min(k, n)] = s
    return axes, U


def force_ellipsoid(A: ArrayLike, rtol: float | None = None) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    r"""The wrenches (forces or moments) the joints can resist with :math:`\|\tau\|\le 1`.

    With :math:`\tau = A^T F` and :math:`A = U\Sigma V^T`, the set
    :math:`\{F : \|A^T F\| \le 1\}` has semi-axis :math:`1/\sigma_i` along
    column i of U: the same directions as :func:`velocity_ellipsoid`, with
    reciprocal lengths (MR Section 5.4, the force ellipsoid, :math:`(AA^T)^{-1}`).
    Where the arm moves easily it resists poorly, and the converse.

    **Singular directions.** Along a direction with :math:`\sigma_i = 0`
    (taken as :math:`\sigma_i \le \text{rtol}\,\sigma_{\max}`, and every
    direction of a zero matrix) any force is resisted with no torque: the
    ellipsoid is unbounded there and the semi-axis is reported as
    ``numpy.inf``. A plotting routine must clip or mark those axes.

    Parameters
    ----------
    A : array_like, shape (..., k, n)
        Rows of one kind, as for :func:`velocity_ellipsoid`.
    rtol : float, optional
        Relative threshold for a zero singular value; default
        ``max(k, n) * machine epsilon`` (as ``numpy.linalg.matrix_rank``).

    Returns
    -------
    semi_axes : ndarray, shape (..., k)
        :math:`1/\sigma_i`, in the order of :func:`velocity_ellipsoid`'s
        directions (so ascending), ``inf`` along singular directions.
    directions : ndarray, shape (..., k, k)
        Identical to :func:`velocity_ellipsoid`'s.

    >>> axes, dirs = force_ellipsoid([[0.0, 1.0], [2.0, 0.0]])
    >>> axes
    array([0.5, 1. ])
    >>> force_ellipsoid([[1.0, 1.0], [1.0, 1.0]])[0]
    array([0.5, inf])
    """
    A = _matrix(A, "A")
    tol = _rtol(rtol, A)
    axes, U = velocity_ellipsoid(A)
    smax = axes[..., :1]
    zero = axes <= tol * smax
    with np.errstate(divide="ignore"):
        inv = np.where(zero, np.inf, 1.0 / np.where(zero, 1.0, axes))
    return inv, U


def singularity_measure(J: ArrayLike) -> NDArray[np.float64]:
    r"""The smallest singular value :math:`\sigma_{\min}` (of the min(m, n)); zero at a singularity.

    MR: no function; Section 5.3 defines a singularity as a drop in the rank of J.

    >>> round(float(singularity_measure([[1.0, 1.0], [1.0, 1.0]])), 12)
    0.0
    """
    return singular_values(J)[..., -1]


def is_singular(J: ArrayLike, tol: float = 1e-8) -> NDArray[np.bool_]:
    r"""True where J loses rank: :math:`\sigma_{\min} \le \text{tol}\cdot\sigma_{\max}`.

    The test is relative, so it does not depend on the units of length.
    :math:`\sigma_{\min}` is the smallest of the min(m, n) singular values: a
    square J is singular when it is not invertible, a wide one (m < n,
    redundant) when its rank is below m (some task direction is lost), a tall
    one (m > n, e.g. the full 6 x n Jacobian of an arm with n < 6) when its
    rank is below n (some joint motion does nothing). The zero matrix is
    singular. MR: Section 5.3, kinematic singularities.

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    tol : float, positive
        Relative tolerance.

    Returns
    -------
    ndarray of bool, shape (...)

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> bool(is_singular(jac.geometric_jacobian(arm, [0.4, 0.0])[3:5]))   # arm stretched out
    True
    >>> is_singular(jac.geometric_jacobian(arm, [[0.4, 0.0], [0.4, 1.0]])[..., 3:5, :])
    array([ True, False])

    Choose the rows first: all six rows of the same stretched-out arm have
    rank 2 (the angular row still tells the joints apart), so the full
    Jacobian is not singular there.

    >>> bool(is_singular(jac.geometric_jacobian(arm, [0.4, 0.0])))
    False
    """
    tol = positive_float(tol, "tol")
    s = singular_values(J)
    return s[..., -1] <= tol * s[..., 0]


def nullspace(J: ArrayLike, rtol: float | None = None) -> NDArray[np.float64]:
    r"""An orthonormal basis of the null space of one matrix: joint rates that do not move the task.

    :math:`J\dot\theta = 0` for every column of the result. Its number of
    columns, n - rank J, changes with the configuration, so this function
    takes one matrix, not a batch; :func:`nullspace_projector` is batched.
    Redundancy resolution uses it. MR: no counterpart in MR's code.

    Parameters
    ----------
    J : array_like, shape (m, n)
    rtol : float, optional
        Singular values below ``rtol * sigma_max`` count as zero; default
        ``max(m, n) * machine epsilon``.

    Returns
    -------
    N : ndarray, shape (n, n - rank)

    >>> import numpy as np
    >>> N = nullspace([[1.0, 1.0, 0.0]])
    >>> N.shape
    (3, 2)
    >>> np.allclose(np.array([[1.0, 1.0, 0.0]]) @ N, 0)
    True
    """
    A = _matrix(J)
    if A.ndim != 2:
        raise ValueError(
            f"Expected one matrix with shape (m, n), got shape {A.shape}; the null space's size changes with "
            "the configuration, so loop over the batch, or use nullspace_projector (batched)"
        )
    tol = _rtol(rtol, A)
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    rank = int(np.sum(s > tol * s[0])) if s[0] > 0 else 0
    return Vt[rank:].T.copy()


def nullspace_projector(J: ArrayLike, rtol: float | None = None) -> NDArray[np.float64]:
    r"""The orthogonal projector :math:`I - J^\dagger J` onto the null space of J.

    :math:`J (I - J^\dagger J) = 0`; adding :math:`(I - J^\dagger J)z` to a
    joint rate changes the joint motion but not the task velocity.

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    rtol : float, optional
        As for :func:`nullspace`.

    Returns
    -------
    ndarray, shape (..., n, n)

    >>> P = nullspace_projector([[1.0, 0.0]])
    >>> P
    array([[0., 0.],
           [0., 1.]])
    """
    A = _matrix(J)
    tol = _rtol(rtol, A)
    _, s, Vt = np.linalg.svd(A, full_matrices=True)
    n = A.shape[-1]
    keep = np.zeros(A.shape[:-2] + (n,), dtype=bool)
    r = s.shape[-1]
    keep[..., :r] = s > tol * s[..., :1]
    V_range = Vt * keep[..., :, None]  # rows spanning the row space of J
    P: NDArray[np.float64] = np.eye(n) - np.swapaxes(V_range, -1, -2) @ V_range
    return P
