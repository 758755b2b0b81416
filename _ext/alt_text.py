"""Alt text for the images of a page that have none (used by ``offline_fixes.fill_alt_text``).

myst-nb renders a matplotlib output as ``<img>`` whose alt is its file path,
and matplotlib's JS animation has an ``<img>`` with no alt. Each such image
gets, in this order: an explicit ``mystnb: image: alt:`` (kept as is), the
figure caption, the titles the cell's code sets on the figure
(``set_title``/``suptitle``/``plt.title``), else the section the output sits
in. Alt text is read aloud, so TeX is turned into words (:func:`plain`).
"""

from __future__ import annotations

import ast
import html
import re
from pathlib import Path

from docutils import nodes
from notebook_pages import is_notebook, read


def titles_from_code(source: str) -> list[str]:
    """String-literal titles a cell sets on its figure, in order.

    Looks for ``ax.set_title("...")``, ``fig.suptitle("...")`` and
    ``plt.title("...")`` with a literal first argument (f-strings keep their
    literal parts). The code is parsed, never run.

    >>> titles_from_code('ax.set_title("UR5"); plt.plot(x)')
    ['UR5']
    """
    found: list[str] = []
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return found
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or not node.args:
            continue
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
        if name not in ("set_title", "suptitle", "title"):
            continue
        arg = node.args[0]
        text = None
        if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
            text = arg.value
        elif isinstance(arg, ast.JoinedStr):
            text = "".join(
                v.value for v in arg.values if isinstance(v, ast.Constant) and isinstance(v.value, str)
            )
        if text:
            text = re.sub(r"\$([^$]*)\$", r"\1", text)  # drop mathtext dollars
            text = re.sub(r"\\(mathrm|mathcal|mathbf|operatorname)\{([^}]*)\}", r"\2", text)
            text = " ".join(text.replace("\\", "").split())
            if text and text not in found:
                found.append(text)
    return found


def plain(text: str) -> str:
    """Alt text is read aloud: TeX commands as words, no braces or backslashes.

    >>> plain(r"arm at $\\theta = (0.5, 0.6)$, T_{sb}")
    'arm at theta = (0.5, 0.6), T_sb'
    """
    text = text.replace("$", "")
    text = re.sub(r"\\(mathrm|mathcal|mathbf|operatorname|text)\{([^}]*)\}", r"\2", text)
    text = re.sub(r"\\([a-zA-Z]+)", r"\1", text)
    text = text.replace("{", "").replace("}", "").replace("\\", "")
    return " ".join(text.split())


_IMG_TAG = re.compile(r"<img\b[^>]*>", re.IGNORECASE)
_HAS_ALT = re.compile(r"\balt\s*=", re.IGNORECASE)


def add_alt_to_html(fragment: str, alt: str) -> str:
    """Give every ``<img>`` of an HTML fragment without an ``alt`` attribute one.

    >>> add_alt_to_html('<img src="a.png"><img alt="kept" src="b.png">', 'A "plot"')
    '<img alt="A &quot;plot&quot;" src="a.png"><img alt="kept" src="b.png">'
    """

    def fix(match: re.Match[str]) -> str:
        tag = match.group(0)
        if _HAS_ALT.search(tag):
            return tag
        return tag[:4] + f' alt="{html.escape(alt, quote=True)}"' + tag[4:]

    return _IMG_TAG.sub(fix, fragment)


def cell_sources(source: Path) -> dict[int, str]:
    """Code of each cell of a notebook page, by cell index (empty if the page is no notebook)."""
    if not is_notebook(source):
        return {}
    return {i: c.source for i, c in enumerate(read(source).cells) if c.cell_type == "code"}


def _ancestor(node: nodes.Node, kind: type[nodes.Element]) -> nodes.Element | None:
    parent = node.parent
    while parent is not None and not isinstance(parent, kind):
        parent = parent.parent
    return parent


def _cell_index(node: nodes.Node) -> int | None:
    parent = node.parent
    while parent is not None:
        if isinstance(parent, nodes.container) and parent.get("nb_element") == "cell_code":
            idx = parent.get("cell_index")
            return int(idx) if idx is not None else None
        parent = parent.parent
    return None


class _Describer:
    """Descriptions of the images of one page; the notebook is read once, when first needed."""

    def __init__(self, source: Path, page_title: str) -> None:
        self.source = source
        self.page_title = page_title
        self._sources: dict[int, str] | None = None

    def code(self, index: int) -> str:
        if self._sources is None:
            self._sources = cell_sources(self.source)
        return self._sources.get(index, "")

    def __call__(self, node: nodes.Node, kind: str) -> str:
        figure = _ancestor(node, nodes.figure)
        if figure is not None:
            for child in figure.children:
                if isinstance(child, nodes.caption) and child.astext().strip():
                    return plain(child.astext().strip())
        idx = _cell_index(node)
        if idx is not None:
            titles = titles_from_code(self.code(idx))
            if titles:
                return plain(f"{kind}: " + "; ".join(titles))
        section = _ancestor(node, nodes.section)
        title = next((c.astext() for c in section.children if isinstance(c, nodes.title)), None) if section else None
        title = title or self.page_title
        return plain(f"{kind} in the section “{title}”" if title else kind)


def describe_image(doctree: nodes.document, source: Path, page_title: nodes.Node | None) -> int:
    """Fill in the missing alt text of ``doctree`` (the page read from ``source``); return how many images got one."""
    describe = _Describer(source, page_title.astext() if page_title is not None else "")
    changed = 0
    for img in list(doctree.findall(nodes.image)):
        alt = (img.get("alt") or "").strip()
        uri = img.get("uri", "")
        if alt and alt != uri and Path(alt).name != Path(uri).name:
            continue
        img["alt"] = describe(img, "Figure")
        changed += 1
    for raw in list(doctree.findall(nodes.raw)):
        if "html" not in raw.get("format", "").split():
            continue
        text = raw.astext()
        if "<img" not in text.lower():
            continue
        kind = "Animation" if "_anim_img" in text or "anim-buttons" in text else "Figure"
        fixed = add_alt_to_html(text, describe(raw, kind))
        if fixed != text:
            new = nodes.raw(fixed, fixed, **{k: v for k, v in raw.attributes.items() if k != "ids"})
            new["ids"] = list(raw.get("ids", []))
            raw.replace_self(new)
            changed += 1
    return changed
