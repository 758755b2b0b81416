r"""Symbolic Jacobians with sympy, in the conventions of Modern Robotics.

The same objects as the numeric library (product-of-exponentials forward
kinematics, space, body and geometric Jacobians), built as sympy matrices of
joint symbols and link lengths, so a chapter can show the closed form and a
test can check it against the numbers. Twists are angular first,
:math:`\mathcal V = (\omega, v)`; screw axes are the columns of a 6 x n matrix.

Every function takes sympy matrices (or anything :class:`sympy.Matrix`
accepts: nested lists, numpy arrays) and returns a ``sympy.Matrix``. Strings
are refused: nothing here parses text.

The kinematics functions (:func:`fk`, :func:`space_jacobian`,
:func:`body_jacobian`, :func:`geometric_jacobian`, :func:`link_jacobian`)
simplify as they multiply (``simplify=True``, the default), which is both
faster and more readable than simplifying the expanded product at the end;
``simplify=False`` gives the raw expanded products.

This module imports sympy; ``import jacobians`` does not import it.

>>> import sympy as sp
>>> from jacobians import symbolic as sym
>>> arm, (t1, t2), (l1, l2) = sym.planar_chain(2)
>>> J_s = sym.space_jacobian(arm.screw_axes, [t1, t2])
>>> J_s[3:5, :]
Matrix([
[0,  l1*sin(theta1)],
[0, -l1*cos(theta1)]])
>>> sym.space_jacobian(arm.screw_axes, [t1, t2], simplify=False) == J_s   # already in simplest form here
True
"""

from __future__ import annotations

import numbers

import numpy as np
import sympy as sp
from sympy.simplify.fu import TR10i as _TR10i

__all__ = [
    "SymbolicChain",
    "skew",
    "exp_so3",
    "exp_se3",
    "adjoint",
    "inverse_transform",
    "twist_from_matrix",
    "matrix_from_twist",
    "fk",
    "space_jacobian",
    "body_jacobian",
    "geometric_jacobian",
    "link_jacobian",
    "planar_chain",
    "simplify_matrix",
    "lambdify_matrix",
    "to_numeric_chain",
]


# ---------------------------------------------------------------- validation

def _describe(value) -> str:
    if isinstance(value, sp.MatrixBase):
        return f"sympy Matrix with shape {value.shape}"
    if isinstance(value, np.ndarray):
        return f"array with shape {value.shape} and dtype {value.dtype}"
    if isinstance(value, (list, tuple)):
        return f"{type(value).__name__} of length {len(value)}"
    return f"{type(value).__name__} {value!r}"[:120]


def _scalar(value, name: str) -> sp.Expr:
    """A sympy expression from a number or a sympy object; never parses strings."""
    if isinstance(value, (str, bytes)) or value is None or isinstance(value, bool):
        raise TypeError(f"Expected a number or a sympy expression for {name}, got {_describe(value)}")
    if isinstance(value, sp.Basic):
        if not isinstance(value, sp.Expr):
            raise TypeError(f"Expected a sympy expression for {name}, got {_describe(value)}")
        return value
    if isinstance(value, numbers.Number) or isinstance(value, np.generic):
        if isinstance(value, (complex, np.complexfloating)):
            raise TypeError(f"Expected a real number for {name}, got {value!r}")
        if isinstance(value, (float, np.floating)) and not np.isfinite(value):
            raise ValueError(f"Expected a finite number for {name}, got {value!r}")
        return sp.sympify(value)
    raise TypeError(f"Expected a number or a sympy expression for {name}, got {_describe(value)}")


def _matrix(value, name: str, shape: tuple | None = None) -> sp.Matrix:
    """A mutable sympy Matrix with checked shape (``None`` entries match any size)."""
    if isinstance(value, (str, bytes)) or value is None or isinstance(value, (bool, numbers.Number)):
        raise TypeError(f"Expected a sympy Matrix (or nested list) for {name}, got {_describe(value)}")
    if isinstance(value, sp.MatrixBase):
        A = sp.Matrix(value)
    else:
        if isinstance(value, np.ndarray) and value.dtype.kind == "c":
            raise TypeError(f"Expected real entries for {name}, got a complex array")
        try:
            A = sp.Matrix(value)
        except Exception as exc:  # sympy raises several types for ragged input
            raise TypeError(f"Expected a sympy Matrix (or nested list) for {name}, got {_describe(value)} ({exc})") from None
    for entry in A:
        _scalar(entry, f"an entry of {name}")
    if shape is not None:
        ok = len(shape) == 2 and all(s is None or s == h for s, h in zip(shape, A.shape))
        if not ok:
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
            raise ValueError(f"Expected {name} with shape {want}, got shape {A.shape}")
    return A


def _vector(value, name: str, length: int) -> sp.Matrix:
    """A column vector of the given length from a list, a row or a column."""
    A = _matrix(value, name)
    if A.shape == (1, length):
        A = A.T
    if A.shape != (length, 1):
        raise ValueError(f"Expected {name} with {length} entries (a list, a row or a column), got shape {A.shape}")
    return A


def _thetas(thetas, n: int, name: str = "thetas") -> list:
    if isinstance(thetas, (str, bytes)) or thetas is None:
        raise TypeError(f"Expected a sequence of {n} joint symbols or values for {name}, got {_describe(thetas)}")
    if isinstance(thetas, sp.MatrixBase):
        items = list(thetas)
    elif isinstance(thetas, (list, tuple, np.ndarray)):
        items = list(np.asarray(thetas, dtype=object).ravel()) if isinstance(thetas, np.ndarray) else list(thetas)
    elif n == 1 and (isinstance(thetas, sp.Expr) or isinstance(thetas, numbers.Number)):
        items = [thetas]
    else:
        raise TypeError(f"Expected a sequence of {n} joint symbols or values for {name}, got {_describe(thetas)}")
    if len(items) != n:
        raise ValueError(f"Expected {n} joint variables in {name} (one per screw axis), got {len(items)}")
    return [_scalar(t, f"{name}[{i}]") for i, t in enumerate(items)]


def _not_one(expr) -> bool:
    """True when a squared norm is a number that is not 1 (to 1e-9); symbolic ones are taken as 1."""
    if expr.free_symbols:
        return False
    try:
        value = complex(expr.evalf())
    except (TypeError, ValueError):  # pragma: no cover - not a number after all
        return False
    return abs(value - 1) > 1e-9


def _check_unit_or_zero_omega(w: sp.Matrix, v: sp.Matrix, name: str) -> bool:
    """Return True for a revolute/screw axis (|omega| = 1), False for prismatic (omega = 0).

    Symbolic entries that sympy cannot decide are taken as a unit axis (the
    caller's responsibility, stated in the docstrings).
    """
    if all(e.is_zero for e in w):
        nv = sum(e**2 for e in v)
        if _not_one(nv):
            raise ValueError(f"Expected {name} with omega = 0 to have a unit linear part, got |v|^2 = {nv}")
        return False
    nw = sum(e**2 for e in w)
    if _not_one(nw):
        raise ValueError(
            f"Expected {name} to have a unit angular part (|omega| = 1) or omega = 0, got |omega|^2 = {nw}; "
            "normalise the axis and scale theta instead"
        )
    return True


# ---------------------------------------------------------------- Lie-group helpers

def skew(w) -> sp.Matrix:
    r"""The skew-symmetric matrix :math:`[\omega]`, with :math:`[\omega]x = \omega\times x`. MR: ``VecToso3``.

    Parameters
    ----------
    w : sympy Matrix or sequence, 3 entries

    Returns
    -------
    sympy.Matrix, shape (3, 3)

    >>> import sympy as sp
    >>> skew([1, 2, 3])
    Matrix([
    [ 0, -3,  2],
    [ 3,  0, -1],
    [-2,  1,  0]])
    """
    x, y, z = _vector(w, "w", 3)
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def _unskew(W: sp.Matrix) -> sp.Matrix:
    return sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])


def exp_so3(w_hat, theta) -> sp.Matrix:
    r"""Rodrigues' formula :math:`e^{[\hat\omega]\theta} = I + \sin\theta\,[\hat\omega] + (1-\cos\theta)[\hat\omega]^2`.

    MR: ``MatrixExp3`` (which takes :math:`[\hat\omega]\theta` instead).

    Parameters
    ----------
    w_hat : sympy Matrix, shape (3, 3) skew-symmetric, or 3 entries
        The unit rotation axis, as :math:`[\hat\omega]` or as the vector :math:`\hat\omega`.
        Numeric axes are checked to be unit length; a symbolic axis is assumed to be.
    theta : number or sympy expression
        Rotation angle.

    Returns
    -------
    R : sympy.Matrix, shape (3, 3)

    >>> import sympy as sp
    >>> t = sp.Symbol("t")
    >>> exp_so3([0, 0, 1], t)
    Matrix([
    [cos(t), -sin(t), 0],
    [sin(t),  cos(t), 0],
    [     0,       0, 1]])
    """
    A = _matrix(w_hat, "w_hat")
    if A.shape == (3, 3):
        if any(not (A[i, j] + A[j, i]).is_zero and sp.simplify(A[i, j] + A[j, i]) != 0
               for i in range(3) for j in range(i, 3)):
            raise ValueError("Expected w_hat to be a skew-symmetric 3 x 3 matrix [w], got a matrix that is not skew-symmetric")
        W = A
    elif A.shape in ((3, 1), (1, 3)):
        W = skew(A)
    else:
        raise ValueError(f"Expected w_hat as a 3 x 3 skew-symmetric matrix or 3 entries, got shape {A.shape}")
    theta = _scalar(theta, "theta")
    w = _unskew(W)
    nw = sum(e**2 for e in w)
    if _not_one(nw):
        raise ValueError(f"Expected a unit rotation axis, got |w|^2 = {nw}; normalise it and scale theta instead")
    return sp.eye(3) + sp.sin(theta) * W + (1 - sp.cos(theta)) * W * W


def exp_se3(S_col, theta) -> sp.Matrix:
    r"""The transform :math:`e^{[\mathcal S]\theta}` of a screw axis :math:`\mathcal S = (\omega, v)`.

    Closed form (MR Prop. 3.25): for :math:`\|\omega\| = 1`,

    .. math:: e^{[\mathcal S]\theta} = \begin{bmatrix} e^{[\omega]\theta} & G(\theta) v\\ 0 & 1\end{bmatrix},\quad
              G(\theta) = I\theta + (1-\cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2;

    for :math:`\omega = 0` the rotation is I and the translation :math:`v\theta`.
    MR: ``MatrixExp6`` (which takes :math:`[\mathcal S]\theta`).

    Parameters
    ----------
    S_col : sympy Matrix or sequence, 6 entries
        Numeric entries are checked (unit :math:`\omega`, or :math:`\omega = 0`
        and unit :math:`v`); symbolic entries are assumed to satisfy this.
    theta : number or sympy expression

    Returns
    -------
    sympy.Matrix, shape (4, 4)

    >>> import sympy as sp
    >>> t, l = sp.symbols("t l")
    >>> exp_se3([0, 0, 1, 0, -l, 0], t)   # about z through (l, 0, 0)
    Matrix([
    [cos(t), -sin(t), 0, -l*cos(t) + l],
    [sin(t),  cos(t), 0,     -l*sin(t)],
    [     0,       0, 1,             0],
    [     0,       0, 0,             1]])
    """
    S = _vector(S_col, "S_col", 6)
    theta = _scalar(theta, "theta")
    w, v = S[:3, 0], S[3:, 0]
    revolute = _check_unit_or_zero_omega(w, v, "S_col")
    T = sp.eye(4)
    if not revolute:
        T[:3, 3] = v * theta
        return T
    W = skew(w)
    W2 = W * W
    T[:3, :3] = sp.eye(3) + sp.sin(theta) * W + (1 - sp.cos(theta)) * W2
    G = sp.eye(3) * theta + (1 - sp.cos(theta)) * W + (theta - sp.sin(theta)) * W2
    T[:3, 3] = (G * v).applyfunc(sp.expand)
    return T


def _split(T: sp.Matrix) -> tuple:
    return T[:3, :3], T[:3, 3]


def _transform(T, name: str = "T") -> sp.Matrix:
    T = _matrix(T, name, (4, 4))
    bottom = T[3, :]
    if any(sp.simplify(b - e) != 0 for b, e in zip(bottom, (0, 0, 0, 1))):
        raise ValueError(f"Expected {name} in SE(3) with last row [0, 0, 0, 1], got last row {list(bottom)}")
    return T


def adjoint(T) -> sp.Matrix:
    r"""The 6 x 6 adjoint :math:`[\mathrm{Ad}_T] = \begin{bmatrix} R & 0\\ [p]R & R\end{bmatrix}`. MR: ``Adjoint``.

    Parameters
    ----------
    T : sympy Matrix, shape (4, 4)

    Returns
    -------
    sympy.Matrix, shape (6, 6)

    >>> import sympy as sp
    >>> T = sp.Matrix([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> (adjoint(T) * sp.Matrix([0, 0, 1, 0, 0, 0])).T   # a z axis seen from 1 m along x
    Matrix([[0, 0, 1, 0, -1, 0]])
    """
    R, p = _split(_transform(T))
    Ad = sp.zeros(6, 6)
    Ad[:3, :3] = R
    Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) * R
    return Ad


def inverse_transform(T) -> sp.Matrix:
    r""":math:`T^{-1} = \begin{bmatrix} R^T & -R^T p\\ 0 & 1\end{bmatrix}` (no matrix inversion). MR: ``TransInv``.

    >>> import sympy as sp
    >>> t = sp.Symbol("t")
    >>> T = exp_se3([0, 0, 1, 0, -1, 0], t)
    >>> simplify_matrix(inverse_transform(T) * T) == sp.eye(4)
    True
    """
    R, p = _split(_transform(T))
    out = sp.eye(4)
    out[:3, :3] = R.T
    out[:3, 3] = -(R.T * p)
    return out


def matrix_from_twist(V) -> sp.Matrix:
    r"""The se(3) matrix :math:`[\mathcal V] = \begin{bmatrix}[\omega] & v\\ 0 & 0\end{bmatrix}` of a twist. MR: ``VecTose3``.

    >>> matrix_from_twist([0, 0, 1, 2, 0, 0])
    Matrix([
    [0, -1, 0, 2],
    [1,  0, 0, 0],
    [0,  0, 0, 0],
    [0,  0, 0, 0]])
    """
    V = _vector(V, "V", 6)
    out = sp.zeros(4, 4)
    out[:3, :3] = skew(V[:3, 0])
    out[:3, 3] = V[3:, 0]
    return out


def twist_from_matrix(M) -> sp.Matrix:
    r"""The 6-vector :math:`(\omega, v)` of an se(3) matrix :math:`[\mathcal V]`. MR: ``se3ToVec``.

    Parameters
    ----------
    M : sympy Matrix, shape (4, 4)
        Upper-left block skew-symmetric, last row zero (checked after simplification).

    Returns
    -------
    sympy.Matrix, shape (6, 1)

    >>> twist_from_matrix(matrix_from_twist([1, 2, 3, 4, 5, 6])).T
    Matrix([[1, 2, 3, 4, 5, 6]])
    """
    M = _matrix(M, "M", (4, 4))
    W = M[:3, :3]
    if any(sp.simplify(e) != 0 for e in (W + W.T)):
        raise ValueError("Expected M in se(3): its upper-left 3 x 3 block must be skew-symmetric")
    if any(sp.simplify(e) != 0 for e in M[3, :]):
        raise ValueError(f"Expected M in se(3) with a zero last row, got {list(M[3, :])}")
    return sp.Matrix([W[2, 1], W[0, 2], W[1, 0], M[0, 3], M[1, 3], M[2, 3]])


# ---------------------------------------------------------------- kinematics

def _screw_axes(S, name: str = "S") -> sp.Matrix:
    A = _matrix(S, name)
    if A.rows != 6:
        hint = " (it looks transposed: the axes must be the columns)" if A.cols == 6 else ""
        raise ValueError(f"Expected {name} with shape (6, n), one screw axis per column, got shape {A.shape}{hint}")
    if A.cols == 0:
        raise ValueError(f"Expected {name} with at least one column, got shape {A.shape}")
    for i in range(A.cols):
        _check_unit_or_zero_omega(A[:3, i], A[3:, i], f"column {i} of {name}")
    return A


def _tidy(A: sp.Matrix, simplify: bool, cache: dict | None = None) -> sp.Matrix:
    """Expand every entry, and simplify it cheaply if asked (used on partial products)."""
    if not simplify:
        return A.applyfunc(sp.expand)
    cache = {} if cache is None else cache
    return A.applyfunc(lambda e: _simplify_entry(e, cache))


def fk(S, M, thetas, simplify: bool = True) -> sp.Matrix:
    r"""Forward kinematics :math:`T_{sb} = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_n]\theta_n} M`. MR: ``FKinSpace``.

    Parameters
    ----------
    S : sympy Matrix, shape (6, n)
        Space-frame screw axes as columns.
    M : sympy Matrix, shape (4, 4)
        Home pose of {b}.
    thetas : sequence of n symbols or numbers
    simplify : bool
        If True (default) the partial products and the result are simplified
        with :func:`simplify_matrix` as they are built (fast, and the result
        reads like a textbook); if False every entry is the fully expanded
        product of sines and cosines of single joint angles.

    Returns
    -------
    T_sb : sympy.Matrix, shape (4, 4)

    >>> arm, th, ls = planar_chain(2)
    >>> fk(arm.screw_axes, arm.home, th)[0, 3]
    l1*cos(theta1) + l2*cos(theta1 + theta2)
    """
    S = _screw_axes(S)
    M = _transform(M, "M")
    th = _thetas(thetas, S.cols)
    cache: dict = {}
    T = sp.eye(4)
    for i in range(S.cols):
        T = _tidy(T * exp_se3(S[:, i], th[i]), simplify, cache)
    return _tidy(T * M, simplify, cache)


def _ad_apply(R: sp.Matrix, p: sp.Matrix, V: sp.Matrix) -> sp.Matrix:
    """[Ad_(R,p)] V without forming the 6 x 6 matrix."""
    w = R * V[:3, 0]
    v = R * V[3:, 0] + p.cross(w)
    return sp.Matrix.vstack(w, v)


def space_jacobian(S, thetas, simplify: bool = True) -> sp.Matrix:
    r"""Space Jacobian :math:`J_s(\theta)`: column i is :math:`[\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_{i-1}]\theta_{i-1}}}]\mathcal S_i`.

    MR: ``JacobianSpace``.

    Parameters
    ----------
    S : sympy Matrix, shape (6, n)
    thetas : sequence of n symbols or numbers
    simplify : bool
        Simplify as it goes (default), or return the expanded products (see :func:`fk`).

    Returns
    -------
    J_s : sympy.Matrix, shape (6, n)

    >>> import sympy as sp
    >>> t1, t2 = sp.symbols("theta1 theta2")
    >>> S = sp.Matrix([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]]).T
    >>> space_jacobian(S, [t1, t2])[:, 1].T
    Matrix([[0, 0, 1, sin(theta1), -cos(theta1), 0]])
    """
    S = _screw_axes(S)
    th = _thetas(thetas, S.cols)
    cache: dict = {}
    cols = []
    T = sp.eye(4)
    for i in range(S.cols):
        cols.append(_ad_apply(T[:3, :3], T[:3, 3], S[:, i]) if i else sp.Matrix(S[:, 0]))
        if i < S.cols - 1:
            T = _tidy(T * exp_se3(S[:, i], th[i]), simplify, cache)
    return _tidy(sp.Matrix.hstack(*cols), simplify, cache)


def body_jacobian(B, thetas, simplify: bool = True) -> sp.Matrix:
    r"""Body Jacobian :math:`J_b(\theta)`: column i is :math:`[\mathrm{Ad}_{e^{-[\mathcal B_n]\theta_n}\cdots e^{-[\mathcal B_{i+1}]\theta_{i+1}}}]\mathcal B_i`.

    MR: ``JacobianBody``.

    Parameters
    ----------
    B : sympy Matrix, shape (6, n)
        Body-frame screw axes :math:`\mathcal B_i = [\mathrm{Ad}_{M^{-1}}]\mathcal S_i`
        (``SymbolicChain.body_axes``).
    thetas : sequence of n symbols or numbers
    simplify : bool
        Simplify as it goes (default), or return the expanded products (see :func:`fk`).

    Returns
    -------
    J_b : sympy.Matrix, shape (6, n)

    >>> import sympy as sp
    >>> t1, t2 = sp.symbols("theta1 theta2")
    >>> B = sp.Matrix([[0, 0, 1, 0, 2, 0], [0, 0, 1, 0, 1, 0]]).T   # planar 2R, unit links
    >>> body_jacobian(B, [t1, t2])[:, 0].T
    Matrix([[0, 0, 1, sin(theta2), cos(theta2) + 1, 0]])
    """
    B = _screw_axes(B, "B")
    th = _thetas(thetas, B.cols)
    n = B.cols
    cache: dict = {}
    cols = [None] * n
    T = sp.eye(4)  # e^{-[B_n] th_n} ... e^{-[B_{i+1}] th_{i+1}}
    for i in range(n - 1, -1, -1):
        cols[i] = _ad_apply(T[:3, :3], T[:3, 3], B[:, i]) if i < n - 1 else sp.Matrix(B[:, i])
        if i > 0:
            T = _tidy(T * exp_se3(B[:, i], -th[i]), simplify, cache)
    return _tidy(sp.Matrix.hstack(*cols), simplify, cache)


def _space_to_geometric(J_s: sp.Matrix, p: sp.Matrix) -> sp.Matrix:
    """Rows (omega_s, v_s + omega_s x p)."""
    out = sp.Matrix(J_s)
    for i in range(J_s.cols):
        w = J_s[:3, i]
        out[3:, i] = J_s[3:, i] + w.cross(p)
    return out


def geometric_jacobian(S, M, thetas, simplify: bool = True) -> sp.Matrix:
    r"""Geometric Jacobian: rows :math:`(\omega_s, \dot p)`, with :math:`\dot p` the velocity of the origin of {b} in {s}.

    :math:`J = \begin{bmatrix} I & 0\\ -[p] & I\end{bmatrix} J_s`, p the
    position of {b}. For a revolute joint the column is
    :math:`(\hat z_i, \hat z_i\times(p - p_i))`. Not in MR's code (MR works with twists).

    Parameters
    ----------
    S : sympy Matrix, shape (6, n)
    M : sympy Matrix, shape (4, 4)
    thetas : sequence of n symbols or numbers
    simplify : bool
        Simplify as it goes (default), or return the expanded products (see :func:`fk`).

    Returns
    -------
    J : sympy.Matrix, shape (6, n)

    >>> arm, th, ls = planar_chain(2)
    >>> geometric_jacobian(arm.screw_axes, arm.home, th)[3:5, :]
    Matrix([
    [-l1*sin(theta1) - l2*sin(theta1 + theta2), -l2*sin(theta1 + theta2)],
    [ l1*cos(theta1) + l2*cos(theta1 + theta2),  l2*cos(theta1 + theta2)]])
    """
    S = _screw_axes(S)
    M = _transform(M, "M")
    th = _thetas(thetas, S.cols)
    T = fk(S, M, th, simplify)
    return _tidy(_space_to_geometric(space_jacobian(S, th, simplify), T[:3, 3]), simplify)


def link_jacobian(S, thetas, i: int, link_home=None, frame: str = "space", simplify: bool = True) -> sp.Matrix:
    r"""Jacobian of the frame fixed to link i (1-based): joints after i do not move it.

    Link i is moved by joints 1..i only, so its space Jacobian is the space
    Jacobian of the whole chain with columns i+1..n set to zero (the frame
    fixed to the link does not matter for the space twist).

    Parameters
    ----------
    S : sympy Matrix, shape (6, n)
    thetas : sequence of n symbols or numbers
    i : int, 1 <= i <= n
        Link number, as in the notes: link i is carried by joints 1..i.
    link_home : sympy Matrix, shape (4, 4), optional
        Home pose :math:`M_i` of the frame fixed to link i; needed for
        ``frame="body"`` and ``frame="geometric"``.
    frame : {"space", "body", "geometric"}
        ``"space"``: :math:`\mathcal V_{s} = J\dot\theta`; ``"body"``: the twist of
        the link frame in itself, :math:`[\mathrm{Ad}_{T_{s,i}^{-1}}]J_{s,i}`;
        ``"geometric"``: :math:`(\omega_s, \dot p_i)` of the link frame's origin.
        The numeric counterpart is :func:`jacobians.link_jacobians` (entry i - 1).
    simplify : bool

    Returns
    -------
    sympy.Matrix, shape (6, n)

    >>> arm, th, ls = planar_chain(3)
    >>> link_jacobian(arm.screw_axes, th, 1)[:, 1:].is_zero_matrix
    True
    """
    S = _screw_axes(S)
    th = _thetas(thetas, S.cols)
    n = S.cols
    if isinstance(i, bool) or not isinstance(i, numbers.Integral):
        raise TypeError(f"Expected an integer link number i, got {_describe(i)}")
    if not 1 <= i <= n:
        raise ValueError(f"Expected a link number i with 1 <= i <= {n} (links are numbered from 1), got {i}")
    if frame not in ("space", "body", "geometric"):
        raise ValueError(f"Expected frame 'space', 'body' or 'geometric', got {frame!r}")
    if frame != "space" and link_home is None:
        raise ValueError(f"frame={frame!r} needs link_home, the home pose M_i of the frame fixed to link {i}")
    J = space_jacobian(S[:, :i], th[:i], simplify)
    J = sp.Matrix.hstack(J, sp.zeros(6, n - i))
    if frame == "space":
        return J
    M_i = _transform(link_home, "link_home")
    T_i = fk(S[:, :i], M_i, th[:i], simplify)
    if frame == "geometric":
        return _tidy(_space_to_geometric(J, T_i[:3, 3]), simplify)
    Tinv = inverse_transform(T_i)
    return _tidy(sp.Matrix.hstack(*[_ad_apply(Tinv[:3, :3], Tinv[:3, 3], J[:, k]) for k in range(n)]), simplify)


# ---------------------------------------------------------------- chains

class SymbolicChain:
    r"""A serial chain with symbolic screw axes and home pose.

    Parameters
    ----------
    screw_axes : sympy Matrix, shape (6, n)
        Columns :math:`\mathcal S_i = (\omega_i, v_i)` in {s} at home.
    home : sympy Matrix, shape (4, 4)
        :math:`M`, the pose of {b} at home.
    thetas : sequence of n sympy symbols, optional
        The joint symbols; default ``theta1 .. thetan`` (real).
    params : sequence of sympy symbols, optional
        Other symbols (link lengths) the chain depends on, kept for
        :func:`lambdify_matrix` and :func:`to_numeric_chain`.
    link_homes : sequence of n sympy 4 x 4 matrices, optional
        Home poses :math:`M_i` of frames fixed to the links (for
        :meth:`link_jacobian`); ``None`` if not given.

    The methods ``fk``, ``space_jacobian``, ``body_jacobian``,
    ``geometric_jacobian`` and ``link_jacobian`` take optional ``thetas``
    (default: the chain's symbols) and ``simplify`` (default True).

    >>> import sympy as sp
    >>> S = sp.Matrix([[0, 0, 1, 0, 0, 0]]).T
    >>> M = sp.Matrix([[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> SymbolicChain(S, M).geometric_jacobian().T
    Matrix([[0, 0, 1, -2*sin(theta1), 2*cos(theta1), 0]])
    """

    def __init__(self, screw_axes, home, thetas=None, params=(), link_homes=None):
        self.screw_axes = _screw_axes(screw_axes, "screw_axes")
        self.home = _transform(home, "home")
        n = self.screw_axes.cols
        if link_homes is not None:
            if isinstance(link_homes, (str, bytes, sp.MatrixBase)) or not hasattr(link_homes, "__len__"):
                raise TypeError(f"Expected a sequence of {n} 4 x 4 matrices for link_homes, got {_describe(link_homes)}")
            if len(link_homes) != n:
                raise ValueError(f"Expected {n} link home poses (one per joint), got {len(link_homes)}")
            link_homes = tuple(_transform(M_i, f"link_homes[{i}]") for i, M_i in enumerate(link_homes))
        self.link_homes = link_homes
        if thetas is None:
            thetas = sp.symbols(f"theta1:{n + 1}", real=True)
        self.thetas = tuple(_thetas(thetas, n))
        if isinstance(params, (str, bytes)):
            raise TypeError("Expected a sequence of sympy symbols for params, got a str")
        self.params = tuple(_scalar(p, "params") for p in params)
        Minv = inverse_transform(self.home)
        self.body_axes = simplify_matrix(sp.Matrix.hstack(
            *[_ad_apply(Minv[:3, :3], Minv[:3, 3], self.screw_axes[:, k]) for k in range(n)]))

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return self.screw_axes.cols

    def __repr__(self) -> str:
        return f"<SymbolicChain: {self.dof} joints, symbols {self.thetas + self.params}>"

    def _th(self, thetas):
        return self.thetas if thetas is None else thetas

    def fk(self, thetas=None, simplify: bool = True) -> sp.Matrix:
        """:func:`fk` of this chain."""
        return fk(self.screw_axes, self.home, self._th(thetas), simplify)

    def space_jacobian(self, thetas=None, simplify: bool = True) -> sp.Matrix:
        """:func:`space_jacobian` of this chain."""
        return space_jacobian(self.screw_axes, self._th(thetas), simplify)

    def body_jacobian(self, thetas=None, simplify: bool = True) -> sp.Matrix:
        """:func:`body_jacobian` of this chain (from its body axes)."""
        return body_jacobian(self.body_axes, self._th(thetas), simplify)

    def geometric_jacobian(self, thetas=None, simplify: bool = True) -> sp.Matrix:
        """:func:`geometric_jacobian` of this chain."""
        return geometric_jacobian(self.screw_axes, self.home, self._th(thetas), simplify)

    def link_jacobian(self, i: int, frame: str = "space", thetas=None, simplify: bool = True) -> sp.Matrix:
        """:func:`link_jacobian` of link i (1-based) of this chain, with its ``link_homes``."""
        M_i = None
        if self.link_homes is not None and isinstance(i, numbers.Integral) and 1 <= i <= self.dof:
            M_i = self.link_homes[i - 1]
        return link_jacobian(self.screw_axes, self._th(thetas), i, link_home=M_i, frame=frame, simplify=simplify)

    @classmethod
    def from_numeric(cls, chain, exact: bool = True, thetas=None) -> "SymbolicChain":
        """The symbolic twin of a :class:`jacobians.SerialChain`.

        Parameters
        ----------
        chain : jacobians.SerialChain
        exact : bool
            If True, each float is replaced by the shortest rational that
            prints like it (0.425 -> 17/40), so sympy can simplify exactly;
            if False the floats are kept. Entries below 1e-12 in size become 0.

        >>> import jacobians as jac
        >>> SymbolicChain.from_numeric(jac.robots.planar_2r(0.5, 0.25)).screw_axes[4, 1]
        -1/2
        """
        from .chain import SerialChain

        if not isinstance(chain, SerialChain):
            raise TypeError(f"Expected a jacobians.SerialChain, got {type(chain).__name__}")

        def conv(x):
            x = float(x)
            if abs(x) < 1e-12:  # round-off left by numeric constructors
                return sp.Integer(0)
            return sp.nsimplify(repr(x), rational=True) if exact else sp.Float(x)

        S = sp.Matrix(6, chain.dof, lambda i, j: conv(chain.screw_axes[i, j]))
        M = sp.Matrix(4, 4, lambda i, j: conv(chain.home[i, j]))
        homes = [sp.Matrix(4, 4, lambda i, j: conv(H[i, j])) for H in chain.link_homes]
        return cls(S, M, thetas=thetas, link_homes=homes)


def planar_chain(n: int, lengths=None):
    r"""A planar nR arm with symbolic link lengths.

    Joint i turns about z through :math:`(l_1 + \dots + l_{i-1}, 0, 0)`; the tool
    frame {b} is at :math:`(l_1 + \dots + l_n, 0, 0)` with the orientation of {s}.
    Same geometry as :func:`jacobians.robots.planar`.

    Parameters
    ----------
    n : int, at least 1
    lengths : sequence of n numbers or sympy expressions, optional
        Default: positive real symbols ``l1 .. ln``.

    Returns
    -------
    chain : SymbolicChain
        ``chain.thetas`` are the joint symbols, ``chain.params`` the length
        symbols, ``chain.link_homes`` frames at the middle of each link (as
        :func:`jacobians.robots.planar`).
    thetas : tuple of n real symbols ``theta1 .. thetan``
    lengths : tuple of n link lengths (the symbols, or the values given)

    >>> arm, th, ls = planar_chain(3)
    >>> arm.screw_axes[:, 2].T
    Matrix([[0, 0, 1, 0, -l1 - l2, 0]])
    >>> arm.home[0, 3]
    l1 + l2 + l3
    """
    if isinstance(n, bool) or not isinstance(n, numbers.Integral):
        raise TypeError(f"Expected an integer number of joints n, got {_describe(n)}")
    if n < 1:
        raise ValueError(f"Expected at least one joint, got n = {n}")
    thetas = sp.symbols(f"theta1:{n + 1}", real=True)
    if lengths is None:
        ls = sp.symbols(f"l1:{n + 1}", positive=True)
        params = ls
    else:
        if isinstance(lengths, (str, bytes)) or not hasattr(lengths, "__len__"):
            raise TypeError(f"Expected a sequence of {n} link lengths, got {_describe(lengths)}")
        if len(lengths) != n:
            raise ValueError(f"Expected {n} link lengths, got {len(lengths)}")
        ls = tuple(_scalar(v, f"lengths[{i}]") for i, v in enumerate(lengths))
        for i, v in enumerate(ls):
            if v.is_number and not v.is_positive:
                raise ValueError(f"Expected positive link lengths, got lengths[{i}] = {v}")
        params = tuple(sorted(set().union(*[v.free_symbols for v in ls]), key=str))
    x = [sp.Integer(0)]
    for v in ls:
        x.append(x[-1] + v)
    S = sp.zeros(6, n)
    for i in range(n):
        # revolute about z through q = (x_i, 0, 0): v = -w x q = (0, -x_i, 0)
        S[2, i] = 1
        S[4, i] = -x[i]
    M = sp.eye(4)
    M[0, 3] = x[n]
    homes = []
    for i in range(n):  # link frames at mid-link, as in jacobians.robots.planar
        M_i = sp.eye(4)
        M_i[0, 3] = x[i] + ls[i] / 2
        homes.append(M_i)
    chain = SymbolicChain(S, M, thetas=thetas, params=params, link_homes=homes)
    return chain, tuple(thetas), tuple(ls)


# ---------------------------------------------------------------- simplification and numbers

def _is_trig_power(t) -> bool:
    return (t.is_Pow and isinstance(t.base, (sp.sin, sp.cos)) and t.exp.is_Integer and t.exp >= 2)


def _pythagoras(e: sp.Expr, keep) -> sp.Expr:
    """Rewrite every power (>= 2) of the trig function other than ``keep`` with sin^2 + cos^2 = 1, and expand."""
    other = sp.cos if keep is sp.sin else sp.sin

    def lower(t):
        if _is_trig_power(t) and isinstance(t.base, other):
            x = t.base.args[0]
            return other(x) ** (t.exp - 2) * (1 - keep(x) ** 2)
        return t

    for _ in range(8):  # each pass lowers every exponent by 2
        new = sp.expand(e.replace(_is_trig_power, lower))
        if new == e:
            break
        e = new
    return e


def _simplify_entry(e: sp.Expr, cache: dict) -> sp.Expr:
    """Expand, cancel sin^2 + cos^2, then fold c_a c_b - s_a s_b into c_{a+b} (Fu's rule TR10i)."""
    if e in cache:
        return cache[e]
    out = sp.expand(e)
    if out.has(sp.sin, sp.cos):
        if any(_is_trig_power(t) for t in out.atoms(sp.Pow)):
            out = min([out, _pythagoras(out, sp.cos), _pythagoras(out, sp.sin)], key=sp.count_ops)
        out = _TR10i(out)
        if any(_is_trig_power(t) for t in out.atoms(sp.Pow)):
            # folding may have produced new squares of angle sums
            out = _TR10i(min([out, _pythagoras(out, sp.cos), _pythagoras(out, sp.sin)], key=sp.count_ops))
    cache[e] = out
    return out


def simplify_matrix(A) -> sp.Matrix:
    r"""Simplify every entry of a matrix of sines, cosines and lengths.

    Each entry is expanded; powers of sines and cosines are reduced with
    :math:`\sin^2 + \cos^2 = 1` when that shortens the entry; then Fu's rule
    TR10i folds sums of products into sines and cosines of angle sums
    (:math:`c_1c_2 - s_1s_2 \to c_{12}`, :math:`s_1c_2 + c_1s_2 \to s_{12}`).
    These targeted rules are much faster than ``sympy.trigsimp`` and give the
    textbook forms (planar 3R Jacobians in a fraction of a second, the UR5's in
    a few seconds). Repeated entries are simplified once. Not a general
    simplifier: rational functions are only expanded.

    Parameters
    ----------
    A : sympy Matrix (any shape)

    Returns
    -------
    sympy.Matrix, same shape

    >>> import sympy as sp
    >>> a, b, l = sp.symbols("a b l")
    >>> simplify_matrix(sp.Matrix([[l*sp.cos(a)*sp.cos(b) - l*sp.sin(a)*sp.sin(b)]]))
    Matrix([[l*cos(a + b)]])
    """
    A = _matrix(A, "A")
    cache: dict = {}
    return A.applyfunc(lambda e: _simplify_entry(e, cache))


def _flatten_symbols(symbols) -> list:
    if isinstance(symbols, (str, bytes)):
        raise TypeError("Expected sympy symbols, got a str (pass sympy.Symbol objects)")
    if isinstance(symbols, sp.Symbol):
        return [symbols]
    if isinstance(symbols, sp.MatrixBase):
        symbols = list(symbols)
    if not isinstance(symbols, (list, tuple)):
        raise TypeError(f"Expected a sequence of sympy symbols, got {_describe(symbols)}")
    out = []
    for s in symbols:
        if isinstance(s, (list, tuple, sp.MatrixBase)):
            out.extend(_flatten_symbols(s))
        elif isinstance(s, sp.Symbol):
            out.append(s)
        else:
            raise TypeError(f"Expected sympy symbols, got {_describe(s)}")
    if len(set(out)) != len(out):
        raise ValueError(f"Expected distinct symbols, got {out}")
    return out


def lambdify_matrix(A, symbols):
    r"""A fast numeric function of a symbolic matrix.

    Parameters
    ----------
    A : sympy Matrix, shape (r, c)
    symbols : sequence of sympy symbols (nested sequences are flattened)
        The k symbols, in the order the values will come. Every free symbol
        of A must be among them.

    Returns
    -------
    f : callable
        ``f(x)`` with x of shape (..., k) returns an ndarray of shape
        (..., r, c); ``f(x1, ..., xk)`` with k scalars or broadcastable
        arrays also works. With a single symbol (k = 1), ``f(x)`` takes the
        values of that symbol, any shape (...).

    >>> import numpy as np, sympy as sp
    >>> arm, th, ls = planar_chain(2)
    >>> f = lambdify_matrix(arm.space_jacobian(), th + ls)
    >>> f([0.0, np.pi / 2, 1.0, 1.0])[3:5].round(12) + 0.0
    array([[ 0.,  0.],
           [ 0., -1.]])
    """
    A = _matrix(A, "A")
    syms = _flatten_symbols(symbols)
    missing = A.free_symbols - set(syms)
    if missing:
        raise ValueError(f"The matrix depends on {sorted(map(str, missing))}, which are not in symbols {syms}")
    r, c = A.shape
    k = len(syms)
    funcs = sp.lambdify(syms, list(A), modules="numpy", cse=True)

    def f(*args):
        if len(args) == 1 and k != 1:
            x = np.asarray(args[0], dtype=float)
            if x.ndim == 0 or x.shape[-1] != k:
                raise ValueError(f"Expected values with shape (..., {k}) for the symbols {syms}, got shape {x.shape}")
            vals = [x[..., j] for j in range(k)]
        elif len(args) == k:
            vals = [np.asarray(a, dtype=float) for a in args]
        else:
            raise TypeError(f"Expected one array of shape (..., {k}) or {k} values, got {len(args)} arguments")
        shape = np.broadcast_shapes(*[v.shape for v in vals]) if vals else ()
        entries = funcs(*vals)
        out = np.empty(shape + (r * c,))
        for j, e in enumerate(entries):
            out[..., j] = e
        return out.reshape(shape + (r, c))

    f.symbols = tuple(syms)
    return f


def to_numeric_chain(chain: SymbolicChain, values=None, name: str | None = None):
    r"""The numeric :class:`jacobians.SerialChain` of a symbolic chain with its parameters substituted.

    Parameters
    ----------
    chain : SymbolicChain
    values : dict {symbol: number}, optional
        A value for every parameter (link length) of the chain.

    >>> arm, th, (l1, l2) = planar_chain(2)
    >>> to_numeric_chain(arm, {l1: 1.0, l2: 0.5}).home[0, 3]
    np.float64(1.5)
    """
    from .chain import SerialChain

    if not isinstance(chain, SymbolicChain):
        raise TypeError(f"Expected a SymbolicChain, got {type(chain).__name__}")
    values = {} if values is None else values
    if not isinstance(values, dict):
        raise TypeError(f"Expected a dict {{symbol: value}} for values, got {_describe(values)}")
    subs = {k: _scalar(v, f"values[{k}]") for k, v in values.items()}
    S = chain.screw_axes.subs(subs)
    M = chain.home.subs(subs)
    homes = None if chain.link_homes is None else [H.subs(subs) for H in chain.link_homes]
    free = S.free_symbols | M.free_symbols
    if homes is not None:
        free = free.union(*[H.free_symbols for H in homes])
    if free:
        raise ValueError(f"Expected a value for every parameter, missing {sorted(map(str, free))}")
    link_homes = None if homes is None else np.array([np.array(H.evalf(), dtype=float) for H in homes])
    return SerialChain(np.array(S.evalf(), dtype=float), np.array(M.evalf(), dtype=float),
                       link_homes=link_homes, name=name)
