"""Tests of jacobians.symbolic: the sympy layer against the numeric library,
against finite differences, against closed forms derived by hand, and on bad input."""

from __future__ import annotations

import inspect
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

import jacobians as jac
from jacobians import lie
from jacobians import symbolic as sym

RNG = np.random.default_rng(20261121)
s, c = sp.sin, sp.cos


def _random_thetas(n, k=6):
    return RNG.uniform(-np.pi, np.pi, size=(k, n))


def _one_joint():
    return sym.SymbolicChain(sp.Matrix([0, 0, 1, 0, 0, 0]), sp.eye(4))


def _is_zero_matrix(A):
    return sym.simplify_matrix(A).is_zero_matrix


# ------------------------------------------------------------------ Lie helpers

def test_skew_is_cross_product():
    a, b = sp.symbols("a b", real=True)
    w = sp.Matrix([a, 2, b])
    x = sp.Matrix([1, a, 3])
    assert sp.expand(sym.skew(w) * x - w.cross(x)) == sp.zeros(3, 1)
    assert sym.skew([1, 2, 3]) == -sym.skew([1, 2, 3]).T


def test_exp_so3_is_a_rotation_and_matches_numeric():
    t = sp.Symbol("t", real=True)
    axis = sp.Matrix([2, -1, 2]) / 3  # unit length
    R = sym.exp_so3(axis, t)
    assert _is_zero_matrix(R.T * R - sp.eye(3))
    assert sym.exp_so3(sym.skew(axis), t) == R  # both input forms agree
    for val in (-2.0, 0.3, 3.0):
        num = lie.exp_so3(np.array(axis, dtype=float).ravel() * val)
        assert np.allclose(np.array(R.subs(t, val), dtype=float), num, atol=1e-12)


@pytest.mark.parametrize("col", [
    [0, 0, 1, 0, -2, 0],            # revolute about z through (2, 0, 0)
    [0, 1, 0, -0.5, 0, 0.25],       # revolute about y, off the origin
    [0.6, 0, 0.8, 1, 2, 3],         # a screw with pitch (unit omega)
    [0, 0, 0, 0, 0.6, 0.8],         # prismatic
])
def test_exp_se3_matches_numeric(col):
    t = sp.Symbol("t", real=True)
    T = sym.exp_se3([sp.nsimplify(v) for v in col], t)
    for val in (-1.7, 0.4, 2.9):
        num = lie.exp_se3(np.array(col, dtype=float) * val)
        assert np.allclose(np.array(T.subs(t, val), dtype=float), num, atol=1e-12)


def test_exp_se3_derivative_is_the_twist():
    # d/dt e^{[S]t} at t = 0 is [S]: an identity, not a copy of the formula
    t = sp.Symbol("t", real=True)
    a, b = sp.symbols("a b", real=True)
    S = sp.Matrix([0, 0, 1, a, b, 0])
    T = sym.exp_se3(S, t)
    assert sp.simplify(T.diff(t).subs(t, 0) - sym.twist_to_matrix(S)) == sp.zeros(4, 4)


def test_adjoint_and_inverse_against_numeric():
    T_num = lie.exp_se3(np.array([0.3, -0.2, 0.5, 1.0, -2.0, 0.7]))
    T = sp.Matrix(T_num)
    assert np.allclose(np.array(sym.adjoint(T), dtype=float), lie.adjoint(T_num), atol=1e-12)
    assert np.allclose(np.array(sym.inverse_transform(T), dtype=float), np.linalg.inv(T_num), atol=1e-12)


def test_adjoint_identity_symbolic():
    # T [V] T^-1 = [Ad_T V] for a symbolic T
    t = sp.Symbol("t", real=True)
    T = sym.exp_se3([0, 1, 0, -1, 0, 2], t)
    V = sp.Matrix(sp.symbols("w1 w2 w3 v1 v2 v3", real=True))
    lhs = T * sym.twist_to_matrix(V) * sym.inverse_transform(T)
    rhs = sym.twist_to_matrix(sym.adjoint(T) * V)
    assert _is_zero_matrix(lhs - rhs)


def test_twist_matrix_round_trip():
    V = sp.Matrix(sp.symbols("w1 w2 w3 v1 v2 v3"))
    assert sym.matrix_to_twist(sym.twist_to_matrix(V)) == V
    assert sym.twist_to_matrix(V)[3, :] == sp.zeros(1, 4)


# ------------------------------------------------------------------ planar chains

@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_planar_chain_matches_robots_planar(n):
    arm, th, ls = sym.planar_chain(n)
    assert len(th) == n and len(ls) == n
    assert all(l.is_positive for l in ls) and all(t.is_real for t in th)
    lengths = RNG.uniform(0.3, 2.0, size=n)
    num = jac.robots.planar(list(lengths))
    subs = dict(zip(ls, lengths, strict=True))
    assert np.allclose(np.array(arm.screw_axes.subs(subs), dtype=float), num.screw_axes)
    assert np.allclose(np.array(arm.home.subs(subs), dtype=float), num.home)
    assert np.allclose(np.array(arm.body_axes.subs(subs), dtype=float), num.body_axes)
    fs = {name: sym.lambdify_matrix(getattr(sym, name)(arm), th + ls)
          for name in ("space_jacobian", "body_jacobian", "geometric_jacobian")}
    fs["fk"] = sym.lambdify_matrix(arm.fk(), th + ls)
    thetas = _random_thetas(n)
    x = np.concatenate([thetas, np.broadcast_to(lengths, thetas.shape)], axis=-1)
    assert np.allclose(fs["space_jacobian"](x), jac.space_jacobian(num, thetas), atol=1e-12)
    assert np.allclose(fs["body_jacobian"](x), jac.body_jacobian(num, thetas), atol=1e-12)
    assert np.allclose(fs["geometric_jacobian"](x), jac.geometric_jacobian(num, thetas), atol=1e-12)
    assert np.allclose(fs["fk"](x), num.fk(thetas), atol=1e-12)


def test_planar_chain_numeric_lengths_and_to_numeric_chain():
    arm, th, ls = sym.planar_chain(2, lengths=[sp.Rational(1, 2), 2])
    assert ls == (sp.Rational(1, 2), 2)
    assert arm.params == ()
    num = sym.to_numeric_chain(arm)
    assert np.allclose(num.screw_axes, jac.robots.planar_2r(0.5, 2.0).screw_axes)
    a = sp.Symbol("a", positive=True)
    arm2, _, _ = sym.planar_chain(2, lengths=[a, 2 * a])
    assert arm2.params == (a,)
    assert np.allclose(sym.to_numeric_chain(arm2, {a: 0.5}).home, jac.robots.planar_2r(0.5, 1.0).home)


def test_planar_2r_textbook_closed_forms():
    """Closed forms derived by hand (s1 = sin theta1, c12 = cos(theta1 + theta2), ...)."""
    arm, (t1, t2), (l1, l2) = sym.planar_chain(2)
    s1, c1, s12, c12 = s(t1), c(t1), s(t1 + t2), c(t1 + t2)
    # position rows of the geometric Jacobian = d/dtheta of (x, y)
    J_p = sp.Matrix([[-l1 * s1 - l2 * s12, -l2 * s12],
                     [l1 * c1 + l2 * c12, l2 * c12]])
    J = sym.geometric_jacobian(arm)
    assert J[3:5, :] == J_p                       # textbook form, exactly
    assert J[:3, :] == sp.Matrix([[0, 0], [0, 0], [1, 1]])
    assert J[5, :] == sp.zeros(1, 2)
    # independent derivation: differentiate the forward kinematics
    p = arm.fk()[:2, 3]
    assert _is_zero_matrix(p.jacobian([t1, t2]) - J_p)
    # the lecture note's (2,1) entry l1*c1 is wrong: it misses l2*c12
    wrong = J_p.copy()
    wrong[1, 0] = l1 * c1
    assert not _is_zero_matrix(wrong - J_p)
    assert sp.simplify(J_p[1, 0] - wrong[1, 0] - l2 * c12) == 0
    # space and body Jacobians
    assert sym.space_jacobian(arm) == sp.Matrix([[0, 0], [0, 0], [1, 1], [0, l1 * s1], [0, -l1 * c1], [0, 0]])
    assert sym.body_jacobian(arm) == sp.Matrix([[0, 0], [0, 0], [1, 1],
                                             [l1 * s(t2), 0], [l1 * c(t2) + l2, l2], [0, 0]])
    # manipulability of the position rows: |det J_p| = l1 l2 |sin theta2|
    assert sp.simplify(sym.simplify_matrix(sp.Matrix([J_p.det()]))[0] - l1 * l2 * s(t2)) == 0


def test_planar_3r_textbook_closed_forms():
    arm, (t1, t2, t3), (l1, l2, l3) = sym.planar_chain(3)
    s1, c1, s12, c12 = s(t1), c(t1), s(t1 + t2), c(t1 + t2)
    s123, c123 = s(t1 + t2 + t3), c(t1 + t2 + t3)
    J_s = sp.Matrix([[0, 0, 0], [0, 0, 0], [1, 1, 1],
                     [0, l1 * s1, l1 * s1 + l2 * s12],
                     [0, -l1 * c1, -l1 * c1 - l2 * c12],
                     [0, 0, 0]])
    J_b = sp.Matrix([[0, 0, 0], [0, 0, 0], [1, 1, 1],
                     [l1 * s(t2 + t3) + l2 * s(t3), l2 * s(t3), 0],
                     [l1 * c(t2 + t3) + l2 * c(t3) + l3, l2 * c(t3) + l3, l3],
                     [0, 0, 0]])
    J = sp.Matrix([[0, 0, 0], [0, 0, 0], [1, 1, 1],
                   [-l1 * s1 - l2 * s12 - l3 * s123, -l2 * s12 - l3 * s123, -l3 * s123],
                   [l1 * c1 + l2 * c12 + l3 * c123, l2 * c12 + l3 * c123, l3 * c123],
                   [0, 0, 0]])
    assert sym.space_jacobian(arm) == J_s
    assert sym.body_jacobian(arm) == J_b
    assert sym.geometric_jacobian(arm) == J
    T = arm.fk()
    assert T[:2, 3] == sp.Matrix([l1 * c1 + l2 * c12 + l3 * c123, l1 * s1 + l2 * s12 + l3 * s123])
    assert T[:3, :3] == sym.exp_so3([0, 0, 1], t1 + t2 + t3)


@pytest.mark.parametrize("n", [2, 3])
def test_relations_between_jacobians_simplify_to_zero(n):
    arm, th, _ = sym.planar_chain(n)
    T = arm.fk()
    J_s, J_b, J = sym.space_jacobian(arm), sym.body_jacobian(arm), sym.geometric_jacobian(arm)
    assert _is_zero_matrix(J_b - sym.adjoint(sym.inverse_transform(T)) * J_s)
    assert _is_zero_matrix(J_s - sym.adjoint(T) * J_b)
    R = T[:3, :3]
    assert _is_zero_matrix(J - sp.diag(R, R) * J_b)


def _symbolic_rrp():
    h, r = sp.symbols("h r", positive=True)
    S = sp.Matrix([[0, 0, 1, 0, 0, 0], [0, 1, 0, -h, 0, 0], [0, 0, 0, 1, 0, 0]]).T
    M = sp.eye(4)
    M[0, 3], M[2, 3] = r, h
    return sym.SymbolicChain(S, M, params=(h, r)), (h, r)


def test_spatial_rrp_symbolic_against_numeric_and_twist_definition():
    arm, (h, r) = _symbolic_rrp()
    th = arm.thetas
    T = arm.fk()
    J_s = sym.space_jacobian(arm)
    # definition: [V_s] = Tdot T^-1, so column i is the twist of dT/dtheta_i T^-1
    Tinv = sym.inverse_transform(T)
    for i in range(3):
        col = sym.matrix_to_twist(sym.simplify_matrix(T.diff(th[i]) * Tinv))
        assert _is_zero_matrix(col - J_s[:, i])
    J_b = sym.body_jacobian(arm)
    for i in range(3):
        col = sym.matrix_to_twist(sym.simplify_matrix(Tinv * T.diff(th[i])))
        assert _is_zero_matrix(col - J_b[:, i])
    # numbers
    num = jac.robots.spatial_rrp(h=0.7, reach=1.3)
    vals = {h: 0.7, r: 1.3}
    thetas = _random_thetas(3)
    for A, ref in ((J_s, jac.space_jacobian(num, thetas)), (J_b, jac.body_jacobian(num, thetas)),
                   (sym.geometric_jacobian(arm), jac.geometric_jacobian(num, thetas)), (T, num.fk(thetas))):
        f = sym.lambdify_matrix(A.subs(vals), th)
        assert np.allclose(f(thetas), ref, atol=1e-12)


def test_geometric_jacobian_is_derivative_of_position():
    arm, _ = _symbolic_rrp()
    T = arm.fk()
    J = sym.geometric_jacobian(arm)
    assert _is_zero_matrix(T[:3, 3].jacobian(list(arm.thetas)) - J[3:, :])


@pytest.fixture(scope="module")
def ur5_symbolic():
    """The UR5's symbolic Jacobians, computed once (the slowest thing in this file)."""
    chain = jac.robots.ur5()
    arm = sym.SymbolicChain.from_numeric(chain)
    return chain, arm, {"space": sym.space_jacobian(arm), "body": sym.body_jacobian(arm),
                        "geometric": sym.geometric_jacobian(arm), "fk": arm.fk()}


def test_ur5_symbolic_matches_numeric(ur5_symbolic):
    chain, arm, out = ur5_symbolic
    thetas = _random_thetas(6, 8)
    refs = {"space": jac.space_jacobian(chain, thetas), "body": jac.body_jacobian(chain, thetas),
            "geometric": jac.geometric_jacobian(chain, thetas), "fk": chain.fk(thetas)}
    for key, A in out.items():
        assert np.allclose(sym.lambdify_matrix(A, arm.thetas)(thetas), refs[key], atol=1e-12), key
    # a few entries in closed form (MR Example 5.7's structure): the first three
    # columns of J_s are z, -s1 x + c1 y (twice) in the angular rows
    assert out["space"][:3, 0] == sp.Matrix([0, 0, 1])
    assert out["space"][:3, 1] == sp.Matrix([-s(arm.thetas[0]), c(arm.thetas[0]), 0])


@pytest.mark.parametrize("factory", [jac.robots.scara, jac.robots.zyx_wrist])
def test_from_numeric_matches_numeric(factory):
    chain = factory()
    arm = sym.SymbolicChain.from_numeric(chain)
    assert arm.dof == chain.dof
    thetas = _random_thetas(chain.dof, 4)
    for simplify in (True, False):
        pairs = ((sym.space_jacobian(arm, simplify=simplify), jac.space_jacobian(chain, thetas)),
                 (sym.body_jacobian(arm, simplify=simplify), jac.body_jacobian(chain, thetas)),
                 (sym.geometric_jacobian(arm, simplify=simplify), jac.geometric_jacobian(chain, thetas)),
                 (arm.fk(simplify=simplify), chain.fk(thetas)))
        for A, ref in pairs:
            assert np.allclose(sym.lambdify_matrix(A, arm.thetas)(thetas), ref, atol=1e-12)


def test_from_numeric_exact_rationals_and_floats():
    ur5 = jac.robots.ur5()
    exact = sym.SymbolicChain.from_numeric(ur5)
    assert exact.screw_axes[5, 2] == sp.Rational(17, 40)
    floats = sym.SymbolicChain.from_numeric(ur5, exact=False)
    assert isinstance(floats.screw_axes[5, 2], sp.Float)


def test_ur5_jacobian_is_finite_difference_of_fk(ur5_symbolic):
    chain, arm, out = ur5_symbolic
    f_T = sym.lambdify_matrix(out["fk"], arm.thetas)
    f_J = sym.lambdify_matrix(out["geometric"], arm.thetas)
    theta = RNG.uniform(-np.pi, np.pi, 6)
    fd = jac.numerical_jacobian(lambda x: f_T(x)[:3, 3], theta)
    assert np.allclose(f_J(theta)[3:], fd, atol=1e-8)


def test_link_jacobians_against_numeric():
    arm, th, ls = sym.planar_chain(3)
    lengths = [0.8, 1.1, 0.5]
    num = jac.robots.planar(lengths)
    subs = dict(zip(ls, lengths, strict=True))
    thetas = _random_thetas(3, 3)
    for frame in ("space", "body", "geometric"):
        ref = jac.link_jacobians(num, thetas, frame=frame)
        homes = [sp.Matrix(H).applyfunc(sp.nsimplify) for H in num.link_homes]
        exact = sym.SymbolicChain(arm.screw_axes.subs(subs).applyfunc(sp.nsimplify), sp.eye(4), link_homes=homes)
        J_links = sym.link_jacobians(exact, th, frame=frame)
        assert len(J_links) == 3
        for i in range(1, 4):
            J_i = J_links[i - 1]
            assert J_i[:, i:].is_zero_matrix
            assert np.allclose(sym.lambdify_matrix(J_i, th)(thetas), ref[:, i - 1], atol=1e-12)


def test_simplify_matrix_strategy():
    a, b, l = sp.symbols("a b l", real=True)
    A = sp.Matrix([[s(a) ** 2 + c(a) ** 2, l * (c(a) * c(b) - s(a) * s(b))],
                   [s(a) * c(b) + c(a) * s(b), s(a) ** 4 - c(a) ** 4 + 2 * c(a) ** 2]])
    out = sym.simplify_matrix(A)
    assert out[0, 0] == 1
    assert out[0, 1] == l * c(a + b)
    assert out[1, 0] == s(a + b)
    assert out[1, 1] == 1  # sin^4 - cos^4 = sin^2 - cos^2
    assert sym.simplify_matrix(sp.Matrix([[l + 1]])) == sp.Matrix([[l + 1]])


def test_lambdify_matrix_shapes_and_calls():
    a, b = sp.symbols("a b")
    f = sym.lambdify_matrix(sp.Matrix([[a, b], [a * b, 1]]), [a, b])
    assert f([2.0, 3.0]).shape == (2, 2)
    assert np.allclose(f([2.0, 3.0]), [[2, 3], [6, 1]])
    x = RNG.normal(size=(4, 5, 2))
    out = f(x)
    assert out.shape == (4, 5, 2, 2)
    assert np.allclose(out[..., 1, 0], x[..., 0] * x[..., 1])
    assert np.allclose(out[..., 1, 1], 1.0)
    assert np.allclose(f(2.0, np.array([1.0, 2.0]))[:, 1, 0], [2.0, 4.0])
    assert f.symbols == (a, b)
    with pytest.raises(ValueError, match=r"\(\.\.\., 2\)"):
        f([1.0, 2.0, 3.0])
    with pytest.raises(TypeError, match="2 values"):
        f(1.0, 2.0, 3.0)
    with pytest.raises(ValueError, match="not in symbols"):
        sym.lambdify_matrix(sp.Matrix([[a, b]]), [a])
    with pytest.raises(TypeError, match="str"):
        sym.lambdify_matrix(sp.Matrix([[a]]), "a")
    with pytest.raises(ValueError, match="distinct"):
        sym.lambdify_matrix(sp.Matrix([[a]]), [a, a])


def test_importing_jacobians_does_not_import_sympy():
    code = "import sys, jacobians; assert 'sympy' not in sys.modules, 'sympy imported'"
    subprocess.run([sys.executable, "-c", code], check=True)


# ------------------------------------------------------------------ bad input

@pytest.mark.parametrize("call, exc, match", [
    (lambda: sym.skew("x y z"), TypeError, "sympy Matrix"),
    (lambda: sym.skew([1, 2]), ValueError, "3 entries"),
    (lambda: sym.skew(None), TypeError, "sympy Matrix"),
    (lambda: sym.exp_so3([1, 1, 0], 0.3), ValueError, "unit rotation axis"),
    (lambda: sym.exp_so3(sp.Matrix([[0, 1, 0], [1, 0, 0], [0, 0, 0]]), 0.3), ValueError, "skew-symmetric"),
    (lambda: sym.exp_so3([0, 0, 1], "t"), TypeError, "theta"),
    (lambda: sym.exp_so3(sp.zeros(2, 2), 1), ValueError, "3 x 3"),
    (lambda: sym.exp_se3([0, 0, 2, 0, 0, 0], 1), ValueError, "unit angular part"),
    (lambda: sym.exp_se3([0, 0, 0, 0, 0, 2], 1), ValueError, "unit linear part"),
    (lambda: sym.exp_se3([0, 0, 1, 0, 0], 1), ValueError, "6 entries"),
    (lambda: sym.exp_se3([0, 0, 1, 0, 0, 0], 1 + 2j), TypeError, "real"),
    (lambda: sym.exp_se3([0, 0, 1, 0, 0, 0], float("nan")), ValueError, "finite"),
    (lambda: sym.adjoint(sp.eye(3)), ValueError, r"shape \(4, 4\)"),
    (lambda: sym.adjoint(sp.ones(4, 4)), ValueError, "last row"),
    (lambda: sym.inverse_transform([[1, 2], [3]]), TypeError, "nested list"),
    (lambda: sym.matrix_to_twist(sp.ones(4, 4)), ValueError, "skew-symmetric"),
    (lambda: sym.matrix_to_twist(sym.twist_to_matrix([1, 0, 0, 0, 0, 0]) + sp.Matrix(4, 4, lambda i, j: int(i == 3))),
     ValueError, "zero last row"),
    (lambda: sym.SymbolicChain(sp.ones(3, 6), sp.eye(4)), ValueError, "transposed"),
    (lambda: sym.SymbolicChain(sp.zeros(6, 0), sp.eye(4)), ValueError, "at least one column"),
    (lambda: _one_joint().fk([1, 2]), ValueError, "1 joint variables"),
    (lambda: _one_joint().fk("t"), TypeError, "joint symbols"),
    (lambda: sym.space_jacobian(_one_joint(), [1, 2]), ValueError, "1 joint variables"),
    (lambda: sym.SymbolicChain(sp.Matrix([0, 0, 0, 0, 0, 0]), sp.eye(4)), ValueError, "unit linear part"),
    (lambda: sym.SymbolicChain(np.ones((6, 2)) * (1 + 1j), sp.eye(4)), TypeError, "complex"),
    (lambda: _one_joint().prefix_transforms([1, 2]), ValueError, "1 joint variables"),
    (lambda: _one_joint().joint_transforms("t"), TypeError, "joint symbols"),
    (lambda: sym.link_jacobians(_one_joint(), [1], frame="body"), ValueError, "link_home"),
    (lambda: sym.link_jacobians(_one_joint(), [1], frame="world"), ValueError, "frame"),
    (lambda: sym.jacobian(_one_joint(), [1], frame="analytic"), ValueError, "frame"),
    (lambda: sym.space_jacobian(jac.robots.planar_2r(), [1, 2]), TypeError, "SymbolicChain"),
    (lambda: sym.space_to_body(sp.ones(3, 2), sp.eye(4)), ValueError, r"shape \(6, n\)"),
    (lambda: sym.unskew(sp.ones(3, 3)), ValueError, "skew-symmetric"),
    (lambda: sym.rotation_about("w", 1), ValueError, "axis"),
    (lambda: sym.is_zero("x - x"), TypeError, "sympy expression"),
    (lambda: sym.is_zero(sp.Eq(sp.Symbol("x"), 1)), TypeError, "sympy expression"),
    (lambda: sym.planar_chain(0), ValueError, "at least one joint"),
    (lambda: sym.planar_chain(True), TypeError, "integer"),
    (lambda: sym.planar_chain(2, lengths=[1]), ValueError, "2 link lengths"),
    (lambda: sym.planar_chain(2, lengths=[1, -1]), ValueError, "positive"),
    (lambda: sym.planar_chain(2, lengths="12"), TypeError, "link lengths"),
    (lambda: sym.SymbolicChain.from_numeric("ur5"), TypeError, "SerialChain"),
    (lambda: sym.SymbolicChain(sp.Matrix([0, 0, 1, 0, 0, 0]), sp.eye(4), params="l"), TypeError, "params"),
    (lambda: sym.to_numeric_chain(sym.planar_chain(2)[0]), ValueError, "missing"),
    (lambda: sym.to_numeric_chain(sym.planar_chain(2)[0], [1, 2]), TypeError, "dict"),
    (lambda: sym.to_numeric_chain("arm"), TypeError, "SymbolicChain"),
    (lambda: sym.simplify_matrix(3), TypeError, "sympy Matrix"),
    (lambda: sym.exp_so3([0, 0, 1], sp.Eq(sp.Symbol("x"), 1)), TypeError, "sympy expression"),
])
def test_bad_input_is_refused_clearly(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


# ------------------------------------------------------------------ smaller paths

def test_input_forms_are_accepted():
    t = sp.Symbol("t", real=True)
    S1 = sp.Matrix([0, 0, 1, 0, 0, 0])
    M = sp.eye(4)
    # one joint: a bare symbol, a list, a numpy array of numbers
    one = sym.SymbolicChain(S1, M)
    assert one.fk(t) == one.fk([t])
    assert np.allclose(np.array(one.fk(np.array([0.5])), dtype=float), lie.exp_se3([0, 0, 0.5, 0, 0, 0]))
    # screw axes as a numpy array, transforms as nested lists, rows for vectors
    assert sym.space_jacobian(sym.SymbolicChain(np.array([[0, 0, 1, 0, 0, 0]]).T, M), [t]) == sp.Matrix(S1)
    assert sym.adjoint(np.eye(4, dtype=int).tolist()) == sp.eye(6)
    assert sym.exp_se3(sp.Matrix([[0, 0, 1, 0, 0, 0]]), t) == sym.exp_se3([0, 0, 1, 0, 0, 0], t)
    # a prismatic joint with a symbolic direction is taken as unit
    a = sp.Symbol("a", real=True)
    T = sym.exp_se3([0, 0, 0, sp.cos(a), sp.sin(a), 0], t)
    assert T[:3, 3] == sp.Matrix([t * sp.cos(a), t * sp.sin(a), 0])
    # lambdify with nested symbols, a Matrix of symbols and a single symbol
    arm, th, ls = sym.planar_chain(2)
    f = sym.lambdify_matrix(arm.fk(), [th, sp.Matrix(ls)])
    assert f.symbols == th + ls
    g = sym.lambdify_matrix(sp.Matrix([[t**2]]), t)
    assert np.allclose(g(np.array([1.0, 3.0])), [[[1.0]], [[9.0]]])
    with pytest.raises(TypeError, match="sympy symbols"):
        sym.lambdify_matrix(sp.Matrix([[t]]), [t, 2])
    with pytest.raises(TypeError, match="sequence of sympy symbols"):
        sym.lambdify_matrix(sp.Matrix([[t]]), {t})


def test_symbolic_chain_repr_and_custom_symbols():
    q = sp.symbols("q1 q2", real=True)
    arm = sym.SymbolicChain(sp.Matrix([[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0]]).T, sp.eye(4), thetas=q)
    assert "2 joints" in repr(arm)
    assert arm.thetas == q
    assert sym.space_jacobian(arm)[:, 1].T == sp.Matrix([[0, 0, 0, sp.cos(q[0]), sp.sin(q[0]), 0]])
    assert arm.body_axes == arm.screw_axes  # home = identity


def test_float_axes_are_checked_with_a_tolerance():
    t = sp.Symbol("t", real=True)
    w = np.array([1.0, 2.0, 2.0]) / 3  # unit only up to round-off
    R = sym.exp_so3(list(w), t)
    assert np.allclose(np.array(R.subs(t, 0.7), dtype=float), lie.exp_so3(w * 0.7))
    chain = jac.SerialChain(np.array([[0.6, 0, 0.8, 0, 0, 0], [1e-17, 0, 0, 0.6, 0.8, 0]]).T, np.eye(4))
    arm = sym.SymbolicChain.from_numeric(chain, exact=False)
    assert arm.screw_axes[0, 1] == 0
    theta = np.array([0.4, -0.3])
    f = sym.lambdify_matrix(sym.space_jacobian(arm), arm.thetas)
    assert np.allclose(f(theta), jac.space_jacobian(chain, theta))
    with pytest.raises(ValueError, match="unit"):
        sym.exp_so3([0.6, 0.0, 0.8 + 1e-6], t)


def test_link_homes_of_planar_chain_and_round_trip():
    arm, th, ls = sym.planar_chain(3)
    lengths = [0.8, 1.1, 0.5]
    num = jac.robots.planar(lengths)
    subs = dict(zip(ls, lengths, strict=True))
    assert np.allclose([np.array(H.subs(subs), dtype=float) for H in arm.link_homes], num.link_homes)
    back = sym.to_numeric_chain(arm, subs)
    assert np.allclose(back.link_homes, num.link_homes)
    thetas = _random_thetas(3, 3)
    ref = jac.link_jacobians(num, thetas, frame="geometric")
    for i in (1, 2, 3):
        J_i = sym.link_jacobians(arm, frame="geometric")[i - 1].subs(subs)
        assert np.allclose(sym.lambdify_matrix(J_i, th)(thetas), ref[:, i - 1], atol=1e-12)
    # from_numeric keeps the numeric chain's link frames
    ur5 = jac.robots.ur5()
    assert np.allclose([np.array(H, dtype=float) for H in sym.SymbolicChain.from_numeric(ur5).link_homes],
                       ur5.link_homes)
    with pytest.raises(ValueError, match="3 link home poses"):
        sym.SymbolicChain(arm.screw_axes, arm.home, link_homes=[sp.eye(4)])
    with pytest.raises(TypeError, match="link_homes"):
        sym.SymbolicChain(arm.screw_axes, arm.home, link_homes=sp.eye(4))
    with pytest.raises(ValueError, match="link_home"):
        sym.link_jacobians(sym.SymbolicChain(arm.screw_axes, arm.home), frame="body")


# ------------------------------------------------------------------ one API: the symbolic mirrors the numeric

def _params(f):
    return [p for p in inspect.signature(f).parameters if p != "simplify"]


@pytest.mark.parametrize("name", ["skew", "unskew", "twist_to_matrix", "matrix_to_twist", "make_transform",
                                  "inverse_transform", "adjoint", "ad", "rotation_about"])
def test_lie_functions_have_the_numeric_names_and_arguments(name):
    assert _params(getattr(sym, name)) == _params(getattr(lie, name))


@pytest.mark.parametrize("name", ["space_jacobian", "body_jacobian", "geometric_jacobian", "link_jacobians",
                                  "space_to_body", "body_to_space", "space_to_geometric", "geometric_to_space",
                                  "body_to_geometric", "geometric_to_body"])
def test_jacobian_functions_have_the_numeric_names_and_arguments(name):
    assert _params(getattr(sym, name)) == _params(getattr(jac, name))


def test_jacobian_by_frame_takes_chain_theta_frame_like_the_numeric_one():
    assert _params(sym.jacobian)[:3] == _params(jac.jacobian)[:3] == ["chain", "theta", "frame"]


def test_exponentials_take_axis_then_angle():
    # the one documented difference: sympy cannot split a product omega*theta back into axis and angle
    assert _params(sym.exp_so3) == ["omega", "theta"]
    assert _params(sym.exp_se3) == ["screw", "theta"]


def test_symbolic_chain_is_read_only_like_serial_chain():
    arm, th, ls = sym.planar_chain(2)
    num = jac.robots.planar_2r()
    for attr in ("screw_axes", "body_axes", "home", "link_homes", "dof", "joint_types", "name"):
        assert hasattr(num, attr) and hasattr(arm, attr), attr
    for attr in ("screw_axes", "body_axes", "home", "link_homes", "dof", "joint_types", "thetas", "params"):
        with pytest.raises(AttributeError):
            setattr(arm, attr, None)
    with pytest.raises(TypeError):
        arm.screw_axes[0, 0] = 5  # an immutable matrix
    for method in ("fk", "joint_transforms", "prefix_transforms", "link_poses"):
        assert _params(getattr(arm, method)) == _params(getattr(num, method)) == ["theta"], method
    assert arm.joint_types == num.joint_types == "RR"
    assert arm.thetas == th and arm.params == ls


def test_small_lie_functions_against_numeric():
    V = np.array([0.3, -0.2, 0.5, 1.0, -2.0, 0.7])
    assert np.allclose(np.array(sym.ad(V), dtype=float), lie.ad(V))
    assert np.allclose(np.array(sym.unskew(lie.skew(V[:3])), dtype=float).ravel(), V[:3])
    R, p = lie.exp_so3(V[:3]), V[3:]
    assert np.allclose(np.array(sym.make_transform(R, p), dtype=float), lie.make_transform(R, p))
    for axis in "xyz":
        assert np.allclose(np.array(sym.rotation_about(axis, 0.7), dtype=float), lie.rotation_about(axis, 0.7))


def test_conversions_and_jacobian_by_frame_against_numeric():
    arm = sym.SymbolicChain.from_numeric(jac.robots.spatial_rrp())
    num = jac.robots.spatial_rrp()
    theta = np.array([0.3, -0.8, 0.4])
    T = arm.fk(theta)
    J_s, J_b, J = (sym.jacobian(arm, theta, f) for f in sym.SYMBOLIC_FRAMES)
    num_of = {"space": jac.space_jacobian, "body": jac.body_jacobian, "geometric": jac.geometric_jacobian}
    for f, A in zip(sym.SYMBOLIC_FRAMES, (J_s, J_b, J), strict=True):
        assert np.allclose(np.array(A, dtype=float), num_of[f](num, theta), atol=1e-12), f
    pairs = [(sym.space_to_body(J_s, T), J_b), (sym.body_to_space(J_b, T), J_s),
             (sym.space_to_geometric(J_s, T), J), (sym.geometric_to_space(J, T), J_s),
             (sym.body_to_geometric(J_b, T), J), (sym.geometric_to_body(J, T), J_b)]
    for got, want in pairs:
        assert np.allclose(np.array(got, dtype=float), np.array(want, dtype=float), atol=1e-12)


def test_link_poses_against_numeric():
    arm, th, ls = sym.planar_chain(3)
    lengths = [0.8, 1.1, 0.5]
    num = jac.robots.planar(lengths)
    theta = np.array([0.2, -1.0, 0.6])
    poses = arm.link_poses(theta)
    subs = dict(zip(ls, lengths, strict=True))
    assert np.allclose([np.array(P.subs(subs), dtype=float) for P in poses], num.link_poses(theta))
    prefixes = arm.prefix_transforms(theta)
    assert len(prefixes) == 4 and prefixes[0] == sp.eye(4)
    assert np.allclose([np.array(P.subs(subs), dtype=float) for P in prefixes], num.prefix_transforms(theta))
    assert np.allclose([np.array(E.subs(subs), dtype=float) for E in arm.joint_transforms(theta)],
                       num.joint_transforms(theta))
    with pytest.raises(ValueError, match="link_homes"):
        sym.SymbolicChain(arm.screw_axes, arm.home).link_poses()


def test_is_zero_decides_identities_exactly():
    a, b, l = sp.symbols("a b l", real=True)
    assert sym.is_zero(s(a + b) - s(a) * c(b) - c(a) * s(b))
    assert sym.is_zero(c(2 * a) - 1 + 2 * s(a) ** 2)
    assert sym.is_zero(l * (s(a) ** 2 + c(a) ** 2) / (1 + l**2) - l / (1 + l**2))
    assert not sym.is_zero(sp.sqrt(l**2) - l)  # l real: |l| - l is not zero
    assert not sym.is_zero(s(a) - c(a))
    assert not sym.is_zero(s(a + b) - s(a) - s(b))
    assert sym.is_zero_matrix(sp.Matrix([[0, s(a) ** 2 + c(a) ** 2 - 1]]))
    assert not sym.is_zero_matrix(sp.Matrix([[0, s(a)]]))
    n = sp.Symbol("n", negative=True)  # no probe at positive values: the answer comes from simplify
    assert not sym.is_zero(n + 1 + n**2) and sym.is_zero(sp.sqrt(n**2) + n)
    # the relations between the Jacobians of the 3R arm, decided without simplify_matrix
    arm, th, _ = sym.planar_chain(3)
    T = arm.fk(simplify=False)
    assert sym.is_zero_matrix(sym.body_jacobian(arm, simplify=False) - sym.space_to_body(sym.space_jacobian(arm), T))
