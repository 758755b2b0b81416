"""_ext/lazy_frames.py: an animation's inline frames become files, its image a still, the rest fetched on play."""

from __future__ import annotations

import base64
import io
import re

import lazy_frames
import matplotlib.pyplot as plt
import pytest

from jacobians.plotting import FrameSource, animation_html


def _player(n: int = 4) -> str:
    fig, ax = plt.subplots(figsize=(2, 1.5), dpi=30)
    ax.set_xlim(0, n)
    (dot,) = ax.plot([0.0], [0.5], "o")
    return animation_html(FrameSource(fig, lambda k: dot.set_data([k], [0.5]), n, moving=[dot])).data


def test_frames_become_files_and_the_image_a_still():
    html = _player(4)
    inline = [base64.b64decode(b.replace("\\\n", "")) for _, b in lazy_frames._FRAME.findall(html)]
    assert len(inline) == 4
    written: dict[str, bytes] = {}
    out, moved = lazy_frames.externalise(html, lambda name, data: written.setdefault(name, data), "../")
    assert moved == 4
    assert "data:image/png;base64" not in out
    urls = re.findall(r'frames\[\d+\] = "([^"]+)"', out)
    assert urls == [f"../_images/anim/{name}" for name in
                    [lazy_frames.hashlib.sha256(d).hexdigest()[:24] + ".png" for d in inline]]
    # every file holds the frame that was inline, byte for byte
    assert [written[u.rsplit("/", 1)[1]] for u in urls] == inline
    # the player's image shows frame 0 without JavaScript, with its size, lazily
    img = re.search(r"<img[^>]*_anim_img[^>]*>", out).group(0)
    assert f'src="{urls[0]}"' in img and 'loading="lazy"' in img
    from PIL import Image

    w, h = Image.open(io.BytesIO(inline[0])).size
    assert f'width="{w}"' in img and f'height="{h}"' in img
    # the constructor no longer loads every frame; the lazy methods follow the class
    assert "this.frames[i] = new Image();" not in out
    assert out.count("P.fetch_frames = function") == 1


def test_html_without_inline_frames_is_unchanged():
    assert lazy_frames.externalise("<p>no animation</p>", lambda *a: None, "") == ("<p>no animation</p>", 0)


def test_a_changed_player_is_an_error_not_a_silent_heavy_page():
    html = _player(2).replace("this.frames[i] = new Image();", "this.frames[i] = makeImage();")
    with pytest.raises(ValueError, match="player has changed"):
        lazy_frames.externalise(html, lambda *a: None, "")


def test_not_a_png_is_an_error():
    html = _player(2)
    bad = lazy_frames._FRAME.sub(
        lambda m: f'frames[{m.group(1)}] = "data:image/png;base64,{base64.b64encode(b"GIF89a" + bytes(30)).decode()}"',
        html)
    with pytest.raises(ValueError, match="not a PNG"):
        lazy_frames.externalise(bad, lambda *a: None, "")


def test_book_images_load_lazily_and_the_decks_are_left_alone(tmp_path):
    """On the book's HTML builder every image node gets loading="lazy" (an image that already says how it loads
    keeps it), and docutils' HTML writer, which Sphinx's calls for every image, writes it; the decks' builder
    (revealjs) is left alone: a slide's figure must be there when the slide is shown or printed."""
    from types import SimpleNamespace

    from docutils import nodes
    from docutils.core import publish_from_doctree
    from docutils.utils import new_document

    def page() -> nodes.document:
        doc = new_document("page.md")
        doc += nodes.image(uri="_images/fig.png", alt="a figure")
        doc += nodes.image(uri="_images/top.png", alt="kept eager", loading="link")
        return doc

    def run(builder: str) -> nodes.document:
        doc = page()
        lazy_frames.lazy_frames(SimpleNamespace(builder=SimpleNamespace(name=builder), outdir=str(tmp_path)),
                                doc, "chapters/page")
        return doc

    book = run("html")
    assert [im.get("loading") for im in book.findall(nodes.image)] == ["lazy", "link"]
    html = publish_from_doctree(book, writer_name="html5", settings_overrides={"output_encoding": "unicode"})
    assert '<img alt="a figure" loading="lazy" src="_images/fig.png" />' in html, html
    assert [im.get("loading") for im in run("revealjs").findall(nodes.image)] == [None, "link"]
