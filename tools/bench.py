"""Speed benchmark of the jacobians library (`make bench`). Prints figures and ratios; asserts nothing.

* one configuration of the UR5: jacobians vs modern_robotics.JacobianSpace (goal: >= 5x faster);
* a batch of 10^5 configurations: microseconds per configuration (goal: <= 1 us),
  compared with Pinocchio called from a Python loop.
"""

from __future__ import annotations

import functools
import statistics
import sys
import timeit
from collections.abc import Callable

import numpy as np

import jacobians as jac


def best_of(stmt: Callable[[], object], number: int, repeat: int = 7) -> tuple[float, float]:
    times = timeit.repeat(stmt, number=number, repeat=repeat)
    return min(times) / number, statistics.median(times) / number


def main() -> int:
    import modern_robotics as mr

    ur = jac.robots.ur5()
    rng = np.random.default_rng(0)
    theta = rng.uniform(-np.pi, np.pi, 6)
    S, B = ur.screw_axes.copy(), ur.body_axes.copy()
    assert np.allclose(jac.space_jacobian(ur, theta), mr.JacobianSpace(S, theta))

    print("UR5, one configuration (best / median of 7 runs)")
    rows = []
    for label, ours, theirs in [
        ("space Jacobian", lambda: jac.space_jacobian(ur, theta), lambda: mr.JacobianSpace(S, theta)),
        ("body Jacobian", lambda: jac.body_jacobian(ur, theta), lambda: mr.JacobianBody(B, theta)),
        ("forward kinematics", lambda: ur.fk(theta), lambda: mr.FKinSpace(ur.home, S, theta)),
    ]:
        t_ours, m_ours = best_of(ours, 2000)
        t_mr, m_mr = best_of(theirs, 200)
        rows.append((label, t_ours, t_mr))
        print(f"  {label:20s} jacobians {t_ours * 1e6:7.1f} us (median {m_ours * 1e6:6.1f})   "
              f"modern_robotics {t_mr * 1e6:7.1f} us (median {m_mr * 1e6:6.1f})   "
              f"ratio {t_mr / t_ours:5.1f}x  (goal >= 5x)")

    N = 100_000
    thetas = rng.uniform(-np.pi, np.pi, (N, 6))
    print(f"\nUR5, a batch of {N} configurations in one call (best of 5)")
    for frame in ("space", "body", "geometric"):
        label = f"{frame} Jacobian"
        t, _ = best_of(functools.partial(jac.jacobian, ur, thetas, frame), 1, repeat=5)
        print(f"  {label:20s} {t * 1e3:7.1f} ms   {t / N * 1e6:5.2f} us per configuration  (goal <= 1 us)")
    t_fk, _ = best_of(lambda: ur.fk(thetas), 1, repeat=5)
    print(f"  {'forward kinematics':20s} {t_fk * 1e3:7.1f} ms   {t_fk / N * 1e6:5.2f} us per configuration")

    bench_ik(ur, mr, rng)

    try:
        import pinocchio as pin

        from jacobians.interop import SWAP, to_pinocchio_model
    except ImportError:
        print("\nPinocchio not installed: skipped")
        return 0
    model, fid = to_pinocchio_model(ur)
    data = model.createData()
    qs = thetas[:10_000]

    def pin_loop() -> np.ndarray:
        out = np.empty((len(qs), 6, 6))
        for k, q in enumerate(qs):
            out[k] = pin.computeFrameJacobian(model, data, q, fid, pin.ReferenceFrame.WORLD)
        return out

    got = pin_loop()
    assert np.allclose(SWAP @ got, jac.space_jacobian(ur, qs))
    t_pin, _ = best_of(pin_loop, 1, repeat=3)
    t_ours, _ = best_of(lambda: jac.space_jacobian(ur, thetas), 1, repeat=5)
    per_pin = t_pin / len(qs)
    per_ours = t_ours / N
    print(f"\nPinocchio computeFrameJacobian(WORLD) from a Python loop: {per_pin * 1e6:5.2f} us per configuration")
    print(f"jacobians batched space Jacobian:                        {per_ours * 1e6:5.2f} us per configuration"
          f"   ratio {per_pin / per_ours:4.1f}x  (goal > 1x)")
    return 0


def bench_ik(ur: jac.SerialChain, mr: object, rng: np.random.Generator) -> None:
    """Newton-Raphson IK on the UR5 (body frame, MR's tolerances): solves per second, jacobians vs MR's IKinBody."""
    n_targets = 200
    sol = rng.uniform(-np.pi, np.pi, (n_targets, 6))
    T_d = ur.fk(sol)
    theta0 = sol + rng.normal(scale=0.3, size=(n_targets, 6))
    B = ur.body_axes.copy()
    ik_body = mr.IKinBody  # type: ignore[attr-defined]
    eomg, ev = 1e-3, 1e-4
    t_mr, _ = best_of(lambda: [ik_body(B, ur.home, T_d[k], theta0[k], eomg, ev) for k in range(20)], 1, repeat=3)
    t_one, _ = best_of(lambda: [jac.ik.ik(ur, T_d[k], theta0[k], eps_omega=eomg, eps_v=ev, max_iterations=20)
                                for k in range(20)], 1, repeat=3)
    t_batch, _ = best_of(lambda: jac.ik.ik(ur, T_d, theta0, eps_omega=eomg, eps_v=ev, max_iterations=20), 1, repeat=3)
    print(f"\nUR5 inverse kinematics, Newton-Raphson on the body twist (eomg {eomg}, ev {ev}, 20 iterations at most)")
    print(f"  modern_robotics IKinBody, one at a time  {20 / t_mr:8.0f} solves/s")
    print(f"  jacobians.ik.ik, one at a time            {20 / t_one:8.0f} solves/s   ratio {t_mr / t_one:5.1f}x")
    print(f"  jacobians.ik.ik, {n_targets} targets in one call  {n_targets / t_batch:8.0f} solves/s"
          f"   ratio {(t_mr / 20) / (t_batch / n_targets):5.1f}x")


if __name__ == "__main__":
    sys.exit(main())
