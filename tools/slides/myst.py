"""Convert MyST Markdown to the Markdown + HTML that nbconvert's slides render.

nbconvert knows CommonMark and dollar math, nothing of MyST: a
``{prf:definition}`` would show as a literal code block. This module rewrites a
Markdown cell's source so that

* directives (```` ```{name} ```` and ``:::{name}`` fences, options given as
  ``:key: value`` lines or a ``---`` YAML block, nested to any depth) become
  ``<div class="box box-KIND">`` boxes whose title and body stay Markdown;
* ``{solution}`` blocks and everything between ``{solution-start}`` and
  ``{solution-end}`` (which may span cells) are dropped;
* ``{math}`` blocks become ``$$ ... $$`` display math;
* roles (``{ref}``, ``{doc}``, ``{prf:ref}``, ``{numref}``, ``{eq}``, ...)
  become plain text, resolved to the target's title when it is known;
* targets ``(label)=``, comments ``% ...`` and equation labels
  ``$$ ... $$ (label)`` disappear.

Directive blocks are found by myst-parser's own block parser (the one that
builds the book); the rest is string processing with no nbconvert import, so
it is unit-tested directly (tests/slides/test_myst.py).
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass, field
from pathlib import Path

from .reader import (
    COMMENT,
    EXPLICIT,
    PLAIN_FENCE,
    PRF_KINDS,
    ROLE,
    TARGET,
    Directive,
    is_close,
    readable,
    split_blocks,
)

# ---------------------------------------------------------------- vocabulary

#: admonition directives -> displayed title
ADMONITIONS = {
    "note": "Note",
    "warning": "Warning",
    "tip": "Tip",
    "important": "Important",
    "caution": "Caution",
    "attention": "Attention",
    "danger": "Danger",
    "error": "Error",
    "hint": "Hint",
    "seealso": "See also",
}

#: directives that carry nothing for a slide
DROPPED = {"toctree", "tableofcontents", "bibliography", "glossary", "index", "only"}

#: directives whose content is code
CODE_DIRECTIVES = {"code-block", "code", "sourcecode", "literalinclude"}

#: kinds that open their own (sub)slide when the author gave no slide metadata
KEY_KINDS = {"definition", "theorem", "proposition", "lemma", "corollary", "exercise"}
_EQ_LABEL = re.compile(r"(\$\$)[ \t]*\(([^()\s]+)\)[ \t]*$")
_LINK = re.compile(r"(?<![!\\])\[(?P<text>[^\]]*)\]\((?P<target>[^()\s]*)\)")
_IMAGE = re.compile(r"!\[(?P<alt>[^\]]*)\]\((?P<target>[^()\s]+)\)")


@dataclass
class Context:
    """State carried across the cells of one notebook.

    ``labels`` maps a label (section target, prf label, exercise label, doc
    name) to the text a role pointing at it shows. ``in_solution`` is True
    between ``{solution-start}`` and ``{solution-end}``, which may be in
    different cells. ``images`` collects (source path, name in deck) pairs for
    local figures the deck must ship next to it.
    """

    labels: dict = field(default_factory=dict)
    source_dir: Path | None = None
    asset_prefix: str = ""
    in_solution: bool = False
    images: list = field(default_factory=list)
    warnings: list = field(default_factory=list)


# ---------------------------------------------------------------- inline text


def resolve(target: str, ctx: Context) -> str:
    """The text a reference to ``target`` shows: its title if known."""
    target = target.strip()
    normal = re.sub(r"^(\.\./|\./|/)+", "", target)
    normal = re.sub(r"\.(md|ipynb)$", "", normal)
    for key in (target, target.lstrip("#"), normal, target.rsplit("/", 1)[-1], Path(target).stem):
        if key in ctx.labels:
            return str(ctx.labels[key])
    return readable(target.lstrip("#"))


def convert_role(name: str, text: str, ctx: Context) -> str:
    """Render one role ``{name}`text``` as slide text (never a live link)."""
    name = name.lower()
    if name == "math":
        return f"${text}$"
    if name in {"sub", "sup", "kbd"}:
        return f"<{name}>{html.escape(text)}</{name}>"
    if name in {"code", "literal", "file", "samp", "command"}:
        return f"`{text}`"
    if name == "abbr":
        return re.sub(r"\s*\([^)]*\)\s*$", "", text)
    m = EXPLICIT.match(text)
    if m and m.group("text"):
        shown, target = m.group("text"), m.group("target")
        if "%s" in shown or "{number}" in shown or "{name}" in shown:
            title = resolve(target, ctx)
            shown = shown.replace("%s", "").replace("{number}", "").replace("{name}", title)
            shown = re.sub(r"\s+", " ", shown).strip()
        return shown
    target = (m.group("target") if m else text).strip()
    if name == "eq":
        return "(" + resolve(target, ctx) + ")" if target in ctx.labels else "the equation"
    if name in {"ref", "doc", "prf:ref", "numref", "any", "term", "download", "cite", "external"} or ":" in name:
        return resolve(target, ctx) if name not in {"term", "cite"} else target
    return text


_PROTECT = re.compile(r"(`+)(?:.|\n)*?\1|\$\$(?:.|\n)*?\$\$|\$(?!\$)(?:[^$\n]|\n(?!\s*\n))+?\$"
                      r"|\\\[(?:.|\n)*?\\\]|\\\((?:.|\n)*?\\\)")


def convert_inline(text: str, ctx: Context) -> str:
    """Roles, cross-reference links, equation labels and local images in ``text``.

    Links and images are not looked for inside code spans or math; inline math
    spread over several lines is joined into one line.
    """
    out = ROLE.sub(lambda m: convert_role(m.group("name"), m.group("text"), ctx), text)
    out = "\n".join(_EQ_LABEL.sub(r"\1", line) for line in out.split("\n"))

    def link(m: re.Match[str]) -> str:
        target = m.group("target")
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
            return m.group(0)
        return m.group("text") or resolve(target, ctx)

    def plain(segment: str) -> str:
        segment = _LINK.sub(link, segment)
        return _IMAGE.sub(lambda m: _image_markdown(m.group("alt"), m.group("target"), ctx), segment)

    pieces = []
    last = 0
    for m in _PROTECT.finditer(out):
        pieces.append(plain(out[last:m.start()]))
        token = m.group(0)
        if token.startswith("$") and not token.startswith("$$"):
            # inline math over several lines: one line, so that a line starting
            # with "+" or "-" inside it is not read as a Markdown list
            token = re.sub(r"\s*\n\s*", " ", token)
        pieces.append(token)
        last = m.end()
    pieces.append(plain(out[last:]))
    return "".join(pieces)


def _image_src(target: str, ctx: Context) -> str:
    if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
        return target  # data: or a URL; a remote URL is caught by the browser tests
    if ctx.source_dir is None:
        return target
    src = (ctx.source_dir / target).resolve()
    if not src.is_file():
        ctx.warnings.append(f"image not found: {target}")
        return target
    name = f"{ctx.asset_prefix}{src.name}"
    ctx.images.append((src, name))
    return name


def _image_markdown(alt: str, target: str, ctx: Context) -> str:
    return f'<img class="slide-image" alt="{html.escape(alt)}" src="{html.escape(_image_src(target, ctx))}">'


# ---------------------------------------------------------------- blocks


def _box(kind: str, title: str, body_md: str, extra_class: str = "") -> str:
    cls = f"box box-{kind}" + (f" {extra_class}" if extra_class else "")
    title_part = f'<div class="box-title">\n\n{title}\n\n</div>\n' if title else ""
    return f'<div class="{cls}">\n{title_part}<div class="box-body">\n\n{body_md}\n\n</div>\n</div>'


def _display_math(body: str) -> str:
    parts = [p.strip() for p in re.split(r"\n\s*\n", body) if p.strip()]
    out = []
    for p in parts:
        if "\\\\" in p and "\\begin" not in p:
            p = "\\begin{split}" + p + "\\end{split}"
        out.append(f"$$\n{p}\n$$")
    return "\n\n".join(out)


def _title(name: str, arg: str, ctx: Context) -> str:
    arg = convert_inline(arg, ctx).strip()
    return f"**{name}** ({arg})" if arg else f"**{name}**"


def convert_directive(d: Directive, ctx: Context) -> str:
    """Markdown/HTML for one directive (its body converted recursively)."""
    name = d.name
    if name in {"solution", "solution-end", "solution-start"}:
        return ""
    if name in DROPPED:
        return ""
    if name == "math":
        return _display_math(d.body)
    if name in CODE_DIRECTIVES:
        lang = d.arg.split()[0] if d.arg else ""
        return f"```{lang}\n{d.body}\n```"
    if name == "raw":
        return d.body if "html" in d.arg.lower() else ""
    if name in {"figure", "image"}:
        src = _image_src(d.arg.strip(), ctx)
        alt = d.options.get("alt", "")
        img = f'<img class="slide-image" alt="{html.escape(alt)}" src="{html.escape(src)}">'
        caption = convert_markdown(d.body, ctx) if (name == "figure" and d.body) else ""
        if caption:
            return f'<figure class="slide-figure">\n{img}\n<figcaption>\n\n{caption}\n\n</figcaption>\n</figure>'
        return f'<figure class="slide-figure">\n{img}\n</figure>'
    body = convert_markdown(d.body, ctx)
    kind = name.split(":", 1)[1] if name.startswith("prf:") else name
    if name.startswith("prf:") or kind in PRF_KINDS:
        shown = PRF_KINDS.get(kind, kind.replace("-", " ").title())
        if kind == "proof":
            return _box("proof", "**Proof.**", body + '\n\n<p class="qed">&#8718;</p>')
        return _box(kind, _title(shown, d.arg, ctx), body)
    if name == "exercise":
        title = convert_inline(d.arg, ctx).strip()
        return _box("exercise", f"**Try it** ({title})" if title else "**Try it**", body)
    if name in ADMONITIONS:
        # these admonitions take no argument: MyST puts first-line text in the body
        first = convert_inline(d.arg, ctx).strip()
        if first:
            body = f"**{first}**\n\n{body}" if body else f"**{first}**"
        return _box(name, f"**{ADMONITIONS[name]}**", body)
    if name == "admonition":
        classes = d.options.get("class", "").split()
        colour = next((c for c in classes if c in ADMONITIONS), "note")
        title = convert_inline(d.arg, ctx).strip() or "Note"
        return _box(colour, f"**{title}**", body)
    # anything else (margin, sidebar, dropdown, card, tab-item, topic, epigraph, ...)
    title = convert_inline(d.arg, ctx).strip()
    return _box("other", f"**{title}**" if title else "", body, extra_class=f"box-{re.sub(r'[^a-z0-9-]', '-', name)}")


def _clean_lines(text: str) -> str:
    lines = []
    in_fence = None
    for line in text.split("\n"):
        pm = PLAIN_FENCE.match(line)
        if in_fence:
            lines.append(line)
            if is_close(line, in_fence):
                in_fence = None
            continue
        if pm:
            in_fence = pm.group("fence")
            lines.append(line)
            continue
        if TARGET.match(line) or COMMENT.match(line):
            continue
        lines.append(line)
    return "\n".join(lines)


def _convert_text(text: str, ctx: Context) -> str:
    """Convert plain Markdown (no directive) outside code fences."""
    out = []
    chunk: list[str] = []
    in_fence = None
    for line in _clean_lines(text).split("\n"):
        if in_fence:
            out.append(line)
            if is_close(line, in_fence):
                in_fence = None
            continue
        pm = PLAIN_FENCE.match(line)
        if pm:
            if chunk:
                out.append(convert_inline("\n".join(chunk), ctx))
                chunk = []
            in_fence = pm.group("fence")
            out.append(line)
            continue
        chunk.append(line)
    if chunk:
        out.append(convert_inline("\n".join(chunk), ctx))
    return "\n".join(out)


def convert_markdown(text: str, ctx: Context) -> str:
    """Convert a MyST Markdown text to slide Markdown (see the module docstring).

    ``ctx.in_solution`` is honoured on entry and updated on exit, so a
    solution opened in one cell swallows the following cells until its end.
    """
    out: list[str] = []
    for piece in split_blocks(text):
        if isinstance(piece, Directive):
            if piece.name == "solution-start":
                ctx.in_solution = True
                continue
            if piece.name == "solution-end":
                ctx.in_solution = False
                continue
            if ctx.in_solution:
                continue
            out.append(convert_directive(piece, ctx))
        elif not ctx.in_solution:
            out.append(_convert_text(piece, ctx))
    result = "\n\n".join(p.strip("\n") for p in out if p.strip())
    return result
