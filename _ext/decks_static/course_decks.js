/* The lecture decks (_ext/decks.py): math laid out before the slides are measured,
   animations driven by the keyboard or a clicker, and the keys kept for the presenter. */
(function () {
  "use strict";
  function buttons(slide, what) {
    return slide ? slide.querySelectorAll('.animation button[onclick*="' + what + '"]') : [];
  }
  function stories(slide, pressed) {
    // the story live views (lib/jacobians/widgets/live/story/view.js): their Play button, when (not) playing
    return slide ? slide.querySelectorAll('.jac-live[data-story] button.jl-play[aria-pressed="' + pressed + '"]') : [];
  }
  function play(slide) {
    // an animation starts when its slide is shown; the focus stays off it, so the arrow keys still change slides
    buttons(slide, "play_animation()").forEach(function (b) { b.click(); b.blur(); });
    stories(slide, "false").forEach(function (b) { b.click(); b.blur(); });
  }
  function pause(slide) {
    buttons(slide, "pause_animation()").forEach(function (b) { b.click(); b.blur(); });
    stories(slide, "true").forEach(function (b) { b.click(); b.blur(); });
  }

  /* Keys belong to the presenter. The rule:
     - PageUp, PageDown, Space, N, P, Esc, B, "." and the number keys (what a clicker or a
       presenter types) always reach reveal.js, even with a slider or a button of a slide
       focused: the control loses the focus and the key does what it does in the deck.
     - The arrow keys (and Home/End) move a slide's control only while it is held: being
       dragged, or focused, clicked or changed less than HOLD_MS ago (each arrow press
       counts as a change, so holding or tapping an arrow keeps it). Otherwise the control
       loses the focus and the arrow goes to reveal.js.
     - HOLD_MS after the last touch of a control, it loses the focus by itself. */
  var HOLD_MS = 1000;
  var ALWAYS = [33, 34, 32, 78, 80, 27, 66, 190, 58, 59, 86];
  var HELD = [37, 38, 39, 40, 36, 35];
  var dragging = false;
  var heldUntil = 0;
  var timer = null;
  function isDigit(k) { return (k >= 48 && k <= 57) || (k >= 96 && k <= 105); }
  function slides() { return document.querySelector(".reveal .slides"); }
  function control() {
    var a = document.activeElement, s = slides();
    return a && a !== document.body && s && s.contains(a) ? a : null;
  }
  function held() { return dragging || Date.now() < heldUntil; }
  function release() {
    clearTimeout(timer);
    if (held()) { timer = setTimeout(release, Math.max(heldUntil - Date.now(), 50)); return; }
    var c = control();
    if (c && c.blur) { c.blur(); }
  }
  function hold() {
    heldUntil = Date.now() + HOLD_MS;
    clearTimeout(timer);
    timer = setTimeout(release, HOLD_MS + 10);
  }
  function toDeck(ev) {
    // the same key again, for reveal.js's own handler on the document (it reads keyCode)
    var copy = new KeyboardEvent("keydown", { key: ev.key, code: ev.code, shiftKey: ev.shiftKey,
      altKey: ev.altKey, ctrlKey: ev.ctrlKey, metaKey: ev.metaKey, bubbles: true, cancelable: true });
    Object.defineProperty(copy, "keyCode", { value: ev.keyCode });
    Object.defineProperty(copy, "which", { value: ev.keyCode });
    document.dispatchEvent(copy);
  }
  function onKey(ev) {
    if (!ev.isTrusted) { return; }
    var c = control();
    if (!c) { return; }
    var k = ev.keyCode;
    if (HELD.indexOf(k) >= 0 && held()) { hold(); return; }       // the held control's
    if (HELD.indexOf(k) < 0 && ALWAYS.indexOf(k) < 0 && !isDigit(k)) { return; }  // Tab, Enter, letters: the control's
    ev.stopImmediatePropagation();
    ev.preventDefault();
    heldUntil = 0;
    dragging = false;
    c.blur();
    toDeck(ev);
  }
  function inSlide(ev) { var s = slides(); return s && ev.target && ev.target.nodeType === 1 && s.contains(ev.target); }
  function keys() {
    window.addEventListener("keydown", onKey, true);
    document.addEventListener("pointerdown", function (ev) { if (inSlide(ev)) { dragging = true; hold(); } }, true);
    document.addEventListener("pointerup", function () { if (dragging) { dragging = false; hold(); } }, true);
    document.addEventListener("pointercancel", function () { if (dragging) { dragging = false; hold(); } }, true);
    ["focusin", "input", "change"].forEach(function (name) {
      document.addEventListener(name, function (ev) { if (inSlide(ev)) { hold(); } }, true);
    });
    // a held control that is not a text field (an SVG view, a button) keeps its arrows from reveal.js too
    Reveal.configure({ keyboardCondition: function (ev) {
      return !(control() && HELD.indexOf(ev.keyCode) >= 0 && held());
    } });
  }

  /* The pacing timer (T): time since the first step past the title slide, against the plan, the sum of the
     speaker notes' minutes ("About N min.") of the slides before this one. Shown only when asked for. */
  var started = null;
  var box = null;
  function planned(upTo) {
    var sum = 0;
    Reveal.getSlides().forEach(function (s, i) {
      var m = s.querySelector("aside.notes p.minutes");
      var n = m ? parseFloat((m.textContent.match(/[\d.]+/) || ["0"])[0]) : 0;
      if (i < upTo) { sum += n; }
    });
    return sum;
  }
  function clock(sec) {
    var s = Math.max(0, Math.round(Math.abs(sec)));
    return Math.floor(s / 60) + ":" + ("0" + (s % 60)).slice(-2);
  }
  function showPace() {
    if (!box || box.hidden) { return; }
    var now = started === null ? 0 : (Date.now() - started) / 1000;
    var i = Reveal.getIndices().h;
    var plan = planned(i) * 60;
    var total = planned(Reveal.getTotalSlides());
    var late = now - plan;
    box.textContent = clock(now) + " of " + Math.round(total) + " min \u00b7 plan here " + clock(plan)
      + (Math.abs(late) < 30 ? " \u00b7 on time" : late > 0 ? " \u00b7 " + clock(late) + " behind" : " \u00b7 " + clock(late) + " ahead");
    box.className = "deck-pacing" + (late > 120 ? " behind" : "");
  }
  function pacing() {
    box = document.createElement("div");
    box.className = "deck-pacing";
    box.hidden = true;
    box.setAttribute("role", "timer");
    document.querySelector(".reveal").appendChild(box);
    Reveal.on("slidechanged", function (e) { if (started === null && e.indexh > 0) { started = Date.now(); } showPace(); });
    setInterval(showPace, 1000);
    Reveal.addKeyBinding({ keyCode: 84, key: "T", description: "Pacing timer (against the notes' minutes)" }, function () {
      box.hidden = !box.hidden;
      showPace();
    });
  }

  // The slide menu (reveal.js-menu) scrolls its list of slides: make each panel reachable from the keyboard.
  function focusableMenu() {
    document.querySelectorAll(".slide-menu-panel").forEach(function (panel) {
      if (!panel.hasAttribute("tabindex")) { panel.setAttribute("tabindex", "0"); }
      if (!panel.hasAttribute("aria-label")) { panel.setAttribute("aria-label", "Slides of this deck"); }
    });
  }

  function ready() {
    if (!window.Reveal) { return; }
    keys();
    pacing();
    var deck = document.querySelector(".reveal");
    if (deck) { deck.addEventListener("menu-ready", focusableMenu); }
    focusableMenu();
    Reveal.on("ready", function (e) { play(e.currentSlide); });
    Reveal.on("slidechanged", function (e) { pause(e.previousSlide); play(e.currentSlide); });
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
      MathJax.startup.promise.then(function () {
        Reveal.layout();
        document.documentElement.setAttribute("data-math-done", "1");
      });
    } else {
      document.documentElement.setAttribute("data-math-done", "1");
    }
  }
  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", ready);
  } else {
    ready();
  }
})();
