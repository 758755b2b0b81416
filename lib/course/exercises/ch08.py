"""Exercises of chapter 8: the Jacobians of every link."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

import jacobians as jac
from jacobians.grading import Exercise, Mistake, numeric_exercise
from jacobians.testing import TOL, fd_tol

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import planar_points, planar_trig
from ._kinematics import DEG, Array, adj, blockdiag, expS, fk, inv_T, planar_chain, space_jac
from ._latex import degs, vec
from ._mistakes import degrees_mistake, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import LAYOUT_TEXT, angles_deg, layout_cases, lengths, planar_example, planar_pose, worked_example


def link_space_jacobians(S: ArrayLike, theta: ArrayLike) -> Array:
    """(n, 6, n): link i's space Jacobian = J_s with the columns after i zeroed."""
    J_s = space_jac(S, theta)
    n = J_s.shape[1]
    return np.stack([J_s * (np.arange(n) <= i) for i in range(n)])


def link_poses(S: Array, link_homes: Array, theta: Array) -> Array:
    """The pose of every link's frame: (n, 4, 4)."""
    n = np.asarray(S).shape[1]
    out = []
    T = np.eye(4)
    for i in range(n):
        T = T @ expS(S[:, i], theta[i])
        out.append(T @ link_homes[i])
    return np.stack(out)


def _library_ch08_ex1(ex: Exercise) -> None:
    """Link 2's Jacobian is the library's (space frame)."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    np.testing.assert_allclose(ex.solution(), jac.link_jacobians(arm, th, frame="space")[1], atol=1e-12)


@register("ch08_ex1", library=_library_ch08_ex1)
def _ch08_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    J_s = space_jac(arm.screw_axes, th)
    ref = link_space_jacobians(arm.screw_axes, th)[1]
    Tl = link_poses(arm.screw_axes, arm.link_homes, th)[1]
    mistakes = [
        Mistake("not_zeroed", J_s, "Column 3 should be zero: joint 3 comes after link 2 and does not move it."),
        Mistake("zeroed_wrong_side", J_s * (np.arange(3) >= 1),
                "You zeroed the wrong columns: link 2 is moved by joints 1 and 2, not by the joints after it."),
        Mistake("body_link", adj(inv_T(Tl)) @ ref, "This is the body Jacobian of link 2 (expressed in the link's "
                "frame). The exercise asks for its space Jacobian."),
        degrees_mistake(link_space_jacobians(arm.screw_axes, th_deg)[1]),
        swap_mistake(ref),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give the space Jacobian "
          "$J_{s,2}$ of link 2 ($6\\times3$: the map from all three joint rates to the spatial twist of link 2).")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, the joint points q_1, q_2; columns 1, 2 are (z, −z × q_i) = (0, 0, 1, q_iy, −q_ix, 0), column 3
        zero."""
        Q = planar_points(r, ls, planar_trig(r, th))
        out = np.zeros((6, 3))
        out[2, :2] = 1.0
        out[3, :2], out[4, :2] = Q[:2, 1], -Q[:2, 0]
        return out

    return numeric_exercise("The space Jacobian of a middle link", st, {"lengths": ls, "theta_deg": th_deg}, ref,
                            mistakes, what="link Jacobian", method=method)


def centre_jacobian(ls: Array, th: Array, link: int = 1) -> Array:
    """Geometric Jacobian (omega_s, pdot of the centre of link `link`, 0-based) of a planar arm."""
    arm = planar_chain(ls)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)[link]
    c = link_poses(S, arm.link_homes, th)[link][:3, 3]
    out = np.array(Jl, dtype=float)
    out[3:] = Jl[3:] - np.cross(c, Jl[:3].T).T
    return out


def _library_ch08_ex2(ex: Exercise) -> None:
    """Link 2's Jacobian is the library's (geometric)."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    np.testing.assert_allclose(ex.solution(), jac.link_jacobians(arm, th, frame="geometric")[1], atol=1e-12)


@register("ch08_ex2", library=_library_ch08_ex2)
def _ch08_ex2(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 3)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)[1]
    ref = centre_jacobian(ls, th)
    T = fk(S, arm.home, th)
    Jtool = space_jac(S, th)
    Jtool[3:] = Jtool[3:] - np.cross(T[:3, 3], Jtool[:3].T).T
    q2 = fk(S[:, :1], np.eye(4), th[:1]) @ np.array([ls[0], 0, 0, 1.0])
    at_joint = Jl.copy()
    at_joint[3:] = Jl[3:] - np.cross(q2[:3], Jl[:3].T).T
    mistakes = [
        Mistake("tool_point", Jtool, "This is the geometric Jacobian of the tool. Link 2's centre is moved by "
                "joints 1 and 2 only, and its lever arms end at the centre."),
        Mistake("space_link", Jl, "This is the space Jacobian of link 2: its linear rows are the velocity of the "
                "point at the origin of {s}, not of the centre of link 2."),
        Mistake("at_joint_2", at_joint, "This is the velocity of the point at joint 2, not of the centre of link 2."),
        degrees_mistake(centre_jacobian(ls, th_deg)),
        swap_mistake(ref),
    ]
    st = (f"A planar 3R arm with $L = {vec(ls, 1)}$ (uniform links, centre of mass at the middle of each link) is "
          f"at $\\theta = {degs(th_deg)}$. Give the geometric Jacobian of the centre of link 2: the $6\\times3$ "
          "matrix with rows $(\\omega_2, \\dot p_{c2})$, both in {s}.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, the joint points q_1, q_2, the centre c = q_2 + (L_2/2)(cos, sin) of link 2; columns 1, 2 are
        (z, z × (c − q_i)) = (0, 0, 1, −(c − q_i)_y, (c − q_i)_x, 0), column 3 zero."""
        trig = planar_trig(r, th)
        Q = planar_points(r, ls, trig)
        c = np.asarray(r(Q[1] + ls[1] / 2 * np.array([trig[0][1], trig[1][1]])))
        d = np.asarray(r(c - Q[:2]))
        out = np.zeros((6, 3))
        out[2, :2] = 1.0
        out[3, :2], out[4, :2] = -d[:, 1], d[:, 0]
        return out

    return numeric_exercise("The geometric Jacobian of a link's centre of mass", st,
                            {"lengths": ls, "theta_deg": th_deg}, ref, mistakes, what="link Jacobian", method=method)


def mass_matrix_2r(ls: Array, ms: Array, th: Array, frame: str = "body", with_rotation: bool = True) -> Array:
    """The mass matrix of a planar 2R arm of uniform rods; the options give the two catalogued mistakes."""
    arm = planar_chain(ls)
    S = arm.screw_axes
    Jl = link_space_jacobians(S, th)
    Tl = link_poses(S, arm.link_homes, th)
    M = np.zeros((2, 2))
    for i in range(2):
        Irot = np.diag([0.0, 1.0, 1.0]) * ms[i] * ls[i] ** 2 / 12 if with_rotation else np.zeros((3, 3))
        G = blockdiag(Irot, ms[i] * np.eye(3))
        J = adj(inv_T(Tl[i])) @ Jl[i] if frame == "body" else Jl[i]
        M += J.T @ G @ J
    return M


def _library_ch08_ex3(ex: Exercise) -> None:
    """The mass matrix of two uniform rods, from finite differences of the library's link poses (the kinetic
    energy of each centre and spin), and the two closed-form entries."""
    L, m = ex.given["lengths"], ex.given["masses"]
    arm = jac.robots.planar(L)
    th = np.radians(ex.given["theta_deg"])
    M_fd = np.zeros((2, 2))
    def centre(i: int) -> Callable[[Array], Array]:
        return lambda x: arm.link_poses(x)[i][:2, 3]

    bound = 0.0
    for i in range(2):
        Jc = jac.numerical_jacobian(centre(i), th)
        Jw = np.array([[1.0, 1.0 if i == 1 else 0.0]])
        M_fd += m[i] * Jc.T @ Jc + m[i] * L[i] ** 2 / 12 * Jw.T @ Jw
        # Jc = J + E with |E_kj| <= δ = fd_tol (truncation plus rounding, from the centre's position itself), so an
        # entry of JcᵀJc (a sum over the 2 rows) is off by at most 2 (2 δ max|J| + δ²), m_i times that in M
        delta = fd_tol(centre(i), th)
        bound += m[i] * 2 * (2 * delta * (float(np.abs(Jc).max()) + delta) + delta**2)
    # the sums and the closed form add TOL of the terms' size
    assert_within(ex.solution(), M_fd, bound + TOL * size(M_fd, ex.solution()), "mass matrix")
    assert np.isclose(ex.solution()[1, 1], m[1] * L[1] ** 2 / 3)
    assert np.isclose(ex.solution()[0, 1], m[1] * L[1] ** 2 / 3 + m[1] * L[0] * L[1] / 2 * np.cos(th[1]))


@register("ch08_ex3", library=_library_ch08_ex3)
def _ch08_ex3(rng: Generator) -> Exercise:
    ls = lengths(rng, 2)
    ms = np.round(rng.uniform(1.0, 4.0, size=2), 1)
    th_deg = angles_deg(rng, 2)
    th = th_deg * DEG
    ref = mass_matrix_2r(ls, ms, th)
    mistakes = [
        Mistake("no_rotational_inertia", mass_matrix_2r(ls, ms, th, with_rotation=False),
                "You left out the rotational inertia of the links (the 3x3 block of G_i): a rod spinning about its "
                "centre has kinetic energy too."),
        Mistake("space_jacobians", mass_matrix_2r(ls, ms, th, frame="space"),
                "You used the space Jacobians of the links with inertias G_i written in the link frames: the "
                "Jacobian and G_i must be in the same frame (use the body Jacobian of each link)."),
        degrees_mistake(mass_matrix_2r(ls, ms, th_deg)),
    ]
    st = (f"A planar 2R arm has uniform thin rods: lengths $L = {vec(ls, 1)}$ m, masses $m = {vec(ms, 1)}$ kg, "
          "centre of mass at the middle, rotational inertia $m_i l_i^2/12$ about the centre (about any axis "
          f"perpendicular to the rod). At $\\theta = {degs(th_deg)}$ give the mass matrix "
          "$M(\\theta) = \\sum_i J_{b,i}^T G_i J_{b,i}$ ($2\\times2$, kg m$^2$), with $J_{b,i}$ the body "
          "Jacobian of the frame at the centre of link $i$ and $G_i$ its spatial inertia.")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos θ2 written down; then M11 = m1 L1²/3 + m2 (L1² + L2²/3 + L1 L2 cos θ2), M12 = m2 (L2²/3 +
        L1 L2 cos θ2 / 2), M22 = m2 L2²/3 (the sum of JᵀGJ over the two rods, worked out)."""
        c2 = float(r(np.cos(th[1])))
        (l1, l2), (m1, m2) = ls, ms
        m12 = m2 * (l2 ** 2 / 3 + l1 * l2 * c2 / 2)
        return np.array([[m1 * l1 ** 2 / 3 + m2 * (l1 ** 2 + l2 ** 2 / 3 + l1 * l2 * c2), m12],
                         [m12, m2 * l2 ** 2 / 3]])

    return numeric_exercise("The mass matrix from link Jacobians", st,
                            {"lengths": ls, "masses": ms, "theta_deg": th_deg}, ref, mistakes, what="mass matrix",
                            method=method)


def _links_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    ref = link_space_jacobians(S, th)
    J_s = space_jac(S, th)
    n = S.shape[1]
    mistakes = [
        Mistake("not_zeroed", np.stack([J_s] * n), "Every link gets the full J_s: the columns of the joints after "
                "link i must be zero."),
        Mistake("zeroed_wrong_side", np.stack([J_s * (np.arange(n) >= i) for i in range(n)]),
                "You zeroed the columns before link i; zero those after it."),
        Mistake("off_by_one", np.stack([J_s * (np.arange(n) < i) for i in range(n)]),
                "Off by one: link i is moved by joints 1..i, including joint i itself."),
    ]
    return (S, th), ref, mistakes


def _links_example(layout: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm of the seed (lengths, angles in tenths of a radian) and the stack of link Jacobians the
    function must return: varies the statement, so that two IDs rarely share one."""
    def build(rng: Generator) -> tuple[dict[str, Any], Any]:
        _, th, B, M = planar_example(rng)
        S = np.round(adj(M) @ B, 12)
        return {"S": S if layout == "columns" else S.T, "theta": th}, link_space_jacobians(S, th)
    return worked_example("my_link_jacobians(S, theta)", build)


def _library_ch08_ex4(ex: Exercise) -> None:
    """On every test case, link i's space Jacobian is the library's space Jacobian of the chain cut after joint i
    (link i's pose is e^[S1]θ1···e^[Si]θi times a constant), padded with zero columns for the joints after it,
    instead of J_s with columns zeroed. The same products of exponentials: within TOL of |J|."""
    for (axes, th), out in reference_runs(ex):
        S = np.asarray(axes, dtype=float).T if ex.given["layout"] == "rows" else np.asarray(axes, dtype=float)
        n = S.shape[1]
        expected = np.zeros((n, 6, n))
        for i in range(n):
            expected[i, :, :i + 1] = jac.space_jacobian(jac.SerialChain(S[:, :i + 1], np.eye(4)), th[:i + 1])
        assert_close(out, expected, "stack of link Jacobians", scale=size(expected))


register_code("ch08_ex4", "Code: the Jacobians of every link", [
    CodeVariant(f"Write `my_link_jacobians(S, theta)`: `S` is {LAYOUT_TEXT[layout]}, `theta` a length-$n$ array; "
                "return an array of shape $(n, 6, n)$ whose entry `[i]` is the space Jacobian of link $i+1$ "
                "(0-based `i`). You may call `jacobians.space_jacobian` with `jacobians.SerialChain(S, np.eye(4))` "
                "(which wants the axes as columns), but not `link_jacobians`. Set `answer = my_link_jacobians`.",
                link_space_jacobians if layout == "columns"
                else (lambda S, th: link_space_jacobians(np.asarray(S).T, th)),
                case, "my_link_jacobians", "stack of link Jacobians", {"layout": layout},
                example=_links_example(layout))
    for layout, case in layout_cases(_links_case).items()], library=_library_ch08_ex4)
