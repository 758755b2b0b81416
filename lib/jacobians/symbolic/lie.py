r"""SO(3) and SE(3) in sympy: the functions of :mod:`jacobians.lie`, same names and argument order.

The one difference: the exponentials take the unit axis and the angle as two
arguments, ``exp_so3(omega, theta)`` and ``exp_se3(screw, theta)``, where the
numeric ones take the product :math:`\hat\omega\theta` (a product of symbols
cannot be split back into an axis and an angle).

>>> import sympy as sp
>>> t = sp.Symbol("t")
>>> exp_se3([0, 0, 1, 0, -1, 0], t)[:2, 3].T   # about z through (1, 0, 0)
Matrix([[1 - cos(t), -sin(t)]])
"""

from __future__ import annotations

import sympy as sp

from ._checks import check_unit_axis, is_revolute, matrix, scalar, transform, vector
from .simplify import is_zero

__all__ = [
    "skew",
    "unskew",
    "exp_so3",
    "exp_se3",
    "twist_to_matrix",
    "matrix_to_twist",
    "make_transform",
    "inverse_transform",
    "adjoint",
    "ad",
    "rotation_about",
]


def skew(omega: object) -> sp.Matrix:
    r"""The skew-symmetric matrix :math:`[\omega]`, with :math:`[\omega]x = \omega\times x`. MR: ``VecToso3``.

    >>> skew([1, 2, 3])
    Matrix([
    [ 0, -3,  2],
    [ 3,  0, -1],
    [-2,  1,  0]])
    """
    x, y, z = vector(omega, "omega", 3)
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def unskew(W: object) -> sp.Matrix:
    r"""The vector :math:`\omega` of a skew-symmetric :math:`[\omega]` (checked with :func:`is_zero`). MR: ``so3ToVec``.

    >>> unskew(skew([1, 2, 3])).T
    Matrix([[1, 2, 3]])
    """
    A = matrix(W, "W", (3, 3))
    if not all(is_zero(e) for e in A + A.T):
        raise ValueError("Expected W to be a skew-symmetric 3 x 3 matrix [w], got a matrix that is not skew-symmetric")
    return sp.Matrix([A[2, 1], A[0, 2], A[1, 0]])


def exp_so3(omega: object, theta: object) -> sp.Matrix:
    r"""Rodrigues' formula :math:`e^{[\hat\omega]\theta} = I + \sin\theta\,[\hat\omega] + (1-\cos\theta)[\hat\omega]^2`.

    MR: ``MatrixExp3``; numeric twin :func:`jacobians.lie.exp_so3`, which takes
    the product :math:`\hat\omega\theta`.

    Parameters
    ----------
    omega : 3 entries, or the 3 x 3 skew-symmetric :math:`[\hat\omega]`
        The unit rotation axis. Numeric axes are checked to be unit length; a
        symbolic axis is assumed to be.
    theta : number or sympy expression

    >>> t = sp.Symbol("t")
    >>> exp_so3([0, 0, 1], t)
    Matrix([
    [cos(t), -sin(t), 0],
    [sin(t),  cos(t), 0],
    [     0,       0, 1]])
    """
    A = matrix(omega, "omega")
    if A.shape == (3, 3):
        W = skew(unskew(A))
    elif A.shape in ((3, 1), (1, 3)):
        W = skew(A)
    else:
        raise ValueError(f"Expected omega as 3 entries or a 3 x 3 skew-symmetric matrix, got shape {A.shape}")
    angle = scalar(theta, "theta")
    check_unit_axis(unskew(W), "omega")
    return sp.eye(3) + sp.sin(angle) * W + (1 - sp.cos(angle)) * W * W


def exp_se3(screw: object, theta: object) -> sp.Matrix:
    r"""The transform :math:`e^{[\mathcal S]\theta}` of a screw axis :math:`\mathcal S = (\omega, v)`.

    Closed form (MR Prop. 3.25): for :math:`\|\omega\| = 1`,

    .. math:: e^{[\mathcal S]\theta} = \begin{bmatrix} e^{[\omega]\theta} & G(\theta) v\\ 0 & 1\end{bmatrix},\quad
              G(\theta) = I\theta + (1-\cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2;

    for :math:`\omega = 0` the rotation is I and the translation :math:`v\theta`.
    MR: ``MatrixExp6``; numeric twin :func:`jacobians.lie.exp_se3`, which takes
    the product :math:`\mathcal S\theta`.

    Parameters
    ----------
    screw : 6 entries
        Numeric entries are checked (unit :math:`\omega`, or :math:`\omega = 0`
        and unit :math:`v`); symbolic entries are assumed to satisfy this.
    theta : number or sympy expression

    >>> t, l = sp.symbols("t l")
    >>> exp_se3([0, 0, 1, 0, -l, 0], t)   # about z through (l, 0, 0)
    Matrix([
    [cos(t), -sin(t), 0, -l*cos(t) + l],
    [sin(t),  cos(t), 0,     -l*sin(t)],
    [     0,       0, 1,             0],
    [     0,       0, 0,             1]])
    """
    S = vector(screw, "screw", 6)
    angle = scalar(theta, "theta")
    w, v = S[:3, 0], S[3:, 0]
    T = sp.eye(4)
    if not is_revolute(w, v, "screw"):
        T[:3, 3] = v * angle
        return T
    W = skew(w)
    W2 = W * W
    T[:3, :3] = sp.eye(3) + sp.sin(angle) * W + (1 - sp.cos(angle)) * W2
    G = sp.eye(3) * angle + (1 - sp.cos(angle)) * W + (angle - sp.sin(angle)) * W2
    T[:3, 3] = (G * v).applyfunc(sp.expand)
    return T


def twist_to_matrix(twist: object) -> sp.Matrix:
    r"""The se(3) matrix :math:`[\mathcal V] = \begin{bmatrix}[\omega] & v\\ 0 & 0\end{bmatrix}` of a twist.

    MR: ``VecTose3``.

    >>> twist_to_matrix([0, 0, 1, 2, 0, 0])
    Matrix([
    [0, -1, 0, 2],
    [1,  0, 0, 0],
    [0,  0, 0, 0],
    [0,  0, 0, 0]])
    """
    V = vector(twist, "twist", 6)
    out = sp.zeros(4, 4)
    out[:3, :3] = skew(V[:3, 0])
    out[:3, 3] = V[3:, 0]
    return out


def matrix_to_twist(M: object) -> sp.Matrix:
    r"""The twist :math:`(\omega, v)` of an se(3) matrix :math:`[\mathcal V]`, a 6 x 1 matrix. MR: ``se3ToVec``.

    The upper-left block must be skew-symmetric and the last row zero (checked with :func:`is_zero`).

    >>> matrix_to_twist(twist_to_matrix([1, 2, 3, 4, 5, 6])).T
    Matrix([[1, 2, 3, 4, 5, 6]])
    """
    A = matrix(M, "M", (4, 4))
    W = A[:3, :3]
    if not all(is_zero(e) for e in W + W.T):
        raise ValueError("Expected M in se(3): its upper-left 3 x 3 block must be skew-symmetric")
    if not all(is_zero(e) for e in A[3, :]):
        raise ValueError(f"Expected M in se(3) with a zero last row, got {list(A[3, :])}")
    return sp.Matrix([W[2, 1], W[0, 2], W[1, 0], A[0, 3], A[1, 3], A[2, 3]])


def make_transform(R: object, p: object) -> sp.Matrix:
    """The transform with rotation ``R`` (3 x 3) and translation ``p`` (3 entries). MR: ``RpToTrans``.

    The rotation is not checked to be orthogonal (a symbolic one rarely simplifies to it cheaply).

    >>> make_transform(sp.eye(3), [1, 2, 3])[:, 3].T
    Matrix([[1, 2, 3, 1]])
    """
    T = sp.eye(4)
    T[:3, :3] = matrix(R, "R", (3, 3))
    T[:3, 3] = vector(p, "p", 3)
    return T


def inverse_transform(T: object) -> sp.Matrix:
    r""":math:`T^{-1} = \begin{bmatrix} R^T & -R^T p\\ 0 & 1\end{bmatrix}` (no matrix inversion). MR: ``TransInv``.

    >>> t = sp.Symbol("t")
    >>> T = exp_se3([0, 0, 1, 0, -1, 0], t)
    >>> (inverse_transform(T) * T).applyfunc(sp.trigsimp) == sp.eye(4)
    True
    """
    A = transform(T)
    R, p = A[:3, :3], A[:3, 3]
    return make_transform(R.T, -(R.T * p))


def adjoint(T: object) -> sp.Matrix:
    r"""The 6 x 6 adjoint :math:`[\mathrm{Ad}_T] = \begin{bmatrix} R & 0\\ [p]R & R\end{bmatrix}`. MR: ``Adjoint``.

    >>> T = sp.Matrix([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> (adjoint(T) * sp.Matrix([0, 0, 1, 0, 0, 0])).T   # a z axis seen from 1 m along x
    Matrix([[0, 0, 1, 0, -1, 0]])
    """
    A = transform(T)
    R, p = A[:3, :3], A[:3, 3]
    Ad = sp.zeros(6, 6)
    Ad[:3, :3] = R
    Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) * R
    return Ad


def ad(twist: object) -> sp.Matrix:
    r"""Small adjoint :math:`[\mathrm{ad}_{\mathcal V}] = \begin{bmatrix}[\omega] & 0\\ [v] & [\omega]\end{bmatrix}`.

    MR: ``ad``.

    >>> ad([0, 0, 1, 0, 0, 0])[:3, :3]
    Matrix([
    [0, -1, 0],
    [1,  0, 0],
    [0,  0, 0]])
    """
    V = vector(twist, "twist", 6)
    W = skew(V[:3, 0])
    out = sp.zeros(6, 6)
    out[:3, :3] = W
    out[3:, 3:] = W
    out[3:, :3] = skew(V[3:, 0])
    return out


def rotation_about(axis: str, angle: object) -> sp.Matrix:
    """Rotation about the coordinate axis ``"x"``, ``"y"`` or ``"z"`` by ``angle``.

    >>> rotation_about("z", sp.Symbol("a"))
    Matrix([
    [cos(a), -sin(a), 0],
    [sin(a),  cos(a), 0],
    [     0,       0, 1]])
    """
    if axis not in ("x", "y", "z"):
        raise ValueError(f"Expected axis 'x', 'y' or 'z', got {axis!r}")
    e = sp.zeros(3, 1)
    e["xyz".index(axis)] = 1
    return exp_so3(e, angle)
