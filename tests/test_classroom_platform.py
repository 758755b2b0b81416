"""make grade on other machines: as a normal user, and with cgroup v2 (this machine has v1), tested with stand-ins
where the real thing is not here; and the class page's notes on a class with attackers. No notebook is run."""

from __future__ import annotations

import os
import shutil
import subprocess

import pytest

from course.classroom import grade, sandbox
from course.classroom.grade import Row
from course.classroom.report import class_page
from course.classroom.sandbox import Limits


def test_a_normal_user_is_refused_with_the_reason(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(sandbox.os, "geteuid", lambda: 1000)
    how = sandbox.probe_isolation()
    assert not how.ok and "not root" in how.reason and "sudo make grade" in how.reason
    monkeypatch.setattr(grade, "isolation", lambda: how)
    monkeypatch.delenv(sandbox.UNSAFE_ENV, raising=False)
    assert grade.main([str(tmp_path)]) == 3
    err = capsys.readouterr().err
    assert "refuses to grade" in err and "not root" in err and "UNSAFE=1" in err
    assert not (tmp_path / "gradebook.csv").exists()


@pytest.mark.skipif(os.geteuid() != 0 or shutil.which("bwrap") is None or shutil.which("setpriv") is None,
                    reason="needs root (to become a normal user) and bubblewrap")
def test_user_namespaces_let_a_normal_user_run_bwrap_here():
    # what the refusal above gives up: bwrap itself works unprivileged here (user namespaces are allowed), but a
    # normal user cannot give each notebook a uid and a cgroup of its own
    done = subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "--", "bwrap",
                           "--unshare-all", "--ro-bind", "/usr", "/usr", "--symlink", "usr/bin", "/bin",
                           "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64", "--proc", "/proc",
                           "--dev", "/dev", "--", "/usr/bin/id", "-u"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == "65534", done


def _v2(root, controllers="cpuset cpu io memory hugetlb pids rdma misc"):
    root.mkdir(exist_ok=True)
    (root / "cgroup.controllers").write_text(controllers + "\n")
    (root / "cgroup.subtree_control").write_text("")
    return root


def test_cgroup_v2_is_recognised_and_what_it_lacks_is_said(tmp_path):
    assert sandbox._cgroup_kind(_v2(tmp_path / "full")) == ("v2", "")
    kind, why = sandbox._cgroup_kind(_v2(tmp_path / "nopids", "cpu io memory"))
    assert kind is None and "lacks the memory or pids controller" in why
    kind, why = sandbox._cgroup_kind(tmp_path / "none")
    assert kind is None and "no writable cgroup hierarchy" in why
    v1 = tmp_path / "v1"
    for h in ("memory", "pids", "freezer"):
        (v1 / h).mkdir(parents=True)
        (v1 / h / "cgroup.procs").write_text("")
    assert sandbox._cgroup_kind(v1) == ("v1", "")


def test_a_cgroup_v2_sandbox_gets_its_limits_and_reports_what_it_hit(tmp_path):
    root = _v2(tmp_path / "cg")
    cg = sandbox._Cgroup("v2", "2100000001", Limits(memory=300 << 20, processes=48), root=root)
    d = root / sandbox.CGROUP_PARENT / "2100000001"
    assert (d / "memory.max").read_text() == str(300 << 20) and (d / "pids.max").read_text() == "48"
    for parent in (root, root / sandbox.CGROUP_PARENT):
        assert (parent / "cgroup.subtree_control").read_text() == "+memory +pids"
    assert cg.procs == [str(d / "cgroup.procs")]
    (d / "memory.events").write_text("low 0\nhigh 0\nmax 3\noom 1\noom_kill 1\n")
    (d / "pids.events").write_text("max 0\n")
    assert cg.hit_limits() == ["memory"]
    (d / "pids.events").write_text("max 7\n")
    (d / "memory.events").write_text("low 0\nhigh 0\nmax 0\noom 0\noom_kill 0\n")
    assert cg.hit_limits() == ["processes"]
    (d / "memory.peak").write_text("12345\n")
    assert cg.memory_peak() == 12345


def test_the_class_page_lists_what_needs_a_look_and_the_roster_apart():
    n = "(notebook)"
    rows = [Row("s-a", "a.ipynb", "ch02_ex1", "s-a", "1", "Correct."),
            Row("s-b", "b.ipynb", "ch02_ex1", "s-b", "0", "wrong: off", "transposed"),
            Row("s-a", "a.ipynb", n, "s-a", "", "left 1 process(es) running after its last cell (sh); they were "
                                                "killed with its sandbox"),
            Row("s-b", "b.ipynb", n, "s-b", "", "code cell 2 raised OSError: [Errno 101] Network is unreachable"),
            Row("s-c", "", "(roster)", "", "", "this ID is not on the roster")]
    page = class_page(rows)
    assert "2 notebooks need a look" in page and 'href="reports/s-a.html"' in page
    assert "It left 1 process(es) running" in page and "Code cell 2 raised OSError" in page
    assert '<h2 id="roster">' in page and "<strong>s-c</strong>: This ID is not on the roster" in page
    assert "Tried (of 2)" in page and "UNSAFE" not in page
    unsafe = [Row(r.student, r.notebook, r.exercise, r.seed, r.correct, grade.UNSAFE_NOTE + r.message) for r in rows]
    assert "Graded without isolation (UNSAFE=1)" in class_page(unsafe)
