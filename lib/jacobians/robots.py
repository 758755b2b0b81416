r"""Teaching robots used throughout the course.

Every function returns a :class:`~jacobians.SerialChain`. Lengths are in the
units you pass (metres for the UR5). Planar arms move in the x–y plane of {s},
their joints turn about z, and at the home pose the links lie along the x axis.

>>> import jacobians as jac
>>> arm = jac.robots.planar_3r(l1=1.0, l2=1.0, l3=1.0)
>>> arm.screw_axes.T + 0.0
array([[ 0.,  0.,  1.,  0.,  0.,  0.],
       [ 0.,  0.,  1.,  0., -1.,  0.],
       [ 0.,  0.,  1.,  0., -2.,  0.]])
>>> jac.robots.ur5().dof
6
"""

from __future__ import annotations

from collections.abc import Collection
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import positive_float
from .chain import SerialChain

__all__ = [
    "planar",
    "planar_2r",
    "planar_3r",
    "ur5",
    "spatial_rrp",
    "scara",
    "spatial_5r",
    "zyx_wrist",
    "zyz_wrist",
    "panda",
    "puma560",
    "iiwa14",
    "stanford",
    "puma_like",
    "DH_TABLES",
    "URDF_ROBOTS",
    "urdf_path",
    "PLANAR_NAMES",
]

PLANAR_NAMES = ("planar_2r", "planar_3r")


def _revolute(axis: ArrayLike, point: ArrayLike) -> NDArray[np.float64]:
    w = np.asarray(axis, dtype=float)
    q = np.asarray(point, dtype=float)
    return np.concatenate([w, -np.cross(w, q)])


def _prismatic(direction: ArrayLike) -> NDArray[np.float64]:
    return np.concatenate([np.zeros(3), np.asarray(direction, dtype=float)])


def _translation(p: ArrayLike) -> NDArray[np.float64]:
    T = np.eye(4)
    T[:3, 3] = p
    return T


def planar(lengths: Collection[float], name: str | None = None) -> SerialChain:
    r"""A planar arm of revolute joints with the given link lengths.

    Joint i turns about z through :math:`(l_1 + \dots + l_{i-1}, 0, 0)`; the tool
    frame {b} sits at :math:`(l_1 + \dots + l_n, 0, 0)` with the orientation of {s}.
    Link frame i is at the middle of link i (the centre of mass of a uniform rod),
    oriented like {s} at home.
    """
    if not hasattr(lengths, "__len__") or isinstance(lengths, str):
        raise TypeError(f"Expected a sequence of link lengths, got {type(lengths).__name__}")
    ls = [positive_float(v, f"l{i + 1}") for i, v in enumerate(lengths)]
    if not ls:
        raise ValueError("Expected at least one link length")
    x = np.concatenate([[0.0], np.cumsum(ls)])
    S = np.stack([_revolute([0, 0, 1], [x[i], 0, 0]) for i in range(len(ls))], axis=1)
    links = np.stack([_translation([x[i] + ls[i] / 2, 0, 0]) for i in range(len(ls))])
    return SerialChain(S, _translation([x[-1], 0, 0]), link_homes=links, name=name or f"planar {len(ls)}R",
                       joint_points=[[x[i], 0, 0] for i in range(len(ls))])


def planar_2r(l1: float = 1.0, l2: float = 1.0) -> SerialChain:
    """Planar 2R arm: joints about z at (0,0,0) and (l1,0,0); tool at (l1+l2,0,0)."""
    return planar([l1, l2], name="planar 2R")


def planar_3r(l1: float = 1.0, l2: float = 1.0, l3: float = 1.0) -> SerialChain:
    """Planar 3R arm: joints about z at (0,0,0), (l1,0,0), (l1+l2,0,0); tool at (l1+l2+l3,0,0)."""
    return planar([l1, l2, l3], name="planar 3R")


def ur5() -> SerialChain:
    r"""The UR5 of Modern Robotics, Example 4.5, in metres.

    :math:`W_1 = 0.109, W_2 = 0.082, L_1 = 0.425, L_2 = 0.392, H_1 = 0.089, H_2 = 0.095`.
    """
    W1, W2, L1, L2, H1, H2 = 0.109, 0.082, 0.425, 0.392, 0.089, 0.095
    S = np.array([
        [0, 0, 1, 0, 0, 0],
        [0, 1, 0, -H1, 0, 0],
        [0, 1, 0, -H1, 0, L1],
        [0, 1, 0, -H1, 0, L1 + L2],
        [0, 0, -1, -W1, L1 + L2, 0],
        [0, 1, 0, H2 - H1, 0, L1 + L2],
    ], dtype=float).T
    M = np.array([[-1, 0, 0, L1 + L2], [0, 0, 1, W1 + W2], [0, 1, 0, H1 - H2], [0, 0, 0, 1]], dtype=float)
    points: list[list[float]] = [
        [0, 0, 0], [0, 0, H1], [L1, 0, H1], [L1 + L2, 0, H1], [L1 + L2, W1, 0], [L1 + L2, 0, H1 - H2]
    ]
    return SerialChain(S, M, name="UR5", joint_points=points)


def spatial_rrp(h: float = 1.0, reach: float = 1.0) -> SerialChain:
    r"""A spatial RRP (polar) arm.

    Joint 1 turns about z through the origin, joint 2 about y through
    :math:`(0, 0, h)`, joint 3 slides along x (the arm's direction at home).
    The tool is at :math:`(\text{reach}, 0, h)` at home.
    """
    h, reach = positive_float(h, "h"), positive_float(reach, "reach")
    S = np.stack([_revolute([0, 0, 1], [0, 0, 0]), _revolute([0, 1, 0], [0, 0, h]), _prismatic([1, 0, 0])], axis=1)
    return SerialChain(S, _translation([reach, 0, h]), name="spatial RRP",
                       joint_points=[[0.0, 0.0, 0.0], [0.0, 0.0, h], [0.0, 0.0, h]])


def scara(l1: float = 0.5, l2: float = 0.4, h: float = 0.3) -> SerialChain:
    r"""A SCARA arm (RRPR): two revolute joints about z, a vertical slide (down), a revolute wrist about z.

    Joints 1, 2, 4 turn about z through :math:`(0,0,0)`, :math:`(l_1,0,0)`,
    :math:`(l_1+l_2,0,0)`; joint 3 slides along :math:`-z`. Tool at
    :math:`(l_1+l_2, 0, h)` at home.
    """
    l1, l2, h = positive_float(l1, "l1"), positive_float(l2, "l2"), positive_float(h, "h")
    S = np.stack([
        _revolute([0, 0, 1], [0, 0, 0]),
        _revolute([0, 0, 1], [l1, 0, 0]),
        _prismatic([0, 0, -1]),
        _revolute([0, 0, 1], [l1 + l2, 0, 0]),
    ], axis=1)
    return SerialChain(S, _translation([l1 + l2, 0, h]), name="SCARA",
                       joint_points=[[0.0, 0.0, 0.0], [l1, 0, 0], [l1 + l2, 0, h], [l1 + l2, 0, 0]])


def spatial_5r(h: float = 0.5, l1: float = 1.0, l2: float = 1.0, l3: float = 0.5, l4: float = 0.3) -> SerialChain:
    r"""A spatial 5R arm for comparing space and body columns.

    Axes at home: z through the origin; y through :math:`(0,0,h)`; y through
    :math:`(l_1,0,h)`; x through :math:`(l_1+l_2,0,h)`; z through
    :math:`(l_1+l_2+l_3,0,h)`. Tool at :math:`(l_1+l_2+l_3+l_4, 0, h)`.
    """
    h, l1, l2, l3, l4 = (
        positive_float(v, k) for v, k in zip((h, l1, l2, l3, l4), ("h", "l1", "l2", "l3", "l4"), strict=True)
    )
    S = np.stack([
        _revolute([0, 0, 1], [0, 0, 0]),
        _revolute([0, 1, 0], [0, 0, h]),
        _revolute([0, 1, 0], [l1, 0, h]),
        _revolute([1, 0, 0], [l1 + l2, 0, h]),
        _revolute([0, 0, 1], [l1 + l2 + l3, 0, h]),
    ], axis=1)
    points: list[list[float]] = [[0, 0, 0], [0, 0, h], [l1, 0, h], [l1 + l2, 0, h], [l1 + l2 + l3, 0, h]]
    return SerialChain(S, _translation([l1 + l2 + l3 + l4, 0, h]), name="spatial 5R", joint_points=points)


def zyx_wrist(tool: float = 0.2) -> SerialChain:
    r"""A wrist of three intersecting revolute joints about z, y and x (through the origin).

    Its orientation is :math:`R = R_z(\theta_1)R_y(\theta_2)R_x(\theta_3)`, so its
    ZYX coordinates are the joint angles; it reaches gimbal lock at
    :math:`\theta_2 = \pm\pi/2`, where axes 1 and 3 line up. The tool point is at
    :math:`(\text{tool}, 0, 0)` at home.
    """
    tool = positive_float(tool, "tool", allow_zero=True)
    origin = [0, 0, 0]
    S = np.stack([_revolute([0, 0, 1], origin), _revolute([0, 1, 0], origin), _revolute([1, 0, 0], origin)], axis=1)
    return SerialChain(S, _translation([tool, 0, 0]), name="ZYX wrist")


def zyz_wrist(tool: float = 0.2) -> SerialChain:
    r"""A spherical wrist of three intersecting revolute joints about z, y and z.

    Its orientation is :math:`R = R_z(\theta_1)R_y(\theta_2)R_z(\theta_3)`: a
    kinematic singularity at :math:`\theta_2 = 0` (axes 1 and 3 line up), but
    full rank at :math:`\theta_2 = \pm\pi/2`, where its ZYX (roll–pitch–yaw)
    coordinates can reach gimbal lock. So with this wrist the analytic
    Jacobian in ZYX coordinates blows up while the geometric Jacobian stays
    well-conditioned: a representation singularity, not a robot singularity.
    (For :func:`zyx_wrist` the two coincide: its ZYX analytic Jacobian is the
    identity and its geometric Jacobian loses rank at gimbal lock.)
    """
    tool = positive_float(tool, "tool", allow_zero=True)
    origin = [0, 0, 0]
    S = np.stack([_revolute([0, 0, 1], origin), _revolute([0, 1, 0], origin), _revolute([0, 0, 1], origin)], axis=1)
    return SerialChain(S, _translation([0, 0, tool]), name="ZYZ wrist")


# ---------------------------------------------------------------- industrial arms
# Denavit–Hartenberg tables of arms students meet, in metres and radians, from the
# makers' published kinematics (the same numbers as the Robotics Toolbox's models):
# columns a, alpha, d, theta (theta: a revolute joint's home angle, a prismatic
# joint's constant angle), the joint types, the convention, and the pose of {b}
# in the last DH frame.
_PI = float(np.pi)
DH_TABLES: dict[str, dict[str, object]] = {
    # Franka Emika Panda, Craig's (modified) convention, from Franka's documentation;
    # {b} is the flange (panda_link8), 0.107 m along z of frame 7.
    "panda": dict(
        a=[0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088],
        alpha=[0.0, -_PI / 2, _PI / 2, _PI / 2, -_PI / 2, _PI / 2, _PI / 2],
        d=[0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0],
        theta=[0.0] * 7, joint_types="RRRRRRR", convention="modified", tool_z=0.107,
    ),
    # Unimation Puma 560, classical convention (Corke and Armstrong-Hélouvry; the
    # base height 0.67183 m is in d1); {b} is frame 6 at the wrist centre.
    "puma560": dict(
        a=[0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0],
        alpha=[_PI / 2, 0.0, -_PI / 2, _PI / 2, -_PI / 2, 0.0],
        d=[0.67183, 0.0, 0.15005, 0.4318, 0.0, 0.0],
        theta=[0.0] * 6, joint_types="RRRRRR", convention="classical", tool_z=0.0,
    ),
    # KUKA LBR iiwa 14 R820, classical convention, lengths from KUKA's data sheet
    # (0.36, 0.42, 0.40 m between the wrist-like joint groups); {b} is the flange,
    # 0.126 m past joint 7's intersection point.
    "iiwa14": dict(
        a=[0.0] * 7,
        alpha=[-_PI / 2, _PI / 2, _PI / 2, -_PI / 2, -_PI / 2, _PI / 2, 0.0],
        d=[0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126],
        theta=[0.0] * 7, joint_types="RRRRRRR", convention="classical", tool_z=0.0,
    ),
    # Stanford arm (Scheinman), classical convention; joint 3 is prismatic with the
    # constant angle -pi/2; {b} is frame 6.
    "stanford": dict(
        a=[0.0, 0.0, 0.0203, 0.0, 0.0, 0.0],
        alpha=[-_PI / 2, _PI / 2, 0.0, -_PI / 2, _PI / 2, 0.0],
        d=[0.412, 0.154, 0.0, 0.0, 0.0, 0.0],
        theta=[0.0, 0.0, -_PI / 2, 0.0, 0.0, 0.0], joint_types="RRPRRR", convention="classical", tool_z=0.0,
    ),
}

# The URDF files shipped with the library (kinematics only, no meshes): name -> (file, base link, tip link).
URDF_ROBOTS: dict[str, tuple[str, str, str]] = {
    "panda": ("panda.urdf", "panda_link0", "panda_link8"),
    "puma560": ("puma560.urdf", "base_link", "link6"),
    "iiwa14": ("iiwa14.urdf", "base_link", "tool0"),
    "stanford": ("stanford.urdf", "base_link", "link6"),
}

_NAMES = {"panda": "Franka Panda", "puma560": "Puma 560", "iiwa14": "KUKA iiwa 14", "stanford": "Stanford arm"}


def _from_table(key: str) -> SerialChain:
    t = DH_TABLES[key]
    tool = _translation([0.0, 0.0, float(t["tool_z"])])  # type: ignore[arg-type]
    return SerialChain.from_dh(
        t["a"], t["alpha"], t["d"], offset=t["theta"], joint_types=str(t["joint_types"]),  # type: ignore[arg-type]
        convention=str(t["convention"]), tool=tool, name=_NAMES[key],
    )


def panda() -> SerialChain:
    """The Franka Emika Panda (7 revolute joints) to its flange, from its modified DH table (``DH_TABLES``).

    At home (all joints zero) the arm points straight up and the flange is at
    (0.088, 0, 0.926) m facing down. The same arm as a URDF file: ``urdf_path("panda")``.
    """
    return _from_table("panda")


def puma560() -> SerialChain:
    """The Unimation Puma 560 (6 revolute joints, spherical wrist), from its classical DH table.

    {s} is on the floor under joint 1 (d1 = 0.67183 m) and {b} is frame 6,
    at the wrist centre. The same arm as a URDF file: ``urdf_path("puma560")``.
    """
    return _from_table("puma560")


def iiwa14() -> SerialChain:
    """The KUKA LBR iiwa 14 R820 (7 revolute joints) to its flange, from its classical DH table.

    Joints 2, 4, 6 are the shoulder, elbow and wrist; the flange is 1.306 m
    above the base at home. The same arm as a URDF file: ``urdf_path("iiwa14")``.
    """
    return _from_table("iiwa14")


def stanford() -> SerialChain:
    """The Stanford arm (RRPRRR: joint 3 slides), from its classical DH table; {b} is frame 6.

    The same arm as a URDF file: ``urdf_path("stanford")``.
    """
    return _from_table("stanford")


def puma_like(H: float = 0.66, L1: float = 0.43, L2: float = 0.43, d6: float = 0.06) -> SerialChain:
    r"""A Puma-like arm with no shoulder offset and a spherical wrist (6 revolute joints).

    Joint 1 turns about z through the origin; joints 2 and 3 about y through
    :math:`(0, 0, H)` and :math:`(L_1, 0, H)`; the wrist axes x, y, x meet at
    the wrist centre :math:`p_w = (L_1 + L_2, 0, H)`. The tool {b} is at
    :math:`p_w + (d_6, 0, 0)` with the orientation of {s}.
    """
    H, L1, L2, d6 = (positive_float(v, k) for v, k in zip((H, L1, L2, d6), ("H", "L1", "L2", "d6"), strict=True))
    pw = [L1 + L2, 0.0, H]
    axes: list[tuple[list[float], list[float]]] = [
        ([0, 0, 1], [0, 0, 0]), ([0, 1, 0], [0, 0, H]), ([0, 1, 0], [L1, 0, H]),
        ([1, 0, 0], pw), ([0, 1, 0], pw), ([1, 0, 0], pw),
    ]
    S = np.stack([_revolute(w, q) for w, q in axes], axis=1)
    return SerialChain(S, _translation([L1 + L2 + d6, 0.0, H]), name="Puma-like",
                       joint_points=[q for _, q in axes])


def urdf_path(name: str) -> Path:
    """The path of a URDF file shipped with the library: ``"panda"``, ``"puma560"``, ``"iiwa14"`` or ``"stanford"``.

    Load it with ``SerialChain.from_urdf(urdf_path(name), base, tip)``; the
    base and tip links of each are in ``URDF_ROBOTS``.
    """
    if not isinstance(name, str):
        raise TypeError(f"Expected a robot name as a str, got {type(name).__name__}")
    if name not in URDF_ROBOTS:
        raise ValueError(f"No shipped URDF named {name!r}: expected one of {sorted(URDF_ROBOTS)}")
    return Path(__file__).resolve().parent / "data" / URDF_ROBOTS[name][0]
