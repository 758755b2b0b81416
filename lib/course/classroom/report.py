"""The HTML report of each student: one self-contained page (no script, no web font, no network).

>>> from course.classroom.grade import Row
>>> page = student_page("s1", [Row("s1", "a/02.ipynb", "ch02_ex1", "s1", "1", "Correct."),
...                            Row("s1", "a/02.ipynb", "(notebook)", "s1", "", "code cell 3 raised <NameError>")])
>>> "1 of 1 exercises right" in page, "&lt;NameError&gt;" in page
(True, True)
"""

from __future__ import annotations

import hashlib
import html
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["class_page", "report_name", "student_page", "write_reports"]

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;font-size:17px;line-height:1.5;color:#1a1a1a;
max-width:60rem;margin:1.5rem auto;padding:0 1rem}
h1{font-size:1.6rem}h2{font-size:1.2rem;margin-top:2rem;word-break:break-all}
table{border-collapse:collapse;width:100%}th,td{text-align:left;vertical-align:top;padding:.45rem .6rem;
border-bottom:1px solid #ddd}td.v{white-space:nowrap;font-weight:600}
.ok{color:#007a5a}.no{color:#b34700}.note{background:#fdf4e3;border-left:5px solid #E69F00;padding:.4rem .7rem;
margin:.4rem 0}code{font-size:.95em}
"""


def report_name(student: str) -> str:
    """A file name for ``student``'s report: the ID's safe characters, and a short hash when any were dropped."""
    safe = re.sub(r"[^A-Za-z0-9._-]", "_", student)[:60].strip("._") or "no-id"
    if safe != student:
        safe += "-" + hashlib.sha256(student.encode()).hexdigest()[:8]
    return safe + ".html"


def student_page(student: str, rows: Sequence[Any]) -> str:
    """The report of ``student`` from their gradebook rows."""
    e = html.escape
    graded = [r for r in rows if r.correct in ("0", "1")]
    right = sum(r.correct == "1" for r in graded)
    title = f"Exercises of student {student}" if student else "Notebooks without a student ID"
    parts = [f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
             f'<meta name="viewport" content="width=device-width,initial-scale=1"><title>{e(title)}</title>'
             f"<style>{_CSS}</style></head><body><h1>{e(title)}</h1>"
             f"<p><strong>{right} of {len(graded)} exercises right.</strong> Each answer was run again and "
             "graded with the course's reference for this ID.</p>"]
    for r in rows:
        if r.exercise == "(roster)":
            parts.append(f'<p class="note">{e(r.message)}</p>')
    for nb in sorted({r.notebook for r in rows if r.exercise != "(roster)"}):
        mine = [r for r in rows if r.notebook == nb]
        parts.append(f"<h2>{e(nb)}</h2>")
        for r in mine:
            if r.correct == "":
                parts.append(f'<p class="note">The notebook {e(r.message)}</p>' if r.exercise == "(notebook)"
                             else f'<p class="note">{e(r.message)}</p>')
        ex = [r for r in mine if r.correct in ("0", "1")]
        if ex:
            parts.append('<table><thead><tr><th scope="col">Exercise</th><th scope="col">Verdict</th>'
                         '<th scope="col">Feedback</th></tr></thead><tbody>')
            for r in ex:
                tests = getattr(r, "tests", "")
                verdict = '<td class="v ok">&#10004; right</td>' if r.correct == "1" else \
                    f'<td class="v no">&#10008; not yet<br>{e(tests.replace("/", " of "))} tests</td>' \
                    if tests else '<td class="v no">&#10008; not yet</td>'
                message = r.message.removeprefix("wrong: ")  # (the verdict column says it)
                parts.append(f"<tr><td><code>{e(r.exercise)}</code></td>{verdict}<td>{e(message)}</td></tr>")
            parts.append("</tbody></table>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_reports(folder: Path, rows: Sequence[Any]) -> list[Path]:
    """One page per student (rows without a student ID share one page) in ``folder``; the paths written.

    The pages of an earlier run are removed first, so the folder holds exactly this run's reports."""
    folder.mkdir(parents=True, exist_ok=True)
    for old in folder.glob("*.html"):
        old.unlink()
    by: dict[str, list[Any]] = {}
    for r in rows:
        if r.exercise != "(submissions)":
            by.setdefault(r.student, []).append(r)
    out = []
    for student, mine in sorted(by.items()):
        path = folder / report_name(student)
        path.write_text(student_page(student, mine), encoding="utf-8")
        out.append(path)
    return out


def class_page(rows: Sequence[Any]) -> str:
    """The class page: per exercise, how many students tried it, how many got it right, and the three
    mistakes the checker named most often in wrong answers (rows that count only; one student once)."""
    from collections import Counter

    e = html.escape
    by: dict[str, dict[str, Any]] = {}
    for r in rows:
        if r.correct not in ("0", "1") or not r.student:
            continue
        ex = by.setdefault(r.exercise, {"tried": set(), "right": set(), "mistakes": Counter()})
        if not r.message.startswith("not attempted"):
            ex["tried"].add(r.student)
        if r.correct == "1":
            ex["right"].add(r.student)
        elif getattr(r, "mistake", ""):
            ex["mistakes"][r.mistake] += 1
    students = {r.student for r in rows if r.student and r.exercise != "(roster)"}
    notebooks = {r.notebook for r in rows if r.notebook and r.exercise not in ("(roster)", "(submissions)")}
    unsafe = any(r.message.startswith("[UNSAFE") for r in rows)
    parts = ['<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
             '<meta name="viewport" content="width=device-width,initial-scale=1"><title>The class, exercise by '
             f'exercise</title><style>{_CSS}td.n,th.n{{text-align:right;font-variant-numeric:tabular-nums}}'
             '.warn{background:#fde8e8;border-left:5px solid #b30000;padding:.5rem .8rem}'
             'ul.look li{margin:.3rem 0}</style>'
             '</head><body><h1>The class, exercise by exercise</h1>']
    if unsafe:
        parts.append('<p class="warn"><strong>Graded without isolation (UNSAFE=1).</strong> Student code ran '
                     "as your own user: it could have read or changed other students' work and these grades.</p>")
    parts.append(f"<p>{len(notebooks)} notebooks of {len(students)} students were graded (a notebook whose ID is "
                 "the template's placeholder counts as a student of its own). Per exercise: <em>tried</em> is how "
                 "many students gave an answer to its check, <em>right</em> how many have the answer that counts "
                 "right, and the mistakes are those the checker named in wrong answers, most frequent first "
                 "(with how many students made each).</p>")
    look = _needs_a_look(rows)
    roster = {k: v for k, v in look.items() if k[1] == "(roster)"}
    look = {k: v for k, v in look.items() if k[1] != "(roster)"}
    if look:
        parts.append(f'<p><a href="#look">{len(look)} notebooks need a look</a> (errors, attempts the sandbox '
                     "refused, limits reached, duplicate or unusable IDs): the list is below the table."
                     + (f' <a href="#roster">{len(roster)} roster notes</a>.' if roster else "") + "</p>")
    parts.append('<table><thead><tr><th scope="col">Exercise</th>'
                 f'<th scope="col" class="n">Tried (of {len(students)})</th>'
                 f'<th scope="col" class="n">Right (of {len(students)})</th>'
                 '<th scope="col">Most common named mistakes</th></tr></thead><tbody>')
    for eid in sorted(by):
        ex = by[eid]
        top = ", ".join(f"{e(name)} ({n})" for name, n in ex["mistakes"].most_common(3)) or "&mdash;"
        parts.append(f"<tr><td><code>{e(eid)}</code></td><td class=\"n\">{len(ex['tried'])}</td>"
                     f"<td class=\"n\">{len(ex['right'])}</td><td>{top}</td></tr>")
    parts.append("</tbody></table>")
    if look:
        parts.append('<h2 id="look">Notebooks that need a look</h2><p>What the grader noticed, per notebook; the '
                     "student's report (linked) has the rest. Whatever a notebook tried, it ran in a sandbox of its "
                     "own: these notes say what was stopped, not what got through.</p><ul class=\"look\">")
        for (student, notebook), notes in look.items():
            who = (f'<a href="reports/{e(report_name(student))}">{e(student)}</a>' if student else
                   "no student ID")
            items = "".join(f"<li>{e(m[:300])}</li>" for m in notes[:6])
            more = f"<li>and {len(notes) - 6} more</li>" if len(notes) > 6 else ""
            parts.append(f"<li><strong>{who}</strong>, <code>{e(notebook)}</code><ul>{items}{more}</ul></li>")
        parts.append("</ul>")
    if roster:
        parts.append('<h2 id="roster">The roster</h2><ul class="look">')
        for (student, _), notes in roster.items():
            parts.append(f"<li><strong>{e(student)}</strong>: {e('; '.join(notes))}</li>")
        parts.append("</ul>")
    parts.append("</body></html>")
    return "\n".join(parts)


def _needs_a_look(rows: Sequence[Any]) -> dict[tuple[str, str], list[str]]:
    """The notes on notebooks and the roster, grouped by (student, notebook), in the order of the rows."""
    out: dict[tuple[str, str], list[str]] = {}
    for r in rows:
        if r.correct == "" and r.exercise in ("(notebook)", "(roster)", "(submissions)"):
            note = r.message.removeprefix("[UNSAFE: graded without isolation] ")
            if r.exercise == "(notebook)" and not note.startswith("code cell"):
                note = "It " + note  # (the notes on a notebook are sentences about it without their subject)
            note = note[:1].upper() + note[1:]
            out.setdefault((r.student, r.notebook or "(roster)"), []).append(note)
    return out
