r"""Figures and animations for the course (matplotlib).

Every drawing helper returns a small *artist* object that keeps the matplotlib
artists it made and has an ``update(...)`` method that moves them with
``set_data`` / ``set_offsets``; nothing is rebuilt. The widgets of
:mod:`jacobians.widgets` and the animations rely on that.

=====================  =======================================================
module                 job
=====================  =======================================================
``style``              :data:`PALETTE` (Okabe–Ito, semantic keys), :func:`set_style`, :func:`smallest_text_px`
``artists``            frames, arrows, ellipses; :func:`check_planar`, :func:`arm_reach`
``planar``             the planar arm, its Jacobian columns, :func:`planar_arm_animation`
``spatial``            spatial chains on 3-D axes, axis numbers placed clear of each other
``matrices``           :func:`matrix_latex`, :func:`draw_matrix`
``animation``          :class:`FrameSource`, :func:`animation_html` (offline, palette PNG frames)
=====================  =======================================================

Colours come from :data:`PALETTE`, the Okabe–Ito palette, which stays
distinguishable under the common colour-vision deficiencies; its semantic keys
(``"space"``, ``"body"``, ``"velocity"``, ...) keep one meaning across the book.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> import jacobians as jac
>>> from jacobians import plotting
>>> arm = jac.robots.planar_2r()
>>> fig, ax = plt.subplots()
>>> art = plotting.draw_planar_arm(ax, arm, [0.3, 0.5])
>>> art.link_line.get_xydata().shape
(3, 2)
>>> plt.close(fig)
"""

from .animation import FrameSource, animation_html, compact_png
from .artists import (
    EllipseArtist,
    FrameArtist,
    TwistArtist,
    arm_reach,
    check_planar,
    draw_ellipse,
    draw_frame,
    draw_twist,
)
from .matrices import MatrixArtist, draw_matrix, matrix_latex
from .planar import PlanarArmArtist, column_arrows, draw_planar_arm, planar_arm_animation, setup_planar_axes
from .spatial import SpatialChainArtist, draw_spatial_chain, setup_3d_axes
from .style import COLUMN_COLORS, PALETTE, set_style, smallest_text_px

__all__ = [
    "PALETTE",
    "COLUMN_COLORS",
    "set_style",
    "smallest_text_px",
    "check_planar",
    "arm_reach",
    "PlanarArmArtist",
    "setup_planar_axes",
    "draw_planar_arm",
    "column_arrows",
    "planar_arm_animation",
    "FrameSource",
    "animation_html",
    "compact_png",
    "EllipseArtist",
    "draw_ellipse",
    "FrameArtist",
    "draw_frame",
    "TwistArtist",
    "draw_twist",
    "SpatialChainArtist",
    "setup_3d_axes",
    "draw_spatial_chain",
    "matrix_latex",
    "MatrixArtist",
    "draw_matrix",
]
