"""The live views' colours on their own ground, light and dark: lines >= 3:1, text >= 4.5:1 (WCAG 1.4.11, 1.4.3).

The views draw the library's Okabe–Ito palette through one table,
``lib/jacobians/widgets/live/palette.js`` (``SWATCHES``): each colour
has a shade for a line and one for text, on the light ground and on the dark
one. The view paints its ground itself (``THEME_CSS``), so the ratios below are
the ratios a reader sees in either mode. The browser side (the computed colours
of every drawn element of every view, in both modes) is checked by
``tests/browser/test_live_theme.py``.
"""

from __future__ import annotations

import colorsys
import re
from pathlib import Path

import pytest

from jacobians.plotting.style import COLUMN_COLORS, PALETTE
from jacobians.widgets import live

LIVE = Path(__file__).resolve().parents[1] / "lib" / "jacobians" / "widgets" / "live"
SOURCE = (LIVE / "palette.js").read_text(encoding="utf-8")
HEX = r'"(#[0-9A-Fa-f]{6})"'


def luminance(hex_colour: str) -> float:
    def channel(c: int) -> float:
        v = c / 255
        return v / 12.92 if v <= 0.03928 else ((v + 0.055) / 1.055) ** 2.4
    h = hex_colour.lstrip("#")
    r, g, b = (int(h[i:i + 2], 16) for i in (0, 2, 4))
    return 0.2126 * channel(r) + 0.7152 * channel(g) + 0.0722 * channel(b)


def contrast(a: str, b: str) -> float:
    hi, lo = sorted((luminance(a), luminance(b)), reverse=True)
    return (hi + 0.05) / (lo + 0.05)


def _grounds() -> tuple[str, str]:
    m = re.search(rf"export const GROUND = \{{ light: {HEX}, dark: {HEX} \}};", SOURCE)
    assert m, "GROUND not found in palette.js"
    return m.group(1), m.group(2)


def _swatches() -> dict[str, dict[str, tuple[str, ...]]]:
    body = re.search(r"export const SWATCHES = \{(.*?)\n\};", SOURCE, re.S)
    assert body, "SWATCHES not found in palette.js"
    rows = re.findall(rf"(\w+): \{{ hex: {HEX}, line: \[{HEX}, {HEX}\], text: \[{HEX}, {HEX}\] \}}", body.group(1))
    assert len(rows) == body.group(1).count("hex:"), "a swatch is not written as the test reads it"
    return {name: {"hex": (h,), "line": (l0, l1), "text": (t0, t1)} for name, h, l0, l1, t0, t1 in rows}


GROUND = _grounds()
SWATCHES = _swatches()
MODES = {"light": 0, "dark": 1}
CASES = [(name, mode) for name in SWATCHES for mode in MODES]


def test_contrast_formula_on_known_pairs():
    assert contrast("#000000", "#FFFFFF") == pytest.approx(21.0)
    assert contrast("#767676", "#FFFFFF") == pytest.approx(4.54, abs=0.01)  # the WCAG-known 4.5:1 grey


@pytest.mark.parametrize("name,mode", CASES)
def test_every_line_is_3_to_1_on_its_ground(name, mode):
    k = MODES[mode]
    c = SWATCHES[name]["line"][k]
    assert contrast(c, GROUND[k]) >= 3.0, f"{name} as a line in {mode} mode: {c} on {GROUND[k]}"


@pytest.mark.parametrize("name,mode", CASES)
def test_every_text_colour_is_4_5_to_1_on_its_ground(name, mode):
    k = MODES[mode]
    c = SWATCHES[name]["text"][k]
    assert contrast(c, GROUND[k]) >= 4.5, f"{name} as text in {mode} mode: {c} on {GROUND[k]}"


def _hue(c: str) -> tuple[float, float]:
    r, g, b = (int(c[i:i + 2], 16) / 255 for i in (1, 3, 5))
    h, _, s = colorsys.rgb_to_hls(r, g, b)
    return 360 * h, s


@pytest.mark.parametrize("name", [n for n in SWATCHES if _hue(SWATCHES[n]["hex"][0])[1] > 0.2])
def test_each_shade_keeps_the_hue_of_the_library_colour(name):
    """A shade is the same colour, lighter or darker: its hue within 12 degrees of the library's (a reader matches
    a line to its legend and to the chapter's figures by hue)."""
    h0, _ = _hue(SWATCHES[name]["hex"][0])
    for c in (*SWATCHES[name]["line"], *SWATCHES[name]["text"]):
        h, _ = _hue(c)
        assert min(abs(h - h0), 360 - abs(h - h0)) <= 12, f"{name}: {c} has hue {h:.0f}, the library's {h0:.0f}"


def test_every_library_colour_has_a_swatch():
    """graphic() and ink() map a library colour to its swatch by hex: one missing would be drawn as given, on
    either ground."""
    known = {s["hex"][0].upper() for s in SWATCHES.values()}
    drawn = {c.upper() for c in (*PALETTE.values(), *COLUMN_COLORS)} - {"#F0E442"}  # yellow: no view draws it
    assert drawn <= known, f"no swatch for {sorted(drawn - known)}"


def test_slider_limit_comes_from_the_library_only():
    """The joint sliders' range is set in one place, jacobians.widgets.live.LIMIT, and reaches the views with their
    model (ui.js sliderLimit reads it and refuses a model without it); no module of the views writes it again."""
    from jacobians.widgets import live_spatial as spatial

    assert live.planar_model("planar_3r")["limit"] == live.LIMIT
    assert spatial.columns_model()["limit"] == live.LIMIT
    for js in sorted(LIVE.rglob("*.js")):
        text = js.read_text(encoding="utf-8")
        assert not re.search(r"\bconst\s+LIMIT\b|\b3\.14\b", text), f"{js.name} writes the sliders' range again"
