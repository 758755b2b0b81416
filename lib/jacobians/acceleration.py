r"""The time derivative of the Jacobian, and the acceleration of the end-effector.

Along a motion :math:`\theta(t)` the Jacobian changes, and differentiating
:math:`\mathcal V = J(\theta)\dot\theta` once more gives the acceleration

.. math:: \dot{\mathcal V} = J(\theta)\,\ddot\theta + \dot J(\theta, \dot\theta)\,\dot\theta .

:func:`jacobian_derivative` computes :math:`\dot J` in closed form, with no
differentiation, from the Lie bracket of twists; :func:`acceleration` returns
:math:`J\ddot\theta + \dot J\dot\theta`.

**The bracket form, and why it holds.** Write
:math:`[\mathrm{ad}_{\mathcal V}] = \begin{bmatrix}[\omega] & 0\\ [v] & [\omega]\end{bmatrix}`
(:func:`jacobians.lie.ad`).

*Lemma.* If :math:`T(t)` is a motion with space twist :math:`[\mathcal V] =
\dot TT^{-1}` and :math:`X` a constant twist, then
:math:`\tfrac{d}{dt}[\mathrm{Ad}_T]X = [\mathrm{ad}_{\mathcal V}][\mathrm{Ad}_T]X`.
*Proof.* In matrix form :math:`[\mathrm{Ad}_T X] = T[X]T^{-1}`, so its derivative
is :math:`\dot T[X]T^{-1} - T[X]T^{-1}\dot TT^{-1} = [\mathcal V]Y - Y[\mathcal V]`
with :math:`Y = T[X]T^{-1}`, and the commutator of two se(3) matrices is the
matrix of :math:`[\mathrm{ad}_{\mathcal V}]` applied to the second.
If instead :math:`[\mathcal V_b] = T^{-1}\dot T` (body twist), the same
computation for :math:`T^{-1}[X]T` gives
:math:`\tfrac{d}{dt}[\mathrm{Ad}_{T^{-1}}]X = -[\mathrm{ad}_{\mathcal V_b}][\mathrm{Ad}_{T^{-1}}]X`.

*Space Jacobian.* :math:`J_{si} = [\mathrm{Ad}_{T_{i-1}}]\mathcal S_i` with
:math:`T_{i-1} = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_{i-1}]\theta_{i-1}}`.
The space twist of :math:`T_{i-1}` is that of a chain made of joints
:math:`1..i-1`, whose space Jacobian is the first :math:`i-1` columns of
:math:`J_s`; so by the lemma

.. math:: \dot J_{si} = \Big[\mathrm{ad}_{\sum_{j<i} J_{sj}\dot\theta_j}\Big] J_{si} .

*Body Jacobian.* :math:`J_b = [\mathrm{Ad}_{T_{sb}^{-1}}]J_s`. The lemma (body
form, with :math:`\mathcal V_b = J_b\dot\theta`) and the product rule give
:math:`\dot J_b = [\mathrm{Ad}_{T_{sb}^{-1}}]\dot J_s - [\mathrm{ad}_{\mathcal V_b}]J_b`;
since :math:`[\mathrm{Ad}_{T^{-1}}]` preserves brackets, the first term is
:math:`\sum_{j<i}[\mathrm{ad}_{J_{bj}\dot\theta_j}]J_{bi}`, and as
:math:`[\mathrm{ad}_{J_{bi}}]J_{bi} = 0` what is left is

.. math:: \dot J_{bi} = -\Big[\mathrm{ad}_{\sum_{j>i} J_{bj}\dot\theta_j}\Big] J_{bi} .

*Geometric Jacobian.* :math:`J = \begin{bmatrix}I&0\\-[p]&I\end{bmatrix}J_s`,
and :math:`\dot p` is the linear part of :math:`J\dot\theta`, so

.. math:: \dot J = \begin{bmatrix}I&0\\-[p]&I\end{bmatrix}\dot J_s
          + \begin{bmatrix}0&0\\-[\dot p]&0\end{bmatrix}J_s .

Pinocchio: ``computeJointJacobiansTimeVariation`` then
``getFrameJacobianTimeVariation`` in ``WORLD``, ``LOCAL`` and
``LOCAL_WORLD_ALIGNED`` give the same three matrices with the rows in the order
:math:`(v, \omega)` (the tests check it). MR's code has no :math:`\dot J`.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()
>>> Jdot = jacobian_derivative(arm, [0.0, np.pi / 2], [1.0, 0.0], "geometric")
>>> Jdot[3:5].round(12) + 0.0   # columns (-1, 1), (-1, 0) turn at 1 rad/s: z x column
array([[-1.,  0.],
       [-1., -1.]])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import theta_array
from .chain import SerialChain, _as_chain
from .frames import Frame, check_frame
from .jacobian import _evaluate_pose

__all__ = ["jacobian_derivative", "acceleration", "bracket"]

_FRAMES = ("space", "body", "geometric")


def _cross(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """a x b along axis -2 (the 3 rows), broadcasting the rest."""
    out: NDArray[np.float64] = np.stack(
        [a[..., 1, :] * b[..., 2, :] - a[..., 2, :] * b[..., 1, :],
         a[..., 2, :] * b[..., 0, :] - a[..., 0, :] * b[..., 2, :],
         a[..., 0, :] * b[..., 1, :] - a[..., 1, :] * b[..., 0, :]], axis=-2)
    return out


def bracket(V: NDArray[np.float64], X: NDArray[np.float64]) -> NDArray[np.float64]:
    r"""Column-wise Lie bracket :math:`[\mathrm{ad}_{V_k}]X_k` of twists stored as columns, shape (..., 6, n).

    :math:`[\mathrm{ad}_{(\omega, v)}](\omega_x, v_x) = (\omega\times\omega_x,\ v\times\omega_x + \omega\times v_x)`.
    No validation (internal building block, exposed for the chapters' checks).

    >>> import numpy as np
    >>> from jacobians import lie
    >>> V, X = np.arange(6.0)[:, None], np.array([1.0, -2, 0.5, 3, 1, -1])[:, None]
    >>> np.allclose(bracket(V, X)[:, 0], lie.ad(V[:, 0]) @ X[:, 0])
    True
    """
    w, v = V[..., :3, :], V[..., 3:, :]
    wx, vx = X[..., :3, :], X[..., 3:, :]
    return np.concatenate([_cross(w, wx), _cross(v, wx) + _cross(w, vx)], axis=-2)


def _rates(chain: SerialChain, theta: ArrayLike, theta_dot: ArrayLike,
           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    n = chain.dof
    th = theta_array(theta, n)
    thd = theta_array(theta_dot, n, "theta_dot")
    try:
        shape = np.broadcast_shapes(th.shape, thd.shape)
    except ValueError:
        raise ValueError(
            f"The batch shapes of theta {th.shape[:-1]} and theta_dot {thd.shape[:-1]} do not broadcast"
        ) from None
    return np.broadcast_to(th, shape), np.broadcast_to(thd, shape)


def _derivative_and_jacobian(chain: SerialChain, th: NDArray[np.float64], thd: NDArray[np.float64],
                             frame: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(J̇, J) in ``frame`` for broadcast-equal th, thd of shape (..., n)."""
    if frame == "body":
        J, _ = _evaluate_pose(chain, th, "body", with_pose=False)
        cols = J * thd[..., None, :]  # J_bj θ̇_j
        # Q_i = sum_{j > i} J_bj θ̇_j: reverse cumulative sum, shifted by one
        after = np.cumsum(cols[..., ::-1], axis=-1)[..., ::-1] - cols
        return -bracket(after, J), J
    J_s, T = _evaluate_pose(chain, th, "space", with_pose=True)
    assert T is not None
    cols = J_s * thd[..., None, :]
    before = np.cumsum(cols, axis=-1) - cols  # P_i = sum_{j < i} J_sj θ̇_j
    Jd_s = bracket(before, J_s)
    if frame == "space":
        return Jd_s, J_s
    p = T[..., :3, 3][..., :, None]  # (..., 3, 1)
    w, wd = J_s[..., :3, :], Jd_s[..., :3, :]
    J = np.concatenate([w, J_s[..., 3:, :] - _cross(np.broadcast_to(p, w.shape), w)], axis=-2)
    pdot = (J[..., 3:, :] @ thd[..., :, None])  # (..., 3, 1)
    lin = Jd_s[..., 3:, :] - _cross(np.broadcast_to(p, wd.shape), wd) - _cross(np.broadcast_to(pdot, w.shape), w)
    return np.concatenate([wd, lin], axis=-2), J


def jacobian_derivative(chain: SerialChain, theta: ArrayLike, theta_dot: ArrayLike,
                        frame: Frame = "space") -> NDArray[np.float64]:
    r"""The time derivative :math:`\dot J = \frac{d}{dt}J(\theta(t))` when the joints move at :math:`\dot\theta`.

    :math:`\dot J = \sum_k \frac{\partial J}{\partial\theta_k}\dot\theta_k`, linear
    in :math:`\dot\theta`: with :math:`\dot\theta = e_k` it is
    :math:`\partial J/\partial\theta_k`. Computed from the bracket form of the
    module docstring, in O(n) brackets.

    Parameters
    ----------
    chain : SerialChain
    theta : array_like, shape (..., n)
    theta_dot : array_like, shape (..., n)
        Joint rates; batch shapes of ``theta`` and ``theta_dot`` broadcast.
    frame : {"space", "body", "geometric"}
        ``"space"``: :math:`\dot J_s`, column i is
        :math:`[\mathrm{ad}_{\sum_{j<i}J_{sj}\dot\theta_j}]J_{si}`.
        ``"body"``: :math:`\dot J_b`, column i is
        :math:`-[\mathrm{ad}_{\sum_{j>i}J_{bj}\dot\theta_j}]J_{bi}`.
        ``"geometric"``: :math:`\dot J` of :math:`(\omega_s, \dot p)`.
        The analytic Jacobian is refused (its derivative needs the
        derivative of :math:`B(\phi)^{-1}`, which this library does not provide).

    Returns
    -------
    J_dot : ndarray, shape (..., 6, n)

    >>> import numpy as np
    >>> import jacobians as jac
    >>> ur = jac.robots.ur5()
    >>> th, thd = np.full(6, 0.3), np.linspace(-1, 1, 6)
    >>> fd = (jac.body_jacobian(ur, th + 1e-6 * thd) - jac.body_jacobian(ur, th - 1e-6 * thd)) / 2e-6
    >>> np.allclose(jacobian_derivative(ur, th, thd, "body"), fd, atol=1e-8)
    True
    >>> jacobian_derivative(ur, th, thd, "analytic")
    Traceback (most recent call last):
    ...
    ValueError: Expected frame 'space', 'body' or 'geometric', got 'analytic'
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, _FRAMES)
    th, thd = _rates(chain, theta, theta_dot)
    return _derivative_and_jacobian(chain, th, thd, frame)[0]


def acceleration(chain: SerialChain, theta: ArrayLike, theta_dot: ArrayLike, theta_ddot: ArrayLike,
                 frame: Frame = "geometric") -> NDArray[np.float64]:
    r"""The end-effector acceleration :math:`J\ddot\theta + \dot J\dot\theta`, shape (..., 6).

    It is the time derivative of :math:`J\dot\theta` in the chosen frame:

    * ``"geometric"`` (default): :math:`(\dot\omega_s, \ddot p)`, the angular
      acceleration of {b} in {s} and the ordinary acceleration of the origin of {b}
      (the classical acceleration: what an accelerometer at the tool, minus gravity, reads, in {s} axes);
    * ``"space"``: :math:`\dot{\mathcal V}_s`, the derivative of the space twist;
    * ``"body"``: :math:`\dot{\mathcal V}_b`, the derivative of the body twist.
      Its linear part is :math:`\dot v_b`, *not* the tool's acceleration in {b}
      axes, which is :math:`\dot v_b + \omega_b\times v_b`.

    Parameters
    ----------
    theta, theta_dot, theta_ddot : array_like, shape (..., n), broadcasting
    frame : {"space", "body", "geometric"}

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()     # spinning joint 1 at 1 rad/s, stretched out
    >>> acceleration(arm, [0.0, 0.0], [1.0, 0.0], [0.0, 0.0])[3:5] + 0.0   # centripetal: -2 m/s^2 along x
    array([-2.,  0.])
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, _FRAMES)
    th, thd = _rates(chain, theta, theta_dot)
    thdd = theta_array(theta_ddot, chain.dof, "theta_ddot")
    try:
        np.broadcast_shapes(th.shape, thdd.shape)
    except ValueError:
        raise ValueError(
            f"The batch shapes of theta {th.shape[:-1]} and theta_ddot {thdd.shape[:-1]} do not broadcast"
        ) from None
    Jd, J = _derivative_and_jacobian(chain, th, thd, frame)
    out: NDArray[np.float64] = (J @ thdd[..., :, None] + Jd @ thd[..., :, None])[..., 0]
    return out
