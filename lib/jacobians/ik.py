r"""Numerical inverse kinematics with the Jacobian.

Given a wanted pose :math:`T_{sd}` of the end-effector, find :math:`\theta`
with :math:`T_{sb}(\theta) = T_{sd}`. Two solvers:

* :func:`ik` drives the pose error to zero by iteration, the
  Newton–Raphson method of Modern Robotics §6.2 and its damped and
  transpose variants;
* :func:`clik` makes the arm *follow* a moving pose, closed-loop inverse
  kinematics (Siciliano et al. §3.7) with an orientation error.

**The error is a twist.** At :math:`\theta_k` the body twist
:math:`\mathcal V_b = \log(T_{sb}(\theta_k)^{-1}T_{sd})^\vee` is the constant
twist that, followed for unit time, carries {b} onto {d} (MR §6.2). To first
order a joint step :math:`\Delta\theta` moves {b} by the twist
:math:`J_b(\theta_k)\Delta\theta` (in {b}), so the Newton step solves
:math:`J_b\Delta\theta = \mathcal V_b`. The same step in {s} uses
:math:`\mathcal V_s = [\mathrm{Ad}_{T_{sb}}]\mathcal V_b` and :math:`J_s`
(MR's ``IKinSpace``); the iteration stops when
:math:`\|\omega\| \le \varepsilon_\omega` and :math:`\|v\| \le \varepsilon_v`
for the error twist :math:`(\omega, v)` of the chosen frame.

Which step (``method``):

=============  ==============================================  ==========================================
``method``     step :math:`\Delta\theta`                        when to use it
=============  ==============================================  ==========================================
"newton"       :math:`J^\dagger\mathcal V`                      Default. Quadratic convergence near a
                                                                regular solution; MR's ``IKinBody`` /
                                                                ``IKinSpace``. Steps blow up near a
                                                                singularity, where :math:`1/\sigma_{\min}`
                                                                is large.
"dls"          :math:`(J^TJ + \lambda^2I)^{-1}J^T\mathcal V`    Targets near or beyond the workspace
                                                                boundary, starts near singularities: every
                                                                step is at most
                                                                :math:`\|\mathcal V\|/(2\lambda)`; still
                                                                converges to an exact solution, linearly.
                                                                For an unreachable target it settles at the
                                                                nearest pose in the least-squares sense.
"transpose"    :math:`\alpha J^T\mathcal V`                     No matrix to solve, never singular (it is
                                                                gradient descent on
                                                                :math:`\tfrac12\|\mathcal V\|^2` to first
                                                                order); slow, many iterations. Here
                                                                :math:`\alpha = \frac{e^TJJ^Te}{\|JJ^Te\|^2}`
                                                                (:math:`e = \mathcal V`), the step that
                                                                minimises the linearised error along
                                                                :math:`J^Te`.
=============  ==============================================  ==========================================

All three are batched: many targets, many starts, or both, solved in one call
(the arrays broadcast); each problem stops on its own.

>>> import numpy as np
>>> import jacobians as jac
>>> ur = jac.robots.ur5()
>>> T_d = ur.fk([0.5, -0.8, 1.0, 0.3, 0.7, -0.2])
>>> out = ik(ur, T_d, theta0=[0.4, -0.7, 0.9, 0.4, 0.6, -0.1])
>>> bool(out.converged), int(out.iterations) <= 6
(True, True)
>>> np.allclose(ur.fk(out.theta), T_d, atol=1e-6)
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import (
    as_float_array,
    check_finite,
    positive_float,
    positive_int,
    theta_array,
    transform_array,
)
from .chain import SerialChain, _as_chain
from .frames import Frame, check_frame
from .jacobian import _evaluate_pose
from .lie import _adjoint, _inverse_transform, _log_so3, log_se3
from .representations import RepresentationSingularityError, _Binv, _coords, _margin
from .velocity import dls_rates, pinv_rates

__all__ = ["ik", "IKResult", "pose_error", "clik", "CLIKResult", "wrap_angles"]

Method = Literal["newton", "dls", "transpose"]
_METHODS = ("newton", "dls", "transpose")


@dataclass(frozen=True)
class IKResult:
    """What :func:`ik` returns. Arrays have the batch shape ``B`` of the broadcast inputs (``()`` for one problem)."""

    #: (B..., n) the last iterate (a solution where ``converged``).
    theta: NDArray[np.float64]
    #: (B...) whether the error met both tolerances.
    converged: NDArray[np.bool_]
    #: (B...) how many steps were taken (0 if the start already met the tolerances).
    iterations: NDArray[np.int64]
    #: (B...) :math:`\|\omega\|` of the final error twist (in the solver's frame).
    error_omega: NDArray[np.float64]
    #: (B...) :math:`\|v\|` of the final error twist.
    error_v: NDArray[np.float64]
    #: (K + 1, B..., n) every iterate, row 0 the start, if asked for (a problem that stopped repeats its last value).
    history: NDArray[np.float64] | None = field(default=None, repr=False)

    def __repr__(self) -> str:
        conv = np.asarray(self.converged)
        if conv.ndim == 0:
            return (f"IKResult(converged={bool(conv)}, iterations={int(self.iterations)}, "
                    f"error_omega={float(self.error_omega):.3g}, error_v={float(self.error_v):.3g}, "
                    f"theta={np.array2string(np.asarray(self.theta), precision=4)})")
        return (f"IKResult(batch {conv.shape}: {int(conv.sum())} of {conv.size} converged, "
                f"at most {int(np.max(self.iterations))} iterations)")


def pose_error(chain: SerialChain, theta: ArrayLike, T_d: ArrayLike, frame: Frame = "body") -> NDArray[np.float64]:
    r"""The error twist that carries {b} at ``theta`` onto the pose ``T_d``, shape (..., 6).

    ``"body"``: :math:`\mathcal V_b = \log(T_{sb}^{-1}T_{sd})^\vee`, in {b}.
    ``"space"``: :math:`\mathcal V_s = [\mathrm{Ad}_{T_{sb}}]\mathcal V_b`, the same twist in {s}.
    Zero exactly when :math:`T_{sb}(\theta) = T_{sd}`.

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> pose_error(arm, [0.0, 0.0], arm.fk([0.0, 0.0])) + 0.0
    array([0., 0., 0., 0., 0., 0.])
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, ("space", "body"))
    T = chain.fk(theta)
    Td = transform_array(T_d, "T_d")
    return _error(T, Td, frame)


def _error(T: NDArray[np.float64], Td: NDArray[np.float64], frame: str) -> NDArray[np.float64]:
    Vb = log_se3(_inverse_transform(T) @ Td)
    if frame == "body":
        return Vb
    out: NDArray[np.float64] = (_adjoint(T) @ Vb[..., :, None])[..., 0]
    return out


def wrap_angles(theta: ArrayLike) -> NDArray[np.float64]:
    r"""Angles wrapped into :math:`(-\pi, \pi]`: :math:`\theta - 2\pi\lceil(\theta - \pi)/(2\pi)\rceil`.

    >>> import numpy as np
    >>> wrap_angles([np.pi, -np.pi, 3 * np.pi / 2, 7.0]).round(6)
    array([ 3.141593,  3.141593, -1.570796,  0.716815])
    """
    th = as_float_array(theta, "theta")
    check_finite(th, "theta")
    return _wrap(th)


def _wrap(th: NDArray[np.float64]) -> NDArray[np.float64]:
    out: NDArray[np.float64] = th - 2 * np.pi * np.ceil((th - np.pi) / (2 * np.pi))
    return out


def _limits(limits: ArrayLike | None, n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(lower, upper), each of shape (n,), from ``limits`` of shape (n, 2); no limits if None."""
    if limits is None:
        return np.full(n, -np.inf), np.full(n, np.inf)
    L = as_float_array(limits, "limits")
    if L.shape != (n, 2):
        raise ValueError(f"Expected limits of shape ({n}, 2), one row (lower, upper) a joint, got shape {L.shape}")
    if np.any(np.isnan(L)):
        raise ValueError("Expected limits without NaN (use -inf or inf for a joint without a limit)")
    if np.any(L[:, 0] > L[:, 1]):
        i = int(np.argmax(L[:, 0] > L[:, 1]))
        raise ValueError(f"Expected lower <= upper for every joint, got limits[{i}] = {L[i].tolist()}")
    return L[:, 0].copy(), L[:, 1].copy()


def ik(chain: SerialChain, T_d: ArrayLike, theta0: ArrayLike, frame: Frame = "body", method: Method = "newton",
       eps_omega: float = 1e-6, eps_v: float = 1e-6, max_iterations: int = 100, damping: float = 0.05,
       record_history: bool = False, limits: ArrayLike | None = None, wrap: bool = False) -> IKResult:
    r"""Solve :math:`T_{sb}(\theta) = T_{sd}` by iteration from ``theta0``.

    Each step: :math:`\mathcal V = ` the error twist in ``frame``
    (:func:`pose_error`); stop if :math:`\|\omega\|\le\varepsilon_\omega` and
    :math:`\|v\|\le\varepsilon_v`; else :math:`\theta\leftarrow\theta + \Delta\theta`
    with the step of ``method`` (module table) and the Jacobian of ``frame``.

    With ``method="newton"`` and ``max_iterations=20`` this is MR's
    ``IKinBody(Blist, M, T, thetalist0, eomg, ev)`` (``frame="body"``) or
    ``IKinSpace`` (``frame="space"``), step for step: no angle wrapping, same
    stopping test (``eps_omega`` is ``eomg``, ``eps_v`` is ``ev``).

    Parameters
    ----------
    chain : SerialChain
    T_d : array_like, shape (..., 4, 4)
        Wanted pose(s) of {b} in {s}.
    theta0 : array_like, shape (..., n)
        Start(s). The batch shapes of ``T_d`` and ``theta0`` broadcast: one
        target from many starts, many targets from one start, or pairs.
    frame : {"body", "space"}
    method : {"newton", "dls", "transpose"}
    eps_omega, eps_v : float, positive
        Tolerances on the angular (rad) and linear (length units) parts of the error twist.
    max_iterations : int, >= 0
    damping : float, >= 0
        :math:`\lambda` for ``"dls"`` (ignored otherwise).
    record_history : bool
        Keep every iterate in ``IKResult.history``.
    limits : array_like, shape (n, 2), optional
        Hard joint limits, one row ``(lower, upper)`` a joint (``-inf``/``inf`` for none). Each
        iterate, the start included, is *clamped* into them: :math:`\theta_i \leftarrow
        \min(\max(\theta_i, \text{lower}_i), \text{upper}_i)`. A clamped iteration is no longer
        Newton's method: it can converge to another solution than the free one, or stall at a limit
        with the error left (``converged`` False).
    wrap : bool
        Wrap each revolute joint into :math:`(-\pi, \pi]` after every step (before clamping), which
        changes no pose. Prismatic joints and screw joints (nonzero pitch, whose pose is not periodic)
        are never wrapped.

    Returns
    -------
    IKResult
        ``theta``, ``converged``, ``iterations``, ``error_omega``, ``error_v``
        (and ``history``).

    Notes
    -----
    Newton's method converges to *a* solution, the one whose basin holds the
    start; from a start far from every solution, or one that crosses a
    singularity, it can wander or fail (``converged`` False). Joint angles are
    not wrapped into :math:`(-\pi, \pi]` unless ``wrap`` is set.

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> T_d = arm.fk([0.3, 1.2])
    >>> starts = np.array([[0.0, 0.5], [1.0, -0.5], [3.0, 3.0]])   # three starts, one call
    >>> out = ik(arm, T_d, starts, eps_omega=1e-9, eps_v=1e-9)
    >>> out.converged, out.iterations
    (array([ True,  True,  True]), array([4, 5, 6]))
    >>> out.theta.round(6)              # the third found the same pose 2 pi further round
    array([[0.3     , 1.2     ],
           [0.3     , 1.2     ],
           [6.583185, 1.2     ]])
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, ("space", "body"))
    if method not in _METHODS:
        raise ValueError(f"Expected method 'newton', 'dls' or 'transpose', got {method!r}")
    eps_w = positive_float(eps_omega, "eps_omega")
    eps_v_ = positive_float(eps_v, "eps_v")
    k_max = positive_int(max_iterations, "max_iterations")
    if k_max < 0:
        raise ValueError(f"Expected max_iterations >= 0, got {k_max}")
    lam = positive_float(damping, "damping", allow_zero=True)
    if not isinstance(record_history, bool):
        raise TypeError(f"Expected record_history True or False, got {type(record_history).__name__}")
    if not isinstance(wrap, bool):
        raise TypeError(f"Expected wrap True or False, got {type(wrap).__name__}")
    n = chain.dof
    lower, upper = _limits(limits, n)
    # joints whose motion is 2 pi-periodic: revolute with zero pitch (a screw joint advances as it turns)
    S = chain.screw_axes
    revolute = np.array([c == "R" for c in chain.joint_types]) & (np.abs(np.sum(S[:3] * S[3:], axis=0)) < 1e-12)

    def constrain(th: NDArray[np.float64]) -> NDArray[np.float64]:
        if wrap:
            th = np.where(revolute, _wrap(th), th)
        return np.clip(th, lower, upper)

    th0 = theta_array(theta0, n, "theta0")
    Td = transform_array(T_d, "T_d")
    try:
        batch = np.broadcast_shapes(th0.shape[:-1], Td.shape[:-2])
    except ValueError:
        raise ValueError(
            f"The batch shapes of T_d {Td.shape[:-2]} and theta0 {th0.shape[:-1]} do not broadcast"
        ) from None
    theta = constrain(np.array(np.broadcast_to(th0, batch + (n,)), dtype=float))
    Td = np.broadcast_to(Td, batch + (4, 4))

    def measure(th: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        J, T = _evaluate_pose(chain, th, frame, with_pose=True)
        assert T is not None
        return _error(T, Td, frame), J, T

    V, J, _ = measure(theta)
    ew, ev = np.linalg.norm(V[..., :3], axis=-1), np.linalg.norm(V[..., 3:], axis=-1)
    active = (ew > eps_w) | (ev > eps_v_)
    iterations = np.zeros(batch, dtype=np.int64)
    history = [theta.copy()] if record_history else None
    for _ in range(k_max):
        if not np.any(active):
            break
        if method == "newton":
            step = pinv_rates(J, V, rcond=1e-15)
        elif method == "dls":
            step = dls_rates(J, V, lam)
        else:
            JJtV = (J @ (np.swapaxes(J, -1, -2) @ V[..., :, None]))[..., 0]
            num = np.sum(V * JJtV, axis=-1)
            den = np.sum(JJtV * JJtV, axis=-1)
            alpha = np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)
            step = alpha[..., None] * (np.swapaxes(J, -1, -2) @ V[..., :, None])[..., 0]
        theta = np.where(active[..., None], constrain(theta + step), theta)
        iterations += active
        V_new, J_new, _ = measure(theta)
        V = np.where(active[..., None], V_new, V)
        J = np.where(active[..., None, None], J_new, J)
        ew, ev = np.linalg.norm(V[..., :3], axis=-1), np.linalg.norm(V[..., 3:], axis=-1)
        active = (ew > eps_w) | (ev > eps_v_)
        if history is not None:
            history.append(theta.copy())
    hist = np.stack(history) if history is not None else None
    return IKResult(theta=theta, converged=np.asarray(~active), iterations=iterations,
                    error_omega=np.asarray(ew), error_v=np.asarray(ev), history=hist)


# ---------------------------------------------------------------- closed-loop IK

@dataclass(frozen=True)
class CLIKResult:
    """What :func:`clik` returns; arrays indexed by the time step k = 0..N-1."""

    #: (N, n) joint values (row 0 is ``theta0``).
    thetas: NDArray[np.float64]
    #: (N, n) joint rates applied from step k to k + 1.
    rates: NDArray[np.float64]
    #: (N,) orientation error :math:`\|e_o\|` (rad), :math:`e_o = \log(R_dR^T)^\vee`: the angle between
    #: :math:`R` and :math:`R_d`, whichever error the law fed back.
    error_orientation: NDArray[np.float64]
    #: (N,) position error :math:`\|p_d - p\|`.
    error_position: NDArray[np.float64]
    #: (N, 3) the Euler-angle error :math:`e_\phi = \phi_d - \phi` (wrapped) fed back, for an Euler
    #: ``orientation``; None for ``"axis-angle"``.
    error_angles: NDArray[np.float64] | None = None

    def __repr__(self) -> str:
        return (f"CLIKResult({self.thetas.shape[0]} steps, final errors: orientation "
                f"{self.error_orientation[-1]:.3g} rad, position {self.error_position[-1]:.3g})")


def clik(chain: SerialChain, theta0: ArrayLike, target_poses: ArrayLike, dt: float, gain: float = 10.0,
         target_velocities: ArrayLike | None = None, method: str = "pinv", damping: float = 0.05,
         orientation: str = "axis-angle") -> CLIKResult:
    r"""Follow a path of poses by closed-loop inverse kinematics with an orientation error.

    With the geometric Jacobian (rows :math:`(\omega_s, \dot p)`) and, at step k,
    the errors :math:`e_o = \log(R_dR^T)^\vee` (axis times angle, in {s}) and
    :math:`e_p = p_d - p`,

    .. math:: \dot\theta = J^{\#}\begin{bmatrix} R R_d^T\omega_d + K e_o\\ \dot p_d + K e_p\end{bmatrix},
              \qquad \theta_{k+1} = \theta_k + \dot\theta\,\Delta t .

    Why this law: if the joints deliver it exactly, the rotation error
    :math:`R_e = R_dR^T` satisfies :math:`\dot R_eR_e^T = [\omega_d] - [R_e\omega]`,
    and since :math:`R_e e_o = e_o`, :math:`R_e\omega = \omega_d + Ke_o`, so
    :math:`\dot R_eR_e^T = -K[e_o]`: the error turns about its own fixed axis
    and its angle decays as :math:`e^{-Kt}`; likewise :math:`\dot e_p = -Ke_p`.
    (The simpler feed-forward :math:`\omega_d` instead of :math:`RR_d^T\omega_d`
    is the same to first order in the error.) Discretised with Euler steps, it
    is stable for :math:`0 < K\Delta t < 2`; :math:`K\Delta t = 1` on a fixed
    target is one Newton step of the geometric error per time step.

    **Euler angles** (``orientation="zyx"`` or ``"zyz"``). With :math:`\phi` the Euler angles of
    :math:`R` (:mod:`jacobians.representations`, :math:`\omega_s = B(\phi)\dot\phi`), the analytic
    Jacobian :math:`J_A = \operatorname{diag}(B(\phi)^{-1}, I)\,J` and the error
    :math:`e_\phi = \phi_d - \phi` (each angle wrapped into :math:`(-\pi, \pi]`), the law is

    .. math:: \dot\theta = J_A^{\#}\begin{bmatrix}\dot\phi_d + Ke_\phi\\ \dot p_d + Ke_p\end{bmatrix},

    so that :math:`\dot e_\phi = -Ke_\phi` where :math:`J_A` exists; :math:`\dot\phi_d` is
    :math:`B(\phi_d)^{-1}\omega_d` from ``target_velocities``, else the forward differences of the
    (wrapped) :math:`\phi_d`. Near the representation's singularity (ZYX pitch :math:`\pm\pi/2`,
    ZYZ middle angle 0 or :math:`\pi`) :math:`B^{-1}`, :math:`\dot\phi_d` and the error's yaw and roll
    parts grow like one over the distance to it; exactly at it the law does not exist and
    :class:`~jacobians.representations.RepresentationSingularityError` is raised.

    When to use it: to follow a *path* in real time, one cheap step per
    control cycle, the error staying small; :func:`ik` is for one pose, solved
    to tolerance, from a start that may be far.

    Parameters
    ----------
    chain : SerialChain
    theta0 : array_like, shape (n,)
    target_poses : array_like, shape (N, 4, 4), N >= 2
        :math:`T_{sd}` at times 0, dt, 2 dt, ...
    dt : float, positive
    gain : float, >= 0
        K in 1/s.
    target_velocities : array_like, shape (N, 6), optional
        :math:`(\omega_d, \dot p_d)` in {s}; default from forward differences
        of the path (:math:`\log(R_{d,k+1}R_{d,k}^T)/\Delta t` and
        :math:`(p_{d,k+1} - p_{d,k})/\Delta t`), zero at the end.
    method : {"pinv", "dls"}
        :math:`J^{\#}` is the pseudo-inverse or damped least squares.
    damping : float, >= 0
    orientation : {"axis-angle", "zyx", "zyz"}
        The orientation error fed back: :math:`\log(R_dR^T)^\vee` with the geometric Jacobian, or
        an Euler-angle error with the analytic Jacobian (above).

    >>> import numpy as np
    >>> import jacobians as jac
    >>> ur = jac.robots.ur5()
    >>> t = np.linspace(0, 1, 101)
    >>> path = ur.fk(np.array([0.3, -0.9, 1.1, 0.2, 0.5, 0.1]) + np.outer(t, [0.4, 0.2, -0.3, 0.1, 0.3, 0.5]))
    >>> out = clik(ur, [0.3, -0.9, 1.1, 0.2, 0.5, 0.1], path, dt=0.01)
    >>> bool(out.error_orientation.max() < 1e-3 and out.error_position.max() < 1e-3)
    True
    """
    chain = _as_chain(chain)
    n = chain.dof
    theta = theta_array(theta0, n, "theta0")
    if theta.ndim != 1:
        raise ValueError(f"Expected theta0 with shape ({n},), got shape {theta.shape}")
    P = transform_array(target_poses, "target_poses")
    if P.ndim != 3 or P.shape[0] < 2:
        raise ValueError(f"Expected target_poses with shape (N, 4, 4), N >= 2, got shape {P.shape}")
    N = P.shape[0]
    dt = positive_float(dt, "dt")
    K = positive_float(gain, "gain", allow_zero=True)
    if method not in ("pinv", "dls"):
        raise ValueError(f"Expected method 'pinv' or 'dls', got {method!r}")
    lam = positive_float(damping, "damping", allow_zero=True)
    if orientation not in ("axis-angle", "zyx", "zyz"):
        raise ValueError(f"Expected orientation 'axis-angle', 'zyx' or 'zyz', got {orientation!r}")
    euler = orientation != "axis-angle"
    if target_velocities is None:
        Vd = np.zeros((N, 6))
        Vd[:-1, :3] = _log_so3(P[1:, :3, :3] @ np.swapaxes(P[:-1, :3, :3], -1, -2)) / dt
        Vd[:-1, 3:] = np.diff(P[:, :3, 3], axis=0) / dt
    else:
        Vd = as_float_array(target_velocities, "target_velocities")
        if Vd.shape != (N, 6):
            raise ValueError(f"Expected target_velocities with shape ({N}, 6), (omega_d, pdot_d), got {Vd.shape}")
        check_finite(Vd, "target_velocities")
    if euler:
        phi_d = _coords(P[:, :3, :3], orientation)
        if target_velocities is None:
            phid_dot = np.zeros((N, 3))
            phid_dot[:-1] = _wrap(np.diff(phi_d, axis=0)) / dt
        else:
            _no_lock(phi_d, orientation, "the target path")
            phid_dot = (_Binv(phi_d, orientation) @ Vd[:, :3, None])[..., 0]
    thetas = np.empty((N, n))
    rates = np.empty((N, n))
    e_o_norm = np.empty(N)
    e_p_norm = np.empty(N)
    e_phi = np.empty((N, 3)) if euler else None
    for k in range(N):
        J, T = _evaluate_pose(chain, theta, "geometric", with_pose=True)
        assert T is not None
        R, p = T[:3, :3], T[:3, 3]
        Rd, pd = P[k, :3, :3], P[k, :3, 3]
        e_o = _log_so3(Rd @ R.T)
        e_p = pd - p
        if e_phi is None:
            ref = np.concatenate([R @ Rd.T @ Vd[k, :3] + K * e_o, Vd[k, 3:] + K * e_p])
        else:
            phi = _coords(R, orientation)
            _no_lock(phi, orientation, f"the arm's orientation at step {k}")
            e_phi[k] = _wrap(phi_d[k] - phi)
            J = np.concatenate([_Binv(phi, orientation) @ J[:3], J[3:]])        # the analytic Jacobian
            ref = np.concatenate([phid_dot[k] + K * e_phi[k], Vd[k, 3:] + K * e_p])
        rate = pinv_rates(J, ref) if method == "pinv" else dls_rates(J, ref, lam)
        thetas[k], rates[k] = theta, rate
        e_o_norm[k], e_p_norm[k] = np.linalg.norm(e_o), np.linalg.norm(e_p)
        theta = theta + rate * dt
    return CLIKResult(thetas, rates, e_o_norm, e_p_norm, e_phi)


def _no_lock(phi: NDArray[np.float64], representation: str, what: str) -> None:
    """Raise where the Euler angles ``phi`` are at their representation's singularity (B not invertible)."""
    bad = _margin(phi, representation) < 1e-9
    if np.any(bad):
        raise RepresentationSingularityError(
            f"The {representation!r} angles of {what} are at their singularity (phi = "
            f"{np.asarray(phi).reshape(-1, 3)[int(np.argmax(bad.reshape(-1)))]}): the analytic Jacobian does not "
            "exist there; use orientation='axis-angle'")
