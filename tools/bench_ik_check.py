"""The first check of the IK code exercise (``make bench``): how long a student waits for the verdict the first
time they check ``my_ik`` in a session, when the test cases of their variant are drawn (later checks reuse them).

``python -m tools.bench_ik_check [N]`` times the first check of the reference loop for N IDs (default 20), each with
the cache of drawn cases emptied, and prints the median and the largest, in CPU seconds of this process and in
wall-clock seconds (the wall clock counts the other work on the machine too).
"""

from __future__ import annotations

import statistics
import sys
import time


def main(n: int = 20) -> None:
    from course import exercises
    from jacobians.grading import exercise as grading

    cpu, wall = [], []
    for k in range(n):
        seed = f"s{2417000 + 37 * k}"
        ex = exercises.load("ch10_ex4", seed=seed)
        grading._CASES.clear()
        t0, c0 = time.perf_counter(), time.process_time()
        fb = exercises.check("ch10_ex4", ex.reference, seed=seed)
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - t0)
        if not fb.correct:
            raise SystemExit(f"the reference loop was refused for {seed}: {fb.message}")
    print(f"ch10_ex4 first check over {n} IDs: CPU median {statistics.median(cpu):.2f} s, max {max(cpu):.2f} s; "
          f"wall median {statistics.median(wall):.2f} s, max {max(wall):.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)
