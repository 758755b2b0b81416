// node --test: the parts of ui.js that need no page: the sliders' range read from the model (the one
// place it is set is the library's LIMIT) and the data-* contract every view writes (publish).

import { test } from "node:test";
import assert from "node:assert/strict";
import { publish, sliderLimit } from "../../lib/jacobians/widgets/live/ui.js";

/** A model stand-in holding `state`. @param {Record<string, unknown>} state */
const model = (state) => ({ get: (k) => state[k], set() {}, on() {}, off() {}, save_changes() {} });

test("sliderLimit gives the model's limit and refuses a model without a usable one", () => {
  assert.equal(sliderLimit(model({ limit: 3.14 })), 3.14);
  assert.equal(sliderLimit(model({ limit: "2.5" })), 2.5); // a number written as text by a kernel is still one
  for (const bad of [undefined, null, 0, -1, Number.NaN, Number.POSITIVE_INFINITY, "pi", [1, 2]]) {
    assert.throws(() => sliderLimit(model({ limit: bad })), /Expected the model's limit \(the sliders' range, rad\)/,
      `limit ${String(bad)}`);
  }
});

test("publish writes a word bare and everything else as JSON, and only what changed", () => {
  const writes = [];
  const dataset = new Proxy({}, {
    set(target, k, v) {
      writes.push(k);
      target[k] = v;
      return true;
    },
  });
  const el = /** @type {any} */ ({ dataset });
  publish(el, { view: "planar_explorer", theta: [0.5, -0.02, 1e-17], level: "ok", step: 40, playing: 0, moved: [] });
  assert.deepEqual({ ...dataset }, { view: "planar_explorer", theta: "[0.5,-0.02,1e-17]", level: "ok", step: "40",
    playing: "0", moved: "[]" });
  // JSON keeps a double exactly: what a reader parses is the number the view drew
  assert.equal(JSON.parse(dataset.theta)[2], 1e-17);
  writes.length = 0;
  publish(el, { view: "planar_explorer", theta: [0.5, -0.02, 1e-17], level: "warning" });
  assert.deepEqual(writes, ["level"]);
});
