r"""Bridges to other conventions and libraries.

The course orders every 6-row quantity angular first, :math:`(\omega, v)`.
Many books (Siciliano et al.) and libraries (Pinocchio, Corke's Robotics
Toolbox) order linear first, :math:`(v, \omega)`. The swap is the permutation

.. math:: P = \begin{bmatrix} 0 & I_3 \\ I_3 & 0 \end{bmatrix}, \qquad P = P^{-1} = P^T .

Pinocchio's reference frames (``pinocchio.ReferenceFrame``) relate to our
Jacobians as follows (proved in the conversions chapter, checked in the tests):

=========================  =====================================
Pinocchio                  ours
=========================  =====================================
``LOCAL``                  :math:`P\,J_b` (body Jacobian)
``WORLD``                  :math:`P\,J_s` (space Jacobian)
``LOCAL_WORLD_ALIGNED``    :math:`P\,J` (geometric Jacobian)
=========================  =====================================

>>> import numpy as np
>>> J = np.arange(12.0).reshape(6, 2)
>>> np.array_equal(to_linear_first(to_linear_first(J)), J)
True
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import jacobian_array
from .chain import SerialChain, _as_chain

__all__ = ["to_linear_first", "to_angular_first", "SWAP", "to_pinocchio_model"]

#: The 6x6 permutation that swaps the angular and linear halves.
SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


def to_linear_first(J: ArrayLike) -> NDArray[np.float64]:
    """Reorder rows from (ω, v) to (v, ω): shape (..., 6, n) or (..., 6) for a twist."""
    J = np.asarray(J, dtype=float)
    if J.ndim >= 1 and J.shape[-1] == 6 and (J.ndim == 1 or J.shape[-2] != 6):
        return np.concatenate([J[..., 3:], J[..., :3]], axis=-1)
    J = jacobian_array(J, "J")
    return np.concatenate([J[..., 3:, :], J[..., :3, :]], axis=-2)


def to_angular_first(J: ArrayLike) -> NDArray[np.float64]:
    """Reorder rows from (v, ω) to (ω, v); the same permutation, which is its own inverse."""
    return to_linear_first(J)


def to_pinocchio_model(chain: SerialChain) -> tuple[Any, int]:
    """A Pinocchio model of the chain, with the tool frame {b} as an operational frame named ``"tool"``.

    Each joint i becomes a ``JointModelRevoluteUnaligned`` (or
    ``JointModelPrismaticUnaligned``) placed at a point of its axis, with
    all joint frames aligned with {s} at the home pose. Revolute joints with a
    nonzero pitch are refused (Pinocchio has no helical joint of this form).
    Needs the ``pin`` package.

    Returns
    -------
    (model, tool_frame_id) : (pinocchio.Model, int)
    """
    import pinocchio as pin

    chain = _as_chain(chain)
    S = chain.screw_axes
    model = pin.Model()
    parent = 0
    prev = np.zeros(3)
    for i in range(chain.dof):
        w, v = S[:3, i], S[3:, i]
        if chain.joint_types[i] == "R":
            if abs(np.dot(w, v)) > 1e-9:
                raise ValueError(f"Joint {i} is a screw with nonzero pitch; Pinocchio has no such joint model")
            point = np.cross(w, v)
            joint = pin.JointModelRevoluteUnaligned(*w)
        else:
            point = prev
            joint = pin.JointModelPrismaticUnaligned(*v)
        placement = pin.SE3(np.eye(3), point - prev)
        jid = model.addJoint(parent, joint, placement, f"joint{i + 1}")
        model.appendBodyToJoint(jid, pin.Inertia.FromSphere(1.0, 0.1), pin.SE3.Identity())
        parent, prev = jid, point
    M = chain.home
    tool = pin.SE3(M[:3, :3].copy(), M[:3, 3] - prev)
    fid = model.addFrame(pin.Frame("tool", parent, tool, pin.FrameType.OP_FRAME))
    return model, fid
