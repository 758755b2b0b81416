r"""Minimal coordinates of orientation and the matrices that relate their rates to ω.

Three representations :math:`\phi` of a rotation :math:`R`:

``"zyx"``
    Z–Y–X Euler angles, in the order **(yaw, pitch, roll)**:
    :math:`R = R_z(\phi_1) R_y(\phi_2) R_x(\phi_3)` with :math:`\phi_1` the yaw
    (about z), :math:`\phi_2` the pitch (about y), :math:`\phi_3` the roll
    (about x); :math:`\phi_1, \phi_3 \in (-\pi, \pi]`, :math:`\phi_2 \in [-\pi/2, \pi/2]`.
    Singular (gimbal lock) where :math:`\cos\phi_2 = 0`. The same rotation
    as roll–pitch–yaw angles about fixed axes, but the vector is listed the
    other way round from URDF's ``rpy`` and the Robotics Toolbox's
    ``tr2rpy(R, order="zyx")`` / ``rpy2r(..., order="zyx")``, which give and take
    **(roll, pitch, yaw)**: reverse it (``phi[::-1]``), or use
    :func:`roll_pitch_yaw` and :func:`rotation_from_roll_pitch_yaw`, which
    take and give that order.
``"zyz"``
    Euler angles: :math:`R = R_z(\phi_1) R_y(\phi_2) R_z(\phi_3)`,
    :math:`\phi_2 \in [0, \pi]`. Singular where :math:`\sin\phi_2 = 0`.
``"exp"``
    exponential coordinates :math:`\phi = \hat\omega\theta`, :math:`\theta \in [0, \pi]`.
    The map from :math:`\dot\phi` to ω is invertible for
    :math:`\theta < 2\pi`, but the coordinates themselves jump at
    :math:`\theta = \pi` (:math:`\hat\omega\pi` and :math:`-\hat\omega\pi` are the
    same rotation), so the derivative does not exist there.

For each, :math:`\omega_s = B(\phi)\,\dot\phi` where :math:`\omega_s` is the
angular velocity expressed in the fixed frame {s}.

>>> import numpy as np
>>> phi = np.array([0.3, -0.2, 0.1])
>>> R = rotation_from_coordinates(phi, "zyx")
>>> np.allclose(coordinates_from_rotation(R, "zyx"), phi)
True
>>> bool(np.isclose(np.linalg.det(rate_to_angular_velocity(phi, "zyx")), -np.cos(-0.2)))
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import real_array, rotation_array
from .lie import _exp_so3, _log_so3, left_jacobian_so3, left_jacobian_so3_inverse

__all__ = [
    "REPRESENTATIONS",
    "rotation_from_coordinates",
    "coordinates_from_rotation",
    "rate_to_angular_velocity",
    "angular_velocity_to_rate",
    "representation_singularity_margin",
    "RepresentationSingularityError",
    "roll_pitch_yaw",
    "rotation_from_roll_pitch_yaw",
]

REPRESENTATIONS = ("zyx", "zyz", "exp")


class RepresentationSingularityError(ValueError):
    """Raised where a minimal orientation representation is singular (gimbal lock)."""


def check_representation(representation: object) -> str:
    if not isinstance(representation, str):
        raise TypeError(
            f"Expected representation as a str, one of {REPRESENTATIONS}, got {type(representation).__name__}"
        )
    if representation not in REPRESENTATIONS:
        raise ValueError(f"Unknown representation {representation!r}: expected one of {REPRESENTATIONS}")
    return representation


def _rz(a: NDArray[np.float64]) -> NDArray[np.float64]:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def _ry(a: NDArray[np.float64]) -> NDArray[np.float64]:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def _rx(a: NDArray[np.float64]) -> NDArray[np.float64]:
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def rotation_from_coordinates(phi: ArrayLike, representation: str = "zyx") -> NDArray[np.float64]:
    r"""The rotation matrix (..., 3, 3) described by ``phi`` (..., 3).

    For ``"zyx"``, ``phi`` is (yaw, pitch, roll): :math:`R = R_z(\phi_1)R_y(\phi_2)R_x(\phi_3)`
    (reversed from URDF's ``rpy``; see :func:`rotation_from_roll_pitch_yaw`).
    """
    representation = check_representation(representation)
    phi = real_array(phi, "phi", (3,))
    if representation == "exp":
        return _exp_so3(phi)
    a, b, c = phi[..., 0], phi[..., 1], phi[..., 2]
    if representation == "zyx":
        return _rz(a) @ _ry(b) @ _rx(c)
    return _rz(a) @ _ry(b) @ _rz(c)


def _coords(R: NDArray[np.float64], representation: str) -> NDArray[np.float64]:
    if representation == "exp":
        return _log_so3(R)
    if representation == "zyx":
        pitch = np.arctan2(-R[..., 2, 0], np.hypot(R[..., 0, 0], R[..., 1, 0]))
        lock = np.hypot(R[..., 0, 0], R[..., 1, 0]) < 1e-12
        yaw = np.where(lock, np.arctan2(-R[..., 0, 1], R[..., 1, 1]), np.arctan2(R[..., 1, 0], R[..., 0, 0]))
        roll = np.where(lock, 0.0, np.arctan2(R[..., 2, 1], R[..., 2, 2]))
        return np.stack([yaw, pitch, roll], -1)
    # zyz
    sb = np.hypot(R[..., 2, 0], R[..., 2, 1])
    b = np.arctan2(sb, R[..., 2, 2])
    lock = sb < 1e-12
    a = np.where(lock, np.arctan2(R[..., 1, 0], R[..., 0, 0]), np.arctan2(R[..., 1, 2], R[..., 0, 2]))
    c = np.where(lock, 0.0, np.arctan2(R[..., 2, 1], -R[..., 2, 0]))
    # At b = pi: R = Rz(a) Ry(pi) Rz(c) = Rz(a - c) Ry(pi); with c = 0, a from R[1,0], R[0,0] sign-flipped
    a = np.where(lock & (R[..., 2, 2] < 0), np.arctan2(-R[..., 1, 0], -R[..., 0, 0]), a)
    return np.stack([a, b, c], -1)


def coordinates_from_rotation(R: ArrayLike, representation: str = "zyx") -> NDArray[np.float64]:
    r"""Coordinates ``phi`` (..., 3) of the rotation ``R`` (..., 3, 3), within the principal ranges.

    For ``"zyx"`` they come in the order (yaw, pitch, roll), with
    :math:`R = R_z(\phi_1)R_y(\phi_2)R_x(\phi_3)`: the reverse of the Robotics
    Toolbox's ``tr2rpy(R, order="zyx")`` and of URDF's ``rpy`` (see :func:`roll_pitch_yaw`).

    At a representation singularity one of the infinitely many solutions is
    returned (the last angle set to zero).
    """
    representation = check_representation(representation)
    return _coords(rotation_array(R, "R"), representation)


def roll_pitch_yaw(R: ArrayLike) -> NDArray[np.float64]:
    r"""Angles (roll, pitch, yaw), shape (..., 3), of ``R`` = :math:`R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})`.

    The order of URDF's ``rpy`` attribute and of the Robotics Toolbox's
    ``tr2rpy(R, order="zyx")``: the ``"zyx"`` coordinates reversed.

    >>> R = rotation_from_coordinates([0.3, -0.2, 0.1], "zyx")  # yaw 0.3, pitch -0.2, roll 0.1
    >>> roll_pitch_yaw(R).round(12) + 0.0
    array([ 0.1, -0.2,  0.3])
    """
    return _coords(rotation_array(R, "R"), "zyx")[..., ::-1].copy()


def rotation_from_roll_pitch_yaw(rpy: ArrayLike) -> NDArray[np.float64]:
    r"""The rotation :math:`R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})`, shape (..., 3, 3), of ``rpy``.

    ``rpy`` = (roll, pitch, yaw), shape (..., 3).

    What a URDF ``origin`` with ``rpy="roll pitch yaw"`` means, and the
    Robotics Toolbox's ``rpy2r(roll, pitch, yaw, order="zyx")``.
    """
    rpy = real_array(rpy, "rpy", (3,))
    return _rz(rpy[..., 2]) @ _ry(rpy[..., 1]) @ _rx(rpy[..., 0])


def _B(phi: NDArray[np.float64], representation: str) -> NDArray[np.float64]:
    if representation == "exp":
        return left_jacobian_so3(phi)
    a, b = phi[..., 0], phi[..., 1]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    z, o = np.zeros_like(a), np.ones_like(a)
    if representation == "zyx":
        rows = [[z, -sa, ca * cb], [z, ca, sa * cb], [o, z, -sb]]
    else:
        rows = [[z, -sa, ca * sb], [z, ca, sa * sb], [o, z, cb]]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def rate_to_angular_velocity(phi: ArrayLike, representation: str = "zyx") -> NDArray[np.float64]:
    r"""The matrix :math:`B(\phi)` with :math:`\omega_s = B(\phi)\dot\phi`, shape (..., 3, 3).

    ZYX: columns :math:`\hat z`, :math:`R_z(\phi_1)\hat y`, :math:`R_z(\phi_1)R_y(\phi_2)\hat x`;
    :math:`\det B = -\cos\phi_2`. ZYZ: :math:`\det B = -\sin\phi_2`.
    Exponential coordinates: the left Jacobian of SO(3).
    """
    representation = check_representation(representation)
    return _B(real_array(phi, "phi", (3,)), representation)


def representation_singularity_margin(phi: ArrayLike, representation: str = "zyx") -> NDArray[np.float64]:
    r"""How far ``phi`` is from the singularity of its representation (0 at the singularity).

    ``zyx``: :math:`|\cos\phi_2|`; ``zyz``: :math:`|\sin\phi_2|`; ``exp``:
    :math:`\pi - \|\phi\|` (where the coordinates jump).
    """
    representation = check_representation(representation)
    phi = real_array(phi, "phi", (3,))
    return _margin(phi, representation)


def _margin(phi: NDArray[np.float64], representation: str) -> NDArray[np.float64]:
    if representation == "zyx":
        return np.abs(np.cos(phi[..., 1]))
    if representation == "zyz":
        return np.abs(np.sin(phi[..., 1]))
    angle: NDArray[np.float64] = np.linalg.norm(phi, axis=-1)
    return np.pi - angle


def _Binv(phi: NDArray[np.float64], representation: str) -> NDArray[np.float64]:
    if representation == "exp":
        return left_jacobian_so3_inverse(phi)
    a, b = phi[..., 0], phi[..., 1]
    ca, sa, cb, sb = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
    z = np.zeros_like(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        if representation == "zyx":
            # inverse of [[0,-sa,ca cb],[0,ca,sa cb],[1,0,-sb]]
            rows = [[ca * sb / cb, sa * sb / cb, np.ones_like(a)], [-sa, ca, z], [ca / cb, sa / cb, z]]
        else:
            # inverse of [[0,-sa,ca sb],[0,ca,sa sb],[1,0,cb]]
            rows = [[-ca * cb / sb, -sa * cb / sb, np.ones_like(a)], [-sa, ca, z], [ca / sb, sa / sb, z]]
    return np.stack([np.stack(r, -1) for r in rows], -2)


def angular_velocity_to_rate(phi: ArrayLike, representation: str = "zyx", tol: float = 1e-9) -> NDArray[np.float64]:
    r""":math:`B(\phi)^{-1}`, the map from :math:`\omega_s` to :math:`\dot\phi` (the notes' :math:`E(x)` block).

    Raises :class:`RepresentationSingularityError` where the representation is
    singular (margin below ``tol``), instead of returning huge or infinite numbers.
    """
    representation = check_representation(representation)
    phi = real_array(phi, "phi", (3,))
    bad = _margin(phi, representation) < tol
    if np.any(bad):
        raise RepresentationSingularityError(
            f"The {representation!r} representation is singular at phi = {phi[bad].reshape(-1, 3)[0]}: "
            "the angle rates are not determined by the angular velocity there (gimbal lock)"
        )
    return _Binv(phi, representation)
