"""jacobians.verified: the records of hidden checks, rendered as one box per section."""

import pytest

from jacobians.verified import Verified, VerifiedBox


def test_box_lists_records_in_order_and_resets():
    v = Verified()
    v(r"$J_{s1} = \mathcal S_1$", "sympy")
    v(r"$J_b = [\mathrm{Ad}_{T_{bs}}] J_s$", "finite differences of `fk`")
    assert v.pending == 2 and v.total == 2
    box = v.box()
    md = box._repr_markdown_()
    assert md.splitlines()[0] == ":::{admonition} Verified by code (2 checks)"
    assert ":class: dropdown verified" in md
    assert md.index(r"$J_{s1} = \mathcal S_1$") < md.index(r"$J_b = [\mathrm{Ad}_{T_{bs}}] J_s$")
    assert md.rstrip().endswith(":::")
    assert v.pending == 0 and v.total == 2
    v("$x = 1$", "arithmetic")
    assert v.box()._repr_markdown_().splitlines()[0].endswith("(1 check)")


def test_empty_box_is_an_error():
    with pytest.raises(ValueError, match="at least one verified statement"):
        Verified().box()


@pytest.mark.parametrize("statement, how", [("", "sympy"), ("$x$", ""), (None, "sympy"), ("$x$", 3)])
def test_bad_records_are_refused(statement, how):
    with pytest.raises(TypeError, match="Expected"):
        Verified()(statement, how)


def test_blank_lines_are_refused():
    with pytest.raises(ValueError, match="without blank lines"):
        Verified()("$x$\n\n$y$", "sympy")


def test_plain_repr_names_every_record():
    box = VerifiedBox((("$a$", "one"), ("$b$", "two")))
    text = repr(box)
    assert "$a$" in text and "[two]" in text
