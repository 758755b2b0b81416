r"""Serial chains read from URDF files (the robot description format of ROS).

A URDF file describes a robot as a tree of links joined by joints. Each joint
has a parent link, a child link, an ``origin`` (the pose of the joint frame in
the parent link's frame, as ``xyz`` and fixed-axis roll–pitch–yaw ``rpy``:
:math:`R = R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})`) and an ``axis``
expressed in the joint frame. At joint value q the child link's frame is

.. math:: T_{\text{parent},\text{child}}(q) = T_{\text{origin}}\;
          \begin{cases} e^{[\hat a]q} & \text{revolute, continuous}\\
          \mathrm{Trans}(q\hat a) & \text{prismatic}\\ I & \text{fixed.}\end{cases}

Walking from the base link to the tip link and multiplying these at q = 0 gives
the home pose :math:`T_j` of each joint frame in the base frame {s}; a moving
joint's screw axis in {s} is then, with :math:`R_j, p_j` the rotation and
origin of :math:`T_j`,

.. math:: \mathcal S_j = \begin{bmatrix} R_j\hat a_j \\ -R_j\hat a_j\times p_j\end{bmatrix}
          \ \text{(revolute)},\qquad
          \mathcal S_j = \begin{bmatrix} 0 \\ R_j\hat a_j\end{bmatrix}\ \text{(prismatic)},

and the home pose M is the tip link's frame in {s}. This is the product of
exponentials because :math:`T_j e^{[\hat a]q} T_j^{-1} = e^{[\mathrm{Ad}_{T_j}(\hat a, 0)]q}`.

The file is parsed by `yourdfpy <https://pypi.org/project/yourdfpy/>`_, imported
only when a file is read (``pip install jacobians[urdf]``); the numeric core
needs numpy only. Meshes are not loaded: only the kinematics is read.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["UrdfChain", "read_chain", "MOVING_JOINTS"]

MOVING_JOINTS = ("revolute", "continuous", "prismatic")
_UNSUPPORTED = {
    "floating": "a floating joint has six degrees of freedom",
    "planar": "a planar joint has three degrees of freedom",
}


@dataclass(frozen=True)
class UrdfChain:
    """What :func:`read_chain` reads: the chain from ``base`` to ``tip`` at the home pose.

    Attributes
    ----------
    screw_axes : ndarray, shape (6, n)
        Space-frame screw axes of the moving joints, in the order base to tip.
    home : ndarray, shape (4, 4)
        The tip link's frame in the base link's frame at q = 0.
    joint_points : ndarray, shape (n, 3)
        The origin of each moving joint's frame at home (a point of its axis).
    link_homes : ndarray, shape (n, 4, 4)
        The frame of the child link of each moving joint at home.
    joint_names : tuple of str
        The URDF names of the moving joints (fixed joints are folded in).
    joint_types : str
        ``'R'`` (revolute or continuous) or ``'P'`` per moving joint.
    lower, upper : ndarray, shape (n,)
        Joint limits from the file (``-inf``/``inf`` for a continuous joint or a
        missing limit).
    robot_name : str
    """

    screw_axes: NDArray[np.float64]
    home: NDArray[np.float64]
    joint_points: NDArray[np.float64]
    link_homes: NDArray[np.float64]
    joint_names: tuple[str, ...]
    joint_types: str
    lower: NDArray[np.float64]
    upper: NDArray[np.float64]
    robot_name: str


def _load(path: object) -> object:
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"Expected the path of a URDF file (str or os.PathLike), got {type(path).__name__}")
    if not os.path.isfile(path):
        raise FileNotFoundError(f"No URDF file at {os.fspath(path)!r}")
    try:
        import yourdfpy
    except ImportError as exc:  # pragma: no cover - depends on the installation
        raise ImportError(
            "Reading URDF files needs the package yourdfpy: pip install 'jacobians[urdf]' (or pip install yourdfpy)"
        ) from exc
    try:
        return yourdfpy.URDF.load(
            os.fspath(path), build_scene_graph=False, build_collision_scene_graph=False,
            load_meshes=False, load_collision_meshes=False,
        )
    except Exception as exc:
        raise ValueError(f"Could not read {os.fspath(path)!r} as a URDF file: {exc}") from exc


def _path_of_joints(robot: object, base: str, tip: str) -> list[object]:
    """The joints from ``base`` down to ``tip``, in that order, or a ValueError that says why there is no path."""
    links = [link.name for link in robot.robot.links]  # type: ignore[attr-defined]
    for which, name in (("base", base), ("tip", tip)):
        if not isinstance(name, str):
            raise TypeError(f"Expected the {which} link's name as a str, got {type(name).__name__}")
        if name not in links:
            shown = ", ".join(repr(x) for x in links[:12]) + (", ..." if len(links) > 12 else "")
            raise ValueError(f"The URDF has no link named {name!r} (the {which}); its links are {shown}")
    parent_joint = {}
    for joint in robot.robot.joints:  # type: ignore[attr-defined]
        if joint.child in parent_joint:
            raise ValueError(f"Link {joint.child!r} is the child of two joints: the URDF is not a tree")
        parent_joint[joint.child] = joint
    path: list[object] = []
    link = tip
    seen = {tip}
    while link != base:
        joint = parent_joint.get(link)
        if joint is None:
            above = [j.parent for j in path]  # type: ignore[attr-defined]
            where = (f"the links above it are {' -> '.join(above)} (up to the root)" if above
                     else f"{tip!r} is the root of the tree")
            raise ValueError(
                f"Link {tip!r} is not below link {base!r} in the URDF tree: {where}. The base must be an "
                "ancestor of the tip (a chain cannot go up to a branch point and down another branch)."
            )
        path.append(joint)
        link = joint.parent
        if link in seen:
            raise ValueError(f"The URDF's joints form a loop through link {link!r}: it is not a tree")
        seen.add(link)
    return path[::-1]


def _origin(joint: object) -> NDArray[np.float64]:
    T = getattr(joint, "origin", None)
    if T is None:
        return np.eye(4)
    T = np.asarray(T, dtype=float)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise ValueError(f"Joint {joint.name!r} has an origin that is not a finite pose")  # type: ignore[attr-defined]
    return T


def _axis(joint: object) -> NDArray[np.float64]:
    a = getattr(joint, "axis", None)
    a = np.array([1.0, 0.0, 0.0]) if a is None else np.asarray(a, dtype=float).reshape(-1)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ValueError(f"Joint {joint.name!r} has an axis that is not three finite numbers")  # type: ignore[attr-defined]
    norm = float(np.linalg.norm(a))
    if norm < 1e-9:
        raise ValueError(f"Joint {joint.name!r} has a zero axis")  # type: ignore[attr-defined]
    return a / norm  # URDF asks for a unit axis; a scaled one is read as its direction


def read_chain(path: str | os.PathLike[str], base: str, tip: str) -> UrdfChain:
    r"""Read the serial chain from link ``base`` to link ``tip`` of a URDF file.

    Revolute, continuous and prismatic joints become joints of the chain;
    fixed joints are folded into the transforms. The base link's frame is {s}
    and the tip link's frame is {b}.

    Raises
    ------
    FileNotFoundError
        No file at ``path``.
    ValueError
        A link that the file does not have; a tip that is not below the base;
        a floating or planar joint, or a mimic joint, on the way.
    """
    robot = _load(path)
    joints = _path_of_joints(robot, base, tip)
    T = np.eye(4)
    columns: list[NDArray[np.float64]] = []
    points: list[NDArray[np.float64]] = []
    links: list[NDArray[np.float64]] = []
    names: list[str] = []
    types: list[str] = []
    lower: list[float] = []
    upper: list[float] = []
    for joint in joints:
        kind = joint.type  # type: ignore[attr-defined]
        name = joint.name  # type: ignore[attr-defined]
        if kind in _UNSUPPORTED:
            raise ValueError(
                f"Joint {name!r} is {kind}: {_UNSUPPORTED[kind]}, and a serial chain here has one-degree-of-freedom "
                "joints only (revolute, continuous, prismatic, and fixed ones folded in)"
            )
        if kind not in MOVING_JOINTS and kind != "fixed":
            raise ValueError(f"Joint {name!r} has the unknown type {kind!r}")
        if kind != "fixed" and getattr(joint, "mimic", None) is not None:
            raise ValueError(
                f"Joint {name!r} mimics joint {joint.mimic.joint!r}: its value is tied to another joint's, "  # type: ignore[attr-defined]
                "so the chain's joints would not be independent. Mimic joints are not supported."
            )
        T = T @ _origin(joint)  # the joint frame at home, in {s}
        if kind != "fixed":
            a = T[:3, :3] @ _axis(joint)
            p = T[:3, 3].copy()
            if kind == "prismatic":
                columns.append(np.concatenate([np.zeros(3), a]))
                types.append("P")
            else:
                columns.append(np.concatenate([a, -np.cross(a, p)]))
                types.append("R")
            points.append(p)
            names.append(name)
            limit = getattr(joint, "limit", None)
            lo = getattr(limit, "lower", None) if kind != "continuous" else None
            hi = getattr(limit, "upper", None) if kind != "continuous" else None
            lower.append(-np.inf if lo is None else float(lo))
            upper.append(np.inf if hi is None else float(hi))
            links.append(T.copy())  # the child link's frame is the joint frame
    if not columns:
        raise ValueError(f"There is no revolute, continuous or prismatic joint between {base!r} and {tip!r}")
    S = np.stack(columns, axis=1)
    S[np.abs(S) < 1e-15] = 0.0
    return UrdfChain(
        screw_axes=S,
        home=T,
        joint_points=np.array(points),
        link_homes=np.array(links),
        joint_names=tuple(names),
        joint_types="".join(types),
        lower=np.array(lower),
        upper=np.array(upper),
        robot_name=str(getattr(robot.robot, "name", "") or ""),  # type: ignore[attr-defined]
    )
