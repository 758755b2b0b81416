r"""``planar_explorer`` (chapters 2 and 5): a planar arm, its Jacobian in the frame chosen, the velocity and
force ellipses, a singularity banner, Play sweeping a joint.

The model: the chain's keys (``S``, ``M``, ``Q``, ``name``, ``reach``), ``theta`` (rad, written back by the
view), ``frame`` (``"space"``, ``"body"``, ``"geometric"``, ``"analytic"``), ``sing_tol``, ``vel_scale``,
``force_scale``, ``force_clip``, ``sweep``.

>>> w = PlanarExplorer(theta=[0.3, 1.2])
>>> w.frame, [round(float(t), 2) for t in w.theta], w.J.shape
('space', [0.3, 1.2], (6, 2))
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ....chain import SerialChain
from ....frames import check_frame
from ....jacobian import analytic_jacobian, jacobian
from ....plotting import arm_reach
from .._base import (
    LIMIT,
    LiveView,
    Shown,
    ViewSpec,
    angles,
    chain_model,
    checked_theta,
    expect,
    expect_table,
    planar_chain,
    text,
    whole,
)

__all__ = ["PlanarExplorer", "planar_model", "PLANAR_FRAMES", "SPEC"]

PLANAR_FRAMES = ("space", "body", "geometric", "analytic")
SING_TOL = 0.08  # x reach: sigma_min(J_v) below this is "near a singularity" in the planar views
VEL_SCALE = 0.35  # drawn metres per m/s


def planar_model(robot: str | SerialChain = "planar_2r", theta: Sequence[float] | None = None,
                 frame: str = "space", sweep: int | None = None) -> dict[str, Any]:
    """The model of ``planar_explorer`` for ``robot`` at ``theta`` (rad).

    >>> m = planar_model("planar_2r", [0.3, 1.2], "body")
    >>> len(m["S"]), len(m["S"][0]), m["theta"], m["frame"], round(m["sing_tol"], 3), m["sweep"]
    (6, 2, [0.3, 1.2], 'body', 0.16, 1)
    """
    name, chain = planar_chain(robot)
    if frame not in PLANAR_FRAMES:
        raise ValueError(f"Expected frame one of {', '.join(PLANAR_FRAMES)}, got {frame!r}")
    n = chain.dof
    sw = n - 1 if sweep is None else sweep
    if not isinstance(sw, int) or not 0 <= sw < n:
        raise ValueError(f"Expected sweep as a joint index 0..{n - 1} (the joint Play turns), got {sweep!r}")
    reach = arm_reach(chain)
    # the default pose is the matplotlib explorer's
    th = checked_theta(theta, [0.5, 1.2, -0.8, 0.4, 0.3][:n], n, name)
    return {**chain_model(chain), "theta": th, "frame": frame, "limit": LIMIT, "sing_tol": SING_TOL * reach,
            "vel_scale": VEL_SCALE, "force_scale": 0.1 * reach ** 2, "force_clip": 1.25 * reach, "sweep": sw}


class PlanarExplorer(LiveView):
    """The live planar arm explorer; ``theta`` and ``frame`` settable, ``J`` from the library.

    ``PlanarExplorer(robot="planar_3r", theta=[...], frame="geometric")``, with
    ``robot`` a name in ``ROBOTS`` or a planar :class:`SerialChain`.
    """

    def __init__(self, robot: str | SerialChain = "planar_2r", theta: Sequence[float] | None = None,
                 frame: str = "space", sweep: int | None = None) -> None:
        _, self.chain = planar_chain(robot)
        super().__init__("planar_explorer", planar_model(self.chain, theta, frame, sweep))

    @property
    def J(self) -> NDArray[np.float64]:
        """The shown Jacobian at the current ``theta``: 6×n, or for ``"analytic"`` 3×n in (x, y, φ)."""
        th = np.asarray(self.theta, dtype=float)
        if self.frame == "analytic":
            return analytic_jacobian(self.chain, th, "zyx")[[3, 4, 0]]
        return jacobian(self.chain, th, check_frame(self.frame))


def check_shown(shown: Shown) -> None:
    """The Jacobian the view shows is the library's (:attr:`PlanarExplorer.J`) at the arm and frame shown."""
    from .... import robots

    robot = {2: "planar_2r", 3: "planar_3r"}[len(shown["theta"])]
    same = np.array_equal(shown["model"]["S"], getattr(robots, robot)().screw_axes)
    expect(same, f"planar_explorer: not the {robot}")
    expect_table(shown, "jl-matrix", PlanarExplorer(robot, theta=shown["theta"], frame=shown["frame"]).J)


SPEC = ViewSpec(name="planar_explorer", model=planar_model, widget=PlanarExplorer,
                options={"robot": text, "theta": angles, "frame": text, "sweep": whole},
                probe=("input.jl-theta", 0.35),
                example={"robot": "planar_3r", "theta": "0.1 0.2 0.3", "frame": "body", "sweep": "0"},
                folder=Path(__file__).resolve().parent, data_keys=frozenset({"frame", "playing", "level"}),
                check=check_shown)
