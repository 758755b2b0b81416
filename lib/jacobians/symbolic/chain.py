r"""Symbolic serial chains: :class:`SymbolicChain`, shaped like :class:`jacobians.SerialChain`.

>>> arm, th, ls = planar_chain(2)
>>> arm.fk()[0, 3]
l1*cos(theta1) + l2*cos(theta1 + theta2)
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence

import numpy as np
import sympy as sp

from ..chain import SerialChain
from ._checks import describe, is_revolute, joint_values, scalar, transform
from ._checks import screw_axes as checked_axes
from .lie import exp_se3, inverse_transform
from .simplify import simplify_matrix, tidy

__all__ = ["SymbolicChain", "planar_chain", "to_numeric_chain"]


def ad_apply(R: sp.Matrix, p: sp.Matrix, V: sp.Matrix) -> sp.Matrix:
    """[Ad_(R,p)] V without forming the 6 x 6 matrix."""
    w = R * V[:3, 0]
    v = R * V[3:, 0] + p.cross(w)
    return sp.Matrix.vstack(w, v)


class SymbolicChain:
    r"""A serial chain with symbolic screw axes and home pose; read-only, like :class:`jacobians.SerialChain`.

    Parameters
    ----------
    screw_axes : sympy Matrix, shape (6, n)
        Columns :math:`\mathcal S_i = (\omega_i, v_i)` in {s} at home.
    home : sympy Matrix, shape (4, 4)
        :math:`M`, the pose of {b} at home.
    link_homes : sequence of n sympy 4 x 4 matrices, optional
        Home poses :math:`M_i` of frames fixed to the links (for
        :func:`jacobians.symbolic.link_jacobians`); ``None`` if not given.
    name : str, optional
    thetas : sequence of n sympy symbols, optional
        The joint symbols; default ``theta1 .. thetan`` (real).
    params : sequence of sympy symbols, optional
        Other symbols (link lengths) the chain depends on, kept for
        :func:`lambdify_matrix` and :func:`to_numeric_chain`.

    >>> S = sp.Matrix([[0, 0, 1, 0, 0, 0]]).T
    >>> M = sp.Matrix([[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    >>> SymbolicChain(S, M).fk()[:2, 3].T
    Matrix([[2*cos(theta1), 2*sin(theta1)]])
    """

    def __init__(self, screw_axes: object, home: object, link_homes: Sequence[object] | None = None,
                 name: str | None = None, thetas: object = None, params: Sequence[object] = ()) -> None:
        S = checked_axes(screw_axes, "screw_axes")
        M = transform(home, "home")
        n = S.cols
        homes: tuple[sp.ImmutableMatrix, ...] | None = None
        if link_homes is not None:
            if isinstance(link_homes, (str, bytes, sp.MatrixBase)) or not hasattr(link_homes, "__len__"):
                raise TypeError(f"Expected a sequence of {n} 4 x 4 matrices for link_homes, got {describe(link_homes)}")
            if len(link_homes) != n:
                raise ValueError(f"Expected {n} link home poses (one per joint), got {len(link_homes)}")
            homes = tuple(sp.ImmutableMatrix(transform(M_i, f"link_homes[{i}]")) for i, M_i in enumerate(link_homes))
        if name is not None and not isinstance(name, str):
            raise TypeError(f"Expected a str for name, got {type(name).__name__}")
        if isinstance(params, (str, bytes)):
            raise TypeError("Expected a sequence of sympy symbols for params, got a str")
        symbols = sp.symbols(f"theta1:{n + 1}", real=True) if thetas is None else thetas
        Minv = inverse_transform(M)
        B = simplify_matrix(sp.Matrix.hstack(*[ad_apply(Minv[:3, :3], Minv[:3, 3], S[:, k]) for k in range(n)]))
        self._S = sp.ImmutableMatrix(S)
        self._M = sp.ImmutableMatrix(M)
        self._B = sp.ImmutableMatrix(B)
        self._link_homes = homes
        self._name = name
        self._thetas = joint_values(symbols, n, "thetas")
        self._params = tuple(scalar(p, "params") for p in params)
        self._types = "".join("R" if is_revolute(S[:3, i], S[3:, i], "screw_axes") else "P" for i in range(n))

    # ------------------------------------------------------------ properties
    @property
    def dof(self) -> int:
        """Number of joints n."""
        return int(self._S.cols)

    @property
    def screw_axes(self) -> sp.ImmutableMatrix:
        """(6, n) space-frame screw axes at home."""
        return self._S

    @property
    def body_axes(self) -> sp.ImmutableMatrix:
        r"""(6, n) body-frame screw axes :math:`\mathcal B_i = [\mathrm{Ad}_{M^{-1}}]\mathcal S_i`, simplified."""
        return self._B

    @property
    def home(self) -> sp.ImmutableMatrix:
        """(4, 4) home pose M of {b}."""
        return self._M

    @property
    def link_homes(self) -> tuple[sp.ImmutableMatrix, ...] | None:
        """The n home poses of the link frames, or None if not given."""
        return self._link_homes

    @property
    def joint_types(self) -> str:
        """One letter per joint: ``'R'`` revolute, ``'P'`` prismatic (numeric axes; symbolic ones count as R)."""
        return self._types

    @property
    def name(self) -> str | None:
        """Shown in ``repr``."""
        return self._name

    @property
    def thetas(self) -> tuple[sp.Expr, ...]:
        """The joint symbols, the default ``theta`` of every function of the chain."""
        return self._thetas

    @property
    def params(self) -> tuple[sp.Expr, ...]:
        """Other symbols of the chain (link lengths)."""
        return self._params

    def __repr__(self) -> str:
        label = f" {self._name!r}" if self._name else ""
        return f"<SymbolicChain{label}: {self.dof} joints {self._types}, symbols {self._thetas + self._params}>"

    def joint_values(self, theta: object = None) -> tuple[sp.Expr, ...]:
        """``theta`` checked (n symbols or values), or the chain's symbols if None."""
        return self._thetas if theta is None else joint_values(theta, self.dof)

    # ------------------------------------------------------------ kinematics
    def fk(self, theta: object = None, simplify: bool = True) -> sp.Matrix:
        r"""Forward kinematics :math:`T_{sb} = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_n]\theta_n} M`.

        MR: ``FKinSpace``; numeric twin :meth:`jacobians.SerialChain.fk`.

        ``theta`` defaults to the chain's symbols. With ``simplify=True`` the
        partial products are simplified as they are built (fast, and the result
        reads like a textbook); with False every entry is the expanded product.
        """
        return tidy(self.prefix_transforms(theta, simplify)[-1] * self._M, simplify)

    def joint_transforms(self, theta: object = None) -> tuple[sp.Matrix, ...]:
        r"""The n exponentials :math:`e^{[\mathcal S_i]\theta_i}` (:meth:`jacobians.SerialChain.joint_transforms`)."""
        th = self.joint_values(theta)
        return tuple(exp_se3(self._S[:, k], th[k]) for k in range(self.dof))

    def prefix_transforms(self, theta: object = None, simplify: bool = True) -> tuple[sp.Matrix, ...]:
        r"""The n + 1 partial products :math:`e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_i]\theta_i}`, i = 0..n.

        Entry 0 is the identity; numeric twin :meth:`jacobians.SerialChain.prefix_transforms`.
        """
        cache: dict[sp.Expr, sp.Expr] = {}
        out = [sp.eye(4)]
        for E in self.joint_transforms(theta):
            out.append(tidy(out[-1] * E, simplify, cache))
        return tuple(out)

    def link_poses(self, theta: object = None, simplify: bool = True) -> tuple[sp.Matrix, ...]:
        r"""Poses :math:`T_{s,i} = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_i]\theta_i} M_i` of the links."""
        if self._link_homes is None:
            raise ValueError("This chain has no link_homes: give them to SymbolicChain(..., link_homes=...)")
        prefixes = self.prefix_transforms(theta, simplify)
        return tuple(tidy(prefixes[i + 1] * M_i, simplify) for i, M_i in enumerate(self._link_homes))

    @classmethod
    def from_numeric(cls, chain: SerialChain, exact: bool = True, thetas: object = None) -> SymbolicChain:
        """The symbolic twin of a :class:`jacobians.SerialChain` (its link frames and name too).

        With ``exact=True`` each float is replaced by the shortest rational that
        prints like it (0.425 -> 17/40), so sympy can simplify exactly; with
        False the floats are kept. Entries below 1e-12 in size become 0.

        >>> import jacobians as jac
        >>> SymbolicChain.from_numeric(jac.robots.planar_2r(0.5, 0.25)).screw_axes[4, 1]
        -1/2
        """
        if not isinstance(chain, SerialChain):
            raise TypeError(f"Expected a jacobians.SerialChain, got {type(chain).__name__}")

        def conv(x: object) -> sp.Expr:
            x = float(x)  # type: ignore[arg-type]
            if abs(x) < 1e-12:  # round-off left by numeric constructors
                return sp.Integer(0)
            return sp.nsimplify(repr(x), rational=True) if exact else sp.Float(x)

        S = sp.Matrix(6, chain.dof, lambda i, j: conv(chain.screw_axes[i, j]))
        M = sp.Matrix(4, 4, lambda i, j: conv(chain.home[i, j]))
        homes = [sp.Matrix(4, 4, lambda i, j, H=H: conv(H[i, j])) for H in chain.link_homes]
        return cls(S, M, link_homes=homes, name=chain.name, thetas=thetas)


def planar_chain(n: int, lengths: Sequence[object] | None = None
                 ) -> tuple[SymbolicChain, tuple[sp.Symbol, ...], tuple[sp.Expr, ...]]:
    r"""A planar nR arm with symbolic link lengths, the twin of :func:`jacobians.robots.planar`.

    Joint i turns about z through :math:`(l_1 + \dots + l_{i-1}, 0, 0)`; the tool
    frame {b} is at :math:`(l_1 + \dots + l_n, 0, 0)` with the orientation of {s};
    the link frames are at the middle of each link.

    Parameters
    ----------
    n : int, at least 1
    lengths : sequence of n numbers or sympy expressions, optional
        Default: positive real symbols ``l1 .. ln``.

    Returns
    -------
    (chain, thetas, lengths) : the SymbolicChain, its n joint symbols ``theta1 .. thetan``,
        and the n link lengths (the symbols, or the values given).

    >>> arm, th, ls = planar_chain(3)
    >>> arm.screw_axes[:, 2].T
    Matrix([[0, 0, 1, 0, -l1 - l2, 0]])
    """
    if isinstance(n, bool) or not isinstance(n, numbers.Integral):
        raise TypeError(f"Expected an integer number of joints n, got {describe(n)}")
    if n < 1:
        raise ValueError(f"Expected at least one joint, got n = {n}")
    thetas = sp.symbols(f"theta1:{n + 1}", real=True)
    ls: tuple[sp.Expr, ...]
    if lengths is None:
        ls = sp.symbols(f"l1:{n + 1}", positive=True)
        params: tuple[sp.Expr, ...] = ls
    else:
        if isinstance(lengths, (str, bytes)) or not hasattr(lengths, "__len__"):
            raise TypeError(f"Expected a sequence of {n} link lengths, got {describe(lengths)}")
        if len(lengths) != n:
            raise ValueError(f"Expected {n} link lengths, got {len(lengths)}")
        ls = tuple(scalar(v, f"lengths[{i}]") for i, v in enumerate(lengths))
        for i, v in enumerate(ls):
            if v.is_number and not v.is_positive:
                raise ValueError(f"Expected positive link lengths, got lengths[{i}] = {v}")
        params = tuple(sorted(set().union(*[v.free_symbols for v in ls]), key=str))
    x = [sp.Integer(0)]
    for v in ls:
        x.append(x[-1] + v)
    S = sp.zeros(6, n)
    for i in range(n):  # revolute about z through q = (x_i, 0, 0): v = -w x q = (0, -x_i, 0)
        S[2, i] = 1
        S[4, i] = -x[i]
    M = sp.eye(4)
    M[0, 3] = x[n]
    homes = []
    for i in range(n):
        M_i = sp.eye(4)
        M_i[0, 3] = x[i] + ls[i] / 2
        homes.append(M_i)
    chain = SymbolicChain(S, M, link_homes=homes, thetas=thetas, params=params)
    return chain, tuple(thetas), tuple(ls)


def to_numeric_chain(chain: SymbolicChain, values: dict[sp.Symbol, object] | None = None,
                     name: str | None = None) -> SerialChain:
    r"""The numeric :class:`jacobians.SerialChain` of a symbolic chain with its parameters substituted.

    ``values`` gives a number for every parameter (link length) of the chain.

    >>> arm, th, (l1, l2) = planar_chain(2)
    >>> to_numeric_chain(arm, {l1: 1.0, l2: 0.5}).home[0, 3]
    np.float64(1.5)
    """
    if not isinstance(chain, SymbolicChain):
        raise TypeError(f"Expected a SymbolicChain, got {type(chain).__name__}")
    values = {} if values is None else values
    if not isinstance(values, dict):
        raise TypeError(f"Expected a dict {{symbol: value}} for values, got {describe(values)}")
    subs = {k: scalar(v, f"values[{k}]") for k, v in values.items()}
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
                       link_homes=link_homes, name=name if name is not None else chain.name)
