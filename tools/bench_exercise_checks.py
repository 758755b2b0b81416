"""How fast does an exercise page check an answer, and how much checking data does it load? Prints, never asserts.

On the built book (``make book`` first), in headless Chromium: every exercise page is opened once; for each
exercise it checks, 200 answers (the reference, mistakes, wrong shapes, text: the answers of the agreement
test, for a few IDs) are checked one at a time with the page's ``courseExercises.checkText`` (reading the text
with math.js and comparing), each timed with ``performance.now()``. Prints the median and the worst per page,
the size of each exercise's bank file, and the size of the checker script; and each exercise page's weight on a
first visit (every byte its requests brought, with the HTTP cache off, once the statements of its variants are on
the page). Budgets (the issue's): a check <= 50 ms median, a bank <= 100 KB, a first visit <= 2 MB.

    .venv/bin/python -m tools.bench_exercise_checks
"""

from __future__ import annotations

import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "browser"))

import bookcheck  # type: ignore[import-not-found]  # noqa: E402
from exercise_answers import answers_for  # type: ignore[import-not-found]  # noqa: E402

from course import exercises  # noqa: E402
from course.exercises._bank import PAGE_KINDS, variant_index  # noqa: E402

HTML = ROOT / "_build" / "html"


def main() -> None:
    from playwright.sync_api import sync_playwright

    if not (HTML / "exercises" / "01_twists.html").is_file():
        raise SystemExit("Build the book first (make book)")
    banks = HTML / "_static" / "exercise-checks" / "banks"
    sizes = {p.stem: p.stat().st_size for p in sorted(banks.glob("*.js"))}
    statements = [p.stat().st_size for p in (HTML / "_static" / "exercise-checks" / "statements").glob("*/*.js")]
    checker = HTML / "_static" / "exercise-checks" / "checker.js"
    print(f"checker.js (math.js included, minified): {checker.stat().st_size / 1024:.1f} KB")
    print(f"banks: {len(sizes)}, largest {max(sizes.values()) / 1024:.1f} KB ({max(sizes, key=sizes.__getitem__)}), "
          f"median {statistics.median(sizes.values()) / 1024:.1f} KB")
    print(f"typeset statements: {len(statements)}, largest {max(statements) / 1024:.1f} KB, "
          f"median {statistics.median(statements) / 1024:.1f} KB (one a variant; the page loads the reader's)")
    all_times: list[float] = []
    weights: dict[str, tuple[int, int]] = {}
    with bookcheck.BookServer(HTML) as server, sync_playwright() as p, bookcheck.opened_browser(p) as context:
        for page in sorted((ROOT / "exercises").glob("*.md")):
            tab = context.new_page()
            responses: list = []
            tab.on("response", lambda r, seen=responses: seen.append(r))
            tab.route("**/*", lambda r: r.continue_())  # (routing turns the HTTP cache off: a first visit)
            tab.goto(f"{server.base}/exercises/{page.stem}.html", wait_until="load")
            tab.wait_for_function("window.courseExercises !== undefined")
            tab.evaluate("window.courseExercises.typesetDone().then(() => true)")
            tab.wait_for_load_state("networkidle")
            weight = sum(r.request.sizes()["responseBodySize"] for r in responses)
            weights[page.stem] = (weight, len(responses))
            ids = tab.eval_on_selector_all(".course-answer[data-exercise]", "els => els.map(e => e.dataset.exercise)")
            times: list[float] = []
            for eid in ids:
                if exercises.load(eid, seed="x").kind not in PAGE_KINDS:
                    continue
                batch = []
                for sid in ("s1", "s2", "s3", "s4", "s5"):
                    ex = exercises.load(eid, seed=sid)
                    batch += [[variant_index(eid, sid), text] for text, _ in answers_for(ex)]
                batch = batch[:200]
                times += tab.evaluate("""([eid, batch]) => batch.map(([k, text]) => {
                    const t0 = performance.now();
                    window.courseExercises.checkText(eid, k, text);
                    return performance.now() - t0; })""", [eid, batch])
            tab.close()
            all_times += times
            print(f"{page.stem}: {len(times)} checks, median {statistics.median(times):.3f} ms, "
                  f"worst {max(times):.2f} ms; banks "
                  + ", ".join(f"{e} {sizes[e] / 1024:.0f} KB" for e in ids if e in sizes))
    print(f"all pages: {len(all_times)} checks, median {statistics.median(all_times):.3f} ms "
          f"(budget 50 ms), worst {max(all_times):.2f} ms")
    print("first visit of each exercise page (budget 2 MB = 2,000,000 bytes):")
    for stem, (weight, n) in weights.items():
        print(f"  {stem:28s} {weight:>10,d} bytes ({weight / 2**20:.2f} MiB) over {n} requests")


if __name__ == "__main__":
    main()
