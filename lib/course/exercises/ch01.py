"""Exercises of chapter 1: twists, screw axes and the adjoint."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.random import Generator

import jacobians as jac
from jacobians import lie
from jacobians.grading import Case, Exercise, Mistake, numeric_exercise
from jacobians.testing import fd_tol

from ._checks import assert_close, assert_within, conjugated, conjugated_columns, reference_runs, size
from ._hand import adjoint_steps
from ._kinematics import Array, adj, inv_T, swap
from ._latex import bmatrix, vec
from ._mistakes import swap_mistake
from ._registry import CodeVariant, register, register_code
from ._variants import random_transform, worked_example

SKEW_HINT = "Recall [p] is the skew matrix with [p]x = p × x."


def _library_ch01_ex1(ex: Exercise) -> None:
    """The screw axis is the twist of the body turning about the axis at unit rate: [S] = Ṫ(0) for
    T(t) = Trans(q) Rot(ω̂, t) Trans(−q) (T(0) = I), by central differences of the library's exp_so3, not
    from −ω × q. The difference quotient is within fd_tol of Ṫ(0); q − R q is rounded relative to |q|."""
    w, q = ex.given["omega"], ex.given["q"]

    def pose(t: Array) -> Array:
        R = lie.exp_so3(w * t[0])
        return np.asarray(lie.make_transform(R, q - R @ q), dtype=float)

    Tdot = jac.numerical_jacobian(pose, np.zeros(1))[..., 0]
    assert_within(ex.solution(), lie.matrix_to_twist(Tdot), fd_tol(pose, np.zeros(1), scale=size(q)), "screw axis")


@register("ch01_ex1", library=_library_ch01_ex1)
def _ch01_ex1(rng: Generator) -> Exercise:
    axes = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], float)
    w = axes[rng.integers(6)]
    while True:
        q = rng.integers(-3, 4, size=3).astype(float)
        if np.linalg.norm(np.cross(w, q)) > 0.5:
            break
    ref = np.concatenate([w, -np.cross(w, q)])
    mistakes = [
        Mistake("v_sign", np.concatenate([w, np.cross(w, q)]),
                "The linear part has the wrong sign. v is the velocity of the point of the body at the origin "
                "of {s}: work out which way that point moves when the body turns about the axis."),
        swap_mistake(ref),
        Mistake("q_as_v", np.concatenate([w, q]),
                "You put the point q itself in the linear part. The linear part is a velocity, built from "
                "ω and q with a cross product."),
    ]
    st = (f"A revolute joint turns about the unit axis $\\hat\\omega = {vec(w)}$ through the point "
          f"$q = {vec(q)}$ (in {{s}}). Give its screw axis $\\mathcal S = (\\omega, v)$ as a 6-vector, "
          "angular part first.")
    def method(r: Callable[[Any], Any]) -> Any:
        """v = −ω × q written down (integers: nothing to round, but the rule does not assume it)."""
        return np.concatenate([w, r(-np.cross(w, q))])

    return numeric_exercise("Screw axis of a revolute joint", st, {"omega": w, "q": q}, ref, mistakes,
                            what="screw axis", hint="Check v = -ω × q entry by entry.", method=method)
def _adj_mistakes(T: Array) -> list[Mistake]:
    R, p = T[:3, :3], T[:3, 3]
    A = adj(T)
    wrong_order = A.copy()
    wrong_order[3:, :3] = R @ lie.skew(p)
    vfirst = np.zeros((6, 6))
    vfirst[:3, :3] = R
    vfirst[3:, 3:] = R
    vfirst[:3, 3:] = lie.skew(p) @ R
    no_block = A.copy()
    no_block[3:, :3] = 0
    return [
        Mistake("product_order", wrong_order,
                "The lower-left block has its two factors in the wrong order: the skew matrix of p and R do "
                "not commute. " + SKEW_HINT),
        Mistake("v_first_layout", vfirst,
                "This is the adjoint for twists ordered (v, ω). In this course twists are (ω, v), "
                "so the coupling block sits below the diagonal."),
        Mistake("inverse", adj(inv_T(T)),
                "This is the adjoint of the inverse transform. Check which transform the exercise asks about."),
        Mistake("missing_block", no_block,
                "The coupling block is missing: the block-diagonal part alone only rotates, it forgets that the "
                "frames' origins are apart."),
    ]


def _adjoint_by_conjugation(T: Array) -> Array:
    """Column k of [Ad_T] is the unit twist e_k seen through T, (T [e_k] T⁻¹)^∨."""
    return conjugated_columns(T, np.eye(6))


def _library_ch01_ex2(ex: Exercise) -> None:
    """[Ad_T] column by column from its definition, T [V] T⁻¹ (4x4 products): exact algebra on terms of size
    |T| |T⁻¹|, so within TOL of that."""
    T = ex.given["T"]
    assert_close(ex.solution(), _adjoint_by_conjugation(T), "adjoint", scale=size(T) ** 2)


@register("ch01_ex2", library=_library_ch01_ex2)
def _ch01_ex2(rng: Generator) -> Exercise:
    T = random_transform(rng)
    ref = adj(T)
    st = (f"Give the $6\\times 6$ adjoint matrix $[\\mathrm{{Ad}}_T]$ of \n\n$$T = {bmatrix(T, 6)},$$\n\n"
          "for twists ordered $(\\omega, v)$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """R copied, the block [p]R written down."""
        return adjoint_steps(r, T)

    return numeric_exercise("The adjoint of a transform", st, {"T": T}, ref, _adj_mistakes(T), what="adjoint matrix",
                            hint="Compare block by block with [[R, 0], [[p]R, R]].", method=method)


def _library_ch01_ex3(ex: Exercise) -> None:
    """[V_a] = T_ab [V_b] T_ab⁻¹ (4x4 products, not the 6x6 adjoint): exact algebra on terms of size
    |T| |V| |T⁻¹|."""
    T, V = ex.given["T_ab"], ex.given["V_b"]
    assert_close(ex.solution(), conjugated(T, V), "twist", scale=size(T) ** 2 * size(V))


@register("ch01_ex3", library=_library_ch01_ex3)
def _ch01_ex3(rng: Generator) -> Exercise:
    T_ab = random_transform(rng)
    V_b = rng.integers(-3, 4, size=6).astype(float)
    V_b[:3] = V_b[:3] if np.any(V_b[:3]) else np.array([1.0, 0, 0])
    ref = adj(T_ab) @ V_b
    R = T_ab[:3, :3]
    mistakes = [
        Mistake("inverse", adj(inv_T(T_ab)) @ V_b,
                "You used the adjoint of T_ba = T_ab⁻¹. To re-express a twist from {b} in {a}, "
                "use the transform whose subscripts read 'a from b'."),
        swap_mistake(ref),
        Mistake("rotation_only", np.concatenate([R @ V_b[:3], R @ V_b[3:]]),
                "You only rotated both halves. The linear part also picks up p × (R ω) because the "
                "origins of {a} and {b} differ."),
        Mistake("vfirst_input", swap(adj(T_ab) @ swap(V_b)),
                "You read the given twist as (v, ω). It is given angular part first."),
    ]
    st = (f"A body has the twist $\\mathcal V_b = {vec(V_b)}$ expressed in frame {{b}}, and "
          f"\n\n$$T_{{ab}} = {bmatrix(T_ab, 4)}.$$\n\nGive the same twist expressed in {{a}}, $\\mathcal V_a$.")
    def method(r: Callable[[Any], Any]) -> Any:
        """the block [p]R of the adjoint, then [Ad_T_ab] V_b."""
        return adjoint_steps(r, T_ab) @ V_b

    return numeric_exercise("Changing the frame of a twist", st, {"T_ab": T_ab, "V_b": V_b}, ref, mistakes,
                            what="twist", method=method)


def _adj_case(rng: Generator) -> Case:
    T = random_transform(rng)
    T[:3, 3] = rng.uniform(-2, 2, size=3)
    return Case((T,), adj(T), _adj_mistakes(T), f"T with p = {vec(T[:3, 3], 2)}")


def ref_adjoint_of_inverse(T: Array) -> Array:
    """Reference of the second variant: [Ad_{T^-1}] = [[R^T, 0], [-R^T [p], R^T]]."""
    return adj(inv_T(T))


def _adj_inv_case(rng: Generator) -> Case:
    T = random_transform(rng)
    T[:3, 3] = rng.uniform(-2, 2, size=3)
    Ti = inv_T(T)
    R, p = T[:3, :3], T[:3, 3]
    no_sign = adj(Ti)
    no_sign[3:, :3] = R.T @ lie.skew(p)
    mistakes = [
        Mistake("not_inverted", adj(T), "Your function returns [Ad_T]; this variant asks for the adjoint of the "
                "inverse, T⁻¹ = [[Rᵀ, -Rᵀp], [0, 1]]."),
        Mistake("inverse_sign", no_sign, "The lower-left block has the wrong sign: for T⁻¹ the position is -Rᵀp, "
                "so the block is [-Rᵀp]Rᵀ = -Rᵀ[p]."),
        Mistake("transposed_only", adj(T).T, "You transposed [Ad_T]; that is not its inverse (only the rotation "
                "blocks invert by transposing)."),
    ]
    return Case((T,), adj(Ti), mistakes, f"T with p = {vec(p, 2)}")


_ADJ_TASK = ("Write a function `my_adjoint(T)` that takes a $4\\times4$ transform $T$ (numpy array) and returns ")


def _adj_example(inverse: bool) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """A transform of the seed (an exact rotation, a position in halves) and the adjoint the function must
    return on it: varies the statement, so that two IDs rarely share one."""
    def build(rng: Generator) -> tuple[dict[str, Any], Any]:
        T = random_transform(rng)
        return {"T": T}, adj(inv_T(T)) if inverse else adj(T)
    return worked_example("my_adjoint(T)", build)


def _library_ch01_ex4(ex: Exercise) -> None:
    """On every test case, the reference function's matrix is the adjoint by conjugation (of T⁻¹ in the second
    variant), as in ch01_ex2."""
    for (T,), out in reference_runs(ex):
        T_used = np.linalg.inv(T) if ex.given["inverse"] else T
        assert_close(out, _adjoint_by_conjugation(T_used), "adjoint", scale=size(T) ** 2)


register_code("ch01_ex4", "Code: the adjoint map", [
    CodeVariant(_ADJ_TASK + "its $6\\times 6$ adjoint $[\\mathrm{Ad}_T]$ for twists ordered $(\\omega, v)$. "
                "Set `answer = my_adjoint`. It is tested on random transforms.",
                adj, _adj_case, "my_adjoint", "adjoint matrix", {"inverse": False}, example=_adj_example(False)),
    CodeVariant(_ADJ_TASK + "the $6\\times 6$ adjoint of its inverse, $[\\mathrm{Ad}_{T^{-1}}]$, for twists "
                "ordered $(\\omega, v)$, written from $R$ and $p$ (do not call a matrix inverse). "
                "Set `answer = my_adjoint`. It is tested on random transforms.",
                ref_adjoint_of_inverse, _adj_inv_case, "my_adjoint", "adjoint matrix", {"inverse": True},
                example=_adj_example(True)),
], library=_library_ch01_ex4)
