"""Which Jacobian: the one vocabulary for the frame a Jacobian (or a wrench) is taken in.

Every function of the course that lets you choose a Jacobian takes a
parameter named ``frame`` whose value is one of :data:`FRAMES`, checked by
:func:`check_frame` (one error message everywhere):

=============  =====================================================  ===============
``frame``      what :math:`J\\dot\\theta` is                           symbol
=============  =====================================================  ===============
"space"        twist :math:`\\mathcal V_s`, in {s}                      :math:`J_s`
"body"         twist :math:`\\mathcal V_b`, in {b}                      :math:`J_b`
"geometric"    :math:`(\\omega_s, \\dot p)`                              :math:`J`
"analytic"     :math:`(\\dot\\phi, \\dot p)`, :math:`\\phi` minimal coords  :math:`J_a`
=============  =====================================================  ===============

Some functions accept only some frames (a wrench is "space" or "body"; a
link Jacobian has no analytic form here); they pass their subset to
:func:`check_frame`, and the message lists it.

>>> check_frame("body")
'body'
>>> check_frame("world")
Traceback (most recent call last):
...
ValueError: Expected frame 'space', 'body', 'geometric' or 'analytic', got 'world'
>>> check_frame("analytic", TWIST_FRAMES + ("geometric",))
Traceback (most recent call last):
...
ValueError: Expected frame 'space', 'body' or 'geometric', got 'analytic'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal, cast, get_args

__all__ = ["Frame", "FRAMES", "TWIST_FRAMES", "JACOBIAN_SYMBOLS", "check_frame"]

#: The frame a Jacobian is taken in (see the module's table).
Frame = Literal["space", "body", "geometric", "analytic"]

#: Every frame, in the book's order.
FRAMES: tuple[Frame, ...] = cast("tuple[Frame, ...]", get_args(Frame))

#: The frames whose Jacobians map joint rates to twists (and wrenches to torques).
TWIST_FRAMES: tuple[Frame, ...] = ("space", "body")

#: The book's symbol for the Jacobian in each frame (LaTeX).
JACOBIAN_SYMBOLS: dict[str, str] = {"space": "J_s", "body": "J_b", "geometric": "J", "analytic": "J_a"}


def _options(allowed: Sequence[str]) -> str:
    quoted = [repr(a) for a in allowed]
    if len(quoted) == 1:
        return quoted[0]
    return ", ".join(quoted[:-1]) + " or " + quoted[-1]


def check_frame(frame: object, allowed: Sequence[str] = FRAMES) -> Frame:
    """Return ``frame`` if it is one of ``allowed`` (default :data:`FRAMES`), else raise ``ValueError``."""
    if not isinstance(frame, str) or frame not in allowed:
        raise ValueError(f"Expected frame {_options(allowed)}, got {frame!r}")
    return cast(Frame, frame)
