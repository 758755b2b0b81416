"""tools/vendor.py: only the files pages and decks load, one copy per site, stale trees removed, and a built
site left working (no target that vendors leaves a page without its MathJax); reveal.js from npm."""

from __future__ import annotations

from pathlib import Path

import pytest
from tools import vendor


@pytest.fixture(autouse=True)
def node_modules() -> None:
    """Every test here copies from node_modules: its absence is a failure that says what to run."""
    if not (vendor.NODE_MODULES / "mathjax" / "es5" / "startup.js").is_file():
        pytest.fail("node_modules/mathjax is missing: run `npm ci` (make setup does it)", pytrace=False)


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
    assert "mathjax/es5/startup.js" in files and "mathjax/es5/tex-mml-chtml.js" not in files
    components = tuple(f"mathjax/es5/{c}.js" for c in vendor.MATHJAX_COMPONENTS)
    assert all(f in components or f.startswith(("mathjax/es5/output/chtml/fonts/woff-v2/",
                                                "mathjax/es5/input/tex/extensions/", "mathjax/es5/sre/mathmaps/"))
               for f in files), files
    assert {f for f in files if f.startswith("mathjax/es5/sre/")} == {
        "mathjax/es5/sre/mathmaps/base.json", "mathjax/es5/sre/mathmaps/en.json"}  # English speech rules only
    # what a deck with math downloads at first (a book page downloads none of it: its math is typeset at build
    # time; the menu, explorer and speech rules load when a reader asks for them)
    first = [f"mathjax/es5/{c}.js" for c in ("startup", "core", "input/tex-base", "output/chtml",
                                             "output/chtml/fonts/tex", "a11y/assistive-mml")]
    assert set(first) <= set(components) and sum((dest / f).stat().st_size for f in first) < 800_000
    assert sum((dest / f).stat().st_size for f in files) < 3_500_000
    # the old trees went, and the fresh MathJax is in the built site at once (no Sphinx build needed)
    site = _tree(static)
    assert "mathjax/es5/old.js" not in site and not any(f.startswith("html-manager/") for f in site)
    assert [f for f in site if not f.startswith("mathjax/")] == ["course.css", "require.js"]
    assert [f for f in site if f.startswith("mathjax/")] == files


def test_missing_package_says_what_to_run(tmp_path):
    missing = vendor.Package("no-such-package", "x", ("a.js",), "a.js")
    with pytest.raises(FileNotFoundError, match="npm ci"):
        missing.copy(tmp_path)


def test_the_books_mathjax_loader_names_only_vendored_components():
    """Every component _config.yml asks MathJax to load is a vendored file (a missing one
    would be a failed request and unrendered math), and every vendored one is asked for."""
    import yaml

    cfg = yaml.safe_load((vendor.ROOT / "_config.yml").read_text(encoding="utf-8"))["sphinx"]["config"]["mathjax3_config"]
    load = cfg["loader"]["load"]
    root = vendor.NODE_MODULES / "mathjax" / "es5"
    files = []
    for comp in load:
        if comp.startswith("[tex]/"):
            files.append(f"input/tex/extensions/{comp[6:]}.js")
        else:
            assert comp in vendor.MATHJAX_COMPONENTS, f"{comp} is loaded but not in vendor.MATHJAX_COMPONENTS"
            files.append(f"{comp}.js")
    for f in files:
        assert (root / f).is_file(), f
    # the decks' loader (_config.yml) and the book's on-demand loader (_theme/math_menu.js) together ask for
    # every vendored component; the loader fetches core and the CommonHTML font itself (dependencies of tex-base
    # and chtml), and the explorer's semantic enrichment its speech engine and MathML input
    import re
    menu_js = (vendor.ROOT / "_theme" / "math_menu.js").read_text(encoding="utf-8")
    on_demand = re.findall(r'"((?:input|output|ui|a11y)/[\w-]+)"', menu_js)
    assert "ui/menu" in on_demand and "a11y/explorer" in on_demand
    assert set(vendor.MATHJAX_COMPONENTS) == {"startup", "core", "output/chtml/fonts/tex", "a11y/semantic-enrich",
                                              "a11y/sre", "input/mml"} | {
        c for c in [*load, *on_demand] if not c.startswith("[tex]/")}
    packages = cfg["tex"]["packages"]["[+]"]
    assert sorted(packages) == sorted(c[6:] for c in load if c.startswith("[tex]/"))
    assert "configmacros" in packages, "the macros (Ad, ad) need the configmacros package"


def test_reveal_js_comes_from_npm_and_a_different_bundled_release_stops_the_build(tmp_path):
    from tools import build_slides

    reveal = tmp_path / "revealjs"
    (reveal / "dist").mkdir(parents=True)
    (reveal / "dist" / "reveal.js").write_text("/* another release */")
    with pytest.raises(ValueError, match="another reveal.js than npm's"):
        build_slides.reveal_from_npm(reveal)
    (reveal / "dist" / "reveal.js").unlink()
    build_slides.reveal_from_npm(reveal)
    for rel in build_slides.REVEAL_KEEP:
        assert (reveal / rel).read_bytes() == (vendor.NODE_MODULES / "reveal.js" / rel).read_bytes()
    with pytest.raises(FileNotFoundError, match="npm ci"):
        build_slides.reveal_from_npm(reveal, node_modules=tmp_path / "nowhere")


def test_the_pinned_reveal_js_is_the_release_sphinx_revealjs_bundles():
    """package.json pins the reveal.js that sphinx-revealjs was made for: the files a deck loads are the same bytes."""
    import sphinx_revealjs
    from tools import build_slides

    bundled = Path(sphinx_revealjs.__file__).parent / "_static" / "revealjs"
    for rel in build_slides.REVEAL_KEEP:
        assert (bundled / rel).read_bytes() == (vendor.NODE_MODULES / "reveal.js" / rel).read_bytes(), rel


@pytest.fixture
def built(tmp_path: Path) -> tuple[Path, Path]:
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
