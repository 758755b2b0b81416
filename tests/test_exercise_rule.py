"""The checker a student can trust, over every exercise and 50 IDs.

For every numeric exercise and every ID: the reference is accepted; the exercise's own method worked by hand,
every intermediate rounded to the decimals the statement asks to carry and the answer to the decimals asked, is
accepted; an answer just inside the stated tolerance is accepted and one just outside gets the message about
precision (never a catalogued mistake, never a hint about the method); every catalogued mistake is named; a
vector with its entries in the wrong order is named as such. The printed data is the exercise's data (a printed
pose is a pose: the library's functions take it as given, and they solve the exercise). For the code exercise of
inverse kinematics, the faulty loops of the catalogue get their names and the right ones (returning θ, or MR's
(θ, success)) are accepted.

The number of (exercise, ID) pairs covered is printed by ``test_pairs_covered``.
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

import jacobians as jac
from course import exercises
from course.exercises._variants import _py
from jacobians.grading import rounding
from jacobians.grading.compare import NEAR

IDS = [f"s{2417000 + 37 * k}" for k in range(50)]
ALL = exercises.exercise_ids()
NUMERIC = [e for e in ALL if exercises.load(e, seed=IDS[0]).kind == "numeric"]
SCALAR = [e for e in ALL if exercises.load(e, seed=IDS[0]).kind == "scalar"]

#: Exercises answered from printed data by one library call: the call, on the variant's given.
LIBRARY = {
    "ch01_ex2": lambda g: jac.adjoint(g["T"]),
    "ch01_ex3": lambda g: jac.adjoint(g["T_ab"]) @ g["V_b"],
    "ch03_ex2": lambda g: jac.adjoint(jac.lie.inverse_transform(g["M"])) @ g["S"],
    "ch04_ex1": lambda g: jac.space_to_body(g["J_s"], g["T_sb"]),
    "ch04_ex2": lambda g: jac.body_to_space(g["J_b"], g["T_sb"]),
    "ch05_ex2": lambda g: jac.body_to_geometric(g["J_b"], g["T_sb"]),
}


def _pose_keys(given):
    return [k for k, v in given.items() if isinstance(v, np.ndarray) and v.shape == (4, 4)]


#: The generic names of an answer in the wrong order (jacobians.grading.compare), beside the catalogued ones.
ORDER_MISTAKES = {"wrong_order", "transposed", "column_order", "row_order", "block_order"}


def _reorderings(ref):
    """The answer's own values in a wrong order, each with what was done: a vector reversed, each pair of
    neighbouring entries swapped, a twist's halves swapped; a matrix transposed, each pair of neighbouring columns
    and of neighbouring rows swapped, the halves of 6 rows swapped; a stack of matrices in reverse order, and each
    of its matrices reordered as a matrix is."""
    ref = np.asarray(ref, dtype=float)
    out = []
    if ref.ndim == 1 and ref.size > 1:
        out.append(("reversed", ref[::-1]))
        out += [(f"entries {i + 1}, {i + 2} swapped", ref[_swap(ref.size, i)]) for i in range(ref.size - 1)]
        if ref.size == 6:
            out.append(("halves swapped", np.r_[ref[3:], ref[:3]]))
    elif ref.ndim == 2:
        out.append(("transposed", ref.T))
        out += [(f"columns {j + 1}, {j + 2} swapped", ref[:, _swap(ref.shape[1], j)]) for j in range(ref.shape[1] - 1)]
        out += [(f"rows {i + 1}, {i + 2} swapped", ref[_swap(ref.shape[0], i)]) for i in range(ref.shape[0] - 1)]
        if ref.shape[0] == 6:
            out.append(("row halves swapped", np.vstack([ref[3:], ref[:3]])))
    elif ref.ndim == 3:
        out.append(("blocks reversed", ref[::-1]))
        for how, _ in _reorderings(ref[0]):
            out.append((f"each block: {how}", np.stack([dict(_reorderings(b))[how] for b in ref])))
    return out


def _swap(n, i):
    order = list(range(n))
    order[i], order[i + 1] = i + 1, i
    return order


#: How many reorderings of each kind the tests checked (printed by test_pairs_covered).
reordered: Counter[str] = Counter()


@pytest.mark.parametrize("eid", NUMERIC)
def test_numeric_exercise_accepts_right_work_and_names_every_wrong_answer(eid):
    for seed in IDS:
        ex = exercises.load(eid, seed=seed)
        ref = np.asarray(ex.reference, dtype=float)
        assert ex.tol is not None and ex.tol > 0
        tol_text = f"{ex.tol:.10f}".rstrip("0").rstrip(".")
        assert f"±{tol_text} of the exact value is accepted" in ex.statement, (seed, ex.statement[-300:])
        assert ex.check(ref).correct, seed
        # Right hand-work: the method with every step rounded as the statement says (every numeric exercise has
        # its method, so its tolerance is derived, not a default).
        assert ex.method is not None, eid
        hand = rounding.hand_answer(ex.method, ex.carry, ex.decimals)
        fb = ex.check(hand)
        assert fb.correct, (seed, np.max(np.abs(hand - ref)), ex.tol, fb)
        # The stated rule: just inside is right, just outside is told to carry more decimals.
        e0 = np.zeros_like(ref)
        e0.flat[0] = 1.0
        assert ex.check(ref + 0.9 * ex.tol * e0).correct, seed
        fb = ex.check(ref + 0.5 * (1 + NEAR) * ex.tol * e0)
        assert not fb.correct and fb.mistake == "imprecise", (seed, fb)
        assert "carry more decimals" in fb.message and "method looks right" in fb.message
        # Every catalogued mistake is named, by its own name.
        for m in ex.mistakes:
            fb = ex.check(np.asarray(m.value, dtype=float))
            assert not fb.correct and fb.mistake == m.name, (seed, m.name, fb)
        # Values in the wrong order, where the order matters: each reordering that is not the answer within the rule
        # is named as an order mistake (or as the catalogued mistake it is, such as (v, ω) rows or ascending).
        named = ORDER_MISTAKES | {m.name for m in ex.mistakes}
        for how, wrong in _reorderings(ref):
            if wrong.shape == ref.shape and np.max(np.abs(wrong - ref)) <= 2 * (1 + NEAR) * ex.tol:
                continue  # (a reordering that changes nothing the rule sees, such as swapping two equal entries)
            fb = ex.check(wrong)
            assert not fb.correct and fb.mistake in named, (seed, how, fb)
            reordered[how] += 1
        # Printed data is the data: poses are poses to the last bit, and what is printed is what is given.
        for key in _pose_keys(ex.given):
            R = ex.given[key][:3, :3]
            assert np.abs(R.T @ R - np.eye(3)).max() < 1e-12, (seed, key)
            jac.lie.inverse_transform(ex.given[key])  # the library takes it as given
        for key, v in ex.given.items():
            if isinstance(v, np.ndarray) and v.dtype.kind == "f" and v.ndim == 2:
                assert np.allclose(np.round(v, 6), v, rtol=0, atol=1e-12), (seed, key)  # printed with 6 decimals
        if eid in LIBRARY:
            fb = ex.check(LIBRARY[eid](ex.given))
            assert fb.correct, (seed, fb)


@pytest.mark.parametrize("eid", SCALAR)
def test_scalar_exercise_states_its_rule_and_accepts_the_reference(eid):
    for seed in IDS:
        ex = exercises.load(eid, seed=seed)
        assert "of the exact value is accepted" in ex.statement
        assert ex.check(ex.solution()).correct
        for m in ex.mistakes:
            assert ex.check(float(m.value)).mistake == m.name, (seed, m.name)


CODE = [e for e in ALL if exercises.load(e, seed=IDS[0]).kind == "function"]


#: The reorderings a code answer is tried with, by the number of indices of its output.
CODE_REORDERINGS = {1: ("reversed", "entries 1, 2 swapped"),
                    2: ("transposed", "columns 1, 2 swapped", "rows 1, 2 swapped", "row halves swapped"),
                    3: ("blocks reversed", "each block: transposed", "each block: rows 1, 2 swapped")}


def _reordering_function(ref_fn, how, seen_ndim=None):
    """A student's function that computes the right values and returns them reordered as ``how`` says (``None``:
    unchanged; a function of the IK exercise may return (θ, success): θ is reordered); ``seen_ndim`` collects the
    number of indices of the outputs."""
    def reorder(out):
        if seen_ndim is not None:
            seen_ndim.add(out.ndim)
        return out if how is None else dict(_reorderings(out)).get(how, out)

    def fn(*args):
        out = ref_fn(*args)
        if isinstance(out, tuple):
            return (reorder(np.asarray(out[0], dtype=float)), *out[1:])
        return reorder(np.asarray(out, dtype=float))
    return fn


@pytest.mark.parametrize("eid", CODE)
def test_a_code_answer_in_the_wrong_order_is_named_as_such(eid):
    """A function that returns the right values in a wrong order (as :func:`_reorderings` makes them) is named as
    an order mistake, or as the catalogued mistake it is, on 3 IDs (each check runs the function on several
    tests; the numeric exercises take 50; 1 ID for the inverse kinematics loop, whose checker runs a search per
    ID); some reordering applies to every code exercise."""
    seen = set()
    for seed in IK_IDS[:1] if eid == "ch10_ex4" else IDS[:3]:
        ex = exercises.load(eid, seed=seed)
        catalogued = {m.name for c in (ex.cases() if hasattr(ex, "cases") else []) for m in c.mistakes}
        ndim: set[int] = set()
        assert ex.check(_reordering_function(ex.reference, None, ndim)).correct, seed
        (k,) = ndim
        for how in CODE_REORDERINGS[k]:
            fb = ex.check(_reordering_function(ex.reference, how))
            if fb.correct:  # (this reordering changes none of the values of any test)
                continue
            assert fb.mistake in ORDER_MISTAKES | catalogued | {"v_omega_swapped", "unchanged"}, (seed, how, fb)
            seen.add(how)
            reordered[f"code: {how}"] += 1
    assert seen, "some reordering applies to every code exercise"


def test_issue_cases_are_accepted():
    """The hand-worked answers a student gave with the ID s2417093, each 1-2 units of the last decimal off."""
    # The variants that student worked on are the catalogue's for the seed text "s2417093" (drawn before IDs
    # picked one of the variant banks' variants): load them from the catalogue directly.
    seed = "s2417093"
    assert exercises.CATALOGUE.load("ch11_ex4", seed=seed).check(2.628).correct
    assert exercises.CATALOGUE.load("ch10_ex2", seed=seed).check([1.520, -1.736]).correct
    ex = exercises.CATALOGUE.load("ch12_ex3", seed=seed)
    assert ex.check(rounding.hand_answer(ex.method, 3, 3)).correct


def test_right_singular_values_in_the_wrong_order_are_named_as_an_order_mistake():
    for seed in IDS[:10]:
        ex = exercises.load("ch11_ex3", seed=seed)
        ref = np.asarray(ex.reference)
        for perm in ([2, 1, 0], [1, 0, 2], [0, 2, 1]):
            if np.max(np.abs(ref - ref[perm])) > 2 * (1 + NEAR) * ex.tol:
                fb = ex.check(ref[perm])
                assert fb.mistake in ("ascending", "wrong_order") and "order" in fb.message + fb.mistake, fb


def test_messages_agree_with_their_subject():
    ex = exercises.CATALOGUE.load("ch10_ex2", seed="s2417093")
    assert "joint values match the reference" in ex.check(ex.reference).message
    assert "matches" in exercises.CATALOGUE.load("ch11_ex4", seed="s2417093").check(2.6288).message


# ----------------------------------------------------------------------------------- the code exercise of IK

def _loop(frame, *, stop="both", cap="arg", shift=0, ret="theta", error="right", sign=1.0, transpose=False,
          flag="right"):
    """A student's Newton–Raphson loop, written with Modern Robotics' functions (not the checker's)."""
    mr = pytest.importorskip("modern_robotics")

    def my_ik(axes, M, T_sd, theta0, eps_omega, eps_v, max_iterations):
        th = np.array(theta0, dtype=float)
        steps = {"arg": max_iterations + shift, "mr": 20, "none": 10 ** 9}[cap]
        k = 0
        while True:
            T = mr.FKinBody(M, axes, th) if frame == "body" else mr.FKinSpace(M, axes, th)
            body = mr.TransInv(T) @ T_sd
            space = T_sd @ mr.TransInv(T)
            X = {"right": body if frame == "body" else space, "other": space if frame == "body" else body}[error]
            V = mr.se3ToVec(mr.MatrixLog6(X))
            w, v = np.linalg.norm(V[:3]), np.linalg.norm(V[3:])
            done = {"both": w <= eps_omega and v <= eps_v, "either": w <= eps_omega or v <= eps_v,
                    "norm_omega": np.linalg.norm(V) <= eps_omega, "norm_v": np.linalg.norm(V) <= eps_v,
                    "never": False}[stop]
            if done or k >= steps:
                break
            J = mr.JacobianBody(axes, th) if frame == "body" else mr.JacobianSpace(axes, th)
            th = th + sign * (J.T @ V if transpose else np.linalg.pinv(J) @ V)
            k += 1
        if ret == "pair":
            return th, (bool(done) if flag == "right" else True)
        return th

    return my_ik


FAULTY = {
    "stop_on_either": {"stop": "either"},
    "stop_on_norm_eps_omega": {"stop": "norm_omega"},
    "no_iteration_cap": {"cap": "none"},
    "ignores_max_iterations": {"cap": "mr"},
    "fixed_steps": {"stop": "never", "cap": "mr"},
    "one_step_short": {"shift": -1},
    "one_step_over": {"shift": +1},
    "reversed_error": {"sign": -1.0},
    "transpose_step": {"transpose": True},
    "wrong_success_flag": {"ret": "pair", "flag": "always_true"},
}

IK_IDS = ["s2417093", "alice01", "bob02", "s2417000"]


@pytest.mark.parametrize("seed", IK_IDS)
def test_ik_loop_right_forms_accepted_and_faulty_loops_named(seed):
    ex = exercises.load("ch10_ex4", seed=seed)
    frame = ex.given["frame"]
    assert "at most 20 steps" not in ex.hint and "max_iterations" in ex.hint
    assert ex.check(_loop(frame)).correct
    assert ex.check(_loop(frame, ret="pair")).correct
    other = "space_twist_for_body" if frame == "body" else "body_twist_for_space"
    named = {other: ex.check(_loop(frame, error="other"))}
    for name, kw in FAULTY.items():
        named[name] = ex.check(_loop(frame, **kw))
    # Each faulty loop gets its own name; where no test tells two mistakes apart (the search for tolerances that
    # separate the stop tests can fail), the message offers both, the right one among them, and names neither.
    messages = {c.name: c.message for case in ex.cases() for c in case.mistakes}
    wrong = {name: fb.mistake for name, fb in named.items()
             if fb.correct or (fb.mistake != name and not (fb.mistake == "ambiguous" and name in messages
                                                           and messages[name] in fb.message))}
    assert not wrong, wrong
    assert not any(fb.mistake == "ambiguous" for fb in named.values()), {n: fb.mistake for n, fb in named.items()}


def _imitation(cases, name):
    """A loop that makes mistake ``name`` exactly where the catalogue says it shows (its value there), and is
    right elsewhere: the checker's own record of the mistake, without running a faulty loop."""
    def my_ik(*args):
        for case_args, ref, mistakes, _ in cases:
            if all(np.array_equal(np.asarray(a), np.asarray(b)) for a, b in zip(case_args, args, strict=True)):
                return next((np.array(m.value) for m in mistakes if m.name == name), np.array(ref))
        raise AssertionError("unexpected input")
    return my_ik


def test_ik_loop_reference_accepted_and_every_catalogued_mistake_named_alone_over_50_ids():
    """No ID gets "ambiguous" for the reference or for a catalogued mistake: each mistake of the catalogue is
    named by its own name (the tests tell it from every other), and the library's loop is right."""
    from course.exercises import ch10
    for seed in IDS:
        ex = exercises.load("ch10_ex4", seed=seed)
        cases = ex.cases()
        assert not ch10.unseparated(cases), seed
        assert ex.check(ex.reference).correct, seed
        for name in sorted({m.name for c in cases for m in c.mistakes}):
            fb = ex.check(_imitation(cases, name))
            assert not fb.correct and fb.mistake == name, (seed, name, fb.mistake)


def test_pairs_covered(capsys):
    code = 3 * (len(CODE) - 1) + 1  # (the code exercises in the wrong order; the IK loop's 50 IDs are counted below)
    pairs = len(NUMERIC) * len(IDS) + len(SCALAR) * len(IDS) + len(IDS) + code
    with capsys.disabled():
        if reordered:  # (when the tests above ran in this process)
            print(f"\nwrong orders named: {sum(reordered.values())} answers: " +
                  ", ".join(f"{how} {n}" for how, n in sorted(reordered.items())))
        print(f"\n(exercise, ID) pairs covered: {len(NUMERIC)} numeric and {len(SCALAR)} scalar exercises x "
              f"{len(IDS)} IDs + {len(IDS)} IDs of the IK code exercise + {code} (code exercise, ID) pairs in the "
              f"wrong order = {pairs}")
    assert pairs >= 50 * 30


# ----------------------------------------------------------------------------------- enough variants

@pytest.mark.parametrize("eid", ALL)
def test_every_exercise_has_at_least_20_distinct_statements(eid):
    """40 IDs see at least 20 different statements of every exercise (numbers, arm, asked column or task, or the
    worked example of a code exercise), so two students of a class rarely share one."""
    statements = {exercises.load(eid, seed=f"student{k:03d}").statement for k in range(40)}
    assert len(statements) >= 20, (eid, len(statements))


#: The worked example of each code exercise, solved with the library's own functions from its printed input.
EXAMPLE_BY_LIBRARY = {
    "ch01_ex4": lambda g, a: jac.adjoint(jac.lie.inverse_transform(a["T"]) if g["inverse"] else a["T"]),
    "ch02_ex4": lambda g, a: jac.space_jacobian(jac.SerialChain(_cols(g, a["S"]), np.eye(4)), a["theta"]),
    "ch04_ex3": lambda g, a: (jac.space_to_body if g["direction"] == "space_to_body" else jac.body_to_space)(
        a["J"], a["T_sb"]),
    "ch05_ex4": lambda g, a: jac.geometric_jacobian(jac.SerialChain(_cols(g, a["S"]), a["M"]), a["theta"]),
    "ch07_ex4": lambda g, a: np.vstack([a["J"][3:], a["J"][:3]]),
    "ch08_ex4": lambda g, a: jac.link_jacobians(jac.SerialChain(_cols(g, a["S"]), np.eye(4)), a["theta"]),
}


def _cols(given, axes):
    return axes if given["layout"] == "columns" else axes.T


@pytest.mark.parametrize("eid", sorted(EXAMPLE_BY_LIBRARY))
def test_worked_example_of_a_code_exercise_is_the_librarys_answer_and_the_references(eid):
    """The example printed in the statement: the library's answer on the printed input, what the exercise's
    reference returns, and what the statement prints (4 decimals); the input is printed exactly."""
    for seed in IDS:
        ex = exercises.load(eid, seed=seed)
        args, result = ex.given["example"], ex.given["example_result"]
        for v in args.values():
            assert np.allclose(np.round(v, 6), v, rtol=0, atol=1e-12), (seed, v)  # printed with 6 decimals
        lib = np.asarray(EXAMPLE_BY_LIBRARY[eid](ex.given, args), dtype=float)
        if eid == "ch07_ex4":  # Pinocchio's rows (v, ω): the library's Jacobian of the same arm, rows swapped back
            assert np.allclose(np.vstack([result[3:], result[:3]]), args["J"], atol=1e-12)
        np.testing.assert_allclose(lib, result, atol=1e-9, err_msg=seed)
        np.testing.assert_allclose(ex.reference(*args.values()), result, atol=1e-9, err_msg=seed)
        assert ex.check(ex.reference).correct, seed
        assert f"must return {_py(result, 4)} (to 4 decimals)" in ex.statement, seed


def test_the_fast_kinematics_of_the_ik_cases_follows_the_library():
    """The search of IK test cases runs the loop with plain-numpy kinematics; its iterates are the library's (same
    formulas: they agree to rounding, far below the 1e-11 nudge a case must survive), on random chains with
    prismatic joints, from starts near and far."""
    from course.exercises import ch10
    from course.exercises._variants import random_chain_data

    rng = np.random.default_rng(23)
    for _ in range(12):
        S, M, th = random_chain_data(rng)
        chain = jac.SerialChain(S, M)
        T_sd = chain.fk(th)
        th0 = th + rng.uniform(0.05, 1.0) * rng.normal(size=len(th))
        for frame in ("body", "space"):
            fast, lib = ch10._trail(chain, T_sd, th0, frame, 8), ch10.trail_by_library(chain, T_sd, th0, frame, 8)
            k = min(len(fast.thetas), len(lib.thetas))
            assert k >= 2
            for a, b, na, nb in zip(fast.thetas[:k], lib.thetas[:k], fast.norms[:k], lib.norms[:k], strict=True):
                if nb[2] > 1e-12:  # before convergence to rounding (after it the fast trail stops computing)
                    np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * (1 + np.abs(b).max()))
                    np.testing.assert_allclose(na, nb, rtol=1e-6, atol=1e-13)
