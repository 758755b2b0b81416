"""An answer given to ``exercises.check``, as plain JSON data and back, without ``eval``.

The kernel that runs a student's notebook under ``make grade`` encodes each
answer with :func:`encode`; the grader decodes it with :func:`decode` and
grades it itself. Nothing in the data is ever executed by the grader:

* numbers, lists, tuples, dicts and numpy arrays become JSON values (floats as
  their ``repr``, so NaN and infinities survive);
* sympy objects become a tree of node names and arguments, rebuilt from a fixed
  list of sympy classes (anything else comes back as :class:`Opaque`);
* a function becomes its source, with the sources of the functions of the
  notebook it calls, the modules it uses and the numeric constants it reads
  (:class:`CodeAnswer`); only a sandboxed process ever runs it.

>>> import numpy as np
>>> decode(encode(np.array([[1.0, float("nan")], [2.5, -0.0]])))
array([[ 1. ,  nan],
       [ 2.5, -0. ]])
>>> decode(encode([1, (2.0, None), "text"]))
[1, (2.0, None), 'text']
>>> import sympy as sp
>>> t = sp.Symbol("theta1", real=True)
>>> m = decode(encode(sp.Matrix([[sp.sin(t) * 2, sp.pi / 3]])))
>>> m, type(m).__name__, m.free_symbols == {t}
(Matrix([[2*sin(theta1), pi/3]]), 'MutableDenseMatrix', True)
>>> decode(encode(object()))
<an object of type object that could not be collected>
"""

from __future__ import annotations

import builtins
import inspect
import textwrap
import types
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["CodeAnswer", "Opaque", "decode", "encode"]

#: Most entries of an array, nodes of a sympy tree or items of a list kept; bigger answers are Opaque.
MAX_NODES = 200_000
#: Bounds that keep decoding cheap whatever the data (the grader decodes outside any sandbox). Every
#: rational number a sympy tree builds, at any node, has a numerator and denominator of at most
#: MAX_BITS bits, and every rational exponent at most MAX_EXPONENT in numerator and denominator: no answer
#: of this course comes near (the largest exponents are squares and square roots), and with both bounds each
#: arithmetic step that sympy evaluates while rebuilding works on at most MAX_BITS-bit numbers and makes at
#: most MAX_BITS * MAX_EXPONENT bits, a fraction of a millisecond; ``["F", "Pow", [3, 100000000]]`` costs
#: nothing. A tree that breaks a bound decodes to ``Opaque("too large")``.
MAX_BITS = 4096
MAX_EXPONENT = 64
_MAX_TEXT = 20_000

# sympy classes a tree may name: arithmetic, the elementary functions, matrices and arrays.
_SYMPY_FUNCS = ("Add", "Mul", "Pow", "sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "atan2",
                "acot", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "exp", "log", "Abs", "sign", "re", "im",
                "conjugate", "floor", "ceiling", "Max", "Min", "sinc", "Tuple")
_SYMPY_SINGLETONS = ("Pi", "Exp1", "ImaginaryUnit", "Infinity", "NegativeInfinity", "ComplexInfinity", "NaN",
                     "EulerGamma", "GoldenRatio", "Catalan")
_SYMPY_MATRICES = ("MutableDenseMatrix", "ImmutableDenseMatrix", "MutableSparseMatrix", "ImmutableSparseMatrix")
_SYMPY_ARRAYS = ("ImmutableDenseNDimArray", "MutableDenseNDimArray", "ImmutableSparseNDimArray",
                 "MutableSparseNDimArray")


@dataclass
class Opaque:
    """An answer the kernel could not turn into data (its type name is kept for the message)."""

    type_name: str

    def __repr__(self) -> str:
        if self.type_name == "too large":
            return "<an answer too large to grade (see answers.MAX_BITS and MAX_EXPONENT)>"
        return f"<an object of type {self.type_name} that could not be collected>"


@dataclass
class CodeAnswer:
    """A function answer as source code: ``name`` defined by ``source`` after ``imports``, ``helpers`` and
    ``constants`` (name -> encoded value). ``library`` is ``(module, qualname)`` when the answer is a function
    of an installed module rather than code of the notebook."""

    name: str
    source: str | None = None
    helpers: list[str] = field(default_factory=list)
    imports: list[list[str]] = field(default_factory=list)
    constants: dict[str, Any] = field(default_factory=dict)
    library: list[str] | None = None

    def __repr__(self) -> str:
        return f"<function {self.name} (source collected)>"


class _TooBig(Exception):
    pass


# --------------------------------------------------------------------------- encode (runs in the kernel)
def encode(answer: Any) -> dict[str, Any]:
    """``answer`` as JSON-safe data; never raises (what cannot be encoded becomes an ``opaque`` node)."""
    budget = [MAX_NODES]
    try:
        return _enc(answer, budget, 0)
    except (_TooBig, RecursionError):
        return {"t": "opaque", "type": type(answer).__name__[:60]}
    except Exception:  # pragma: no cover - a broken __eq__ or similar in a student's object
        return {"t": "opaque", "type": type(answer).__name__[:60]}


def _spend(budget: list[int], n: int = 1) -> None:
    budget[0] -= n
    if budget[0] < 0:
        raise _TooBig()


def _is_exercise(cls: type) -> bool:
    """Whether ``cls`` is the grading package's Exercise or one of its kinds (found by name along the class's
    bases, without importing the package)."""
    return any(c.__name__ == "Exercise" and (c.__module__ or "").startswith("jacobians.grading")
               for c in getattr(cls, "__mro__", ()))


def _enc(x: Any, budget: list[int], depth: int) -> dict[str, Any]:
    _spend(budget)
    if depth > 40:
        raise _TooBig()
    if x is None:
        return {"t": "none"}
    if isinstance(x, (bool, np.bool_)):
        return {"t": "bool", "v": bool(x)}
    if isinstance(x, (int, np.integer)):
        return {"t": "int", "v": str(int(x))}
    if isinstance(x, (float, np.floating)):
        return {"t": "float", "v": repr(float(x))}
    if isinstance(x, (complex, np.complexfloating)):
        return {"t": "complex", "re": repr(float(x.real)), "im": repr(float(x.imag))}
    if isinstance(x, str):
        return {"t": "str", "v": x[:_MAX_TEXT]}
    if isinstance(x, np.ndarray):
        _spend(budget, int(x.size))
        if x.dtype.kind in "biuf":
            return {"t": "ndarray", "dtype": x.dtype.kind, "shape": list(x.shape),
                    "v": [repr(float(v)) if x.dtype.kind == "f" else str(int(v)) for v in x.ravel().tolist()]}
        if x.dtype.kind == "c":
            return {"t": "ndarray", "dtype": "c", "shape": list(x.shape),
                    "v": [[repr(v.real), repr(v.imag)] for v in x.ravel().tolist()]}
        return {"t": "ndarray", "dtype": "O", "shape": list(x.shape),
                "v": [_enc(v, budget, depth + 1) for v in x.ravel().tolist()]}
    if isinstance(x, (list, tuple)):
        return {"t": "list" if isinstance(x, list) else "tuple", "v": [_enc(v, budget, depth + 1) for v in x]}
    if isinstance(x, dict):
        return {"t": "dict", "v": [[_enc(k, budget, depth + 1), _enc(v, budget, depth + 1)] for k, v in x.items()]}
    module = type(x).__module__ or ""
    if module.startswith("sympy"):
        return _enc_sympy(x, budget)
    if _is_exercise(type(x)) and isinstance(getattr(x, "id", None), str):
        # the notebook's ``exN`` (an exercise of any kind): rebuilt, not copied (see EXERCISE)
        return {"t": "exercise", "id": x.id[:60]}
    if isinstance(x, (types.FunctionType, types.BuiltinFunctionType, types.MethodType)):
        return _enc_function(x, budget)
    return {"t": "opaque", "type": type(x).__name__[:60]}


def _enc_sympy(x: Any, budget: list[int]) -> dict[str, Any]:
    import sympy as sp

    cls = type(x).__name__
    if isinstance(x, sp.MatrixBase):
        return {"t": "sympy-matrix", "cls": cls if cls in _SYMPY_MATRICES else "MutableDenseMatrix",
                "shape": [int(x.rows), int(x.cols)], "v": [_tree(e, budget) for e in x]}
    if isinstance(x, sp.NDimArray):
        return {"t": "sympy-array", "cls": cls if cls in _SYMPY_ARRAYS else "ImmutableDenseNDimArray",
                "shape": [int(n) for n in x.shape], "v": [_tree(e, budget) for e in sp.flatten(x.tolist())]}
    if isinstance(x, sp.Basic):
        return {"t": "sympy", "v": _tree(x, budget)}
    return {"t": "opaque", "type": cls[:60]}


def _tree(e: Any, budget: list[int]) -> list[Any]:
    import sympy as sp

    _spend(budget)
    if not isinstance(e, sp.Basic):
        e = sp.sympify(e, strict=True)  # a Python number inside a matrix
    cls = type(e).__name__
    if isinstance(e, sp.Symbol):
        return ["Symbol", e.name, {k: v for k, v in e.assumptions0.items() if isinstance(v, bool)}]
    if isinstance(e, sp.Integer):
        return ["Integer", str(e.p)]
    if isinstance(e, sp.Rational):
        return ["Rational", str(e.p), str(e.q)]
    if isinstance(e, sp.Float):
        return ["Float", repr(float(e))]
    if cls in _SYMPY_SINGLETONS:
        return ["S", cls]
    if isinstance(e.func, sp.core.function.UndefinedFunction):
        return ["Undefined", str(e.func), [_tree(a, budget) for a in e.args]]
    if cls in _SYMPY_FUNCS:
        return ["F", cls, [_tree(a, budget) for a in e.args]]
    raise _TooBig()  # a sympy class outside the list: the whole answer becomes opaque


def _enc_function(fn: Any, budget: list[int]) -> dict[str, Any]:
    name = str(getattr(fn, "__name__", "function"))[:100]
    module = getattr(fn, "__module__", None) or ""
    qualname = getattr(fn, "__qualname__", name)
    if module not in ("__main__", "builtins", "") and "<" not in qualname:
        return {"t": "function", "name": name, "library": [module, qualname]}
    code = getattr(fn, "__code__", None)
    if code is None:
        return {"t": "opaque", "type": type(fn).__name__}
    out: dict[str, Any] = {"t": "function", "name": name, "source": _source(fn), "helpers": [], "imports": [],
                           "constants": {}}
    seen: set[int] = {id(fn)}
    todo = [fn]
    while todo:
        f = todo.pop()
        g = getattr(f, "__globals__", {})
        for n in sorted(_global_names(f.__code__)):
            if n not in g:
                continue
            v = g[n]
            if isinstance(v, types.ModuleType):
                out["imports"].append(["import", v.__name__, n])
            elif isinstance(v, types.FunctionType) and (v.__module__ == "__main__") and "<" not in v.__qualname__:
                if id(v) not in seen:
                    seen.add(id(v))
                    src = _source(v)
                    if src:
                        out["helpers"].append(src)
                    todo.append(v)
            elif callable(v) and getattr(v, "__module__", None) and "<" not in getattr(v, "__qualname__", "<"):
                out["imports"].append(["from", str(v.__module__), str(v.__qualname__), n])
            elif n not in vars(builtins):
                try:
                    out["constants"][n] = _enc(v, budget, 1)
                except _TooBig:
                    pass
    return out


def _global_names(code: types.CodeType) -> set[str]:
    names = set(code.co_names)
    for c in code.co_consts:
        if isinstance(c, types.CodeType):
            names |= _global_names(c)
    return names


def _source(fn: Any) -> str | None:
    try:
        src = textwrap.dedent(inspect.getsource(fn))
    except (OSError, TypeError):
        return None
    return src[:_MAX_TEXT * 5]


#: How :func:`decode` turns an exercise variable of the notebook (``ex4 = exercises.load("ch01_ex4", ...)``,
#: which a function answer may read, as the book's worked solutions read ``ex4.given``) back into an object:
#: only the sandbox that calls a student's function sets ``load`` (:mod:`course.classroom._callee`), to load
#: the exercise again for the ID being graded. Elsewhere it decodes to an :class:`Opaque`.
_EXERCISE_LOADER: dict[str, Any] = {}


# --------------------------------------------------------------------------- decode (runs in the grader)
def decode(data: Any) -> Any:
    """The answer :func:`encode` gave ``data`` for; malformed data gives an :class:`Opaque`. Never evaluates.

    >>> decode({"t": "sympy", "v": ["F", "Pow", [["Integer", "3"], ["Integer", "100000000"]]]})
    <an answer too large to grade (see answers.MAX_BITS and MAX_EXPONENT)>
    """
    budget = [MAX_NODES]
    try:
        return _dec(data, 0, budget)
    except _TooBig:
        return Opaque("too large")
    except Exception:
        return Opaque("malformed")


def _dec(d: Any, depth: int, budget: list[int]) -> Any:
    _spend(budget)
    if depth > 60 or not isinstance(d, dict):
        raise ValueError("malformed")
    t = d.get("t")
    if t == "none":
        return None
    if t == "bool":
        return bool(d["v"])
    if t == "int":
        return int(str(d["v"])[:400])
    if t == "float":
        return float(str(d["v"]))
    if t == "complex":
        return complex(float(d["re"]), float(d["im"]))
    if t == "str":
        return str(d["v"])
    if t in ("list", "tuple"):
        items = [_dec(v, depth + 1, budget) for v in d["v"]]
        return items if t == "list" else tuple(items)
    if t == "dict":
        return {_dec(k, depth + 1, budget): _dec(v, depth + 1, budget) for k, v in d["v"]}
    if t == "ndarray":
        shape = tuple(int(n) for n in d["shape"])
        _spend(budget, len(d["v"]))
        kind = d["dtype"]
        if kind in "biu":
            return np.array([int(v) for v in d["v"]], dtype=bool if kind == "b" else int).reshape(shape)
        if kind == "f":
            return np.array([float(v) for v in d["v"]], dtype=float).reshape(shape)
        if kind == "c":
            return np.array([complex(float(a), float(b)) for a, b in d["v"]]).reshape(shape)
        arr = np.empty(len(d["v"]), dtype=object)
        for i, v in enumerate(d["v"]):
            arr[i] = _dec(v, depth + 1, budget)
        return arr.reshape(shape)
    if t in ("sympy", "sympy-matrix", "sympy-array"):
        return _dec_sympy(d, budget)
    if t == "function":
        return CodeAnswer(str(d.get("name", "function")), d.get("source"), [str(h) for h in d.get("helpers", [])],
                          [[str(p) for p in i] for i in d.get("imports", [])], dict(d.get("constants", {})),
                          [str(p) for p in d["library"]] if d.get("library") else None)
    if t == "opaque":
        return Opaque(str(d.get("type", "?"))[:60])
    if t == "exercise":
        load = _EXERCISE_LOADER.get("load")
        return load(str(d.get("id"))[:60]) if load else Opaque("Exercise")
    raise ValueError("malformed")


def _dec_sympy(d: dict[str, Any], budget: list[int]) -> Any:
    import sympy as sp

    if d["t"] == "sympy":
        return _untree(d["v"], 0, budget)
    entries = [_untree(e, 0, budget) for e in d["v"]]
    shape = [int(n) for n in d["shape"]]
    if d["t"] == "sympy-matrix":
        cls = getattr(sp.matrices, d["cls"]) if d["cls"] in _SYMPY_MATRICES else sp.Matrix
        return cls(shape[0], shape[1], entries)
    cls = getattr(sp, d["cls"]) if d["cls"] in _SYMPY_ARRAYS else sp.Array
    return cls(entries, tuple(shape))


def _bounded(e: Any) -> Any:
    """``e`` if its numbers are within :data:`MAX_BITS` and its exponent within :data:`MAX_EXPONENT`."""
    import sympy as sp

    if isinstance(e, sp.Rational) and max(abs(e.p).bit_length(), abs(e.q).bit_length()) > MAX_BITS:
        raise _TooBig()
    if isinstance(e, sp.Pow) and isinstance(e.exp, sp.Rational) and max(abs(e.exp.p), e.exp.q) > MAX_EXPONENT:
        raise _TooBig()
    return e


def _untree(node: Any, depth: int, budget: list[int]) -> Any:
    import sympy as sp

    _spend(budget)
    if depth > 200 or not isinstance(node, list) or not node:
        raise ValueError("malformed")
    head = node[0]
    if head == "Symbol":
        assumptions = {str(k): bool(v) for k, v in dict(node[2]).items()}
        try:
            return sp.Symbol(str(node[1]), **assumptions)
        except Exception:  # inconsistent assumptions: the name is what the checker uses
            return sp.Symbol(str(node[1]))
    if head == "Integer":
        return sp.Integer(int(str(node[1])[:400]))
    if head == "Rational":
        return sp.Rational(int(str(node[1])[:400]), int(str(node[2])[:400]))
    if head == "Float":
        return sp.Float(float(str(node[1])))
    if head == "S" and node[1] in _SYMPY_SINGLETONS:
        return getattr(sp.S, str(node[1]))
    if head == "Undefined":
        return sp.Function(str(node[1])[:100])(*[_untree(a, depth + 1, budget) for a in node[2]])
    if head == "F" and node[1] in _SYMPY_FUNCS:
        cls = getattr(sp, str(node[1]))
        args = [_untree(a, depth + 1, budget) for a in node[2]]
        if cls is sp.Pow and len(args) == 2:
            _bounded(sp.Pow(sp.Symbol("x"), args[1], evaluate=False))  # the exponent, before any evaluation
        return _bounded(cls(*args))
    raise ValueError("malformed")
