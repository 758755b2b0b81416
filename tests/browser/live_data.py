"""How a test reads what a live view shows from its host element: the view's ``data-*`` attributes.

Every view writes the same keys for the same things (AUTHORING.md, "Adding a live view"; ``publish`` in
``lib/jacobians/widgets/live/ui.js``): ``data-view``, ``data-ready`` (the page's host, once the view is
drawn), ``data-theta`` (the joint angles shown, rad), and ``data-level``, ``data-step``, ``data-playing``
where the view has them; then its own keys (``data-frame``, ``data-column``, ``data-wrist``...). A value is
JSON, except a word (``data-level="warning"``), which is written bare. ``DATA_JS`` reads them all back at
once, parsed, with the keys as ``el.dataset`` names them (``data-changed-s`` is ``changedS``); the model
(``data-model``) is left out, being what the view was given, not what it shows.
"""

from __future__ import annotations

from typing import Any

#: (el) => {view, theta, level, ...}: the view's data-* attributes, parsed (a JS function for Playwright)
DATA_JS = """((el) => Object.fromEntries(Object.entries(el.dataset).filter(([k]) => k !== "model").map(([k, v]) => {
  try { return [k, JSON.parse(v)]; } catch { return [k, v]; }
})))"""


def with_data(body: str) -> str:
    """A JS function ``(el) => ...`` whose expression ``body`` can use ``data``, the view's parsed data-*."""
    return f"(el) => {{ const data = {DATA_JS}(el); return ({body}); }}"


def live_data(el: Any) -> dict[str, Any]:
    """The view's data-* attributes, parsed, from a Playwright element handle."""
    return el.evaluate(DATA_JS)  # type: ignore[no-any-return]


#: (el) => what a view shows, as a view's spec's ``check`` reads it (``jacobians.widgets.live._base.Shown``): its
#: data-* keys (``view``, ``theta``, ``step``, ...), ``model`` (data-model), ``state`` (the numbers it drew,
#: ``el.jacLive``, its DOM references left out), ``tables`` (each table's text rows by its last class) and ``text``
SHOWN_JS = with_data("""(() => {
  const tables = {};
  for (const t of el.querySelectorAll("table")) {
    tables[t.classList[t.classList.length - 1] || "table"] = [...t.querySelectorAll("tbody tr")]
      .map((tr) => [...tr.querySelectorAll("td")].map((c) => c.textContent));
  }
  const state = {};
  for (const [k, v] of Object.entries(el.jacLive || {})) {
    try { state[k] = JSON.parse(JSON.stringify(v) ?? "null"); } catch { /* a DOM reference: not a number shown */ }
  }
  return { ...data, model: JSON.parse(el.dataset.model || "null"), state, tables, text: el.innerText,
    markup: el.innerHTML };
})()""")


def shown(el: Any) -> dict[str, Any]:
    """What the view shows (``SHOWN_JS``), from a Playwright element handle: what a spec's ``check`` takes."""
    return el.evaluate(SHOWN_JS)  # type: ignore[no-any-return]
