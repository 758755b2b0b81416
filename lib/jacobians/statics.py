r"""Statics: the joint torques that hold a wrench, :math:`\tau = J^T\mathcal F`.

A wrench is :math:`\mathcal F = (m, f)`, moment first, matching the twist
order :math:`(\omega, v)`, so that the power :math:`\mathcal F^T\mathcal V`
is a plain dot product. By the principle of virtual work
:math:`\tau^T\dot\theta = \mathcal F^T\mathcal V` for every motion, so
:math:`\tau = J^T\mathcal F` **with J and F in the same frame**:
:math:`\tau = J_s^T\mathcal F_s = J_b^T\mathcal F_b`. The torques are what the
joints must apply to hold the end-effector against the wrench
:math:`\mathcal F` it applies to the environment (MR Section 5.2).

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r(l1=1.0, l2=1.0)
>>> F_b = [0, 0, 0, 0, 1.0, 0]       # 1 N along y_b at the tip, stretched out
>>> joint_torques_from_wrench(arm, [0.0, 0.0], F_b, frame="body")
array([2., 1.])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_finite, transform_array
from .chain import SerialChain, _as_chain
from .frames import TWIST_FRAMES, Frame, check_frame
from .jacobian import jacobian
from .lie import _adjoint, _inverse_transform

__all__ = ["joint_torques", "joint_torques_from_wrench", "wrench_body_to_space", "wrench_space_to_body"]


def _wrench(F: object, m: int, name: str = "wrench") -> NDArray[np.float64]:
    F = as_float_array(F, name)
    if F.ndim < 1 or F.shape[-1] != m:
        hint = " as (m_x, m_y, m_z, f_x, f_y, f_z), moment first" if m == 6 else ""
        raise ValueError(f"Expected {name} with shape (..., {m}){hint}, got shape {F.shape}")
    return check_finite(F, name)


def joint_torques(J: ArrayLike, wrench: ArrayLike) -> NDArray[np.float64]:
    r"""Joint torques :math:`\tau = J^T\mathcal F` (forces for prismatic joints).

    J and the wrench must be expressed in the same frame and the same row
    order: :math:`J_s` with :math:`\mathcal F_s`, :math:`J_b` with
    :math:`\mathcal F_b`, a block of rows with the matching components. For
    the geometric Jacobian :math:`(\omega_s, \dot p)` the matching "wrench" is
    :math:`(m, f)` with the moment taken about the origin of {b} and both
    expressed in {s}. MR: :math:`\tau = J_b^T(\theta)\mathcal F_b` of Section 5.2.

    Parameters
    ----------
    J : array_like, shape (..., m, n)
    wrench : array_like, shape (..., m)

    Returns
    -------
    tau : ndarray, shape (..., n)

    >>> import numpy as np
    >>> J = np.array([[0.0, 0.0], [1.0, 1.0]])      # rows: x, y velocities
    >>> joint_torques(J, [5.0, 2.0])
    array([2., 2.])
    """
    A = as_float_array(J, "J")
    if A.ndim < 2 or A.shape[-1] == 0 or A.shape[-2] == 0:
        raise ValueError(f"Expected J with shape (..., m, n), got shape {A.shape}")
    check_finite(A, "J")
    F = _wrench(wrench, A.shape[-2])
    try:
        np.broadcast_shapes(A.shape[:-2], F.shape[:-1])
    except ValueError:
        raise ValueError(f"The batch shapes of J {A.shape[:-2]} and wrench {F.shape[:-1]} do not broadcast") from None
    tau: NDArray[np.float64] = (np.swapaxes(A, -1, -2) @ F[..., :, None])[..., 0]
    return tau


def joint_torques_from_wrench(chain: SerialChain, theta: ArrayLike, wrench: ArrayLike,
                              frame: Frame = "space") -> NDArray[np.float64]:
    r"""Joint torques that hold the wrench :math:`\mathcal F = (m, f)` at configuration theta.

    Parameters
    ----------
    chain : SerialChain
    theta : array_like, shape (..., n)
    wrench : array_like, shape (..., 6)
        ``frame="space"``: :math:`\mathcal F_s`, moment about the origin of {s},
        components in {s}; :math:`\tau = J_s^T\mathcal F_s`.
        ``frame="body"``: :math:`\mathcal F_b`, moment about the origin of {b},
        components in {b}; :math:`\tau = J_b^T\mathcal F_b`.
    frame : {"space", "body"}

    Returns
    -------
    tau : ndarray, shape (..., n)

    Notes
    -----
    The two agree for the same physical wrench,
    :math:`\mathcal F_b = [\mathrm{Ad}_{T_{sb}}]^T\mathcal F_s`
    (:func:`wrench_space_to_body`). MR: Section 5.2.

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> # the tip, at (2, 0, 0), pushes down on a table with 9.81 N:
    >>> # f = (0, -9.81, 0), moment about the origin of {s} = (2, 0, 0) x f
    >>> F_s = [0, 0, 2 * -9.81, 0, -9.81, 0]
    >>> joint_torques_from_wrench(arm, [0.0, 0.0], F_s, frame="space")
    array([-19.62,  -9.81])
    """
    frame = check_frame(frame, TWIST_FRAMES)
    J = jacobian(_as_chain(chain), theta, frame)
    return joint_torques(J, _wrench(wrench, 6))


def wrench_space_to_body(F_s: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`\mathcal F_b = [\mathrm{Ad}_{T_{sb}}]^T\mathcal F_s` (the same wrench, seen in {b}).

    Wrenches change frame with the transposed adjoint, so that
    :math:`\mathcal F_b^T\mathcal V_b = \mathcal F_s^T\mathcal V_s`. MR: Section 3.3 (wrenches).

    Parameters
    ----------
    F_s : array_like, shape (..., 6), (m, f)
    T_sb : array_like, shape (..., 4, 4)

    Returns
    -------
    F_b : ndarray, shape (..., 6)

    >>> import numpy as np
    >>> T_sb = np.eye(4); T_sb[0, 3] = 2.0
    >>> # 1 N along y through the origin of {b}: its moment about {s} is (2, 0, 0) x f
    >>> wrench_space_to_body([0, 0, 2.0, 0, 1.0, 0], T_sb) + 0.0
    array([0., 0., 0., 0., 1., 0.])
    >>> # the same force through the origin of {s} has a moment about {b}
    >>> wrench_space_to_body([0, 0, 0, 0, 1.0, 0], T_sb) + 0.0
    array([ 0.,  0., -2.,  0.,  1.,  0.])
    """
    F = _wrench(F_s, 6, "F_s")
    T = transform_array(T_sb, "T_sb")
    F_b: NDArray[np.float64] = (np.swapaxes(_adjoint(T), -1, -2) @ F[..., :, None])[..., 0]
    return F_b


def wrench_body_to_space(F_b: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`\mathcal F_s = [\mathrm{Ad}_{T_{bs}}]^T\mathcal F_b`, the inverse of :func:`wrench_space_to_body`.

    >>> import numpy as np
    >>> T_sb = np.eye(4); T_sb[0, 3] = 2.0
    >>> wrench_body_to_space([0, 0, 0, 0, 1.0, 0], T_sb)   # moment 2 N m about z_s
    array([0., 0., 2., 0., 1., 0.])
    """
    F = _wrench(F_b, 6, "F_b")
    T = transform_array(T_sb, "T_sb")
    F_s: NDArray[np.float64] = (np.swapaxes(_adjoint(_inverse_transform(T)), -1, -2) @ F[..., :, None])[..., 0]
    return F_s
