"""Mutation checks: the library's tests and the chapters' hidden checks must fail when the library is wrong.

Four mutants, each a classic mistake, are patched in with ``monkeypatch``:

* ``jacobian``: space-Jacobian column i uses the product of joints 1..i-2 (forgets the joint just before);
* ``adjoint``: :math:`[\\mathrm{Ad}_T]` with :math:`[p]R^T` in the lower-left block instead of :math:`[p]R`;
* ``exponential``: the translation of :math:`e^{[\\mathcal S]\\theta}` with the sign of its
  :math:`(\\theta - \\sin\\theta)[\\omega]^2v` term flipped (the rotation stays right), in the kernels;
* ``public_exp_se3``: the same mistake in the public ``jacobians.lie.exp_se3`` only (the forward kinematics,
  which has its own kernel, is untouched). A check such as det[Ad_{exp(X)}] = 1 holds for any
  rotation-and-translation, right or wrong, so it cannot catch this one: a chapter must compare the
  exponential itself.

Part 1: each check below is a deterministic copy of an oracle of tests/test_ik.py, test_jacobian_derivative.py,
test_dynamics.py and test_redundancy.py (finite differences, Modern Robotics, Pinocchio). The matrix
``CAUGHT`` lists which check catches which of the first three mutants; a pair not listed is a mutant that does
not change what that check computes (e.g. no adjoint is used by J̇), and each mutant is caught by several checks.

Part 2: chapters 10, 11 and 12 are executed in this process under each mutant (one harness,
:func:`run_until_a_check_fails`): each must stop with an AssertionError, in a hidden check cell (for chapter 12
under the three kernel mutants, in any cell: :data:`VISIBLE_STOP_ALLOWED`).
"""

from pathlib import Path

import numpy as np
import pytest
from fp_bounds import newton_step_bound

import jacobians as jac
from jacobians import _kernels, lie
from jacobians.acceleration import acceleration, jacobian_derivative
from jacobians.dynamics import gravity_torques, potential_energy
from jacobians.ik import ik
from jacobians.redundancy import manipulability_gradient
from jacobians.testing import close, fd2_tol, fd_tol, random_chain, random_theta, within

# ---------------------------------------------------------------- mutants


def _bad_columns(orig):
    def columns(C, Rs, ps):
        Rs2, ps2 = Rs.copy(), ps.copy()
        Rs2[1:] = Rs[:-1]
        ps2[1:] = ps[:-1]
        Rs2[1], ps2[1] = np.eye(3), np.zeros(3)
        out = orig(C, Rs2, ps2)
        out[:, 0] = orig(C, Rs, ps)[:, 0]
        return out
    return columns


def _bad_adjoint(T):
    R = T[..., :3, :3]
    out = np.zeros(T.shape[:-2] + (6, 6))
    out[..., :3, :3] = R
    out[..., 3:, 3:] = R
    out[..., 3:, :3] = lie._skew(T[..., :3, 3]) @ np.swapaxes(R, -1, -2)
    return out


def _bad_exp_stack(C, theta):
    c, s = np.cos(theta), np.sin(theta)
    omc = 1.0 - c
    R = np.eye(3) + s[:, None, None] * C.K + omc[:, None, None] * C.K2
    p = theta[:, None] * C.v + omc[:, None] * C.Kv - (theta - s)[:, None] * C.K2v
    return R, p


def _bad_exp_se3(xi):
    T = _ORIG_EXP(xi)
    w, v = xi[..., :3], xi[..., 3:]
    theta = np.linalg.norm(w, axis=-1)
    _, _, Cc = lie._coefficients(theta)
    K = lie._skew(w)
    T[..., :3, 3] -= 2 * ((Cc[..., None, None] * (K @ K)) @ v[..., None])[..., 0]
    return T


_ORIG_EXP = lie._exp_se3
_PUBLIC_EXP = lie.exp_se3


def _wrong_public_exp_se3(twist_theta):
    xi = np.asarray(twist_theta, dtype=float)
    T = _PUBLIC_EXP(xi)
    w, v = xi[..., :3], xi[..., 3:]
    _, _, C = lie._coefficients(np.linalg.norm(w, axis=-1))
    K = lie._skew(w)
    T[..., :3, 3] -= 2 * ((C[..., None, None] * (K @ K)) @ v[..., None])[..., 0]
    return T


def apply(mutant, mp):
    import jacobians.chain as chain_mod
    import jacobians.ik as ik_mod
    import jacobians.statics as statics_mod

    if mutant == "jacobian":
        mp.setattr(_kernels, "space_columns_single", _bad_columns(_kernels.space_columns_single))
    elif mutant == "adjoint":
        for mod in (lie, chain_mod, ik_mod, statics_mod):
            mp.setattr(mod, "_adjoint", _bad_adjoint)
    elif mutant == "exponential":
        mp.setattr(_kernels, "exp_stack", _bad_exp_stack)
        for mod in (lie, chain_mod):
            mp.setattr(mod, "_exp_se3", _bad_exp_se3)
    elif mutant == "public_exp_se3":
        mp.setattr(lie, "exp_se3", _wrong_public_exp_se3)
    else:  # pragma: no cover
        raise ValueError(mutant)


# ---------------------------------------------------------------- checks (one configuration at a time)

def _chains():
    rng = np.random.default_rng(16)
    return [jac.robots.ur5(), random_chain(rng, dof=5, pitch_probability=0.0, prismatic_probability=0.0),
            random_chain(rng, dof=4, pitch_probability=0.0)], rng


def check_ik_against_modern_robotics():
    mr = pytest.importorskip("modern_robotics")
    ur = jac.robots.ur5()
    rng = np.random.default_rng(0)
    for frame in ("body", "space"):
        for _ in range(4):
            sol = rng.uniform(-np.pi, np.pi, 6)
            T_d, th0 = mr.FKinSpace(ur.home, ur.screw_axes, sol), sol + 0.2 * rng.normal(size=6)
            axes = ur.body_axes if frame == "body" else ur.screw_axes
            th_mr, ok = (mr.IKinBody if frame == "body" else mr.IKinSpace)(axes, ur.home, T_d, th0, 1e-3, 1e-4)
            out = ik(ur, T_d, th0, frame=frame, eps_omega=1e-3, eps_v=1e-4, max_iterations=20)
            assert bool(out.converged) == ok
            # MR's iteration replayed step by step: from each of its iterates θ the library's one Newton step is
            # MR's next iterate within that step's conditioning (newton_step_bound: the solve's condition number
            # and the logarithm's), never two whole runs compared
            th = th0
            for _ in range(20):
                if frame == "body":
                    V = mr.se3ToVec(mr.MatrixLog6(mr.TransInv(mr.FKinBody(ur.home, axes, th)) @ T_d))
                    J = mr.JacobianBody(axes, th)
                else:
                    T = mr.FKinSpace(ur.home, axes, th)
                    V = mr.Adjoint(T) @ mr.se3ToVec(mr.MatrixLog6(mr.TransInv(T) @ T_d))
                    J = mr.JacobianSpace(axes, th)
                if np.linalg.norm(V[:3]) <= 1e-3 and np.linalg.norm(V[3:]) <= 1e-4:
                    break
                step = np.linalg.pinv(J) @ V
                one = ik(ur, T_d, th, frame=frame, eps_omega=1e-300, eps_v=1e-300, max_iterations=1)
                bound = newton_step_bound(J, V, step, th, max(1.0, float(np.abs(T_d).max())))
                assert np.abs(one.theta - (th + step)).max() <= max(1e-12, bound)
                th = th + step
            assert np.array_equal(th, th_mr)            # the replay is MR's own run


def check_jdot_against_finite_differences():
    chains, rng = _chains()
    for chain in chains:
        th, thd = random_theta(chain, rng), rng.normal(size=chain.dof)
        for frame in ("space", "body", "geometric"):
            h = 1e-6
            fd = (jac.jacobian(chain, th + h * thd, frame) - jac.jacobian(chain, th - h * thd, frame)) / (2 * h)
            # central difference along θ + sθ̇: truncation h²/6·max|J'''| + rounding (fd_tol, from J itself)
            bound = fd_tol(lambda s, chain=chain, th=th, thd=thd, frame=frame: jac.jacobian(chain, th + s[0] * thd, frame),
                           np.zeros(1), h)
            assert within(jacobian_derivative(chain, th, thd, frame), fd, bound)


def check_acceleration_against_fk():
    chains, rng = _chains()
    for chain in chains:
        n = chain.dof
        th, thd, thdd = random_theta(chain, rng), rng.normal(size=n), rng.normal(size=n)
        h = 1e-3
        p = lambda t, th=th, thd=thd, thdd=thdd, chain=chain: chain.fk(th + t * thd + 0.5 * t * t * thdd)[:3, 3]
        # second difference: truncation h²/12·max|p''''| + rounding 4·512·EPS·max|p|/h² (fd2_tol)
        assert within(acceleration(chain, th, thd, thdd)[3:], (p(h) - 2 * p(0.0) + p(-h)) / h**2, fd2_tol(p, 0.0, h))


def check_jdot_against_pinocchio():
    pin = pytest.importorskip("pinocchio")
    from jacobians.interop import SWAP, to_pinocchio_model

    chains, rng = _chains()
    refs = {"space": pin.ReferenceFrame.WORLD, "body": pin.ReferenceFrame.LOCAL,
            "geometric": pin.ReferenceFrame.LOCAL_WORLD_ALIGNED}
    for chain in chains:
        model, fid = to_pinocchio_model(chain)
        data = model.createData()
        q, v = random_theta(chain, rng), rng.normal(size=chain.dof)
        pin.computeJointJacobiansTimeVariation(model, data, q, v)
        pin.updateFramePlacements(model, data)
        for frame, ref in refs.items():
            theirs = SWAP @ np.reshape(pin.getFrameJacobianTimeVariation(model, data, fid, ref), (6, chain.dof))
            assert close(theirs, jacobian_derivative(chain, q, v, frame))     # exact algebra both sides: TOL


def check_gravity_against_potential_energy():
    chains, rng = _chains()
    for chain in chains:
        m, c, g = rng.uniform(0.5, 2, chain.dof), 0.3 * rng.normal(size=(chain.dof, 3)), rng.normal(size=3)
        th = random_theta(chain, rng)
        fd = jac.numerical_jacobian(lambda t, chain=chain, m=m, g=g, c=c: potential_energy(chain, t, m, g, c), th)
        bound = fd_tol(lambda t, chain=chain, m=m, g=g, c=c: potential_energy(chain, t, m, g, c), th)   # FD bound
        assert within(gravity_torques(chain, th, m, g, c), fd, bound)


def check_gravity_against_modern_robotics():
    mr = pytest.importorskip("modern_robotics")
    ur = jac.robots.ur5()
    rng = np.random.default_rng(3)
    m = rng.uniform(0.5, 2, 6)
    F = ur.link_homes
    Mlist = [F[0]] + [np.linalg.inv(F[i - 1]) @ F[i] for i in range(1, 6)] + [np.linalg.inv(F[-1]) @ ur.home]
    Glist = [np.diag([0.01, 0.01, 0.01, mi, mi, mi]) for mi in m]
    for _ in range(3):
        q = random_theta(ur, rng)
        theirs = mr.GravityForces(q, [0, 0, -9.81], Mlist, Glist, ur.screw_axes)
        # sums of terms m_i g · (lever arm): rounding relative to their size, not to τ (close with that scale)
        lever = max(1.0, float(np.abs(ur.link_poses(q)[:, :3, 3]).max()))
        assert close(theirs, gravity_torques(ur, q, m), scale=9.81 * float(m.sum()) * lever)


def check_manipulability_gradient():
    chains, rng = _chains()
    for chain in chains[:2]:
        th = random_theta(chain, rng)
        w = lambda t, chain=chain: jac.analysis.manipulability(jac.geometric_jacobian(chain, t)[3:])
        fd = jac.numerical_jacobian(w, th)
        assert within(manipulability_gradient(chain, th, rows=[3, 4, 5]), fd, fd_tol(w, th))   # FD bound


CHECKS = {f.__name__: f for f in [
    check_ik_against_modern_robotics, check_jdot_against_finite_differences, check_acceleration_against_fk,
    check_jdot_against_pinocchio, check_gravity_against_potential_energy, check_gravity_against_modern_robotics,
    check_manipulability_gradient]}

#: (mutant, check) pairs that must fail. Found by running every pair; a pair left out is one where
#: the mutant leaves the checked computation unchanged (stated in the comment).
CAUGHT = {
    "jacobian": ["check_ik_against_modern_robotics", "check_jdot_against_finite_differences",
                 "check_acceleration_against_fk", "check_jdot_against_pinocchio",
                 "check_gravity_against_potential_energy", "check_gravity_against_modern_robotics",
                 "check_manipulability_gradient"],
    # J̇, the acceleration, gravity and the gradient use no adjoint: only the space-frame IK error does
    # (and the body axes of a chain, which the space-frame kernels do not use).
    "adjoint": ["check_ik_against_modern_robotics"],
    "exponential": ["check_ik_against_modern_robotics", "check_jdot_against_finite_differences",
                    "check_acceleration_against_fk", "check_jdot_against_pinocchio",
                    "check_gravity_against_potential_energy", "check_gravity_against_modern_robotics",
                    "check_manipulability_gradient"],
}


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_checks_pass_on_the_real_library(name):
    CHECKS[name]()


@pytest.mark.parametrize(("mutant", "name"), [(m, c) for m, cs in CAUGHT.items() for c in cs])
def test_checks_fail_on_a_mutant(mutant, name, monkeypatch):
    apply(mutant, monkeypatch)
    with pytest.raises(AssertionError):
        CHECKS[name]()


@pytest.mark.parametrize(("mutant", "name"), [(m, c) for m in CAUGHT for c in sorted(CHECKS) if c not in CAUGHT[m]])
def test_a_mutant_that_does_not_reach_a_check_leaves_it_passing(mutant, name, monkeypatch):
    """The pairs left out of CAUGHT are left out because the mutated function is not used there, not by oversight."""
    apply(mutant, monkeypatch)
    CHECKS[name]()


def test_the_public_exp_se3_mutant_is_wrong_and_the_kernel_untouched():
    rng = np.random.default_rng(0)
    X = rng.normal(size=6)
    assert np.abs(_wrong_public_exp_se3(X) - _PUBLIC_EXP(X)).max() > 1e-2
    assert close(_wrong_public_exp_se3(X)[:3, :3], _PUBLIC_EXP(X)[:3, :3])


# ---------------------------------------------------------------- the chapters' hidden checks

CHAPTERS = Path(__file__).resolve().parent.parent / "chapters"
#: chapter -> what it needs besides the library (reference libraries its hidden checks compare with)
NEEDS = {"10_inverse_kinematics": ("modern_robotics",), "11_redundancy": (),
         "12_jacobian_derivative": ("modern_robotics", "pinocchio")}
#: (chapter, mutant) pairs where any stop counts: under a corrupted kernel chapter 12 need only stop, not
#: necessarily in a hidden cell
VISIBLE_STOP_ALLOWED = {("12_jacobian_derivative", m) for m in CAUGHT}


def run_until_a_check_fails(path: Path) -> tuple[int, bool] | None:
    """Execute the code cells of a chapter in this process; return (index, is a hidden cell) of the first cell
    that raised AssertionError, or None if the chapter ran to its end."""
    import jupytext
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    nb = jupytext.read(path)
    namespace: dict = {}
    printoptions = np.get_printoptions()
    rc = matplotlib.rc_context()  # the page's set-up changes the figure style: keep it to this run
    rc.__enter__()
    try:
        for k, cell in enumerate(c for c in nb.cells if c.cell_type == "code"):
            try:
                exec(compile(cell.source, f"{path.name} code cell {k}", "exec"), namespace)
            except AssertionError:
                return k, "remove-cell" in cell.metadata.get("tags", [])
    finally:
        plt.close("all")
        rc.__exit__(None, None, None)
        np.set_printoptions(**printoptions)
    return None


@pytest.mark.parametrize("mutant", [*sorted(CAUGHT), "public_exp_se3"])
@pytest.mark.parametrize("chapter", sorted(NEEDS))
def test_chapter_fails_on_each_mutant(chapter, mutant, monkeypatch):
    """A hidden check of the chapter raises AssertionError when the library is corrupted (the book build runs
    it clean)."""
    for module in NEEDS[chapter]:
        pytest.importorskip(module)
    apply(mutant, monkeypatch)
    failed = run_until_a_check_fails(CHAPTERS / f"{chapter}.md")
    assert failed is not None, f"chapter {chapter} ran to the end with the {mutant} mutant"
    assert failed[1] or (chapter, mutant) in VISIBLE_STOP_ALLOWED, \
        f"chapter {chapter} stopped in cell {failed[0]}, not a hidden check cell, with the {mutant} mutant"
