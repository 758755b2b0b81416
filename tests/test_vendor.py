"""tools/vendor.py keeps a built site working: no target that vendors leaves a page without its MathJax."""

from pathlib import Path

import pytest
from tools import vendor


@pytest.fixture
def built(tmp_path: Path) -> tuple[Path, Path]:
    if not (vendor.NODE_MODULES / "mathjax" / "es5" / "startup.js").is_file():
        pytest.fail("node_modules/mathjax is missing: run `npm ci` (make setup does it)", pytrace=False)
    dest, static = tmp_path / "_vendor", tmp_path / "site" / "_static"
    (dest / "retired").mkdir(parents=True)            # a tree vendor.py held before and holds no more
    (static / "retired").mkdir(parents=True)
    (static / "retired" / "old.js").write_text("")
    (static / "mathjax" / "es5").mkdir(parents=True)   # an older copy of a current tree, with a stale file
    (static / "mathjax" / "es5" / "stale.js").write_text("")
    (static / "theme.css").write_text("")              # Sphinx's and the theme's files are left alone
    return dest, static


def test_vendoring_into_a_built_site_leaves_it_working(built):
    dest, static = built
    vendor.book(dest, static)
    for package in vendor.BOOK:
        assert (dest / package.folder / package.entry).is_file()
        assert (static / package.folder / package.entry).is_file(), "the built site lost what its pages load"
        copied = sorted(p.relative_to(dest).as_posix() for p in (dest / package.folder).rglob("*") if p.is_file())
        in_site = sorted(p.relative_to(static).as_posix() for p in (static / package.folder).rglob("*") if p.is_file())
        assert copied == in_site                      # the same files: the stale one is gone, nothing missing
    assert not (static / "retired").exists() and (static / "theme.css").is_file()


def test_vendoring_with_no_built_site_writes_only_vendor(tmp_path):
    vendor.book(tmp_path / "_vendor", tmp_path / "no-site" / "_static")
    assert (tmp_path / "_vendor" / "mathjax" / "es5" / "startup.js").is_file()
    assert not (tmp_path / "no-site").exists()
