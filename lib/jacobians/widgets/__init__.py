r"""The live views of the course: one ES module per view, the same code in the book, the decks and JupyterLab.

Each view is a folder ``lib/jacobians/widgets/live/<view>/`` (its module ``view.js``, anywidget's
``render({model, el})``, which computes in the browser with no kernel; its deck style; its model, widget
and spec, registered in :data:`jacobians.widgets.live.VIEWS`):

* ``planar_explorer`` (chapters 2 and 5): a planar arm, its Jacobian in the frame
  chosen, the velocity and force ellipses, a singularity banner, Play sweeping a joint;
* ``resolved_rate`` (chapter 9): a planar arm following a preset or drawn path with the
  pseudo-inverse or damped least squares, its joint rates plotted;
* ``story`` (chapters 1, 3 and 7): a scripted motion with its twists;
* ``columns_explorer`` (chapter 4): which joints change which columns of J_s and J_b;
* ``gimbal_lock`` (chapter 6): a wrist's coordinates and where their Jacobian breaks.

The static book mounts them with the ``{live-view}`` directive (``_ext/live_views.py``), with the models
their specs build. In JupyterLab the
anywidgets :class:`~jacobians.widgets.live.PlanarExplorer`, :class:`~jacobians.widgets.live.ResolvedRate`,
:class:`~jacobians.widgets.live_spatial.ColumnsExplorer` and :class:`~jacobians.widgets.live_spatial.GimbalLock`
run the same modules, and give the library's numbers of what they show (``w.J``, ``w.run``).

The numbers come from the library: the browser tests compare each view's with
:mod:`jacobians` (tests/browser/test_live_*.py), and the JavaScript kinematics
with values the library writes under Node (tests/js/).
"""

from ..plotting import PALETTE
from .live import LiveView, PlanarExplorer, ResolvedRate

__all__ = ["LiveView", "PlanarExplorer", "ResolvedRate", "PALETTE"]
