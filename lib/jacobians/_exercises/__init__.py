"""Definitions of the course's exercises; importing this package registers them with
:mod:`jacobians.grading`. One module per group of chapters; each builder takes a
seeded ``numpy.random.Generator`` and returns a :class:`jacobians.grading.Exercise`."""

from . import ch01_03, ch04_06, ch07_09  # noqa: F401
