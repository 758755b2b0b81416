"""The story live view (``lib/jacobians/widgets/live/story/view.js``) against the library: shared by test_live_story.py and
test_live_views.py (the built chapter pages 1, 3 and 7).

:func:`library_state` is what the view must draw at time t, from ``jacobians`` only;
:func:`compare` checks the view's numbers (``el.jacLive``: all of them, not rounded) within
``TOL`` and the drawn SVG against those numbers; :func:`check_view` reads a mounted view.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
from live_data import with_data

import jacobians as jac
from jacobians.widgets.live.story import TOL, story_state, story_times
from jacobians.widgets.live.story import largest_difference as story_difference

HALF_ULP = 0.005 + 1e-9  # the table shows 2 decimals

# The view's state (every number it drew) and the drawn SVG, read at once.
READ_JS = with_data("""(() => {
  const s = el.jacLive;
  const arrow = (g) => {
    const l = g.querySelector("line"), h = g.querySelector("polygon");
    return g.getAttribute("visibility") === "hidden" ? null
      : {from: [+l.getAttribute("x1"), +l.getAttribute("y1")], tip: h.getAttribute("points").split(" ")[0].split(",").map(Number)};
  };
  const pick = (sel) => [...el.querySelectorAll(sel)].map(arrow);
  const link = el.querySelector("polyline.jl-link");
  return {
    state: JSON.parse(JSON.stringify({...s, drawn: undefined})),
    frame: data.step, playing: data.playing, theta: data.theta,
    link: link ? link.getAttribute("points").split(" ").map((p) => p.split(",").map(Number)) : null,
    vs: pick("g.js-vs"), pdot: pick("g.js-pdot"), left: pick("g.js-left"), right: pick("g.js-right"),
    xb: pick("g.js-xb"),
    table: [...el.querySelectorAll("table.js-numbers tbody tr")].map((tr) => [...tr.querySelectorAll("td")].map((td) => td.textContent)),
    slider: el.querySelector("input.js-time").value, time: el.querySelector("output.js-time-value").textContent,
    text: el.innerText, markup: el.innerHTML,
  };
})()""")


def chain_of(model: dict[str, Any]) -> jac.SerialChain:
    return jac.SerialChain(np.array(model["S"]), np.array(model["M"]), joint_points=np.array(model["Q"]))


def library_state(model: dict[str, Any], chain: jac.SerialChain, t: float) -> dict[str, np.ndarray]:
    """What the view must show at time t, computed by the library (``story_state``; ``chain`` is the model's)."""
    return story_state(model, t)


def largest_difference(model: dict[str, Any], chain: jac.SerialChain, got: dict[str, Any]) -> float:
    """max over the state's arrays of |js - lib| / max(1, max |lib|)."""
    return story_difference(model, got)


def _number(cell: str) -> float:
    return float(cell.replace("\u2212", "-"))


def check_view(el: Any, model: dict[str, Any]) -> dict[str, Any]:
    """The shown frame: numbers = library (TOL), drawn SVG = those numbers, table = library (2 decimals)."""
    chain = chain_of(model)
    got = el.evaluate(READ_JS)
    s = got["state"]
    k = got["frame"]
    assert s["frame"] == k and int(got["slider"]) == k
    assert got["theta"] == s["theta"]  # data-theta: the angles drawn, the same numbers (JSON keeps a double exactly)
    assert s["t"] == story_times(model)[k]
    assert got["time"] == f"t = {s['t']:.2f} s".replace("-", "\u2212")
    assert largest_difference(model, chain, s) <= TOL
    want = library_state(model, chain, s["t"])
    tip = lambda a: np.asarray(a["tip"]) - np.asarray(a["from"])
    if model["story"] != "fixed_axis":
        assert np.allclose(got["link"], want["points"], atol=1e-12, rtol=0)  # the drawn arm
    if model["story"] == "body_columns":
        for i in range(3):
            assert np.allclose(got["left"][i]["from"], want["p"], atol=1e-12)
            assert np.allclose(tip(got["left"][i]), model["scale"] * want["vs"][i], atol=1e-12)
            assert np.allclose(tip(got["right"][i]), want["vb"][i], atol=1e-12)
        shown = np.array([[_number(c) for c in row] for row in got["table"]])
        assert np.abs(shown - want["vb"].T).max() <= HALF_ULP
    else:
        scale = model.get("vel_scale", 1.0)
        assert np.allclose(got["vs"][0]["from"], [0, 0]) and np.allclose(tip(got["vs"][0]), scale * want["vS"][:2], atol=1e-12)
        assert np.allclose(got["pdot"][0]["from"], want["p"], atol=1e-12)
        assert np.allclose(tip(got["pdot"][0]), scale * want["pDot"][:2], atol=1e-12)
        shown = np.array([[_number(c) for c in row] for row in got["table"]])
        if model["story"] == "fixed_axis":
            rows = [np.r_[want["vS"][:2], np.linalg.norm(want["vS"])], np.r_[want["pDot"][:2], np.linalg.norm(want["pDot"])]]
        else:
            rows = [np.r_[want[key], np.linalg.norm(want[key])] for key in ("omegaS", "omegaB", "pDot", "vS", "vB")]
        assert np.abs(shown - np.array(rows)).max() <= HALF_ULP
    assert not any(re.fullmatch(r"[-\u2212]0\.00", c) for row in got["table"] for c in row)
    assert "NaN" not in got["text"] and "NaN" not in got["markup"] and "Infinity" not in got["markup"]
    return got
