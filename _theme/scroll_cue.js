// A formula or printout wider than the page scrolls inside its own box; this
// marks such boxes so that course.css can show which side hides more, and
// makes them reachable from the keyboard (arrow keys scroll a focused box).
// On a phone, a wide figure (legend beside the drawing, panels side by side)
// squeezed to the page's width has labels too small to read: it is shown at up
// to twice the page's width, in a box of its own that scrolls the same way.
(function () {
  "use strict";
  // (a display formula inside a box, e.g. a warning or a proposition, scrolls in its own mjx-container)
  const SELECTOR = "div.math, .cell_output div.math, .cell_output pre, .jac-fig-scroll, mjx-container[display=\"true\"]";
  const PHONE = window.matchMedia("(max-width: 600px)");
  const WIDE = 1.5;  // width : height from which a figure is "wide"

  function widen(img) {
    if (!img.naturalWidth || !img.naturalHeight) return;
    let box = img.parentElement.classList.contains("jac-fig-scroll") ? img.parentElement : null;
    if (!box) {
      if (!PHONE.matches || img.naturalWidth < WIDE * img.naturalHeight) return;
      box = document.createElement("div");
      box.className = "jac-fig-scroll";
      img.parentElement.insertBefore(box, img);
      box.appendChild(img);
      box.addEventListener("scroll", () => update(box), { passive: true });
    }
    const page = box.clientWidth;
    img.style.width = PHONE.matches ? Math.min(img.naturalWidth, 2 * page) + "px" : "";
  }

  function figures() {
    document.querySelectorAll("figure img").forEach((img) => {
      if (img.complete) widen(img);
      else img.addEventListener("load", () => { widen(img); all(); }, { once: true });
    });
  }

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
    figures();
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
