"""Write the kinematics-only URDF files of ``lib/jacobians/data/`` from the DH tables of ``jacobians.robots``.

    python -m tools.make_robot_urdfs          # rewrite the files
    python -m tools.make_robot_urdfs --check  # exit 1 if a file differs from what would be written

Each DH row becomes one URDF joint whose ``origin`` is the constant part of the
DH product before the joint's motion (URDF moves a joint after its origin):

- classical, revolute:  origin = P Rz(theta_i), motion Rz(q), then P = Tz(d_i) Tx(a_i) Rx(alpha_i);
- classical, prismatic: origin = P Rz(theta_i) Tz(d_i), motion Tz(q), then P = Tx(a_i) Rx(alpha_i);
- modified, revolute:   origin = P Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i), motion Rz(q), then P = Tz(d_i);
- modified, prismatic:  origin = P Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i), motion Tz(q), then P = I;

and a fixed joint carries P and the tool transform to the tip link. The tests
load every file with Pinocchio and compare it with the DH chain.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from jacobians.representations import coordinates_from_rotation
from jacobians.robots import DH_TABLES, URDF_ROBOTS

DATA = Path(__file__).resolve().parent.parent / "lib" / "jacobians" / "data"

# Joint limits (rad, or m for the prismatic joint) from the makers' data, as the Robotics Toolbox lists them.
LIMITS: dict[str, list[tuple[float, float]]] = {
    "panda": [(-2.8973, 2.8973), (-1.7628, 1.7628), (-2.8973, 2.8973), (-3.0718, -0.0698),
              (-2.8973, 2.8973), (-0.0175, 3.7525), (-2.8973, 2.8973)],
    "puma560": [(-2.7925, 2.7925), (-0.7854, 3.927), (-3.927, 0.7854), (-1.9199, 2.9671),
                (-1.7453, 1.7453), (-4.6426, 4.6426)],
    "iiwa14": [(-2.9671, 2.9671), (-2.0944, 2.0944), (-2.9671, 2.9671), (-2.0944, 2.0944),
               (-2.9671, 2.9671), (-2.0944, 2.0944), (-3.0543, 3.0543)],
    "stanford": [(-2.9671, 2.9671), (-2.9671, 2.9671), (0.3048, 1.27), (-2.9671, 2.9671),
                 (-1.5708, 1.5708), (-2.9671, 2.9671)],
}


def _T(axis: str, kind: str, x: float) -> NDArray[np.float64]:
    T = np.eye(4)
    i = "xyz".index(axis)
    if kind == "t":
        T[i, 3] = x
    else:
        c, s = np.cos(x), np.sin(x)
        j, k = (i + 1) % 3, (i + 2) % 3
        T[j, j], T[j, k], T[k, j], T[k, k] = c, -s, s, c
    return T


def _num(x: float) -> str:
    return "0" if abs(x) < 1e-15 else repr(float(x))  # the shortest text that reads back as the same float


def _origin(T: NDArray[np.float64]) -> str:
    yaw, pitch, roll = coordinates_from_rotation(T[:3, :3], "zyx")  # URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll)
    xyz = " ".join(_num(v) for v in T[:3, 3])
    rpy = " ".join(_num(v) for v in (roll, pitch, yaw))
    return f'<origin xyz="{xyz}" rpy="{rpy}"/>'


def _links_and_joints(key: str) -> tuple[list[str], list[str]]:
    t = DH_TABLES[key]
    a, alpha, d, theta = (np.asarray(t[k], dtype=float) for k in ("a", "alpha", "d", "theta"))
    types, modified = str(t["joint_types"]), t["convention"] == "modified"
    _, base, tip = URDF_ROBOTS[key]
    prefix = "panda_" if key == "panda" else ""
    link = [f"{prefix}link0" if key == "panda" else base] + [f"{prefix}link{i + 1}" for i in range(len(a))]
    links = [f'  <link name="{name}"/>' for name in link]
    joints = []
    P = np.eye(4)
    for i, kind in enumerate(types):
        if modified:
            origin = P @ _T("x", "r", alpha[i]) @ _T("x", "t", a[i]) @ _T("z", "r", theta[i])
            P = _T("z", "t", d[i])
            if kind == "P":
                origin, P = origin @ P, np.eye(4)
        else:
            origin = P @ _T("z", "r", theta[i])
            if kind == "P":
                origin = origin @ _T("z", "t", d[i])
                P = _T("x", "t", a[i]) @ _T("x", "r", alpha[i])
            else:
                P = _T("z", "t", d[i]) @ _T("x", "t", a[i]) @ _T("x", "r", alpha[i])
        lo, hi = LIMITS[key][i]
        effort = ' effort="100" velocity="1"'
        joints.append(
            f'  <joint name="{prefix}joint{i + 1}" type="{"prismatic" if kind == "P" else "revolute"}">\n'
            f'    <parent link="{link[i]}"/>\n    <child link="{link[i + 1]}"/>\n'
            f'    {_origin(origin)}\n    <axis xyz="0 0 1"/>\n'
            f'    <limit lower="{_num(lo)}" upper="{_num(hi)}"{effort}/>\n  </joint>'
        )
    tool = P @ _T("z", "t", float(t["tool_z"]))  # type: ignore[arg-type]
    if tip != link[-1]:
        links.append(f'  <link name="{tip}"/>')
        joints.append(f'  <joint name="{prefix}joint{len(a) + 1}" type="fixed">\n'
                      f'    <parent link="{link[-1]}"/>\n    <child link="{tip}"/>\n    {_origin(tool)}\n  </joint>')
    elif not np.allclose(tool, np.eye(4)):
        raise ValueError(f"{key}: the tip is the last DH frame but the table has a tool transform")
    if key == "panda":
        # Franka's hand on the flange, turned -45 deg about z, with its two fingers 0.0584 m out; the right
        # finger mimics the left one (as in Franka's own description), so the file has a branch and a mimic joint.
        links += ['  <link name="panda_hand"/>', '  <link name="panda_leftfinger"/>',
                  '  <link name="panda_rightfinger"/>']
        joints.append('  <joint name="panda_hand_joint" type="fixed">\n    <parent link="panda_link8"/>\n'
                      f'    <child link="panda_hand"/>\n    {_origin(_T("z", "r", -np.pi / 4))}\n  </joint>')
        for side, y, mimic in (("left", "1", ""), ("right", "-1", '\n    <mimic joint="panda_finger_joint1"/>')):
            n = 1 if side == "left" else 2
            joints.append(
                f'  <joint name="panda_finger_joint{n}" type="prismatic">\n    <parent link="panda_hand"/>\n'
                f'    <child link="panda_{side}finger"/>\n    <origin xyz="0 0 0.0584" rpy="0 0 0"/>\n'
                f'    <axis xyz="0 {y} 0"/>\n    <limit lower="0" upper="0.04" effort="100" velocity="0.2"/>{mimic}\n'
                "  </joint>"
            )
    return links, joints


def urdf_text(key: str) -> str:
    links, joints = _links_and_joints(key)
    robot = {"panda": "panda", "puma560": "puma560", "iiwa14": "iiwa14", "stanford": "stanford_arm"}[key]
    head = (f'<?xml version="1.0"?>\n<!-- {robot}: kinematics only (no meshes, no inertia), written by '
            "tools/make_robot_urdfs.py from the DH table in jacobians.robots.DH_TABLES. Lengths in metres. -->\n")
    return head + f'<robot name="{robot}">\n' + "\n".join(links + joints) + "\n</robot>\n"


def main(argv: list[str]) -> int:
    check = "--check" in argv
    DATA.mkdir(parents=True, exist_ok=True)
    stale = []
    for key, (fname, _, _) in URDF_ROBOTS.items():
        text, path = urdf_text(key), DATA / fname
        if check:
            if not path.exists() or path.read_text(encoding="utf-8") != text:
                stale.append(fname)
        else:
            path.write_text(text, encoding="utf-8")
    if stale:
        print("URDF files that differ from their DH tables:", ", ".join(stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
