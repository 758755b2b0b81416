"""Random variants: nice angles, lengths, rotations, chains and poses drawn from the seeded generator,
and the test cases of function exercises."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.random import Generator

from jacobians import robots
from jacobians.chain import SerialChain
from jacobians.grading import Case, Mistake

from ._kinematics import DEG, Array, adj, blockdiag, body_jac, fk, planar_chain, space_jac


def angles_deg(rng: Generator, n: int, step: int = 15, low: int = -150, high: int = 150,
               nonzero: bool = True) -> Array:
    """``n`` angles in degrees, multiples of ``step`` in [low, high] (0 excluded unless ``nonzero`` is False)."""
    choices = np.arange(low, high + 1, step)
    if nonzero:
        choices = choices[choices != 0]
    return rng.choice(choices, size=n).astype(float)


def lengths(rng: Generator, n: int, low: float = 0.5, high: float = 1.5) -> Array:
    """``n`` link lengths with one decimal."""
    return np.round(rng.uniform(low, high, size=n), 1)


#: Cosine and sine pairs with one exact decimal (the 3-4-5 triangle and the quarter turn): a rotation about
#: coordinate axes by such angles has entries that are short exact decimals, so a pose printed with them is a
#: pose (Rᵀ R = I to the last bit), which the library's functions accept as given.
EXACT_CS = [(0.6, 0.8), (0.8, 0.6), (-0.6, 0.8), (-0.8, 0.6)]


def exact_angle(rng: Generator) -> float:
    """An angle (rad) whose cosine and sine are in :data:`EXACT_CS` up to the sign of the sine: 36.87°, 53.13°,
    126.87° or 143.13°, or their negatives."""
    c, s = EXACT_CS[int(rng.integers(len(EXACT_CS)))]
    return float(np.arctan2(s * float(rng.choice([-1.0, 1.0])), c))


def axis_rotation(axis: int, angle: float) -> Array:
    """The rotation about coordinate axis ``axis`` (0, 1, 2 = x, y, z) by ``angle``, entries rounded to 12
    decimals (exact for the angles of :func:`exact_angle`: their cosines and sines are one-decimal numbers)."""
    j, k = (axis + 1) % 3, (axis + 2) % 3
    c, s = np.round(np.cos(angle), 12), np.round(np.sin(angle), 12)
    R = np.eye(3)
    R[j, j], R[j, k], R[k, j], R[k, k] = c, -s, s, c
    return R


def random_rotation(rng: Generator) -> Array:
    """A rotation about two random coordinate axes in turn, by angles with exact one-decimal cosines and sines:
    its entries are exact decimals of at most two digits (e.g. 0.48), so the printed matrix is a rotation."""
    R = axis_rotation(int(rng.integers(3)), exact_angle(rng)) @ axis_rotation(int(rng.integers(3)), exact_angle(rng))
    return np.round(R, 12)


def random_transform(rng: Generator) -> Array:
    """A transform with an exact rotation (:func:`random_rotation`) and a position in halves."""
    T = np.eye(4)
    T[:3, :3] = random_rotation(rng)
    T[:3, 3] = rng.integers(-3, 4, size=3) * 0.5
    if not np.any(T[:3, 3]):
        T[0, 3] = 1.0
    return T


def random_chain_data(rng: Generator, n: int | None = None, prismatic: bool = True) -> tuple[Array, Array, Array]:
    """A random spatial chain (S 6xn, M 4x4): unit axes through random points, maybe a prismatic joint."""
    n = int(rng.integers(2, 7)) if n is None else n
    cols = []
    for _ in range(n):
        w = rng.normal(size=3)
        w /= np.linalg.norm(w)
        if prismatic and rng.random() < 0.2:
            cols.append(np.concatenate([np.zeros(3), w]))
        else:
            q = rng.uniform(-1, 1, size=3)
            cols.append(np.concatenate([w, -np.cross(w, q)]))
    S = np.stack(cols, axis=1)
    M = np.eye(4)
    M[:3, :3] = random_rotation(rng)
    M[:3, 3] = rng.uniform(-1, 1, size=3)
    theta = rng.uniform(-np.pi, np.pi, size=n)
    return S, M, theta


class PlanarPose(NamedTuple):
    """A random planar arm at a random pose: lengths, angles in degrees and radians, the chain."""

    lengths: Array
    theta_deg: Array
    theta: Array
    arm: SerialChain


def planar_pose(rng: Generator, n: int, step: int = 15, low: int = -150, high: int = 150) -> PlanarPose:
    """A planar nR arm (lengths drawn first, then angles, as :func:`lengths` and :func:`angles_deg` draw)."""
    ls = lengths(rng, n)
    th_deg = angles_deg(rng, n, step=step, low=low, high=high)
    return PlanarPose(ls, th_deg, th_deg * DEG, planar_chain(ls))


class SpatialPose(NamedTuple):
    """The spatial 5R arm at a random pose, as a statement shows it (4 digits): the pose, the body,
    geometric and space Jacobians."""

    T: Array
    J_b: Array
    J: Array
    J_s: Array


def exact_angles(rng: Generator, n: int, rich: int = 2) -> Array:
    """``n`` joint angles (rad): ``rich`` of them (at random places) from :func:`exact_angle`, the others quarter
    or half turns, so that a pose of an arm with coordinate joint axes has short exact decimals."""
    th = rng.choice([-0.5 * np.pi, 0.5 * np.pi, np.pi], size=n).astype(float)
    for j in rng.choice(n, size=min(rich, n), replace=False):
        th[int(j)] = exact_angle(rng)
    return th


def spatial_5r_pose(rng: Generator) -> SpatialPose:
    """The spatial 5R arm (joint axes along coordinate axes) with random dimensions at a random pose whose
    angles have exact one-decimal cosines and sines (:func:`exact_angles`): the pose and the Jacobians are
    exact short decimals (at most 6 decimals; the rounding to 10 only removes binary noise), so printed with 6
    decimals they are the data of the problem, and T_sb is a pose the library accepts."""
    vals = [float(v) for v in rng.choice([0.3, 0.5, 0.8, 1.0], size=5)]
    arm = robots.spatial_5r(*vals)
    th = exact_angles(rng, 5)
    T = np.round(fk(arm.screw_axes, arm.home, th), 10)
    J_b = np.round(body_jac(arm.body_axes, th), 10)
    R = T[:3, :3]
    return SpatialPose(T, J_b, np.round(blockdiag(R, R) @ J_b, 10), np.round(adj(T) @ J_b, 10))


# ----------------------------------------------------------------- test cases of function exercises

CaseBody = Callable[[Array, Array, Array], tuple[tuple[Any, ...], Any, list[Mistake]]]


def chain_case(body: CaseBody, layout: str = "columns") -> Callable[[Generator], Case]:
    """A ``make_case`` for a function exercise on a random chain: ``body(S, M, theta)`` gives the
    arguments, the reference and the mistakes; the case is labelled by the chain's number of joints.
    With ``layout="rows"`` the first argument (the axes, 6 x n) is passed transposed, one axis per row."""
    def make_case(rng: Generator) -> Case:
        S, M, th = random_chain_data(rng)
        args, ref, mistakes = body(S, M, th)
        if layout == "rows":
            args = (np.asarray(args[0]).T.copy(), *args[1:])
        return Case(args, ref, mistakes, f"a random {S.shape[1]}-joint chain")
    make_case.__doc__ = body.__doc__
    return make_case


#: How a variant of a Jacobian code exercise passes the screw axes, for its statement.
LAYOUT_TEXT = {
    "columns": "a $6\\times n$ numpy array whose columns are the screw axes $(\\omega, v)$",
    "rows": ("an $n\\times 6$ numpy array whose rows are the screw axes $(\\omega, v)$, one row per joint (as "
             "some libraries store them)"),
}


def layout_cases(body: CaseBody) -> dict[str, Callable[[Generator], Case]]:
    """The ``make_case`` of each layout of the axes, for the two variants of a Jacobian code exercise."""
    return {layout: chain_case(body, layout) for layout in LAYOUT_TEXT}


def planar_column(rng: Generator, frame: str, low: int, high: int
                   ) -> tuple[Array, Array, int, Array, Array, Array, Array]:
    """Ch. 2 and 3's "one column by hand": a planar 3R arm at a random pose and a joint i in [low, high).

    Returns the lengths, the angles in degrees, i, the home screw axes of ``frame`` ("space" or "body"),
    the Jacobian of ``frame``, the other Jacobian, and the Jacobian of ``frame`` computed with the angles
    in degrees (a mistake)."""
    ls, th_deg, th, arm = planar_pose(rng, 3)
    i = int(rng.integers(low, high))
    jacobian: dict[str, tuple[Array, Callable[[Array, Array], Array]]] = {
        "space": (arm.screw_axes, space_jac), "body": (arm.body_axes, body_jac)}
    home, own = jacobian[frame]
    axes_other, other = jacobian["body" if frame == "space" else "space"]
    return ls, th_deg, i, home, own(home, th), other(axes_other, th), own(home, th_deg)


# ----------------------------------------------------------------- worked examples of code exercises

def _py(a: Any, digits: int = 6) -> str:
    """A number, vector or matrix as Python source a student can paste (at most ``digits`` decimals)."""
    arr = np.asarray(a, dtype=float)
    if arr.ndim == 0:
        text = f"{float(arr):.{digits}f}".rstrip("0").rstrip(".")
        return "0" if text in ("-0", "") else text
    return "[" + ", ".join(_py(x, digits) for x in arr) + "]"


def planar_example(rng: Generator, exact: bool = False) -> tuple[Array, Array, Array, Array]:
    """A planar 2R arm for a worked example: lengths (one decimal), angles in rad (multiples of 0.1, printed
    exactly; or, with ``exact``, angles of :func:`exact_angle`, whose pose has short exact decimals), its body
    screw axes B (6 x 2, columns) and home pose M."""
    ls = lengths(rng, 2)
    if exact:
        th = np.array([exact_angle(rng), exact_angle(rng)])
    else:
        th = rng.integers(-25, 26, size=2) / 10.0
    arm = planar_chain(ls)
    return ls, th, np.round(arm.body_axes, 12), np.round(arm.home, 12)


def example_text(call: str, args: dict[str, Any], result: Any) -> str:
    """The sentence of a worked example: the inputs as Python, and what the function must return (4 decimals)."""
    inputs = "; ".join(f"`{k} = np.array({_py(v)})`" if np.ndim(v) else f"`{k} = {_py(v)}`"
                       for k, v in args.items())
    return (f"Try it first on this example (yours, from your ID): {inputs}; `{call}` must return "
            f"{_py(result, 4)} (to 4 decimals).")


#: What a worked example is built from: the seed's stream in; the arguments (name -> value, in call order) and
#: what the function must return on them out.
ExampleBuild = Callable[[Generator], tuple[dict[str, Any], Any]]


def worked_example(call: str, build: ExampleBuild) -> Callable[[Generator], tuple[str, dict[str, Any]]]:
    """The ``example`` of a code variant: an input drawn per ID and the result the function must return on it,
    added to the statement (so that two IDs rarely share one) and to the given as ``example`` (the arguments)
    and ``example_result``, where the tests check it against the library."""
    def example(rng: Generator) -> tuple[str, dict[str, Any]]:
        args, result = build(rng)
        return example_text(call, args, result), {"example": args, "example_result": np.asarray(result, float)}
    return example


def planar_exact_state(rng: Generator) -> tuple[Array, Array, Array, Array]:
    """A planar 2R arm of :func:`planar_example` at exact angles, as printed: its space screw axes S (columns),
    home pose M, angles θ (rad) and the pose T_sb(θ), whose entries are short exact decimals (the rounding to 10
    only removes binary noise), so the printed pose is a pose."""
    _, th, B, M = planar_example(rng, exact=True)
    S = np.round(adj(M) @ B, 12)
    return S, M, th, np.round(fk(S, M, th), 10)
