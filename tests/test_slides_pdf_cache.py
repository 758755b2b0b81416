"""tools/slides_pdf.py prints a deck again only when something it shows changed (no browser: a stand-in
records what is printed)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from tools import slides_pdf


class _Page:
    def __init__(self, log: list[str]) -> None:
        self.log, self.url = log, ""

    def goto(self, url: str, wait_until: str, timeout: float | None = None) -> None:
        self.url = url

    def wait_for_selector(self, *args, **kwargs) -> None:
        pass

    def wait_for_timeout(self, ms: int) -> None:
        pass

    def evaluate(self, script: str):
        return 7 if "getTotalSlides" in script else None

    def pdf(self, path: str, **kwargs) -> None:
        self.log.append(Path(path).name)
        Path(path).write_bytes(b"%PDF " + self.url.encode())

    def close(self) -> None:
        pass


class _Browser:
    def __init__(self) -> None:
        self.printed: list[str] = []

    def new_page(self, viewport: dict) -> _Page:
        return _Page(self.printed)


@pytest.fixture
def slides(tmp_path, monkeypatch) -> Path:
    monkeypatch.setattr(slides_pdf, "CACHE", tmp_path / "cache")
    site = tmp_path / "slides"
    (site / "chapters").mkdir(parents=True)
    (site / "_static").mkdir()
    (site / "_static" / "deck.css").write_text("body {}")
    decks = []
    for name in ("01_a", "02_b"):
        (site / "chapters" / f"{name}.html").write_text(f"<section>{name}</section>")
        decks.append({"name": name, "file": f"chapters/{name}.html", "pdf": f"pdf/{name}.pdf",
                      "handout": f"pdf/{name}-notes.pdf"})
    (site / "decks.json").write_text(json.dumps(decks))
    return site


def _print(site: Path, **kw) -> list[str]:
    browser = _Browser()
    rows = slides_pdf.print_decks(site, browser=browser, **kw)
    assert sorted(r["name"] for r in rows) == ["01_a", "02_b"] and all(r["slides"] == 7 for r in rows)
    for r in rows:
        assert Path(r["pdf"]).read_bytes().endswith(b"print-pdf")          # each file holds its own print
        assert Path(r["handout"]).read_bytes().endswith(b"showNotes=separate-page")
    return sorted(browser.printed)


def test_a_deck_is_printed_again_only_when_what_it_shows_changed(slides):
    both = ["01_a-notes.pdf", "01_a.pdf", "02_b-notes.pdf", "02_b.pdf"]
    assert _print(slides) == both                                   # first run: everything
    assert _print(slides) == []                                     # nothing changed: copied from the cache
    (slides / "pdf" / "01_a.pdf").unlink()                          # a rebuilt deck folder (no pdf/): copied back
    assert _print(slides) == [] and (slides / "pdf" / "01_a.pdf").is_file()
    (slides / "chapters" / "02_b.html").write_text("<section>02_b, changed</section>")
    assert _print(slides) == ["02_b-notes.pdf", "02_b.pdf"]        # one deck changed: only it
    (slides / "_static" / "deck.css").write_text("body { color: red }")
    assert _print(slides) == both                                   # a file every deck loads: all of them
    (slides / "index.html").write_text("<a href='pdf/01_a.pdf'>")   # the index is not printed
    assert _print(slides) == []
    assert _print(slides, force=True) == both
