"""What every test folder shares: which tests are browser tests, and the one Chromium a pytest process uses.

The rule that splits ``make test-lib`` from the browser stages (``make test-browser``, ``make test-install``,
``make test-targets``): a test is marked ``browser`` when it needs Chromium or the built site, and
``make test-lib`` runs every test that is not. A test gets the mark

* by where it lives: every test under ``tests/browser``, ``tests/install`` or ``tests/site``;
* by what it asks for: any test that uses one of :data:`BROWSER_FIXTURES` (the shared Chromium, the served
  book, the decks' browser or their copy on a "USB stick"), wherever it lives (e.g. ``tests/slides``), and
  every other test of the same module (a module that opens the built site in a browser also reads it
  directly, as ``tests/slides/test_decks.py`` does);
* or by hand: ``@pytest.mark.browser`` on a test that starts its own browser or reads ``_build/html``.
"""

from __future__ import annotations

import contextlib
import sys
from pathlib import Path

import pytest
from hypothesis import settings

# No per-example deadline: a property test checks values, and how long an example takes depends on the machine and
# its load (speed is measured by make bench, never asserted in a test).
settings.register_profile("course", deadline=None)
settings.load_profile("course")

TESTS = Path(__file__).resolve().parent
#: folders whose every test needs Chromium or the built site
BROWSER_FOLDERS = tuple(TESTS / name for name in ("browser", "install", "site"))
#: fixtures that start Chromium or need the built book or decks
BROWSER_FIXTURES = frozenset({"browser_context", "book_html", "book_url", "page_reports", "deck_browser", "usb"})


def pytest_configure(config):
    config.addinivalue_line("markers", "browser: needs Chromium or the built site (not run by make test-lib)")


def _asks_for_a_browser(item: pytest.Item) -> bool:
    path = Path(str(item.path)).resolve()
    return (any(path.is_relative_to(folder) for folder in BROWSER_FOLDERS)
            or bool(BROWSER_FIXTURES & set(getattr(item, "fixturenames", ())))
            or item.get_closest_marker("browser") is not None)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    browser_modules = {Path(str(item.path)).resolve() for item in items if _asks_for_a_browser(item)}
    for item in items:
        if Path(str(item.path)).resolve() in browser_modules and item.get_closest_marker("browser") is None:
            item.add_marker(pytest.mark.browser)


#: test modules whose tests share one expensive load per parameter, kept in a per-process cache: test_pages.py
#: (each page opened once, ``page_reports``) and test_decks.py (each deck walked once, ``walk``)
SHARED_LOAD_MODULES = ("test_pages.py", "test_decks.py")


def work_unit(nodeid: str) -> str:
    """The unit of work that one xdist worker runs whole: one page's or one deck's tests in the modules above
    (their load is shared, and the pages and decks spread over the workers), and every other module whole (its
    module-scoped browser page or server is started once).

    >>> work_unit("tests/browser/test_pages.py::test_math_is_typeset[chapters/01_twists.html]")
    'tests/browser/test_pages.py[chapters/01_twists.html]'
    >>> work_unit("tests/slides/test_decks.py::test_lectures_open_from_the_copy")
    'tests/slides/test_decks.py'
    >>> work_unit("tests/browser/test_chrome.py::test_x[a]")
    'tests/browser/test_chrome.py'
    """
    module, _, test = nodeid.partition("::")
    if Path(module).name in SHARED_LOAD_MODULES and test.endswith("]") and "[" in test:
        return f"{module}[{test[test.index('[') + 1:-1]}]"
    return module


@pytest.hookimpl(optionalhook=True)   # a run without pytest-xdist (-p no:xdist) does not know the hook
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadscope`` with the work units of ``work_unit``. (xdist's ``loadgroup`` would say the same with
    marks, but pytest-xdist 3.8 loses the marks' groups under pytest 9.2: pytest-dev/pytest-xdist#1386.)"""
    if config.getvalue("dist") != "loadscope":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class ByWorkUnit(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return work_unit(nodeid)

    return ByWorkUnit(config, log)


@pytest.fixture(autouse=True)
def _no_slide_frames_after_a_test():
    """A chapter's ``start_page`` (run by some tests in-process) asks every later animation for a second set
    of frames, drawn for the slides: a process-wide switch. Each test leaves it off, as it found it."""
    yield
    animation = sys.modules.get("jacobians.plotting.animation")   # never imported: nothing to switch off
    if animation is not None:
        animation.set_slide_frames(None)


@pytest.fixture(scope="session")
def browser_context():
    """Debian's headless Chromium (``bookcheck.launch_browser``: its settings are written there only), started
    once per pytest process (once per xdist worker) and shared by every test of that process."""
    import bookcheck  # tests/browser, on the pythonpath (pyproject.toml)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p, contextlib.ExitStack() as stack:
        try:
            context = stack.enter_context(bookcheck.opened_browser(p))
        except FileNotFoundError as exc:
            pytest.fail(str(exc), pytrace=False)
        yield context
