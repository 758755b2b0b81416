"""A hostile class: what a student's code can try in make grade's sandbox, and what the grader must not do.

Part 1 runs small attacker programs straight in a sandbox (:func:`course.classroom.sandbox.start`), one
property each. Part 2 grades a class of hostile notebooks next to honest ones and checks each row, that the
submissions are byte-identical afterwards and that nothing is left running.

Every bomb is bounded on its own (a few dozen processes, a few hundred MB), so that a broken sandbox cannot
harm the machine. The tests need root and bubblewrap (``make test-lib`` installs it); without them they are
skipped with the reason :func:`course.classroom.sandbox.isolation` gives.
"""

from __future__ import annotations

import json
import os
import socket
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course.classroom import sandbox
from course.classroom.sandbox import Limits, kill_tree, limits_hit, make_scratch, remove_scratch, start

ISOLATION = sandbox.isolation()
pytestmark = pytest.mark.skipif(not ISOLATION.ok, reason=f"no isolation here: {ISOLATION.reason}")


@pytest.fixture()
def parent() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="hostile-"))
    path.chmod(0o711)
    yield path
    import shutil

    shutil.rmtree(path, ignore_errors=True)


def _run(code: str, parent: Path, limits: Limits | None = None, timeout: float = 60) -> tuple[dict, list[str]]:
    """Run ``code`` in a fresh sandbox; it prints one JSON object. Returns it and the limits the sandbox hit."""
    scratch = make_scratch(parent)
    (scratch / "attack.py").write_text(code, encoding="utf-8")  # (a file: the sandbox's /proc shows argv)
    proc = start([sys.executable, "-P", "attack.py"], scratch, limits or Limits(), cpu_seconds=timeout,
                 pipes=True)
    try:
        out, _ = proc.communicate(timeout=timeout)
    finally:
        hit = limits_hit(proc)
        kill_tree(proc)
        remove_scratch(scratch)
    return json.loads(out.decode() or "{}"), hit


def _alive(uid: int) -> list[int]:
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if entry.stat().st_uid == uid:
                    out.append(int(entry.name))
            except OSError:
                pass
    return out


def test_the_sandbox_sees_only_itself(parent):
    secret = parent.parent / f"submissions-{os.getpid()}"
    secret.mkdir(exist_ok=True)
    (secret / "classmate.ipynb").write_text("answers of a classmate", encoding="utf-8")
    try:
        code = f"""
import json, os
out = {{"uid": os.getuid(), "cwd": os.getcwd(), "pids": sorted(int(p) for p in os.listdir("/proc") if p.isdigit())}}
out["cmdlines"] = [open(f"/proc/{{p}}/cmdline", "rb").read().decode(errors="replace") for p in out["pids"]
                   if p != os.getpid()]  # (this program's own command line holds the paths it tries)
out["environ"] = sorted(os.environ)
out["etc"] = sorted(os.listdir("/etc"))
for name, path in [("submission", {str(secret / "classmate.ipynb")!r}), ("shadow", "/etc/shadow"),
                   ("grader_tmp", {str(parent)!r})]:
    try:
        os.listdir(path) if name == "grader_tmp" else open(path).read()
        out[name] = "readable"
    except OSError as exc:
        out[name] = type(exc).__name__
print(json.dumps(out))
"""
        got, _ = _run(code, parent)
    finally:
        import shutil

        shutil.rmtree(secret)
    assert got["uid"] >= sandbox.UID_BASE and got["cwd"] == sandbox.HOME
    assert got["pids"][0] == 1 and len(got["pids"]) <= 3  # bwrap's init, the program (its own PID namespace)
    assert got["cmdlines"] and not any(str(secret) in c or str(parent) in c for c in got["cmdlines"])
    assert got["submission"] == got["shadow"] == got["grader_tmp"] == "FileNotFoundError"
    assert set(got["etc"]) <= {"ld.so.cache", "localtime", "nsswitch.conf"}
    assert "JACOBIANS_PROGRESS_LOG" not in got["environ"] and "SUDO_USER" not in got["environ"]


def test_no_network_not_even_to_a_server_of_this_machine(parent):
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(5)
    server.settimeout(0.2)
    port = server.getsockname()[1]
    accepted: list[bytes] = []
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            accepted.append(conn.recv(4096))
            conn.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    code = f"""
import json, socket
out = {{}}
for host in ("127.0.0.1", "localhost", "10.0.2.2"):
    try:
        s = socket.create_connection((host, {port}), timeout=2)
        s.sendall(b"a classmate's notebook")
        out[host] = "connected"
    except OSError as exc:
        out[host] = type(exc).__name__
print(json.dumps(out))
"""
    try:
        got, _ = _run(code, parent)
    finally:
        stop.set()
        thread.join()
        server.close()
    assert got and "connected" not in got.values(), got
    assert accepted == []


def test_a_survivor_that_leaves_the_session_dies_with_the_sandbox(parent):
    # setsid and execve with an empty environment, through ctypes (no audit event): the old kill_tree missed it
    code = r"""
import ctypes, json, os, time
libc = ctypes.CDLL(None)
pid = os.fork()
if pid == 0:
    libc.setsid()
    argv = (ctypes.c_char_p * 4)(b"/bin/sh", b"-c", b"sleep 300", None)
    envp = (ctypes.c_char_p * 1)(None)
    libc.execve(b"/bin/sh", argv, envp)
    os._exit(1)
time.sleep(0.5)
print(json.dumps({"child": pid}))
"""
    scratch = make_scratch(parent)
    uid = sandbox.scratch_owner(scratch)
    proc = start([sys.executable, "-P", "-c", code], scratch, Limits(), cpu_seconds=30, pipes=True)
    out, _ = proc.communicate(timeout=60)
    assert json.loads(out)["child"] > 0
    assert uid is not None and _alive(uid), "the survivor should be running before the sandbox is killed"
    kill_tree(proc)
    remove_scratch(scratch)
    deadline = time.monotonic() + 5
    while _alive(uid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _alive(uid) == []
    for hierarchy in ("pids", "memory", "freezer"):
        assert not (Path("/sys/fs/cgroup") / hierarchy / sandbox.CGROUP_PARENT / str(uid)).exists()


def test_a_fork_bomb_is_capped_for_the_whole_sandbox(parent):
    # 50 forks at most (harmless even without a sandbox); the sandbox allows 16 processes and threads
    code = r"""
import json, os, time
made, refused = 0, 0
for _ in range(50):
    try:
        pid = os.fork()
    except OSError:
        refused += 1
        continue
    if pid == 0:
        time.sleep(20)
        os._exit(0)
    made += 1
print(json.dumps({"made": made, "refused": refused}), flush=True)
"""
    got, hit = _run(code, parent, Limits(processes=16), timeout=60)
    assert got["made"] < 16 and got["refused"] > 30, got
    assert "processes" in hit


def test_memory_is_capped_for_the_whole_sandbox_not_per_process(parent):
    # three processes of 120 MB each (360 MB at most); the sandbox may use 250 MB in all
    code = r"""
import json, os, time
kids = []
for _ in range(3):
    pid = os.fork()
    if pid == 0:
        block = bytearray(120 << 20)
        for i in range(0, len(block), 4096):
            block[i] = 1
        time.sleep(5)
        os._exit(0)
    kids.append(pid)
status = [os.waitpid(k, 0)[1] for k in kids]
print(json.dumps({"killed": sum(os.WIFSIGNALED(s) for s in status)}), flush=True)
"""
    got, hit = _run(code, parent, Limits(memory=250 << 20), timeout=60)
    assert got["killed"] >= 1, got
    assert "memory" in hit


def test_writes_to_shared_memory_and_tmp_through_libc_vanish_with_the_sandbox(parent):
    marker = f"hostile-{os.getpid()}"
    code = f"""
import ctypes, json, os
libc = ctypes.CDLL(None)
out = {{}}
for path in ("/dev/shm/{marker}", "/tmp/{marker}", "/var/tmp/{marker}", "/{marker}"):
    fd = libc.open(path.encode(), os.O_WRONLY | os.O_CREAT, 0o644)
    out[path] = fd >= 0 and libc.write(fd, b"left behind", 11) == 11
print(json.dumps(out))
"""
    got, _ = _run(code, parent)
    assert got[f"/dev/shm/{marker}"] and got[f"/tmp/{marker}"]  # its own tmpfs: allowed, and private
    assert not got[f"/var/tmp/{marker}"] and not got[f"/{marker}"]  # read-only everywhere else
    for path in (f"/dev/shm/{marker}", f"/tmp/{marker}", f"/var/tmp/{marker}", f"/{marker}"):
        assert not os.path.exists(path), path


def test_without_isolation_the_grader_refuses_unless_unsafe(monkeypatch, tmp_path):
    from course.classroom import grade

    monkeypatch.setattr(grade, "isolation", lambda: sandbox.Isolation(False, "bwrap is missing"))
    monkeypatch.delenv(sandbox.UNSAFE_ENV, raising=False)
    with pytest.raises(grade.Refused, match="bwrap is missing.*UNSAFE=1"):
        grade.grade_class(tmp_path)
    assert not (tmp_path / "gradebook.csv").exists()


# --------------------------------------------------------------------------- the grader's own work is bounded
@pytest.mark.parametrize("tree", [
    ["F", "Pow", [["Integer", "3"], ["Integer", "100000000"]]],  # 85 s of the grader's CPU before the bounds
    ["F", "Pow", [["F", "Pow", [["Integer", "3"], ["Integer", "64"]]], ["Integer", "64"]]],  # 3**4096
    ["F", "Pow", [["Integer", "9" * 399], ["Integer", "64"]]],
    ["F", "Mul", [["Symbol", "x", {}]] * 100],  # x**100, made by Mul
    ["F", "Pow", [["Symbol", "x", {}], ["Rational", "1", "100000"]]],
])
def test_a_decoder_bomb_decodes_to_too_large(tree):
    from course.classroom.answers import Opaque, decode

    assert decode({"t": "sympy", "v": tree}) == Opaque("too large")


def test_answers_of_the_course_still_decode():
    import sympy as sp

    from course.classroom.answers import decode, encode

    x = sp.Symbol("x", real=True)
    for value in (sp.sqrt(2) * x**2, (1 + x) ** -3, sp.Rational(2**200, 3), sp.Matrix([[x**64, 1 / x]])):
        assert decode(encode(value)) == value


def test_overlong_log_lines_are_skipped_unread(tmp_path):
    from course.classroom import grade

    log = tmp_path / "checks.jsonl"
    good = json.dumps({"exercise": "ch02_ex1", "answer": {"t": "int", "v": "1"}})
    log.write_text(good + "\n" + json.dumps({"exercise": "ch02_ex1", "answer": {"t": "str", "v": "x" * (
        grade.MAX_LOG_LINE + 10)}}) + "\n", encoding="utf-8")
    assert grade._last_checks(log, {"ch02_ex1"})["ch02_ex1"]["answer"] == {"t": "int", "v": "1"}


def test_the_checker_gets_a_cpu_budget():
    from course.classroom import grade

    with pytest.raises(grade._OverTime), grade._cpu_limit(0.2):
        while True:
            pass


def test_an_exercise_variable_travels_as_its_id_and_is_rebuilt_only_in_the_sandbox():
    from course import exercises
    from course.classroom.answers import Opaque, decode, encode

    ns = {"__name__": "__main__", "ex4": exercises.load("ch01_ex4", seed="s1")}
    exec("def f(T):\n    return ex4.given['inverse']\n", ns)
    data = encode(ns["f"])
    assert data["constants"]["ex4"] == {"t": "exercise", "id": "ch01_ex4"}
    assert decode(data["constants"]["ex4"]) == Opaque("Exercise")  # the grader never builds it
