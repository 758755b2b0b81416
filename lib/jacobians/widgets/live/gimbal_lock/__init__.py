r"""``gimbal_lock`` (chapter 6): a spherical wrist (``zyz_wrist`` or ``zyx_wrist``), its ZYX or ZYZ coordinates
φ, :math:`B(\phi)`, det B, :math:`J_a` next to :math:`J`. :func:`gimbal_model` and the widget
:class:`GimbalLock` (``w.theta``, ``w.wrist``, ``w.rep`` settable; ``w.J``, ``w.Ja``, ``w.B``, ``w.phi``
from the library).

>>> g = GimbalLock(theta=[0.5, 1.0, 0.0], rep="zyx")
>>> g.view, g.wrist, g.J.shape, g.Ja.shape, round(float(g.det_B), 4)
('gimbal_lock', 'zyz_wrist', (6, 3), (6, 3), -0.5403)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .... import representations as _reps
from .... import robots
from ....chain import SerialChain
from ....jacobian import analytic_jacobian, geometric_jacobian, pose_coordinates
from ....plotting.style import COLUMN_COLORS
from .._base import LiveView, Shown, ViewSpec, angles, checked_theta, expect, expect_table, palette, text

__all__ = ["GimbalLock", "gimbal_model", "WRISTS", "WRIST_TOOL", "REPS", "GIMBAL_LIMIT_DEG", "NEAR_LOCK",
           "WRIST_SINGULAR", "SPEC"]

WRIST_TOOL = 0.3  # m, the tool's offset from the wrist centre
WRISTS: dict[str, Callable[[], SerialChain]] = {"zyz_wrist": lambda: robots.zyz_wrist(WRIST_TOOL),
                                                "zyx_wrist": lambda: robots.zyx_wrist(WRIST_TOOL)}
REPS = ("zyx", "zyz")
GIMBAL_LIMIT_DEG = 180.0  # the gimbal view's sliders, degrees
NEAR_LOCK = 0.1  # |det B| below this: "near gimbal lock"
WRIST_SINGULAR = 1e-3  # sigma_min of J's angular rows below this: the wrist itself is singular


def gimbal_model(robot: str = "zyz_wrist", theta: Sequence[float] | None = None, rep: str = "zyx") -> dict[str, Any]:
    """The model of the gimbal-lock view, as ``gimbal_lock/view.js`` reads it.

    Both wrists are in the model (the view switches between them); ``robot`` is
    the one shown first. ``theta`` in rad (default 30°, 60°, 0°).

    >>> m = gimbal_model(theta=[0.5, 1.0, 0.0], rep="zyx")
    >>> m["wrist"], m["rep"], sorted(m["wrists"]), len(m["wrists"]["zyz_wrist"]["S"][0])
    ('zyz_wrist', 'zyx', ['zyx_wrist', 'zyz_wrist'], 3)
    """
    if robot not in WRISTS:
        raise ValueError(f"Expected robot one of {', '.join(WRISTS)}, got {robot!r}")
    if rep not in REPS:
        raise ValueError(f"Expected rep one of {', '.join(REPS)}, got {rep!r}")
    lim = math.radians(GIMBAL_LIMIT_DEG)
    th = checked_theta(theta, [math.radians(30.0), math.radians(60.0), 0.0], 3, robot, lim + 1e-12)
    wrists = {}
    for key, make in WRISTS.items():
        chain = make()
        wrists[key] = {"name": chain.name, "S": chain.screw_axes.tolist(), "M": chain.home.tolist(),
                       "Q": chain.axis_points().tolist()}
    return {
        "wrist": robot,
        "wrists": wrists,
        "theta": th,
        "rep": rep,
        "limit_deg": GIMBAL_LIMIT_DEG,
        "step_deg": 0.5,
        "tool": WRIST_TOOL,
        "near": NEAR_LOCK,
        "wrist_singular": WRIST_SINGULAR,
        "palette": palette(),
        "column_colors": list(COLUMN_COLORS),
    }


class GimbalLock(LiveView):
    """The live gimbal-lock view of chapter 6: ``theta``, ``wrist``, ``rep`` settable; ``J``, ``Ja``, ``B`` computed.

    ``GimbalLock("zyz_wrist", theta=[...], rep="zyx")``, ``theta`` in rad (the
    view's sliders are in degrees). At the lock ``Ja`` is all NaN (the view
    shows "—": J_a does not exist there).
    """

    def __init__(self, robot: str = "zyz_wrist", theta: Sequence[float] | None = None, rep: str = "zyx") -> None:
        model = gimbal_model(robot, theta, rep)
        self.chains = {k: make() for k, make in WRISTS.items()}
        super().__init__("gimbal_lock", model)

    @property
    def chain(self) -> SerialChain:
        """The wrist shown (``wrist`` picks it)."""
        return self.chains[self.wrist]

    def _th(self) -> NDArray[np.float64]:
        return np.asarray(self.theta, dtype=float)

    @property
    def J(self) -> NDArray[np.float64]:
        """The geometric Jacobian J (6×3, rows (ω, v) in {s}) at the current ``theta``."""
        return geometric_jacobian(self.chain, self._th())

    @property
    def phi(self) -> NDArray[np.float64]:
        """The tool orientation's coordinates φ (rad) in ``rep``."""
        return np.asarray(pose_coordinates(self.chain.fk(self._th()), self.rep)[:3])

    @property
    def B(self) -> NDArray[np.float64]:
        """B(φ) with ω_s = B(φ) φ̇."""
        return _reps.rate_to_angular_velocity(self.phi, self.rep)

    @property
    def det_B(self) -> float:
        """det B(φ): 0 at the lock."""
        return float(np.linalg.det(self.B))

    @property
    def Ja(self) -> NDArray[np.float64]:
        """The analytic Jacobian J_a = diag(B⁻¹, I) J (6×3); NaN at the lock, where it does not exist."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return analytic_jacobian(self.chain, self._th(), self.rep, on_singularity="nan")


def check_shown(shown: Shown) -> None:
    """J, B and J_a the view shows are the library's at the wrist, θ and representation shown ("—" in J_a's
    cells at the lock, where it does not exist)."""
    w = GimbalLock(shown["wrist"], theta=shown["theta"], rep=shown["rep"])
    expect_table(shown, "jl-J", w.J)
    expect_table(shown, "jl-B", w.B)
    if np.isnan(w.Ja).any():
        dashes = all(c == "\u2014" for row in shown["tables"]["jl-Ja"] for c in row)
        expect(dashes, "gimbal_lock: J_a shown at the lock")
    else:
        expect_table(shown, "jl-Ja", w.Ja)


SPEC = ViewSpec(name="gimbal_lock", model=gimbal_model, widget=GimbalLock,
                options={"robot": text, "theta": angles, "rep": text},
                probe=("input.jl-theta:nth-of-type(2)", 89),
                example={"robot": "zyx_wrist", "theta": "0.1 1.5 -0.2", "rep": "zyz"},
                folder=Path(__file__).resolve().parent, data_keys=frozenset({"wrist", "rep", "level"}),
                check=check_shown)
