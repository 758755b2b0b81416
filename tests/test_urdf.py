"""SerialChain.from_urdf against Pinocchio reading the same file, and its errors.

Pinocchio's conventions: a spatial velocity is (v, omega), linear part first;
``getFrameJacobian(..., LOCAL)`` is the body Jacobian of the frame (in its own
axes), ``WORLD`` the Jacobian of the twist at the world origin in world axes,
i.e. the space Jacobian. A continuous joint has two configuration numbers
(cos q, sin q) and one velocity.

Tolerances: a chain of at most 8 joints with offsets below 1.5 m and
translations |q| <= 1 m; every entry of T and J is a sum of products of
rotation entries (<= 1) and lengths (<= 20 m in all), formed by at most 2 * 12
matrix products, so the two libraries' rounding differs by well under
100 * 12 * 20 * eps ~ 5e-12. We compare to 1e-10.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

import jacobians as jac
from jacobians import robots
from jacobians.representations import roll_pitch_yaw, rotation_from_roll_pitch_yaw
from jacobians.urdf import read_chain

pin = pytest.importorskip("pinocchio")
pytest.importorskip("yourdfpy")

TOL = 1e-10


def _pose(rng):
    return rng.uniform(-1.5, 1.5, 3), rng.uniform(-np.pi, np.pi, 3)


def _fmt(v):
    return " ".join(repr(float(x)) for x in v)


def random_urdf(rng, n_joints):
    """A random tree: a main branch base -> ... -> tip of random joints (revolute, continuous, prismatic,
    fixed), random origins and (not unit) axes, and a side branch off the middle."""
    links = ["base"] + [f"l{i}" for i in range(1, n_joints + 1)]
    kinds = rng.choice(["revolute", "continuous", "prismatic", "fixed"], n_joints, p=[0.35, 0.2, 0.25, 0.2])
    joints = []
    for i, kind in enumerate(kinds):
        xyz, rpy = _pose(rng)
        axis = rng.normal(size=3) * rng.uniform(0.5, 2)  # URDF asks for unit axes; a scaled one means its direction
        limit = '<limit lower="-3" upper="3" effort="1" velocity="1"/>' if kind in ("revolute", "prismatic") else ""
        joints.append(f'<joint name="j{i + 1}" type="{kind}"><parent link="{links[i]}"/><child link="{links[i + 1]}"/>'
                      f'<origin xyz="{_fmt(xyz)}" rpy="{_fmt(rpy)}"/><axis xyz="{_fmt(axis)}"/>{limit}</joint>')
    mid = links[n_joints // 2]
    xyz, rpy = _pose(rng)
    joints.append(f'<joint name="side" type="revolute"><parent link="{mid}"/><child link="side_link"/>'
                  f'<origin xyz="{_fmt(xyz)}" rpy="{_fmt(rpy)}"/><axis xyz="0 1 0"/>'
                  '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    body = "".join(f'<link name="{name}"/>' for name in links + ["side_link"])
    return f'<?xml version="1.0"?><robot name="random">{body}{"".join(joints)}</robot>', kinds


def _pin_q(model, names, theta, rng):
    """Pinocchio's configuration vector: the chain's joints at theta, every other joint at random."""
    q = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    for name, value in zip(names, theta, strict=True):
        j = model.joints[model.getJointId(name)]
        if j.nq == 2:  # continuous: (cos, sin)
            q[j.idx_q:j.idx_q + 2] = np.cos(value), np.sin(value)
        else:
            q[j.idx_q] = value
    return q


def _pin_kinematics(model, names, base, tip, q):
    """T_base,tip and the space and body Jacobians of the chain, in MR's (omega, v) order, from Pinocchio."""
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    fb, ft = model.getFrameId(base), model.getFrameId(tip)
    T_wb, T_wt = data.oMf[fb].homogeneous, data.oMf[ft].homogeneous
    T = np.linalg.inv(T_wb) @ T_wt
    cols = [model.joints[model.getJointId(name)].idx_v for name in names]
    J_world = pin.getFrameJacobian(model, data, ft, pin.ReferenceFrame.WORLD)[:, cols]
    J_local = pin.getFrameJacobian(model, data, ft, pin.ReferenceFrame.LOCAL)[:, cols]
    Jb = np.vstack([J_local[3:], J_local[:3]])
    Js_world = np.vstack([J_world[3:], J_world[:3]])
    Js = jac.adjoint(np.linalg.inv(T_wb)) @ Js_world  # the space frame is the base link's, not Pinocchio's world
    return T, Js, Jb


def _compare(path, base, tip, rng, n_configs):
    chain = jac.SerialChain.from_urdf(path, base, tip)
    data = read_chain(path, base, tip)
    model = pin.buildModelFromUrdf(str(path))
    worst = 0.0
    scale = np.where(np.array(list(chain.joint_types)) == "R", np.pi, 1.0)
    for _ in range(n_configs):
        theta = rng.uniform(-1, 1, chain.dof) * scale
        T, Js, Jb = _pin_kinematics(model, data.joint_names, base, tip, _pin_q(model, data.joint_names, theta, rng))
        d = max(np.abs(chain.fk(theta) - T).max(), np.abs(jac.space_jacobian(chain, theta) - Js).max(),
                np.abs(jac.body_jacobian(chain, theta) - Jb).max())
        assert d < TOL, (path, theta, d)
        worst = max(worst, d)
    return chain, worst


def test_random_trees_agree_with_pinocchio(tmp_path):
    rng = np.random.default_rng(20)
    worst, count = 0.0, 0
    for k in range(25):
        n = int(rng.integers(2, 9))
        text, kinds = random_urdf(rng, n)
        if all(kind == "fixed" for kind in kinds):
            continue
        path = tmp_path / f"r{k}.urdf"
        path.write_text(text)
        chain, w = _compare(path, "base", f"l{n}", rng, 8)
        assert chain.joint_types == "".join("P" if kind == "prismatic" else "R" for kind in kinds if kind != "fixed")
        worst, count = max(worst, w), count + 8
        # a base that is not the root: the chain from l1 is the tail of the tree, seen from l1's frame
        if any(kind != "fixed" for kind in kinds[1:]):
            _, w = _compare(path, "l1", f"l{n}", rng, 4)
            worst = max(worst, w)
    assert count >= 150 and worst < TOL


@pytest.mark.parametrize("name", sorted(robots.URDF_ROBOTS))
def test_shipped_urdfs_agree_with_pinocchio_and_with_the_dh_robots(name):
    _, base, tip = robots.URDF_ROBOTS[name]
    rng = np.random.default_rng(5)
    chain, worst = _compare(robots.urdf_path(name), base, tip, rng, 100)
    dh = getattr(robots, name)()
    assert chain.joint_types == dh.joint_types
    for theta in rng.uniform(-np.pi, np.pi, (50, dh.dof)):
        assert np.allclose(chain.fk(theta), dh.fk(theta), atol=TOL)
        assert np.allclose(jac.space_jacobian(chain, theta), jac.space_jacobian(dh, theta), atol=TOL)


def test_urdf_files_are_what_the_dh_tables_write():
    from tools.make_robot_urdfs import DATA, urdf_text

    for name, (fname, _, _) in robots.URDF_ROBOTS.items():
        assert (DATA / fname).read_text(encoding="utf-8") == urdf_text(name), "run python -m tools.make_robot_urdfs"


def test_the_urdf_conventions_of_the_writer():
    """URDF's rpy is (roll, pitch, yaw) with R = Rz(yaw) Ry(pitch) Rx(roll): the writer's round trip."""
    rng = np.random.default_rng(3)
    for rpy in rng.uniform(-3, 3, (20, 3)) * [1, 0.5, 1]:
        R = rotation_from_roll_pitch_yaw(rpy)
        assert np.allclose(rotation_from_roll_pitch_yaw(roll_pitch_yaw(R)), R, atol=1e-12)


def test_read_chain_names_limits_and_panda_hand():
    data = read_chain(robots.urdf_path("panda"), "panda_link0", "panda_link8")
    assert data.joint_names == tuple(f"panda_joint{i}" for i in range(1, 8))
    assert np.isclose(data.lower[3], -3.0718) and np.isclose(data.upper[5], 3.7525)
    # to a finger: 7 revolute joints and the finger's slide along y of the hand (turned -45 deg about z)
    finger = jac.SerialChain.from_urdf(robots.urdf_path("panda"), "panda_link0", "panda_leftfinger")
    assert finger.joint_types == "RRRRRRRP"
    hand = robots.panda().fk(np.zeros(7))[:3, :3] @ jac.lie.rotation_about("z", -np.pi / 4)
    assert np.allclose(finger.screw_axes[3:, 7], hand[:, 1], atol=1e-12)
    assert "panda" in repr(finger)


def _write(tmp_path, body, name="t.urdf"):
    path = tmp_path / name
    path.write_text(f'<?xml version="1.0"?><robot name="t">{body}</robot>')
    return path


LINKS = '<link name="a"/><link name="b"/><link name="c"/>'


def _joint(name, kind, parent, child, extra=""):
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>{extra}</joint>')


def test_errors(tmp_path):
    good = _write(tmp_path, LINKS + _joint("j1", "revolute", "a", "b") + _joint("j2", "revolute", "a", "c"))
    with pytest.raises(ValueError, match="no link named 'hand' \\(the tip\\); its links are 'a', 'b', 'c'"):
        jac.SerialChain.from_urdf(good, "a", "hand")
    with pytest.raises(ValueError, match="no link named 'x' \\(the base\\)"):
        jac.SerialChain.from_urdf(good, "x", "b")
    with pytest.raises(ValueError, match="'c' is not below link 'b' in the URDF tree: the links above it are a \\(up to the root\\)"):  # b and c are on two branches
        jac.SerialChain.from_urdf(good, "b", "c")
    with pytest.raises(ValueError, match="'a' is not below link 'b' in the URDF tree: 'a' is the root"):  # upside down
        jac.SerialChain.from_urdf(good, "b", "a")
    with pytest.raises(ValueError, match="no revolute, continuous or prismatic joint"):
        jac.SerialChain.from_urdf(good, "a", "a")
    for kind, what in (("floating", "six degrees"), ("planar", "three degrees")):
        bad = _write(tmp_path, LINKS + _joint("j1", kind, "a", "b") + _joint("j2", "revolute", "b", "c"), f"{kind}.urdf")
        with pytest.raises(ValueError, match=f"Joint 'j1' is {kind}: .*{what}"):
            jac.SerialChain.from_urdf(bad, "a", "c")
        assert jac.SerialChain.from_urdf(bad, "b", "c").dof == 1  # the part past it is still a chain
    mimic = _write(tmp_path, LINKS + _joint("j1", "revolute", "a", "b")
                   + _joint("j2", "revolute", "b", "c", '<mimic joint="j1" multiplier="2"/>'), "mimic.urdf")
    with pytest.raises(ValueError, match="Joint 'j2' mimics joint 'j1'.*not supported"):
        jac.SerialChain.from_urdf(mimic, "a", "c")
    with pytest.raises(ValueError, match="mimics"):
        jac.SerialChain.from_urdf(robots.urdf_path("panda"), "panda_link0", "panda_rightfinger")
    zero = _write(tmp_path, LINKS + _joint("j1", "revolute", "a", "b").replace('xyz="0 0 1"', 'xyz="0 0 0"'), "z.urdf")
    with pytest.raises(ValueError, match="zero axis"):
        jac.SerialChain.from_urdf(zero, "a", "b")
    with pytest.raises(FileNotFoundError, match="No URDF file"):
        jac.SerialChain.from_urdf(tmp_path / "missing.urdf", "a", "b")
    with pytest.raises(TypeError, match="path of a URDF file"):
        jac.SerialChain.from_urdf(3, "a", "b")
    with pytest.raises(TypeError, match="base link's name"):
        jac.SerialChain.from_urdf(good, 1, "b")
    junk = tmp_path / "junk.urdf"
    junk.write_text("this is not xml")
    with pytest.raises(ValueError, match="Could not read"):
        jac.SerialChain.from_urdf(junk, "a", "b")


def test_default_axis_and_continuous_joint(tmp_path):
    """No <axis> means (1, 0, 0); a continuous joint is revolute with no limits."""
    body = ('<link name="a"/><link name="b"/><joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
            '<origin xyz="0 2 0" rpy="0 0 0"/></joint>')
    path = _write(tmp_path, body)
    chain = jac.SerialChain.from_urdf(path, "a", "b")
    # axis x through (0, 2, 0): S = (x, -x cross (0, 2, 0)) = (1, 0, 0, 0, 0, -2)
    assert np.allclose(chain.screw_axes[:, 0], [1, 0, 0, 0, 0, -2])
    data = read_chain(path, "a", "b")
    assert data.lower[0] == -np.inf and data.upper[0] == np.inf


def test_numeric_core_does_not_import_the_parser():
    """Importing jacobians (and jacobians.urdf) loads numpy, not yourdfpy: the parser is loaded when a file is read."""
    import subprocess
    import sys

    code = ("import sys, jacobians, jacobians.urdf, jacobians.robots\n"
            "print(any(m.split('.')[0] in ('yourdfpy', 'trimesh', 'lxml') for m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parent.parent, env={**os.environ})
    assert out.stdout.strip() == "False", out.stderr
