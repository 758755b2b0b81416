// MathJax's menu and explorer, loaded when a reader asks for them.
//
// The book's formulas are typeset at build time (_ext/math_prerender.py): a
// page loads no MathJax. When a reader focuses a formula (Tab, a click),
// right-clicks it or double-clicks it, this loads the vendored MathJax with its
// menu (show or copy the TeX, zoom, speech settings) and its explorer (arrow
// keys walk through the formula and it is spoken), typesets that formula again
// from its TeX (data-tex; as CommonHTML, whose fonts load then, where the page's
// own formulas are SVG), and passes the reader's action on to it. Other
// formulas follow when they are used. Everything comes from _static/mathjax.
(function () {
  "use strict";
  const script = document.currentScript;
  const STATIC = script ? new URL(".", script.src).href : "";
  const TRIGGERS = ["focusin", "contextmenu", "dblclick"];
  let loading = null;

  function config() {
    const el = document.getElementById("math-menu-config");
    return el ? JSON.parse(el.textContent) : { macros: {} };
  }

  /** Load MathJax with the menu and explorer, once; resolves when it is ready. */
  function load() {
    if (loading) return loading;
    const { macros } = config();
    window.MathJax = {
      loader: {
        paths: { mathjax: STATIC + "mathjax/es5" },
        load: ["input/tex-base", "[tex]/ams", "[tex]/newcommand", "[tex]/configmacros", "[tex]/noundefined",
          "[tex]/require", "[tex]/autoload", "output/chtml", "ui/menu", "a11y/assistive-mml", "a11y/explorer"],
      },
      tex: { packages: { "[+]": ["ams", "newcommand", "configmacros", "noundefined", "require", "autoload"] }, macros },
      options: { menuOptions: { settings: { zoom: "DoubleClick", explorer: true, assistiveMml: true } } },
      startup: { typeset: false },
    };
    loading = new Promise((resolve, reject) => {
      const s = document.createElement("script");
      s.src = STATIC + "mathjax/es5/startup.js";
      s.onload = () => window.MathJax.startup.promise.then(resolve, reject);
      s.onerror = () => reject(new Error("MathJax could not be loaded"));
      document.head.appendChild(s);
    });
    return loading;
  }

  const pending = new WeakMap();  // formula box -> promise of its container typeset again

  /** Typeset one formula (a span.math or div.math with data-tex) again, with the menu; its new container. */
  function activate(box) {
    if (!pending.has(box)) {
      box.dataset.mathLive = "loading";
      pending.set(box, load().then(() => {
        const display = box.tagName === "DIV";
        const eqno = box.querySelector(":scope > .eqno");
        box.textContent = display ? "\\[" + box.dataset.tex + "\\]" : "\\(" + box.dataset.tex + "\\)";
        if (eqno) box.prepend(eqno);
        return window.MathJax.typesetPromise([box]);
      }).then(() => {
        box.dataset.mathLive = "1";
        return box.querySelector("mjx-container");
      }));
    }
    return pending.get(box);
  }

  function onTrigger(ev) {
    const old = ev.target.closest && ev.target.closest("mjx-container");
    const box = old && old.parentElement && old.parentElement.closest("[data-tex]");
    if (!box || box.dataset.mathLive === "1" || !ev.isTrusted) return;  // MathJax's own from here on
    if (ev.type !== "focusin") ev.preventDefault();
    const { type, clientX, clientY } = ev;
    activate(box).then((fresh) => {
      if (!fresh) return;
      if (type === "focusin") {
        if (document.activeElement === document.body || document.activeElement === old) fresh.focus();
      } else {
        fresh.dispatchEvent(new MouseEvent(type, { bubbles: true, cancelable: true, clientX, clientY }));
      }
    }, (err) => console.error(err));
  }

  // In the tab order, as MathJax's menu puts every formula, except inside a link or a button (a focusable
  // element inside another is no good to a screen reader).
  function tabStops() {
    document.querySelectorAll("[data-tex] > mjx-container").forEach((c) => {
      if (!c.hasAttribute("tabindex") && !c.closest("a, button, summary, label")) c.setAttribute("tabindex", "0");
    });
  }

  TRIGGERS.forEach((t) => document.addEventListener(t, onTrigger, true));
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", tabStops);
  else tabStops();
  window.courseMath = { load, activate };  // for the browser tests
})();
