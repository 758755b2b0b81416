"""tools/vendor.py: only the files pages load, one copy per site, stale trees removed."""

from __future__ import annotations

from pathlib import Path

import pytest
from tools import vendor

pytestmark = pytest.mark.skipif(not (vendor.NODE_MODULES / "mathjax").is_dir(),
                                reason="node_modules is installed by `npm ci` (make setup)")


def _tree(folder: Path) -> list[str]:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())


def test_book_vendors_mathjax_only_and_clears_stale_trees(tmp_path):
    dest, static = tmp_path / "_vendor", tmp_path / "html" / "_static"
    (dest / "html-manager").mkdir(parents=True)            # left by an older vendor.py
    for old in ("html-manager/embed-amd.js", "mathjax/es5/old.js", "require.js", "course.css"):
        (static / old).parent.mkdir(parents=True, exist_ok=True)
        (static / old).write_text("x")
    vendor.book(dest, site_static=static)
    files = _tree(dest)
    assert [p.name for p in dest.iterdir()] == ["mathjax"]
    assert "mathjax/es5/tex-mml-chtml.js" in files
    assert all(f.startswith(("mathjax/es5/tex-mml-chtml.js", "mathjax/es5/output/chtml/fonts/woff-v2/",
                             "mathjax/es5/input/tex/extensions/")) for f in files), files
    assert sum((dest / f).stat().st_size for f in files) < 2_500_000
    assert _tree(static) == ["course.css", "require.js"]     # the old trees went; Sphinx copies the new one


def test_missing_package_says_what_to_run(tmp_path):
    missing = vendor.Package("no-such-package", "x", ("a.js",), "a.js")
    with pytest.raises(FileNotFoundError, match="npm ci"):
        missing.copy(tmp_path)
