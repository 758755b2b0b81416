"""The planar 2R arm in sympy, built from exponentials and adjoints: the references and the catalogue
of mistakes of the symbolic exercises of chapters 2 and 3 (space and body Jacobian)."""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp

from jacobians.grading import Mistake


def sym_names(syms: tuple[Any, ...]) -> dict[str, Any]:
    return dict(zip(("theta1", "theta2", "l1", "l2"), syms, strict=True))


def _sym_2r() -> tuple[Any, Any, Any, Any]:
    th1, th2, l1, l2 = sp.symbols("theta1 theta2 l1 l2", real=True)
    return th1, th2, l1, l2


def _sym_exp(S: Any, th: Any) -> Any:
    """exp([S] th) for a planar revolute screw (about z), sympy."""
    w = S[:3, 0]
    v = S[3:, 0]
    c, s = sp.cos(th), sp.sin(th)
    R = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]]) if w[2] == 1 else None
    W = sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G = sp.eye(3) * th + (1 - c) * W + (th - s) * W * W
    p = G * v
    T = sp.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def _sym_adj(T: Any) -> Any:
    R, p = T[:3, :3], T[:3, 3]
    P = sp.Matrix([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    A = sp.zeros(6, 6)
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = P * R
    return A


@functools.lru_cache(maxsize=1)
def sym_planar_2r() -> tuple[tuple[Any, Any, Any, Any], Any, Any, Any, Any, Any, Any]:
    """Symbolic S, M, J_s, J_b, B of the planar 2R arm, built from exponentials and adjoints (cached)."""
    th1, th2, l1, l2 = _sym_2r()
    S1 = sp.Matrix([0, 0, 1, 0, 0, 0])
    S2 = sp.Matrix([0, 0, 1, 0, -l1, 0])
    E1 = _sym_exp(S1, th1)
    E2 = _sym_exp(S2, th2)
    M = sp.eye(4)
    M[0, 3] = l1 + l2

    def tidy(A: Any) -> Any:
        return A.applyfunc(lambda e: sp.trigsimp(sp.expand(sp.expand_trig(e))))

    J_s = tidy(sp.Matrix.hstack(S1, _sym_adj(E1) * S2))
    Minv = sp.eye(4)
    Minv[0, 3] = -(l1 + l2)
    B = tidy(_sym_adj(Minv) * sp.Matrix.hstack(S1, S2))
    # Body recursion: J_b2 = B2, J_b1 = Ad(e^{-[B2] theta2}) B1.
    J_b = tidy(sp.Matrix.hstack(_sym_adj(_sym_exp(B[:, 1], -th2)) * B[:, 0], B[:, 1]))
    T = E1 * E2 * M
    return (th1, th2, l1, l2), sp.Matrix.hstack(S1, S2), M, J_s, J_b, B, T


def sym_catalogue(ref: Any, other: Any, other_name: str, other_msg: str, home: Any, home_msg: str) -> list[Mistake]:
    def neg_col(A: Any, j: int) -> Any:
        W = A.copy()
        W[:, j] = -W[:, j]
        return W
    sw = sp.Matrix.vstack(ref[3:, :], ref[:3, :])
    return [
        Mistake(other_name, other, other_msg),
        Mistake("v_omega_swapped", sw, "Your rows are in the order (v, ω): this course puts the angular part "
                "first, rows 1-3 ω and rows 4-6 v."),
        Mistake("home_axes", home, "These are the screw axes at the home pose. " + home_msg),
        Mistake("sign_column_1", neg_col(ref, 0), "Column 1 has the opposite sign: check the direction of "
                "joint 1's axis and the sign in v = -ω × q."),
        Mistake("sign_column_2", neg_col(ref, 1), "Column 2 has the opposite sign: check the direction of "
                "joint 2's axis and the sign in v = -ω × q."),
    ]


SYM_NOTE = ("Use sympy: `theta1, theta2, l1, l2 = sympy.symbols('theta1 theta2 l1 l2', real=True)` and give a "
            "`sympy.Matrix`.")
