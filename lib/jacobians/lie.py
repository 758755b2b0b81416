r"""Rotations, rigid transforms, twists and the adjoint map.

Conventions of Modern Robotics: a twist is :math:`\mathcal V = (\omega, v)`,
angular part first; :math:`[\mathcal V] = \begin{bmatrix}[\omega] & v\\ 0 & 0\end{bmatrix}`;
a transform is :math:`T = \begin{bmatrix} R & p\\ 0 & 1\end{bmatrix}`.

Every function broadcasts over leading dimensions: ``skew`` of an array with
shape ``(..., 3)`` returns shape ``(..., 3, 3)``, and so on.

>>> import numpy as np
>>> from jacobians import lie
>>> T = lie.exp_se3([0, 0, np.pi / 2, 1, 0, 0])
>>> np.round(T, 3)
array([[ 0.   , -1.   ,  0.   ,  0.637],
       [ 1.   ,  0.   ,  0.   ,  0.637],
       [ 0.   ,  0.   ,  1.   ,  0.   ],
       [ 0.   ,  0.   ,  0.   ,  1.   ]])
>>> np.allclose(lie.log_se3(T), [0, 0, np.pi / 2, 1, 0, 0])
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import real_array, rotation_array, transform_array

__all__ = [
    "skew",
    "unskew",
    "exp_so3",
    "log_so3",
    "exp_se3",
    "log_se3",
    "twist_to_matrix",
    "matrix_to_twist",
    "make_transform",
    "inverse_transform",
    "adjoint",
    "ad",
    "rotation_about",
    "left_jacobian_so3",
    "left_jacobian_so3_inverse",
]

_SMALL = 1e-4  # below this angle the series expansions are used


def _skew(w: NDArray[np.float64]) -> NDArray[np.float64]:
    x, y, z = w[..., 0], w[..., 1], w[..., 2]
    zero = np.zeros_like(x)
    return np.stack(
        [np.stack([zero, -z, y], -1), np.stack([z, zero, -x], -1), np.stack([-y, x, zero], -1)], -2
    )


def skew(omega: ArrayLike) -> NDArray[np.float64]:
    r"""The skew-symmetric matrix :math:`[\omega]` with :math:`[\omega] x = \omega \times x`.

    MR: ``VecToso3``.

    Parameters
    ----------
    omega : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    >>> skew([1, 2, 3])
    array([[ 0., -3.,  2.],
           [ 3.,  0., -1.],
           [-2.,  1.,  0.]])
    """
    return _skew(real_array(omega, "omega", (3,)))


def unskew(W: ArrayLike) -> NDArray[np.float64]:
    r"""The vector :math:`\omega` of a skew-symmetric matrix :math:`[\omega]`. MR: ``so3ToVec``.

    Only the skew-symmetric part of ``W`` is used.

    >>> unskew([[0, -3, 2], [3, 0, -1], [-2, 1, 0]])
    array([1., 2., 3.])
    """
    W = real_array(W, "W", (3, 3))
    return _unskew(W)


def _unskew(W: NDArray[np.float64]) -> NDArray[np.float64]:
    return 0.5 * np.stack(
        [W[..., 2, 1] - W[..., 1, 2], W[..., 0, 2] - W[..., 2, 0], W[..., 1, 0] - W[..., 0, 1]], -1
    )


def _coefficients(
    theta: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A = sin t / t, B = (1 - cos t) / t^2, C = (t - sin t) / t^3, stable near 0."""
    t2 = theta * theta
    small = theta < _SMALL
    safe = np.where(small, 1.0, theta)
    s, c = np.sin(safe), np.cos(safe)
    A = np.where(small, 1.0 - t2 / 6.0, s / safe)
    B = np.where(small, 0.5 - t2 / 24.0, (1.0 - c) / (safe * safe))
    C = np.where(small, 1.0 / 6.0 - t2 / 120.0, (safe - s) / (safe * safe * safe))
    return A, B, C


def _exp_so3(w: NDArray[np.float64]) -> NDArray[np.float64]:
    theta = np.linalg.norm(w, axis=-1)
    A, B, _ = _coefficients(theta)
    K = _skew(w)
    return np.eye(3) + A[..., None, None] * K + B[..., None, None] * (K @ K)


def exp_so3(omega_theta: ArrayLike) -> NDArray[np.float64]:
    r"""Rotation :math:`e^{[\hat\omega]\theta}` from exponential coordinates :math:`\hat\omega\theta`.

    Rodrigues' formula. MR: ``MatrixExp3`` (which takes the matrix ``[ω]θ``).

    Parameters
    ----------
    omega_theta : array_like, shape (..., 3)

    Returns
    -------
    R : ndarray, shape (..., 3, 3)

    >>> np.round(exp_so3([0, 0, np.pi / 2]), 6) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    return _exp_so3(real_array(omega_theta, "omega_theta", (3,)))


def _log_so3(R: NDArray[np.float64]) -> NDArray[np.float64]:
    a = _unskew(R)  # = sin(theta) * omega_hat
    s: NDArray[np.float64] = np.linalg.norm(a, axis=-1)
    c: NDArray[np.float64] = 0.5 * (np.trace(R, axis1=-2, axis2=-1) - 1.0)
    theta = np.arctan2(s, c)
    # Regular branch: omega_theta = a * theta / sin(theta)
    small = theta < _SMALL
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.where(small, 1.0 + theta * theta / 6.0, theta / np.where(s == 0, 1.0, s))
    out = a * factor[..., None]
    # Near pi: sin(theta) is tiny and carries no direction; use the symmetric part.
    near_pi = c < -0.99
    if np.any(near_pi):
        Rn = R[near_pi]
        cn = c[near_pi]
        sym = 0.5 * (Rn + np.swapaxes(Rn, -1, -2)) - cn[:, None, None] * np.eye(3)
        sym = sym / (1.0 - cn)[:, None, None]  # = omega_hat omega_hat^T
        diag = np.diagonal(sym, axis1=-2, axis2=-1)
        k = np.argmax(diag, axis=-1)
        col = np.take_along_axis(sym, k[:, None, None], axis=-1)[..., 0]
        w_hat = col / np.linalg.norm(col, axis=-1, keepdims=True)
        sign = np.sign(np.sum(w_hat * a[near_pi], axis=-1))
        sign = np.where(sign == 0, 1.0, sign)
        out[near_pi] = w_hat * (sign * theta[near_pi])[:, None]
    return out


def log_so3(R: ArrayLike) -> NDArray[np.float64]:
    r"""Exponential coordinates :math:`\hat\omega\theta` of a rotation, with :math:`\theta \in [0, \pi]`.

    MR: ``MatrixLog3`` (which returns the matrix ``[ω]θ``). At :math:`\theta = \pi`
    both :math:`\pm\hat\omega\pi` describe ``R``; one of them is returned.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3), rotation matrices

    Returns
    -------
    ndarray, shape (..., 3)

    >>> log_so3(exp_so3([0.1, -0.2, 0.3])).round(12)
    array([ 0.1, -0.2,  0.3])
    """
    return _log_so3(rotation_array(R, "R"))


def _exp_se3(xi: NDArray[np.float64]) -> NDArray[np.float64]:
    w, v = xi[..., :3], xi[..., 3:]
    theta = np.linalg.norm(w, axis=-1)
    A, B, C = _coefficients(theta)
    K = _skew(w)
    K2 = K @ K
    R = np.eye(3) + A[..., None, None] * K + B[..., None, None] * K2
    G = np.eye(3) + B[..., None, None] * K + C[..., None, None] * K2
    T = np.zeros(xi.shape[:-1] + (4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = (G @ v[..., None])[..., 0]
    T[..., 3, 3] = 1.0
    return T


def exp_se3(twist_theta: ArrayLike) -> NDArray[np.float64]:
    r"""The transform :math:`e^{[\mathcal S]\theta}` from the 6-vector :math:`\mathcal S\theta`.

    MR: ``MatrixExp6`` (which takes the matrix ``[S]θ``). Works for any twist,
    including a pure translation (:math:`\omega = 0`).

    Parameters
    ----------
    twist_theta : array_like, shape (..., 6), ordered (ω, v)

    Returns
    -------
    T : ndarray, shape (..., 4, 4)

    >>> exp_se3([0, 0, 0, 1, 2, 3])[:3, 3]
    array([1., 2., 3.])
    """
    return _exp_se3(real_array(twist_theta, "twist_theta", (6,)))


def _gamma(theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """(1/t^2) (1 - (t/2) cot(t/2)), the [w]^2 coefficient of the inverse left Jacobian."""
    small = theta < _SMALL
    safe = np.where(small, 1.0, theta)
    half = 0.5 * safe
    return np.where(
        small, 1.0 / 12.0 + theta * theta / 720.0, (1.0 - half * np.cos(half) / np.sin(half)) / (safe * safe)
    )


def log_se3(T: ArrayLike) -> NDArray[np.float64]:
    r"""The 6-vector :math:`\mathcal S\theta` with :math:`e^{[\mathcal S]\theta} = T`.

    MR: ``MatrixLog6`` (which returns the matrix ``[S]θ``).

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)

    Returns
    -------
    ndarray, shape (..., 6)
    """
    T = transform_array(T, "T")
    w = _log_so3(T[..., :3, :3])
    theta = np.linalg.norm(w, axis=-1)
    K = _skew(w)
    Ginv = np.eye(3) - 0.5 * K + _gamma(theta)[..., None, None] * (K @ K)
    v = (Ginv @ T[..., :3, 3:4])[..., 0]
    return np.concatenate([w, v], axis=-1)


def twist_to_matrix(twist: ArrayLike) -> NDArray[np.float64]:
    r"""The 4x4 matrix :math:`[\mathcal V]` of a twist. MR: ``VecTose3``."""
    V = real_array(twist, "twist", (6,))
    out = np.zeros(V.shape[:-1] + (4, 4))
    out[..., :3, :3] = _skew(V[..., :3])
    out[..., :3, 3] = V[..., 3:]
    return out


def matrix_to_twist(M: ArrayLike) -> NDArray[np.float64]:
    r"""The twist :math:`\mathcal V` of a 4x4 matrix :math:`[\mathcal V]` in se(3). MR: ``se3ToVec``.

    Raises ``ValueError`` if ``M`` is not in se(3) (skew-symmetric top-left block,
    zero last row).
    """
    M = real_array(M, "M", (4, 4))
    top = M[..., :3, :3]
    scale = max(1.0, float(np.abs(M).max(initial=0.0)))
    asymmetry = np.abs(top + np.swapaxes(top, -1, -2)).max(initial=0.0)
    if asymmetry > 1e-6 * scale or np.abs(M[..., 3, :]).max(initial=0.0) > 1e-6 * scale:
        raise ValueError("Expected a matrix in se(3): skew-symmetric 3x3 block and a zero last row")
    return np.concatenate([_unskew(top), M[..., :3, 3]], axis=-1)


def make_transform(R: ArrayLike, p: ArrayLike) -> NDArray[np.float64]:
    """The transform with rotation ``R`` (..., 3, 3) and translation ``p`` (..., 3). MR: ``RpToTrans``.

    >>> make_transform(np.eye(3), [1, 2, 3])[:, 3]
    array([1., 2., 3., 1.])
    """
    R = rotation_array(R, "R")
    p = real_array(p, "p", (3,))
    shape = np.broadcast_shapes(R.shape[:-2], p.shape[:-1])
    T = np.zeros(shape + (4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = p
    T[..., 3, 3] = 1.0
    return T


def _inverse_transform(T: NDArray[np.float64]) -> NDArray[np.float64]:
    Rt = np.swapaxes(T[..., :3, :3], -1, -2)
    out = np.zeros_like(T)
    out[..., :3, :3] = Rt
    out[..., :3, 3] = -(Rt @ T[..., :3, 3:4])[..., 0]
    out[..., 3, 3] = 1.0
    return out


def inverse_transform(T: ArrayLike) -> NDArray[np.float64]:
    r"""The inverse :math:`T^{-1} = \begin{bmatrix}R^T & -R^Tp\\0&1\end{bmatrix}`. MR: ``TransInv``.

    >>> T = exp_se3([0.3, 0.2, 0.1, 1, 2, 3])
    >>> np.allclose(inverse_transform(T) @ T, np.eye(4))
    True
    """
    return _inverse_transform(transform_array(T, "T"))


def _adjoint(T: NDArray[np.float64]) -> NDArray[np.float64]:
    R = T[..., :3, :3]
    P = _skew(T[..., :3, 3])
    out = np.zeros(T.shape[:-2] + (6, 6))
    out[..., :3, :3] = R
    out[..., 3:, 3:] = R
    out[..., 3:, :3] = P @ R
    return out


def adjoint(T: ArrayLike) -> NDArray[np.float64]:
    r"""The adjoint map :math:`[\mathrm{Ad}_T] = \begin{bmatrix}R & 0\\ [p]R & R\end{bmatrix}`.

    It maps a twist expressed in frame {b} to the same twist expressed in {a}
    when ``T = T_ab``: :math:`\mathcal V_a = [\mathrm{Ad}_{T_{ab}}]\mathcal V_b`.
    MR: ``Adjoint``.

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)

    Returns
    -------
    ndarray, shape (..., 6, 6)

    >>> A = adjoint(exp_se3([0, 0, 0, 1, 0, 0]))
    >>> A[3:, :3]
    array([[ 0.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    """
    return _adjoint(transform_array(T, "T"))


def ad(twist: ArrayLike) -> NDArray[np.float64]:
    r"""The small adjoint :math:`[\mathrm{ad}_{\mathcal V}]
    = \begin{bmatrix}[\omega] & 0\\ [v] & [\omega]\end{bmatrix}`.

    :math:`[\mathrm{ad}_{\mathcal V_1}]\mathcal V_2` is the Lie bracket of two twists. MR: ``ad``.

    >>> ad([0, 0, 1, 0, 0, 0])[:3, :3] + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  0.]])
    """
    V = real_array(twist, "twist", (6,))
    W = _skew(V[..., :3])
    out = np.zeros(V.shape[:-1] + (6, 6))
    out[..., :3, :3] = W
    out[..., 3:, 3:] = W
    out[..., 3:, :3] = _skew(V[..., 3:])
    return out


def rotation_about(axis: str, angle: ArrayLike) -> NDArray[np.float64]:
    """Rotation about the coordinate axis ``"x"``, ``"y"`` or ``"z"`` by ``angle`` (radians, broadcasts).

    >>> rotation_about("z", np.pi / 2).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    if axis not in ("x", "y", "z"):
        raise ValueError(f"Expected axis 'x', 'y' or 'z', got {axis!r}")
    a = real_array(angle, "angle", ())
    c, s = np.cos(a), np.sin(a)
    one, zero = np.ones_like(a), np.zeros_like(a)
    rows = {
        "x": [[one, zero, zero], [zero, c, -s], [zero, s, c]],
        "y": [[c, zero, s], [zero, one, zero], [-s, zero, c]],
        "z": [[c, -s, zero], [s, c, zero], [zero, zero, one]],
    }[axis]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def left_jacobian_so3(omega_theta: ArrayLike) -> NDArray[np.float64]:
    r"""Left Jacobian of SO(3): :math:`\omega_s = J_l(r)\,\dot r` for :math:`R = e^{[r]}`.

    :math:`J_l(r) = I + \frac{1-\cos\theta}{\theta^2}[r] + \frac{\theta-\sin\theta}{\theta^3}[r]^2`,
    :math:`\theta = \|r\|`. It maps the rate of exponential coordinates to the
    angular velocity expressed in the fixed frame.
    """
    r = real_array(omega_theta, "omega_theta", (3,))
    theta = np.linalg.norm(r, axis=-1)
    _, B, C = _coefficients(theta)
    K = _skew(r)
    return np.eye(3) + B[..., None, None] * K + C[..., None, None] * (K @ K)


def left_jacobian_so3_inverse(omega_theta: ArrayLike) -> NDArray[np.float64]:
    r"""Inverse of :func:`left_jacobian_so3`: :math:`I - \tfrac12[r] + \gamma(\theta)[r]^2`.

    :math:`\gamma(\theta) = \frac{1}{\theta^2}\left(1 - \frac{\theta}{2}\cot\frac{\theta}{2}\right)`;
    finite for :math:`\theta < 2\pi`.
    """
    r = real_array(omega_theta, "omega_theta", (3,))
    theta = np.linalg.norm(r, axis=-1)
    K = _skew(r)
    return np.eye(3) - 0.5 * K + _gamma(theta)[..., None, None] * (K @ K)
