"""_ext/accessibility.py: accessible names and zoomable decks (the browser's axe-core test checks the built site)."""

from __future__ import annotations

from types import SimpleNamespace

import accessibility as a11y

DECK_HEAD = ('<head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1.0, '
             'maximum-scale=1.0, user-scalable=no"><title>x</title></head><body></body>')


def test_deck_lets_the_reader_zoom_and_shows_a_readable_slide_number():
    out = a11y.fix_deck_html(DECK_HEAD)
    assert "user-scalable=no" not in out and "maximum-scale" not in out
    assert a11y.ZOOMABLE in out and out.count(a11y.SLIDE_NUMBER_STYLE) == 1
    assert a11y.fix_deck_html(out) == out  # a second pass changes nothing


def test_slide_number_veil_gives_white_text_at_least_4_5_to_1():
    # white text on black at alpha .75 over a white slide: the veil is 0.25 * 255 = 64 grey (#404040)
    def lum(v: float) -> float:
        c = v / 255
        return c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4
    veil = lum(0.25 * 255)
    assert (1.0 + 0.05) / (veil + 0.05) >= 4.5


def test_hidden_cell_summary_is_named_by_what_it_shows():
    writer = SimpleNamespace(body=[])
    a11y.visit_hidden_cell(writer, {"classes": ["above-input"], "prompt_show": "Show code cell source",
                                    "prompt_hide": "Hide code cell source"})
    html = "".join(writer.body)
    assert "<summary>" in html and "aria-label" not in html and "Show code cell source" in html


def test_search_button_template_has_no_name_apart_from_its_text():
    text = (a11y.TEMPLATES / "search-button-field.html").read_text(encoding="utf-8")
    assert "aria-label" not in text.split("#}", 1)[1] and "search-button__default-text" in text
    assert "aria-label=\"{{ _('Search') }}\"" in a11y._upstream_search_button().read_text(encoding="utf-8")
