"""A made-up chapter, ``ch00``, that the tests of ``make grade`` hand in (``tests/test_classroom*.py``).

One exercise of each kind the grader meets (two numeric, a symbolic, a code one), on a planar arm, so that
changing the course's chapters never changes what those tests grade, nor the other way round. Its page is
``tests/fixtures/00_fixture.md``, in the exercise pages' layout (``tools/make_exercises.py``).

It is not part of the course: importing this module registers nothing. :func:`register` adds the chapter to the
catalogue and :func:`unregister` removes it (the tests do both around a test module); :mod:`course.exercises`
calls :func:`register` on import when the environment variable :data:`ENV` is set, which the tests set and the
sandbox of ``make grade`` passes on (:func:`course.classroom.sandbox._environment`), so that the notebooks
graded there load the same chapter. The definitions live in the package, not under ``tests/``, because the
sandbox sees the course's ``lib`` folder and nothing else of the checkout.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import sympy as sp
from numpy.random import Generator

import jacobians as jac
from jacobians.grading import Case, Exercise, Mistake, numeric_exercise, symbolic_exercise
from jacobians.testing import fd_tol

from ._checks import assert_close, assert_within, reference_runs, size
from ._kinematics import DEG, Array
from ._latex import num
from ._mistakes import degrees_mistake
from ._registry import CATALOGUE, LIBRARY_CHECKS, CodeVariant, register_code
from ._registry import register as _register

__all__ = ["CHAPTER", "ENV", "IDS", "register", "unregister"]

#: The environment variable that makes :mod:`course.exercises` register this chapter on import.
ENV = "COURSE_FIXTURE_CHAPTER"
#: The chapter's id and its exercises, in page order.
CHAPTER = "ch00"
IDS = ("ch00_ex1", "ch00_ex2", "ch00_ex3", "ch00_ex4")


def _one_link(rng: Generator) -> tuple[float, float]:
    """A link length (m) and a joint angle (degrees, a multiple of 15 away from the axes)."""
    angles = [a for a in range(-165, 180, 15) if a % 90]
    return float(rng.choice([0.5, 1.0, 1.5, 2.0])), float(rng.choice(angles))


def _tip(ex: Exercise) -> None:
    """The tip is the library's forward kinematics of the one-link arm: within TOL of L."""
    L, th = ex.given["length"], np.radians(ex.given["theta_deg"])
    assert_close(ex.solution(), jac.robots.planar([L]).fk([th])[:2, 3], "tip", scale=L)


def _build_tip(rng: Generator) -> Exercise:
    L, th_deg = _one_link(rng)
    th = th_deg * DEG
    ref = L * np.array([np.cos(th), np.sin(th)])
    mistakes = [degrees_mistake(L * np.array([np.cos(th_deg), np.sin(th_deg)])),
                Mistake("x_y_swapped", ref[::-1], "x and y are swapped: x = L cos θ, y = L sin θ.")]
    st = (f"A one-link planar arm of length $L = {num(L)}$ m turns about $z$ at the origin and is at "
          f"$\\theta = {int(th_deg)}^\\circ$. Give its tip $(x, y)$ in m.")

    def method(r: Callable[[Any], Any]) -> Any:
        """cos θ and sin θ written down, times L."""
        return L * np.array([r(np.cos(th)), r(np.sin(th))])

    return numeric_exercise("Tip of a one-link arm", st, {"length": L, "theta_deg": th_deg}, ref, mistakes,
                            what="tip position", method=method)


def _velocity(ex: Exercise) -> None:
    """The tip velocity is the library's geometric Jacobian's position rows times the rate: within TOL of L θ̇."""
    g = ex.given
    J = jac.geometric_jacobian(jac.robots.planar([g["length"]]), [np.radians(g["theta_deg"])])
    assert_close(ex.solution(), J[3:5, 0] * g["theta_dot"], "tip velocity", scale=g["length"] * abs(g["theta_dot"]))


def _build_velocity(rng: Generator) -> Exercise:
    L, th_deg = _one_link(rng)
    rate = float(rng.choice([-2.0, -1.0, -0.5, 0.5, 1.0, 2.0]))
    th = th_deg * DEG
    ref = L * rate * np.array([-np.sin(th), np.cos(th)])
    mistakes = [Mistake("sign", -ref, "The velocity points the wrong way: turning by +θ̇ moves the tip "
                        "counter-clockwise, (−sin θ, cos θ) times L θ̇."),
                degrees_mistake(L * rate * np.array([-np.sin(th_deg), np.cos(th_deg)]))]
    st = (f"A one-link planar arm of length $L = {num(L)}$ m is at $\\theta = {int(th_deg)}^\\circ$ and turns at "
          f"$\\dot\\theta = {num(rate)}$ rad/s. Give the velocity $(\\dot x, \\dot y)$ of its tip in m/s.")

    def method(r: Callable[[Any], Any]) -> Any:
        """sin θ and cos θ written down, times L θ̇."""
        return L * rate * np.array([-r(np.sin(th)), r(np.cos(th))])

    return numeric_exercise("Tip velocity of a one-link arm", st, {"length": L, "theta_deg": th_deg,
                                                                   "theta_dot": rate}, ref, mistakes,
                            what="tip velocity", method=method)


#: The link's direction at home and the joint axis's sign: four arms.
_HOME = {"x": 0.0, "y": np.pi / 2}


def _jacobian_column(ex: Exercise) -> None:
    """At a point, the reference is central differences of the library's forward kinematics of that arm (a chain
    with screw axis (0, 0, ±1, 0, 0, 0) and the tip at l along the home direction), within fd_tol."""
    g = ex.given
    th1, l1 = g["symbols"]["theta1"], g["symbols"]["l1"]
    M = np.eye(4)
    M[:2, 3] = 1.3 * np.array([np.cos(_HOME[g["home"]]), np.sin(_HOME[g["home"]])])
    chain = jac.SerialChain(np.array([[0.0], [0.0], [g["axis"]], [0.0], [0.0], [0.0]]), M)
    at = np.array([0.7])
    value = np.array(ex.reference.subs({th1: at[0], l1: 1.3}).evalf().tolist(), dtype=float)

    def tip(t: Array) -> Array:
        return np.asarray(chain.fk(t)[:2, 3], dtype=float)

    assert_within(value, jac.numerical_jacobian(tip, at), fd_tol(tip, at, scale=1.3), "position Jacobian")


def _build_column(rng: Generator) -> Exercise:
    home = str(rng.choice(list(_HOME)))
    axis = float(rng.choice([-1.0, 1.0]))
    th1, l1 = sp.symbols("theta1 l1", real=True)
    angle = axis * th1 + (0 if home == "x" else sp.pi / 2)
    x, y = l1 * sp.cos(angle), l1 * sp.sin(angle)
    ref = sp.Matrix([[sp.diff(x, th1)], [sp.diff(y, th1)]])
    mistakes = [Mistake("position", sp.Matrix([[x], [y]]), "This is the tip's position; the exercise asks for its "
                        "derivative with respect to θ1."),
                Mistake("sign", -ref, "The sign is flipped: differentiate cos and sin carefully.")]
    where = {"x": "along $x$", "y": "along $y$"}[home]
    turn = "counter-clockwise" if axis > 0 else "clockwise"
    st = (f"A one-link planar arm of length $l_1$ lies {where} at $\\theta_1 = 0$ and turns {turn} about $z$ as "
          "$\\theta_1$ grows. Give its position Jacobian $\\partial(x, y)/\\partial\\theta_1$ as a $2\\times1$ sympy "
          "Matrix in `theta1, l1` (real symbols).")
    ex = symbolic_exercise("Position Jacobian of a one-link arm", st, {"theta1": th1, "l1": l1}, ref, mistakes,
                           what="position Jacobian")
    ex.hint = "Differentiate x and y of the tip with respect to θ1."
    ex.given.update({"home": home, "axis": axis})
    return ex


def _tip_of(lengths: Array, theta: Array) -> Array:
    """The tip (x, y) of a planar arm: link i points along θ1 + ... + θi."""
    c = np.cumsum(theta)
    return np.array([np.sum(lengths * np.cos(c)), np.sum(lengths * np.sin(c))])


def _tip_case(unit: str) -> Callable[[Generator], Case]:
    def make_case(rng: Generator) -> Case:
        n = int(rng.integers(1, 5))
        lengths = np.round(rng.uniform(0.5, 1.5, size=n), 2)
        theta = np.round(rng.uniform(-3.0, 3.0, size=n), 2)
        given = np.degrees(theta) if unit == "deg" else theta
        ref = _tip_of(lengths, theta)
        c = np.cos(theta), np.sin(theta)
        mistakes = [Mistake("relative_angles", np.array([lengths @ c[0], lengths @ c[1]]),
                            "Each link points along the sum of the joint angles before it, not its own angle.")]
        if unit == "deg":
            mistakes.append(degrees_mistake(_tip_of(lengths, given)))
        return Case((lengths, given), ref, mistakes, f"{n} links")
    return make_case


def _tip_code(ex: Exercise) -> None:
    """On every test case, the reference function's tip is the library's forward kinematics of the planar arm
    (angles in radians), within TOL of the arm's reach."""
    for (lengths, theta), out in reference_runs(ex):
        th = np.radians(theta) if ex.given["unit"] == "deg" else np.asarray(theta, dtype=float)
        expected = jac.robots.planar([float(v) for v in lengths]).fk(th)[:2, 3]
        assert_close(out, expected, "tip", scale=size(np.sum(lengths)))


_TIP_TASK = ("Write `my_tip(lengths, theta)`: the tip $(x, y)$ of a planar arm whose links have the lengths "
             "`lengths` (a numpy array of $n$ numbers) at joint angles `theta` ")


def _variants() -> list[CodeVariant]:
    return [CodeVariant(_TIP_TASK + "(in radians). Set `answer = my_tip`.", _tip_of, _tip_case("rad"), "my_tip",
                        "tip position", {"unit": "rad"}),
            CodeVariant(_TIP_TASK + "(in **degrees**). Set `answer = my_tip`.",
                        lambda lengths, theta: _tip_of(np.asarray(lengths), np.radians(theta)), _tip_case("deg"),
                        "my_tip", "tip position", {"unit": "deg"})]


def register() -> None:
    """Add the chapter's exercises to the catalogue (nothing if they are there already)."""
    if IDS[0] in CATALOGUE:
        return
    _register("ch00_ex1", library=_tip)(_build_tip)
    _register("ch00_ex2", library=_velocity)(_build_velocity)
    _register("ch00_ex3", library=_jacobian_column)(_build_column)
    register_code("ch00_ex4", "Code: the tip of a planar arm", _variants(), library=_tip_code)


def unregister() -> None:
    """Remove the chapter's exercises from the catalogue again (nothing if they are not there)."""
    for eid in IDS:
        if eid in CATALOGUE:
            CATALOGUE.unregister(eid)
        LIBRARY_CHECKS.pop(eid, None)
