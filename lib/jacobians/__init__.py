"""jacobians: manipulator Jacobians in the conventions of Modern Robotics.

Twists and every 6-row quantity are angular first, (omega, v); a chain's screw
axes are the columns of a 6 x n array. Importing this package imports numpy
only. The heavier libraries come with the subpackages that use them:
:mod:`jacobians.symbolic` imports sympy, :mod:`jacobians.plotting` matplotlib,
:mod:`jacobians.widgets` matplotlib and ipywidgets; :mod:`jacobians.grading`
imports sympy only to grade a symbolic answer.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r()
>>> J_s = jac.space_jacobian(arm, [0.3, 0.4])
>>> J_b = jac.body_jacobian(arm, [0.3, 0.4])
>>> np.allclose(jac.space_to_body(J_s, arm.fk([0.3, 0.4])), J_b)
True
>>> np.allclose(jac.jacobian(arm, [0.3, 0.4], "body"), J_b)   # the frame as a parameter
True

The submodule :mod:`jacobians.jacobian` is shadowed by the function
``jacobians.jacobian``; import from it by name (``from jacobians.jacobian import
space_to_body``).
"""

from . import (
    acceleration,
    analysis,
    dynamics,
    frames,
    ik,
    interop,
    lie,
    redundancy,
    representations,
    robots,
    statics,
    velocity,
)
from .acceleration import jacobian_derivative
from .chain import SerialChain
from .dynamics import gravity_torques
from .frames import FRAMES, Frame
from .jacobian import (
    analytic_jacobian,
    body_jacobian,
    body_to_geometric,
    body_to_space,
    geometric_jacobian,
    geometric_to_analytic,
    geometric_to_body,
    geometric_to_space,
    jacobian,
    link_jacobians,
    numerical_jacobian,
    pose_coordinates,
    space_jacobian,
    space_to_body,
    space_to_geometric,
)
from .lie import adjoint
from .representations import RepresentationSingularityError

__version__ = "0.1.0"

__all__ = [
    "SerialChain",
    "Frame",
    "FRAMES",
    "jacobian",
    "space_jacobian",
    "body_jacobian",
    "geometric_jacobian",
    "analytic_jacobian",
    "pose_coordinates",
    "space_to_body",
    "body_to_space",
    "body_to_geometric",
    "geometric_to_body",
    "space_to_geometric",
    "geometric_to_space",
    "geometric_to_analytic",
    "link_jacobians",
    "numerical_jacobian",
    "adjoint",
    "RepresentationSingularityError",
    "lie",
    "representations",
    "robots",
    "analysis",
    "frames",
    "interop",
    "statics",
    "velocity",
    "acceleration",
    "dynamics",
    "ik",
    "redundancy",
    "jacobian_derivative",
    "gravity_torques",
]
