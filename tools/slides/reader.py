"""Read MyST Markdown with the book's own parser: directive blocks, headings, labels.

``split_blocks`` finds the top-level directive blocks of a Markdown text with
myst-parser (the parser that builds the book); the helpers split a cell into
the pieces a slide shows (:func:`split_cell`), tell what a piece starts with,
and index the labels a source defines (:func:`index_labels`). Conversion to
slide Markdown is in :mod:`tools.slides.myst`.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Iterator
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from markdown_it import MarkdownIt
from markdown_it.renderer import RendererHTML
from myst_parser.config.main import MdParserConfig
from myst_parser.parsers.mdit import create_md_parser

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

_DIRECTIVE_INFO = re.compile(r"^\{(?P<name>[A-Za-z][\w:.+-]*)\}[ \t]*(?P<arg>.*?)\s*$")
OPEN = re.compile(r"^(?P<indent>[ ]{0,3})(?P<fence>`{3,}|:{3,})\{(?P<name>[A-Za-z][\w:.+-]*)\}[ \t]*(?P<arg>.*?)\s*$")
PLAIN_FENCE = re.compile(r"^(?P<indent>[ ]{0,3})(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
_OPTION = re.compile(r"^:(?P<key>[\w-]+):(?:[ \t]+(?P<value>.*?))?\s*$")
TARGET = re.compile(r"^\s{0,3}\(([^()\s]+)\)=\s*$")
COMMENT = re.compile(r"^\s{0,3}%")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
ROLE = re.compile(r"\{(?P<name>[A-Za-z][\w:.+-]*)\}`(?P<text>[^`]*)`")
EXPLICIT = re.compile(r"^(?P<text>.*?)\s*<(?P<target>[^<>]+)>$", re.S)


@dataclass
class Directive:
    """One parsed directive block."""

    name: str
    arg: str
    options: dict
    body: str


# ---------------------------------------------------------------- parsing


def is_close(line: str, fence: str) -> bool:
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


def readable(label: str) -> str:
    return label.rsplit("/", 1)[-1].replace("_", " ").replace("-", " ")


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
                if is_close(line, in_fence):
                    in_fence = None
                continue
            pm = PLAIN_FENCE.match(line)
            if pm:
                in_fence = pm.group("fence")
                pieces[-1].append(line)
                continue
            h = HEADING.match(line)
            if h and len(h.group(1)) <= max_level and any(x.strip() for x in pieces[-1]):
                # carry trailing targets/comments/blank lines with the heading
                carry: list[str] = []
                while pieces[-1] and (not pieces[-1][-1].strip() or TARGET.match(pieces[-1][-1])
                                      or COMMENT.match(pieces[-1][-1])):
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
        if not line.strip() or TARGET.match(line) or COMMENT.match(line):
            continue
        h = HEADING.match(line)
        return len(h.group(1)) if h else 0
    return 0


def leading_directive(text: str) -> str | None:
    """Name of the directive the text starts with (after targets/comments), if any."""
    for line in text.split("\n"):
        if not line.strip() or TARGET.match(line) or COMMENT.match(line):
            continue
        m = OPEN.match(line)
        return m.group("name").lower() if m else None
    return None


def has_math(text: str) -> bool:
    return bool(re.search(r"\$|\\\[|\\\(|\{math\}|\\begin\{", text))


# ---------------------------------------------------------------- label index


def _strip_inline(text: str) -> str:
    def shown(m: re.Match[str]) -> str:
        explicit = EXPLICIT.match(m.group("text"))
        return explicit.group("text") if explicit else m.group("text")

    text = ROLE.sub(shown, text)
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
            if is_close(line, in_fence):
                in_fence = None
            continue
        m = TARGET.match(line)
        if m:
            pending.append(m.group(1))
            continue
        h = HEADING.match(line)
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
        pm = PLAIN_FENCE.match(line)
        if pm and not OPEN.match(line):
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
                    labels[label] = title or readable(label)
            walk(piece.body)

    walk(text)
    return labels
