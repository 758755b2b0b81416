"""Course content: what the book teaches with the library (chapter set-up, exercise definitions).

The machinery that runs it lives in ``jacobians`` (the numeric core and its teaching layer).

The course ships in the same wheel as ``jacobians`` but needs more than numpy:
its exercises grade symbolic answers with sympy, and the chapters' set-up draws
with matplotlib and displays with IPython. Those come with the ``course``
extra (``pip install "jacobians[course]"``, or ``[student]`` for JupyterLab
too). Importing ``course`` without them stops at once with an error that says
so, instead of a bare ``No module named 'sympy'`` from deep inside an exercise.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Iterable

__all__ = ["require"]

#: what ``import course`` needs (the ``course`` extra): the exercise modules import sympy when they load,
#: the chapters' set-up (``course.chapter``) matplotlib and IPython
NEEDS: tuple[str, ...] = ("sympy", "matplotlib", "IPython")


def require(modules: Iterable[str], what: str, extra: str = "course") -> None:
    """Raise ImportError naming the pip extra when one of ``modules`` is not installed.

    >>> require(["json"], "the standard library")
    >>> try:
    ...     require(["no_such_module_xyz"], "the test")
    ... except ImportError as exc:
    ...     print(exc.name, "|", str(exc)[:70])
    no_such_module_xyz | the test needs no_such_module_xyz, which is not installed. Install the
    """
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        raise ImportError(
            f"{what} needs {', '.join(missing)}, which {'is' if len(missing) == 1 else 'are'} not installed. "
            f'Install the course with: pip install "jacobians[{extra}]" (a student: "jacobians[student]"; '
            f'from a checkout: pip install ".[{extra}]")',
            name=missing[0],
        )


require(NEEDS, "The course package (course: exercises and their checker)")
