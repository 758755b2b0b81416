"""Sphinx extension: an answer box under each exercise of the exercise pages, checked in the page.

An exercise page writes, in a ``book-only`` Markdown cell after the exercise's ``exercises.load`` cell::

    ```{answer-box} ch01_ex1
    ```

For an exercise the page checks (numbers, vectors, matrices, one number in a range, formulas: kinds
:data:`course.exercises._bank.PAGE_KINDS`), this writes a host ``<div class="course-answer"
data-exercise=...>`` and a deferred ``<script>`` loading that exercise's bank,
``_static/exercise-checks/banks/<id>.js`` (``window.__courseBanks[id] = {...}``: every variant's reference,
tolerance rule, catalogued mistakes with their messages, and hint, computed by the library,
:func:`course.exercises._bank.bank`). Banks are written when the build finishes, for the exercises that have a
box, and kept while no Python file under ``lib/`` changes (a stamp of their hash). The statements of the variants
(:func:`course.exercises._bank.statements`) are typeset at build time by the pages' own MathJax in Node
(``_ext/math_prerender.py``, with the page they belong to, so that the page's CSS has their characters) into
``_static/exercise-checks/statements/<id>/<k>.js``, one small script per variant: the page adds the script of the
reader's variant only, and never needs MathJax to show it. The page's script,
``_static/exercise-checks/checker.js``, is bundled by npm's esbuild from ``_ext/exercise_checks/*.js`` (math.js
included) into one classic script, added to the pages with a box only: it mounts the boxes, the ID panel and
progress (localStorage), and compares as :func:`jacobians.grading.compare.compare` does. Classic scripts, no
fetch: the page works from ``file://`` as well as served.

Exercises of other kinds (code) get a sentence saying they are checked in the notebook,
with a link to the page's student notebook (``student/<page>.ipynb``).

The role ``{exercise-count}`02``` writes how many exercises chapter 2 has, by kind, as the catalogue says
("4: 2 numeric, 1 symbolic, 1 code"): no page writes a count of its own.
"""

from __future__ import annotations

import hashlib
import html
import json
import os
import shutil
import subprocess
from concurrent.futures import ProcessPoolExecutor
from functools import cache
from pathlib import Path
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective, SphinxRole

__all__ = ["AnswerBox", "ExerciseCount", "box_html", "count_text", "setup", "write_banks"]

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
OUT_DIR = "_static/exercise-checks"
#: Where the statements' sources wait for the math typesetting (under the doctree folder: not shipped)
SOURCES = "exercise-statements"
LOG = logging.getLogger(__name__)


@cache
def exercise_kind(exercise_id: str) -> str:
    """The kind of an exercise (from its variant 0; ``KeyError`` for an unknown id)."""
    from course.exercises import CATALOGUE
    from course.exercises._bank import variant_seed
    return CATALOGUE.load(exercise_id, seed=variant_seed(0)).kind


def box_html(exercise_id: str, kind: str, docname: str) -> str:
    """The HTML under an exercise: the host of its answer box and its bank's script, or the sentence that it is
    checked in the notebook."""
    from course.exercises._bank import PAGE_KINDS
    depth = docname.count("/")
    notebook = "student/" + docname.rsplit("/", 1)[-1] + ".ipynb"
    link = f'<a href="{html.escape(notebook)}" download>the student notebook</a>'
    if kind not in PAGE_KINDS:
        what = "a function you write" if kind == "function" else "code"
        return (f'<div class="course-answer course-answer-elsewhere" data-exercise-elsewhere="{exercise_id}">'
                f"<p>The answer to this exercise is {what}: it is checked in the notebook, not on this page. "
                f"Download {link}, write your answer in its answer cell and run the check cell.</p></div>")
    src = ("../" * depth) + f"{OUT_DIR}/banks/{exercise_id}.js"
    statements = ("../" * depth) + f"{OUT_DIR}/statements/{exercise_id}/"
    return (f'<div class="course-answer" data-exercise="{exercise_id}" data-kind="{kind}" '
            f'data-statements="{html.escape(statements)}">'
            f"<noscript>Checking your answer on this page needs JavaScript; {link} checks it in Jupyter."
            f"</noscript></div>\n<script defer src=\"{html.escape(src)}\"></script>")


#: How the count names each kind: a number checked by a rule (predicate, scalar) is a numeric exercise.
KIND_NAMES = {"numeric": "numeric", "predicate": "numeric", "scalar": "numeric", "symbolic": "symbolic",
              "function": "code"}


def count_text(chapter: int) -> str:
    """How many exercises ``chapter`` has in the catalogue, by kind: ``"4: 2 numeric, 1 symbolic, 1 code"``."""
    from course.exercises import exercise_ids

    ids = [e for e in exercise_ids() if e.startswith(f"ch{chapter:02d}_")]
    if not ids:
        raise KeyError(f"chapter {chapter} has no exercise")
    names = [KIND_NAMES[exercise_kind(e)] for e in ids]
    parts = [f"{names.count(k)} {k}" for k in ("numeric", "symbolic", "code") if k in names]
    return f"{len(ids)}: {', '.join(parts)}"


class ExerciseCount(SphinxRole):
    """``{exercise-count}`NN```: the exercises of chapter NN, counted from the catalogue (:func:`count_text`)."""

    def run(self) -> tuple[list[nodes.Node], list[nodes.system_message]]:
        try:
            chapter = int(self.text.strip())
            text = count_text(chapter)
        except (ValueError, KeyError) as exc:
            msg = self.inliner.reporter.error(f"exercise-count: {exc}", line=self.lineno)
            return [self.inliner.problematic(self.rawtext, self.rawtext, msg)], [msg]
        for module in sorted((ROOT / "lib" / "course" / "exercises").glob(f"ch{chapter:02d}.py")):
            self.env.note_dependency(str(module))  # re-read the page when the chapter's definitions change
        return [nodes.Text(text)], []


class AnswerBox(SphinxDirective):
    """``{answer-box} <exercise id>``: the answer box of one exercise (see the module's docstring)."""

    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        exercise_id = self.arguments[0].strip()
        try:
            kind = exercise_kind(exercise_id)
        except KeyError as exc:
            raise self.error(f"answer-box: {exc}") from None
        store: dict[str, list[str]] = getattr(self.env, "course_answer_boxes", {})
        store.setdefault(self.env.docname, [])
        if exercise_id not in store[self.env.docname]:
            store[self.env.docname].append(exercise_id)
        self.env.course_answer_boxes = store  # type: ignore[attr-defined]
        return [nodes.raw("", box_html(exercise_id, kind, self.env.docname), format="html")]


def _purge(app: Sphinx, env: Any, docname: str) -> None:
    getattr(env, "course_answer_boxes", {}).pop(docname, None)


def _merge(app: Sphinx, env: Any, docnames: set[str], other: Any) -> None:
    store = getattr(env, "course_answer_boxes", {})
    store.update({d: ids for d, ids in getattr(other, "course_answer_boxes", {}).items() if d in docnames})
    env.course_answer_boxes = store


def _page_assets(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any], doctree: Any) -> None:
    """The checker's script and style on the pages with an answer box only."""
    if getattr(app.env, "course_answer_boxes", {}).get(pagename):
        app.add_js_file("exercise-checks/checker.js", loading_method="defer")
        app.add_css_file("exercise-checks/answers.css")


def _lib_stamp() -> str:
    """A hash of every Python file under lib/ (the references, mistakes and checker the banks come from)."""
    h = hashlib.sha256()
    for p in sorted((ROOT / "lib").rglob("*.py")):
        h.update(str(p.relative_to(ROOT)).encode() + b"\0" + p.read_bytes())
    return h.hexdigest()


def write_banks(out: Path, exercise_ids: list[str], sources: Path | None = None) -> list[str]:
    """Write the bank script of each exercise the page checks into ``out`` (a folder), and the sources of its
    statements (``<id>.json``, a list of HTML strings) into ``sources``; returns those written.
    Skipped when the stamp of lib/ and the list of exercises are those of the banks already there."""
    from course.exercises._bank import PAGE_KINDS
    wanted = sorted(e for e in set(exercise_ids) if exercise_kind(e) in PAGE_KINDS)
    stamp = _lib_stamp() + "\n" + ",".join(wanted)
    stamp_file = out / ".stamp"
    if (stamp_file.is_file() and stamp_file.read_text() == stamp and all((out / f"{e}.js").is_file() for e in wanted)
            and (sources is None or all((sources / f"{e}.json").is_file() for e in wanted))):
        return []
    out.mkdir(parents=True, exist_ok=True)
    if sources is not None:
        sources.mkdir(parents=True, exist_ok=True)
    # each exercise's bank is computed by the library on its own: on every core, in worker processes
    workers = max(1, min(os.cpu_count() or 1, len(wanted)))
    with ProcessPoolExecutor(max_workers=workers) as pool:
        made = pool.map(_bank_files, wanted, [sources is not None] * len(wanted))
        for e, (shown, script) in zip(wanted, made, strict=True):
            if sources is not None:
                (sources / f"{e}.json").write_text(shown, encoding="utf-8")
            (out / f"{e}.js").write_text(script, encoding="utf-8")
    stamp_file.write_text(stamp)
    return wanted


def _bank_files(exercise_id: str, with_statements: bool) -> tuple[str, str]:
    """The statements' sources (JSON, when asked for) and the bank script of one exercise (in a worker process)."""
    from course.exercises._bank import bank, statements

    shown = json.dumps(statements(exercise_id), ensure_ascii=False) if with_statements else ""
    data = json.dumps(bank(exercise_id), separators=(",", ":"), ensure_ascii=False, allow_nan=False)
    # "</" cannot end the script early: JSON allows "<\/"
    text = data.replace("</", "<\\/")
    return shown, f"(window.__courseBanks=window.__courseBanks||{{}})[{json.dumps(exercise_id)}]={text};\n"


def bundle(out_file: Path) -> None:
    """The page's checker as one classic script, bundled by npm's esbuild (math.js included)."""
    esbuild = ROOT / "node_modules" / ".bin" / "esbuild"
    if not esbuild.is_file():
        raise FileNotFoundError(f"{esbuild} is missing: run `npm ci` (make does this) first")
    done = subprocess.run([str(esbuild), str(HERE / "entry.js"), "--bundle", "--format=iife", "--target=es2020",
                           "--minify", "--legal-comments=eof", f"--outfile={out_file}", "--log-level=warning"],
                          cwd=ROOT, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"esbuild failed to bundle the exercise checker:\n{done.stderr}")


def _finished(app: Sphinx, exception: Exception | None) -> None:
    if exception is not None or app.builder.name not in ("html", "dirhtml"):  # not the decks' revealjs build
        return
    ids = [e for ids in getattr(app.env, "course_answer_boxes", {}).values() for e in ids]
    if not ids:
        return
    out = Path(app.outdir) / OUT_DIR
    out.mkdir(parents=True, exist_ok=True)
    bundle(out / "checker.js")
    shutil.copyfile(HERE / "answers.css", out / "answers.css")
    sources = Path(app.doctreedir) / SOURCES
    written = write_banks(out / "banks", ids, sources)
    if written:
        LOG.info(f"exercise checks: wrote {len(written)} banks into {out / 'banks'}")
    # the statements go to the math typesetting, with their page (_ext/math_prerender.py reads this)
    from course.exercises._bank import PAGE_KINDS
    fragments: dict[str, list[dict[str, str]]] = {}
    for page, page_ids in getattr(app.env, "course_answer_boxes", {}).items():
        for e in page_ids:
            if exercise_kind(e) in PAGE_KINDS:
                fragments.setdefault(page, []).append(
                    {"src": str(sources / f"{e}.json"), "out": str(out / "statements" / e), "key": e})
    app.course_math_fragments = fragments  # type: ignore[attr-defined]


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("answer-box", AnswerBox)
    app.add_role("exercise-count", ExerciseCount())
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.connect("html-page-context", _page_assets)
    app.connect("build-finished", _finished)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
