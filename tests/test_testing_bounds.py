"""The derived bounds of jacobians.testing hold on random arms, and reject a value off by a realistic bug.

A bound that is too small fails a right result on some machine; one that is too large accepts a wrong one.
Each helper is checked both ways: over random revolute arms and configurations (a counterexample search),
and against a result carrying a realistic mistake (a gain 5 % off, a first-order term left in a remainder).
"""

import numpy as np

import jacobians as jac
from jacobians import lie, representations
from jacobians.ik import clik
from jacobians.testing import (
    chain_curvature,
    clik_step_tol,
    euler_step_tol,
    random_chain,
    random_theta,
    taylor_tol,
    within,
)


def _revolute_chains(rng, count):
    return [random_chain(rng, dof=int(rng.integers(2, 7)), prismatic_probability=0.0, pitch_probability=0.3)
            for _ in range(count)]


def test_chain_curvature_bounds_every_second_derivative_of_the_tool_point():
    rng = np.random.default_rng(31)
    worst = 0.0
    for chain in _revolute_chains(rng, 30):
        D = chain_curvature(chain)
        p = (lambda c: lambda t: c.fk(t)[:3, 3])(chain)
        for th in random_theta(chain, rng, size=4):
            u = rng.normal(size=chain.dof)
            h = 1e-3
            # the second difference along u is d²p/ds² up to h²/12 max|p''''| (≪ 1e-6 here) and rounding 4e-16/h²
            d2 = (p(th + h * u) - 2 * p(th) + p(th - h * u)) / h**2
            ratio = np.linalg.norm(d2) / (D * np.sum(np.abs(u)) ** 2)
            assert ratio <= 1 + 1e-6
            worst = max(worst, ratio)
    assert worst > 0.2            # not a vacuous bound: some direction comes within a factor 5 of it
    assert chain_curvature(jac.robots.planar_3r(1.0, 0.8, 0.5)) == 2.3


def test_clik_step_tol_holds_on_random_arms_and_rejects_a_wrong_gain():
    rng = np.random.default_rng(32)
    steps = rejected = 0
    # the bound needs J J⁺ = I: a full-row-rank 6×n Jacobian, n = 6 or 7
    for chain in [random_chain(rng, dof=6 + i % 2, prismatic_probability=0.0, pitch_probability=0.3) for i in range(4)]:
        th = random_theta(chain, rng)
        T_d = chain.fk(th)
        for gain, bug in ((20.0, False), (21.0, True)):
            out = clik(chain, th + rng.normal(scale=0.02, size=chain.dof), np.repeat(T_d[None], 25, axis=0),
                       dt=0.01, gain=gain)
            e = out.error_orientation + out.error_position
            ok = True
            for k in range(24):
                J = jac.geometric_jacobian(chain, out.thetas[k])
                if np.linalg.svd(J, compute_uv=False)[-1] < 1e-3:
                    break
                b_o, b_p = clik_step_tol(chain, J, out.thetas[k + 1] - out.thetas[k], out.error_orientation[k], 0.0,
                                         0.2, scale=np.abs(T_d[:3, 3]).max())
                # the right law contracts by 1 - K dt = 0.8; the bug (K = 21) by 0.79
                good = abs(e[k + 1] - 0.8 * e[k]) <= b_o + b_p
                if not bug:
                    assert good, (k, e[k + 1] / e[k])
                    steps += 1
                ok &= good
            rejected += bug and not ok
    assert steps > 50 and rejected >= 2


def test_clik_step_tol_bounds_a_tracking_step_with_feed_forward():
    rng = np.random.default_rng(33)
    ur = jac.robots.ur5()
    for _ in range(3):
        start = random_theta(ur, rng)
        t = np.linspace(0, 1, 101)
        path = ur.fk(start + np.outer(np.sin(2 * t), rng.normal(scale=0.4, size=6)))
        out = clik(ur, start + rng.normal(scale=0.01, size=6), path, dt=0.01, gain=20.0)
        for k in range(100):
            J = jac.geometric_jacobian(ur, out.thetas[k])
            if np.linalg.svd(J, compute_uv=False)[-1] < 1e-2:
                continue
            w = np.linalg.norm(lie.log_so3(path[k + 1, :3, :3] @ path[k, :3, :3].T))
            b_o, b_p = clik_step_tol(ur, J, out.thetas[k + 1] - out.thetas[k], out.error_orientation[k], w, 0.2,
                                     scale=np.abs(path[:, :3, 3]).max())
            assert out.error_orientation[k + 1] <= 0.8 * out.error_orientation[k] + b_o
            assert out.error_position[k + 1] <= 0.8 * out.error_position[k] + b_p


def test_euler_step_tol_holds_near_and_far_from_the_lock_and_rejects_a_wrong_gain():
    ur = jac.robots.ur5()
    rng = np.random.default_rng(34)
    checked = rejected = 0
    for _ in range(6):
        th = random_theta(ur, rng)
        phi0 = representations.coordinates_from_rotation(ur.fk(th)[:3, :3], "zyx")
        if abs(np.cos(phi0[1])) < 0.2 or np.linalg.svd(jac.geometric_jacobian(ur, th), compute_uv=False)[-1] < 0.05:
            continue
        for gain, bug in ((20.0, False), (21.0, True)):
            out = clik(ur, th + 0.01, np.repeat(ur.fk(th)[None], 20, axis=0), dt=0.01, gain=gain, orientation="zyx")
            e = np.linalg.norm(out.error_angles, axis=-1)
            ok = True
            for k in range(19):
                phi = representations.coordinates_from_rotation(ur.fk(out.thetas[k])[:3, :3], "zyx")
                J = jac.geometric_jacobian(ur, out.thetas[k])
                J_A = np.vstack([representations.angular_velocity_to_rate(phi, "zyx") @ J[:3], J[3:]])
                good = abs(e[k + 1] - 0.8 * e[k]) <= euler_step_tol(out.thetas[k + 1] - out.thetas[k],
                                                                    abs(np.cos(phi[1])), J_A)
                if not bug:
                    assert good, k
                    checked += 1
                ok &= good
            rejected += bug and not ok
    assert checked > 30 and rejected >= 2


def _remainder(chain, th, d, J):
    """e -> T(θ + e d) - T(θ) exp(J e d): of order 2 when J is the body Jacobian."""
    T = chain.fk(th)
    return lambda e: chain.fk(th + e * d) - T @ lie.exp_se3(J @ (e * d))


def test_taylor_tol_holds_for_exponential_remainders_and_rejects_a_first_order_term():
    rng = np.random.default_rng(35)
    for chain in _revolute_chains(rng, 10):
        th, d = random_theta(chain, rng), rng.normal(size=chain.dof)
        T = chain.fk(th)
        Jb = jac.body_jacobian(chain, th)
        rem = _remainder(chain, th, d, Jb)
        bound = taylor_tol(rem, 1e-2, scale=np.abs(T).max())
        assert within(rem(1e-2), 4 * rem(5e-3), bound)
        # a Jacobian with one entry 1e-3 off (a slip in one entry's formula) leaves a first-order term h 1e-3 |d_0|
        J_bug = Jb.copy()
        J_bug[0, 0] += 1e-3
        bad = _remainder(chain, th, d, J_bug)
        # at h = 1e-3 (the bound's h³ term shrinks a thousandfold, the bug's h term tenfold) it is outside
        assert within(rem(1e-3), 4 * rem(5e-4), taylor_tol(rem, 1e-3, scale=np.abs(T).max()))
        if abs(d[0]) > 0.1:
            assert not within(bad(1e-3), 4 * bad(5e-4), taylor_tol(bad, 1e-3, scale=np.abs(T).max()))


def test_resolved_rate_tol_covers_a_perturbed_run_and_rejects_a_wrong_step():
    """A run from a start moved by η stays within E (computed with e0 = |η|) of the run shown, on random arms,
    with the pseudo-inverse and with DLS; a run whose steps are 0.2 % long leaves it (a wrong dt or a rate scale)."""
    from jacobians.testing import resolved_rate_tol
    from jacobians.velocity import resolved_rate

    rng = np.random.default_rng(36)
    covered = rejected = tight = 0
    for chain in _revolute_chains(rng, 8):
        dim = 2 if chain.dof == 2 else 3
        th0 = random_theta(chain, rng)
        t = np.linspace(0, 1, 41)
        # a reachable path: the tool point along a smooth joint motion
        path = chain.fk(th0 + np.outer(np.sin(2 * t), rng.normal(scale=0.3, size=chain.dof)))[:, :dim, 3]
        for damping in (0.0, 0.1):
            if damping == 0.0 and dim > chain.dof:
                continue
            method = "pinv" if damping == 0.0 else "dls"
            out = resolved_rate(chain, th0, path, 1 / 40, method=method, damping=max(damping, 1e-3), gain=2.0)
            eta = 1e-10 * rng.normal(size=chain.dof)
            moved = resolved_rate(chain, th0 + eta, path, 1 / 40, method=method, damping=max(damping, 1e-3), gain=2.0)
            E, R = resolved_rate_tol(chain, out.thetas, out.rates, path, 1 / 40, 2.0, damping=damping,
                                     e0=np.linalg.norm(moved.thetas[0] - out.thetas[0]))
            E_m, _ = resolved_rate_tol(chain, moved.thetas, moved.rates, path, 1 / 40, 2.0, damping=damping)
            ok = np.isfinite(E) & np.isfinite(E_m)
            d = np.linalg.norm(moved.thetas - out.thetas, axis=1)
            assert np.all(d[ok] <= E[ok] + E_m[ok])
            dr = np.linalg.norm(moved.rates - out.rates, axis=1)
            assert np.all(dr[ok] <= R[ok] + resolved_rate_tol(chain, moved.thetas, moved.rates, path, 1 / 40, 2.0,
                                                              damping=damping)[1][ok])
            covered += int(ok.sum())
            tight += bool(np.any(E[ok] < 1e3 * np.maximum(d[ok], 1e-300)))
            long_steps = resolved_rate(chain, th0, path, 1.002 / 40, method=method, damping=max(damping, 1e-3),
                                       gain=2.0)
            rejected += bool(np.any(np.linalg.norm(long_steps.thetas - out.thetas, axis=1)[ok] > E[ok]))
    assert covered > 300 and rejected >= 8 and tight >= 8
