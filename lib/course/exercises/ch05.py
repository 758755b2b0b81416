"""Exercises of chapter 5: the geometric Jacobian."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

import jacobians as jac
from jacobians import lie
from jacobians.grading import Exercise, Mistake, numeric_exercise
from jacobians.testing import fd_tol

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import planar_jv, rotate_halves
from ._kinematics import DEG, Array, adj, blockdiag, body_jac, fk, inv_T, nearest_pose, space_jac
from ._latex import bmatrix, degs, vec
from ._mistakes import degrees_mistake, sign_mistakes, swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import LAYOUT_TEXT, layout_cases, planar_example, planar_pose, spatial_5r_pose, worked_example


def _geo_catalogue(ref: Array, J_b: Array, R: Array, J_s: Array | None = None) -> list[Mistake]:
    ms = [
        Mistake("R_missing", J_b, "This is the body Jacobian J_b: its rows are expressed in the tool frame. The "
                "geometric Jacobian expresses both ω and ṗ in {s}: rotate each half by R_sb."),
        Mistake("only_angular_rotated", blockdiag(R, np.eye(3)) @ J_b,
                "Only the angular half is rotated into {s}; the linear half needs R_sb too."),
        Mistake("only_linear_rotated", blockdiag(np.eye(3), R) @ J_b,
                "Only the linear half is rotated into {s}; the angular half needs R_sb too."),
        Mistake("R_transposed", blockdiag(R.T, R.T) @ J_b,
                "You rotated with R_sbᵀ: to express a vector given in {b} in {s}, multiply by R_sb."),
    ]
    if J_s is not None:
        ms.append(Mistake("space_for_geometric", J_s,
                          "This is the space Jacobian: its linear rows are the velocity of the body point at the "
                          "origin of {s}, not of the tool point p."))
    return ms + [swap_mistake(ref)]


def _library_ch05_ex1(ex: Exercise) -> None:
    """The library's geometric Jacobian; its linear rows are the tool point's, by finite differences."""
    arm = jac.robots.planar(ex.given["lengths"])
    th = np.radians(ex.given["theta_deg"])
    np.testing.assert_allclose(ex.solution(), jac.geometric_jacobian(arm, th), atol=1e-12)
    point = lambda x: arm.fk(x)[:3, 3]  # noqa: E731
    # central differences within fd_tol of ∂p/∂θ: truncation h²/6 max|∂³p| plus rounding, from p itself
    assert_within(ex.solution()[3:], jac.numerical_jacobian(point, th), fd_tol(point, th), "linear rows")


@register("ch05_ex1", library=_library_ch05_ex1)
def _ch05_ex1(rng: Generator) -> Exercise:
    ls, th_deg, th, arm = planar_pose(rng, 2)
    J_b = body_jac(arm.body_axes, th)
    J_s = space_jac(arm.screw_axes, th)
    T = fk(arm.screw_axes, arm.home, th)
    R = T[:3, :3]
    ref = blockdiag(R, R) @ J_b
    deg_T = fk(arm.screw_axes, arm.home, th_deg)
    deg_ref = blockdiag(deg_T[:3, :3], deg_T[:3, :3]) @ body_jac(arm.body_axes, th_deg)
    mistakes = _geo_catalogue(ref, J_b, R, J_s) + [degrees_mistake(deg_ref)] + sign_mistakes(ref)
    st = (f"A planar 2R arm with $L = {vec(ls, 1)}$ is at $\\theta = {degs(th_deg)}$. Give its geometric "
          "Jacobian $J(\\theta)$ ($6\\times2$, rows $(\\omega_s, \\dot p)$, $p$ the tool point).")
    def method(r: Callable[[Any], Any]) -> Any:
        """cos, sin, the position Jacobian's entries (z × (p − q_i)); ω = z."""
        th = th_deg * DEG
        Jv = planar_jv(r, ls, th)
        out = np.zeros((6, len(ls)))
        out[2] = 1.0
        out[3:5] = Jv
        return out

    return numeric_exercise("Geometric Jacobian of a planar 2R arm", st, {"lengths": ls, "theta_deg": th_deg}, ref,
                            mistakes, what="geometric Jacobian",
                            hint="Column i is (z_i, z_i × (p - p_i)) with p_i the current position of joint i.",
                            method=method)

def _library_ch05_ex2(ex: Exercise) -> None:
    """The library's body-to-geometric change, on the exact rotation nearest the printed one (see ch04_ex1)."""
    np.testing.assert_allclose(ex.solution(), jac.body_to_geometric(ex.given["J_b"], nearest_pose(ex.given["T_sb"])),
                               atol=2e-3)


@register("ch05_ex2", library=_library_ch05_ex2)
def _ch05_ex2(rng: Generator) -> Exercise:
    T, J_b, ref, J_s = spatial_5r_pose(rng)
    mistakes = _geo_catalogue(ref, J_b, T[:3, :3], J_s)
    st = (f"A 5-joint arm has body Jacobian \n\n$$J_b = {bmatrix(J_b, 6)}$$\n\nat a pose with "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 6)}.$$\n\nGive its geometric Jacobian $J$ (rows $(\\omega_s, \\dot p)$).")
    def method(r: Callable[[Any], Any]) -> Any:
        """R_sb times each half of J_b, written down."""
        return rotate_halves(r, T[:3, :3], J_b)

    return numeric_exercise("From the body to the geometric Jacobian", st, {"J_b": J_b, "T_sb": T}, ref, mistakes,
                            what="geometric Jacobian", method=method)


def _library_ch05_ex3(ex: Exercise) -> None:
    """The column is (z_i, ṗ) with ṗ the velocity of the tool point turning about the axis at unit rate:
    p(t) = p_i + Rot(z_i, t)(p − p_i) (the library's exp_so3), differentiated by central differences, not
    z_i × (p − p_i). Within fd_tol, the rounding relative to |p|, |p_i|."""
    z, p_i, p = ex.given["z_i"], ex.given["p_i"], ex.given["p"]

    def point(t: Array) -> Array:
        return np.asarray(p_i + lie.exp_so3(z * t[0]) @ (p - p_i), dtype=float)

    p_dot = jac.numerical_jacobian(point, np.zeros(1))[:, 0]
    bound = fd_tol(point, np.zeros(1), scale=size(p, p_i))
    assert_within(ex.solution(), np.concatenate([z, p_dot]), bound, "column")


@register("ch05_ex3", library=_library_ch05_ex3)
def _ch05_ex3(rng: Generator) -> Exercise:
    axes = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1], [0, -1, 0]], float)
    z = axes[rng.integers(len(axes))]
    while True:
        p_i = rng.integers(-2, 3, size=3).astype(float)
        p = rng.integers(-2, 3, size=3).astype(float)
        if np.linalg.norm(np.cross(z, p - p_i)) > 0.5 and np.linalg.norm(np.cross(z, p)) > 0.5 \
                and not np.allclose(np.cross(z, p), np.cross(z, p - p_i)):
            break
    ref = np.concatenate([z, np.cross(z, p - p_i)])
    mistakes = [
        Mistake("reversed_difference", np.concatenate([z, np.cross(z, p_i - p)]),
                "The linear part has the wrong sign: it is the velocity of the tool point turning about the "
                "joint axis, so the lever arm points from the joint to the tool."),
        Mistake("no_cross", np.concatenate([z, p - p_i]),
                "The linear part is the lever arm itself; the velocity is the cross product of the axis with "
                "the lever arm."),
        Mistake("lever_from_origin", np.concatenate([z, np.cross(z, p)]),
                "Your lever arm starts at the origin of {s}; it must start at a point of the joint axis."),
        swap_mistake(ref),
    ]
    st = (f"Joint $i$ of an arm is revolute; at the current configuration its axis points along "
          f"$z_i = {vec(z)}$ and passes through $p_i = {vec(p_i)}$, and the tool point is at $p = {vec(p)}$. "
          "Give column $i$ of the geometric Jacobian (6-vector, angular part first).")
    def method(r: Callable[[Any], Any]) -> Any:
        """the lever arm p − p_i, then z_i × (p − p_i), written down."""
        return np.concatenate([z, r(np.cross(z, r(p - p_i)))])

    return numeric_exercise("A geometric-Jacobian column from the axis", st, {"z_i": z, "p_i": p_i, "p": p}, ref,
                            mistakes, what="column", method=method)


def ref_geometric_jacobian(S: ArrayLike, M: ArrayLike, theta: ArrayLike) -> Array:
    """Reference: J = blockdiag(R, R) J_b."""
    T = fk(S, M, theta)
    R = T[:3, :3]
    B = adj(inv_T(M)) @ np.asarray(S, float)
    return blockdiag(R, R) @ body_jac(B, theta)


def _geo_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    T = fk(S, M, th)
    B = adj(inv_T(M)) @ S
    J_b = body_jac(B, th)
    R = T[:3, :3]
    ref = blockdiag(R, R) @ J_b
    J_s = space_jac(S, th)
    mistakes = _geo_catalogue(ref, J_b, R, J_s)
    return (S, M, th), ref, mistakes


def _geo_example(layout: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A planar 2R arm of the seed (lengths, angles in tenths of a radian) and the geometric Jacobian the
    function must return: varies the statement, so that two IDs rarely share one."""
    def build(rng: Generator) -> tuple[dict[str, Any], Any]:
        _, th, B, M = planar_example(rng)
        S = np.round(adj(M) @ B, 12)
        return {"S": S if layout == "columns" else S.T, "M": M, "theta": th}, ref_geometric_jacobian(S, M, th)
    return worked_example("my_geometric_jacobian(S, M, theta)", build)


def _library_ch05_ex4(ex: Exercise) -> None:
    """On every test case, J from the library's space Jacobian instead of the body one: ω_s is its angular
    rows, and the tool point p moves at ṗ = v_s + ω_s × p (v_s is the velocity of the body point at the origin
    of {s}). Exact algebra on terms of size |J_s| max(1, |p|)."""
    for (axes, M, th), out in reference_runs(ex):
        S = np.asarray(axes, dtype=float).T if ex.given["layout"] == "rows" else np.asarray(axes, dtype=float)
        chain = jac.SerialChain(S, M)
        J_s, p = jac.space_jacobian(chain, th), chain.fk(th)[:3, 3]
        expected = np.vstack([J_s[:3], J_s[3:] + np.cross(J_s[:3].T, p).T])
        assert_close(out, expected, "geometric Jacobian", scale=size(J_s) * size(p))


register_code("ch05_ex4", "Code: the geometric Jacobian", [
    CodeVariant(f"Write `my_geometric_jacobian(S, M, theta)` returning the geometric Jacobian $J(\\theta)$ (rows "
                f"$(\\omega_s, \\dot p)$, $6\\times n$) of the chain whose space screw axes `S` are "
                f"{LAYOUT_TEXT[layout]}, with home pose `M`. You may use `jacobians.space_jacobian`/`body_jacobian` "
                "with `jacobians.SerialChain(S, M)` (which wants the axes as columns), but not `geometric_jacobian` "
                "or the conversion functions. Set `answer = my_geometric_jacobian`.",
                ref_geometric_jacobian if layout == "columns"
                else (lambda S, M, th: ref_geometric_jacobian(np.asarray(S).T, M, th)),
                case, "my_geometric_jacobian", "geometric Jacobian", {"layout": layout},
                example=_geo_example(layout))
    for layout, case in layout_cases(_geo_case).items()], library=_library_ch05_ex4)
