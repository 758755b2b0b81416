"""tools/precompress.cjs: a .gz and a .br next to each text file of 1 KB or more, the same bytes unpacked.

Run on a small made-up site: the copies unpack to the original (gzip with Python,
brotli with Node's zlib), small and binary files get none, a copy whose original
changed is written again, and a copy whose original is gone is removed.
"""

from __future__ import annotations

import gzip
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "precompress.cjs"


def _run(site: Path) -> str:
    node = shutil.which("node")
    if node is None:
        pytest.fail("node is missing (make setup needs it)", pytrace=False)
    return subprocess.run([node, str(SCRIPT), str(site)], capture_output=True, text=True, check=True).stdout


def _unbrotli(path: Path) -> bytes:
    return subprocess.run(["node", "-e", "process.stdout.write(require('zlib').brotliDecompressSync("
                           "require('fs').readFileSync(process.argv[1])))", str(path)],
                          capture_output=True, check=True).stdout


def test_precompressed_copies(tmp_path):
    site = tmp_path / "html"
    (site / "_static").mkdir(parents=True)
    page = "<html><body>" + "<p>The space Jacobian J_s maps joint rates to the twist.</p>\n" * 60 + "</body></html>"
    (site / "index.html").write_text(page)
    (site / "_static" / "app.js").write_text("console.log('x');\n" * 100)
    (site / "_static" / "tiny.css").write_text("p{}")
    (site / "_static" / "font.woff").write_bytes(os.urandom(4000))
    out = _run(site)
    assert "precompress:" in out
    for name in ("index.html", "_static/app.js"):
        original = (site / name).read_bytes()
        assert gzip.decompress((site / (name + ".gz")).read_bytes()) == original
        assert _unbrotli(site / (name + ".br")) == original
        assert (site / (name + ".br")).stat().st_size < len(original) / 4
    assert not list(site.glob("_static/tiny.css.*")) and not list(site.glob("_static/font.woff.*"))
    # a changed original gets new copies; a copy without its original goes
    (site / "index.html").write_text(page.replace("space", "body"))
    later = (site / "index.html.gz").stat().st_mtime + 5
    os.utime(site / "index.html", (later, later))
    (site / "_static" / "app.js").unlink()
    _run(site)
    assert b"body Jacobian" in gzip.decompress((site / "index.html.gz").read_bytes())
    assert b"body Jacobian" in _unbrotli(site / "index.html.br")
    assert not (site / "_static" / "app.js.gz").exists() and not (site / "_static" / "app.js.br").exists()


def test_precompress_refuses_a_folder_that_is_no_site(tmp_path):
    run = subprocess.run(["node", str(SCRIPT), str(tmp_path)], capture_output=True, text=True, check=False)
    assert run.returncode == 2 and "no index.html" in run.stderr
