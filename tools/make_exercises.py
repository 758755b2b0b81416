"""The exercise pages' cells, and the student notebooks written from the pages.

The sources exercises/NN_name.md are the instructor versions (MyST Markdown
notebooks). Every exercise on them is one block of cells, always the same,
written by :func:`render_block` from the parts its author owns (:class:`Block`:
heading, task, answer cell, solution)::

    ## Exercise N.K: heading; the {exercise} box with the task
    exK = exercises.load("chNN_exK", seed=SEED)  statement, shown in book and notebook
    (book-only Markdown line)                    "in the notebook, your answer goes here"
    {answer-box} chNN_exK                        the page's own answer box
    answer = None  # your answer here            tag remove-cell: hidden in the book
    (solution-start ... solution cells ...)      tag solution
    exercises.check("chNN_exK", answer, ...)     tag solution: the verdict on the
                                                 solution, last cell of the dropdown
    (solution-end)                               tag solution
    exercises.check("chNN_exK", answer, ...)     tag remove-cell: the student's check
    assert _fb.correct                           tags solution, remove-cell: CI only

and a page ends with the progress cell (:func:`render_tail`). A page that is not
exactly what the generator writes is refused (:func:`parse_page`).

For each source this script writes DEST/NN_name.ipynb with

* every cell tagged ``solution`` removed (the dropdown's opening and closing
  Markdown cells, the solution code, the verdict on the solution, the
  instructor-only asserts), and every ``book-only`` cell;
* the answer cell and the check cell kept (their ``remove-cell`` tag only
  hides them in the book, and is dropped here), so each exercise reads:
  statement, answer, check;
* no outputs and no execution counts;
* the MyST-only markup a plain Jupyter front end shows as raw text turned into
  plain Markdown: the ``{exercise}`` block becomes a quoted task, ``{doc}`` and
  ``{ref}`` roles become plain text.

Usage::

    python -m tools.make_exercises DEST         the student notebooks (make exercises: _build/exercises)
    python -m tools.make_exercises --new ID     write a newly defined exercise's cells into its page
    python -m tools.make_exercises --check      every page is what the generator writes (exit 1 if not)
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

import jupytext
import nbformat
from _ext.reader_notebooks import configured_course, imported_modules, install_cell

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ROOT / "exercises"
SOLUTION_TAG = "solution"
BOOK_ONLY_TAG = "book-only"  # cells for the web page only (the link to this very notebook)
BOOK_HIDDEN_TAG = "remove-cell"  # the answer and check cells: run but not shown in the book

_EXERCISE = re.compile(r"```\{exercise\}[^\n]*\n((?::[^\n]*\n)*)(.*?)\n```", re.S)
_ROLE = re.compile(r"\{(?:doc|ref|numref|prf:ref)\}`([^`<]*?)(?:\s*<([^>]*)>)?`")
_LABEL = re.compile(r"^\([\w-]+\)=\s*$", re.M)


def _role_text(match: re.Match[str]) -> str:
    text, target = match.group(1).strip(), match.group(2)
    if target:  # {ref}`words <target>`
        return text
    name = Path(text).stem if "/" in text or text.startswith("..") else text
    return f"the chapter *{name.replace('_', ' ')}*" if "/chapters/" in text or text.startswith("../") else name


def _plain_markdown(source: str) -> str:
    source = _EXERCISE.sub(lambda m: "> **Task.** " + m.group(2).strip().replace("\n", "\n> "), source)
    source = _ROLE.sub(_role_text, source)
    source = _LABEL.sub("", source)
    return source.strip("\n")


def student_notebook(path: Path, course: str | None = None) -> nbformat.NotebookNode:
    """The student version of one source notebook.

    Its first code cell installs what the notebook imports when it is missing
    (``_ext/reader_notebooks.py``: the course from ``course``, a pip requirement,
    when given; else the cell says how to install it).
    """
    nb: nbformat.NotebookNode = jupytext.read(path)
    cells = []
    for cell in nb.cells:
        tags = cell.get("metadata", {}).get("tags", [])
        if SOLUTION_TAG in tags or BOOK_ONLY_TAG in tags:
            continue
        if BOOK_HIDDEN_TAG in tags:  # hidden in the book only; a plain tag-free cell for the student
            tags = [t for t in tags if t != BOOK_HIDDEN_TAG]
            if tags:
                cell.metadata["tags"] = tags
            else:
                cell.metadata.pop("tags")
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
        elif cell.cell_type == "markdown":
            cell.source = _plain_markdown(cell.source)
            if not cell.source.strip():
                continue
        cells.append(cell)
    banner = nbformat.v4.new_markdown_cell(
        "*Student version, generated from `exercises/" + path.name + "` by `make exercises`. "
        "Run the cells from the top; put your answer in each `answer = ...` cell and run the check "
        "cell below it. First put your student ID between the quotes of `SEED = \"student-id\"` in the "
        "first code cell: it picks your own variant of every exercise, and your instructor grades that "
        "variant.*")
    needs = imported_modules(nbformat.v4.new_notebook(cells=cells))  # what the student version imports
    nb.cells = [banner, install_cell(needs, course)] + cells
    nb.metadata.pop("mystnb", None)
    jt = nb.metadata.get("jupytext")
    if isinstance(jt, dict):  # a plain .ipynb: no pairing with the source
        jt.pop("text_representation", None)
        if not jt:
            nb.metadata.pop("jupytext")
    return nb


_LOAD = re.compile(r'exercises\.load\("(\w+)", seed=SEED\)')

#: The set-up line that sets the student's seed; a grader finds it (with ``ast``) to regrade that variant.
SEED_LINE = 'SEED = "student-id"  # your student ID (any text): it picks your variant of every exercise'

_ANSWER = re.compile(r"^answer = None\b", re.M)


def exercise_cells(nb: nbformat.NotebookNode) -> dict[str, list[nbformat.NotebookNode]]:
    """The code cells of each exercise, by id: from its ``exercises.load`` cell to the next one."""
    out: dict[str, list] = {}
    current = None
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        if cell.source.strip().startswith("exercises.summary("):  # the progress cell ends the exercises
            current = None
            continue
        m = _LOAD.search(cell.source)
        if m:
            current = m.group(1)
            assert current not in out, f"exercise {current} is loaded twice"
            out[current] = []
        if current is not None:
            out[current].append(cell)
    return out


def check_student(nb: nbformat.NotebookNode) -> None:
    """Raise AssertionError if a solution or an output slipped through, or an exercise lost its
    answer cell or its check cell (each exercise: load, answer = None, check, in that order)."""
    for cell in nb.cells:
        assert SOLUTION_TAG not in cell.get("metadata", {}).get("tags", []), "a solution cell remains"
        if cell.cell_type == "code":
            assert not cell.get("outputs"), "a code cell has outputs"
            assert cell.get("execution_count") is None, "a code cell has an execution count"
        assert "solution-start" not in cell.source and "solution-end" not in cell.source, "solution markup remains"
    seed_cells = [c for c in nb.cells if c.cell_type == "code" and SEED_LINE in c.source.splitlines()]
    assert len(seed_cells) == 1, f"expected the set-up line {SEED_LINE!r} in exactly one code cell"
    by_id = exercise_cells(nb)
    assert by_id, "no exercise (no exercises.load cell)"
    for eid, cells in by_id.items():
        sources = [c.source.strip() for c in cells]
        assert len(cells) == 3, f"{eid}: expected 3 code cells (load, answer, check), got {len(cells)}: {sources}"
        one_answer = len(re.findall(r"^answer\s*=", sources[1], re.M)) == 1 and _ANSWER.search(sources[1])
        assert one_answer, f"{eid}: no answer cell: {sources[1]!r}"
        assert sources[2] == f'exercises.check("{eid}", answer, seed=SEED)', f"{eid}: no check cell: {sources[2]!r}"


# --------------------------------------------------------------------------- the exercise pages' cells
#
# Every exercise of a page is one block of cells, always the same, written by render_block from the few parts
# its author owns (Block): the statement is the definition's (exercises.load), the answer and check cells, the
# solution dropdown's frame, its verdict cell and the instructor's assert follow from the id. A page is its
# head (title, introduction, set-up cell), its blocks in the catalogue's order, and the progress cell.

#: What the book page says where the student notebook has its answer cell (function exercises: a stub).
_ANSWER_LINE = ("*In the student notebook*, a cell here reads `answer = None`: put your answer in `answer`, and the "
                "next cell checks it.")
_STUB_LINE = ("*In the student notebook*, a cell here holds a stub of `{call}`: write the function and set "
              "`answer = {name}`; the next cell checks it.")
_STUB = re.compile(r"^def (\w+)\(([^)]*)\):", re.M)

_BLOCK = """## Exercise {chapter}.{number}: {heading}

```{{exercise}}
:label: ex-{eid}
:nonumber:

{task}
```

```{{code-cell}} ipython3
ex{number} = exercises.load("{eid}", seed=SEED)
ex{number}
```

+++ {{"tags": ["book-only"], "slideshow": {{"slide_type": "skip"}}}}

{answer_line}

```{{answer-box}} {eid}
```

```{{code-cell}} ipython3
:tags: [remove-cell]

{answer}
```

+++ {{"tags": ["solution"]}}

```{{solution-start}} ex-{eid}
:class: dropdown
```

{solution}

```{{code-cell}} ipython3
:tags: [solution]

exercises.check("{eid}", answer, seed=SEED)
```

+++ {{"tags": ["solution"]}}

```{{solution-end}}
```

```{{code-cell}} ipython3
:tags: [remove-cell]

exercises.check("{eid}", answer, seed=SEED)
```

```{{code-cell}} ipython3
:tags: [solution, remove-cell]

# Instructor version only: the reference solution above must be accepted.
_fb = exercises.check("{eid}", answer, seed=SEED)
assert _fb.correct, _fb
```

"""

_TAIL = """+++ {{"tags": ["remove-cell"], "slideshow": {{"slide_type": "skip"}}}}

## Your progress

The cell below lists the exercises of this notebook that you have right, those you tried that are not right yet, \
and those you have not touched yet. It counts as the grader does: the last answer you checked for each exercise, \
under your ID; checks under the placeholder ID `student-id` are practice and count for nothing. Run it again at any \
time.

```{{code-cell}} ipython3
:tags: [remove-cell]

exercises.summary("{chapter_id}")
```
"""


@dataclass
class Block:
    """What the author writes of one exercise on its page: the heading's words, the task (one or two sentences
    in the ``{exercise}`` box; the numbers are the definition's), the answer cell (``answer = None`` and, for a
    function exercise, the stub), and the solution (Markdown and ``{code-cell}`` cells, tagged ``solution``, that
    set ``answer``)."""

    eid: str
    heading: str
    task: str
    answer: str
    solution: str


def _numbers(eid: str) -> tuple[int, int]:
    m = re.fullmatch(r"ch(\d\d)_ex(\d+)", eid)
    if m is None:
        raise ValueError(f"Expected an exercise id such as 'ch02_ex1', got {eid!r}")
    return int(m.group(1)), int(m.group(2))


def answer_line(answer: str) -> str:
    """The book-only line that stands where the student's answer cell is."""
    stub = _STUB.search(answer)
    if stub is None:
        return _ANSWER_LINE
    name, args = stub.groups()
    if len(args.split(",")) > 3:  # a long signature is the statement's business; the line stays one line
        args = "..."
    return _STUB_LINE.format(call=f"{name}({args})", name=name)


def render_block(b: Block) -> str:
    """The MyST text of one exercise: statement, answer, check, solution (ending with its verdict), the
    instructor's assert (see the module's docstring for what each cell is and which tags hide it where)."""
    chapter, number = _numbers(b.eid)
    return _BLOCK.format(chapter=chapter, number=number, heading=b.heading, eid=b.eid, task=b.task.strip("\n"),
                         answer_line=answer_line(b.answer), answer=b.answer.strip("\n"),
                         solution=b.solution.strip("\n"))


def render_tail(chapter: int) -> str:
    """The end of an exercise page: the student's progress cell."""
    return _TAIL.format(chapter_id=f"ch{chapter:02d}")


def _block_pattern() -> re.Pattern[str]:
    text = re.escape(_BLOCK.format(chapter="\0C", number="\0N", heading="\0H", eid="\0E", task="\0T",
                                   answer_line="\0L", answer="\0A", solution="\0S"))
    for mark, group in (("C", r"(?P<chapter>\d+)"), ("H", r"(?P<heading>[^\n]+)"), ("T", r"(?P<task>.*?)"),
                        ("L", r"[^\n]+"), ("A", r"(?P<answer>.*?)"), ("S", r"(?P<solution>.*?)")):
        text = text.replace(re.escape("\0" + mark), group, 1)
    text = text.replace(re.escape("\0N"), r"(?P<number>\d+)", 1).replace(re.escape("\0N"), "(?P=number)")
    text = text.replace(re.escape("\0E"), r"(?P<eid>ch\d\d_ex\d+)", 1).replace(re.escape("\0E"), "(?P=eid)")
    return re.compile(text, re.S)


_BLOCK_RE = _block_pattern()


def parse_page(text: str) -> tuple[str, list[Block], int]:
    """A page's head, its exercises (in page order) and its chapter number; raises ValueError where the page is
    not what :func:`render_page` writes (the message names the place)."""
    first = text.find("## Exercise ")
    if first < 0:  # a new page: its head and the progress cell
        m = re.search(r'exercises\.summary\("ch(\d\d)"\)', text)
        tail = render_tail(int(m.group(1))) if m else ""
        if not m or not text.endswith(tail):
            raise ValueError("no exercise (no '## Exercise' heading) and no progress cell")
        return text[:-len(tail)], [], int(m.group(1))
    head, pos, blocks = text[:first], first, []
    chapter = None
    while text.startswith("## Exercise ", pos):
        m = _BLOCK_RE.match(text, pos)
        if m is None:
            line = text[pos:].splitlines()[0]
            raise ValueError(f"the exercise {line!r} is not in the generated layout (tools/make_exercises.py "
                             "render_block): write it with `python -m tools.make_exercises --new ID`")
        blocks.append(Block(m["eid"], m["heading"], m["task"], m["answer"], m["solution"]))
        chapter = int(m["chapter"])
        pos = m.end()
    assert chapter is not None
    if text[pos:] != render_tail(chapter):
        raise ValueError(f"the page does not end with the progress cell of ch{chapter:02d} after its last exercise")
    return head, blocks, chapter


def render_page(head: str, blocks: list[Block], chapter: int) -> str:
    """The MyST text of an exercise page."""
    return head + "".join(render_block(b) for b in blocks) + render_tail(chapter)


def new_block(eid: str) -> Block:
    """A new exercise's block, from its definition (registered in ``course.exercises``): the heading is its
    title, the answer cell ``answer = None`` (a function exercise: a stub named as its statement asks); the task
    and the solution are for the author to write."""
    from course import exercises

    ex = exercises.load(eid, seed=0)
    answer = "answer = None  # your answer here"
    if ex.kind == "function":
        name = getattr(ex, "fn_name", "my_function")
        call = re.search(rf"`({re.escape(name)}\([^)`]*\))`", ex.statement)
        sig = call.group(1) if call else f"{name}(*args)"
        answer = (f"def {sig}:\n    # your code here\n    return None\n\n\n"
                  f"answer = None  # set answer = {name} when your function is ready")
    _, number = _numbers(eid)
    solution = ("(How to solve it, in a few sentences.)\n\n```{code-cell} ipython3\n:tags: [solution]\n\n"
                f"g = ex{number}.given\nanswer = None  # the worked solution, from g, with the library\n```")
    return Block(eid, ex.title[0].lower() + ex.title[1:], "(The task, in one sentence.)", answer, solution)


def page_of(eid: str) -> Path:
    """The exercise page of ``eid``'s chapter."""
    chapter, _ = _numbers(eid)
    (path,) = SOURCES.glob(f"{chapter:02d}_*.md")
    return path


def add_exercise(eid: str) -> Path:
    """Write the block of a newly defined exercise into its chapter's page, in the catalogue's order."""
    from course import exercises

    path = page_of(eid)
    head, blocks, chapter = parse_page(path.read_text(encoding="utf-8"))
    if any(b.eid == eid for b in blocks):
        raise ValueError(f"{eid} is on {path.name} already")
    order = [e for e in exercises.exercise_ids() if e.startswith(eid.split("_")[0] + "_")]
    blocks.append(new_block(eid))
    blocks.sort(key=lambda b: order.index(b.eid) if b.eid in order else len(order))
    path.write_text(render_page(head, blocks, chapter), encoding="utf-8")
    return path


def check_pages() -> list[str]:
    """What is wrong with the exercise pages: a page not in the generated layout, or whose exercises are not its
    chapter's in the catalogue, in order (empty when all is right)."""
    from course import exercises

    problems = []
    ids = exercises.exercise_ids()
    for path in sorted(SOURCES.glob("[0-9][0-9]_*.md")):
        text = path.read_text(encoding="utf-8")
        try:
            head, blocks, chapter = parse_page(text)
        except ValueError as exc:
            problems.append(f"{path.name}: {exc}")
            continue
        if render_page(head, blocks, chapter) != text:
            problems.append(f"{path.name}: not what the generator writes")
        on_page = [b.eid for b in blocks]
        defined = [e for e in ids if e.startswith(f"ch{chapter:02d}_")]
        if on_page != defined or path.name[:2] != f"{chapter:02d}":
            problems.append(f"{path.name}: exercises {on_page}, but chapter {chapter}'s definitions are {defined} "
                            "(add a missing one with --new ID)")
    return problems


def main(dest: Path) -> int:
    dest.mkdir(parents=True, exist_ok=True)
    paths = sorted(SOURCES.glob("[0-9][0-9]_*.md"))
    if not paths:
        print("make_exercises: no exercise sources found in", SOURCES, file=sys.stderr)
        return 1
    course = configured_course(ROOT)  # repository.url of _config.yml: where the install cell gets the course
    for path in paths:
        nb = student_notebook(path, course=course)
        check_student(nb)
        nbformat.validate(nb)
        nbformat.write(nb, dest / f"{path.stem}.ipynb")
    print(f"make_exercises: wrote {len(paths)} student notebooks to {dest}")
    return 0


def _cli(argv: list[str]) -> int:
    if argv[:1] == ["--new"] and len(argv) == 2:
        path = add_exercise(argv[1])
        print(f"make_exercises: wrote the cells of {argv[1]} into {path.relative_to(ROOT)}; now write its task and "
              "solution there (AUTHORING.md, 'Adding an exercise')")
        return 0
    if argv == ["--check"]:
        problems = check_pages()
        for p in problems:
            print("make_exercises:", p, file=sys.stderr)
        return 1 if problems else 0
    if len(argv) == 1 and not argv[0].startswith("-"):
        return main(Path(argv[0]))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(_cli(sys.argv[1:]))
