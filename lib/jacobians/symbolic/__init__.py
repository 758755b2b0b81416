r"""Symbolic Jacobians with sympy, mirroring the numeric library name for name.

The same functions as :mod:`jacobians.lie` and :mod:`jacobians.jacobian`, with
the same names and argument order, on sympy matrices of joint symbols and link
lengths, so a chapter can show the closed form and a check can compare it with
the numbers. :class:`SymbolicChain` is shaped like :class:`jacobians.SerialChain`
(read-only properties ``screw_axes``, ``body_axes``, ``home``, ``link_homes``,
``dof``, ``joint_types``, ``name``; method ``fk``) and adds its joint symbols
``thetas`` and other symbols ``params``. Everywhere ``theta`` defaults to the
chain's symbols.

=======================================  ============================================
numeric                                  symbolic
=======================================  ============================================
``lie.exp_se3(S * t)``                   ``exp_se3(S, t)`` (axis and angle apart)
``lie.twist_to_matrix(V)``, ...          ``twist_to_matrix(V)``, ...
``jac.space_jacobian(chain, theta)``     ``space_jacobian(chain, theta)``
``jac.link_jacobians(chain, theta, f)``  ``link_jacobians(chain, theta, f)`` (a tuple)
``chain.fk(theta)``                      ``chain.fk(theta)``
=======================================  ============================================

Modules: :mod:`.lie` (SO(3), SE(3)), :mod:`.chain` (chains), :mod:`.jacobian`
(Jacobians and conversions), :mod:`.simplify` (simplification, exact zero
tests, numeric functions). Strings are refused everywhere: nothing parses text.
``import jacobians`` does not import sympy; this package does.

>>> from jacobians import symbolic as sym
>>> arm, (t1, t2), (l1, l2) = sym.planar_chain(2)
>>> sym.space_jacobian(arm, (t1, t2))[3:5, :]
Matrix([
[0,  l1*sin(theta1)],
[0, -l1*cos(theta1)]])
"""

from .chain import SymbolicChain, planar_chain, to_numeric_chain
from .jacobian import (
    SYMBOLIC_FRAMES,
    body_jacobian,
    body_to_geometric,
    body_to_space,
    geometric_jacobian,
    geometric_to_body,
    geometric_to_space,
    jacobian,
    link_jacobians,
    space_jacobian,
    space_to_body,
    space_to_geometric,
)
from .lie import (
    ad,
    adjoint,
    exp_se3,
    exp_so3,
    inverse_transform,
    make_transform,
    matrix_to_twist,
    rotation_about,
    skew,
    twist_to_matrix,
    unskew,
)
from .simplify import MatrixFunction, is_zero, is_zero_matrix, lambdify_matrix, simplify_matrix

__all__ = [
    "SymbolicChain",
    "planar_chain",
    "to_numeric_chain",
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
    "simplify_matrix",
    "is_zero",
    "is_zero_matrix",
    "lambdify_matrix",
    "MatrixFunction",
]
