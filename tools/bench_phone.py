"""The built book's first visit on a slow phone, in headless Chromium. Prints, never asserts.

The profile: CPU slowed down four times, 400 kbit/s down and up, 400 ms of
latency on every request, a 412 px wide touch screen; each page is a first
visit (a fresh browser context, empty cache). The site is served by a small
local server that compresses as common static hosts do: a pre-compressed
``.br`` or ``.gz`` file next to the original when there is one and the
browser accepts it (nginx ``gzip_static``/``brotli_static``, Netlify,
Cloudflare), else gzip on the fly for text (GitHub Pages).

For each page it prints, in seconds from the start of the navigation:

* ``DCL``: DOMContentLoaded;
* ``LCP``: the largest contentful paint;
* ``math1``: the first screen's text and math visible: the page is parsed
  past the first screen, its formulas there are typeset (each
  ``span.math``/``div.math`` holds an ``mjx-container``) and the fonts loaded;
* ``math``: every formula of the page typeset, and the fonts loaded;
* ``live``: every live view mounted (its host has ``data-ready``), that is the
  page responds to its sliders: the moment the last one got it, seen by a
  MutationObserver; "-" when the page has none;
* ``MB``: bytes that went over the wire (compressed, headers included),
  decimal megabytes, everything the visit downloaded until the network was
  quiet.

Targets (the course's): math visible within 8 s and live views ready within
12 s on a chapter page; every first visit at most 2 MB.

Give ``--site`` twice to compare two builds in one run (the machine's load
changes from hour to hour, so a before/after pair is only fair in one run; the
sites take turns page by page, and the tables per site come at the end)::

    .venv/bin/python -m tools.bench_phone [--site _build/html] [--site /tmp/old-site] [--pages ...]
"""

from __future__ import annotations

import argparse
import functools
import gzip
import http.server
import mimetypes
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
PAGES = ("chapters/intro.html", "chapters/02_space_jacobian.html", "chapters/06_analytic_jacobian.html",
         "chapters/12_jacobian_derivative.html", "chapters/04_space_vs_body.html",
         "chapters/05_geometric_jacobian.html", "chapters/09_using_the_jacobian.html",
         "chapters/11_redundancy.html")
CPU_SLOWDOWN = 4
KBIT_PER_S = 400
LATENCY_MS = 400
WIDTH, HEIGHT = 412, 915
TIMEOUT_S = 150
#: what common hosts compress on the fly (not images, fonts or archives: they are compressed already)
COMPRESSIBLE = ("text/", "application/javascript", "application/json", "application/xml", "image/svg+xml",
                "application/x-javascript")


class CompressingHandler(http.server.SimpleHTTPRequestHandler):
    """Static files with Content-Encoding as a typical host sends them (see the module's docstring)."""

    def log_message(self, format: str, *args: Any) -> None:
        pass

    def do_GET(self) -> None:
        path = Path(self.translate_path(self.path))
        if path.is_dir():
            path = path / "index.html"
        if not path.is_file():
            self.send_error(404)
            return
        accepted = {e.split(";")[0].strip() for e in self.headers.get("Accept-Encoding", "").split(",")}
        ctype = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
        body, encoding = None, None
        for enc, suffix in (("br", ".br"), ("gzip", ".gz")):
            pre = path.with_name(path.name + suffix)
            if enc in accepted and pre.is_file():
                body, encoding = pre.read_bytes(), enc
                break
        if body is None:
            body = path.read_bytes()
            if "gzip" in accepted and ctype.startswith(COMPRESSIBLE):
                body, encoding = gzip.compress(body, compresslevel=6), "gzip"
        self.send_response(200)
        self.send_header("Content-Type", ctype + ("; charset=utf-8" if ctype.startswith("text/") else ""))
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Vary", "Accept-Encoding")
        if encoding:
            self.send_header("Content-Encoding", encoding)
        self.end_headers()
        self.wfile.write(body)


def serve(site: Path) -> tuple[http.server.ThreadingHTTPServer, str]:
    handler = functools.partial(CompressingHandler, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/"


#: runs in the page before its own scripts: records the largest paint and the moments math and live views are done
PROBE = """(() => {
  const b = window.__bench = {lcp: null, math1: null, math: null, live: null};
  try {
    new PerformanceObserver(l => { for (const e of l.getEntries()) b.lcp = e.startTime; })
      .observe({type: 'largest-contentful-paint', buffered: true});
  } catch (e) {}
  const typeset = m => !!m.querySelector('mjx-container');
  // the moment each live view became ready (its host got data-ready), seen as it happens: a view may mount
  // before the page is parsed to its end (its script is async), and a busy page delays the polling below
  const readyAt = new Map();
  new MutationObserver(records => {
    for (const r of records) {
      const t = r.target;
      if (t.dataset && t.dataset.ready === '1' && !readyAt.has(t)) readyAt.set(t, performance.now());
    }
  }).observe(document, {subtree: true, attributes: true, attributeFilter: ['data-ready']});
  const tick = () => {
    const now = performance.now();
    const fonts = document.fonts.status === 'loaded';
    const math = Array.from(document.querySelectorAll('span.math, div.math'));
    if (b.math1 === null && document.body) {
      // the first screen: formulas whose box starts above the fold (the page is parsed that far)
      const first = math.filter(m => m.getBoundingClientRect().top < innerHeight);
      const parsedPastFold = document.readyState !== 'loading'
        || document.body.getBoundingClientRect().height > 2 * innerHeight;
      if (parsedPastFold && first.every(typeset) && fonts) b.math1 = now;
    }
    if (document.readyState !== 'loading') {
      if (b.math === null && math.every(typeset) && fonts) b.math = now;
      if (b.live === null) {
        const views = Array.from(document.querySelectorAll('[data-model]'));
        if (views.every(v => v.dataset.ready === '1')) {
          b.live = views.length ? Math.max(...views.map(v => readyAt.has(v) ? readyAt.get(v) : now)) : -1;
        }
      }
    }
    if (b.math1 === null || b.math === null || b.live === null) setTimeout(tick, 100);
  };
  tick();
})();"""


def visit(browser: Any, url: str) -> dict[str, Any]:
    context = browser.new_context(viewport={"width": WIDTH, "height": HEIGHT}, is_mobile=True, has_touch=True,
                                  device_scale_factor=2)
    try:
        page = context.new_page()
        page.add_init_script(PROBE)
        cdp = context.new_cdp_session(page)
        cdp.send("Network.enable")
        cdp.send("Network.emulateNetworkConditions", {
            "offline": False, "latency": LATENCY_MS,
            "downloadThroughput": KBIT_PER_S * 1000 / 8, "uploadThroughput": KBIT_PER_S * 1000 / 8})
        cdp.send("Emulation.setCPUThrottlingRate", {"rate": CPU_SLOWDOWN})
        sizes: dict[str, float] = {}
        last = [time.monotonic()]

        def finished(ev: dict[str, Any]) -> None:
            sizes[ev["requestId"]] = ev.get("encodedDataLength", 0)
            last[0] = time.monotonic()

        cdp.on("Network.loadingFinished", finished)
        cdp.on("Network.requestWillBeSent", lambda ev: last.__setitem__(0, time.monotonic()))
        page.goto(url, wait_until="domcontentloaded", timeout=TIMEOUT_S * 1000)
        deadline = time.monotonic() + TIMEOUT_S
        while time.monotonic() < deadline:
            state = page.evaluate("() => [window.__bench.math1, window.__bench.math, window.__bench.live]")
            if None not in state and time.monotonic() - last[0] > 3.0:  # done, and no request for 3 s
                break
            page.wait_for_timeout(500)
        result = page.evaluate("""() => {
          const nav = performance.getEntriesByType('navigation')[0];
          return {dcl: nav.domContentLoadedEventEnd, lcp: window.__bench.lcp, math1: window.__bench.math1,
                  math: window.__bench.math,
                  live: window.__bench.live};
        }""")
        result["bytes"] = sum(sizes.values())
    finally:
        context.close()
    return dict(result)


def _s(ms: float | None) -> str:
    if ms is None:
        return f"  >{TIMEOUT_S:3d}"
    if ms < 0:
        return "     -"
    return "%6.1f" % (ms / 1000)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--site", action="append", type=Path,
                        help="a built site (default _build/html); give it twice to compare two builds")
    parser.add_argument("--pages", nargs="*", default=list(PAGES))
    args = parser.parse_args(argv)
    sites = args.site or [ROOT / "_build" / "html"]
    for site in sites:
        if not (site / "chapters" / "intro.html").is_file():
            parser.error(f"{site} is no built book (run make book)")
    from playwright.sync_api import sync_playwright

    print(f"Slow phone: CPU x{CPU_SLOWDOWN}, {KBIT_PER_S} kbit/s, {LATENCY_MS} ms latency, {WIDTH} px wide, "
          "first visit, served compressed (.br/.gz files when present, else gzip on the fly)")
    print("targets on a chapter page: first screen's text and math (math1) <= 8 s, live views <= 12 s; "
          "every visit <= 2.000 MB")
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync"])
        servers: list[tuple[http.server.ThreadingHTTPServer, str]] = []
        try:
            servers.extend(serve(site) for site in sites)
            # page by page, each site in turn: the machine's load drifts during a run, and a drift must not fall
            # on one site's pages only
            rows: dict[Path, list[str]] = {site: [] for site in sites}
            for page in args.pages:
                for site, (_, base) in zip(sites, servers, strict=True):
                    try:
                        r = visit(browser, base + page)
                    except Exception as exc:  # a page that never loads is a result too: print it, go on
                        row = f"{page:42s} did not load within {TIMEOUT_S} s: {str(exc).splitlines()[0]}"
                    else:
                        row = (f"{page:42s} {_s(r['dcl'])} {_s(r['lcp'])} {_s(r['math1'])} {_s(r['math'])} "
                               f"{_s(r['live'])} {r['bytes'] / 1e6:7.3f}")
                    rows[site].append(row)
                    print(row if len(sites) == 1 else f"{row}  ({site})", flush=True)
            if len(sites) > 1:
                for site in sites:
                    print(f"\nsite {site}")
                    print(f"{'page':42s} {'DCL':>6s} {'LCP':>6s} {'math1':>6s} {'math':>6s} {'live':>6s} {'MB':>7s}")
                    print("\n".join(rows[site]))
        finally:
            for server, _ in servers:
                server.shutdown()
                server.server_close()
            browser.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
