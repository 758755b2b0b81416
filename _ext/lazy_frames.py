"""Animation frames as files of their own, fetched when the reader plays the animation.

A notebook's animation (``jacobians.plotting.animation_html``, matplotlib's
HTML player) carries every frame inline as a base64 PNG, so the notebook is
self-contained in JupyterLab. In the book that made a chapter page 300-450 KB
of HTML, downloaded (and parsed) on every first visit even by a reader who
never plays it. For the book's HTML builder only, each animation is rewritten:

- every frame becomes a PNG file ``_images/anim/<sha256>.png`` (named by its
  content: a frame shared by two pages, or unchanged between builds, is one
  file), and the player gets the files' addresses instead of the data;
- the player's ``<img>`` shows the first frame as a plain ``src`` with
  ``loading="lazy"``, its size and its alt text: the still a reader without
  JavaScript, a printout and the whole-book PDF (``tools/book_pdf.py``) see;
- the player fetches the other frames only when the reader first plays, steps
  or drags the animation, and while a frame is still on its way it waits on
  the frame it shows rather than flashing a blank one.

Every other image of a book page (the figures) gets ``loading="lazy"`` too:
the browser fetches it as it nears the screen, so on a slow connection the
text, the math and the first screen's figures do not share the line with a
chapter's worth of figures further down. Printing loads them all first
(``tools/book_pdf.py``), and so do the browser checks (``bookcheck``).

The notebooks and the decks (``revealjs`` builder) are left as they are.
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import re
import struct
from pathlib import Path
from typing import Any

from docutils import nodes
from sphinx.application import Sphinx

#: the folder of the frame files, under the built site
FRAME_DIR = "_images/anim"

# one frame of matplotlib's HTMLWriter player (base64 lines may be joined by "\" + newline)
_FRAME = re.compile(r'frames\[(\d+)\] = "data:image/png;base64,([^"]*)"')
# the player's frame image (an id made of "_anim_img" and the animation's uuid)
_IMG = re.compile(r'<img\b([^>]*)\bid="(_anim_img[0-9a-f]+)"([^>]*)>')
# the loop of matplotlib's Animation constructor that loads every frame at once
_PRELOAD = re.compile(
    r"for \(var i=0; i<frames\.length; i\+\+\)\s*\{\s*this\.frames\[i\] = new Image\(\);\s*"
    r"this\.frames\[i\]\.src = frames\[i\];\s*\}"
)
_LAZY_CONSTRUCTOR = """// frames are files (_ext/lazy_frames.py), fetched when the reader first plays or steps
    this.urls = frames;
    this.fetched = false;
    for (var i=0; i<frames.length; i++) { this.frames[i] = {src: frames[i], complete: i === 0}; }"""

#: after matplotlib's class: fetch the frames on the first play, step or drag, and never show one not yet here
_LAZY_METHODS = """<script>
(function () {
  var P = Animation.prototype;
  if (P.jacLazy) return;
  P.jacLazy = true;
  P.fetch_frames = function () {
    if (this.fetched || !this.urls) return;
    this.fetched = true;
    for (var i = 0; i < this.urls.length; i++) {
      var im = new Image();
      im.src = this.urls[i];
      this.frames[i] = im;
    }
  };
  var setFrame = P.set_frame;
  P.set_frame = function (frame) {
    if (frame !== 0 || this.fetched) this.fetch_frames();
    var want = this.frames[frame];
    if (this.direction !== 0 && want && !want.complete) {
      this.current_frame = frame - this.direction;  // try this frame again on the next tick
      return;
    }
    var img = document.getElementById(this.img_id);
    if (img.getAttribute('src') === this.urls[frame]) {
      this.current_frame = frame;
      document.getElementById(this.slider_id).value = frame;
      return;
    }
    setFrame.call(this, frame);
  };
  ['play_animation', 'reverse_animation'].forEach(function (name) {
    var run = P[name];
    P[name] = function () { this.fetch_frames(); return run.apply(this, arguments); };
  });
})();
</script>
"""


def _png_size(data: bytes) -> tuple[int, int]:
    """Width and height of a PNG from its IHDR chunk."""
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        raise ValueError("an animation frame is not a PNG")
    width, height = struct.unpack(">II", data[16:24])
    return int(width), int(height)


def externalise(html: str, write: Any, prefix: str) -> tuple[str, int]:
    """``html`` with its animations' inline frames replaced by files; and how many frames moved.

    ``write(name, data)`` stores a frame file (``name`` under :data:`FRAME_DIR`);
    ``prefix`` is the path from the page to the site's root (``""`` or ``"../"``).
    HTML without an inline frame comes back unchanged. A player that does not
    look like matplotlib's (its constructor or its frame image changed) is an
    error, so a matplotlib upgrade cannot silently bring the inline frames back.
    """
    found = list(_FRAME.finditer(html))
    if not found:
        return html, 0
    players = html.count("new Animation(frames")
    if players == 0 or len(_PRELOAD.findall(html)) != html.count("function Animation("):
        raise ValueError("lazy_frames: matplotlib's HTML player has changed (its constructor's frame loop "
                         "was not found); the frames cannot be made lazy")
    urls: list[str] = []
    stills: list[tuple[str, tuple[int, int]]] = []  # each player's first frame (frames restart at 0)
    for m in found:
        try:
            data = base64.b64decode(m.group(2).replace("\\\n", ""), validate=True)
        except binascii.Error as exc:
            raise ValueError(f"lazy_frames: frame {m.group(1)} of an animation is not base64 ({exc})") from exc
        url = f"{prefix}{FRAME_DIR}/{hashlib.sha256(data).hexdigest()[:24]}.png"
        write(url.rsplit("/", 1)[1], data)
        urls.append(url)
        if m.group(1) == "0":
            stills.append((url, _png_size(data)))
    if len(stills) != players:
        raise ValueError(f"lazy_frames: {players} players but {len(stills)} first frames in one output")
    out = _PRELOAD.sub(lambda m: _LAZY_CONSTRUCTOR, html)
    moved = iter(urls)
    out = _FRAME.sub(lambda m: f'frames[{m.group(1)}] = "{next(moved)}"', out)
    # the methods go right after each class definition (its <script> ends before the player's style)
    out = re.sub(r"(Animation\.prototype\.reverse_animation = function\(\)[\s\S]*?</script>)",
                 lambda m: m.group(1) + "\n" + _LAZY_METHODS, out)
    # each player's image (it comes before its frames) shows its first frame as a plain, lazily loaded still
    shown = iter(stills)

    def still(m: re.Match[str]) -> str:
        url, (w, h) = next(shown)
        attrs = re.sub(r'\s(src|loading|width|height|decoding)="[^"]*"', "", m.group(1) + m.group(3))
        return (f'<img{attrs.rstrip()} id="{m.group(2)}" src="{url}" width="{w}" height="{h}" '
                f'loading="lazy" decoding="async">')

    out, images = _IMG.subn(still, out)
    if images != players:
        raise ValueError(f"lazy_frames: {players} players but {images} frame images in one output")
    return out, len(found)


def lazy_frames(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    """Move the inline frames of the page's animations into files, and load the page's images lazily (book HTML
    builder only)."""
    if app.builder.name != "html":
        return
    for image in doctree.findall(nodes.image):
        image.setdefault("loading", "lazy")   # docutils' HTML writer: <img loading="lazy">
    folder = Path(app.outdir) / FRAME_DIR

    def write(name: str, data: bytes) -> None:
        path = folder / name
        if not path.exists():
            folder.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)

    prefix = "../" * docname.count("/")
    for raw in list(doctree.findall(nodes.raw)):
        if "html" not in raw.get("format", "").split():
            continue
        text = raw.astext()
        if "data:image/png;base64" not in text or "new Animation(frames" not in text:
            continue
        fixed, moved = externalise(text, write, prefix)
        if moved:
            new = nodes.raw(fixed, fixed, **{k: v for k, v in raw.attributes.items() if k != "ids"})
            new["ids"] = list(raw.get("ids", []))
            raw.replace_self(new)


def setup(app: Sphinx) -> dict[str, Any]:
    # after offline_fixes.fill_alt_text (default priority), which names the frame image
    app.connect("doctree-resolved", lazy_frames, priority=600)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
