"""The two 3-D live views for the ``{live-view}`` directive of ``live_views.py``.

* ``columns_explorer`` (chapter 4): the spatial 5R arm; which joints move which
  column of J_s and J_b. Options ``:robot:`` (``spatial_5r``), ``:theta:`` (rad),
  ``:column:`` (the watched column, 1-based).
* ``gimbal_lock`` (chapter 6): a spherical wrist (``zyz_wrist`` or ``zyx_wrist``),
  its ZYX or ZYZ coordinates φ, B(φ), det B, J_a next to J. Options ``:robot:``,
  ``:theta:`` (rad), ``:rep:`` (``zyx`` or ``zyz``).

The models come from the library (:mod:`jacobians.widgets.live_spatial`, where
the JupyterLab widgets ``ColumnsExplorer`` and ``GimbalLock`` build theirs from
the same functions); this module only reads the directive's option texts.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from docutils.parsers.rst import directives

from jacobians.widgets.live_spatial import (  # noqa: F401  (re-exported for the directive and the tests)
    COLUMN_ROBOTS,
    GIMBAL_LIMIT_DEG,
    LIMIT,
    NEAR_LOCK,
    REPS,
    SPATIAL_MODELS,
    SPATIAL_VIEWS,
    WRIST_SINGULAR,
    WRIST_TOOL,
    WRISTS,
    columns_model,
    gimbal_model,
)

SPATIAL_OPTIONS = {"column": directives.unchanged, "rep": directives.unchanged}


def _angles(text: str) -> list[float]:
    try:
        return [float(t) for t in text.replace(",", " ").split()]
    except ValueError as exc:
        raise ValueError(f"Expected :theta: as angles in rad separated by spaces, got {text!r}") from exc


def spatial_model(view: str, options: Mapping[str, Any]) -> dict[str, Any]:
    """The model of ``view`` (one of :data:`SPATIAL_VIEWS`) from the directive's options."""
    theta = _angles(options["theta"]) if "theta" in options else None
    if view == "columns_explorer":
        unknown = set(options) - {"robot", "theta", "column"}
        if unknown:
            raise ValueError(f"Expected options robot, theta, column for columns_explorer, got {sorted(unknown)}")
        text = str(options.get("column", "3")).strip()
        if not text.isdigit():
            raise ValueError(f"Expected :column: as an integer, got {text!r}")
        return SPATIAL_MODELS[view](options.get("robot", "spatial_5r"), theta, int(text))
    if view == "gimbal_lock":
        unknown = set(options) - {"robot", "theta", "rep"}
        if unknown:
            raise ValueError(f"Expected options robot, theta, rep for gimbal_lock, got {sorted(unknown)}")
        return SPATIAL_MODELS[view](options.get("robot", "zyz_wrist"), theta, options.get("rep", "zyx"))
    raise ValueError(f"Expected a 3-D live view one of {', '.join(SPATIAL_VIEWS)}, got {view!r}")
