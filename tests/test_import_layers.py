"""The layers show in the imports: ``jacobians`` (numeric core and teaching machinery) never imports
``course`` (the course content); the grading machinery and the exercise definitions import each other
one way only (course.exercises -> jacobians.grading); no import cycle between any two modules."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIB = ROOT / "lib"
PACKAGES = ("jacobians", "course")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(LIB).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for pkg in PACKAGES for p in sorted((LIB / pkg).rglob("*.py"))}


def _imports(name: str, path: Path, known: set[str]) -> set[str]:
    """The modules of ``known`` that ``name`` imports, anywhere in its body (function-level imports too).

    ``from pkg import x`` counts as importing ``pkg.x`` when that is a module, else ``pkg``."""
    is_package = path.name == "__init__.py"
    here = name if is_package else name.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            for a in node.names:
                sub = f"{target}.{a.name}"
                out.add(sub if sub in known else target)
    return {m for m in out if m in known and m != name}


def _graph() -> dict[str, set[str]]:
    mods = _modules()
    return {name: _imports(name, path, set(mods)) for name, path in mods.items()}


def _reaches(graph: dict[str, set[str]], start: str, goal_prefix: str) -> list[str] | None:
    """An import path from ``start`` to a module under ``goal_prefix``, or None."""
    stack, seen = [[start]], {start}
    while stack:
        path = stack.pop()
        for nxt in sorted(graph[path[-1]]):
            if nxt == goal_prefix or nxt.startswith(goal_prefix + "."):
                return [*path, nxt]
            if nxt not in seen:
                seen.add(nxt)
                stack.append([*path, nxt])
    return None


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_import_graph_is_read_correctly():
    graph = _graph()
    assert "jacobians.grading.exercise" in graph and "course.exercises.ch01" in graph
    assert "jacobians.grading.compare" in graph["jacobians.grading.exercise"]
    assert "course.exercises._registry" in graph["course.exercises.ch01"]
    assert "jacobians.grading" in graph["course.exercises._registry"]
    # a cycle and a path are found when there is one
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _reaches({"a": {"b"}, "b": {"c.x"}, "c.x": set()}, "a", "c") == ["a", "b", "c.x"]


def test_jacobians_never_imports_course():
    graph = _graph()
    for name in graph:
        if name.startswith("jacobians"):
            assert _reaches(graph, name, "course") is None, _reaches(graph, name, "course")


def test_exercises_import_grading_and_grading_does_not_import_exercises():
    graph = _graph()
    assert _reaches(graph, "course.exercises", "jacobians.grading") is not None
    for name in graph:
        if name.startswith("jacobians.grading"):
            assert _reaches(graph, name, "course.exercises") is None, name


def test_no_import_cycle_in_jacobians_or_course():
    assert _cycles(_graph()) == []


def test_importing_every_jacobians_module_in_a_fresh_interpreter_loads_nothing_of_course():
    names = sorted(n for n in _modules() if n.startswith("jacobians"))
    code = ("import importlib, sys\n"
            f"for name in {names!r}:\n"
            "    importlib.import_module(name)\n"
            "print(sorted(m for m in sys.modules if m == 'course' or m.startswith('course.')))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "MPLBACKEND": "Agg"}, cwd=ROOT)
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


def test_course_exercises_loads_in_a_fresh_interpreter_and_registers_every_exercise():
    from course import exercises

    code = ("import sys\nfrom course import exercises\n"
            "print(len(exercises.exercise_ids()), 'jacobians.grading' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.split() == [str(len(exercises.exercise_ids())), "True"], out.stderr


# ------------------------------------------------------------------ the numeric core
# The numeric core: the modules that compute. They import numpy, the standard library and
# each other, and nothing of the teaching layer (symbolic, plotting, widgets, grading,
# verified), which may import them. Adapters to other libraries (interop: Pinocchio, the
# Robotics Toolbox; a URDF loader) import those inside the function that needs them, so
# `import jacobians` stays numpy-only.
TEACHING = ("jacobians.symbolic", "jacobians.plotting", "jacobians.widgets", "jacobians.grading",
            "jacobians.verified")
ADAPTERS = {"jacobians.interop", "jacobians.urdf"}


def _core() -> dict[str, Path]:
    return {n: p for n, p in _modules().items()
            if n.startswith("jacobians") and not any(n == t or n.startswith(t + ".") for t in TEACHING)}


def _module_level_imports(path: Path) -> set[str]:
    """Top-level package names imported at module level (not inside a function or class body)."""
    out: set[str] = set()
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and not node.level:
            out.add((node.module or "").split(".")[0])
    return out


def _all_imports(path: Path) -> set[str]:
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and not node.level:
            out.add((node.module or "").split(".")[0])
    return out


def test_the_numeric_core_imports_only_numpy_the_standard_library_and_itself():
    core = _core()
    assert {"jacobians.lie", "jacobians.chain", "jacobians.jacobian", "jacobians.ik", "jacobians.robots"} <= set(core)
    allowed = set(sys.stdlib_module_names) | {"numpy", "jacobians", "__future__"}
    for name, path in core.items():
        extra = _module_level_imports(path) - allowed
        assert not extra, f"{name} imports {sorted(extra)} at module level: the numeric core is numpy-only"
        if name not in ADAPTERS:
            extra = _all_imports(path) - allowed
            assert not extra, f"{name} imports {sorted(extra)}: only the adapters {sorted(ADAPTERS)} may, lazily"


def test_the_numeric_core_never_imports_the_teaching_layer():
    graph = _graph()
    for name in _core():
        for teaching in TEACHING:
            assert _reaches(graph, name, teaching) is None, _reaches(graph, name, teaching)


def test_the_layer_rules_catch_a_violation(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("import numpy as np\nimport sympy\n\ndef f():\n    import matplotlib\n")
    assert _module_level_imports(bad) == {"numpy", "sympy"}
    assert _all_imports(bad) == {"numpy", "sympy", "matplotlib"}
    assert _reaches({"jacobians.lie": {"jacobians.plotting.x"}, "jacobians.plotting.x": set()},
                    "jacobians.lie", "jacobians.plotting") is not None


def test_importing_the_numeric_core_loads_no_heavy_library():
    names = sorted(_core())
    code = ("import importlib, sys\n"
            f"for name in {names!r}:\n"
            "    importlib.import_module(name)\n"
            "heavy = ('sympy', 'matplotlib', 'scipy', 'ipywidgets', 'anywidget', 'IPython', 'pinocchio',\n"
            "         'roboticstoolbox', 'spatialmath', 'yourdfpy')\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy))\n"
            f"print(sorted(m for m in sys.modules if m.startswith({TEACHING!r})))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.split("\n")[:2] == ["[]", "[]"], out.stdout + out.stderr
