"""Source-level rules every chapter follows, checked without building or running anything.

The chapters are read as notebooks with jupytext and their Markdown cells cut into ``##`` sections
with markdown-it (so a ``##`` inside a code fence is not a heading). The rules:

* every ``##`` section that displays a formula (``$$``, a ``{math}`` block, an amsmath environment)
  or states a prf theorem / proposition / lemma / corollary has a code cell calling
  ``verified.box()`` before the next ``##`` heading, after the section's last ``verified(...)``
  record (a record after it would land in the next section's box); the box cell hides its input
  and is skipped on slides; a page that shows boxes renders Markdown outputs as MyST and creates
  ``verified = Verified()``;
* no code cell prints an old "✓ checked" line;
* every code cell with a ``mystnb: figure:`` option gives both ``name`` and ``caption`` (the name
  ``chNN-fig-...`` in chapter NN), and the text refers to the figure with {numref};
* the first code cell (the page's set-up) is at most 15 lines, imports ``course.chapter`` and has no
  ``try`` / ``except`` (no fallbacks: a check that cannot fail is no check);
* no chapter defines its own copy of a helper the library or ``course.chapter`` provides: no function
  named like a public name of ``jacobians.symbolic``, ``jacobians.lie`` or ``course.chapter``, none
  named ``s_...`` or ``s<library name>`` (``sskew``, ``sadjoint``: the old local sympy helpers), and
  none of the retired copies (``fmt``, ``shorthand``, ``short_trig``, ``is_zero_trig``).
"""

from __future__ import annotations

import ast
import functools
import re
import textwrap
from dataclasses import dataclass, field
from pathlib import Path

import jupytext
import pytest
import yaml
from markdown_it import MarkdownIt

ROOT = Path(__file__).resolve().parent.parent
CHAPTERS = sorted((ROOT / "chapters").glob("*.md"))

_PLAIN_FENCE = re.compile(r"^(?P<f>`{3,}(?!`)|~{3,}(?!~))(?!\s*\{)[^\n]*\n.*?^(?P=f)[ \t]*$", re.M | re.S)
_CODE_SPAN = re.compile(r"(`+)(?!`)[^`\n][^\n]*?(?<!`)\1(?!`)")  # on one line: a fence is not a span
_DISPLAY_MATH = re.compile(
    r"\$\$|^\s*[`:]{3,}\s*\{math\}|^\s*\\begin\{(?:equation|align|alignat|gather|multline|flalign|eqnarray)\*?\}", re.M)
# A displayed question ("V_b = {?} θ̇", the slide that opens a chapter) states nothing to verify.
_QUESTION = re.compile(r"\$\$[^$]*\{\?\}[^$]*\$\$", re.S)
_THEOREM = re.compile(r"\{prf:(theorem|proposition|lemma|corollary)\}")
_BOX = re.compile(r"\bverified\.box\(")
_RECORD = re.compile(r"\bverified\(")
_CHECK_PRINT = re.compile(r"""\bprint\(\s*[rRfFbBuU]{0,2}(?:'{3}|"{3}|'|")\s*\u2713""")
_NUMREF = re.compile(r"\{numref\}`(?:[^`<]*<)?([^`>]+)>?`")
_CREATES_VERIFIED = re.compile(r"^\s*verified\s*=\s*Verified\(\)", re.M)


@dataclass
class Section:
    """One ``##`` section (or, with ``title=None``, the text before the first one)."""

    title: str | None
    line: int
    cells: list = field(default_factory=list)  # ("md", text) or ("code", cell), in page order

    @property
    def markdown(self) -> str:
        return "\n".join(t for kind, t in self.cells if kind == "md")

    @property
    def code(self) -> list:
        return [c for kind, c in self.cells if kind == "code"]

    def __str__(self) -> str:
        return f"## {self.title} (line {self.line})" if self.title is not None else "(before the first ##)"


def _h2_cuts(markdown: str) -> list[tuple[int, str]]:
    """(line in the cell, title) of each top-level ``##`` heading of a Markdown cell."""
    tokens = MarkdownIt("commonmark").parse(markdown)
    return [(tok.map[0], tokens[i + 1].content.strip()) for i, tok in enumerate(tokens)
            if tok.type == "heading_open" and tok.tag == "h2" and tok.level == 0]


def split_sections(text: str) -> list[Section]:
    """The sections of a MyST notebook given as text; the first one (title None) is what precedes any ``##``."""
    raw_lines = text.splitlines()

    def line_of(title: str) -> int:
        for n, raw in enumerate(raw_lines, 1):
            if re.fullmatch(r"##\s+" + re.escape(title) + r"\s*#*\s*", raw.strip()):
                return n
        return 0

    nb = jupytext.reads(text, fmt="md:myst")
    sections = [Section(None, 1)]
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            lines = cell.source.splitlines()
            start = 0
            for at, title in _h2_cuts(cell.source):
                sections[-1].cells.append(("md", "\n".join(lines[start:at])))
                sections.append(Section(title, line_of(title)))
                start = at + 1
            sections[-1].cells.append(("md", "\n".join(lines[start:])))
        elif cell.cell_type == "code":
            sections[-1].cells.append(("code", cell))
    return sections


def _prose(markdown: str) -> str:
    """Markdown without plain code fences and inline code (directive fences such as {math} stay)."""
    return _CODE_SPAN.sub("", _PLAIN_FENCE.sub("", markdown))


def needs_box(section: Section) -> list[str]:
    """Why the section must end with a 'Verified by code' box (empty: it need not)."""
    prose = _prose(section.markdown)
    why = []
    if _DISPLAY_MATH.search(_QUESTION.sub('', prose)):
        why.append("display math")
    why += [f"a prf {kind}" for kind in dict.fromkeys(_THEOREM.findall(prose))]
    return why


def box_problems(sections: list[Section]) -> list[str]:
    """Every section that needs a box and has none, or has records after its last box."""
    problems = []
    for sec in sections:
        code = sec.code
        boxes = [i for i, c in enumerate(code) if _BOX.search(c.source)]
        records = [i for i, c in enumerate(code) if _RECORD.search(_BOX.sub("", c.source))]
        why = needs_box(sec)
        if sec.title is not None and why and not boxes:
            problems.append(f"{sec}: has {', '.join(why)} but no code cell calling verified.box()")
        late = [i for i in records if not boxes or i > boxes[-1]]
        if late:
            problems.append(f"{sec}: {len(late)} verified(...) record(s) after the section's last verified.box(), "
                            "or with no box at all (they would show in the next section's box)")
    return problems


def _ids(paths):
    return [p.name for p in paths]


# ------------------------------------------------------------------ the parser itself

SAMPLE = """---
jupytext:
  text_representation:
    extension: .md
    format_name: myst
    format_version: 0.13
kernelspec:
  display_name: Python 3
  language: python
  name: python3
---

# Title

Intro with $$x = 1$$ before any section.

## A formula and its box

$$J = \\partial f/\\partial\\theta$$

```{code-cell} ipython3
verified("$J$", "sympy")
```

```{code-cell} ipython3
verified.box()
```

## A theorem without a box

```{prf:theorem} Something
:label: th
It holds.
```

```python
## not a heading: inside a code fence, and `$$` here is code
```

## A proposition in a four-backtick fence

````{prf:proposition} Nested
:label: pr
```{math}
x = y
```
````

```{code-cell} ipython3
verified.box()
```

## Prose only, with `$$` in inline code

Nothing displayed.

## A box, then a record too late

$$a = b$$

```{code-cell} ipython3
verified.box()
```

```{code-cell} ipython3
verified("$a = b$", "late")
```

### A subsection is part of its section

$$c = d$$
"""


def test_the_section_parser_finds_what_it_should():
    sections = split_sections(SAMPLE)
    assert [s.title for s in sections] == [None, "A formula and its box", "A theorem without a box",
                                           "A proposition in a four-backtick fence",
                                           "Prose only, with `$$` in inline code", "A box, then a record too late"]
    assert [needs_box(s) for s in sections[1:]] == [["display math"], ["a prf theorem"],
                                                    ["display math", "a prf proposition"], [], ["display math"]]
    assert [len(s.code) for s in sections] == [0, 2, 0, 1, 0, 2]
    problems = box_problems(sections)
    assert len(problems) == 2, problems
    assert problems[0].startswith("## A theorem without a box (line ") and "a prf theorem" in problems[0]
    assert problems[1].startswith("## A box, then a record too late") and "after the section's last" in problems[1]
    # the same page with the late record moved above the box, and a box for the theorem: no problem left
    fixed = SAMPLE.replace("It holds.\n```\n", "It holds.\n```\n\n```{code-cell} ipython3\nverified.box()\n```\n")
    fixed = fixed.replace('```{code-cell} ipython3\nverified.box()\n```\n\n```{code-cell} ipython3\n'
                          'verified("$a = b$", "late")\n```', '```{code-cell} ipython3\nverified("$a = b$", "late")\n'
                          '```\n\n```{code-cell} ipython3\nverified.box()\n```')
    assert fixed != SAMPLE and box_problems(split_sections(fixed)) == []


def test_the_check_print_and_numref_patterns():
    assert _CHECK_PRINT.search('print("\u2713 checked: x")') and _CHECK_PRINT.search("print(f'\u2713 {n} agree')")
    assert not _CHECK_PRINT.search('print("checked")') and not _CHECK_PRINT.search('verified("\u2713", "x")')
    assert _NUMREF.findall("see {numref}`ch02-fig-arm` and {numref}`Figure %s <ch02-fig-b>`") == [
        "ch02-fig-arm", "ch02-fig-b"]


def test_there_are_chapters():
    assert len(CHAPTERS) >= 9 and all(p.suffix == ".md" for p in CHAPTERS)


# ------------------------------------------------------------------ the rules, per chapter

@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_every_section_with_a_formula_or_theorem_ends_with_a_verified_box(path):
    problems = box_problems(split_sections(path.read_text(encoding="utf-8")))
    assert not problems, f"{path.name}:\n  " + "\n  ".join(problems)


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_box_cells_hide_their_input_and_pages_with_boxes_are_set_up(path):
    text = path.read_text(encoding="utf-8")
    nb = jupytext.reads(text, fmt="md:myst")
    boxes = [c for c in nb.cells if c.cell_type == "code" and _BOX.search(c.source)]
    if not boxes:
        return
    problems = []
    for c in boxes:
        tags = c.metadata.get("tags", [])
        if "remove-input" not in tags and "remove-cell" not in tags:
            problems.append(f"box cell {c.source.strip()[:40]!r} does not have the tag remove-input")
        if "remove-cell" in tags:
            problems.append(f"box cell {c.source.strip()[:40]!r} is tagged remove-cell: the box would never show")
        if c.metadata.get("slideshow", {}).get("slide_type") != "skip":
            problems.append(f"box cell {c.source.strip()[:40]!r} is not slide_type: skip")
    front = yaml.safe_load(text.split("---", 2)[1]) if text.startswith("---") else {}
    if (front.get("mystnb") or {}).get("render_markdown_format") != "myst":
        problems.append("front matter lacks `mystnb: render_markdown_format: myst` (the boxes would show as raw text)")
    if not any(_CREATES_VERIFIED.search(c.source) for c in nb.cells if c.cell_type == "code"):
        problems.append("no set-up cell creates `verified = Verified()`")
    assert not problems, f"{path.name}:\n  " + "\n  ".join(problems)


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_no_check_printout(path):
    nb = jupytext.reads(path.read_text(encoding="utf-8"), fmt="md:myst")
    found = [line.strip()[:90] for c in nb.cells if c.cell_type == "code"
             for line in c.source.splitlines() if _CHECK_PRINT.search(line)]
    assert not found, f"{path.name}: {len(found)} print(\"\u2713 ...\") line(s) left (record with verified(...)):\n  " + \
        "\n  ".join(found)


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_every_figure_cell_has_a_name_and_a_caption_and_is_referenced(path):
    text = path.read_text(encoding="utf-8")
    nb = jupytext.reads(text, fmt="md:myst")
    number = re.match(r"(\d\d)_", path.name)
    refs = set(_NUMREF.findall("\n".join(c.source for c in nb.cells if c.cell_type == "markdown")))
    problems = []
    for c in nb.cells:
        if c.cell_type != "code" or "figure" not in (c.metadata.get("mystnb") or {}):
            continue
        fig = c.metadata["mystnb"]["figure"] or {}
        name, caption = fig.get("name"), fig.get("caption")
        where = (c.source.strip().splitlines() or [""])[0][:50]
        if not (isinstance(name, str) and name.strip()):
            problems.append(f"figure cell {where!r}: no name")
        elif number and not re.fullmatch(rf"ch{number.group(1)}-fig-[a-z0-9-]+", name):
            problems.append(f"figure {name!r}: the name should read ch{number.group(1)}-fig-<short-name>")
        elif name not in refs:
            problems.append(f"figure {name!r}: the text never refers to it with {{numref}}`{name}`")
        if not (isinstance(caption, str) and caption.strip()):
            problems.append(f"figure cell {where!r} ({name}): no caption")
    assert not problems, f"{path.name}:\n  " + "\n  ".join(problems)


# ------------------------------------------------------------------ set-up cells and helpers

SETUP_MAX_LINES = 15
_RETIRED = {"fmt", "shorthand", "short_trig", "is_zero_trig", "sinv"}
_DEFINES = re.compile(r"^[ \t]*(?:def[ \t]+(\w+)[ \t]*\(|(\w+)[ \t]*=[ \t]*lambda\b)", re.M)
_TRY = re.compile(r"^[ \t]*(?:try[ \t]*:|except\b)", re.M)


def _provided_names() -> set[str]:
    import course.chapter
    from jacobians import lie, symbolic

    return {n for mod in (symbolic, lie, course.chapter) for n in getattr(mod, "__all__", ()) if n[0].islower()}


def helper_copies(source: str, provided: set[str]) -> list[str]:
    """Names of the functions a code cell defines that copy a provided helper (see the module doc)."""
    found = []
    for m in _DEFINES.finditer(source):
        name = m.group(1) or m.group(2)
        base = name[2:] if name.startswith("s_") else name[1:] if name.startswith("s") else None
        if name in provided or name in _RETIRED or name.startswith("s_") or (base is not None and base in provided):
            found.append(name)
    return found


def setup_problems(first_cell: str) -> list[str]:
    """What is wrong with a page's set-up cell."""
    problems = []
    n = len(first_cell.strip("\n").splitlines())
    if n > SETUP_MAX_LINES:
        problems.append(f"the set-up cell has {n} lines (at most {SETUP_MAX_LINES}: import course.chapter)")
    if _TRY.search(first_cell):
        problems.append("the set-up cell has a try/except (no fallbacks: the library is always there)")
    if not re.search(r"^from course\.chapter import\b", first_cell, re.M):
        problems.append("the set-up cell does not import course.chapter")
    return problems


def test_the_setup_and_helper_rules_catch_the_old_patterns():
    provided = _provided_names()
    assert {"skew", "adjoint", "exp_se3", "matrix_to_twist", "clean", "show", "trig_shorthand",
            "is_zero_matrix", "start_page"} <= provided
    old = ("def s_skew(w):\n    return w\n\ndef sadjoint(T):\n    return T\n\ndef fmt(A, digits=4):\n    pass\n"
           "sinv = lambda T: T\ndef is_zero_matrix(A):\n    pass\ndef shorthand(e, t):\n    pass\n"
           "def sexp_se3(S, th):\n    pass\n")
    assert helper_copies(old, provided) == ["s_skew", "sadjoint", "fmt", "sinv", "is_zero_matrix", "shorthand",
                                            "sexp_se3"]
    ok = "def body_columns(chain, theta):\n    pass\ndef spatial_twist(T, t):\n    pass\nsetup = 1\n"
    assert helper_copies(ok, provided) == []
    long_setup = "import numpy as np\ntry:\n    from jacobians.plotting import PALETTE\nexcept ImportError:\n" \
        "    PALETTE = {}\n" + "x = 1\n" * 12
    assert setup_problems(long_setup) == [
        "the set-up cell has 17 lines (at most 15: import course.chapter)",
        "the set-up cell has a try/except (no fallbacks: the library is always there)",
        "the set-up cell does not import course.chapter"]
    assert setup_problems("import numpy as np\nfrom course.chapter import Verified, clean, start_page\n\n"
                          "rng = start_page(seed=1)\nverified = Verified()\n") == []


CODE_CHAPTERS = [p for p in CHAPTERS if "```{code-cell}" in p.read_text(encoding="utf-8")]


@pytest.mark.parametrize("path", CODE_CHAPTERS, ids=_ids(CODE_CHAPTERS))
def test_the_setup_cell_is_one_short_import_of_course_chapter(path):
    nb = jupytext.reads(path.read_text(encoding="utf-8"), fmt="md:myst")
    first = next(c for c in nb.cells if c.cell_type == "code")
    problems = setup_problems(first.source)
    assert not problems, f"{path.name}:\n  " + "\n  ".join(problems)


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_no_chapter_defines_a_copy_of_a_library_helper(path):
    nb = jupytext.reads(path.read_text(encoding="utf-8"), fmt="md:myst")
    provided = _provided_names()
    found = [name for c in nb.cells if c.cell_type == "code" for name in helper_copies(c.source, provided)]
    assert not found, (f"{path.name} defines {found}: use jacobians.symbolic / course.chapter "
                       "(lib/course/chapter.py) instead")


# ---------------------------------------------------------------- no copy of the library's code, under any name
class _Shape(ast.NodeTransformer):
    """A function reduced to its code: names (arguments, locals, globals) become placeholders in order of first
    use, the function's own name, annotations, decorators and docstring go."""

    def __init__(self) -> None:
        self.names: dict[str, str] = {}

    def _name(self, name: str) -> str:
        return self.names.setdefault(name, f"v{len(self.names)}")

    def visit_arg(self, node: ast.arg) -> ast.arg:
        node.arg, node.annotation = self._name(node.arg), None
        return node

    def visit_Name(self, node: ast.Name) -> ast.Name:
        node.id = self._name(node.id)
        return node

    def visit_FunctionDef(self, node: ast.FunctionDef) -> ast.FunctionDef:
        node.name, node.returns, node.decorator_list = "f", None, []
        first = node.body[0] if node.body else None
        if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
            node.body = node.body[1:] or [ast.Pass()]
        self.generic_visit(node)
        return node


#: a function shorter than this (AST nodes of its code) is too small to call a copy: a one-line wrapper
MIN_NODES = 25


def code_shape(fn: ast.FunctionDef) -> str | None:
    """The normalised code of ``fn`` (see :class:`_Shape`), or None if it is too small to count."""
    import copy

    norm = _Shape().visit(copy.deepcopy(fn))
    if sum(1 for _ in ast.walk(norm)) < MIN_NODES:
        return None
    return ast.dump(norm, annotate_fields=False, include_attributes=False)


def _functions(source: str) -> list[ast.FunctionDef]:
    source = "\n".join(line for line in source.splitlines() if not line.lstrip().startswith(("%", "!")))
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return []
    return [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)]


@functools.cache
def _library_shapes() -> dict[str, str]:
    out: dict[str, str] = {}
    for path in sorted((ROOT / "lib").rglob("*.py")):
        for fn in _functions(path.read_text(encoding="utf-8")):
            shape = code_shape(fn)
            if shape is not None:
                out.setdefault(shape, f"{path.relative_to(ROOT / 'lib').as_posix()}:{fn.name}")
    return out


def library_code_copies(source: str, shapes: dict[str, str]) -> list[str]:
    """The functions of ``source`` whose code is a library function's, whatever the names: 'name = where'."""
    return [f"{fn.name} = {shapes[s]}" for fn in _functions(source) if (s := code_shape(fn)) in shapes]


def test_the_code_copy_rule_catches_a_renamed_copy():
    import inspect

    from jacobians import chain, lie

    shapes = _library_shapes()
    copied = inspect.getsource(chain.SerialChain.fk if hasattr(chain.SerialChain, "fk") else lie.log_se3)
    tree = ast.parse(textwrap.dedent(copied))
    for node in ast.walk(tree):  # every name changed, as a student's copy would
        if isinstance(node, ast.Name):
            node.id += "_x"
        elif isinstance(node, ast.arg):
            node.arg += "_x"
        elif isinstance(node, ast.FunctionDef):
            node.name = "my_own_version"
    found = library_code_copies(ast.unparse(tree), shapes)
    assert len(found) == 1 and found[0].startswith("my_own_version = jacobians/"), found
    own = "def body_columns(chain, theta):\n    out = []\n    for i in range(chain.n):\n" \
          "        out.append(chain.screws[:, i] * theta[i] + 1.5 * theta[i] ** 2 - 7)\n    return out\n"
    assert library_code_copies(own, shapes) == []


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_no_chapter_function_has_the_code_of_a_library_function(path):
    nb = jupytext.reads(path.read_text(encoding="utf-8"), fmt="md:myst")
    shapes = _library_shapes()
    found = [f for c in nb.cells if c.cell_type == "code" for f in library_code_copies(c.source, shapes)]
    assert not found, f"{path.name} repeats library code under another name: {found} (call the library instead)"


# ---------------------------------------------------------------- TeX in Python strings
_CONTROL = "\t\x08\x0c\x07\x0b\r"


def tex_escape_problems(source: str) -> list[str]:
    """Strings of a code cell that lose TeX to Python's escapes: an invalid escape such as '\\d' (a warning
    today, an error in a later Python), or a control character that '\\t', '\\b', '\\f', '\\a', '\\v' or
    '\\r' made of \\theta, \\beta, \\frac, \\alpha, \\vec, \\rho (write them in r"..." strings)."""
    import warnings

    source = "\n".join("" if line.lstrip().startswith(("%", "!")) else line for line in source.splitlines())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            tree = ast.parse(source)
        except (SyntaxError, DeprecationWarning, SyntaxWarning) as exc:
            return [f"line {getattr(exc, 'lineno', '?')}: {exc}"]
    return [f"line {n.lineno}: {n.value[:60]!r}" for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str) and any(ch in n.value for ch in _CONTROL)
            and "$" in n.value]


def test_the_tex_escape_rule_catches_both_kinds():
    assert tex_escape_problems('x = "unit $\\\\dot\\\\theta$"') == []
    assert tex_escape_problems('x = r"unit $\\dot\\theta$"') == []
    assert len(tex_escape_problems('x = "unit $\\\\dot\\theta$"')) == 1  # \t: a tab where \theta was
    assert "invalid escape" in tex_escape_problems('x = "unit $\\dot p$"')[0]


@pytest.mark.parametrize("path", CHAPTERS, ids=_ids(CHAPTERS))
def test_tex_in_a_chapters_strings_survives_python(path):
    nb = jupytext.reads(path.read_text(encoding="utf-8"), fmt="md:myst")
    found = [p for c in nb.cells if c.cell_type == "code" for p in tex_escape_problems(c.source)]
    assert not found, f"{path.name}: TeX lost to Python's escapes (use r\"...\"): {found}"
