// The exercise pages' checker as one classic script (esbuild bundles this file, math.js included, into
// _static/exercise-checks/checker.js at build time), so that it runs from file:// too. It mounts the answer
// boxes once every deferred script (the banks) has run, and exposes its functions for the browser tests.
import { decide } from "./decide.js";
import { parseAnswer } from "./parse.js";
import { checkText, fnv1a32, mountAll, normaliseId, variantIndex } from "./page.js";

/** @type {any} */ (window).courseExercises = { checkText, decide, parseAnswer, fnv1a32, normaliseId, variantIndex };

if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", mountAll);
else mountAll();
