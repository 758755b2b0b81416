"""The student-install test: Debian's Chromium for the JupyterLab check, and the closing note.

``make test-install`` runs tests/install. The measurements the tests record
(time of the install, size of the venv, package count) are printed at the end
of the run and written to ``_build/test-artifacts/install/student_install.txt``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "install"
NOTE: dict[str, str] = {}  # what the closing note says, filled by the tests


# browser_context: tests/conftest.py (the one Chromium launch of the tests)


@pytest.fixture(scope="session")
def note() -> dict[str, str]:
    return NOTE


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    if not NOTE:
        return
    lines = [f"{k}: {v}" for k, v in NOTE.items()]
    terminalreporter.write_sep("-", "the student's install")
    for line in lines:
        terminalreporter.write_line(line)
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    (ARTIFACTS / "student_install.txt").write_text("\n".join(lines) + "\n", encoding="utf-8")
