"""Publish the book with or without the solutions: ``make book SOLUTIONS=0`` leaves every solution out.

The Sphinx setting ``course_solutions`` (default True) is taken from the
environment variable ``COURSE_SOLUTIONS`` when it is set (``0``, ``no`` or
``false`` mean without). When it is false, a transform removes every solution
of sphinx-exercise from the pages: the ``{solution}`` blocks and the gated
``{solution-start}`` ... ``{solution-end}`` ones with all the cells between
them (code, outputs, the checker's verdict), and any block of class
``course-solutions-only`` (text that tells the reader about the solutions). It runs after sphinx-exercise has
gathered each gated solution into one node; sphinx-exercise's own
``hide_solutions`` is not used because it drops only the opening marker of a
gated solution and leaves the solution's cells on the page.

Because the setting is a Sphinx configuration value, changing it makes Sphinx
read every page again (the executed notebooks are reused from the cache).
"""

from __future__ import annotations

import os
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.transforms import SphinxTransform

ENV = "COURSE_SOLUTIONS"
#: class of a block (``:::{container} course-solutions-only``) that speaks of the solutions:
#: it goes with them
ONLY_WITH_SOLUTIONS = "course-solutions-only"


def solutions_wanted(value: str | None) -> bool:
    """Whether ``COURSE_SOLUTIONS=value`` keeps the solutions (unset: yes)."""
    if value is None or value.strip() == "":
        return True
    v = value.strip().lower()
    if v in ("1", "yes", "true", "on"):
        return True
    if v in ("0", "no", "false", "off"):
        return False
    raise ValueError(f"Expected {ENV} to be 1 or 0 (with or without solutions), got {value!r}")


class RemoveSolutions(SphinxTransform):
    """Remove every solution node (after sphinx-exercise's MergeGatedSolutions, priority 10)."""

    default_priority = 900

    def apply(self, **kwargs: Any) -> None:
        if self.config.course_solutions:
            return
        from sphinx_exercise.nodes import (  # type: ignore[import-untyped]
            solution_end_node,
            solution_node,
            solution_start_node,
        )

        for kind in (solution_node, solution_start_node, solution_end_node):
            for node in list(self.document.findall(kind)):
                node.parent.remove(node)
        for node in list(self.document.findall(nodes.container)):  # a cell tagged solution outside a block
            if "tag_solution" in node.get("classes", []):
                node.parent.remove(node)
        for node in list(self.document.findall(nodes.Element)):  # text that speaks of the solutions
            if ONLY_WITH_SOLUTIONS in node.get("classes", []) and node.parent is not None:
                node.parent.remove(node)


def _from_environment(app: Sphinx, config: Config) -> None:
    value = os.environ.get(ENV)
    if value is not None:
        config.course_solutions = solutions_wanted(value)


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_config_value("course_solutions", True, "env", types=[bool])
    app.connect("config-inited", _from_environment)
    app.add_transform(RemoveSolutions)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
