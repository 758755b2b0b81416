r"""What every live view shares: its spec, the widget that hosts it, its module's text, the arms and options.

A view is a folder ``jacobians/widgets/live/<view>/`` holding ``view.js`` (the ES module,
``export default { render }``), ``deck.css`` (its rules on a slide) and ``__init__.py``, whose
``SPEC`` (:class:`ViewSpec`) names the model builder, the directive's options and the
widget class that gives the library's numbers of what the view shows. The package
(:mod:`jacobians.widgets.live`) finds the folders and registers their specs.
"""

from __future__ import annotations

import base64
import inspect
import math
import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ... import robots
from ...chain import SerialChain
from ...plotting import arm_reach, check_planar
from ...plotting.style import PALETTE

LIMIT = 3.14  # the views' slider range, rad
#: the planar arms a planar view can show by name
ROBOTS: dict[str, Callable[[], SerialChain]] = {"planar_2r": robots.planar_2r, "planar_3r": robots.planar_3r}
HERE = Path(__file__).resolve().parent
#: a relative import of a view module: ``./name.js`` (a shared module beside it) or ``../name.js`` (from a view folder)
_IMPORT = re.compile(r"""(\bfrom\s*|\bimport\s*)(["'])(\.\.?)/([A-Za-z0-9_]+\.js)\2""")
_NAME = re.compile(r"[a-z0-9_]+")


# ---------------------------------------------------------------- options of the {live-view} directive
def angles(text: str) -> list[float]:
    """``:theta:`` as angles in rad separated by spaces (or commas)."""
    try:
        return [float(t) for t in text.replace(",", " ").split()]
    except ValueError as exc:
        raise ValueError(f"Expected :theta: as angles in rad separated by spaces, got {text!r}") from exc


def whole(text: str) -> int:
    """A whole number, such as a joint index."""
    try:
        return int(text)
    except ValueError as exc:
        raise ValueError(f"Expected a whole number, got {text!r}") from exc


def number(text: str) -> float:
    """A number, such as a damping in m."""
    try:
        return float(text)
    except ValueError as exc:
        raise ValueError(f"Expected a number, got {text!r}") from exc


def text(value: str) -> str:
    """A name, such as a robot's, as written."""
    return value.strip()


# ---------------------------------------------------------------- the spec
@dataclass(frozen=True)
class ViewSpec:
    """One live view: what the directive, the JupyterLab widget, the decks and the tests read.

    ``name`` is the view's folder and its ``data-view``; ``model`` builds the view's model (plain JSON)
    from keyword options; ``options`` maps each ``{live-view}`` option to the parser of its text into
    ``model``'s keyword argument; ``widget`` is the :class:`LiveView` subclass whose properties give
    the library's numbers of what the view shows (the library check the browser tests compare with);
    ``probe`` is a slider of the view (a CSS selector) and a value for it: the deck test moves it and
    compares the numbers shown with ``widget``'s; ``example`` gives every option a text the directive
    accepts (the registry's test builds the model from it); ``data_keys`` are the ``data-*`` keys the view
    writes on its host beside those every view writes (``view``, ``ready``, ``theta``); ``check`` is the
    library check of what a mounted view shows (a :data:`Shown`): it raises AssertionError naming what
    differs from the library's numbers (``widget``'s), and the browser tests call it on every view.
    """

    name: str
    model: Callable[..., dict[str, Any]]
    options: Mapping[str, Callable[[str], Any]]
    widget: type
    probe: tuple[str, float]
    example: Mapping[str, str] = field(default_factory=dict)
    folder: Path = field(default=HERE)
    data_keys: frozenset[str] = frozenset()
    check: Callable[[Mapping[str, Any]], None] | None = None

    def __post_init__(self) -> None:
        if not _NAME.fullmatch(self.name):
            raise ValueError(f"Expected a view name of letters, digits and _, got {self.name!r}")
        if self.folder.name != self.name:
            raise ValueError(f"Expected the spec of {self.name!r} in a folder of that name, got {self.folder}")
        if set(self.example) != set(self.options):
            raise ValueError(f"Expected an example text for each option of {self.name} ({', '.join(self.options)}), "
                             f"got {sorted(self.example)}")

    @property
    def module(self) -> Path:
        """The view's ES module (anywidget's ``_esm``; the book's ``_static/live/<view>/view.js``)."""
        return self.folder / "view.js"

    @property
    def deck_css(self) -> Path:
        """The view's rules on a deck's slide (bundled into the decks' ``_static/live/jac-live.css``)."""
        return self.folder / "deck.css"

    def model_from_options(self, options: Mapping[str, str]) -> dict[str, Any]:
        """The model from the directive's option texts (ValueError on an unknown option or a bad value)."""
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            raise ValueError(f"Expected options {', '.join(self.options)} for {self.name}, got {unknown}: "
                             f"options {sorted(options)} do not all apply to {self.name}")
        needed = [k for k, p in inspect.signature(self.model).parameters.items()
                  if p.default is inspect.Parameter.empty and k not in options]
        if needed:
            raise ValueError(f"Expected the option{'s' * (len(needed) > 1)} {', '.join(':' + k + ':' for k in needed)} "
                             f"for {self.name}, got {sorted(options)}")
        return self.model(**{k: self.options[k](v) for k, v in options.items()})


#: view name -> its spec: the one registry of the live views (the package fills it from its folders)
VIEWS: dict[str, ViewSpec] = {}


# ---------------------------------------------------------------- what a mounted view shows
#: What a mounted view shows, as the browser tests read it (``tests/browser/live_data.py``'s ``SHOWN_JS``):
#: ``view``, ``theta`` and the other ``data-*`` keys (``frame``, ``level``, ``step``, ...; None when the view
#: writes none), ``model`` (its ``data-model``), ``state`` (the numbers it drew, ``el.jacLive``), ``tables``
#: (each table's text rows, keyed by its last class: ``jl-space``, ``js-numbers``, ...) and ``text``.
Shown = Mapping[str, Any]


def shown_numbers(rows: Sequence[Sequence[str]]) -> NDArray[np.float64]:
    """A shown table's rows as numbers (the minus sign U+2212 read as '-')."""
    return np.array([[float(c.replace("\u2212", "-")) for c in row] for row in rows], dtype=float)


def expect(ok: bool, what: str) -> None:
    """Raise AssertionError saying ``what`` differs when ``ok`` is false (a view's check)."""
    if not ok:
        raise AssertionError(what)


def expect_table(shown: Shown, table: str, ref: Any, decimals: int = 2) -> None:
    """The table ``table`` shows ``ref`` rounded to ``decimals`` (within half a unit of the last place)."""
    rows = shown["tables"].get(table)
    expect(rows is not None, f"{shown['view']}: no table {table!r} shown (tables {sorted(shown['tables'])})")
    got, want = shown_numbers(rows), np.asarray(ref, dtype=float)
    half = 0.5 * 10.0 ** -decimals + 1e-9
    expect(got.shape == want.shape and float(np.abs(got - want).max()) <= half,
           f"{shown['view']}: table {table} shows {rows}, the library {want.round(decimals + 2).tolist()}")


# ---------------------------------------------------------------- the modules' text
def live_dir() -> Path:
    """The folder of the view modules: ``$JACOBIANS_LIVE_DIR``, else this package's folder.

    The modules ship inside the package (package data, anywidget's layout), so an installed wheel has them;
    the book copies the same tree into ``_static/live``.
    """
    env = os.environ.get("JACOBIANS_LIVE_DIR")
    d = Path(env) if env else HERE
    if not (d / "kinematics.js").is_file():
        raise FileNotFoundError(f"Expected the live view modules (kinematics.js) in {d}: the package was installed "
                                "without its data files (reinstall it) or JACOBIANS_LIVE_DIR names the wrong folder")
    return d


@cache
def _inlined(path: Path, mtime: float) -> str:
    source = path.read_text(encoding="utf-8")

    def sub(m: re.Match[str]) -> str:
        dep = (path.parent / m.group(3) / m.group(4)).resolve()
        if not dep.is_file():
            raise FileNotFoundError(f"{path.name} imports {m.group(3)}/{m.group(4)}, which is not in {dep.parent}")
        code = _inlined(dep, dep.stat().st_mtime)
        url = "data:text/javascript;base64," + base64.b64encode(code.encode("utf-8")).decode("ascii")
        return f"{m.group(1)}{m.group(2)}{url}{m.group(2)}"

    return _IMPORT.sub(sub, source)


def module_source(view: str) -> str:
    """The ES module ``<view>/view.js`` as one self-contained text (relative imports as data: URLs)."""
    if not isinstance(view, str) or not _NAME.fullmatch(view):
        raise ValueError(f"Expected a view name such as 'planar_explorer' (letters, digits, _), got {view!r}")
    path = live_dir() / view / "view.js"
    if not path.is_file():
        views = sorted(p.parent.name for p in live_dir().glob("*/view.js"))
        raise ValueError(f"Expected a view module in {live_dir()}, one of {views}, got {view!r}")
    return _inlined(path, path.stat().st_mtime)


# ---------------------------------------------------------------- what models share
def planar_chain(robot: str | SerialChain) -> tuple[str, SerialChain]:
    """A planar arm by name (``ROBOTS``) or as a chain, and its name."""
    if isinstance(robot, SerialChain):
        return robot.name or "the arm", check_planar(robot, "a planar live view")
    if robot not in ROBOTS:
        raise ValueError(f"Expected robot one of {', '.join(ROBOTS)} or a planar SerialChain, got {robot!r}")
    return robot, ROBOTS[robot]()


def chain_model(chain: SerialChain) -> dict[str, Any]:
    """The keys of a chain view: name, screw axes S, home M, joint axis points Q, reach."""
    return {"name": chain.name, "S": chain.screw_axes.tolist(), "M": chain.home.tolist(),
            "Q": chain.axis_points().tolist(), "reach": arm_reach(chain)}


def checked_theta(theta: Sequence[float] | NDArray[np.float64] | None, default: Sequence[float], n: int, name: str,
                  limit: float = LIMIT) -> list[float]:
    """``theta`` as n finite angles within ±limit rad (``default`` when None)."""
    if theta is None:
        return [float(t) for t in default]
    try:
        th = [float(t) for t in np.asarray(theta, dtype=float).ravel()]
    except (TypeError, ValueError) as exc:
        raise TypeError(f"Expected theta as {n} numbers (rad) for {name}, got {theta!r}") from exc
    if len(th) != n:
        raise ValueError(f"Expected theta with {n} angles (rad) for {name}, got {len(th)}: {list(th)!r}")
    bad = [t for t in th if not math.isfinite(t) or abs(t) > limit]
    if bad:
        raise ValueError(f"Expected theta as finite angles within ±{limit:.4g} rad, got {bad!r}")
    return th


def palette() -> dict[str, str]:
    """The course colours a 3-D view draws with (:data:`jacobians.plotting.style.PALETTE`)."""
    keys = ("space", "body", "link", "joint", "muted", "analytic", "geometric", "singular", "warning", "ok")
    return {k: PALETTE[k] for k in keys if k in PALETTE}


# ---------------------------------------------------------------- the widget
def _anywidget() -> Any:
    try:
        import anywidget
    except ImportError as exc:  # pragma: no cover - anywidget is pinned in requirements.txt
        raise ImportError("Expected anywidget (pip install anywidget==0.11.0) for the live views in Jupyter") from exc
    return anywidget


def _base() -> type:
    return _anywidget().AnyWidget  # type: ignore[no-any-return]


class LiveView(_base()):  # type: ignore[misc]
    """Any ``<view>/view.js`` as a Jupyter widget: ``LiveView("planar_explorer", **options)``.

    Every key of ``model`` (or, with no model, of the registered spec's ``model(**options)``)
    becomes a synced traitlet, read and set as an attribute; the view's
    changes come back to Python. Subclasses add what the library computes.
    """

    def __init__(self, view: str, model: dict[str, Any] | None = None, **options: Any) -> None:
        import traitlets

        if model is None:
            if view not in VIEWS:
                raise ValueError(f"Expected a model for view {view!r} (no builder in MODELS: {sorted(VIEWS)})")
            model = VIEWS[view].model(**options)
        elif options:
            raise TypeError(f"Expected either a model or options for {view!r}, got both ({sorted(options)})")
        if not isinstance(model, dict) or not all(isinstance(k, str) and k.isidentifier() for k in model):
            raise TypeError(f"Expected the model as a dict with identifier keys, got {type(model).__name__}")
        clash = [k for k in model if hasattr(_base(), k)]
        if clash:
            raise ValueError(f"Expected model keys that are not widget attributes, got {clash}")
        self.add_traits(**{k: traitlets.Any().tag(sync=True) for k in model})
        super().__init__(_esm=module_source(view), **model)
        self.view = view
