"""Sphinx extension: what a published book needs besides its pages.

* **Where the site lives.** ``BOOK_BASE_URL`` (environment) is the address the
  site is served from, e.g. ``https://owner.github.io/jacobians/``. It becomes
  ``html_baseurl`` (sphinx-sitemap writes ``sitemap.xml`` with it), the site
  address of the social-card tags (sphinxext-opengraph) and the path prefix of
  the 404 page's links (sphinx-notfound-page: a 404 page is served at any
  depth, so its links must be absolute). Unset, a local build says
  ``http://localhost:8000/`` (``python -m http.server -d _build/html``).
* **Version and build date in the footer.** The version is the top entry of
  ``CHANGELOG.md``; the build fails if it is not the library's version in
  ``pyproject.toml``, so the two never drift apart. The date is
  ``SOURCE_DATE_EPOCH`` when set (reproducible builds), else today (UTC).
  Both join the course's ``extra_footer`` with the licences.
* **A description of each page** (``<meta name="description">`` and
  ``og:description``): its first paragraphs of prose, math read as plain words
  (``alt_text.plain``), without the "Lecture slides" link, at most 200
  characters. sphinxext-opengraph would take the page's first text as it is,
  TeX included.
* **The root ``index.html``.** Jupyter Book writes a bare ``<meta refresh>``
  there (no title, no language); this writes a small HTML page that redirects
  to the first page and has a title, ``lang`` and a link for readers whose
  browser does not follow the redirect.
"""

from __future__ import annotations

import datetime as _dt
import html
import os
import re
import tomllib
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.config import Config
from sphinx.errors import ConfigError

DEFAULT_BASE_URL = "http://localhost:8000/"
CODE_LICENCE = "MIT"
TEXT_LICENCE = "CC BY 4.0"
_VERSION_HEADING = re.compile(r"^## \[?(\d+\.\d+\.\d+[^\]\s]*)\]?(?:\s*-\s*(\S+))?", re.MULTILINE)


def base_url(environ: dict[str, str] | os._Environ[str] | None = None) -> str:
    """The site's address, ending in "/"; a clear error for one that is no http(s) address."""
    env = os.environ if environ is None else environ
    url = env.get("BOOK_BASE_URL", "").strip() or DEFAULT_BASE_URL
    parts = urlparse(url)
    if parts.scheme not in ("http", "https") or not parts.netloc:
        raise ConfigError("BOOK_BASE_URL must be an http(s) address such as https://owner.github.io/repo/, "
                          f"not {url!r}")
    return url if url.endswith("/") else url + "/"


def changelog_version(text: str) -> str:
    """Version of the newest entry of a Keep-a-Changelog file (its first ``## [x.y.z]`` heading)."""
    m = _VERSION_HEADING.search(text)
    if m is None:
        raise ConfigError("CHANGELOG.md has no '## [x.y.z] - date' entry: add one for this release")
    return m.group(1)


def package_version(pyproject: Path) -> str:
    return str(tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]["version"])


def build_date(environ: dict[str, str] | os._Environ[str] | None = None) -> str:
    env = os.environ if environ is None else environ
    epoch = env.get("SOURCE_DATE_EPOCH")
    when = (_dt.datetime.fromtimestamp(int(epoch), _dt.UTC) if epoch
            else _dt.datetime.now(_dt.UTC))
    return when.date().isoformat()


def footer_note(version: str, date: str) -> str:
    """The footer's second line: version, build date and the two licences (links relative to the root)."""
    return (f'<p class="book-version">Version {html.escape(version)}, built {html.escape(date)}. '
            f"Code under the {CODE_LICENCE} licence, text and figures under {TEXT_LICENCE} "
            f"(see LICENSE and LICENSE-content in the repository).</p>")


def redirect_page(title: str, target: str) -> str:
    t, u = html.escape(title), html.escape(target)
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{t}</title>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<meta http-equiv=\"refresh\" content=\"0; url={u}\">\n<link rel=\"canonical\" href=\"{u}\">\n"
            f"</head>\n<body>\n<p><a href=\"{u}\">{t}: the course starts here</a>.</p>\n</body>\n</html>\n")


def configure(app: Sphinx, config: Config) -> None:
    root = Path(app.confdir)
    version = changelog_version((root / "CHANGELOG.md").read_text(encoding="utf-8"))
    pyproject = root / "pyproject.toml"
    if pyproject.exists() and package_version(pyproject) != version:
        raise ConfigError(f"CHANGELOG.md's newest entry is {version} but pyproject.toml says "
                          f"{package_version(pyproject)}: make them agree")
    config.version = config.release = version
    url = base_url()
    config.html_baseurl = url
    config.ogp_site_url = url
    prefix = urlparse(url).path
    config.notfound_urls_prefix = prefix
    start = prefix + "index.html"  # the site's root page (it leads to the first chapter)
    config.notfound_context = {
        "title": "Page not found",
        "body": ("<h1>Page not found</h1><p>There is no page at this address. The course starts at "
                 f"<a href=\"{html.escape(start)}\">{html.escape(str(config.html_title or config.project))}</a>; "
                 "its sidebar lists "
                 "every chapter, and its search box finds a word on any page.</p>"),
    }
    options = dict(config.html_theme_options or {})
    options["extra_footer"] = (f"<p>{options.get('extra_footer', '')}</p>" if options.get("extra_footer") else "") \
        + footer_note(version, build_date())
    config.html_theme_options = options


DESCRIPTION_CHARS = 200
_GREEK = {name: chr(code) for name, code in (
    ("alpha", 0x3B1), ("beta", 0x3B2), ("gamma", 0x3B3), ("delta", 0x3B4), ("epsilon", 0x3B5), ("theta", 0x3B8),
    ("lambda", 0x3BB), ("mu", 0x3BC), ("pi", 0x3C0), ("sigma", 0x3C3), ("tau", 0x3C4), ("phi", 0x3C6),
    ("omega", 0x3C9), ("Omega", 0x3A9), ("Delta", 0x394), ("Sigma", 0x3A3))}
_SYMBOLS = {**_GREEK, "dots": "…", "ldots": "…", "cdots": "…", "times": "×", "cdot": "·", "in": "∈",
            "to": "→", "le": "≤", "ge": "≥", "neq": "≠", "approx": "≈", "top": "ᵀ", "infty": "∞"}


def plain_math(tex: str) -> str:
    """Inline TeX as text a search engine shows: θ̇_1, …, θ̇_n for \\dot\\theta_1,\\dots,\\dot\\theta_n."""
    s = re.sub(r"\\(?:mathrm|mathcal|mathbf|operatorname|text)\{([^}]*)\}", r"\1", tex)
    s = re.sub(r"\\(dot|ddot|hat)(?![A-Za-z])\s*\{?\\?([A-Za-z])([A-Za-z]*)\}?",
               lambda m: _SYMBOLS.get(m.group(2) + m.group(3), m.group(2) + m.group(3))
               + {"dot": "\u0307", "ddot": "\u0308", "hat": "\u0302"}[m.group(1)], s)
    s = re.sub(r"\\([A-Za-z]+)", lambda m: _SYMBOLS.get(m.group(1), m.group(1)), s)
    s = s.replace("{", "").replace("}", "").replace("\\", "")
    s = re.sub(r",(?=\S)", ", ", s)
    return " ".join(s.split())
_SKIP_CLASSES = {"slides-link", "admonition-title", "caption"}


def page_description(doctree: nodes.document, limit: int = DESCRIPTION_CHARS) -> str:
    """The page's opening prose in plain words, cut at a word before ``limit`` characters."""
    parts: list[str] = []
    size = 0
    for para in doctree.findall(nodes.paragraph):
        if _SKIP_CLASSES & set(para.get("classes", [])) or any(
                isinstance(a, nodes.Admonition | nodes.caption | nodes.table | nodes.footnote)
                or _SKIP_CLASSES & set(a.get("classes", [])) for a in _ancestors(para)):
            continue
        bits = []
        for node in para.findall(nodes.Text):
            math = next((a for a in _ancestors(node) if isinstance(a, nodes.math)), None)
            bits.append(plain_math(node.astext()) if math is not None else node.astext())
        text = " ".join("".join(bits).split())
        if text:
            parts.append(text)
            size += len(text) + 1
        if size >= limit:
            break
    text = " ".join(parts)
    if len(text) <= limit:
        return text
    cut = text[: limit - 1].rsplit(" ", 1)[0].rstrip(",;:")
    return cut + "…"


def _ancestors(node: nodes.Node) -> list[nodes.Element]:
    out = []
    parent = node.parent
    while parent is not None:
        out.append(parent)
        parent = parent.parent
    return out


def add_description(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any],
                    doctree: nodes.document | None) -> None:
    if doctree is None or app.builder.name != "html":
        return
    text = page_description(doctree)
    if not text:
        return
    context["metatags"] = context.get("metatags", "") + f'\n<meta name="description" content="{html.escape(text)}" />'
    meta = context.get("meta")
    if meta is None:
        context["meta"] = meta = {}
    meta.setdefault("og:description", text)


def write_root_redirect(app: Sphinx, exception: Exception | None) -> None:
    if exception is not None or app.builder.name != "html":
        return
    target = app.builder.get_target_uri(app.config.root_doc)
    title = str(app.config.html_title or app.config.project)
    Path(app.outdir, "index.html").write_text(redirect_page(title, target), encoding="utf-8")


def no_404_in_decks(app: Sphinx) -> None:
    """The decks (revealjs builder, same configuration) get no 404 page: its template is the book's."""
    if app.builder.name == "html":
        return
    listeners = app.events.listeners.get("html-collect-pages", [])
    ours = [x for x in listeners if getattr(x.handler, "__module__", "").startswith("notfound")]
    for x in ours:
        app.disconnect(x.id)


def no_canonical_in_decks(app: Sphinx, pagename: str, templatename: str, context: dict[str, Any],
                          doctree: Any) -> None:
    """A deck is not the book's page: it carries no ``<link rel="canonical">`` to the site (it must work from
    a copy of ``slides/`` alone, and a link to the served book would be the only address it names)."""
    if app.builder.name != "html":
        context["pageurl"] = None


def setup(app: Sphinx) -> dict[str, Any]:
    app.connect("builder-inited", no_404_in_decks)
    app.connect("html-page-context", no_canonical_in_decks)
    app.connect("config-inited", configure, priority=100)
    # before sphinxext-opengraph (500), which then keeps this description
    app.connect("html-page-context", add_description, priority=400)
    # before sphinx-external-toc's bare redirect (it writes only when no index.html exists)
    app.connect("build-finished", write_root_redirect, priority=100)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
