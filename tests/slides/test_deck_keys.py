"""Keys belong to the presenter: on every live-view slide, after a touch of each control, a key a clicker
sends (PageDown, Space or N; all three, PageUp and B after the first control) still changes the slide (headless Chromium, the decks opened from a copy of ``slides/`` alone).

The rule (``_ext/decks_static/course_decks.js``): PageUp, PageDown, Space, N, P, Esc, B and the number
keys always reach reveal.js; the arrow keys move a control only while it is held (dragged, or focused,
clicked or changed less than a second ago), and otherwise change the slide.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from tools import build_slides

SOURCES = [s for s in build_slides.deck_sources() if "{live-view}" in s.read_text(encoding="utf-8")]
#: what a clicker sends to go on (a Logitech R400: PageDown; a keyboard: Space, N)
FORWARD = ("PageDown", "Space", "n")
HOLD_S = 1.0

CONTROLS = """(i) => [...Reveal.getSlides()[i].querySelectorAll(".jac-live input, .jac-live select, .jac-live button")]
  .map((c, k) => { c.setAttribute("data-test-control", String(k));
    return { k, tag: c.tagName.toLowerCase(), type: c.type || "", shown: c.getClientRects().length > 0 && !c.disabled }; })
  .filter((c) => c.shown)"""


def _open(browser: Any, usb: Path, source: Path) -> Any:
    page = browser.new_page(viewport={"width": 1280, "height": 720})
    page.goto((usb / build_slides.deck_path(source)).as_uri(), wait_until="load")
    page.wait_for_selector("html[data-math-done]", state="attached", timeout=60_000)
    return page


def _touch(page: Any, control: dict[str, Any]) -> None:
    """What a lecturer does to a control with the mouse: drag a slider's thumb, pick an option, press a button."""
    handle = page.query_selector(f"section.present [data-test-control='{control['k']}']")
    if control["tag"] == "select":
        values = handle.evaluate("(s) => [...s.options].map((o) => o.value)")
        handle.select_option(values[-1] if handle.evaluate("(s) => s.value") != values[-1] else values[0])
        return
    box = handle.bounding_box()
    y = box["y"] + box["height"] / 2
    if control["type"] == "range":
        page.mouse.move(box["x"] + box["width"] * 0.3, y)
        page.mouse.down()
        page.mouse.move(box["x"] + box["width"] * 0.6, y, steps=2)
        page.mouse.up()
    else:
        page.mouse.click(box["x"] + box["width"] / 2, y)


def _at(page: Any, i: int) -> None:
    page.evaluate(f"Reveal.slide({i})")


def _now_at(page: Any, i: int) -> bool:
    """Whether the deck shows slide ``i`` (reveal.js changes slides on the key press itself; one retry)."""
    if page.evaluate("Reveal.getIndices().h") == i:
        return True
    page.wait_for_timeout(150)
    return page.evaluate("Reveal.getIndices().h") == i


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_clicker_keys_change_the_slide_after_each_control_is_touched(deck_browser, usb, source):
    page = _open(deck_browser, usb, source)
    bad: list[str] = []
    try:
        with_view = page.evaluate("Reveal.getSlides().map((s, i) => s.querySelector('.jac-live') ? i : -1)"
                                  ".filter((i) => i >= 0)")
        total = page.evaluate("Reveal.getTotalSlides()")
        assert with_view
        for i in with_view:
            _at(page, i)
            page.wait_for_selector("section.present .jac-live[data-ready='1']", state="attached")
            controls = page.evaluate(CONTROLS, i)
            assert controls, f"slide {i + 1}: no control in the live view"
            for n, c in enumerate(controls):
                # the first control of a view: PageDown, Space and N each; the others one of them in turn
                # (the rule does not depend on the control, and each press costs a page round trip)
                for key in (FORWARD if n == 0 else (FORWARD[n % len(FORWARD)],)):
                    _at(page, i)
                    _touch(page, c)
                    page.keyboard.press(key)
                    if not _now_at(page, min(i + 1, total - 1)):
                        bad.append(f"slide {i + 1}: {key} after touching {c['tag']} #{c['k']} did not go on")
                if n:
                    continue
                # PageUp goes back, and B (black screen) pauses, after a touch
                _at(page, i)
                _touch(page, c)
                page.keyboard.press("PageUp")
                if not _now_at(page, i - 1):
                    bad.append(f"slide {i + 1}: PageUp after touching {c['tag']} #{c['k']} did not go back")
                _at(page, i)
                _touch(page, c)
                page.keyboard.press("b")
                if not page.evaluate("Reveal.isPaused()"):
                    bad.append(f"slide {i + 1}: B after touching {c['tag']} #{c['k']} did not black the screen")
                page.keyboard.press("b")
    finally:
        page.close()
    assert not bad, "\n".join(bad)


def _one_deck_per_view() -> list[Path]:
    """The hold-and-release rule is the deck's, not a view's: one deck per kind of live view is enough."""
    seen: dict[str, Path] = {}
    for source in SOURCES:
        text = source.read_text(encoding="utf-8")
        kind = text.split("{live-view}", 1)[1].split(None, 1)[0]
        seen.setdefault(kind, source)
    return list(seen.values())


ARROW_DECKS = _one_deck_per_view()


@pytest.mark.parametrize("source", ARROW_DECKS, ids=[s.stem for s in ARROW_DECKS])
def test_arrows_move_a_held_slider_then_return_to_the_deck(deck_browser, usb, source):
    """Right after a drag the arrows move the slider; after a second idle, or Esc, they change the slide."""
    page = _open(deck_browser, usb, source)
    try:
        i = page.evaluate("Reveal.getSlides().findIndex((s) => s.querySelector('.jac-live input[type=range]'))")
        total = page.evaluate("Reveal.getTotalSlides()")
        if i < 0:
            pytest.skip("no slider in this deck's live views")
        _at(page, i)
        page.wait_for_selector("section.present .jac-live[data-ready='1']", state="attached")
        page.wait_for_timeout(HOLD_S * 1000)   # nothing held yet
        slider = {"tag": "input", "type": "range",
                  "k": next(c["k"] for c in page.evaluate(CONTROLS, i) if c["type"] == "range")}
        loc = page.query_selector(f"section.present [data-test-control='{slider['k']}']")
        _touch(page, slider)
        before = loc.input_value()
        page.keyboard.press("ArrowLeft" if i + 1 < total else "ArrowRight")
        assert page.evaluate("Reveal.getIndices().h") == i, "an arrow right after the drag changed the slide"
        assert loc.input_value() != before, "an arrow right after the drag did not move the slider"
        # idle: the arrows are the deck's again
        page.wait_for_timeout(HOLD_S * 1000 + 300)
        assert page.evaluate("document.activeElement.closest('.jac-live')") is None
        moved = loc.input_value()
        page.keyboard.press("ArrowRight")
        assert _now_at(page, min(i + 1, total - 1)), "an arrow a second after the drag did not change the slide"
        assert loc.input_value() == moved
        # Esc right after a drag: the slider lets go and reveal.js gets the key (the overview)
        _at(page, i)
        _touch(page, slider)
        page.keyboard.press("Escape")
        assert page.evaluate("Reveal.isOverview()"), "Esc after a drag did not reach reveal.js"
        assert page.evaluate("document.activeElement.closest('.jac-live')") is None
        page.keyboard.press("Escape")
        assert not page.evaluate("Reveal.isOverview()")
        # T shows the pacing timer: time against the plan, the sum of the notes' minutes
        page.keyboard.press("t")
        pace = page.evaluate("document.querySelector('.deck-pacing:not([hidden])')?.textContent || ''")
        assert " min" in pace and "plan here" in pace, pace
    finally:
        page.close()
