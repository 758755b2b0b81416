"""Two-joint planar arms in sympy, built from exponentials and adjoints: the references and the catalogues
of mistakes of the symbolic exercises (space and body Jacobian, chapters 2 and 3; position Jacobian,
chapter 6).

The arm varies with the seed: each joint is revolute about $+z$ or $-z$, or prismatic along $x$ or $y$
(not both prismatic), 12 pairs of joints; and its shape at home: link 1 (length $l_1$) and link 2 (length
$l_2$) each along $x$ or along $y$ (:data:`SHAPES`, 4 shapes), 48 arms in all. Joint 1 sits at the origin,
joint 2 (if revolute) turns about an axis through the end of link 1, and the tool frame is at the end of
link 2 at home, oriented like {s}.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import sympy as sp
from numpy.random import Generator
from sympy.simplify.fu import TR10i

from jacobians.grading import Mistake
from jacobians.testing import close

#: The joints an arm can have: revolute about +z or -z, prismatic along x or y.
JOINTS = ("R+", "R-", "Px", "Py")

#: Every two-joint arm of the symbolic exercises (12): not both joints prismatic.
ARMS: tuple[tuple[str, str], ...] = tuple((a, b) for a in JOINTS for b in JOINTS if not (a[0] == b[0] == "P"))


#: The shapes at home: the directions (x, y) of link 1 and of link 2 in {s}.
SHAPES: dict[str, tuple[tuple[int, int], tuple[int, int]]] = {
    "x": ((1, 0), (1, 0)), "y": ((0, 1), (0, 1)), "xy": ((1, 0), (0, 1)), "yx": ((0, 1), (1, 0))}


def draw_arm(rng: Generator) -> tuple[str, str]:
    """One of :data:`ARMS`, drawn from the exercise's stream."""
    return ARMS[int(rng.integers(len(ARMS)))]


def draw_shape(rng: Generator) -> str:
    """One of :data:`SHAPES`, drawn from the exercise's stream (after :func:`draw_arm`)."""
    return list(SHAPES)[int(rng.integers(len(SHAPES)))]


def sym_names(syms: tuple[Any, ...]) -> dict[str, Any]:
    return dict(zip(("theta1", "theta2", "l1", "l2"), syms, strict=True))


def _sym_2r() -> tuple[Any, Any, Any, Any]:
    th1, th2, l1, l2 = sp.symbols("theta1 theta2 l1 l2", real=True)
    return th1, th2, l1, l2


def _screw(kind: str, qx: Any, qy: Any = 0) -> Any:
    """The screw axis of a joint of kind ``kind`` whose revolute axis passes through (qx, qy, 0)."""
    if kind == "R+":
        return sp.Matrix([0, 0, 1, qy, -qx, 0])     # v = -ω × q = -(−qy, qx, 0)
    if kind == "R-":
        return sp.Matrix([0, 0, -1, -qy, qx, 0])
    if kind == "Px":
        return sp.Matrix([0, 0, 0, 1, 0, 0])
    if kind == "Py":
        return sp.Matrix([0, 0, 0, 0, 1, 0])
    raise ValueError(f"Expected a joint kind in {JOINTS}, got {kind!r}")


def _sym_exp(S: Any, th: Any) -> Any:
    """exp([S] th) for a planar screw: ω = (0, 0, w) with w in {-1, 0, 1}, v in the xy-plane, no pitch."""
    w = S[2]
    T = sp.eye(4)
    if w == 0:
        T[:3, 3] = S[3:, 0] * th
        return T
    c, s = sp.cos(w * th), sp.sin(w * th)
    R = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    q = sp.Matrix([-w * S[4], w * S[3], 0])       # the point of the axis nearest the origin: q = ω × v
    T[:3, :3] = R
    T[:3, 3] = (sp.eye(3) - R) * q
    return T


def _sym_adj(T: Any) -> Any:
    R, p = T[:3, :3], T[:3, 3]
    P = sp.Matrix([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    A = sp.zeros(6, 6)
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = P * R
    return A


def _tidy(A: Any) -> Any:
    """Each entry expanded, its products of sines and cosines gathered into sines and cosines of sums (Fu's
    rule TR10i, far cheaper than ``trigsimp``), common factors taken out."""
    return A.applyfunc(lambda e: sp.factor_terms(TR10i(sp.expand(e))))


@functools.lru_cache(maxsize=len(ARMS) * len(SHAPES))
def sym_arm(arm: tuple[str, str] = ("R+", "R+"), shape: str = "x"
            ) -> tuple[tuple[Any, Any, Any, Any], Any, Any, Any, Any, Any, Any]:
    """Symbolic S, M, J_s, J_b, B and T(θ) of a two-joint planar arm of the given shape (cached per arm)."""
    th1, th2, l1, l2 = _sym_2r()
    (a1, b1), (a2, b2) = SHAPES[shape]
    S1, S2 = _screw(arm[0], 0), _screw(arm[1], a1 * l1, b1 * l1)
    E1, E2 = _sym_exp(S1, th1), _sym_exp(S2, th2)
    M = sp.eye(4)
    M[0, 3], M[1, 3] = a1 * l1 + a2 * l2, b1 * l1 + b2 * l2
    J_s = _tidy(sp.Matrix.hstack(S1, _sym_adj(E1) * S2))
    Minv = sp.eye(4)
    Minv[0, 3], Minv[1, 3] = -M[0, 3], -M[1, 3]
    B = _tidy(_sym_adj(Minv) * sp.Matrix.hstack(S1, S2))
    # Body recursion: J_b2 = B2, J_b1 = Ad(e^{-[B2] theta2}) B1.
    J_b = _tidy(sp.Matrix.hstack(_sym_adj(_sym_exp(B[:, 1], -th2)) * B[:, 0], B[:, 1]))
    T = _tidy(E1 * E2 * M)
    return (th1, th2, l1, l2), sp.Matrix.hstack(S1, S2), M, J_s, J_b, B, T


def sym_planar_2r() -> tuple[tuple[Any, Any, Any, Any], Any, Any, Any, Any, Any, Any]:
    """The planar 2R arm (both joints about +z)."""
    return sym_arm(("R+", "R+"))


def _point(x: str, y: str) -> str:
    return f"$({x}, {y}, 0)$"


def describe_arm(arm: tuple[str, str], shape: str = "x") -> str:
    """The arm in words, for a statement."""
    (a1, b1), (a2, b2) = SHAPES[shape]
    end1 = _point("l_1", "0") if a1 else _point("0", "l_1")
    tool = {"x": _point("l_1 + l_2", "0"), "y": _point("0", "l_1 + l_2"), "xy": _point("l_1", "l_2"),
            "yx": _point("l_2", "l_1")}[shape]

    def joint(kind: str, where: str) -> str:
        if kind[0] == "R":
            return f"turns about ${'+' if kind == 'R+' else '-'}z$ through {where}"
        return f"slides along ${kind[1]}$"
    prismatic = [str(i + 1) for i, k in enumerate(arm) if k[0] == "P"]
    slide = (f" For the prismatic joint {prismatic[0]}, $\\theta_{prismatic[0]}$ is its displacement (0 at home)."
             if prismatic else "")
    links = ("both links along $x$" if shape == "x" else "both links along $y$" if shape == "y" else
             f"link 1 along ${'x' if a1 else 'y'}$, link 2 along ${'x' if a2 else 'y'}$")
    return (f"A planar arm with two joints: joint 1 {joint(arm[0], 'the origin')}, joint 2 "
            f"{joint(arm[1], end1 + ' at home')}; at home ({links}) the tool frame is at {tool}, "
            f"oriented like {{s}}.{slide}")


def _at(expr: Any, point: dict[Any, float]) -> Any:
    return np.array(expr.xreplace(point).evalf().tolist(), dtype=float)


def distinct_sym(ref: Any, mistakes: list[Mistake]) -> list[Mistake]:
    """The symbolic mistakes that differ from the reference and from each other (at two random points)."""
    syms = sorted(ref.free_symbols | {s for m in mistakes for s in m.value.free_symbols}, key=str)
    points = [{s: v for s, v in zip(syms, vals, strict=True)}
              for vals in ([0.37 + 0.29 * k for k in range(len(syms))], [1.13 - 0.23 * k for k in range(len(syms))])]
    seen = [[_at(ref, p) for p in points]]
    kept = []
    for m in mistakes:
        vals = [_at(m.value, p) for p in points]
        # Equal expressions evaluate (evalf, 15 digits, then rounded to doubles) to within a few units of roundoff
        # of their terms' size, a few dozen operations apart: close's TOL relative to max(1, size) holds with a
        # margin. Different ones (a sign, a swapped length, a missing term) differ at these generic points by a
        # fraction of the lengths, nine orders of magnitude more.
        if any(all(a.shape == b.shape and close(a, b) for a, b in zip(vals, s, strict=True))
               for s in seen):
            continue
        seen.append(vals)
        kept.append(m)
    return kept


def theta_mixups(ref: Any) -> list[Mistake]:
    """θ1 written where θ2 was meant, and the reverse, for the joint angles the reference depends on."""
    th1, th2, _, _ = _sym_2r()
    out = []
    if th2 in ref.free_symbols:
        out.append(Mistake("theta1_for_theta2", ref.xreplace({th2: th1}),
                           "You wrote θ1 where θ2 belongs: check which joint's angle each entry depends on."))
    if th1 in ref.free_symbols:
        out.append(Mistake("theta2_for_theta1", ref.xreplace({th1: th2}),
                           "You wrote θ2 where θ1 belongs: check which joint's angle each entry depends on."))
    return out


def sym_catalogue(ref: Any, other: Any, other_name: str, other_msg: str, home: Any, home_msg: str) -> list[Mistake]:
    def neg_col(A: Any, j: int) -> Any:
        W = A.copy()
        W[:, j] = -W[:, j]
        return W
    sw = sp.Matrix.vstack(ref[3:, :], ref[:3, :])
    return distinct_sym(ref, [
        Mistake(other_name, other, other_msg),
        Mistake("v_omega_swapped", sw, "Your rows are in the order (v, ω): this course puts the angular part "
                "first, rows 1-3 ω and rows 4-6 v."),
        Mistake("home_axes", home, "These are the screw axes at the home pose. " + home_msg),
        Mistake("sign_column_1", neg_col(ref, 0), "Column 1 has the opposite sign: check the direction of "
                "joint 1's axis (for a revolute joint also the sign in v = -ω × q)."),
        Mistake("sign_column_2", neg_col(ref, 1), "Column 2 has the opposite sign: check the direction of "
                "joint 2's axis (for a revolute joint also the sign in v = -ω × q)."),
        *theta_mixups(ref),
    ])


SYM_NOTE = ("Use sympy: `theta1, theta2, l1, l2 = sympy.symbols('theta1 theta2 l1 l2', real=True)` and give a "
            "`sympy.Matrix`.")


#: The point a symbolic reference is checked at against the library: lengths and angles of no special value.
CHECK_POINT = {"theta1": 0.4, "theta2": -1.1, "l1": 0.7, "l2": 1.3}


def numeric_arm(reference: Any, S: Any, M: Any, symbols: dict[str, Any]) -> tuple[Any, Any, Any]:
    """A symbolic reference, screw axes and home pose at :data:`CHECK_POINT`: the reference's value, the numeric
    :class:`~jacobians.chain.SerialChain` of the arm at those lengths, and its joint angles."""
    from jacobians.chain import SerialChain

    subs = {symbols[name]: value for name, value in CHECK_POINT.items()}
    ref = np.array(sp.Matrix(reference).subs(subs).evalf().tolist(), dtype=float)
    S_num = np.array(sp.Matrix(S).subs(subs).evalf().tolist(), dtype=float)
    M_num = np.array(sp.Matrix(M).subs(subs).evalf().tolist(), dtype=float)
    return ref, SerialChain(S_num, M_num), np.array([CHECK_POINT["theta1"], CHECK_POINT["theta2"]])
