/* The lecture decks (_ext/decks.py): math laid out before the slides are measured,
   animations driven by the keyboard or a clicker. */
(function () {
  "use strict";
  function buttons(slide, what) {
    return slide ? slide.querySelectorAll('.animation button[onclick*="' + what + '"]') : [];
  }
  function stories(slide, pressed) {
    // the story live views (lib/jacobians/widgets/static/live/story.js): their Play button, when (not) playing
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
  function ready() {
    if (!window.Reveal) { return; }
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
