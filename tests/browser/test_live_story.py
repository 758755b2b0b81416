"""The story live view (``lib/jacobians/widgets/live/story/view.js``, chapters 1, 3 and 7) in Chromium, no kernel.

For every story: at every frame the slider reaches, and at 200 random times through the module's
own ``storyState``, the numbers the view draws are the library's within 1e-12 (see story_views.py);
the drawn arm and arrows are those numbers; the arrow keys step the slider one frame; Play runs
the replay and Pause stops it (from the keyboard too); at 390 px nothing overflows and the text is
at least 14 px; no console error, no request to another host. Needs no built book.
"""

from __future__ import annotations

import json
from pathlib import Path
from urllib.parse import urlsplit

import bookcheck
import numpy as np
import pytest
import story_views as sv
from live_data import DATA_JS, live_data, with_data
from test_live_views import FIT_JS

from course.stories import STORIES, story_model, story_times

ROOT = Path(__file__).resolve().parents[2]
N_TIMES = 200

# Every frame, through the slider as a reader moves it (an input event), read at once.
ALL_FRAMES_JS = """(el) => {
  const slider = el.querySelector("input.js-time");
  const out = [];
  for (let k = 0; k <= +slider.max; k++) {
    slider.value = String(k);
    slider.dispatchEvent(new Event("input", {bubbles: true}));
    out.push(JSON.parse(JSON.stringify({...el.jacLive, arrows: undefined})));
  }
  return out;
}"""

STATE_AT_JS = """async ([url, model, times]) => {
  const St = await import(url);
  const K = await import(new URL("../kinematics.js", url).href);
  const chain = K.makeChain(model.S, model.M, model.Q);
  return times.map((t) => St.storyState(chain, model, t));
}"""


@pytest.fixture(scope="module")
def harness(browser_context):
    with bookcheck.BookServer(ROOT) as server:
        page = browser_context.new_page()
        seen: dict[str, list[str]] = {"console": [], "requests": []}
        page.on("console", lambda m: seen["console"].append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: seen["console"].append(str(e)))
        page.on("request", lambda r: seen["requests"].append(r.url))

        def open_story(story: str, width: int = 1280):
            page.set_viewport_size({"width": width, "height": 900})
            page.goto(server.base + "tests/browser/live_view_harness.html", wait_until="load")
            page.wait_for_selector("body[data-ready='1']", state="attached", timeout=10_000)
            page.evaluate("([v, m]) => window.mountView(v, m)", ["story", story_model(story)])
            return page.wait_for_selector("#host[data-ready='1']", state="attached", timeout=10_000)

        yield page, open_story, seen, server.base
        page.close()


@pytest.mark.parametrize("story", STORIES)
def test_every_frame_is_the_librarys(harness, story):
    page, open_story, seen, _ = harness
    model = story_model(story)
    el = open_story(story)
    sv.check_view(el, model)  # frame 0 as mounted, with the drawing and the table
    states = el.evaluate(ALL_FRAMES_JS)
    assert [s["frame"] for s in states] == list(range(model["frames"]))
    assert np.array_equal([s["t"] for s in states], story_times(model))
    chain = sv.chain_of(model)
    worst = max(sv.largest_difference(model, chain, s) for s in states)
    assert worst <= sv.TOL, worst
    sv.check_view(el, model)  # the last frame, drawn
    assert seen["console"] == []


@pytest.mark.parametrize("story", STORIES)
def test_the_modules_state_at_random_times_is_the_librarys(harness, story):
    page, open_story, seen, base = harness
    model = story_model(story)
    open_story(story)
    rng = np.random.default_rng(13)
    times = np.r_[rng.uniform(-model["t_end"], 2 * model["t_end"], N_TIMES), 0.0, model["t_end"]]
    states = page.evaluate(STATE_AT_JS, [base + "lib/jacobians/widgets/live/story/view.js", model, times.tolist()])
    chain = sv.chain_of(model)
    worst = max(sv.largest_difference(model, chain, s) for s in states)
    assert worst <= sv.TOL, worst


@pytest.mark.parametrize("story", STORIES)
def test_keyboard_steps_the_replay_and_play_runs_it(harness, story):
    page, open_story, seen, _ = harness
    model = story_model(story)
    el = open_story(story)
    el.query_selector("input.js-time").focus()
    for k in (1, 2, 3):
        page.keyboard.press("ArrowRight")
        assert sv.check_view(el, model)["frame"] == k
    page.keyboard.press("End")
    assert sv.check_view(el, model)["frame"] == model["frames"] - 1
    page.keyboard.press("Home")
    first = sv.check_view(el, model)
    assert first["frame"] == 0
    # Play from the keyboard (Tab to the button, Space), the frames advance; Space again pauses
    page.keyboard.press("Tab")
    assert page.evaluate("() => document.activeElement.className") == "jl-play"
    page.keyboard.press("Space")
    assert live_data(el)["playing"] == 1
    assert el.query_selector("button.jl-play").get_attribute("aria-pressed") == "true"
    page.wait_for_timeout(600)
    moved = sv.check_view(el, model)
    assert moved["frame"] > 0 and moved["state"]["t"] > first["state"]["t"]
    page.keyboard.press("Space")
    assert live_data(el)["playing"] == 0
    stopped = sv.check_view(el, model)["frame"]
    page.wait_for_timeout(300)
    assert sv.check_view(el, model)["frame"] == stopped
    # the replay loops: from the last frame, Play goes on at frame 0
    el.query_selector("input.js-time").focus()
    page.keyboard.press("End")
    el.query_selector("button.jl-play").click()
    page.wait_for_function(with_data("data.step < 5"), arg=el, timeout=5_000)
    el.query_selector("button.jl-play").click()
    sv.check_view(el, model)
    # moving the slider while it plays pauses the replay
    el.query_selector("button.jl-play").click()
    el.query_selector("input.js-time").focus()
    page.keyboard.press("ArrowRight")
    assert live_data(el)["playing"] == 0
    assert seen["console"] == []


@pytest.mark.parametrize("story", STORIES)
def test_fits_a_phone_and_the_text_is_readable(harness, story):
    page, open_story, seen, base = harness
    el = open_story(story, width=390)
    fit = el.evaluate(FIT_JS)
    assert fit["overflow"] == [] and fit["scroll"] <= 0 and fit["page"] <= 0, fit
    assert fit["small"] == [], fit
    small_svg = el.evaluate("""(el) => [...el.querySelectorAll("svg text")].filter((t) => t.getBoundingClientRect().height
        && parseFloat(t.getAttribute("font-size")) * t.ownerSVGElement.getScreenCTM().a < 14).map((t) => t.textContent)""")
    assert small_svg == []
    assert seen["console"] == []
    host = urlsplit(base).netloc
    # data: and blob: URLs are made by the page itself (the anywidget test loads its module from a blob), no request
    assert [u for u in seen["requests"] if not u.startswith(("data:", "blob:")) and urlsplit(u).netloc != host] == []


def test_the_directive_embeds_the_model():
    import live_views

    for story in STORIES:
        html = live_views.host_html("story", live_views.model_for("story", {"story": story}), 1, f"x-{story}")
        assert 'data-view="story"' in html and "_static/live/story/view.js" in html
        assert json.loads(html.split('data-model="')[1].split('"')[0].replace("&quot;", '"'))["story"] == story
    with pytest.raises(ValueError, match="Expected story one of"):
        live_views.model_for("story", {"story": "spin"})


ESM_JS = """async ([src, state]) => {
  const data = """ + DATA_JS + """;
  const url = URL.createObjectURL(new Blob([src], {type: "text/javascript"}));
  const mod = await import(url);
  const handlers = new Map();
  const sets = [];
  const model = {get: (k) => state[k], off() {}, save_changes() {},
    set: (k, v) => { state[k] = v; sets.push([k, v]); (handlers.get("change:" + k) || []).forEach((f) => f()); },
    on: (n, f) => handlers.set(n, [...(handlers.get(n) || []), f])};
  const el = document.createElement("div");
  document.body.append(el);
  mod.default.render({model, el});
  const s = el.querySelector("input.js-time");
  s.value = "10";
  s.dispatchEvent(new Event("input"));
  const out = {sets, frame: data(el).step, theta: el.jacLive.theta};
  el.remove();
  return out;
}"""


@pytest.mark.parametrize("story", STORIES)
def test_the_jupyter_widgets_module_renders_and_its_frame_is_pythons(harness, story):
    """StoryView's _esm (relative imports inlined as data: URLs, as anywidget loads it) with a model
    stand-in: the slider writes ``frame``, and StoryView.theta at that frame is the θ the view drew."""
    from jacobians.widgets.live import StoryView

    page, open_story, seen, _ = harness
    open_story(story)
    w = StoryView(story)
    got = page.evaluate(ESM_JS, [w._esm, story_model(story)])
    assert got["sets"] == [["frame", 10]] and got["frame"] == 10
    w.frame = got["sets"][-1][1]
    assert np.allclose(w.theta, got["theta"], atol=1e-12, rtol=0)
    assert seen["console"] == []
