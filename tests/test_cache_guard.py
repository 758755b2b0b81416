"""tools/cache_guard.py: a library change empties the book's execution cache, nothing else does."""

from pathlib import Path

from tools import cache_guard


def _library(tmp_path: Path) -> Path:
    lib = tmp_path / "lib" / "jacobians"
    lib.mkdir(parents=True)
    (lib / "__init__.py").write_text("X = 1\n")
    (lib / "jacobian.py").write_text("def f():\n    return 1\n")
    return lib


def _cache(tmp_path: Path) -> Path:
    cache = tmp_path / "_build" / ".jupyter_cache"
    cache.mkdir(parents=True, exist_ok=True)
    (cache / "entry").write_text("outputs of the old library")
    return cache


def test_unchanged_library_keeps_the_cache(tmp_path):
    lib = _library(tmp_path)
    cache = _cache(tmp_path)
    digest = cache_guard.library_hash(lib, ())
    cache_guard.guard(cache, digest)        # first build: stamp written (cache kept: no stamp yet means
    _cache(tmp_path)                        # a cache of unknown origin, emptied; refill it as a build would)
    assert cache_guard.guard(cache, cache_guard.library_hash(lib, ())) is False
    assert (cache / "entry").exists()


def test_library_change_empties_the_cache(tmp_path):
    lib = _library(tmp_path)
    cache = _cache(tmp_path)
    cache_guard.guard(cache, cache_guard.library_hash(lib, ()))
    _cache(tmp_path)
    (lib / "jacobian.py").write_text("def f():\n    return 2\n")   # a one-character library change
    assert cache_guard.guard(cache, cache_guard.library_hash(lib, ())) is True
    assert not cache.exists()


def test_new_library_file_changes_the_hash(tmp_path):
    lib = _library(tmp_path)
    before = cache_guard.library_hash(lib, ())
    (lib / "new_module.py").write_text("")
    assert cache_guard.library_hash(lib, ()) != before


def test_cache_without_stamp_is_emptied(tmp_path):
    """A cache left by a build from before the guard existed is of unknown origin."""
    cache = _cache(tmp_path)
    assert cache_guard.guard(cache, "abc") is True
    assert not cache.exists()
    assert (cache.parent / ".jupyter_cache.library-hash").read_text().strip() == "abc"


def test_real_library_hash_is_stable():
    assert cache_guard.library_hash() == cache_guard.library_hash()
    assert len(cache_guard.library_hash()) == 64
