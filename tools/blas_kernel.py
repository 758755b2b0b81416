"""Print which BLAS library and CPU kernel numpy runs on (threadpoolctl), and check it is the one asked for.

OpenBLAS picks a kernel for the CPU at start-up; ``OPENBLAS_CORETYPE=<name>``
(e.g. ``Prescott``, ``Sandybridge``, ``Haswell``) makes it use another one, as
another machine would. ``make test-numerics`` runs this before each run of the
floating-point comparisons, so the log says what was tested.

Usage: python -m tools.blas_kernel [--expect NAME]   (exit 1 if numpy's OpenBLAS does not run NAME)
"""

from __future__ import annotations

import argparse
import sys

#: names OpenBLAS reports for a kernel asked for by another name. Without DYNAMIC_OLDER (numpy's wheels),
#: OpenBLAS's dynamic.c defines the Katmai, Coppermine and Northwood tables as the Prescott one, and its
#: name lookup meets Katmai first: OPENBLAS_CORETYPE=Prescott runs the Prescott kernel and says "Katmai".
ALIASES = {"prescott": {"prescott", "katmai", "coppermine", "northwood"}}


def kernels() -> list[dict[str, object]]:
    """threadpoolctl's description of every BLAS library loaded by numpy (after a product, so it is loaded)."""
    import numpy as np
    from threadpoolctl import threadpool_info

    a = np.arange(16.0).reshape(4, 4)
    _ = a @ a
    return [info for info in threadpool_info() if info.get("user_api") == "blas"]


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--expect", help="the OpenBLAS kernel (architecture) that must be running")
    args = parser.parse_args(argv)
    found = kernels()
    for info in found:
        print(f"blas: {info.get('internal_api')} {info.get('version')}, kernel {info.get('architecture')}, "
              f"{info.get('num_threads')} threads ({info.get('filepath')})")
    if not found:
        print("blas: numpy loaded no BLAS library that threadpoolctl knows", file=sys.stderr)
        return 1
    if args.expect:
        archs = {str(info.get("architecture", "")).lower() for info in found}
        if not archs & ALIASES.get(args.expect.lower(), {args.expect.lower()}):
            print(f"blas: expected the {args.expect} kernel, numpy runs {sorted(archs)}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
