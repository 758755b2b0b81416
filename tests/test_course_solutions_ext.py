"""_ext/course_solutions.py: ``make book SOLUTIONS=0`` publishes the pages without any solution."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import course_solutions
import pytest

ROOT = Path(__file__).resolve().parent.parent

PAGE = """# Exercises

```{exercise}
:label: ex-one

Compute the twist.
```

```{solution-start} ex-one
:class: dropdown
```

The twist is SECRET-GATED-ANSWER.

```{solution-end}
```

```{solution} ex-one
:class: dropdown

Also SECRET-PLAIN-ANSWER.
```

After the solutions, the page goes on: VISIBLE-TEXT.

```{tip}
Work in Jupyter.

:::{container} course-solutions-only
A solution folds open: SOLUTIONS-NOTE.
:::
```
"""


def _build(tmp: Path, value: str | None) -> str:
    src = tmp / "src"
    src.mkdir(exist_ok=True)
    (src / "conf.py").write_text(
        f"import sys\nsys.path.insert(0, {str(ROOT / '_ext')!r})\n"
        "extensions = ['myst_parser', 'sphinx_exercise', 'course_solutions']\n"
        "myst_enable_extensions = ['colon_fence']\n", encoding="utf-8")
    (src / "index.md").write_text(PAGE, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k != course_solutions.ENV}
    if value is not None:
        env[course_solutions.ENV] = value
    out = tmp / "out"
    subprocess.run([sys.executable, "-m", "sphinx", "-b", "html", "-q", "-W", str(src), str(out)], env=env,
                   check=True, capture_output=True, text=True)
    return (out / "index.html").read_text(encoding="utf-8")


def test_without_solutions_no_solution_text_remains_and_the_page_goes_on(tmp_path):
    with_them = _build(tmp_path, None)
    assert "SECRET-GATED-ANSWER" in with_them and "SECRET-PLAIN-ANSWER" in with_them
    without = _build(tmp_path, "0")  # same output folder: the change of setting must re-read the page
    assert "SECRET-GATED-ANSWER" not in without and "SECRET-PLAIN-ANSWER" not in without
    assert 'class="solution' not in without and "Solution to" not in without
    assert "VISIBLE-TEXT" in without and "Compute the twist." in without and "Work in Jupyter." in without
    assert "SOLUTIONS-NOTE" in with_them and "SOLUTIONS-NOTE" not in without
    assert "SECRET-GATED-ANSWER" in _build(tmp_path, "1")


@pytest.mark.parametrize("value,wanted", [(None, True), ("", True), ("1", True), ("yes", True), ("0", False),
                                          ("false", False), ("OFF", False)])
def test_the_environment_value(value, wanted):
    assert course_solutions.solutions_wanted(value) is wanted


def test_a_bad_value_says_what_was_expected():
    with pytest.raises(ValueError, match="Expected COURSE_SOLUTIONS to be 1 or 0"):
        course_solutions.solutions_wanted("maybe")
