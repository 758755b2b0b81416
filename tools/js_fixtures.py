"""Values written by the library for the Node tests of the live views' numeric modules.

``python -m tools.js_fixtures OUT.json`` writes, for random chains of the library
(``jacobians.testing.random_chain``, revolute and prismatic joints, 1 to 7 joints) and
the teaching arms, at seeded random configurations: the screw axes, home pose, joint
values, and the library's forward kinematics, space, body and geometric Jacobians,
``exp_se3`` of random twists (large and tiny angles, so both branches of the closed
form are exercised), singular values, and pseudo-inverse and damped least-squares
rates. ``tests/js/kinematics.test.mjs`` (``node --test``) recomputes each with
``kinematics.js`` / ``linalg.js`` and compares, with bounds derived there from the
size of the numbers and the conditioning of each problem.

The file is written fresh by ``make test-js``; nothing of it is committed.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

import jacobians as jac
from jacobians import robots
from jacobians.testing import random_chain, random_theta

SEED = 20261126


def _case(chain: jac.SerialChain, theta: np.ndarray, rng: np.random.Generator) -> dict[str, Any]:
    J_s = jac.space_jacobian(chain, theta)
    J_g = jac.geometric_jacobian(chain, theta)
    V = rng.normal(size=6)
    damping = float(rng.uniform(0.01, 0.5))
    return {
        "name": chain.name or "random",
        "S": chain.screw_axes.tolist(),
        "M": chain.home.tolist(),
        "jointPoints": chain.axis_points().tolist(),
        "theta": theta.tolist(),
        "fk": chain.fk(theta).tolist(),
        "Js": J_s.tolist(),
        "Jb": jac.body_jacobian(chain, theta).tolist(),
        "Jg": J_g.tolist(),
        "jointPositions": chain.joint_positions(theta).tolist(),
        "sigma": jac.analysis.singular_values(J_g).tolist(),
        "V": V.tolist(),
        "damping": damping,
        "pinv": jac.velocity.pinv_rates(J_g, V).tolist(),
        "dls": jac.velocity.dls_rates(J_g, V, damping).tolist(),
    }


def fixtures(n_random: int = 60) -> dict[str, Any]:
    rng = np.random.default_rng(SEED)
    cases = []
    for arm in (robots.planar_2r(), robots.planar_3r(), robots.spatial_5r(), robots.ur5(), robots.scara()):
        for _ in range(4):
            cases.append(_case(arm, random_theta(arm, rng), rng))
    for _ in range(n_random):
        chain = random_chain(rng, dof=int(rng.integers(1, 8)))
        cases.append(_case(chain, random_theta(chain, rng), rng))
    twists = []
    for k in range(40):
        w = rng.normal(size=3)
        w /= np.linalg.norm(w)
        # large angles, then angles around and below the series threshold of lie (1e-4)
        angle = rng.uniform(-np.pi, np.pi) if k < 20 else 10.0 ** rng.uniform(-9, -3)
        xi = np.concatenate([w * angle, rng.normal(size=3)])
        twists.append({"xi": xi.tolist(), "T": jac.lie.exp_se3(xi).tolist()})
    return {"seed": SEED, "cases": cases, "twists": twists}


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("Usage: python -m tools.js_fixtures OUT.json", file=sys.stderr)
        return 2
    out = Path(argv[0])
    out.parent.mkdir(parents=True, exist_ok=True)
    data = fixtures()
    out.write_text(json.dumps(data), encoding="utf-8")
    print(f"js_fixtures: {len(data['cases'])} chains and {len(data['twists'])} twists into {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
