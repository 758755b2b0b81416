"""The notebooks a reader downloads (chapters, exercise pages), their install cell, and the launch settings."""

from __future__ import annotations

import importlib.util
import re
import subprocess
from pathlib import Path

import nbformat
import pytest
from notebook_downloads import theme_launch_options
from reader_notebooks import (
    INSTALL_TAG,
    course_requirement,
    install_cell,
    live_view_code,
    plain_markdown,
    reader_notebook,
)
from tools.make_exercises import check_student, student_notebook

ROOT = Path(__file__).resolve().parent.parent
CHAPTERS = sorted((ROOT / "chapters").glob("[0-9][0-9]_*.md"))
EXERCISES = sorted((ROOT / "exercises").glob("[0-9][0-9]_*.md"))
REPO = "https://github.com/example/manipulator-jacobians"
MYST_LEFT = re.compile(r"(`{3,}|:{3,})\{[\w:-]+\}|\{(doc|ref|numref|prf:ref)\}`|^\([\w:-]+\)=", re.M)
WIDGET_CELL = re.compile(r"^(?:\w+\s*=\s*)?(LiveView|PlanarExplorer|ResolvedRate|ColumnsExplorer|GimbalLock|StoryView)\(", re.M)


@pytest.mark.parametrize("path", CHAPTERS, ids=lambda p: p.stem)
def test_a_chapter_notebook_is_plain_jupyter_with_the_install_cell_first(path):
    nb = reader_notebook(path, None)
    nbformat.validate(nb)
    first = nb.cells[0]
    assert first.cell_type == "code" and INSTALL_TAG in first.metadata["tags"]
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert all(not c.outputs and c.execution_count is None for c in code)
    left = [m.group(0) for c in nb.cells if c.cell_type == "markdown" for m in MYST_LEFT.finditer(c.source)]
    assert left == [], f"MyST markup a plain Jupyter shows raw: {left[:5]}"
    source = path.read_text(encoding="utf-8")
    views = len(re.findall(r"^```\{live-view\}", source, re.M))
    widget_cells = [c for c in code if WIDGET_CELL.search(c.source)]
    assert len(widget_cells) >= views, f"{views} live views, {len(widget_cells)} cells that show one"
    n_src = len([c for c in nbformat.reads(nbformat.writes(nb), 4).cells if c.cell_type == "code"])
    assert n_src == len(code)


def test_every_live_view_of_the_chapters_becomes_a_widget_that_builds():
    found = 0
    for path in CHAPTERS:
        _text, views = plain_markdown(path.read_text(encoding="utf-8"))
        for view, code in views:
            ns: dict = {}
            exec(code.replace("\n", "\n_w = ", 1), ns)  # line 1 imports, line 2 is the widget
            assert ns["_w"].view == view and ns["_w"]._esm
            found += 1
    assert found == sum(len(re.findall(r"^```\{live-view\}", p.read_text(encoding="utf-8"), re.M)) for p in CHAPTERS)


def test_plain_markdown_of_theorems_roles_and_slides():
    text, views = plain_markdown(
        "(lab)=\n## A\n\n```{prf:theorem} Columns\n:label: ch02-thm-columns\n\nText $x$.\n```\n\n"
        "See {prf:ref}`ch02-thm-columns` and {doc}`../chapters/03_body_jacobian`, {ref}`words <lab>`.\n\n"
        "```{slide}\nslide words\n```\n\n```{live-view} planar_explorer\n:robot: planar_2r\n:theta: 0.1 0.2\n```\n")
    assert "> **Theorem (Columns).** Text $x$." in text
    assert "Theorem *columns* (chapter 2)" in text and "the chapter *body jacobian*" in text and "words" in text
    assert "slide words" not in text and "(lab)=" not in text
    assert views == [("planar_explorer", "from jacobians.widgets.live.planar_explorer import PlanarExplorer\n"
                      "PlanarExplorer(robot='planar_2r', theta=[0.1, 0.2])")]
    assert live_view_code("gimbal_lock", {"robot": "zyz_wrist", "rep": "zyx"}).endswith(
        "GimbalLock(robot='zyz_wrist', rep='zyx')")


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.stem)
def test_a_student_notebook_starts_with_the_install_cell_and_stays_a_student_notebook(path):
    nb = student_notebook(path, course=course_requirement(REPO))
    check_student(nb)
    first_code = next(c for c in nb.cells if c.cell_type == "code")
    assert INSTALL_TAG in first_code.metadata["tags"] and REPO + ".git@main" in first_code.source


def _run_install_cell(cell, monkeypatch, missing: set[str], pip_returncode: int = 0):
    calls: list[list[str]] = []
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name in missing else real(name, *a))
    monkeypatch.setattr(subprocess, "run", lambda cmd, *a, **k: calls.append(cmd) or subprocess.CompletedProcess(
        cmd, pip_returncode))
    exec(cell.source, {})
    return calls


def test_the_install_cell_does_nothing_where_the_course_is_installed(monkeypatch):
    cell = install_cell(["numpy", "sympy", "jacobians", "course"], course_requirement(REPO))
    assert _run_install_cell(cell, monkeypatch, missing=set()) == []  # no pip, no network


def test_the_install_cell_installs_the_course_from_the_repository_when_missing(monkeypatch):
    cell = install_cell(["numpy", "scipy", "jacobians", "course"], course_requirement(REPO, "main"))
    calls = _run_install_cell(cell, monkeypatch, missing={"course", "scipy"})
    assert len(calls) == 1 and calls[0][1:4] == ["-m", "pip", "install"]
    assert f"jacobians[course,widgets] @ git+{REPO}.git@main" in calls[0]
    assert any(a.startswith("scipy==") for a in calls[0])  # at the version constraints.txt pins


def test_the_install_cell_offline_stops_with_what_to_do(monkeypatch):
    cell = install_cell(["jacobians", "course"], course_requirement(REPO))
    with pytest.raises(RuntimeError, match=r"offline.*jacobians\[student\]"):
        _run_install_cell(cell, monkeypatch, missing={"course"}, pip_returncode=1)


def test_the_install_cell_without_a_repository_says_how_to_install(monkeypatch):
    cell = install_cell(["jacobians", "course"], None)
    with pytest.raises(ModuleNotFoundError, match=r"jacobians\[student\].*Start here"):
        _run_install_cell(cell, monkeypatch, missing={"course"})


def test_course_requirement():
    assert course_requirement("") is None
    assert course_requirement(REPO + ".git/", "dev", "book/") == \
        f"jacobians[course,widgets] @ git+{REPO}.git@dev#subdirectory=book"


def test_launch_buttons_hidden_while_the_repository_is_empty_and_shown_once_set():
    launch = {"notebook_interface": "jupyterlab", "binderhub_url": "https://mybinder.org", "colab_url": ""}
    html = {"use_repository_button": True}
    off = theme_launch_options({"launch_buttons": launch, "repository": {"url": ""}, "html": html})
    assert off["launch_buttons"] == {} and off["repository_url"] == "" and not off["use_repository_button"]
    on = theme_launch_options({"launch_buttons": launch, "repository": {"url": REPO, "branch": "main"}, "html": html})
    assert on["launch_buttons"]["binderhub_url"] == "https://mybinder.org" and on["repository_url"] == REPO
    assert on["repository_branch"] == "main" and on["use_repository_button"]


def test_the_book_config_names_the_extension_and_leaves_the_repository_to_repository_url():
    import yaml

    cfg = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    assert cfg["sphinx"]["local_extensions"]["notebook_downloads"] == "_ext"
    assert "repository_url" not in cfg["sphinx"]["config"]["html_theme_options"]  # it would hide repository.url
