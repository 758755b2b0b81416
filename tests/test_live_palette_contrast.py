"""The live views' colours on their white ground: lines >= 3:1, coloured text >= 4.5:1 (WCAG 1.4.11, 1.4.3).

The views draw the library's Okabe–Ito palette; ``ui.js`` darkens the hues
that are too light on white (``graphic``) and gives each hue a darker shade
for text (``ink``). In dark mode the views keep their white panel
(``_theme/course.css``), so the same ratios hold in both modes.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from jacobians.plotting.style import PALETTE

UI = (Path(__file__).resolve().parents[1] / "lib" / "jacobians" / "widgets" / "static" / "live" / "ui.js").read_text(
    encoding="utf-8")


def luminance(hex_colour: str) -> float:
    def channel(c: int) -> float:
        v = c / 255
        return v / 12.92 if v <= 0.03928 else ((v + 0.055) / 1.055) ** 2.4
    h = hex_colour.lstrip("#")
    r, g, b = (int(h[i:i + 2], 16) for i in (0, 2, 4))
    return 0.2126 * channel(r) + 0.7152 * channel(g) + 0.0722 * channel(b)


def contrast_on_white(c: str) -> float:
    return 1.05 / (luminance(c) + 0.05)


def js_map(name: str) -> dict[str, str]:
    body = re.search(rf"const {name} = \{{(.*?)\}};", UI, re.S)
    assert body, name
    return {k.upper(): v.upper() for k, v in re.findall(r'"(#[0-9A-Fa-f]{6})": "(#[0-9A-Fa-f]{6})"', body.group(1))}


ON_WHITE = js_map("ON_WHITE")
INK = js_map("INK")
COLUMNS = re.findall(r"#[0-9A-Fa-f]{6}", re.search(r"export const COLUMN_COLORS = \[(.*?)\]", UI).group(1))
LIBRARY = sorted({c.upper() for c in PALETTE.values() if re.fullmatch(r"#[0-9A-Fa-f]{6}", c)})


def test_contrast_formula_on_known_pairs():
    assert contrast_on_white("#000000") == pytest.approx(21.0)
    assert contrast_on_white("#767676") == pytest.approx(4.54, abs=0.01)  # the WCAG-known 4.5:1 grey


@pytest.mark.parametrize("colour", sorted(set(COLUMNS) | set(LIBRARY)))
def test_every_colour_drawn_as_a_line_is_3_to_1(colour):
    drawn = ON_WHITE.get(colour.upper(), colour)
    if colour.upper() in ("#FFFFFF", "#F0E442"):  # white fills; yellow is not drawn by any view
        pytest.skip("not drawn as a line")
    assert contrast_on_white(drawn) >= 3.0, f"{colour} drawn as {drawn}"


@pytest.mark.parametrize("colour", sorted(set(COLUMNS) | set(ON_WHITE)))
def test_every_colour_written_as_text_is_4_5_to_1(colour):
    shown = INK.get(colour.upper(), colour)
    assert contrast_on_white(shown) >= 4.5, f"{colour} written as {shown}"
