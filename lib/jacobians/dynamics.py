r"""Gravity torques from the link Jacobians.

Link i of a chain has mass :math:`m_i` with its centre of mass at a point
fixed to the link. With gravity :math:`\mathfrak g` (an acceleration, e.g.
:math:`(0, 0, -9.81)` m/s² in {s}) the potential energy is
:math:`P(\theta) = -\sum_i m_i\,\mathfrak g^T c_i(\theta)`, where
:math:`c_i(\theta)` is the centre of mass of link i in {s}. The torques that
hold the arm still against its weight are the gradient

.. math:: \tau_g(\theta) = \frac{\partial P}{\partial\theta}
          = -\sum_i J_{v,c_i}(\theta)^T m_i\,\mathfrak g ,

where :math:`J_{v,c_i} = \partial c_i/\partial\theta` is the linear part of the
geometric Jacobian of the centre of mass of link i (the link Jacobians of
chapter 8: columns after joint i are zero). It is the statics formula
:math:`\tau = J^T\mathcal F` applied to each link, with the wrench
:math:`\mathcal F_i = -m_i\mathfrak g` that the joints must supply to cancel the weight.
In the dynamics :math:`\tau = M(\theta)\ddot\theta + c(\theta,\dot\theta) + \tau_g(\theta)`
it is the term :math:`g(\theta)` (MR: ``GravityForces``; Pinocchio:
``computeGeneralizedGravity``).

**Computed in O(n).** With space Jacobians the weight of link i is the wrench
:math:`\mathcal F_i = (c_i\times f_i,\ f_i)`, :math:`f_i = -m_i\mathfrak g`, in
{s}; link i's space Jacobian has the columns of :math:`J_s` up to i and zeros
after, so :math:`\tau_k = J_{sk}^T\sum_{i\ge k}\mathcal F_i`.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()        # links along x, centres at mid-link, gravity along -y
>>> gravity_torques(arm, [0.0, 0.0], masses=[1.0, 1.0], gravity=[0, -9.81, 0]).round(6)
array([19.62 ,  4.905])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_finite, real_array, theta_array
from .chain import SerialChain, _as_chain
from .jacobian import _evaluate_pose

__all__ = ["gravity_torques", "centres_of_mass", "potential_energy"]

#: Standard gravity along -z of {s}, m/s².
GRAVITY = (0.0, 0.0, -9.81)


def _masses(masses: object, n: int) -> NDArray[np.float64]:
    m = as_float_array(masses, "masses")
    if m.shape != (n,):
        raise ValueError(f"Expected masses with shape ({n},), one per link, got shape {m.shape}")
    check_finite(m, "masses")
    if np.any(m < 0):
        raise ValueError(f"Expected non-negative masses, got {m}")
    return m


def _centres(centres: object, n: int) -> NDArray[np.float64]:
    if centres is None:
        return np.zeros((n, 3))
    c = real_array(centres, "centres", (n, 3), batch_allowed=False)
    return c


def centres_of_mass(chain: SerialChain, theta: ArrayLike, centres: ArrayLike | None = None) -> NDArray[np.float64]:
    r"""Centres of mass :math:`c_i(\theta)` of the links in {s}, shape (..., n, 3).

    ``centres`` (shape (n, 3)) gives each centre in its link frame
    (``chain.link_homes``); default: the link frames' origins.

    >>> import jacobians as jac
    >>> centres_of_mass(jac.robots.planar_2r(), [0.0, 0.0])[:, 0]
    array([0.5, 1.5])
    """
    chain = _as_chain(chain)
    n = chain.dof
    th = theta_array(theta, n)
    c = _centres(centres, n)
    T = chain.link_poses(th)
    out: NDArray[np.float64] = (T[..., :3, :3] @ c[:, :, None])[..., 0] + T[..., :3, 3]
    return out


def _gravity(gravity: object) -> NDArray[np.float64]:
    g = as_float_array(gravity, "gravity")
    if g.shape != (3,):
        raise ValueError(f"Expected gravity with shape (3,), an acceleration in {{s}}, got shape {g.shape}")
    return check_finite(g, "gravity")


def potential_energy(chain: SerialChain, theta: ArrayLike, masses: ArrayLike, gravity: ArrayLike = GRAVITY,
                     centres: ArrayLike | None = None) -> NDArray[np.float64]:
    r"""Potential energy :math:`P(\theta) = -\sum_i m_i\,\mathfrak g^T c_i(\theta)`, shape (...).

    Zero level at the origin of {s}. The oracle of :func:`gravity_torques`.

    >>> import jacobians as jac
    >>> float(potential_energy(jac.robots.planar_2r(), [1.5707963267948966, 0.0], [1.0, 1.0], [0, -9.81, 0]))
    19.62
    """
    chain = _as_chain(chain)
    m = _masses(masses, chain.dof)
    g = _gravity(gravity)
    c = centres_of_mass(chain, theta, centres)
    out: NDArray[np.float64] = -np.einsum("i,...ij,j->...", m, c, g)
    return out


def gravity_torques(chain: SerialChain, theta: ArrayLike, masses: ArrayLike, gravity: ArrayLike = GRAVITY,
                    centres: ArrayLike | None = None) -> NDArray[np.float64]:
    r"""Joint torques that hold the arm against its weight, :math:`-\sum_i J_{v,c_i}^T m_i\mathfrak g`.

    Parameters
    ----------
    chain : SerialChain
        Its ``link_homes`` fix the frame of each link.
    theta : array_like, shape (..., n)
    masses : array_like, shape (n,)
        :math:`m_i \ge 0`.
    gravity : array_like, shape (3,)
        The acceleration of gravity in {s}; default ``(0, 0, -9.81)``.
    centres : array_like, shape (n, 3), optional
        Centre of mass of link i in link frame i; default the frame's origin
        (the teaching robots put the link frames at the middle of the links).

    Returns
    -------
    tau_g : ndarray, shape (..., n)
        :math:`\partial P/\partial\theta`; the gravity term :math:`g(\theta)` of
        the equations of motion (forces for prismatic joints).

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> th = np.array([0.4, -1.1])
    >>> fd = jac.numerical_jacobian(lambda t: potential_energy(arm, t, [2.0, 1.0], [0, -9.81, 0]), th)
    >>> np.allclose(gravity_torques(arm, th, [2.0, 1.0], [0, -9.81, 0]), fd)
    True
    """
    chain = _as_chain(chain)
    n = chain.dof
    th = theta_array(theta, n)
    m = _masses(masses, n)
    g = _gravity(gravity)
    c = centres_of_mass(chain, th, centres)  # (..., n, 3)
    J_s, _ = _evaluate_pose(chain, th, "space", with_pose=False)  # (..., 6, n)
    f = -m[:, None] * g  # (n, 3): the force that holds link i
    F = np.concatenate([np.cross(c, f), np.broadcast_to(f, c.shape)], axis=-1)  # (..., n, 6) wrenches in {s}
    tail = np.cumsum(F[..., ::-1, :], axis=-2)[..., ::-1, :]  # sum over i >= k
    tau: NDArray[np.float64] = np.einsum("...jk,...kj->...k", J_s, tail)
    return tau
