"""The built chapters' animations: no frame inside the HTML, a still without JavaScript, the frames on play.

``_ext/lazy_frames.py`` moves each animation's frames into ``_images/anim/``.
Read from the built site (no browser): no page carries an inline frame, and
each player's image has a still that exists, with alt text. In Chromium, one
chapter page: its first visit fetches no frame but the stills it shows, and
pressing play fetches the frames and moves the image.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

#: a chapter with an animation near its top and one further down (the first visit must not fetch their frames)
PAGE = "chapters/02_space_jacobian.html"
INLINE = re.compile(r'frames\[\d+\] = "data:image/png;base64,')
IMG = re.compile(r"<img\b[^>]*\bid=\"_anim_img[0-9a-f]+\"[^>]*>")


def _chapters(book_html: Path) -> list[Path]:
    return sorted((book_html / "chapters").glob("*.html"))


def test_no_page_carries_its_animation_frames_inline(book_html):
    pages = _chapters(book_html)
    heavy = [p.name for p in pages if INLINE.search(p.read_text(encoding="utf-8"))]
    assert not heavy, f"animation frames inline in {heavy} (is _ext/lazy_frames.py loaded?)"


def test_every_player_shows_a_still_that_exists(book_html):
    players = 0
    for page in _chapters(book_html):
        text = page.read_text(encoding="utf-8")
        for img in IMG.findall(text):
            players += 1
            src = re.search(r'\ssrc="([^"]+)"', img)
            alt = re.search(r'\salt="([^"]+)"', img)
            assert src, f"{page.name}: an animation without a still: {img[:120]}"
            assert alt and alt.group(1).strip(), f"{page.name}: an animation's still has no alt text"
            still = (page.parent / src.group(1)).resolve()
            assert still.is_file() and still.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{page.name}: {src.group(1)}"
            frames = re.findall(r'frames\[\d+\] = "([^"]+)"', text)
            assert src.group(1) in frames
    assert players >= 9, f"only {players} animations found in the chapters (ch02, 04-06, 08-12 have them)"


def test_first_visit_fetches_no_frame_until_play(book_html, book_url, browser_context):
    if not (book_html / PAGE).exists():
        pytest.fail(f"{PAGE} is missing from the built site", pytrace=False)
    page = browser_context.new_page()
    anim: list[str] = []
    page.on("request", lambda r: anim.append(r.url) if "/_images/anim/" in r.url else None)
    page.route("**/*", lambda route: route.continue_())  # no HTTP cache: a first visit
    try:
        # "load": the page and its eager resources are in (the chapter never goes network-idle: its live views and
        # lazy images keep fetching as the reader scrolls, so that state is no condition to wait for)
        page.goto(book_url + PAGE, wait_until="load", timeout=120_000)  # (a long page on a loaded machine)
        stills = page.evaluate("() => Array.from(document.querySelectorAll('.animation img')).map(i => i.src)")
        assert len(stills) >= 1
        # before any play, only stills may have been fetched (and only those near the screen: lazy images)
        assert set(anim) <= set(stills), f"frames fetched before play: {sorted(set(anim) - set(stills))[:3]}"
        first = page.locator("div.animation").first
        first.scroll_into_view_if_needed()
        img = first.locator("img").first
        page.wait_for_function("i => i.complete && i.naturalWidth > 0", arg=img.element_handle(), timeout=15_000)
        before = img.evaluate("i => i.src")
        text = (book_html / PAGE).read_text(encoding="utf-8")
        own = {book_url + "chapters/" + u for u in
               re.findall(r'frames\[\d+\] = "([^"]+)"', text[:text.index("new Animation(frames")])}
        own = {page.evaluate("u => new URL(u).href", u) for u in own}  # ../ resolved as the browser does
        first.locator("button[onclick*='play_animation']").first.click()
        page.wait_for_function("([i, s]) => i.src !== s", arg=[img.element_handle(), before], timeout=15_000)
        first.locator("button[onclick*='pause_animation']").first.click()
        assert len(own) > 2
        for _ in range(300):  # the frames' requests, as they are made (at most 60 s)
            if own <= set(anim):
                break
            page.wait_for_timeout(200)
        assert own <= set(anim), f"play fetched {len(own & set(anim))} of the animation's {len(own)} frame files"
    finally:
        page.close()
