r"""The two 3-D live views, importable by the names chapters 4 and 6 use.

Each view is its own folder of :mod:`jacobians.widgets.live`: ``columns_explorer`` (chapter 4: which joints
move which column of :math:`J_s` and :math:`J_b`) and ``gimbal_lock`` (chapter 6: a spherical wrist's ZYX or
ZYZ coordinates, :math:`B(\phi)`, det B, :math:`J_a` next to :math:`J`).
"""

from __future__ import annotations

from .live.columns_explorer import COLUMN_ROBOTS, VIEW_MARGIN, ColumnsExplorer, columns_model, reach_bounds
from .live.gimbal_lock import (
    GIMBAL_LIMIT_DEG,
    NEAR_LOCK,
    REPS,
    WRIST_SINGULAR,
    WRIST_TOOL,
    WRISTS,
    GimbalLock,
    gimbal_model,
)

__all__ = ["ColumnsExplorer", "GimbalLock", "columns_model", "gimbal_model", "reach_bounds", "COLUMN_ROBOTS",
           "VIEW_MARGIN", "WRISTS", "WRIST_TOOL", "REPS", "GIMBAL_LIMIT_DEG", "NEAR_LOCK", "WRIST_SINGULAR"]
