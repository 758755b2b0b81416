// The exercise pages' checker as one classic script (esbuild bundles this file, math.js included, into
// _static/exercise-checks/checker.js at build time), so that it runs from file:// too. It mounts the answer
// boxes once every deferred script (the banks) has run, and exposes its functions for the browser tests.
import { decide } from "./decide.js";
import { parseAnswer } from "./parse.js";
import { checkText, fnv1a32, mountAll, normaliseId, typesetDone, variantIndex } from "./page.js";

/** @type {any} */ (window).courseExercises = { checkText, decide, parseAnswer, fnv1a32, normaliseId, typesetDone, variantIndex };

// A deferred script runs before the deferred bank scripts after it: mount on DOMContentLoaded (after every
// deferred script), or at once if the document is already complete.
let mounted = false;
const mountOnce = () => { if (!mounted) { mounted = true; mountAll(); } };
if (document.readyState === "complete") mountOnce();
else {
  document.addEventListener("DOMContentLoaded", mountOnce);
  window.addEventListener("load", mountOnce);
}
