// The live views of the decks as one classic script (esbuild bundles this file into
// slides/_static/live/jac-live.js: tools/build_slides.py). A deck opened from disk
// (file://) cannot load ES modules (the browser blocks them as cross-origin), so the
// decks do not import the views' modules as the book's pages do: this bundle, built
// from the same modules, mounts every live view of the page once the page is parsed.
// A view that cannot start keeps its static text and says why (see `fail`).
import { mount } from "../../lib/jacobians/widgets/live/host.js";
// every view's module and deck style, as registered (jacobians.widgets.live.VIEWS): tools/build_slides.py
// writes this module and points esbuild at it
import { VIEWS } from "jac-live-views";

/** Leave the host's static content (written by the deck build) and add the reason the view did not start. */
function fail(el, why) {
  el.dataset.failed = "1";
  const note = document.createElement("p");
  note.className = "jl-failed";
  note.textContent = `This live view could not start: ${why}`;
  el.appendChild(note);
  console.warn(`live view ${el.id}: ${why}`);
}

function start(el) {
  if (el.dataset.ready || el.dataset.failed) return;
  const view = VIEWS[el.dataset.view];
  if (!view) {
    fail(el, `no view named "${el.dataset.view}" in this bundle`);
    return;
  }
  const fallback = [...el.childNodes].map((n) => n.cloneNode(true));
  try {
    mount(el, view);
  } catch (err) {
    el.replaceChildren(...fallback);
    fail(el, err && err.message ? err.message : String(err));
  }
}

export function startAll(root = document) {
  root.querySelectorAll(".jac-live[data-view]").forEach(start);
}

window.JacLive = { startAll, views: Object.keys(VIEWS) };
if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", () => startAll());
else startAll();
