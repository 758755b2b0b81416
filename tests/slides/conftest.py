"""Shared set-up of the slide tests: the tools/ folder on sys.path."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
for p in (ROOT / "tools", ROOT / "_ext"):
    if str(p) not in sys.path:
        sys.path.insert(0, str(p))
