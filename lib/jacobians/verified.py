"""What a page's hidden checks verified, shown as one collapsed box per section.

A chapter proves each formula by a hidden code cell (a sympy identity or finite
differences of the forward kinematics) that ends with ``assert``. When the
asserts pass, the cell records the formula it verified, written in real math,
and how it was checked::

    verified = Verified()                       # once, in the page's set-up

    assert is_zero_matrix(J_sym - J_typed)      # a hidden check cell
    verified(r"$J_a = \\partial\\chi/\\partial\\theta$ of the 2R arm",
             "sympy, from the three transforms; finite differences of `arm.fk`")

    verified.box()                              # last cell of the section

``box()`` returns a MyST dropdown admonition listing every record since the
previous box (the page must set ``mystnb: render_markdown_format: myst``), so a
reader sees one "Verified by code" box per section, closed until opened. A
record is only ever made after the asserts above it have passed, so the box
cannot claim a check that did not run.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Verified", "VerifiedBox"]


@dataclass(frozen=True)
class VerifiedBox:
    """The records of one section, rendered as a MyST dropdown admonition."""

    items: tuple[tuple[str, str], ...]
    title: str = "Verified by code"

    def _repr_markdown_(self) -> str:
        n = len(self.items)
        lines = [
            f":::{{admonition}} {self.title} ({n} check{'s' if n != 1 else ''})",
            ":class: dropdown verified",
            "",
        ]
        for statement, how in self.items:
            lines.append(f"- {statement}")
            lines.append(f"  <br>*Checked by:* {how}")
        lines.append(":::")
        return "\n".join(lines)

    def __repr__(self) -> str:  # plain-text front ends (a terminal, nbval)
        body = "\n".join(f"  - {s}  [{how}]" for s, how in self.items)
        return f"{self.title}:\n{body}"


class Verified:
    """Collects the statements a page's checks have verified (see the module doc)."""

    def __init__(self) -> None:
        self._pending: list[tuple[str, str]] = []
        self.total = 0

    def __call__(self, statement: str, how: str) -> None:
        """Record that ``statement`` (MyST text, math in ``$...$``) was checked by ``how``."""
        if not isinstance(statement, str) or not statement.strip():
            raise TypeError(f"Expected the verified statement as non-empty text, got {statement!r}")
        if not isinstance(how, str) or not how.strip():
            raise TypeError(f"Expected how the statement was checked as non-empty text, got {how!r}")
        if "\n\n" in statement or "\n\n" in how:
            raise ValueError("Expected a statement and a method without blank lines (one list item each)")
        self._pending.append((statement.strip(), how.strip()))
        self.total += 1

    @property
    def pending(self) -> int:
        """How many records wait for the next box."""
        return len(self._pending)

    def box(self, title: str = "Verified by code") -> VerifiedBox:
        """The box of every record since the last box; raises if there is none."""
        if not self._pending:
            raise ValueError("Expected at least one verified statement before box(), got none: "
                             "a 'Verified by code' box must not be empty")
        out = VerifiedBox(tuple(self._pending), title)
        self._pending.clear()
        return out
