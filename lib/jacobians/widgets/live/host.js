// @ts-check
// Mount a live view on a static page: the model stand-in of an
// anywidget model (get/set/on/off/save_changes) built from the host element's
// data-model JSON, written at build time by _ext/live_views.py. With no kernel,
// save_changes does nothing; set fires "change:<key>" handlers as Backbone does.

/**
 * The part of an anywidget model a view uses. get returns what the model holds (JSON from Python): a
 * view checks what it reads.
 * @typedef {object} Model
 * @property {(key: string) => any} get
 * @property {(key: string, value: unknown) => void} set
 * @property {(name: string, f: () => void) => void} on
 * @property {(name: string, f?: () => void) => void} off
 * @property {() => void} save_changes
 */
/** @typedef {{render(args: {model: Model, el: HTMLElement}): (() => void) | void}} ViewModule */

/**
 * @param {Record<string, unknown>} state
 * @returns {Model}
 */
export function makeModel(state) {
  /** @type {Map<string, (() => void)[]>} */
  const handlers = new Map();
  /** @param {string} name */
  const fire = (name) => (handlers.get(name) || []).slice().forEach((f) => f());
  return {
    get: (key) => state[key],
    set(key, value) {
      state[key] = value;
      fire(`change:${key}`);
      fire("change");
    },
    on(name, f) {
      for (const n of name.split(" ")) handlers.set(n, [...(handlers.get(n) || []), f]);
    },
    off(name, f) {
      for (const n of name.split(" ")) handlers.set(n, (handlers.get(n) || []).filter((g) => f && g !== f));
    },
    save_changes() {},
  };
}

/** Render `view` (a module with render({model, el})) into `el` from its data-model attribute.
 * @param {HTMLElement} el
 * @param {ViewModule | {default: ViewModule}} view
 */
export function mount(el, view) {
  const render = "render" in view ? view.render : view.default.render;
  const model = makeModel(JSON.parse(el.dataset.model || "{}"));
  el.textContent = "";
  const cleanup = render({ model, el });
  el.dataset.ready = "1";
  return { model, cleanup };
}
