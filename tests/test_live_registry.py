"""jacobians.widgets.live.VIEWS: every live view is one folder and one spec, and each reader of the spec agrees.

For each registered view: its folder holds ``view.js`` (an ES module with a default ``render``),
``deck.css`` (rules only for live views on a slide) and the spec; the directive builds the spec's
model from no options and from every option of the spec; the JupyterLab widget takes the
spec's options as its keywords and holds the same model; the reader notebook's code names that
widget; the decks' bundle imports the view's module and deck style.
"""

from __future__ import annotations

import inspect
import json
import re

import live_views
import pytest
import reader_notebooks
from tools import build_slides

from jacobians.widgets.live import VIEWS, LiveView, ViewSpec, live_dir, module_source


def test_the_registry_is_the_folders():
    folders = sorted(p.parent.name for p in live_dir().glob("*/__init__.py") if p.parent.name != "__pycache__")
    assert sorted(VIEWS) == folders and len(folders) >= 5
    assert live_views.VIEWS is VIEWS and set(live_views.OPTIONS) == {k for s in VIEWS.values() for k in s.options}


@pytest.mark.parametrize("name", sorted(VIEWS))
def test_a_views_folder_and_spec(name):
    spec = VIEWS[name]
    assert isinstance(spec, ViewSpec) and spec.folder == live_dir() / name
    source = spec.module.read_text(encoding="utf-8")
    assert "export default { render }" in source
    # a view's own relative imports reach the shared modules of the package, and inline for anywidget
    deps = re.findall(r"""from\s*["'](\.\.?/[A-Za-z0-9_]+\.js)["']""", source)
    assert deps and all((spec.folder / d).resolve().is_file() for d in deps)
    assert not re.search(r"""from\s*["']\.\.?/""", module_source(name))
    # its deck style holds rules for a live view on a slide only (nothing that could restyle another slide)
    css = re.sub(r"/\*.*?\*/", "", spec.deck_css.read_text(encoding="utf-8"), flags=re.S)
    selectors = [sel.strip() for block in re.findall(r"([^{}]+)\{[^{}]*\}", css) for sel in block.split(",")]
    assert all(sel.startswith(".reveal .jac-live") for sel in selectors), selectors
    # the directive: the spec's model with no options (when its builder needs none), and with every option it takes
    needs = [p for p in inspect.signature(spec.model).parameters.values() if p.default is inspect.Parameter.empty]
    if not needs:
        model = live_views.model_for(name, {})
        assert model == spec.model() and json.loads(json.dumps(model, allow_nan=False)) == model
    else:
        with pytest.raises(ValueError, match=f"Expected the options? .* for {name}"):
            live_views.model_for(name, {})
    options = dict(spec.example)  # an example text for every option (ViewSpec checks there is one)
    assert live_views.model_for(name, options) == spec.model(**{k: spec.options[k](v) for k, v in options.items()})
    with pytest.raises(ValueError, match=f"Expected options .* for {name}"):
        live_views.model_for(name, {"no_such_option": "1"})
    # the widget: a LiveView of this view, with the spec's options as its keywords, holding the same model
    assert issubclass(spec.widget, LiveView)
    params = inspect.signature(spec.widget).parameters
    assert set(spec.options) <= set(params), (set(spec.options) - set(params))
    w = spec.widget(**{k: spec.options[k](v) for k, v in options.items()})
    assert w.view == name and w._esm == module_source(name)
    assert all(getattr(w, k) == v for k, v in spec.model(**{k: spec.options[k](v) for k, v in options.items()}).items()
               if k not in ("theta",)), name
    # the reader notebook's code shows the view with that widget
    code = reader_notebooks.live_view_code(name, options)
    assert code.startswith(f"from {spec.widget.__module__} import {spec.widget.__name__}\n")
    # the decks' bundle imports its module and its deck style
    bundle = build_slides.live_views_module()
    assert json.dumps(spec.module.as_posix()) in bundle and json.dumps(spec.deck_css.as_posix()) in bundle


def test_a_spec_names_its_own_folder():
    spec = VIEWS["story"]
    with pytest.raises(ValueError, match="in a folder of that name"):
        ViewSpec(name="other", model=spec.model, options=spec.options, widget=spec.widget, probe=spec.probe,
                 example=spec.example, folder=spec.folder)
    with pytest.raises(ValueError, match="an example text for each option"):
        ViewSpec(name="story", model=spec.model, options=spec.options, widget=spec.widget, probe=spec.probe,
                 folder=spec.folder)
    with pytest.raises(ValueError, match="letters, digits and _"):
        ViewSpec(name="../story", model=spec.model, options=spec.options, widget=spec.widget, probe=spec.probe,
                 example=spec.example, folder=spec.folder)
