"""Inside the sandbox: define a student's function from its collected source and call it on request.

Protocol on stdin/stdout, one JSON object a line: first the function's spec
(:class:`course.classroom.answer_data.CodeAnswer` fields, and ``seed``: the ID being graded, for which the
notebook's exercise variables such as ``ex4`` are loaded again), answered by
``{"ready": true}`` or ``{"error": ...}``; then ``{"args": [...]}`` requests,
answered by ``{"ok": value}`` or ``{"raised": [name, message]}``. Run by
:class:`course.classroom.sandbox.SandboxedFunction`, never by the grader itself.
"""

from __future__ import annotations

import importlib
import json
import sys
from typing import Any

from course.classroom import answer_data
from course.classroom.answer_data import decode, encode
from course.classroom.sandbox import GUARD


def _exercise_loader(seed: Any) -> Any:
    """Load an exercise variable of the notebook again, for the ID being graded (the spec's ``seed``)."""
    from course import exercises

    def load(exercise_id: str) -> Any:
        if exercise_id not in exercises.exercise_ids():
            raise ValueError(f"unknown exercise {exercise_id!r}")
        return exercises.load(exercise_id, seed=seed)
    return load


def _build(spec: dict[str, Any]) -> Any:
    if spec.get("library"):
        module, qualname = spec["library"]
        obj: Any = importlib.import_module(module)
        for part in qualname.split("."):
            obj = getattr(obj, part)
        return obj
    if spec.get("seed") is not None:
        answer_data._EXERCISE_LOADER["load"] = _exercise_loader(spec["seed"])
    ns: dict[str, Any] = {"__name__": "__main__"}
    for item in spec.get("imports", []):
        if item[0] == "import":
            ns[item[2]] = importlib.import_module(item[1])
        else:
            obj = importlib.import_module(item[1])
            for part in item[2].split("."):
                obj = getattr(obj, part)
            ns[item[3]] = obj
    for name, value in spec.get("constants", {}).items():
        ns[name] = decode(value)
    for src in spec.get("helpers", []):
        exec(compile(src, "<notebook>", "exec"), ns)  # the student's own code, in the sandbox
    if not spec.get("source"):
        raise RuntimeError("the source of your function could not be collected from the notebook")
    exec(compile(spec["source"], "<notebook>", "exec"), ns)
    name = spec["name"]
    if name == "<lambda>":
        raise RuntimeError("give a function defined with def (a lambda's source cannot be collected)")
    return ns[name]


def _send(obj: dict[str, Any]) -> None:
    sys.stdout.write(json.dumps(obj) + "\n")
    sys.stdout.flush()


def main() -> None:
    exec(compile(GUARD, "<grading sandbox>", "exec"), {})
    spec = json.loads(sys.stdin.readline())
    try:
        fn = _build(spec)
    except BaseException as exc:  # the student's top-level code may raise anything
        _send({"error": f"{type(exc).__name__}: {exc}"[:300]})
        return
    _send({"ready": True})
    for line in sys.stdin:
        args = [decode(a) for a in json.loads(line)["args"]]
        try:
            result = fn(*args)
        except BaseException as exc:
            _send({"raised": [type(exc).__name__, str(exc).splitlines()[0][:200] if str(exc) else ""]})
            continue
        _send({"ok": encode(result)})


if __name__ == "__main__":
    main()
