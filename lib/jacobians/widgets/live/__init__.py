r"""The live views: one folder and one spec each, found here and read by the book, the decks and JupyterLab.

A view is a folder ``<view>/`` of this package holding

* ``view.js``: the ES module (anywidget's ``render({model, el})``), which computes in the browser with no
  kernel, importing the shared modules beside this file (``../kinematics.js``, ``../ui.js``, ...);
* ``deck.css``: its rules on a deck's slide (``.reveal .jac-live[data-view=<view>] ...``);
* ``__init__.py``: the model builder, the JupyterLab widget (a :class:`LiveView` whose properties give the
  library's numbers of what the view shows) and ``SPEC``, a :class:`ViewSpec` naming them with the
  ``{live-view}`` directive's options.

:data:`VIEWS` maps each name to its spec. The ``{live-view}`` directive (``_ext/live_views.py``) builds the
page's model and reads the options from it, the book copies this tree into ``_static/live/``, the decks
bundle every ``view.js`` and ``deck.css`` (``tools/build_slides.py``), and the browser tests walk it.
Adding a view is adding a folder.

The contract every view module follows: ``export default { render }`` where ``render({model, el})`` draws
into ``el`` and returns a cleanup function, and uses only ``model.get(key)``, ``model.set(key, value)``,
``model.save_changes()`` and ``model.on/off("change:<key>", f)``. The model keys (plain JSON) of a chain
view: ``S`` (the 6×n screw axes, columns (ω, v)), ``M`` (the 4×4 home pose), ``Q`` (n×3 points on the
joint axes at home), ``name``, ``reach`` (m), ``theta`` (the n joint values in rad, written back by the
view), and what the view's ``__init__.py`` documents.

:class:`LiveView` hosts ANY ``<view>/view.js`` by name: every model key becomes a synced traitlet.
anywidget loads ``_esm`` from a blob: URL, where a relative import such as ``../kinematics.js`` cannot
resolve, so :func:`module_source` inlines a module's relative imports, recursively, as ``data:`` URL
imports.

>>> sorted(VIEWS)
['columns_explorer', 'gimbal_lock', 'planar_explorer', 'resolved_rate', 'story']
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable
from typing import Any

from ._base import (
    LIMIT,
    ROBOTS,
    VIEWS,
    LiveView,
    ViewSpec,
    angles,
    chain_model,
    checked_theta,
    live_dir,
    module_source,
    number,
    planar_chain,
    text,
    whole,
)


def _discover() -> dict[str, ViewSpec]:
    """Every subfolder of this package with a ``SPEC``, checked: its name, ``view.js`` and ``deck.css``."""
    found: dict[str, ViewSpec] = {}
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name):
        if not info.ispkg:
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        spec = getattr(module, "SPEC", None)
        if not isinstance(spec, ViewSpec):
            raise TypeError(f"Expected {module.__name__}.SPEC as a ViewSpec (a live view's folder), got {spec!r}")
        if spec.name != info.name:
            raise ValueError(f"Expected the spec in {info.name}/ named {info.name!r}, got {spec.name!r}")
        for path in (spec.module, spec.deck_css):
            if not path.is_file():
                raise FileNotFoundError(f"Expected {path.name} in the live view's folder {spec.folder}")
        found[spec.name] = spec
    return found


VIEWS.update(_discover())  # the registry (defined in _base, where LiveView reads it)
#: view name -> function of keyword options returning the view's model
MODELS: dict[str, Callable[..., dict[str, Any]]] = {name: spec.model for name, spec in VIEWS.items()}

# The views' own names, importable from here as before the views had folders.
from .planar_explorer import PLANAR_FRAMES, PlanarExplorer, planar_model  # noqa: E402
from .resolved_rate import PATHS, ResolvedRate, planar_path, resample, resolved_rate_model, start_configuration  # noqa: E402
from .story import STORIES, StoryView, register_story, story_model, story_theta, story_theta_dot, story_times  # noqa: E402

__all__ = ["VIEWS", "MODELS", "ViewSpec", "LiveView", "module_source", "live_dir", "LIMIT", "ROBOTS",
           "angles", "number", "text", "whole", "chain_model", "checked_theta", "planar_chain",
           "PlanarExplorer", "planar_model", "PLANAR_FRAMES",
           "ResolvedRate", "resolved_rate_model", "planar_path", "start_configuration", "resample", "PATHS",
           "StoryView", "story_model", "story_theta", "story_theta_dot", "story_times", "STORIES", "register_story"]
