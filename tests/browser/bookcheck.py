"""Open a page of the built book in Chromium and list what a reader would see wrong.

Used by ``test_pages.py`` (every page of the table of contents must come back
clean) and by ``test_checker_catches.py`` (pages broken on purpose must come
back with the right complaint). Nothing here asserts; :func:`check_page`
returns a :class:`PageReport` whose ``problems`` maps an aspect ("console",
"offline", "math", ...) to a list of human-readable complaints.
"""

from __future__ import annotations

import contextlib
import functools
import http.server
import os
import re
import shutil
import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urlsplit

import yaml

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
DESKTOP = {"width": 1280, "height": 900}
PHONE = {"width": 390, "height": 844}
MAX_PAGE_BYTES = 3 * 1024 * 1024

ASPECTS = ("load", "console", "offline", "math", "images", "animations", "widgets", "solutions", "links", "errors",
           "weight", "overflow", "figures", "verdicts", "phone_math", "phone_figures", "negative_zero", "check_lines")

# Console messages that are not errors of the book. Each entry: (console type,
# exact text, why it is harmless). Only types "error" and page errors fail a
# page; warnings are printed with the report, never filtered silently.
HARMLESS_CONSOLE: list[tuple[str, str, str]] = [
    # Nothing is filtered today: every known console error of the stack is
    # fixed in _ext/offline_fixes.py (see its docstring). The html-manager's
    # warning 'strict mode: use allowUnionTypes to allow union type keyword at
    # "#/properties/state/..." (strictTypes)' is a console *warning* printed by
    # the JSON-schema validator bundled in @jupyter-widgets/html-manager 1.0.6
    # while it compiles the widget-state schema; the state still validates and
    # the widgets render. Warnings do not fail a page, so it needs no entry.
]


# ---------------------------------------------------------------- the book
def pages_from_toc(toc_path: Path) -> list[str]:
    """HTML paths (relative to the build) of every page named in a Jupyter Book ``_toc.yml``."""
    toc = yaml.safe_load(Path(toc_path).read_text(encoding="utf-8"))
    if not isinstance(toc, dict) or "root" not in toc:
        raise ValueError(f"Expected a Jupyter Book _toc.yml with a 'root' entry, got {toc_path}")
    files = [toc["root"]]

    def walk(entries):
        for entry in entries or []:
            if not isinstance(entry, dict):
                continue
            if "file" in entry:
                files.append(entry["file"])
            for key in ("parts", "chapters", "sections"):
                walk(entry.get(key))

    for key in ("parts", "chapters", "sections"):
        walk(toc.get(key))
    out = []
    for f in files:
        stem = re.sub(r"\.(md|ipynb|rst)$", "", str(f))
        out.append(stem + ".html")
    return list(dict.fromkeys(out))


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):  # keep the test output readable
        pass


class BookServer:
    """The built HTML on http://127.0.0.1:<free port>/, in a daemon thread."""

    def __init__(self, root: Path):
        self.root = Path(root)
        handler = functools.partial(_QuietHandler, directory=str(self.root))
        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self.httpd.daemon_threads = True
        self.base = f"http://127.0.0.1:{self.httpd.server_port}/"
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.httpd.shutdown()
        self.httpd.server_close()


def launch_browser(playwright):
    """Chromium from Debian (never a downloaded one), headless, fresh profile."""
    if not Path(CHROMIUM).exists():
        raise FileNotFoundError(f"{CHROMIUM} is missing: `make browser` installs Debian's chromium")
    profile = tempfile.mkdtemp(prefix="book-browser-profile-")
    context = playwright.chromium.launch_persistent_context(
        profile,
        executable_path=CHROMIUM,
        args=CHROMIUM_ARGS,
        headless=True,
        viewport=DESKTOP,
        service_workers="block",
    )
    return context, profile


@contextlib.contextmanager
def opened_browser(playwright):
    """``launch_browser``'s context, closed on leaving, with its profile folder removed."""
    context, profile = launch_browser(playwright)
    try:
        yield context
    finally:
        context.close()
        shutil.rmtree(profile, ignore_errors=True)


# ---------------------------------------------------------------- the report
@dataclass
class PageReport:
    path: str
    problems: dict[str, list[str]] = field(default_factory=lambda: {a: [] for a in ASPECTS})
    notes: list[str] = field(default_factory=list)
    total_bytes: int = 0
    own_bytes: int = 0
    requests: int = 0
    seconds: float = 0.0
    counts: dict[str, int] = field(default_factory=dict)
    sizes: list[tuple[str, int]] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)

    def add(self, aspect: str, message: str) -> None:
        msgs = self.problems.setdefault(aspect, [])
        if message not in msgs:  # e.g. an image requested twice, 404 twice
            msgs.append(message)

    def summary(self) -> str:
        c = self.counts
        return (
            f"{self.path:40s} {self.total_bytes / 1024:8.0f} KiB total "
            f"({self.own_bytes / 1024:6.0f} KiB page+images, {self.requests:3d} requests) "
            f"math {c.get('math_rendered', 0)}/{c.get('math_source', 0)}  img {c.get('images', 0)}  "
            f"anim {c.get('animations', 0)}  numbered figures {c.get('figures', 0)}  sliders {c.get('sliders', 0)}  dropdowns {c.get('dropdowns', 0)}  "
            f"links {c.get('links', 0)}  {self.seconds:4.1f} s"
        )


def _harmless(kind: str, text: str) -> bool:
    return any(kind == k and text == t for k, t, _why in HARMLESS_CONSOLE)


# Visible text, with code, scripts and typeset math taken out.
_VISIBLE_TEXT_JS = """
() => {
  const root = document.querySelector('main') || document.body;
  const clone = root.cloneNode(true);
  clone.querySelectorAll('pre, code, script, style, noscript, mjx-container, mjx-assistive-mml, '
    + 'textarea, .highlight, template').forEach(e => e.remove());
  return clone.textContent;
}
"""

RAW_TEX_PATTERNS = [
    (re.compile(r"\$\$"), "$$"),
    (re.compile(r"\\\[|\\\]"), "\\[ or \\]"),
    (re.compile(r"\\\(|\\\)"), "\\( or \\)"),
    (re.compile(r"\\begin\{|\\end\{"), "\\begin{...}"),
    (re.compile(r"\\(?:frac|dot|mathcal|mathrm|mathbb|theta|omega|left|right|hat|sum|int|cdot|times)\b"),
     "a TeX command"),
    (re.compile(r"(?<![\w$])\$[^$\s][^$\n]{0,200}?[^$\s\\]\$(?![\w$])"), "$...$"),
]


def raw_tex_in(text: str) -> list[str]:
    """Snippets of visible text that look like TeX MathJax did not typeset.

    >>> raw_tex_in("the Jacobian $J_s$ maps")
    ['$...$: ...the Jacobian $J_s$ maps...']
    >>> raw_tex_in("costs 5 dollars, the twist V_s")
    []
    """
    found = []
    for pattern, name in RAW_TEX_PATTERNS:
        for m in pattern.finditer(text):
            a, b = max(0, m.start() - 20), min(len(text), m.end() + 20)
            snippet = " ".join(text[a:b].split())
            found.append(f"{name}: ...{snippet}...")
            if len(found) > 8:
                return found
    return found


# ---------------------------------------------------------------- page-quality probes
# Shared JS: the main content, and a short "where" (the heading of the section an element is in).
_JS_COMMON = """
  const ROOT = document.querySelector('article.bd-article') || document.querySelector('main') || document.body;
  const where = e => {
    for (let s = e.closest('section'); s; s = s.parentElement && s.parentElement.closest('section')) {
      const h = s.querySelector(':scope > h1, :scope > h2, :scope > h3, :scope > h4, :scope > h5');
      if (h) return h.textContent.replace(/#\\s*$/, '').trim().slice(0, 70);
    }
    return '(top of the page)';
  };
"""

# Verdicts of the exercise checker (jacobians.grading.Feedback) and `answer = None` cells, and where they are.
_VERDICTS_JS = "() => {" + _JS_COMMON + """
  const verdicts = Array.from(ROOT.querySelectorAll('.jacobians-feedback')).map(e => {
    const m = /jacobians-feedback-(\\w+)/.exec(e.className);
    return {kind: m ? m[1] : '?', head: (e.querySelector('strong') || e).textContent.trim().slice(0, 40),
            solution: !!e.closest('.solution'), where: where(e)};
  });
  const empty = Array.from(ROOT.querySelectorAll('.cell_input, div[class*="highlight-"]'))
    .filter(e => !e.closest('.cell_output') && !e.closest('.solution') && !(e.parentElement && e.parentElement.closest('.cell_input, div[class*="highlight-"]')))
    .filter(e => /^\\s*answer\\s*=\\s*None\\b/m.test(e.textContent)).map(e => where(e));
  const exercisePage = !!ROOT.querySelector('.exercise, .solution') || /\\/exercises\\//.test(location.pathname);
  return {verdicts, empty, exercisePage};
}"""

# Images and animations in the main content that are not in a figure with a numbered caption.
_FIGURES_JS = "() => {" + _JS_COMMON + """
  const exempt = e => !!e.closest('.navbar-brand, .bd-header, .bd-footer, .bd-sidebar-primary, .bd-sidebar-secondary, '
                                  + 'header, footer, .jacobians-feedback') || /(^|\\s)(logo|theme-image)/.test(e.className || '');
  const items = Array.from(ROOT.querySelectorAll('img')).filter(i => !i.closest('.animation')).map(e => ['image', e])
    .concat(Array.from(ROOT.querySelectorAll('div.animation')).map(e => ['animation', e]));
  const out = [];
  let numbered = 0;
  for (const [kind, e] of items) {
    if (exempt(e)) continue;
    const img = kind === 'image' ? e : e.querySelector('img');
    const name = ((img && (img.getAttribute('alt') || (img.getAttribute('src') || '').slice(0, 60))) || '').slice(0, 70);
    const fig = e.closest('figure');
    const cap = fig && fig.querySelector('figcaption');
    let why = null;
    if (!fig) why = 'is not in a figure';
    else if (!cap || !cap.textContent.trim()) why = 'is in a figure without a caption';
    else if (!cap.querySelector('span.caption-number')) why = 'is in a figure whose caption has no number';
    if (why) out.push({kind, name, why, where: where(e)}); else numbered += 1;
  }
  return {out, numbered};
}"""

# Visible text by block (paragraph, list item, output, caption...), without the code the reader types
# (cell inputs, code blocks and inline code outside outputs) and without typeset math; the TeX of every
# formula comes from MathJax's own list; the lines of monospace outputs are listed separately.
_TEXT_JS = "() => {" + _JS_COMMON + """
  const SKIP = '.cell_input, script, style, noscript, textarea, template, mjx-container, .headerlink';
  const CODE = 'code, div[class*="highlight-"], pre';
  const skipped = el => !!el.closest(SKIP) || (!!el.closest(CODE) && !el.closest('.cell_output'));
  const BLOCK = 'p, li, pre, td, th, dt, dd, figcaption, caption, summary, h1, h2, h3, h4, h5, h6, .admonition-title, .cell_output';
  const blocks = new Map();
  const walker = document.createTreeWalker(ROOT, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const el = n.parentElement;
    if (!el || skipped(el)) continue;
    const b = el.closest(BLOCK) || el;
    blocks.set(b, (blocks.get(b) || '') + n.data);
  }
  const text = Array.from(blocks, ([b, t]) => ({where: where(b), text: t, mono: b.tagName === 'PRE'}));
  const tex = [];
  if (window.MathJax && MathJax.startup && MathJax.startup.document) {
    for (const item of MathJax.startup.document.math) {
      const node = item.typesetRoot || (item.start && item.start.node);
      if (node && node.nodeType === 1 && node.closest('.cell_input')) continue;
      tex.push({where: node && node.nodeType === 1 ? where(node) : (node && node.parentElement ? where(node.parentElement) : ''),
                text: String(item.math)});
    }
  } else {  // typeset at build time: the TeX is kept in data-tex (_ext/math_prerender.py)
    ROOT.querySelectorAll('span.math, div.math').forEach(e =>
      tex.push({where: where(e), text: e.dataset.tex || e.textContent}));
  }
  return {text, tex};
}"""

# Boxes whose content is wider than the box, where the box is not a horizontal scroll container and no
# scroll container inside the article takes the overflow. Only the innermost offender is reported.
_OVERFLOW_JS = "() => {" + _JS_COMMON + """
  const ox = e => getComputedStyle(e).overflowX;
  const describe = e => {
    if (e.matches('.admonition')) {
      const t = e.querySelector('.admonition-title');
      return 'box "' + (t ? t.textContent.trim().slice(0, 40) : e.className) + '"';
    }
    if (e.matches('.cell_output')) return 'cell output';
    if (e.matches('div.math')) return 'display-math box';
    return 'display equation';
  };
  // content width: scrollWidth, except that content sticking out on the left (display math is a
  // flex row-reverse box) is not in scrollWidth: for math, the children's extent counts too
  const contentWidth = e => {
    let w = e.scrollWidth;
    if (e.matches('div.math, mjx-container')) {
      const r = e.getBoundingClientRect();
      let lo = r.left, hi = r.right;
      for (const c of e.children) {
        if (!c.getClientRects().length) continue;
        const q = c.getBoundingClientRect();
        lo = Math.min(lo, q.left); hi = Math.max(hi, q.right);
      }
      w = Math.max(w, Math.round(e.clientWidth + (r.left - lo) + (hi - r.right)));
    }
    return w;
  };
  const bad = [];
  for (const e of ROOT.querySelectorAll('.cell_output, .admonition, div.math, mjx-container[display="true"]')) {
    if (!e.getClientRects().length || e.clientWidth === 0) continue;
    if (contentWidth(e) - e.clientWidth <= 2 || /^(auto|scroll)$/.test(ox(e))) continue;
    let ok = false;
    for (let a = e.parentElement; a && a !== ROOT && ROOT.contains(a); a = a.parentElement) {
      const o = ox(a);
      if (o === 'auto' || o === 'scroll') { ok = true; break; }
      if (o === 'hidden' || o === 'clip') break;
    }
    if (!ok) bad.push(e);
  }
  // what sticks out of a box: the innermost descendants past its padding edge (not looking inside
  // descendants that scroll or clip, they keep their content), shown by their text
  const stickingOut = e => {
    const r = e.getBoundingClientRect();
    const lo = r.left + e.clientLeft - 2, hi = r.left + e.clientLeft + e.clientWidth + 2;
    const out = [];
    const walk = n => {
      for (const c of n.children) {
        if (!c.getClientRects().length) continue;
        const q = c.getBoundingClientRect();
        if (q.right > hi || q.left < lo) out.push(c);
        if (ox(c) === 'visible' && !c.matches('mjx-container')) walk(c);
      }
    };
    walk(e);
    const inner = out.filter(c => !out.some(o => o !== c && c.contains(o)));
    return inner.slice(0, 2).map(c => {
      const m = c.closest('mjx-container');
      return (m ? (m.getAttribute('aria-label') || m.textContent) : c.textContent).trim().replace(/\\s+/g, ' ').slice(0, 50);
    }).filter(t => t);
  };
  const boxes = bad.filter(e => !bad.some(o => o !== e && e.contains(o))).map(e => ({
    what: describe(e), content: contentWidth(e), box: e.clientWidth, clipped: /^(hidden|clip)$/.test(ox(e)),
    where: where(e), text: e.textContent.trim().replace(/\\s+/g, ' ').slice(0, 50), culprits: stickingOut(e)}));
  // the whole page wider than the window: the elements that stick out, not inside any clipping box
  const vw = document.documentElement.clientWidth, pw = document.documentElement.scrollWidth;
  const culprits = [];
  if (pw > vw + 2) {
    const free = e => { for (let a = e.parentElement; a && a !== document.body; a = a.parentElement)
                          if (ox(a) !== 'visible') return false; return true; };
    const out = Array.from(ROOT.querySelectorAll('*')).filter(e => e.getClientRects().length
      && e.getBoundingClientRect().right > vw + 2 && free(e));
    for (const e of out.filter(e => !out.some(o => o !== e && e.contains(o))).slice(0, 3)) {
      const block = e.closest('p, li, h1, h2, h3, h4, h5, h6, pre, td, th, .admonition, .cell_output, figure') || e;
      culprits.push({tag: e.tagName.toLowerCase() + (e.className ? '.' + String(e.className).split(' ')[0] : ''),
                     text: (block.textContent || '').trim().replace(/\\s+/g, ' ').slice(0, 60), where: where(e),
                     right: Math.round(e.getBoundingClientRect().right)});
    }
  }
  return {boxes, page: pw, window: vw, culprits};
}"""

# Every formula at the current width: does it fit, scroll in its own box, or get cut off?
_MATH_FIT_JS = "() => {" + _JS_COMMON + """
  const vw = document.documentElement.clientWidth;
  const ox = e => getComputedStyle(e).overflowX;
  const out = [];
  for (const c of ROOT.querySelectorAll('mjx-container')) {
    if (!c.getClientRects().length) continue;
    const display = c.getAttribute('display') === 'true';
    const m = c.querySelector(':scope > mjx-math') || c.firstElementChild || c;
    const r = m.getBoundingClientRect();
    const w = Math.round(r.width);
    const tex = (c.getAttribute('aria-label') || c.textContent || '').trim().slice(0, 40);
    let x = null;
    for (let a = c; a && a !== document.documentElement; a = a.parentElement) {
      if (ox(a) !== 'visible') { x = a; break; }
    }
    let why = null;
    if (x && /^(hidden|clip)$/.test(ox(x))) {
      if (w > x.clientWidth + 2) why = `is ${w} px wide and cut off at ${x.clientWidth} px by overflow: ${ox(x)} (no scroll container)`;
    } else if (x && x !== ROOT && ROOT.contains(x) && x !== document.body) {
      const s = x.getBoundingClientRect();
      if (w > x.clientWidth + 2 && (s.right > vw + 1 || s.left < -1))
        why = `scrolls in a box that itself runs off the ${vw} px screen`;
      for (let a = x.parentElement; !why && a && a !== document.documentElement; a = a.parentElement) {
        if (/^(hidden|clip)$/.test(ox(a)) && s.right > a.getBoundingClientRect().right + 2)
          why = `scrolls in a box that is cut off by overflow: ${ox(a)} of its container`;
      }
    } else if (r.right > vw + 1 || r.left < -1) {
      why = `is ${w} px wide and runs off the ${vw} px screen (no scroll container)`;
    }
    if (why) out.push({display, why, where: where(c), tex});
  }
  return out;
}"""

NEGATIVE_ZERO = re.compile(r"(?<![\w.])[-\u2212]\s?0(?:\.0*)?(?![\d.])")
NEGATIVE_ZERO_TEX = re.compile(r"(?<![\w.}])-\s*0(?:\.0*)?(?![\d.])")
CHECK_LINE = re.compile(r"[\u2713\u2714]\s*(?:checked|verified)\b", re.I)


def negative_zeros_in(text: str, tex: bool = False) -> list[str]:
    """Snippets of ``text`` that show a negative zero ("-0.", "−0.000", "-0").

    >>> negative_zeros_in("array([ 0.    , -0.    ,  1.    ])")
    ['...y([ 0. , -0. , 1....']
    >>> negative_zeros_in("x = -0.5, y = 10-0.3, 1e-05, -0.05, −1.0")
    []
    """
    pattern = NEGATIVE_ZERO_TEX if tex else NEGATIVE_ZERO
    out = []
    for m in pattern.finditer(text):
        a, b = max(0, m.start() - 12), min(len(text), m.end() + 12)
        out.append("..." + " ".join(text[a:b].split()) + "...")
    return out


def check_lines_in(text: str, monospace: bool = False) -> list[str]:
    """Lines of ``text`` that are an old "✓ checked" printout (or, in a monospace output, any line opening with ✓).

    >>> check_lines_in("✓ checked (sympy): e^{+[S1]θ1} ...")
    ['✓ checked (sympy): e^{+[S1]θ1} ...']
    >>> check_lines_in("✓ 4 conversions agree", monospace=True)
    ['✓ 4 conversions agree']
    >>> check_lines_in("Verified by code (3 checks)")
    []
    """
    out = []
    for line in text.splitlines():
        line = line.strip()
        if CHECK_LINE.search(line) or (monospace and line.startswith(("\u2713", "\u2714"))):
            out.append(line[:100])
    return out


def _check_verdicts(page, report: PageReport) -> None:
    v = page.evaluate(_VERDICTS_JS)
    report.counts["verdicts"] = len(v["verdicts"])
    shown_correct = [x for x in v["verdicts"] if x["kind"] == "correct" and not x["solution"]]
    if v["empty"] and shown_correct:
        report.add("verdicts", f"a \u2018{shown_correct[0]['head']}\u2019 verdict is shown ({shown_correct[0]['where']!r}) "
                   f"on a page that shows an empty answer `answer = None` ({v['empty'][0]!r}): "
                   "the book ran the checker on the hidden solution")
    if v["exercisePage"]:
        for x in v["verdicts"]:
            if not x["solution"]:
                report.add("verdicts", f"a checker verdict \u2018{x['head']}\u2019 is shown outside a solution dropdown "
                           f"(section {x['where']!r}): in the book the check cell must show nothing")


def _check_figures(page, report: PageReport) -> None:
    f = page.evaluate(_FIGURES_JS)
    report.counts["figures"] = f["numbered"]
    for x in f["out"]:
        report.add("figures", f"{x['kind']} {x['name']!r} {x['why']} (section {x['where']!r}): every figure and "
                   "animation needs a numbered caption (cell metadata mystnb: figure: name, caption)")


def _check_text(page, report: PageReport) -> None:
    t = page.evaluate(_TEXT_JS)
    for block in t["text"]:
        for snip in negative_zeros_in(block["text"]):
            report.add("negative_zero", f"a negative zero in the text: {snip!r} (section {block['where']!r})")
        for line in check_lines_in(block["text"], monospace=block["mono"]):
            report.add("check_lines", f"a raw \u2713 check printout: {line!r} (section {block['where']!r}): "
                       "record it with verified(...) and show verified.box()")
    for formula in t["tex"]:
        for snip in negative_zeros_in(formula["text"], tex=True):
            report.add("negative_zero", f"a negative zero in a formula: {snip!r} (section {formula['where']!r})")


def _check_layout(page, report: PageReport, width: int) -> None:
    o = page.evaluate(_OVERFLOW_JS)
    for x in o["boxes"]:
        how = "is cut off (overflow: hidden)" if x["clipped"] else "spills out (not a scroll container)"
        what = ("; sticking out: " + ", ".join(repr(t) for t in x["culprits"])) if x["culprits"] else ""
        report.add("overflow", f"at {width} px a {x['what']} is {x['content']} px wide in a {x['box']} px box and {how}: "
                   f"{x['text']!r}{what} (section {x['where']!r})")
    if o["culprits"]:
        what = "; ".join(f"{c['tag']} reaching {c['right']} px in {c['text']!r} (section {c['where']!r})"
                         for c in o["culprits"])
        report.add("overflow", f"at {width} px the whole page scrolls sideways ({o['page']} px wide in a "
                   f"{o['window']} px window): {what}")


_PHONE_FIGURES_JS = """() => {
  // _theme/scroll_cue.js: on a phone a wide figure (width >= 1.5 height) is shown at
  // min(natural width, twice the page's width) in its own box that scrolls sideways
  const out = [];
  for (const img of document.querySelectorAll('main figure img')) {
    if (!img.getClientRects().length || !img.naturalWidth) continue;
    if (img.naturalWidth < 1.5 * img.naturalHeight) continue;
    const box = img.parentElement;
    const name = (img.closest('figure').id || img.getAttribute('src'));
    if (!box.classList.contains('jac-fig-scroll')) { out.push(name + ': not in a scrolling box'); continue; }
    const want = Math.min(img.naturalWidth, 2 * box.clientWidth);
    const shown = img.getBoundingClientRect().width;
    if (Math.abs(shown - want) > 1) out.push(name + ': shown ' + shown.toFixed(0) + ' px wide, not ' + want.toFixed(0));
    if (box.scrollWidth > box.clientWidth + 4 && box.getAttribute('tabindex') !== '0')
      out.push(name + ': scrolls but cannot be reached from the keyboard');
  }
  return out;
}"""


def _check_phone_figures(page, report: PageReport, width: int) -> None:
    page.evaluate("() => window.dispatchEvent(new Event('resize'))")
    page.wait_for_timeout(100)
    for x in page.evaluate(_PHONE_FIGURES_JS):
        report.add("phone_figures", f"at {width} px a wide figure {x}")


def _check_phone_math(page, report: PageReport, width: int) -> None:
    for x in page.evaluate(_MATH_FIT_JS):
        kind = "display equation" if x["display"] else "inline formula"
        report.add("phone_math", f"at {width} px a {kind} {x['why']}: {x['tex']!r} (section {x['where']!r})")


#: files of the site that a build leaves out when told to (the Makefile's BOOK_PDF=0, as make test builds the book):
#: a link to one is "not built in this run", not a broken link, only when that variable says so
LEFT_OUT = {"manipulator-jacobians.pdf": "BOOK_PDF"}


def _left_out(target: Path, root: Path) -> str | None:
    """The variable that left ``target`` out of this build, or None (a file every build has)."""
    try:
        rel = target.relative_to(root).as_posix()
    except ValueError:
        return None
    var = LEFT_OUT.get(rel)
    return var if var is not None and os.environ.get(var, "1") == "0" else None


def _local_target(url: str, base: str, root: Path) -> tuple[Path | None, str]:
    """File of the build a same-origin URL points at (index.html for folders), and its fragment."""
    parts = urlsplit(url)
    rel = unquote(parts.path[len(urlsplit(base).path):]) if parts.path.startswith(urlsplit(base).path) else None
    if rel is None:
        return None, parts.fragment
    target = root / rel
    if rel == "" or rel.endswith("/"):
        target = target / "index.html"
    return target, unquote(parts.fragment)


_ID_CACHE: dict[Path, set[str]] = {}


def _ids_in(path: Path) -> set[str]:
    if path not in _ID_CACHE:
        text = path.read_text(encoding="utf-8", errors="replace")
        _ID_CACHE[path] = set(re.findall(r"""\b(?:id|name)=["']([^"']+)["']""", text))
    return _ID_CACHE[path]


#: what the two passes below share: whether an element is drawn, and a dropdown's head (its <summary> or admonition
#: title) and the content that head shows or hides
_DROPDOWN_PARTS = """
  const shown = (el) => el.checkVisibility({ opacityProperty: true, visibilityProperty: true })
    && el.getClientRects().length > 0;
  const parts = (box) => {
    const details = box.tagName === 'DETAILS';
    return { head: box.querySelector(details ? ':scope > summary' : ':scope > .admonition-title'),
             body: box.querySelector(details ? ':scope > :not(summary)' : ':scope > :not(.admonition-title)') };
  };
"""
#: every dropdown of the page: its content must be hidden, its opener (a togglebutton's button, an admonition's
#: title, a <summary>) must be what a pointer at its centre hits once it is scrolled into view; then it is clicked
#: there (the opener's own click, as a pointer's click dispatches it) and marked data-bookcheck-clicked
_DROPDOWNS_OPEN_JS = "() => {" + _DROPDOWN_PARTS + """
  const out = [];
  document.querySelectorAll('.admonition.dropdown, details.sd-dropdown, details.toggle-details').forEach((box) => {
    const { head, body } = parts(box);
    const item = { title: ((head || box).textContent || '').trim().slice(0, 60), clicked: false, problem: '' };
    out.push(item);
    if (!body || !head) { item.problem = 'no content'; return; }
    if (shown(body)) { item.problem = 'content visible before it is opened (toggle not set up)'; return; }
    const opener = head.querySelector(':scope > button.toggle-button') || head;
    opener.scrollIntoView({ block: 'center', inline: 'nearest' });
    const r = opener.getBoundingClientRect();
    const hit = document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2);
    if (!r.width || !r.height || !hit || !(hit === opener || opener.contains(hit) || head.contains(hit))) {
      item.problem = 'does not open when clicked (its opener is hidden or covered: a click there hits '
        + (hit ? hit.tagName.toLowerCase() + (hit.className ? '.' + String(hit.className).split(' ')[0] : '') : 'nothing') + ')';
      return;
    }
    box.setAttribute('data-bookcheck-clicked', '1');
    opener.click();
    item.clicked = true;
  });
  return out;
}"""
#: the titles of the dropdowns clicked above whose content is still hidden
_DROPDOWNS_HIDDEN_JS = "() => {" + _DROPDOWN_PARTS + """
  return Array.from(document.querySelectorAll('[data-bookcheck-clicked]')).map(parts)
    .filter(({ head, body }) => head && body && !shown(body)).map(({ head }) => head.textContent.trim().slice(0, 60));
}"""
_DROPDOWNS_SHOWN_JS = "() => (" + _DROPDOWNS_HIDDEN_JS + ")().length === 0"


def check_page(context, base: str, root: Path, path: str, shots: Path | None = None,
               phone: bool = True, settle_ms: int = 300) -> PageReport:
    """Load ``path`` (relative to the build root) like a reader and report every problem seen."""
    import time

    t0 = time.monotonic()
    report = PageReport(path)
    root = Path(root)
    clock = [time.monotonic()]

    def _lap(name: str) -> None:  # where the seconds go (printed by the CLI)
        now = time.monotonic()
        report.timings[name] = report.timings.get(name, 0.0) + now - clock[0]
        clock[0] = now
    page_file = root / path
    if not page_file.exists():
        report.add("load", f"{path} is in the table of contents but not in the build ({page_file})")
        return report

    host = urlsplit(base).hostname
    responses = []
    page = context.new_page()
    page.set_viewport_size(DESKTOP)

    # Every request is recorded; any to another host is aborted and is a failure.
    # (Routing also turns off the HTTP cache, so each page's weight is complete.)
    def route(r):
        url = r.request.url
        scheme = urlsplit(url).scheme
        if scheme in ("data", "blob", "about"):
            return r.continue_()
        if urlsplit(url).hostname != host:
            report.add("offline", f"request to another host, blocked: {url}")
            return r.abort("blockedbyclient")
        return r.continue_()

    page.route("**/*", route)

    def on_console(msg):
        if msg.type == "error":
            text = msg.text
            if _harmless("error", text):
                return
            # failed loads are reported once, by the request handlers below
            if text.startswith("Failed to load resource"):
                loc = msg.location.get("url", "") if isinstance(msg.location, dict) else ""
                if loc and urlsplit(loc).hostname != host:
                    return  # a blocked external request, already reported under "offline"
            report.add("console", f"console error: {text} ({msg.location.get('url', '')})")
        elif msg.type == "warning":
            report.notes.append(f"console warning: {msg.text[:160]}")

    page.on("console", on_console)
    page.on("pageerror", lambda err: report.add("console", f"page error (uncaught exception): {err}"))

    def on_failed(req):
        if urlsplit(req.url).hostname != host:
            return  # blocked by us: reported under "offline"
        report.add("load", f"request failed: {req.url} ({req.failure})")

    page.on("requestfailed", on_failed)

    def on_response(resp):
        responses.append(resp)
        if resp.status >= 400:
            report.add("load", f"HTTP {resp.status} for {resp.url}")

    page.on("response", on_response)

    url = base + path
    try:
        page.goto(url, wait_until="load", timeout=30_000)
    except Exception as exc:
        report.add("load", f"could not load {url}: {exc}")
        page.close()
        return report

    # Let MathJax finish if the page loads it (it is loaded with defer and typesets asynchronously);
    # the book's pages are typeset at build time and load none (_ext/math_prerender.py).
    has_mathjax = page.evaluate("() => !!(window.MathJax && window.MathJax.startup)")
    if has_mathjax:
        try:
            page.evaluate("() => MathJax.startup.promise.then(() => true)")
        except Exception as exc:
            report.add("math", f"MathJax did not finish typesetting: {exc}")
    # An exercise page draws each statement for the reader's ID and typesets it with MathJax loaded then
    # (_ext/exercise_checks/page.js): the page is judged once that is done.
    if page.evaluate("() => !!(window.courseExercises && window.courseExercises.typesetDone)"):
        try:
            page.evaluate("() => window.courseExercises.typesetDone().then(() => true)")
        except Exception as exc:
            report.add("math", f"the exercise statements were not typeset: {exc}")
    try:
        page.wait_for_load_state("networkidle", timeout=10_000)
    except Exception:
        report.notes.append("network did not go idle within 10 s")
    page.wait_for_timeout(settle_ms)

    _lap("load+MathJax")
    # ---- desktop screenshot as the reader first sees the page (before any clicks)
    if shots is not None:
        shots.mkdir(parents=True, exist_ok=True)
        stem = path.replace("/", "__").removesuffix(".html")
        page.screenshot(path=str(shots / f"{stem}__desktop.jpg"), full_page=True, type="jpeg", quality=75)

    _lap("desktop screenshot")
    # ---- errors shown to the reader: tracebacks, error outputs
    err = page.evaluate(
        """() => {
          const out = [];
          document.querySelectorAll('.output.error, .output.traceback, .cell_output .traceback, '
            + 'div.highlight-ipythontb, .system-message, .problematic').forEach(e =>
            out.push(e.className + ': ' + e.textContent.trim().slice(0, 160)));
          const t = (document.querySelector('main') || document.body).innerText;
          if (t.includes('Traceback (most recent call last)')) out.push('a Python traceback is shown in the page');
          return out;
        }"""
    )
    for e in err:
        report.add("errors", e)

    _lap("errors")
    # ---- math
    source_html = page_file.read_text(encoding="utf-8", errors="replace")
    n_source = len(re.findall(r"""class=["'][^"']*\bmath\b""", source_html))
    n_rendered = page.evaluate("() => document.querySelectorAll('mjx-container').length")
    n_errors = page.evaluate(
        "() => Array.from(document.querySelectorAll('mjx-merror, [data-mjx-error]'))"
        ".map(e => (e.getAttribute('data-mjx-error') || e.textContent).slice(0, 120))"
    )
    report.counts.update(math_source=n_source, math_rendered=n_rendered)
    if n_source and n_rendered < n_source:
        report.add("math", f"{n_source} math elements in the HTML but only {n_rendered} typeset by MathJax")
    n_prerendered = page.evaluate("() => document.querySelectorAll('[data-tex] > mjx-container').length")
    if n_source and not has_mathjax and not n_prerendered:
        report.add("math", "the page has math but MathJax is not loaded, nor was it typeset at build time")
    for e in n_errors:
        report.add("math", f"MathJax could not typeset: {e}")
    for snippet in raw_tex_in(page.evaluate(_VISIBLE_TEXT_JS)):
        report.add("math", f"raw TeX in the visible text: {snippet}")

    _check_text(page, report)
    _lap("math")
    # ---- exercise verdicts and numbered figures (structure: independent of what is open)
    _check_verdicts(page, report)
    _check_figures(page, report)
    _lap("verdicts+figures")
    # ---- images: loaded, with real alt text
    page.evaluate("() => document.querySelectorAll('img[loading=lazy]').forEach(i => i.loading = 'eager')")
    page.evaluate(
        "() => Promise.allSettled(Array.from(document.images).map(i => i.complete ? null : i.decode()))"
    )
    imgs = page.evaluate(
        """() => Array.from(document.images).map(i => ({
              src: i.currentSrc || i.src || '', alt: i.getAttribute('alt'),
              w: i.naturalWidth, complete: i.complete,
              anim: !!i.closest('.animation'), id: i.id}))"""
    )
    report.counts["images"] = len(imgs)
    for im in imgs:
        name = im["src"][:80] if not im["src"].startswith("data:") else f"<img id={im['id']!r} data URI>"
        if not im["src"] and im["anim"]:
            pass  # an animation's frame is set by its script; checked under "animations"
        elif im["w"] == 0:
            report.add("images", f"image did not load: {name}")
        alt = (im["alt"] or "").strip()
        if not alt:
            report.add("images", f"image without alt text: {name}")
        elif re.search(r"\.(png|jpe?g|svg|gif|webp)$", alt, re.I) or alt.startswith(("../", "_images/")):
            report.add("images", f"alt text is a file name, not a description: {alt!r} ({name})")

    _lap("images")
    # ---- animations (matplotlib jshtml): press play, the frame changes
    anims = page.locator("div.animation")
    report.counts["animations"] = anims.count()
    for k in range(anims.count()):
        a = anims.nth(k)
        img = a.locator("img").first
        play = a.locator("button[onclick*='play_animation']").first
        pause = a.locator("button[onclick*='pause_animation']").first
        if img.count() == 0 or play.count() == 0:
            report.add("animations", f"animation {k + 1}: no frame image or no play button")
            continue
        try:
            a.scroll_into_view_if_needed(timeout=5_000)
        except Exception:
            pass
        before = img.evaluate("i => i.src")
        if not before:  # (a frame file, _ext/lazy_frames.py; a data URI in a notebook's own player)
            report.add("animations", f"animation {k + 1}: shows no frame before play")
        try:
            slider = a.locator("input[type=range]").first
            v0 = slider.input_value() if slider.count() else None
            play.click(timeout=5_000)
            changed = page.wait_for_function(
                "([i, s]) => i.src !== s", arg=[img.element_handle(), before], timeout=4_000
            )
            changed.dispose()
            if pause.count():
                pause.click(timeout=5_000)
            if slider.count() and slider.input_value() == v0:
                report.add("animations", f"animation {k + 1}: the frame changed but the slider did not move")
        except Exception as exc:
            report.add("animations", f"animation {k + 1}: pressing play did not change the frame ({exc.__class__.__name__})")

    _lap("animations")
    # ---- widget sliders: moving one must change something else on the page.
    # An executed `interact` keeps its first output in a static page: the slider
    # moves, nothing redraws. That is a dead control for the reader.
    sliders = page.locator(".jupyter-widgets.widget-slider, .widget-slider.widget-hslider")
    report.counts["sliders"] = sliders.count()
    for k in range(sliders.count()):
        sl = sliders.nth(k)
        handle = sl.locator(".noUi-handle, input[type=range]").first
        if handle.count() == 0:
            report.add("widgets", f"slider {k + 1}: not rendered (no handle): is the widget manager loaded?")
            continue
        snap = """([s]) => {
            const root = s.closest('.cell_output, .output_area, .cell') || document.body;
            const clone = root.cloneNode(true);
            const mark = s.getAttribute('data-bookcheck-slider');
            clone.querySelectorAll(`[data-bookcheck-slider="${mark}"]`).forEach(e => e.remove());
            const imgs = Array.from(root.querySelectorAll('img, canvas')).map(i => i.src || i.toDataURL()).join('|');
            return [clone.innerHTML.replace(/\\s+/g, ' '), imgs, s.textContent];
        }"""
        try:
            sl.evaluate(f"s => s.setAttribute('data-bookcheck-slider', 's{k}')")
            sl.scroll_into_view_if_needed(timeout=5_000)
            before = page.evaluate(snap, [sl.element_handle()])
            handle.focus()
            for _ in range(3):
                page.keyboard.press("ArrowRight")
            page.wait_for_timeout(600)
            after = page.evaluate(snap, [sl.element_handle()])
        except Exception as exc:
            report.add("widgets", f"slider {k + 1}: could not be moved ({exc.__class__.__name__})")
            continue
        if before[2] == after[2]:
            report.add("widgets", f"slider {k + 1}: does not move with the keyboard (its readout stays {before[2]!r})")
        elif before[:2] == after[:2]:
            report.add("widgets", f"slider {k + 1} ({after[2].strip()[:40]!r}): moving it changes nothing else on the "
                       "page: a dead control without a kernel (show an animation instead)")

    _lap("sliders")
    # ---- dropdowns (exercise solutions, togglebutton admonitions, sphinx-design): each one's content is hidden,
    # its opener is what a pointer at its centre hits (nothing covers it), and a click there shows the content.
    # One pass in the page (a round trip per dropdown cost seconds on a long chapter): each opener is scrolled
    # into view and hit-tested as Playwright's click does, then clicked; the page then has 3 s to show them all.
    found = page.evaluate(_DROPDOWNS_OPEN_JS)
    report.counts["dropdowns"] = len(found)
    for d in found:
        if d["problem"]:
            report.add("solutions", f"dropdown {d['title']!r}: {d['problem']}")
    if any(d["clicked"] for d in found):
        try:
            page.wait_for_function(_DROPDOWNS_SHOWN_JS, timeout=3_000)
        except Exception:
            pass
        for d in page.evaluate(_DROPDOWNS_HIDDEN_JS):
            report.add("solutions", f"dropdown {d!r}: does not open when clicked")

    _lap("dropdowns")
    # ---- internal links resolve to a file and anchor of the build
    hrefs = page.evaluate(
        "() => Array.from(document.querySelectorAll('a[href]')).map(a => a.href)"
        ".concat(Array.from(document.querySelectorAll('link[href], script[src], img[src]'))"
        ".map(e => e.href || e.src))"
    )
    local = [h for h in dict.fromkeys(hrefs) if h.startswith(base)]
    report.counts["links"] = len(local)
    for h in local:
        target, frag = _local_target(h, base, root)
        if target is not None and not target.exists() and (var := _left_out(target, root)):
            report.notes.append(f"link to a file not built in this run ({var}=0): {h}")
            continue
        if target is None or not target.exists():
            report.add("links", f"link to a file not in the build: {h}")
            continue
        if frag and target.suffix == ".html" and frag not in _ids_in(target):
            report.add("links", f"link to a missing anchor: {h}")

    _lap("links")
    # ---- weight
    total = own = 0
    for resp in responses:
        try:
            size = resp.request.sizes()["responseBodySize"]
        except Exception:
            size = int(resp.headers.get("content-length", 0) or 0)
        total += size
        report.sizes.append((resp.url, size))
        if "/_static/" not in resp.url:
            own += size
    report.total_bytes, report.own_bytes, report.requests = total, own, len(responses)
    if total > MAX_PAGE_BYTES:
        report.add("weight", f"page weighs {total / 2**20:.2f} MiB (> 3 MiB) over {len(responses)} requests")

    _lap("weight")
    # ---- layout, every dropdown open: boxes that overflow, formulas cut off; desktop, then phone width
    _check_layout(page, report, DESKTOP["width"])
    _check_phone_math(page, report, DESKTOP["width"])
    _lap("layout")
    if phone:
        page.evaluate("() => window.scrollTo(0, 0)")
        page.set_viewport_size(PHONE)
        page.wait_for_timeout(250)
        _check_layout(page, report, PHONE["width"])
        _check_phone_math(page, report, PHONE["width"])
        _check_phone_figures(page, report, PHONE["width"])
        # phone screenshot (after the checks: solutions shown open, animations paused)
        if shots is not None:
            stem = path.replace("/", "__").removesuffix(".html")
            page.screenshot(path=str(shots / f"{stem}__phone.jpg"), full_page=True, type="jpeg", quality=75)
    _lap("phone screenshot")
    page.close()
    report.seconds = time.monotonic() - t0
    return report


def search(context, base: str, query: str) -> list[str]:
    """Result links (relative to the build) of the book's own search page."""
    page = context.new_page()
    host = urlsplit(base).hostname
    page.route("**/*", lambda r: r.continue_() if urlsplit(r.request.url).hostname in (host, None)
               else r.abort("blockedbyclient"))
    page.goto(f"{base}search.html?q={query}", wait_until="load")
    page.wait_for_function(
        "() => { const s = document.querySelector('#search-results');"
        " return s && (s.querySelectorAll('ul.search li').length > 0 || /found|did not match/i.test(s.textContent)); }",
        timeout=15_000,
    )
    page.wait_for_timeout(300)
    links = page.evaluate(
        "() => Array.from(document.querySelectorAll('#search-results ul.search li a')).map(a => a.href)"
    )
    page.close()
    return [urlsplit(h).path[len(urlsplit(base).path):] for h in links]


def main(argv: list[str] | None = None) -> int:
    """``python tests/browser/bookcheck.py HTML_DIR [PAGE ...]``: print full reports (for authors)."""
    import argparse

    from playwright.sync_api import sync_playwright

    ap = argparse.ArgumentParser(description=main.__doc__)
    ap.add_argument("html", type=Path)
    ap.add_argument("pages", nargs="*", help="pages relative to HTML_DIR (default: all of --toc)")
    ap.add_argument("--toc", type=Path, default=Path(__file__).resolve().parents[2] / "_toc.yml")
    ap.add_argument("--shots", type=Path, default=None)
    ap.add_argument("--sizes", action="store_true", help="list every response and its size")
    args = ap.parse_args(argv)
    pages = args.pages or pages_from_toc(args.toc)
    bad = 0
    with BookServer(args.html) as server, sync_playwright() as p, opened_browser(p) as context:
        for path in pages:
            r = check_page(context, server.base, args.html, path, shots=args.shots)
            print(r.summary())
            for aspect, msgs in r.problems.items():
                for m in msgs:
                    bad += 1
                    print(f"   [{aspect}] {m}")
            print("   time: " + ", ".join(f"{k} {v:.1f}s" for k, v in r.timings.items() if v > 0.2))
            for n in dict.fromkeys(r.notes):
                print(f"   (note) {n}")
            if args.sizes:
                for url, size in sorted(r.sizes, key=lambda t: -t[1]):
                    print(f"   {size / 1024:8.1f} KiB  {url}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
