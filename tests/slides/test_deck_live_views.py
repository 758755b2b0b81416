"""The live views on the deck slides, in headless Chromium at 1280x720, opened from a copy of the deck
folder alone (``file://``, as from a USB stick: the views come from the classic bundle ``jac-live.js``).

On every deck slide that holds a live view (``.jac-live``, mounted by the
``{live-view}`` directive): an input event on one of its sliders changes the
displayed numbers to the library's values (the JupyterLab widget classes of
``jacobians.widgets.live`` and ``jacobians.widgets.live_spatial`` compute them
at the same state), a key pressed in a focused slider moves the slider and not
the deck, the slide still holds everything after the change, and, once the
focus has left the view, ArrowRight moves to the next slide (ArrowLeft to the
previous one from a deck's last slide). The decks of
chapters 1, 3, 4, 6, 7 and 9 must have their live view on a slide, and every label drawn
in a view is at least 24 px on the slide. Screenshots go to
``_build/test-artifacts/slides/live-*.png`` (not committed).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import pytest
from live_data import SHOWN_JS
from tools import build_slides

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
ARTIFACTS = ROOT / "_build" / "test-artifacts" / "slides"
#: BOOK_SHOTS=0 (make test): no screenshots (for a person to look at; no test reads them)
SHOTS = os.environ.get("BOOK_SHOTS", "1") != "0"
SOURCES = [s for s in build_slides.deck_sources() if "{live-view}" in s.read_text(encoding="utf-8")]
#: decks whose live view must be on a slide (all four views are in the decks)
MUST = {"01_twists": "story", "03_body_jacobian": "story", "07_conversions": "story",
        "04_space_vs_body": "columns_explorer", "06_analytic_jacobian": "gimbal_lock",
        "09_using_the_jacobian": "resolved_rate"}

READ = SHOWN_JS  # what the view shows, as its spec's check reads it

SET = """([el, sel, v]) => {
  const s = el.querySelector(sel);
  s.value = String(v);
  s.dispatchEvent(new Event("input", { bubbles: true }));
  return s.value;
}"""

OUTSIDE = """() => {
  const slide = Reveal.getCurrentSlide(), box = slide.getBoundingClientRect();
  const visible = (e) => { const r = e.getBoundingClientRect();
    return r.width > 0 && r.height > 0 && getComputedStyle(e).visibility !== "hidden" && !e.closest("aside.notes"); };
  return [...slide.querySelectorAll("*")].filter((e) => visible(e) && !e.closest("mjx-assistive-mml")).filter((e) => {
    const r = e.getBoundingClientRect();
    return r.left < box.left - 2 || r.right > box.right + 2 || r.top < box.top - 2 || r.bottom > box.bottom + 2;
  }).map((e) => e.tagName + "." + (e.getAttribute("class") || "")).slice(0, 5);
}"""


#: the drawn labels of the current slide's live view, in CSS px of the 1280x720 slide (unscaled)
SVG_LABELS = """() => {
  const scale = Reveal.getScale(), out = [];
  for (const t of Reveal.getCurrentSlide().querySelectorAll(".jac-live svg text")) {
    if (!t.getClientRects().length || !t.textContent.trim()) continue;
    const m = t.getScreenCTM();
    out.push([t.textContent.trim(), parseFloat(getComputedStyle(t).fontSize) * Math.hypot(m.a, m.b) / scale]);
  }
  return out;
}"""
MIN_LABEL_PX = 24 - 0.5   # 24 px on a slide, less half a pixel of rounding


def _views() -> dict[str, tuple[str, float, Any]]:
    """view -> (the slider moved, its value before the key press: the spec's probe; the check of what the view
    shows against the library: the spec's)."""
    from jacobians.widgets.live import VIEWS as SPECS

    return {name: (*spec.probe, _checked(spec.check)) for name, spec in SPECS.items()}


def _checked(check: Any) -> Any:
    """A spec's check as the test calls it: on what the view shows (the element is not needed)."""
    return lambda got, el=None: check(got)


VIEWS = _views()


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_live_view_slides_show_the_librarys_numbers_and_arrows_still_move_on(deck_browser, usb, source):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    page = deck_browser.new_page(viewport={"width": 1280, "height": 720})
    problems: list[str] = []
    page.on("console", lambda m: problems.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: problems.append(str(e)))
    try:
        page.goto((usb / build_slides.deck_path(source)).as_uri(), wait_until="load")
        page.wait_for_selector("html[data-math-done]", state="attached", timeout=60_000)
        total = page.evaluate("Reveal.getTotalSlides()")
        with_view = page.evaluate("""() => Reveal.getSlides().map((s, i) => s.querySelector(".jac-live") ? i : -1)
          .filter((i) => i >= 0)""")
        if source.stem in MUST:
            assert with_view, f"{source.stem}: no slide holds the live view {MUST[source.stem]}"
        for i in with_view:
            page.evaluate(f"Reveal.slide({i})")
            el = page.wait_for_selector("section.present .jac-live[data-ready='1']", state="attached")
            view = el.get_attribute("data-view")
            sel, value, check = VIEWS[view]
            check(el.evaluate(READ), el)                               # as mounted
            before = el.evaluate(READ)["markup"]
            assert page.evaluate(SET, [el, sel, value]) == str(value)      # an input event
            got = el.evaluate(READ)
            assert got["markup"] != before, f"slide {i}: the input changed nothing"
            check(got, el)
            small = [(t, round(px, 1)) for t, px in page.evaluate(SVG_LABELS) if px < MIN_LABEL_PX]
            assert not small, f"slide {i}: labels in the drawing below 24 px: {small}"
            if view == "gimbal_lock":  # 1 degree from the ZYX lock: |det B| = cos 89 deg < 0.1, a warning
                assert math.isclose(got["theta"][1], math.radians(89), abs_tol=1e-12) and got["level"] == "warning"
            assert "NaN" not in got["text"] and "Infinity" not in got["text"]
            assert page.evaluate(OUTSIDE) == [], f"slide {i}: outside the slide after the change"
            # a key in the focused slider moves the slider, not the deck
            el.query_selector(sel).focus()
            page.keyboard.press("ArrowRight")
            assert page.evaluate("Reveal.getIndices().h") == i
            after = el.evaluate(READ)
            assert after["markup"] != got["markup"], f"slide {i}: ArrowRight in the slider changed nothing"
            check(after, el)
            if SHOTS:
                page.screenshot(path=str(ARTIFACTS / f"live-{source.stem}-{i:02d}.png"))
            # focus out of the view (a click on the heading), then ArrowRight moves on (ArrowLeft back on the last)
            page.locator("section.present h2, section.present h1").first.click()
            assert page.evaluate("document.activeElement.closest('.jac-live')") is None
            key, to = ("ArrowRight", i + 1) if i + 1 < total else ("ArrowLeft", i - 1)
            page.keyboard.press(key)
            page.wait_for_function(f"Reveal.getIndices().h === {to}", timeout=5_000)
        assert problems == [], problems
    finally:
        page.close()


def test_every_registered_view_has_its_library_check():
    """A view added to jacobians.widgets.live has its slide's numbers compared with its widget's here: its spec
    gives the check."""
    from jacobians.widgets.live import VIEWS as SPECS

    missing = sorted(name for name, spec in SPECS.items() if spec.check is None)
    assert not missing, f"views whose spec has no check: {missing}"


def test_the_live_views_data_model_is_plain_json():
    """What the slide's view reads is the model the library builds (no NaN), for each registered view."""
    from jacobians.widgets.live import VIEWS as SPECS

    for spec in SPECS.values():
        json.dumps(spec.model_from_options(spec.example), allow_nan=False)
