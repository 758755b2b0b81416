r"""Symbolic Jacobians: the functions of :mod:`jacobians.jacobian`, same names and argument order.

Each takes a :class:`SymbolicChain` and ``theta`` (n symbols or values; default
the chain's symbols) and returns a sympy matrix. ``simplify=True`` (the default)
simplifies the partial products as they are built, which is faster and more
readable than simplifying the expanded product at the end.

>>> from jacobians.symbolic import planar_chain
>>> arm, (t1, t2), (l1, l2) = planar_chain(2)
>>> space_jacobian(arm)[3:5, :]
Matrix([
[0,  l1*sin(theta1)],
[0, -l1*cos(theta1)]])
"""

from __future__ import annotations

import sympy as sp

from ..frames import Frame, check_frame
from ._checks import describe, matrix, transform
from .chain import SymbolicChain, ad_apply
from .lie import adjoint, exp_se3, inverse_transform
from .simplify import tidy

__all__ = [
    "SYMBOLIC_FRAMES",
    "jacobian",
    "space_jacobian",
    "body_jacobian",
    "geometric_jacobian",
    "link_jacobians",
    "space_to_body",
    "body_to_space",
    "space_to_geometric",
    "geometric_to_space",
    "body_to_geometric",
    "geometric_to_body",
]

SYMBOLIC_FRAMES: tuple[Frame, ...] = ("space", "body", "geometric")
"""The frames (:mod:`jacobians.frames`) a symbolic Jacobian is given in; the analytic one is numeric only."""


def _chain(chain: object) -> SymbolicChain:
    if not isinstance(chain, SymbolicChain):
        raise TypeError(f"Expected a jacobians.symbolic.SymbolicChain, got {describe(chain)}")
    return chain


def space_jacobian(chain: SymbolicChain, theta: object = None, simplify: bool = True) -> sp.Matrix:
    r"""Space Jacobian :math:`J_s(\theta)`.

    Column i is :math:`[\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_{i-1}]\theta_{i-1}}}]\mathcal S_i`.

    MR: ``JacobianSpace``; numeric twin :func:`jacobians.space_jacobian`.

    >>> t1, t2 = sp.symbols("theta1 theta2")
    >>> arm = SymbolicChain(sp.Matrix([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]]).T, sp.eye(4))
    >>> space_jacobian(arm, [t1, t2])[:, 1].T
    Matrix([[0, 0, 1, sin(theta1), -cos(theta1), 0]])
    """
    S = _chain(chain).screw_axes
    th = chain.joint_values(theta)
    cache: dict[sp.Expr, sp.Expr] = {}
    cols = []
    T = sp.eye(4)
    for i in range(S.cols):
        cols.append(ad_apply(T[:3, :3], T[:3, 3], S[:, i]) if i else sp.Matrix(S[:, 0]))
        if i < S.cols - 1:
            T = tidy(T * exp_se3(S[:, i], th[i]), simplify, cache)
    return tidy(sp.Matrix.hstack(*cols), simplify, cache)


def body_jacobian(chain: SymbolicChain, theta: object = None, simplify: bool = True) -> sp.Matrix:
    r"""Body Jacobian :math:`J_b(\theta)`.

    Column i: :math:`[\mathrm{Ad}_{e^{-[\mathcal B_n]\theta_n}\cdots e^{-[\mathcal B_{i+1}]\theta_{i+1}}}]\mathcal B_i`.

    MR: ``JacobianBody``; numeric twin :func:`jacobians.body_jacobian`.

    >>> from jacobians.symbolic import planar_chain
    >>> arm, th, ls = planar_chain(2, lengths=[1, 1])
    >>> body_jacobian(arm)[:, 0].T
    Matrix([[0, 0, 1, sin(theta2), cos(theta2) + 1, 0]])
    """
    B = _chain(chain).body_axes
    th = chain.joint_values(theta)
    n = B.cols
    cache: dict[sp.Expr, sp.Expr] = {}
    cols: list[sp.Matrix] = [sp.Matrix(B[:, n - 1])] * n
    T = sp.eye(4)  # e^{-[B_n] th_n} ... e^{-[B_{i+1}] th_{i+1}}
    for i in range(n - 1, -1, -1):
        cols[i] = ad_apply(T[:3, :3], T[:3, 3], B[:, i]) if i < n - 1 else sp.Matrix(B[:, i])
        if i > 0:
            T = tidy(T * exp_se3(B[:, i], -th[i]), simplify, cache)
    return tidy(sp.Matrix.hstack(*cols), simplify, cache)


def _shift_to_point(J_s: sp.Matrix, p: sp.Matrix) -> sp.Matrix:
    """Rows (omega_s, v_s + omega_s x p): the velocity of the point p instead of the origin of {s}."""
    out = sp.Matrix(J_s)
    for i in range(J_s.cols):
        out[3:, i] = J_s[3:, i] + J_s[:3, i].cross(p)
    return out


def geometric_jacobian(chain: SymbolicChain, theta: object = None, simplify: bool = True) -> sp.Matrix:
    r"""Geometric Jacobian: rows :math:`(\omega_s, \dot p)`, :math:`\dot p` the velocity of the origin of {b} in {s}.

    :math:`J = \begin{bmatrix} I & 0\\ -[p] & I\end{bmatrix} J_s`, p the position
    of {b}. Numeric twin :func:`jacobians.geometric_jacobian` (not in MR's code).

    >>> from jacobians.symbolic import planar_chain
    >>> arm, th, ls = planar_chain(2)
    >>> geometric_jacobian(arm)[3:5, :]
    Matrix([
    [-l1*sin(theta1) - l2*sin(theta1 + theta2), -l2*sin(theta1 + theta2)],
    [ l1*cos(theta1) + l2*cos(theta1 + theta2),  l2*cos(theta1 + theta2)]])
    """
    th = _chain(chain).joint_values(theta)
    T = chain.fk(th, simplify)
    return tidy(_shift_to_point(space_jacobian(chain, th, simplify), T[:3, 3]), simplify)


def jacobian(chain: SymbolicChain, theta: object = None, frame: Frame = "space", simplify: bool = True) -> sp.Matrix:
    """The Jacobian of the chain in ``frame``, one of :data:`SYMBOLIC_FRAMES`; numeric twin :func:`jacobians.jacobian`.

    >>> from jacobians.symbolic import planar_chain
    >>> arm, th, ls = planar_chain(2)
    >>> jacobian(arm, th, "body") == body_jacobian(arm, th)
    True
    """
    f = check_frame(frame, SYMBOLIC_FRAMES)
    fn = {"space": space_jacobian, "body": body_jacobian, "geometric": geometric_jacobian}[f]
    return fn(chain, theta, simplify)


def link_jacobians(chain: SymbolicChain, theta: object = None, frame: Frame = "space",
                   simplify: bool = True) -> tuple[sp.Matrix, ...]:
    r"""The Jacobians of the frames fixed to links 1..n, a tuple of n 6 x n matrices.

    Numeric twin :func:`jacobians.link_jacobians`.

    Link i is moved by joints 1..i only, so its space Jacobian is the chain's
    with columns i+1..n set to zero. ``frame="body"`` gives the twist of the link
    frame in itself, :math:`[\mathrm{Ad}_{T_{s,i}^{-1}}]J_{s,i}`;
    ``frame="geometric"`` gives :math:`(\omega_s, \dot p_i)` of the link frame's
    origin. Both need the chain's ``link_homes``.

    >>> from jacobians.symbolic import planar_chain
    >>> arm, th, ls = planar_chain(3)
    >>> link_jacobians(arm)[0][:, 1:].is_zero_matrix
    True
    """
    f = check_frame(frame, SYMBOLIC_FRAMES)
    th = _chain(chain).joint_values(theta)
    n = chain.dof
    if f != "space" and chain.link_homes is None:
        raise ValueError(f"frame={f!r} needs the chain's link_homes (the home poses M_i of the link frames)")
    J_s = space_jacobian(chain, th, simplify)
    poses = chain.link_poses(th, simplify) if f != "space" else ()
    out = []
    for i in range(1, n + 1):
        J = sp.Matrix.hstack(J_s[:, :i], sp.zeros(6, n - i))
        if f != "space":
            T_i = poses[i - 1]
            if f == "geometric":
                J = tidy(_shift_to_point(J, T_i[:3, 3]), simplify)
            else:
                Tinv = inverse_transform(T_i)
                J = tidy(sp.Matrix.hstack(*[ad_apply(Tinv[:3, :3], Tinv[:3, 3], J[:, k]) for k in range(n)]),
                         simplify)
        out.append(J)
    return tuple(out)


# ---------------------------------------------------------------- conversions

def _pair(J: object, T_sb: object, name: str) -> tuple[sp.Matrix, sp.Matrix]:
    return matrix(J, name, (6, None)), transform(T_sb, "T_sb")


def space_to_body(J_s: object, T_sb: object) -> sp.Matrix:
    r""":math:`J_b = [\mathrm{Ad}_{T_{sb}^{-1}}] J_s`."""
    J, T = _pair(J_s, T_sb, "J_s")
    return adjoint(inverse_transform(T)) * J


def body_to_space(J_b: object, T_sb: object) -> sp.Matrix:
    r""":math:`J_s = [\mathrm{Ad}_{T_{sb}}] J_b`."""
    J, T = _pair(J_b, T_sb, "J_b")
    return adjoint(T) * J


def space_to_geometric(J_s: object, T_sb: object) -> sp.Matrix:
    r""":math:`J = \begin{bmatrix} I & 0\\ -[p] & I\end{bmatrix} J_s`."""
    J, T = _pair(J_s, T_sb, "J_s")
    return _shift_to_point(J, T[:3, 3])


def geometric_to_space(J: object, T_sb: object) -> sp.Matrix:
    r""":math:`J_s = \begin{bmatrix} I & 0\\ [p] & I\end{bmatrix} J`."""
    A, T = _pair(J, T_sb, "J")
    return _shift_to_point(A, -T[:3, 3])


def body_to_geometric(J_b: object, T_sb: object) -> sp.Matrix:
    r""":math:`J = \mathrm{diag}(R_{sb}, R_{sb})\, J_b`."""
    J, T = _pair(J_b, T_sb, "J_b")
    R = T[:3, :3]
    return sp.diag(R, R) * J


def geometric_to_body(J: object, T_sb: object) -> sp.Matrix:
    r""":math:`J_b = \mathrm{diag}(R_{sb}^T, R_{sb}^T)\, J`."""
    A, T = _pair(J, T_sb, "J")
    R = T[:3, :3]
    return sp.diag(R.T, R.T) * A

