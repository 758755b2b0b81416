"""Exercises of chapter 7: the conventions of other books and libraries."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator
from numpy.typing import ArrayLike

import jacobians as jac
from jacobians.grading import Exercise, Mistake, numeric_exercise

from ._checks import assert_close, assert_within, reference_runs, size
from ._hand import rotate_halves
from ._kinematics import Array, adj, blockdiag, fk, inv_T, nearest_pose, space_jac, swap
from ._latex import bmatrix
from ._registry import CodeVariant, register, register_code
from ._variants import chain_case, planar_exact_state, spatial_5r_pose, worked_example

V_FIRST = ("Rows 1-3 of your answer should be the angular part and rows 4-6 the linear part: Modern Robotics "
           "puts ω first, unlike Siciliano, Corke and Pinocchio.")


def _p_cross(p: Array, J: Array) -> Array:
    """Rows (omega, v + p x omega)."""
    out = J.copy()
    out[3:] = J[3:] + np.cross(p, J[:3].T).T
    return out


def _library_ch07_ex1(ex: Exercise) -> None:
    """The library's reordering of (v, ω) rows to (ω, v) (``interop.to_angular_first``): nothing is computed,
    so the entries are equal."""
    assert_within(ex.solution(), jac.interop.to_angular_first(ex.given["J_sic"]), 0.0, "geometric Jacobian")


@register("ch07_ex1", library=_library_ch07_ex1)
def _ch07_ex1(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_sic = np.round(swap(J), 6)
    ref = swap(J_sic)
    mistakes = [
        Mistake("unchanged", J_sic, "You copied Siciliano's matrix unchanged; its rows are (ṗ, ω). " + V_FIRST),
        Mistake("space_for_geometric", _p_cross(T[:3, 3], ref),
                "You also moved the reference point to the origin of {s}: that is the space Jacobian. The exercise "
                "asks for the geometric Jacobian, which keeps ṗ of the tool point."),
    ]
    st = (f"Siciliano's book writes the geometric Jacobian with rows $(\\dot p, \\omega)$. For a 5-joint arm it "
          f"is \n\n$$J_{{Sic}} = {bmatrix(J_sic, 6)}.$$\n\nGive the same Jacobian in this course's convention, rows "
          "$(\\omega_s, \\dot p)$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """the rows reordered: nothing is computed, nothing rounded."""
        return swap(J_sic)

    return numeric_exercise("Siciliano's geometric Jacobian", st, {"J_sic": J_sic}, ref, mistakes,
                            what="geometric Jacobian", method=method)


def _library_ch07_ex2(ex: Exercise) -> None:
    """The library's geometric-to-space change of the Jacobian in (ω, v) rows, on the exact rotation nearest the
    printed one (see ch04_ex1)."""
    J0 = ex.given["J0"]
    np.testing.assert_allclose(ex.solution(), jac.geometric_to_space(np.vstack([J0[3:], J0[:3]]),
                                                                 nearest_pose(ex.given["T_sb"])), atol=2e-3)


@register("ch07_ex2", library=_library_ch07_ex2)
def _ch07_ex2(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J0 = np.round(swap(J), 6)          # Corke's jacob0: (v of the tool point, omega) in the world frame
    Jg = swap(J0)
    p = T[:3, 3]
    ref = _p_cross(p, Jg)
    mistakes = [
        Mistake("only_swapped", Jg,
                "You reordered the rows, which gives the geometric Jacobian (velocity of the tool point). "
                "J_s wants the velocity of the body point at the origin of {s}: shift the reference point."),
        Mistake("unchanged", J0, "You copied jacob0 unchanged: its rows are (v, ω). " + V_FIRST),
        Mistake("wrong_shift_sign", _p_cross(-p, Jg),
                "The reference-point shift has the wrong sign: v_s = ṗ - ω × p = ṗ + p × ω."),
        Mistake("shift_not_swapped", swap(_p_cross(p, Jg)),
                "The point shift is right but the rows are (v, ω). " + V_FIRST),
    ]
    st = (f"Robotics Toolbox's `jacob0` returns, for a 5-joint arm, the world-frame Jacobian of the tool point "
          f"with rows $(v, \\omega)$: \n\n$$J_0 = {bmatrix(J0, 6)}.$$\n\n"
          f"The tool pose is \n\n$$T_{{sb}} = {bmatrix(T, 6)}.$$\n\n"
          "Give the space Jacobian $J_s$ of Modern Robotics.")
    def method(r: Callable[[Any], Any]) -> Any:
        """the rows reordered, p × ω of each column written down, added to ṗ."""
        out = Jg.copy()
        out[3:] = Jg[3:] + np.asarray(r(np.cross(p, Jg[:3].T).T))
        return out

    return numeric_exercise("From Corke's jacob0 to the space Jacobian", st, {"J0": J0, "T_sb": T}, ref, mistakes,
                            what="space Jacobian", method=method)


def _library_ch07_ex3(ex: Exercise) -> None:
    """Through the space Jacobian instead of a rotation: the rows reordered (``interop``), the library's
    geometric-to-space change, then its space-to-body change, at the printed T_sb (an exact pose: short
    decimals). Exact algebra on terms of size |J| max(1, |p|)²."""
    J_lwa, T = ex.given["J_lwa"], ex.given["T_sb"]
    J_s = jac.geometric_to_space(jac.interop.to_angular_first(J_lwa), T)
    assert_close(ex.solution(), jac.space_to_body(J_s, T), "body Jacobian", scale=size(J_lwa) * size(T) ** 2)


@register("ch07_ex3", library=_library_ch07_ex3)
def _ch07_ex3(rng: Generator) -> Exercise:
    T, J_b, J, J_s = spatial_5r_pose(rng)
    J_lwa = np.round(swap(J), 6)       # Pinocchio LOCAL_WORLD_ALIGNED: (v of the frame origin, omega) in world axes
    R = T[:3, :3]
    Jg = swap(J_lwa)
    ref = blockdiag(R.T, R.T) @ Jg
    mistakes = [
        Mistake("only_swapped", Jg,
                "You reordered the rows only. LOCAL_WORLD_ALIGNED uses the axes of the world frame; J_b needs "
                "both halves expressed in the tool frame."),
        Mistake("R_not_transposed", blockdiag(R, R) @ Jg,
                "You rotated with R_sb; to express world-axis vectors in {b}, multiply by R_sbᵀ."),
        Mistake("only_angular_rotated", blockdiag(R.T, np.eye(3)) @ Jg, "Only the angular half was rotated into {b}."),
        Mistake("only_linear_rotated", blockdiag(np.eye(3), R.T) @ Jg, "Only the linear half was rotated into {b}."),
        Mistake("not_swapped", blockdiag(R.T, R.T) @ J_lwa, "The rotation is right but the rows are (v, ω). "
                + V_FIRST),
    ]
    st = (f"Pinocchio's `getFrameJacobian(..., LOCAL_WORLD_ALIGNED)` gives, for the tool frame of a 5-joint arm, "
          f"rows $(v, \\omega)$ of the frame's origin in world axes: \n\n$$J_{{LWA}} = {bmatrix(J_lwa, 6)},$$\n\nat "
          f"\n\n$$T_{{sb}} = {bmatrix(T, 6)}.$$\n\nGive the body Jacobian $J_b$ of Modern Robotics.")
    def method(r: Callable[[Any], Any]) -> Any:
        """the rows reordered, then R_sbᵀ times each half, written down."""
        return rotate_halves(r, R.T, Jg)

    return numeric_exercise("From Pinocchio's LOCAL_WORLD_ALIGNED to the body Jacobian", st,
                            {"J_lwa": J_lwa, "T_sb": T}, ref, mistakes, what="body Jacobian", method=method)


def ref_from_pinocchio_world(J_world: ArrayLike) -> Array:
    """Reference: Pinocchio WORLD (v, omega) at the world origin -> MR J_s (omega, v)."""
    return swap(np.asarray(J_world, float))


def _world_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    J_s = space_jac(S, th)
    J_world = swap(J_s)
    T = fk(S, M, th)
    mistakes = [
        Mistake("unchanged", J_world, "Your function returns its input unchanged: WORLD rows are (v, ω). " + V_FIRST),
        Mistake("moved_point", space_jac(S, th) - np.vstack([np.zeros((3, J_s.shape[1])),
                                                            np.cross(T[:3, 3], J_s[:3].T).T]),
                "Your function moves the reference point to the tool. WORLD is already taken at the world origin, "
                "like J_s: only the row order differs."),
    ]
    return (J_world,), J_s, mistakes


def _local_case(S: Array, M: Array, th: Array) -> tuple[tuple[Any, ...], Any, list[Mistake]]:
    T = fk(S, M, th)
    J_b = adj(inv_T(T)) @ space_jac(S, th)
    J_local = swap(J_b)
    R = T[:3, :3]
    mistakes = [
        Mistake("unchanged", J_local, "Your function returns its input unchanged: LOCAL rows are (v, ω). " + V_FIRST),
        Mistake("rotated_to_world", blockdiag(R, R) @ J_b,
                "Your function rotates the halves into the world axes. LOCAL is already expressed in the tool "
                "frame, like J_b: only the row order differs."),
    ]
    return (J_local,), J_b, mistakes


def _pinocchio_example(frame: str) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """Pinocchio's WORLD (or LOCAL) Jacobian of a planar 2R arm of the seed at angles with exact one-decimal
    cosines and sines (short exact decimals), and the Modern Robotics Jacobian the function must return."""
    def build(rng: Generator) -> tuple[dict[str, Any], Any]:
        S, _, th, T = planar_exact_state(rng)
        J_s = np.round(space_jac(S, th), 10)
        J = J_s if frame == "WORLD" else np.round(adj(inv_T(T)) @ J_s, 10)
        return {"J": swap(J)}, J
    return worked_example("from_pinocchio(J)", build)


def _library_ch07_ex4(ex: Exercise) -> None:
    """On every test case, the library's reordering (``interop.to_angular_first``) of the given rows: nothing is
    computed, so the entries are equal."""
    for (J,), out in reference_runs(ex):
        assert_within(out, jac.interop.to_angular_first(J), 0.0, "Modern Robotics Jacobian")


register_code("ch07_ex4", "Code: from Pinocchio's conventions", [
    CodeVariant("Pinocchio's `WORLD` Jacobian is the space Jacobian with rows $(v, \\omega)$. Write "
                "`from_pinocchio(J)` that takes it and returns the Modern Robotics space Jacobian $J_s$ "
                "($6\\times n$, numpy). Set `answer = from_pinocchio`.",
                ref_from_pinocchio_world, chain_case(_world_case), "from_pinocchio", "space Jacobian",
                {"pinocchio_frame": "WORLD"}, example=_pinocchio_example("WORLD")),
    CodeVariant("Pinocchio's `LOCAL` Jacobian of the tool frame is the body Jacobian with rows $(v, \\omega)$. "
                "Write `from_pinocchio(J)` that takes it and returns the Modern Robotics body Jacobian $J_b$ "
                "($6\\times n$, numpy). Set `answer = from_pinocchio`.",
                ref_from_pinocchio_world, chain_case(_local_case), "from_pinocchio", "body Jacobian",
                {"pinocchio_frame": "LOCAL"}, example=_pinocchio_example("LOCAL")),
], library=_library_ch07_ex4)
