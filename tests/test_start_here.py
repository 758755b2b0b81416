"""The students' Start here page: near the top of the book, its week plan the same as the instructors', every
chapter and exercise page in it; every chapter links its exercise page; practice exercises are lettered."""

from __future__ import annotations

import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
START = ROOT / "chapters" / "start_here.md"
ROW = re.compile(r"^\| (\d+) \| (.*?) \| (.*?) \|$", re.M)
DOC = re.compile(r"\{doc\}`([^`]+)`")


def _weeks(path: Path) -> dict[int, tuple[list[str], list[str]]]:
    """week -> (pages to read, exercise pages) of the week table of a page."""
    out = {}
    for m in ROW.finditer(path.read_text(encoding="utf-8")):
        out[int(m.group(1))] = (DOC.findall(m.group(2)), DOC.findall(m.group(3)))
    return out


def test_start_here_is_the_first_page_after_the_intro():
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    first = toc["parts"][0]["chapters"][0]["file"]
    assert first == "chapters/start_here"


def test_the_week_plan_is_the_instructors_one_and_names_every_chapter_and_exercise_page():
    students, teachers = _weeks(START), _weeks(ROOT / "chapters" / "teaching.md")
    assert students == teachers and len(students) == 13
    chapters = {p.stem for p in (ROOT / "chapters").glob("[0-9][0-9]_*.md")}
    pages = {p.stem for p in (ROOT / "exercises").glob("[0-9][0-9]_*.md")}
    assert {Path(d).name for r, _ in students.values() for d in r} >= chapters
    assert {Path(d).name for _, e in students.values() for d in e} == pages


def test_start_here_says_how_to_install_set_the_id_and_hand_in():
    text = START.read_text(encoding="utf-8")
    assert '[student]"' in text and "jupyter lab" in text
    assert 'SEED = "student-id"  # your student ID (any text): it picks your variant of every exercise' in text
    assert "## Handing in" in text and "coming" in text  # checking in the page is announced, not promised


def test_every_chapter_links_its_exercise_page_and_letters_its_practice_exercises():
    paths = sorted((ROOT / "chapters").glob("[0-9][0-9]_*.md"))
    assert len(paths) >= 12
    for path in paths:
        text = path.read_text(encoding="utf-8")
        n = int(path.name[:2])
        assert f"{{doc}}`../exercises/{path.stem}`" in text, path.name
        # "2.A", or with a short title after a colon ("10.A: one Newton step by hand"); never numbered
        blocks = re.findall(r"^```\{exercise\}(.*)\n((?::[a-z]+:.*\n)*)", text, re.M)
        assert blocks, path.name
        for title, options in blocks:
            assert re.fullmatch(rf" {n}\.[A-H](: .+)?", title), (path.name, title)
            assert ":nonumber:" in options, (path.name, title)
            assert re.search(rf":label: ch{n:02d}-ex-[A-H]\n", options), (path.name, title, options)
        assert not re.search(rf":label: ch{n:02d}_ex\d", text), f"{path.name}: a practice label looks like a graded id"
