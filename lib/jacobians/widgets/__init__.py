r"""Interactive explorers for the course (ipywidgets 8 + matplotlib), and their static twins.

Two widgets, each a function returning an ``ipywidgets.VBox`` subclass:

* :func:`planar_arm_explorer` (chapters 2 and 5): joint angles and rates, the
  arm with frames {s} and {b}, the tool velocity :math:`\dot p` from
  :math:`J\dot\theta`, a choice of Jacobian shown as a live matrix with its
  formula, velocity and force ellipses, a singularity indicator, a Play button
  that sweeps a joint.
* :func:`resolved_rate_explorer` (chapter 9): a planar arm following a path with
  the pseudo-inverse or damped least squares; joint rates plotted; what happens
  near a singularity.

Live versions: :mod:`jacobians.widgets.live` wraps the book's ES
modules ``lib/jacobians/widgets/static/live/<view>.js`` as anywidgets, the same code the static
book runs without a kernel: :class:`~jacobians.widgets.live.PlanarExplorer`
(``w.theta`` settable, ``w.J`` from the library) and
:class:`~jacobians.widgets.live.ResolvedRate` replace the two matplotlib
classes below in chapters 2, 5 and 9; :class:`~jacobians.widgets.live.LiveView`
hosts any view module by name.

How they draw. The figure is a plain :class:`matplotlib.figure.Figure` on an
Agg canvas (no pyplot, no ipympl). Its fixed parts (axes, ticks, labels,
legend) are drawn once and kept as a bitmap; a change of a control updates the
moving artists with ``set_data`` and draws only those over the kept bitmap
(blitting), then sends the PNG to an ``ipywidgets.Image``. That works in any
Jupyter with a kernel and is easy to test: every widget has a ``set(...)``
method and exposes what it drew.

Which joints change which column of :math:`J_s` and :math:`J_b` (chapter 4)
and the gimbal lock of a wrist's coordinates (chapter 6) are live views in the
browser, no kernel: ``lib/jacobians/widgets/static/live/columns_explorer.js`` and
``lib/jacobians/widgets/static/live/gimbal_lock.js``, mounted by the ``{live-view}`` directive
(models from :mod:`jacobians.widgets.live_spatial`), and in JupyterLab the
anywidgets :class:`~jacobians.widgets.live_spatial.ColumnsExplorer` and
:class:`~jacobians.widgets.live_spatial.GimbalLock` run the same modules.

Static book: each widget has a ``*_animation`` function returning a
:class:`jacobians.plotting.FrameSource` of the same view (its ``explorer`` is
the widget that draws the frames), for :func:`jacobians.plotting.animation_html`.

Which Jacobian a widget shows is a ``frame`` (:mod:`jacobians.frames`).

The numbers come from the library: the ellipses from
:func:`jacobians.analysis.velocity_ellipsoid` and
:func:`jacobians.analysis.force_ellipsoid` (a force semi-axis that is infinite
at a singularity, or too long for the view, is drawn clipped and marked), the
resolved-rate runs from :func:`jacobians.velocity.resolved_rate`.
"""

from ..plotting import PALETTE
from .base import ROW_LABELS, ROW_LABELS_TEX
from .live import LiveView, PlanarExplorer, ResolvedRate
from .path_following import ResolvedRateExplorer, resolved_rate_animation, resolved_rate_explorer
from .planar import (
    FORCE_LABELS,
    JACOBIAN_FORMULAS,
    JACOBIAN_SYMBOLS,
    TWIST_SYMBOLS,
    PlanarArmExplorer,
    planar_arm_explorer,
    planar_arm_explorer_animation,
)

__all__ = [
    "LiveView",
    "PlanarExplorer",
    "ResolvedRate",
    "PlanarArmExplorer",
    "planar_arm_explorer",
    "planar_arm_explorer_animation",
    "ResolvedRateExplorer",
    "resolved_rate_explorer",
    "resolved_rate_animation",
    "PALETTE",
    "JACOBIAN_SYMBOLS",
    "JACOBIAN_FORMULAS",
    "TWIST_SYMBOLS",
    "FORCE_LABELS",
    "ROW_LABELS",
    "ROW_LABELS_TEX",
]
