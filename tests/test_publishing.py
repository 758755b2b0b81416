"""What publishing needs: licences, citation, changelog, the deploy workflow, _ext/publishing.py.

The workflow and CITATION.cff are validated against the schemas vendored in
check-jsonschema (GitHub's workflow schema, the Citation File Format schema);
a broken copy of each must be rejected, so the check can fail.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import publishing
import pytest
import yaml
from sphinx.errors import ConfigError

ROOT = Path(__file__).resolve().parents[1]
WORKFLOW = ROOT / ".github" / "workflows" / "pages.yml"


def schema_check(schema: str, path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "check_jsonschema", "--builtin-schema", schema, str(path)],
                          capture_output=True, text=True, timeout=120)


def test_workflow_is_a_valid_github_workflow(tmp_path):
    ok = schema_check("vendor.github-workflows", WORKFLOW)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    broken = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))
    broken["jobs"]["build"]["step"] = broken["jobs"]["build"].pop("steps")  # a misspelt key
    bad = tmp_path / "pages.yml"
    bad.write_text(yaml.safe_dump(broken), encoding="utf-8")
    assert schema_check("vendor.github-workflows", bad).returncode != 0


def test_workflow_builds_with_make_and_publishes_the_html_folder():
    wf = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))
    steps = wf["jobs"]["build"]["steps"]
    runs = [s.get("run", "") for s in steps]
    assert any(r.strip() == "make book" for r in runs)
    build = next(s for s in steps if s.get("run", "").strip() == "make book")
    assert "BOOK_BASE_URL" in build["env"]  # the sitemap and the 404 page need the site's address
    upload = next(s for s in steps if str(s.get("uses", "")).startswith("actions/upload-pages-artifact"))
    assert upload["with"]["path"] == "_build/html"
    assert any(str(s.get("uses", "")).startswith("actions/deploy-pages") for s in wf["jobs"]["deploy"]["steps"])


def test_citation_is_valid_and_versions_agree(tmp_path):
    ok = schema_check("vendor.citation-file-format", ROOT / "CITATION.cff")
    assert ok.returncode == 0, ok.stdout + ok.stderr
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    changelog = publishing.changelog_version((ROOT / "CHANGELOG.md").read_text(encoding="utf-8"))
    assert cff["version"] == changelog == publishing.package_version(ROOT / "pyproject.toml")
    del cff["authors"]
    bad = tmp_path / "CITATION.cff"
    bad.write_text(yaml.safe_dump(cff), encoding="utf-8")
    assert schema_check("vendor.citation-file-format", bad).returncode != 0


def test_licences_are_there():
    code = (ROOT / "LICENSE").read_text(encoding="utf-8")
    text = (ROOT / "LICENSE-content").read_text(encoding="utf-8")
    assert code.startswith("MIT License") and "WITHOUT WARRANTY OF ANY KIND" in code
    assert "Creative Commons Attribution 4.0 International Public License" in text
    assert "Section 8 – Interpretation." in text  # the whole legal code, not a summary
    for name in ("CONTRIBUTING.md", "CHANGELOG.md"):
        assert (ROOT / name).stat().st_size > 500


def test_changelog_version_reads_the_newest_entry():
    text = "# Changelog\n\n## [Unreleased]\n\n## [1.2.0] - 2027-01-01\n\n## [1.1.0] - 2026-01-01\n"
    assert publishing.changelog_version(text) == "1.2.0"
    with pytest.raises(ConfigError, match="no '## \\[x.y.z\\]"):
        publishing.changelog_version("# Changelog\n\n## [Unreleased]\n")


@pytest.mark.parametrize(("given", "want"), [
    ("", publishing.DEFAULT_BASE_URL),
    ("https://owner.github.io/jacobians", "https://owner.github.io/jacobians/"),
    ("https://course.example.edu/", "https://course.example.edu/"),
])
def test_base_url(given, want):
    assert publishing.base_url({"BOOK_BASE_URL": given}) == want


@pytest.mark.parametrize("bad", ["owner.github.io/jacobians", "ftp://host/x/", "/jacobians/"])
def test_base_url_rejects_what_is_no_address(bad):
    with pytest.raises(ConfigError, match="BOOK_BASE_URL must be an http"):
        publishing.base_url({"BOOK_BASE_URL": bad})


def test_build_date_is_reproducible_with_source_date_epoch():
    assert publishing.build_date({"SOURCE_DATE_EPOCH": "1800000000"}) == "2027-01-15"


def test_root_redirect_has_a_title_a_language_and_a_link():
    page = publishing.redirect_page("Manipulator Jacobians", "chapters/intro.html")
    assert '<html lang="en">' in page and "<title>Manipulator Jacobians</title>" in page
    assert 'content="0; url=chapters/intro.html"' in page and '<a href="chapters/intro.html">' in page


def test_page_description_is_plain_prose_without_the_slides_link():
    from docutils import nodes

    doc = nodes.document(None, None)  # type: ignore[arg-type]
    section = nodes.section()
    link = nodes.paragraph("", "", nodes.Text("▶ Lecture slides for this chapter"), classes=["slides-link"])
    para = nodes.paragraph("", "", nodes.Text("The joints turn at rates "), nodes.math("", r"\dot\theta_1"),
                           nodes.Text(". How fast does the hand move?"))
    long = nodes.paragraph("", "", nodes.Text("word " * 80))
    section += [link, para, long]
    doc += section
    text = publishing.page_description(doc)
    assert text.startswith("The joints turn at rates θ̇_1. How fast does the hand move?")
    assert "Lecture slides" not in text and "\\" not in text
    assert len(text) <= publishing.DESCRIPTION_CHARS and text.endswith("…")
