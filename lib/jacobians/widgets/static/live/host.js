// Mount a live view on a static page: the model stand-in of an
// anywidget model (get/set/on/off/save_changes) built from the host element's
// data-model JSON, written at build time by _ext/live_views.py. With no kernel,
// save_changes does nothing; set fires "change:<key>" handlers as Backbone does.

export function makeModel(state) {
  const handlers = new Map();
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

/** Render `view` (a module with render({model, el})) into `el` from its data-model attribute. */
export function mount(el, view) {
  const render = view.render || (view.default && view.default.render);
  const model = makeModel(JSON.parse(el.dataset.model));
  el.textContent = "";
  const cleanup = render({ model, el });
  el.dataset.ready = "1";
  return { model, cleanup };
}
