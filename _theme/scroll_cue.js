// A formula or printout wider than the page scrolls inside its own box; this
// marks such boxes so that course.css can show which side hides more, and
// makes them reachable from the keyboard (arrow keys scroll a focused box).
(function () {
  "use strict";
  const SELECTOR = "div.math, .cell_output div.math, .cell_output pre";

  function update(el) {
    if (getComputedStyle(el).display === "inline") return;  // inline math never scrolls
    const wide = el.scrollWidth > el.clientWidth + 4;  // a few px of sub-pixel spill is not content
    el.classList.toggle("jac-scroll", wide);
    el.classList.toggle("jac-more-left", wide && el.scrollLeft > 1);
    el.classList.toggle("jac-more-right", wide && el.scrollLeft + el.clientWidth < el.scrollWidth - 1);
    if (wide && !el.hasAttribute("tabindex")) {
      el.setAttribute("tabindex", "0");
      el.setAttribute("role", "region");
      el.setAttribute("aria-label", "Wide content: scroll sideways to see all of it");
    }
  }

  function all() {
    document.querySelectorAll(SELECTOR).forEach(update);
  }

  function start() {
    document.querySelectorAll(SELECTOR).forEach((el) =>
      el.addEventListener("scroll", () => update(el), { passive: true }));
    all();
    window.addEventListener("resize", all);
    const mj = window.MathJax;
    if (mj && mj.startup && mj.startup.promise) mj.startup.promise.then(all);
    else window.addEventListener("load", all);
    setTimeout(all, 1500);  // late layout (fonts, images)
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
