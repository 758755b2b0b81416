r"""The four Jacobians of a serial chain and the maps between them.

=========================  ==================================  ====================================
Jacobian                   what :math:`J\dot\theta` is          relation
=========================  ==================================  ====================================
space :math:`J_s`          twist :math:`\mathcal V_s` in {s}    :math:`J_s = [\mathrm{Ad}_{T_{sb}}] J_b`
body :math:`J_b`           twist :math:`\mathcal V_b` in {b}    :math:`J_b = [\mathrm{Ad}_{T_{bs}}] J_s`
geometric :math:`J`        :math:`(\omega_s, \dot p)`           :math:`J = \mathrm{diag}(R, R)\, J_b`
analytic :math:`J_a`       :math:`(\dot\phi, \dot p)`           :math:`J_a = \mathrm{diag}(B(\phi)^{-1}, I)\, J`
=========================  ==================================  ====================================

Here :math:`T_{sb} = (R, p)` is the forward kinematics, :math:`\omega_s` the
angular velocity of {b} expressed in {s}, :math:`\dot p` the velocity of the
origin of {b} expressed in {s}. All rows are angular first.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()
>>> jac.space_jacobian(arm, [0.0, np.pi / 2]).round(12) + 0.0
array([[ 0.,  0.],
       [ 0.,  0.],
       [ 1.,  1.],
       [ 0.,  0.],
       [ 0., -1.],
       [ 0.,  0.]])
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _kernels as K
from ._validation import (
    broadcast_leading,
    jacobian_array,
    positive_float,
    theta_array,
    transform_array,
)
from .chain import SerialChain, _as_chain
from .frames import FRAMES, Frame, check_frame
from .representations import (
    RepresentationSingularityError,
    _Binv,
    _coords,
    _margin,
    check_representation,
)

__all__ = [
    "jacobian",
    "space_jacobian",
    "body_jacobian",
    "geometric_jacobian",
    "analytic_jacobian",
    "pose_coordinates",
    "space_to_body",
    "body_to_space",
    "body_to_geometric",
    "geometric_to_body",
    "space_to_geometric",
    "geometric_to_space",
    "geometric_to_analytic",
    "link_jacobians",
    "numerical_jacobian",
]


# ---------------------------------------------------------------- core evaluation

def _core_convert(frame: str, J: NDArray[np.float64], R: NDArray[np.float64],
                  p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Convert space columns J (6, n, ...) to ``frame`` with T_sb = (R, p), core axes first.

    R has shape (3, 3, ...) and p (3, ...), batch axes last; J's column axis is
    second, so p[k] (shape (...)) broadcasts against J[k] (shape (n, ...)).
    """
    if frame == "space":
        return J
    w, v = J[:3], J[3:]
    # ṗ-type linear part: v_s + ω_s × p = v_s - p × ω_s
    lin = np.empty_like(v)
    lin[0] = v[0] - (p[1] * w[2] - p[2] * w[1])
    lin[1] = v[1] - (p[2] * w[0] - p[0] * w[2])
    lin[2] = v[2] - (p[0] * w[1] - p[1] * w[0])
    if frame == "geometric":
        out = np.empty_like(J)
        out[:3] = w
        out[3:] = lin
        return out
    # body: R^T ω, R^T (v - p × ω)
    out = np.empty_like(J)
    for j in range(3):
        out[j] = R[0, j] * w[0] + R[1, j] * w[1] + R[2, j] * w[2]
        out[3 + j] = R[0, j] * lin[0] + R[1, j] * lin[1] + R[2, j] * lin[2]
    return out


def _evaluate(chain: SerialChain, theta: ArrayLike, frame: str) -> NDArray[np.float64]:
    """J in ``frame`` (space/body/geometric, already checked), shape (..., 6, n)."""
    return _evaluate_pose(chain, theta, frame, with_pose=False)[0]


def _evaluate_pose(chain: SerialChain, theta: ArrayLike, frame: str,
                   with_pose: bool = True) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """J in ``frame`` (space/body/geometric, already checked) with shape (..., 6, n), and T_sb if ``with_pose``."""
    chain = _as_chain(chain)
    C = chain._C
    n = chain.dof
    th = theta_array(theta, n)
    M = chain.home
    if th.ndim == 1:
        Rs, ps = K.prefixes_single(C, th)
        J = K.space_columns_single(C, Rs, ps)
        R = Rs[-1] @ M[:3, :3]
        p = Rs[-1] @ M[:3, 3] + ps[-1]
        if frame != "space":
            # v - p x w = v + [w] p ... written as a 3x3 product on all columns at once
            P = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
            lin = J[3:] - P @ J[:3]
            if frame == "geometric":
                J[3:] = lin
            else:
                Rt = R.T
                J[:3] = Rt @ J[:3]
                J[3:] = Rt @ lin
        if with_pose:
            T1 = np.eye(4)
            T1[:3, :3] = R
            T1[:3, 3] = p
            return J, T1
        return J, None
    batch = th.shape[:-1]
    flat = th.reshape(-1, n)
    N = flat.shape[0]
    out: NDArray[np.float64] = np.empty((N, 6, n))
    T: NDArray[np.float64] | None = None
    if with_pose:
        T = np.zeros((N, 4, 4))
        T[:, 3, 3] = 1.0
    for a in range(0, N, K.CHUNK):
        b = min(a + K.CHUNK, N)
        if frame == "body" and not with_pose:
            # reversed sweep over -B_n..-B_1: no conversion needed
            thT = np.ascontiguousarray(flat[a:b, ::-1].T)
            Jr, _, _, _ = K.sweep_batch(chain._C_rev, thT, want_columns=True, want_final=False)
            np.negative(Jr[:, ::-1].transpose(2, 0, 1), out=out[a:b])
            continue
        thT = np.ascontiguousarray(flat[a:b].T)
        need_pose = frame != "space" or with_pose
        Jc, Rc, pc, _ = K.sweep_batch(C, thT, want_columns=True, want_final=need_pose)
        if need_pose:
            assert Rc is not None and pc is not None
            Rc, pc = K.times_home(Rc, pc, M)
        out[a:b] = _core_convert(frame, Jc, Rc, pc).transpose(2, 0, 1)  # type: ignore[arg-type]
        if T is not None:
            assert Rc is not None and pc is not None
            T[a:b, :3, :3] = Rc.transpose(2, 0, 1)
            T[a:b, :3, 3] = pc.T
    out = out.reshape(batch + (6, n))
    if T is not None:
        return out, T.reshape(batch + (4, 4))
    return out, None


def jacobian(chain: SerialChain, theta: ArrayLike, frame: Frame, representation: str = "zyx",
             on_singularity: str = "raise", tol: float = 1e-9) -> NDArray[np.float64]:
    r"""The Jacobian of ``chain`` at ``theta`` in ``frame``: the one entry point for "which Jacobian".

    ``frame`` is ``"space"`` (:func:`space_jacobian`), ``"body"``
    (:func:`body_jacobian`), ``"geometric"`` (:func:`geometric_jacobian`) or
    ``"analytic"`` (:func:`analytic_jacobian`, which alone uses
    ``representation``, ``on_singularity`` and ``tol``); see
    :mod:`jacobians.frames`.

    Returns
    -------
    ndarray, shape (..., 6, n)

    >>> import numpy as np
    >>> import jacobians as jac
    >>> arm = jac.robots.planar_2r()
    >>> all(np.allclose(jac.jacobian(arm, [0.3, 0.4], f), g(arm, [0.3, 0.4]))
    ...     for f, g in [("space", jac.space_jacobian), ("body", jac.body_jacobian),
    ...                  ("geometric", jac.geometric_jacobian), ("analytic", jac.analytic_jacobian)])
    True
    >>> jac.jacobian(arm, [0.3, 0.4], "world")
    Traceback (most recent call last):
    ...
    ValueError: Expected frame 'space', 'body', 'geometric' or 'analytic', got 'world'
    """
    frame = check_frame(frame, FRAMES)
    if frame == "analytic":
        return analytic_jacobian(chain, theta, representation, on_singularity=on_singularity, tol=tol)
    return _evaluate(chain, theta, frame)


def space_jacobian(chain: SerialChain, theta: ArrayLike) -> NDArray[np.float64]:
    r"""Space Jacobian :math:`J_s(\theta)`, with :math:`\mathcal V_s = J_s(\theta)\dot\theta`.

    Column i is the screw axis of joint i carried to its current place by the
    joints before it: :math:`J_{s1} = \mathcal S_1`,
    :math:`J_{si} = [\mathrm{Ad}_{e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_{i-1}]\theta_{i-1}}}]\mathcal S_i`.
    MR: ``JacobianSpace``.

    Parameters
    ----------
    chain : SerialChain
    theta : array_like, shape (..., n)

    Returns
    -------
    J_s : ndarray, shape (..., 6, n)

    >>> import jacobians as jac
    >>> jac.space_jacobian(jac.robots.planar_3r(), [0, 0, 0])[:, 2]
    array([ 0.,  0.,  1.,  0., -2.,  0.])
    """
    return _evaluate(chain, theta, "space")


def body_jacobian(chain: SerialChain, theta: ArrayLike) -> NDArray[np.float64]:
    r"""Body Jacobian :math:`J_b(\theta)`, with :math:`\mathcal V_b = J_b(\theta)\dot\theta`.

    Column i is the screw axis of joint i seen from {b}, moved by the joints
    after it: :math:`J_{bn} = \mathcal B_n`,
    :math:`J_{bi} = [\mathrm{Ad}_{e^{-[\mathcal B_n]\theta_n}\cdots e^{-[\mathcal B_{i+1}]\theta_{i+1}}}]\mathcal B_i`.
    Computed as :math:`[\mathrm{Ad}_{T_{bs}}] J_s`. MR: ``JacobianBody``.

    Returns
    -------
    J_b : ndarray, shape (..., 6, n)

    >>> import jacobians as jac
    >>> jac.body_jacobian(jac.robots.planar_3r(), [0, 0, 0])[:, 0]
    array([0., 0., 1., 0., 3., 0.])
    """
    return _evaluate(chain, theta, "body")


def geometric_jacobian(chain: SerialChain, theta: ArrayLike) -> NDArray[np.float64]:
    r"""Geometric Jacobian :math:`J(\theta)`, with :math:`(\omega_s, \dot p) = J(\theta)\dot\theta`.

    :math:`\omega_s` is the angular velocity of {b} in {s}, :math:`\dot p` the
    velocity of the origin of {b} in {s}. Equal to
    :math:`\mathrm{diag}(R, R)\, J_b`; for a revolute joint the column is
    :math:`(z_i, z_i\times(p - p_i))`, for a prismatic one :math:`(0, z_i)`.
    It is not a twist Jacobian: its two halves are taken at different points
    ({s}'s origin is not involved; :math:`\dot p` is the velocity of {b}'s origin).

    Returns
    -------
    J : ndarray, shape (..., 6, n), rows (ω_s, ṗ)

    >>> import jacobians as jac
    >>> jac.geometric_jacobian(jac.robots.planar_2r(), [0, 0])[3:5]
    array([[0., 0.],
           [2., 1.]])
    """
    return _evaluate(chain, theta, "geometric")


def pose_coordinates(T: ArrayLike, representation: str = "zyx") -> NDArray[np.float64]:
    r"""Minimal pose coordinates :math:`x = (\phi, p)` of a transform, shape (..., 6).

    ``representation`` is ``"zyx"``, ``"zyz"`` or ``"exp"`` (see
    :mod:`jacobians.representations`).

    >>> import numpy as np
    >>> T = np.eye(4); T[:3, 3] = [1, 2, 3]
    >>> pose_coordinates(T) + 0.0
    array([0., 0., 0., 1., 2., 3.])
    """
    representation = check_representation(representation)
    T = transform_array(T, "T")
    return np.concatenate([_coords(T[..., :3, :3], representation), T[..., :3, 3]], axis=-1)


def _analytic_from_geometric(J: NDArray[np.float64], T: NDArray[np.float64], representation: str,
                             on_singularity: str, tol: float) -> NDArray[np.float64]:
    phi = _coords(T[..., :3, :3], representation)
    bad = _margin(phi, representation) < tol
    if np.any(bad):
        if on_singularity == "raise":
            where = np.argwhere(bad)
            first = tuple(where[0]) if bad.ndim else ()
            raise RepresentationSingularityError(
                f"The analytic Jacobian does not exist here: the {representation!r} coordinates "
                f"phi = {np.round(phi[first], 6)} are at a representation singularity"
                + (f" (batch index {first}, {int(bad.sum())} configuration(s) in all)" if bad.ndim else "")
                + "; the geometric Jacobian is still defined. "
                "Pass on_singularity='nan' to get NaN there instead."
            )
    Binv = _Binv(phi, representation)
    out = J.copy()
    out[..., :3, :] = Binv @ J[..., :3, :]
    if np.any(bad):
        out[bad] = np.nan
    return out


def analytic_jacobian(chain: SerialChain, theta: ArrayLike, representation: str = "zyx",
                      on_singularity: str = "raise", tol: float = 1e-9) -> NDArray[np.float64]:
    r"""Analytic Jacobian :math:`J_a(\theta) = \partial x / \partial\theta` for :math:`x = (\phi, p)`.

    :math:`J_a = \begin{bmatrix}B(\phi)^{-1} & 0\\ 0 & I\end{bmatrix} J`
    with :math:`\omega_s = B(\phi)\dot\phi` and J the geometric Jacobian.

    Parameters
    ----------
    chain : SerialChain
    theta : array_like, shape (..., n)
    representation : {"zyx", "zyz", "exp"}
    on_singularity : {"raise", "nan"}
        At a representation singularity (``zyx``: pitch ±π/2; ``zyz``: middle
        angle 0 or π; ``exp``: rotation angle π) the analytic Jacobian does not
        exist. ``"raise"`` raises :class:`RepresentationSingularityError`;
        ``"nan"`` fills those configurations with NaN.
    tol : float
        Margin (see :func:`jacobians.representations.representation_singularity_margin`)
        below which a configuration counts as singular.

    Returns
    -------
    J_a : ndarray, shape (..., 6, n), rows (φ̇, ṗ)
    """
    representation = check_representation(representation)
    if on_singularity not in ("raise", "nan"):
        raise ValueError(f"Expected on_singularity 'raise' or 'nan', got {on_singularity!r}")
    tol = positive_float(tol, "tol")
    J, T = _evaluate_pose(chain, theta, "geometric")
    assert T is not None
    return _analytic_from_geometric(J, T, representation, on_singularity, tol)


# ---------------------------------------------------------------- conversions

def _pair(J: object, T: object, names: tuple[str, str] = ("J", "T")) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    Ja = jacobian_array(J, names[0])
    Ta = transform_array(T, names[1])
    broadcast_leading(Ja, 2, Ta, 2, names)
    return Ja, Ta


def _rotate_blocks(R: NDArray[np.float64], J: NDArray[np.float64], transpose: bool = False) -> NDArray[np.float64]:
    Rm = np.swapaxes(R, -1, -2) if transpose else R
    out: NDArray[np.float64] = np.empty(np.broadcast_shapes(J.shape[:-2], R.shape[:-2]) + J.shape[-2:])
    out[..., :3, :] = Rm @ J[..., :3, :]
    out[..., 3:, :] = Rm @ J[..., 3:, :]
    return out


def _cross_cols(p: NDArray[np.float64], w: NDArray[np.float64]) -> NDArray[np.float64]:
    """p × w column-wise: p (..., 3), w (..., 3, n)."""
    q = p[..., :, None]
    out: NDArray[np.float64] = np.stack(
        [q[..., 1, :] * w[..., 2, :] - q[..., 2, :] * w[..., 1, :],
         q[..., 2, :] * w[..., 0, :] - q[..., 0, :] * w[..., 2, :],
         q[..., 0, :] * w[..., 1, :] - q[..., 1, :] * w[..., 0, :]], -2)
    return out


def space_to_body(J_s: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J_b = [\mathrm{Ad}_{T_{bs}}] J_s = [\mathrm{Ad}_{T_{sb}^{-1}}] J_s`.

    Parameters
    ----------
    J_s : array_like, shape (..., 6, n)
    T_sb : array_like, shape (..., 4, 4), the forward kinematics at the same configuration

    Returns
    -------
    J_b : ndarray, shape (..., 6, n)
    """
    Js, T = _pair(J_s, T_sb, ("J_s", "T_sb"))
    R, p = T[..., :3, :3], T[..., :3, 3]
    lin = Js[..., 3:, :] - _cross_cols(p, Js[..., :3, :])
    out = np.concatenate(np.broadcast_arrays(Js[..., :3, :], lin), axis=-2)
    return _rotate_blocks(R, out, transpose=True)


def body_to_space(J_b: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J_s = [\mathrm{Ad}_{T_{sb}}] J_b`: rows :math:`(R\omega_b,\ R v_b + p \times R\omega_b)`."""
    Jb, T = _pair(J_b, T_sb, ("J_b", "T_sb"))
    R, p = T[..., :3, :3], T[..., :3, 3]
    out = _rotate_blocks(R, Jb)
    out[..., 3:, :] += _cross_cols(p, out[..., :3, :])
    return out


def body_to_geometric(J_b: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J = \mathrm{diag}(R_{sb}, R_{sb})\, J_b`."""
    Jb, T = _pair(J_b, T_sb, ("J_b", "T_sb"))
    return _rotate_blocks(T[..., :3, :3], Jb)


def geometric_to_body(J: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J_b = \mathrm{diag}(R_{sb}^T, R_{sb}^T)\, J`."""
    Jg, T = _pair(J, T_sb, ("J", "T_sb"))
    return _rotate_blocks(T[..., :3, :3], Jg, transpose=True)


def space_to_geometric(J_s: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J = \begin{bmatrix} I & 0\\ -[p] & I\end{bmatrix} J_s`.

    Rows :math:`(\omega_s,\ v_s + \omega_s\times p)`.
    """
    Js, T = _pair(J_s, T_sb, ("J_s", "T_sb"))
    p = T[..., :3, 3]
    lin = Js[..., 3:, :] - _cross_cols(p, Js[..., :3, :])
    return np.concatenate(np.broadcast_arrays(Js[..., :3, :], lin), axis=-2)


def geometric_to_space(J: ArrayLike, T_sb: ArrayLike) -> NDArray[np.float64]:
    r""":math:`J_s = \begin{bmatrix} I & 0\\ [p] & I\end{bmatrix} J`.

    Rows :math:`(\omega_s,\ \dot p + p\times\omega_s)`.
    """
    Jg, T = _pair(J, T_sb, ("J", "T_sb"))
    p = T[..., :3, 3]
    lin = Jg[..., 3:, :] + _cross_cols(p, Jg[..., :3, :])
    return np.concatenate(np.broadcast_arrays(Jg[..., :3, :], lin), axis=-2)


def geometric_to_analytic(J: ArrayLike, T_sb: ArrayLike, representation: str = "zyx",
                          on_singularity: str = "raise", tol: float = 1e-9) -> NDArray[np.float64]:
    r""":math:`J_a = \mathrm{diag}(B(\phi)^{-1}, I)\, J` with :math:`\phi` the coordinates of :math:`R_{sb}`."""
    representation = check_representation(representation)
    if on_singularity not in ("raise", "nan"):
        raise ValueError(f"Expected on_singularity 'raise' or 'nan', got {on_singularity!r}")
    Jg, T = _pair(J, T_sb, ("J", "T_sb"))
    shape = np.broadcast_shapes(Jg.shape[:-2], T.shape[:-2])
    Jg = np.broadcast_to(Jg, shape + Jg.shape[-2:])
    T = np.broadcast_to(T, shape + (4, 4))
    return _analytic_from_geometric(Jg, T, representation, on_singularity, positive_float(tol, "tol"))


# ---------------------------------------------------------------- link Jacobians

def link_jacobians(chain: SerialChain, theta: ArrayLike, frame: Frame = "space") -> NDArray[np.float64]:
    r"""The Jacobian of every link frame, shape (..., n, 6, n).

    Entry i (0-based) is the Jacobian of the frame of link i + 1, whose pose is
    :math:`T_{s,i}(\theta) = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_i]\theta_i} M_i`
    (``chain.link_homes``). Link i moves only with joints 1..i, so its columns
    for the joints after i are zero.

    Parameters
    ----------
    frame : {"space", "body", "geometric"}
        ``"space"``: :math:`\mathcal V_{s,i} = J_{s,i}\dot\theta`; its nonzero
        columns are those of the space Jacobian, whatever frame is fixed to the link.
        ``"body"``: twist of link frame i in itself,
        :math:`J_{b,i} = [\mathrm{Ad}_{T_{s,i}^{-1}}] J_{s,i}`.
        ``"geometric"``: :math:`(\omega_s, \dot p_i)` of the link frame's origin.
    """
    chain = _as_chain(chain)
    frame = check_frame(frame, ("space", "body", "geometric"))
    n = chain.dof
    th = theta_array(theta, n)
    J_s = space_jacobian(chain, th)  # (..., 6, n)
    mask = np.tril(np.ones((n, n)))  # row i: links, column k: joints k <= i
    J_links = J_s[..., None, :, :] * mask[:, None, :]
    if frame == "space":
        return J_links
    T_links = chain.link_poses(th)  # (..., n, 4, 4)
    if frame == "body":
        return space_to_body(J_links, T_links)
    return space_to_geometric(J_links, T_links)


# ---------------------------------------------------------------- finite differences

def numerical_jacobian(f: Callable[[NDArray[np.float64]], Any], x: ArrayLike, eps: float = 1e-6) -> NDArray[np.float64]:
    """Central finite differences of ``f`` at ``x``: shape f(x).shape + x.shape[-1:].

    The oracle used by the tests and the chapters' checks. ``f`` maps an
    array of shape (n,) to an array; the result's last axis indexes the inputs.

    >>> import numpy as np
    >>> numerical_jacobian(lambda x: np.array([x[0] * x[1], np.sin(x[0])]), np.array([1.0, 2.0])).round(6)
    array([[2.      , 1.      ],
           [0.540302, 0.      ]])
    """
    x = np.asarray(x, dtype=float)
    eps = positive_float(eps, "eps")
    cols = []
    for i in range(x.shape[-1]):
        dx = np.zeros_like(x)
        dx[..., i] = eps
        cols.append((np.asarray(f(x + dx)) - np.asarray(f(x - dx))) / (2 * eps))
    return np.stack(cols, axis=-1)
