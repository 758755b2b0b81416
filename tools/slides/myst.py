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
import textwrap
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from markdown_it import MarkdownIt
from markdown_it.renderer import RendererHTML
from myst_parser.config.main import MdParserConfig
from myst_parser.parsers.mdit import create_md_parser

# ---------------------------------------------------------------- vocabulary

#: sphinx-proof directive kinds -> displayed name
PRF_KINDS = {
    "definition": "Definition",
    "theorem": "Theorem",
    "proposition": "Proposition",
    "lemma": "Lemma",
    "corollary": "Corollary",
    "proof": "Proof",
    "remark": "Remark",
    "example": "Example",
    "algorithm": "Algorithm",
    "axiom": "Axiom",
    "conjecture": "Conjecture",
    "criterion": "Criterion",
    "observation": "Observation",
    "property": "Property",
    "assumption": "Assumption",
    "notation": "Notation",
}

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

_DIRECTIVE_INFO = re.compile(r"^\{(?P<name>[A-Za-z][\w:.+-]*)\}[ \t]*(?P<arg>.*?)\s*$")
_OPEN = re.compile(r"^(?P<indent>[ ]{0,3})(?P<fence>`{3,}|:{3,})\{(?P<name>[A-Za-z][\w:.+-]*)\}[ \t]*(?P<arg>.*?)\s*$")
_PLAIN_FENCE = re.compile(r"^(?P<indent>[ ]{0,3})(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
_OPTION = re.compile(r"^:(?P<key>[\w-]+):(?:[ \t]+(?P<value>.*?))?\s*$")
_TARGET = re.compile(r"^\s{0,3}\(([^()\s]+)\)=\s*$")
_COMMENT = re.compile(r"^\s{0,3}%")
_HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
_EQ_LABEL = re.compile(r"(\$\$)[ \t]*\(([^()\s]+)\)[ \t]*$")
_ROLE = re.compile(r"\{(?P<name>[A-Za-z][\w:.+-]*)\}`(?P<text>[^`]*)`")
_LINK = re.compile(r"(?<![!\\])\[(?P<text>[^\]]*)\]\((?P<target>[^()\s]*)\)")
_IMAGE = re.compile(r"!\[(?P<alt>[^\]]*)\]\((?P<target>[^()\s]+)\)")
_EXPLICIT = re.compile(r"^(?P<text>.*?)\s*<(?P<target>[^<>]+)>$", re.S)


@dataclass
class Directive:
    """One parsed directive block."""

    name: str
    arg: str
    options: dict
    body: str


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


# ---------------------------------------------------------------- parsing


def _is_close(line: str, fence: str) -> bool:
    s = line.strip()
    return len(s) >= len(fence) and set(s) == {fence[0]}


def parse_options(lines: list[str]) -> tuple[dict, list[str]]:
    """Split a directive's content into its options and its body lines.

    Options are either leading ``:key: value`` lines or a leading YAML block
    between two ``---`` lines (only ``key: value`` pairs are read from it).
    """
    options: dict = {}
    i = 0
    if lines and lines[0].strip() == "---":
        for j in range(1, len(lines)):
            if lines[j].strip() == "---":
                for opt in lines[1:j]:
                    if ":" in opt:
                        key, _, value = opt.partition(":")
                        options[key.strip()] = value.strip()
                return options, lines[j + 1:]
        return options, lines  # unterminated: treat as body
    while i < len(lines):
        m = _OPTION.match(lines[i])
        if not m:
            break
        options[m.group("key")] = (m.group("value") or "").strip()
        i += 1
    return options, lines[i:]


@lru_cache(maxsize=1)
def _block_parser() -> MarkdownIt:
    """The book's own MyST block parser (myst-parser, with the extensions of _config.yml that make blocks)."""
    return create_md_parser(MdParserConfig(enable_extensions={"colon_fence", "dollarmath", "amsmath"}), RendererHTML)


def split_blocks(text: str) -> Iterator[str | Directive]:
    """Yield the pieces of ``text``: plain text (``str``) and top-level :class:`Directive` blocks.

    The blocks are found by myst-parser (the parser that builds the book):
    a top-level backtick or colon fence whose info is ``{name} argument``.
    Nested directives stay in the body of their parent (converted
    recursively); plain code fences are plain text, so nothing inside them is
    a directive. An unterminated directive runs to the end of the text, as in
    MyST. Text pieces are the source lines between the blocks, unchanged.
    """
    lines = text.split("\n")
    pos = 0
    for token in _block_parser().parse(text):
        if token.level != 0 or token.type not in ("fence", "colon_fence") or token.map is None:
            continue
        m = _DIRECTIVE_INFO.match(token.info)
        if not m:
            continue
        start, end = token.map
        if pos < start:
            yield "\n".join(lines[pos:start])
        content = token.content.removesuffix("\n")
        options, body_lines = parse_options(content.split("\n"))
        body = textwrap.dedent("\n".join(body_lines)).strip("\n")
        yield Directive(m.group("name").lower(), m.group("arg"), options, body)
        pos = end
    if pos < len(lines):
        yield "\n".join(lines[pos:])


# ---------------------------------------------------------------- inline text


def _readable(label: str) -> str:
    return label.rsplit("/", 1)[-1].replace("_", " ").replace("-", " ")


def resolve(target: str, ctx: Context) -> str:
    """The text a reference to ``target`` shows: its title if known."""
    target = target.strip()
    normal = re.sub(r"^(\.\./|\./|/)+", "", target)
    normal = re.sub(r"\.(md|ipynb)$", "", normal)
    for key in (target, target.lstrip("#"), normal, target.rsplit("/", 1)[-1], Path(target).stem):
        if key in ctx.labels:
            return str(ctx.labels[key])
    return _readable(target.lstrip("#"))


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
    m = _EXPLICIT.match(text)
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
    out = _ROLE.sub(lambda m: convert_role(m.group("name"), m.group("text"), ctx), text)
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
        pm = _PLAIN_FENCE.match(line)
        if in_fence:
            lines.append(line)
            if _is_close(line, in_fence):
                in_fence = None
            continue
        if pm:
            in_fence = pm.group("fence")
            lines.append(line)
            continue
        if _TARGET.match(line) or _COMMENT.match(line):
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
            if _is_close(line, in_fence):
                in_fence = None
            continue
        pm = _PLAIN_FENCE.match(line)
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


# ---------------------------------------------------------------- cell helpers


def split_at_headings(text: str, max_level: int = 3) -> list[str]:
    """Split a Markdown text before every heading of level <= ``max_level``.

    Headings inside directives or code fences do not split. Targets and
    comments right above a heading stay with it.
    """
    pieces: list[list[str]] = [[]]
    for piece in split_blocks(text):
        if isinstance(piece, Directive):
            pieces[-1].append(_unsplit(piece))
            continue
        in_fence = None
        for line in piece.split("\n"):
            if in_fence:
                pieces[-1].append(line)
                if _is_close(line, in_fence):
                    in_fence = None
                continue
            pm = _PLAIN_FENCE.match(line)
            if pm:
                in_fence = pm.group("fence")
                pieces[-1].append(line)
                continue
            h = _HEADING.match(line)
            if h and len(h.group(1)) <= max_level and any(x.strip() for x in pieces[-1]):
                # carry trailing targets/comments/blank lines with the heading
                carry: list[str] = []
                while pieces[-1] and (not pieces[-1][-1].strip() or _TARGET.match(pieces[-1][-1])
                                      or _COMMENT.match(pieces[-1][-1])):
                    carry.insert(0, pieces[-1].pop())
                if any(x.strip() for x in pieces[-1]):
                    pieces.append(carry)
                else:
                    pieces[-1].extend(carry)
            pieces[-1].append(line)
    texts = ["\n".join(p).strip("\n") for p in pieces]
    return [t for t in texts if t.strip()]


def split_cell(text: str) -> list[str]:
    """Split a Markdown cell before every heading (level <= 3) and around every top-level directive.

    Each piece can then get its own slide type: a definition inside a cell the
    author marked ``skip`` (for its prose) still reaches the slides.
    """
    out: list[str] = []
    for piece in split_at_headings(text):
        buf: list[str] = []
        for block in split_blocks(piece):
            if isinstance(block, Directive):
                if any(x.strip() for x in buf):
                    out.append("\n".join(buf).strip("\n"))
                buf = []
                out.append(_unsplit(block))
            else:
                buf.append(block)
        if any(x.strip() for x in buf):
            out.append("\n".join(buf).strip("\n"))
    return out


def _unsplit(d: Directive) -> str:
    """Re-serialise a parsed directive (used when only splitting, not converting)."""
    fence = "`" * max(3, _longest_backticks(d.body) + 1)
    opts = "".join(f":{k}: {v}\n" for k, v in d.options.items())
    return f"{fence}{{{d.name}}} {d.arg}".rstrip() + "\n" + opts + d.body + f"\n{fence}"


def _longest_backticks(text: str) -> int:
    runs = re.findall(r"^\s*(`{3,})", text, re.M)
    return max((len(r) for r in runs), default=0)


def leading_heading_level(text: str) -> int:
    """Level of the heading the text starts with (after targets/comments), else 0."""
    for line in text.split("\n"):
        if not line.strip() or _TARGET.match(line) or _COMMENT.match(line):
            continue
        h = _HEADING.match(line)
        return len(h.group(1)) if h else 0
    return 0


def leading_directive(text: str) -> str | None:
    """Name of the directive the text starts with (after targets/comments), if any."""
    for line in text.split("\n"):
        if not line.strip() or _TARGET.match(line) or _COMMENT.match(line):
            continue
        m = _OPEN.match(line)
        return m.group("name").lower() if m else None
    return None


def has_math(text: str) -> bool:
    return bool(re.search(r"\$|\\\[|\\\(|\{math\}|\\begin\{", text))


# ---------------------------------------------------------------- label index


def _strip_inline(text: str) -> str:
    def shown(m: re.Match[str]) -> str:
        explicit = _EXPLICIT.match(m.group("text"))
        return explicit.group("text") if explicit else m.group("text")

    text = _ROLE.sub(shown, text)
    return text.strip()


def index_labels(path: Path) -> dict:
    """Labels defined in one MyST source, mapped to the text a reference shows.

    * ``(label)=`` above a heading -> the heading text;
    * ``:label:`` of a prf directive -> "Definition (title)" etc.;
    * ``:label:`` of an exercise -> "Exercise (title)" or "the exercise";
    * the document itself (its stem) -> its first ``#`` heading.
    """
    text = path.read_text(encoding="utf-8")
    labels: dict = {}
    pending: list[str] = []
    in_fence = None
    for line in text.split("\n"):
        if in_fence:
            if _is_close(line, in_fence):
                in_fence = None
            continue
        m = _TARGET.match(line)
        if m:
            pending.append(m.group(1))
            continue
        h = _HEADING.match(line)
        if h:
            title = _strip_inline(h.group(2))
            if h.group(1) == "#" and path.stem not in labels:
                labels[path.stem] = title
            for lab in pending:
                labels[lab] = title
            pending = []
            continue
        if line.strip():
            pending = []
        pm = _PLAIN_FENCE.match(line)
        if pm and not _OPEN.match(line):
            in_fence = pm.group("fence")

    def walk(t: str) -> None:
        for piece in split_blocks(t):
            if not isinstance(piece, Directive):
                continue
            label = piece.options.get("label")
            k = piece.name.split(":", 1)[-1]
            title = _strip_inline(piece.arg)
            if label:
                if k in PRF_KINDS:
                    labels[label] = f"{PRF_KINDS[k]} ({title})" if title else f"the {k}"
                elif k == "exercise":
                    labels[label] = f"Exercise ({title})" if title else "the exercise"
                elif k in {"figure", "math"}:
                    labels[label] = "the figure" if k == "figure" else "the equation"
                else:
                    labels[label] = title or _readable(label)
            walk(piece.body)

    walk(text)
    return labels
