"""The whole book as one PDF, printed from the built pages by Debian's Chromium.

Usage: python -m tools.book_pdf [SITE] [--toc _toc.yml] [--out SITE/manipulator-jacobians.pdf]

Every page of the table of contents, in its order, is opened from a local
server (the live views are ES modules, which Chromium does not load from
``file://``) in headless Chromium (Playwright, ``/usr/bin/chromium``; no
browser download), printed to A4 with the theme's print style (no sidebars,
no buttons), and the pages are joined into one PDF with a bookmark per page
(pypdf). The math is already typeset in the pages (``_ext/math_prerender.py``);
live views are printed once they have drawn, and
each animation as its first frame (its still). The theme's blurred shadows
are left out (Chromium stored each as a page-wide bitmap: 23 MB of PDF became
8.4 MB), and a raster figure more than ``PRINT_SCALE`` times its printed width
(none today) is redrawn at that size. ``make book`` runs it, and the book's
introduction links the PDF.
"""

from __future__ import annotations

import argparse
import functools
import http.server
import io
import sys
import threading
import time
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
PDF_NAME = "manipulator-jacobians.pdf"


def toc_pages(toc: Path) -> list[str]:
    """The built pages (``chapters/intro.html``, ...) in the order of a Jupyter Book ``_toc.yml``."""
    data = yaml.safe_load(toc.read_text(encoding="utf-8"))
    files = [data["root"]]

    def walk(entries: list[dict[str, Any]]) -> None:
        for entry in entries:
            if "file" in entry:
                files.append(entry["file"])
            for key in ("chapters", "sections"):
                walk(entry.get(key) or [])

    walk(data.get("parts") or [])
    walk(data.get("chapters") or [])
    return [f.removesuffix(".md").removesuffix(".ipynb") + ".html" for f in files]


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: Any) -> None:
        pass


#: the printed text width of an A4 page with the margins below, in CSS pixels (96 per inch): 182 mm
PRINT_WIDTH_PX = 688
#: pixels per CSS pixel kept in a printed figure: 1.6 is about 150 dots per inch on paper, sharp on screen and
#: in print at reading distance, and a quarter of the pixels of the figures' full size
PRINT_SCALE = 1.6
#: JPEG quality of a redrawn figure (Chromium's PDF keeps a JPEG as it is, and stores any other image as
#: uncompressed pixels under Flate)
JPEG_QUALITY = 0.88

#: every lazily loaded image (the animations' stills, _ext/lazy_frames.py) loaded before printing
EAGER_JS = """() => {
  document.querySelectorAll('img[loading=lazy]').forEach(i => { i.loading = 'eager'; });
  return Promise.allSettled(Array.from(document.images).map(i => i.complete ? null : i.decode()));
}"""

#: the math, typeset at build time as SVG (each glyph a path: in a PDF every use of a glyph is drawn again, which
#: made the sample 37.7 kB a printed page against the book's 29.8), typeset again for the print as CommonHTML, whose
#: glyphs are characters of MathJax's fonts (embedded once per font): the vendored MathJax, with the TeX macros of
#: _theme/math_menu.js's configuration, on every formula's TeX (data-tex) in one pass; returns how many
PRINT_MATH_JS = r"""async (staticUrl) => {
  const boxes = Array.from(document.querySelectorAll('[data-tex]'));
  if (!boxes.length) return 0;
  const cfg = document.getElementById('math-menu-config');
  const macros = cfg ? JSON.parse(cfg.textContent).macros || {} : {};
  window.MathJax = {
    loader: {paths: {mathjax: staticUrl + 'mathjax/es5'},
             load: ['input/tex-base', '[tex]/ams', '[tex]/newcommand', '[tex]/configmacros', '[tex]/noundefined',
                    'output/chtml']},
    tex: {packages: {'[+]': ['ams', 'newcommand', 'configmacros', 'noundefined']}, macros},
    startup: {typeset: false},
  };
  await new Promise((resolve, reject) => {
    const s = document.createElement('script');
    s.src = staticUrl + 'mathjax/es5/startup.js';
    s.onload = () => window.MathJax.startup.promise.then(resolve, reject);
    s.onerror = () => reject(new Error('MathJax could not be loaded for the print'));
    document.head.appendChild(s);
  });
  for (const box of boxes) {
    const eqno = box.querySelector(':scope > .eqno');
    box.textContent = box.tagName === 'DIV' ? '\\[' + box.dataset.tex + '\\]' : '\\(' + box.dataset.tex + '\\)';
    if (eqno) box.prepend(eqno);
  }
  await window.MathJax.typesetPromise(boxes);
  await document.fonts.ready;
  return boxes.length;
}"""

#: raster figures larger than they print are redrawn at PRINT_SCALE times their printed width, on white, in the
#: same place and size; returns how many it redrew
SHRINK_JS = r"""async ([printWidth, scale, quality]) => {
  let shrunk = 0;
  for (const img of Array.from(document.images)) {
    if (!img.complete || !img.naturalWidth || /\.svg($|[?#])|^data:image\/svg/.test(img.currentSrc)) continue;
    const shown = Math.min(img.getBoundingClientRect().width || img.naturalWidth, printWidth);
    const want = Math.ceil(shown * scale);
    if (img.naturalWidth <= want * 1.15) continue;
    const h = Math.max(1, Math.round(img.naturalHeight * want / img.naturalWidth));
    const canvas = document.createElement('canvas');
    canvas.width = want;
    canvas.height = h;
    const g = canvas.getContext('2d');
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, want, h);
    g.imageSmoothingQuality = 'high';
    g.drawImage(img, 0, 0, want, h);
    const w0 = img.naturalWidth, h0 = img.naturalHeight;
    img.removeAttribute('srcset');
    img.src = canvas.toDataURL('image/jpeg', quality);
    img.setAttribute('width', String(w0));
    img.setAttribute('height', String(h0));
    try { await img.decode(); } catch (e) { /* printed as it is */ }
    shrunk += 1;
  }
  return shrunk;
}"""

#: effects that Chromium's PDF cannot draw as vectors (blurred shadows, filters) are printed as page-wide bitmaps,
#: tens of kilobytes each, tens per chapter; on paper they are a faint grey edge, so the print goes without them
#: (":not(#none)" gives the rule an id's weight, above the theme's own "!important" shadows of admonitions)
NO_RASTER_CSS = ":not(#none), :not(#none)::before, :not(#none)::after { box-shadow: none !important; " \
                "text-shadow: none !important; filter: none !important; backdrop-filter: none !important; }"

#: a page is ready to print when its fonts are loaded and every live view has mounted (or 20 s passed)
READY_JS = """() => document.fonts.status === 'loaded'
  && Array.from(document.querySelectorAll('[data-model]')).every(v => v.dataset.ready === '1')"""


def build(site: Path, toc: Path, out: Path, context: Any = None) -> dict[str, Any]:
    """Print the pages of ``toc`` from ``site`` into ``out``; in a browser context of the caller's (Playwright),
    or in a Chromium of its own."""
    from pypdf import PdfWriter

    pages = toc_pages(toc)
    missing = [p for p in pages if not (site / p).is_file()]
    if missing:
        raise FileNotFoundError(f"book_pdf: pages of {toc.name} missing from {site}: {missing} (run make book)")
    handler = functools.partial(_Quiet, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    writer = PdfWriter()
    start = time.monotonic()
    try:
        if context is not None:
            shrunk = _print_pages(context, base, pages, writer)
        else:
            from playwright.sync_api import sync_playwright

            with sync_playwright() as pw:
                browser = pw.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
                try:
                    own = browser.new_context()
                    shrunk = _print_pages(own, base, pages, writer)
                    own.close()
                finally:
                    browser.close()
    finally:
        server.shutdown()
        server.server_close()
    writer.add_metadata({"/Title": "Manipulator Jacobians", "/Author": "The Manipulator Jacobians course team"})
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("wb") as f:
        writer.write(f)
    return {"pages": len(pages), "pdf_pages": len(writer.pages), "bytes": out.stat().st_size,
            "seconds": time.monotonic() - start, "shrunk": shrunk}


def _print_pages(context: Any, base: str, pages: list[str], writer: Any) -> int:
    """Print each page into ``writer``, a bookmark at its first page; returns the figures printed smaller."""
    from pypdf import PdfReader

    shrunk = 0
    page = context.new_page()
    try:
        page.set_viewport_size({"width": 1000, "height": 1400})
        for path in pages:
            page.emulate_media(media="screen")   # the live views mount (and report ready) on screen
            page.goto(base + path, wait_until="load", timeout=300_000)  # (minutes on a loaded machine)
            try:
                page.wait_for_function(READY_JS, timeout=20_000)
            except Exception:
                print(f"book_pdf: {path}: live views not ready after 20 s, printed as they are", file=sys.stderr)
            page.evaluate(PRINT_MATH_JS, base + "_static/")
            page.add_style_tag(content=NO_RASTER_CSS)
            page.evaluate(EAGER_JS)
            page.emulate_media(media="print")
            shrunk += page.evaluate(SHRINK_JS, [PRINT_WIDTH_PX, PRINT_SCALE, JPEG_QUALITY])
            title = page.title().split("—")[0].split(" | ")[0].strip() or path
            data = page.pdf(format="A4", print_background=True, display_header_footer=False,
                            margin={"top": "15mm", "bottom": "15mm", "left": "14mm", "right": "14mm"})
            first = len(writer.pages)
            for p in PdfReader(io.BytesIO(data)).pages:
                writer.add_page(p)
            writer.add_outline_item(title=title, page_number=first)
    finally:
        page.close()
    return shrunk


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("site", nargs="?", type=Path, default=ROOT / "_build" / "html")
    parser.add_argument("--toc", type=Path, default=ROOT / "_toc.yml")
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args(argv)
    out = args.out or args.site / PDF_NAME
    try:
        r = build(args.site, args.toc, out)
    except FileNotFoundError as exc:
        print(exc, file=sys.stderr)
        return 2
    print(f"book_pdf: {r['pages']} pages of the book -> {out} ({r['pdf_pages']} PDF pages, "
          f"{r['bytes'] / 1e6:.1f} MB, {r['shrunk']} figures printed smaller, {r['seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
