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

import shutil
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

    with sync_playwright() as p:
        try:
            context, profile = bookcheck.launch_browser(p)
        except FileNotFoundError as exc:
            pytest.fail(str(exc), pytrace=False)
        try:
            yield context
        finally:
            context.close()
            shutil.rmtree(profile, ignore_errors=True)
