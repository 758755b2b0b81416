"""A hostile class: what a student's code can try in make grade's sandbox, and what the grader must not do.

Part 1 runs small attacker programs straight in a sandbox (:func:`course.classroom.sandbox.start`), one
property each. Part 2 grades a class of hostile notebooks next to honest ones and checks each row, that the
submissions are byte-identical afterwards and that nothing is left running; the class hands in the made-up
chapter ``ch00`` (``tests/fixtures/classroom.py``), not a chapter of the course.

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
from contextlib import contextmanager
from pathlib import Path

import pytest
from tests.fixtures import classroom
from tests.fixtures.classroom import CODE, IDS, PAGE

from course import exercises
from course.classroom import sandbox
from course.classroom.sandbox import Limits, kill_tree, limits_hit, make_scratch, remove_scratch, start

fixture_chapter = classroom.fixture_chapter  # (the made-up chapter in the catalogue, for this module's tests)
#: The chapter's symbolic exercise (the decoder bomb's target) and a numeric one.
SYMBOLIC = next(eid for eid, kind in classroom.KINDS.items() if kind == "symbolic")
NUMERIC = next(eid for eid, kind in classroom.KINDS.items() if kind == "numeric")
CH = CODE.split("_")[0]

ISOLATION = sandbox.isolation()
pytestmark = pytest.mark.skipif(not ISOLATION.ok and not ISOLATION.broken, reason=f"no isolation here: {ISOLATION.reason}")


def test_the_sandbox_works_where_the_machine_allows_it():
    """A machine with root, bubblewrap and a cgroup must get working sandboxes: their failure is the grader's."""
    assert not ISOLATION.broken, ISOLATION.reason


@pytest.fixture()
def parent() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="hostile-"))
    path.chmod(0o711)
    yield path
    import shutil

    shutil.rmtree(path, ignore_errors=True)


@contextmanager
def _sandbox(code: str, parent: Path, limits: Limits | None = None, cpu_seconds: float = 60):
    """``code`` started in a fresh sandbox (as a file: the sandbox's /proc shows argv); yields (process,
    scratch folder). On exit the sandbox is killed with everything it started and its scratch removed."""
    scratch = make_scratch(parent)
    (scratch / "attack.py").write_text(code, encoding="utf-8")
    proc = start([sys.executable, "-P", "attack.py"], scratch, limits or Limits(), cpu_seconds=cpu_seconds,
                 pipes=True)
    try:
        yield proc, scratch
    finally:
        kill_tree(proc)
        remove_scratch(scratch)


def _run(code: str, parent: Path, limits: Limits | None = None, timeout: float = 60) -> tuple[dict, list[str]]:
    """Run ``code`` in a fresh sandbox; it prints one JSON object. Returns it and the limits the sandbox hit."""
    with _sandbox(code, parent, limits, cpu_seconds=timeout) as (proc, _):
        try:
            out, _ = proc.communicate(timeout=timeout)
        finally:
            hit = limits_hit(proc)
    return json.loads(out.decode() or "{}"), hit


@contextmanager
def _listening_server():
    """A TCP server on 127.0.0.1 that records what it receives: yields (port, received)."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(5)
    server.settimeout(0.2)
    received: list[bytes] = []
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            received.append(conn.recv(4096))
            conn.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield server.getsockname()[1], received
    finally:
        stop.set()
        thread.join()
        server.close()


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
    with _listening_server() as (port, accepted):
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
        got, _ = _run(code, parent)
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
    with _sandbox(code, parent, cpu_seconds=30) as (proc, scratch):
        uid = sandbox.scratch_owner(scratch)
        out, _ = proc.communicate(timeout=60)
        assert json.loads(out)["child"] > 0
        assert uid is not None and _alive(uid), "the survivor should be running before the sandbox is killed"
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
    from course.classroom.answer_data import Opaque, decode

    assert decode({"t": "sympy", "v": tree}) == Opaque("too large")


def test_answers_of_the_course_still_decode():
    import sympy as sp

    from course.classroom.answer_data import decode, encode

    x = sp.Symbol("x", real=True)
    for value in (sp.sqrt(2) * x**2, (1 + x) ** -3, sp.Rational(2**200, 3), sp.Matrix([[x**64, 1 / x]])):
        assert decode(encode(value)) == value


def test_overlong_log_lines_are_skipped_unread(tmp_path):
    from course.classroom import grade

    log = tmp_path / "checks.jsonl"
    good = json.dumps({"exercise": NUMERIC, "answer": {"t": "int", "v": "1"}})
    log.write_text(good + "\n" + json.dumps({"exercise": NUMERIC, "answer": {"t": "str", "v": "x" * (
        grade.MAX_LOG_LINE + 10)}}) + "\n", encoding="utf-8")
    assert grade._last_checks(log, {NUMERIC})[NUMERIC]["answer"] == {"t": "int", "v": "1"}


def test_the_checker_gets_a_cpu_budget():
    from course.classroom import grade

    with pytest.raises(grade._OverTime), grade._cpu_limit(0.2):
        while True:
            pass


def test_an_exercise_variable_travels_as_its_id_and_is_rebuilt_only_in_the_sandbox(fixture_chapter):
    from course.classroom.answer_data import Opaque, decode, encode

    ns = {"__name__": "__main__", "ex4": exercises.load(CODE, seed="s1")}
    exec("def f(T):\n    return ex4.given['unit']\n", ns)
    data = encode(ns["f"])
    assert data["constants"]["ex4"] == {"t": "exercise", "id": CODE}
    assert decode(data["constants"]["ex4"]) == Opaque("Exercise")  # the grader never builds it


# --------------------------------------------------------------------------- part 2: a hostile class, graded
#: The exercises of the chapter the class hands in.
IDS02 = IDS
MARK = f"hostile-{os.getpid()}"

_SURVIVOR = r'''import ctypes
libc = ctypes.CDLL(None)  # fork + setsid + execve with an empty environment, done by libc (posix_spawn with
line = ('{"exercise": "%s", "seed": "x", "correct": false, "kind": "wrong", "answer": {"t": "int", "v": "0"}}')
script = ("end=$(($(date +%%s)+40)); while [ $(date +%%s) -lt $end ]; do for f in /home/*/checks.jsonl "
          "/tmp/*/checks.jsonl /tmp/*/*/checks.jsonl /proc/*/cwd/checks.jsonl /proc/*/root/home/student/checks.jsonl; "
          "do for e in IDS02; do printf '%s\\n' \"$(printf '%s' '%s' | sed s/EX/$e/)\" "
          ">> \"$f\"; done; done 2>/dev/null; sleep 0.2; done") % ("%s", "%s", line % "EX")
attr = ctypes.create_string_buffer(1024)  # POSIX_SPAWN_SETSID: no Python runs in the child; no audit event)
libc.posix_spawnattr_init(attr)
libc.posix_spawnattr_setflags(attr, ctypes.c_short(0x80))
pid = ctypes.c_int(0)
argv = (ctypes.c_char_p * 4)(b"/bin/sh", b"-c", script.encode(), None)
envp = (ctypes.c_char_p * 1)(None)
assert libc.posix_spawn(ctypes.byref(pid), b"/bin/sh", None, attr, argv, envp) == 0
assert libc.getsid(pid.value) == pid.value  # a session of its own: it left the kernel's process group
'''

_READER = r'''import glob, os
found = []
for pattern in (ROOT + "/**/*.ipynb", "/proc/*/cwd/*.ipynb", "/proc/*/root/home/student/*.ipynb", "/home/*/*.ipynb",
                "/tmp/**/*.ipynb", "/dev/shm/*"):
    found += [f for f in glob.glob(pattern, recursive=True)
              if os.path.realpath(f) != "/home/student/submission.ipynb"]  # (its own notebook)
stolen = "".join(open(f, errors="replace").read()[:2000] for f in found)
stolen += "".join(open(f"/proc/{p}/cmdline", errors="replace").read() for p in ("1", "2"))
raise RuntimeError(f"found {len(found)} notebooks; " + ("STOLEN " + stolen[:300] if "s-victim" in stolen or ROOT in
                   stolen.replace(f"ROOT = {ROOT!r}", "") else "nothing of the class"))
'''

_NET = r'''import socket
socket.create_connection(("127.0.0.1", PORT), timeout=3).sendall(b"a classmate's notebook")
'''

_DECODER_BOMB = r'''import json, os
with open(os.environ["JACOBIANS_PROGRESS_LOG"], "a") as f:
    f.write(json.dumps({"exercise": "SYMBOLIC", "seed": SEED, "correct": True, "kind": "correct", "answer": {
        "t": "sympy", "v": ["F", "Pow", [["Integer", "3"], ["Integer", "100000000"]]]}}) + "\n")
'''

_BOMBS = r'''import ctypes, os, time
libc = ctypes.CDLL(None)  # posix_spawn through ctypes: no audit event, and no Python runs in a child


def spawn(*argv):
    pid = ctypes.c_int(0)
    args = (ctypes.c_char_p * (len(argv) + 1))(*[a.encode() for a in argv], None)
    env = (ctypes.c_char_p * 1)(None)
    return pid.value if libc.posix_spawn(ctypes.byref(pid), args[0], None, None, args, env) == 0 else -1


made = sum(spawn("/bin/sleep", "3") > 0 for _ in range(50))  # 50 at most: harmless even without a sandbox
while True:  # wait for them, so that the memory test below has processes to spare
    try:
        os.wait()
    except ChildProcessError:
        break
touch = "b = bytearray(200 << 20)\nfor i in range(0, len(b), 4096): b[i] = 1\nimport time; time.sleep(3)"
kids = [spawn("/usr/bin/python3", "-c", touch) for _ in range(3)]  # 3 x 200 MB at most
status = [os.waitpid(k, 0)[1] for k in kids if k > 0]
print("forks made:", made, "killed:", sum(os.WIFSIGNALED(s) for s in status))
'''

_SHM = r'''import ctypes, os
libc = ctypes.CDLL(None)
for path in (b"/dev/shm/MARK", b"/tmp/MARK"):
    fd = libc.open(path, os.O_WRONLY | os.O_CREAT, 0o644)
    libc.write(fd, b"left behind", 11)
    libc.close(fd)
'''


def _with_cell(nb, index: int, source: str):
    import nbformat

    code = [i for i, c in enumerate(nb.cells) if c.cell_type == "code"]
    nb.cells.insert(code[index], nbformat.v4.new_code_cell(source))  # (index -1: before the progress cell)
    return nb


def _orphans() -> list[int]:
    """Processes of a sandbox uid that no grader holds any more (other graders may run on this machine; a
    uid in use is locked by its grader, see sandbox._take_uid), and cgroups of such uids."""
    import fcntl

    out = []
    for pid in _uids_alive():
        try:
            uid = Path(f"/proc/{pid}").stat().st_uid
        except OSError:
            continue
        fd = os.open(sandbox._uid_lock_dir() / str(uid), os.O_CREAT | os.O_RDWR, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            out.append(pid)  # nobody holds its uid: left behind
        except OSError:
            pass  # another grader's sandbox, running
        finally:
            os.close(fd)
    return out


def _uids_alive() -> list[int]:
    out = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                uid = entry.stat().st_uid
            except OSError:
                continue
            if sandbox.UID_BASE <= uid < sandbox.UID_BASE + sandbox.UID_COUNT:
                out.append(int(entry.name))
    return out


@pytest.fixture(scope="module")
def hostile_class(tmp_path_factory, fixture_chapter):
    root = tmp_path_factory.mktemp("hostile") / "submissions"
    (root / "dup").mkdir(parents=True)
    with _listening_server() as (port, received):
        rows, before, after = _grade_hostile_class(root, port)
    return root, rows, before, after, received


def _grade_hostile_class(root: Path, port: int):
    import hashlib

    import nbformat
    from tools.bench_grade import BOOK, submission

    from course.classroom.grade import grade_class

    w = nbformat.write
    w(_with_cell(submission(PAGE, "s-survivor", "right"), 1, _SURVIVOR.replace("IDS02", " ".join(IDS02))), root / "a_survivor.ipynb")
    w(submission(PAGE, "s-victim", BOOK), root / "b_victim.ipynb")
    w(_with_cell(submission(PAGE, "s-reader", "right"), 1, f"ROOT = {str(root)!r}\n" + _READER),
      root / "c_reader.ipynb")
    w(_with_cell(submission(PAGE, "s-net", "right"), 1, _NET.replace("PORT", str(port))), root / "d_net.ipynb")
    w(_with_cell(submission(PAGE, "s-decoder", "half"), -1, _DECODER_BOMB.replace("SYMBOLIC", SYMBOLIC)), root / "e_decoder.ipynb")
    w(_with_cell(submission(PAGE, "s-bombs", "right"), 4, _BOMBS), root / "f_bombs.ipynb")
    w(_with_cell(submission(PAGE, "s-shm", "right"), 1, _SHM.replace("MARK", MARK)), root / "g_shm.ipynb")
    w(submission(PAGE, "s2401012", "wrong"), root / "dup" / "old.ipynb")
    w(submission(PAGE, " S2401012 ", "right"), root / "dup" / "new.ipynb")
    os.utime(root / "dup" / "old.ipynb", (time.time() - 3600, time.time() - 3600))
    w(submission(PAGE, "student-id", "blank"), root / "h_placeholder1.ipynb")
    w(submission(PAGE, "student-id", "right"), root / "h_placeholder2.ipynb")
    w(submission(PAGE, "=2+3", "blank"), root / "i_injection.ipynb")
    w(submission(PAGE, "s-book", BOOK), root / "j_book.ipynb")
    roster = root.parent / "roster.csv"
    roster.write_text("ID,Name\ns-victim,Vic Tim\ns-book,Bo Ok\nS2401012,Dee Up\ns-absent,Ada Absent\n",
                      encoding="utf-8")
    before = {str(p): hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*") if p.is_file()}
    rows = grade_class(root, workers=2, roster=roster,
                       limits=Limits(cell_timeout=60, notebook_timeout=200, memory=400 << 20, processes=48))
    after = {str(p): hashlib.sha256(p.read_bytes()).hexdigest() for p in root.rglob("*") if p.is_file()
             if p.name not in ("gradebook.csv", "grades.csv", "class.html") and not {"reports", "exports"} & set(p.parts)}
    return rows, before, after


def _of(rows, notebook):
    return [r for r in rows if r.notebook == notebook]


def _grades(rows, notebook):
    return {r.exercise: r.correct for r in _of(rows, notebook) if r.correct in ("0", "1")}


def _notes(rows, notebook):
    return [r.message for r in _of(rows, notebook) if r.exercise == "(notebook)"]


def test_nothing_of_the_submissions_changed_and_nothing_is_left_running(hostile_class):
    root, rows, before, after, _ = hostile_class
    assert after == before
    assert not [r for r in rows if r.exercise == "(submissions)"]
    deadline = time.monotonic() + 5
    while _orphans() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _orphans() == []
    assert not [p for p in (*Path("/tmp").glob(f"{MARK}*"), *Path("/dev/shm").glob(f"{MARK}*"))]


def test_the_survivor_cannot_touch_a_later_student_and_is_reported(hostile_class):
    _, rows, *_ = hostile_class
    assert _grades(rows, "b_victim.ipynb") == dict.fromkeys(IDS02, "1")  # the book's worked solutions
    notes = _notes(rows, "a_survivor.ipynb")
    assert any("process(es) running after its last cell" in m and "/bin/sh" in m for m in notes), notes


def test_classmates_files_and_the_graders_command_line_are_out_of_reach(hostile_class):
    root, rows, *_ = hostile_class
    notes = _notes(rows, "c_reader.ipynb")
    assert any("raised RuntimeError: found 0 notebooks; nothing of the class" in m for m in notes), notes
    assert not [r for r in rows if r.student == "s-reader" and ("s-victim" in r.message or str(root) in r.message)]
    assert _grades(rows, "c_reader.ipynb") == dict.fromkeys(IDS02, "1")


def test_no_network_to_a_server_of_this_machine(hostile_class):
    *_, received = hostile_class
    _, rows, *_ = hostile_class
    assert received == []
    assert any("raised" in m and ("Network is unreachable" in m or "ConnectionRefusedError" in m)
               for m in _notes(rows, "d_net.ipynb")), _notes(rows, "d_net.ipynb")


def test_the_decoder_bomb_is_graded_wrong_cheaply(hostile_class):
    _, rows, *_ = hostile_class
    (row,) = [r for r in _of(rows, "e_decoder.ipynb") if r.exercise == SYMBOLIC]
    assert row.correct == "0" and "too large" in row.message, row


def test_fork_and_memory_bombs_hit_the_whole_sandbox_limits(hostile_class):
    _, rows, *_ = hostile_class
    notes = _notes(rows, "f_bombs.ipynb")
    assert any("more than 48 processes" in m for m in notes), notes
    assert any("used all the memory a notebook may use (400 MB)" in m for m in notes), notes


def test_files_in_shared_memory_and_tmp_are_reported_and_gone(hostile_class):
    _, rows, *_ = hostile_class
    notes = _notes(rows, "g_shm.ipynb")
    assert any(f"/dev/shm/{MARK}" in m and f"/tmp/{MARK}" in m and "are gone" in m for m in notes), notes
    assert _grades(rows, "g_shm.ipynb") == dict.fromkeys(IDS02, "1")


def test_case_and_space_variants_are_one_student_and_the_latest_counts(hostile_class):
    _, rows, *_ = hostile_class
    assert {r.student for r in _of(rows, "dup/new.ipynb")} == {"s2401012"}
    assert _grades(rows, "dup/new.ipynb") == dict.fromkeys(IDS02, "1")
    (old,) = _of(rows, "dup/old.ipynb")
    assert old.student == "s2401012" and old.correct == "" and "dup/new.ipynb is later and counts" in old.message
    assert any("earlier submissions not counted: dup/old.ipynb" in m for m in _notes(rows, "dup/new.ipynb"))
    right = [r for r in rows if r.student == "s2401012" and r.correct == "1"]
    assert len(right) == len(IDS02)  # not twice as many


def test_placeholder_ids_are_flagged_and_never_merged(hostile_class):
    _, rows, *_ = hostile_class
    one, two = ({r.student for r in _of(rows, f"h_placeholder{k}.ipynb")} for k in (1, 2))
    assert len(one) == len(two) == 1 and one != two
    for k in (1, 2):
        assert any("placeholder ID 'student-id'" in m for m in _notes(rows, f"h_placeholder{k}.ipynb"))
    assert _grades(rows, "h_placeholder2.ipynb") == dict.fromkeys(IDS02, "1")


def test_a_formula_id_is_defused_in_the_csv(hostile_class):
    root, rows, *_ = hostile_class
    text = (root / "gradebook.csv").read_text(encoding="utf-8")
    assert "\n'=2+3," in text and "\n=2+3" not in text
    from course.classroom.grade import read_gradebook

    assert read_gradebook(root / "gradebook.csv") == rows


def test_book_style_code_answers_are_graded_right(hostile_class):
    _, rows, *_ = hostile_class
    assert _grades(rows, "j_book.ipynb") == dict.fromkeys(IDS02, "1")


def test_the_roster_flags_unknown_ids_and_missing_students(hostile_class):
    _, rows, *_ = hostile_class
    roster = {r.student: r.message for r in rows if r.exercise == "(roster)"}
    assert "Ada Absent is on the roster, but no notebook" in roster["s-absent"]
    assert "not on the roster" in roster["s-survivor"] and "=2+3" in roster
    assert not {"s-victim", "s-book", "s2401012"} & set(roster)


def _csv(path):
    import csv

    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def test_grades_csv_has_a_row_per_student_a_column_per_chapter_and_a_total(hostile_class):
    from course.classroom.grade import points

    root, *_ = hostile_class
    table = _csv(root / "grades.csv")
    head, body = table[0], {row[0]: row for row in table[1:]}
    worth = points()
    chapters = sorted({e.split("_")[0] for e in worth})
    assert head[:2] == ["student", "name"] and [h.split(" ")[0] for h in head[2:-1]] == chapters
    assert head[-1] == f"total (of {sum(worth.values()):g})"
    col = {h.split(" ")[0]: k for k, h in enumerate(head)}
    full = f"{sum(worth[e] for e in IDS02):g}"  # the chapter's points, all earned
    assert body["s-victim"][col[CH]] == full and body["s-victim"][1] == "Vic Tim"
    assert body["s-book"][col[CH]] == body["s-book"][-1] == full  # (no points from any other chapter)
    assert all(body["s-book"][col[c]] == "0" for c in chapters if c != CH)
    assert body["s2401012"][col[CH]] == full  # the later notebook only
    assert body["s-absent"][-1] == "0" and body["'=2+3"][-1] == "0"  # (defused)
    assert len([k for k in body if k.startswith("(placeholder")]) == 2


def test_exports_follow_each_platforms_columns(hostile_class):
    root, *_ = hostile_class
    canvas, moodle, gradescope = (_csv(root / "exports" / f"{n}.csv") for n in ("canvas", "moodle", "gradescope"))
    assert canvas[0][:5] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]
    assert canvas[0][5].startswith("Jacobians ch") and canvas[1][0].strip() == "Points Possible"
    victim = next(r for r in canvas if r[2] == "s-victim")
    assert victim[0] == "Vic Tim" and victim[canvas[0].index(f"Jacobians {CH}")] == f"{len(IDS02)}"
    assert moodle[0][:2] == ["ID number", "Full name"] and "Total" not in moodle[0]
    assert gradescope[0][:3] == ["Name", "SID", "Email"] and gradescope[0][-1] == "Total Score"
    for table in (canvas, moodle, gradescope):
        assert not [r for r in table if any(c.startswith("(placeholder") for c in r)]
        assert all(len(r) == len(table[0]) for r in table)


def test_the_class_page_counts_tried_right_and_names_mistakes(hostile_class):
    root, rows, *_ = hostile_class
    page = (root / "class.html").read_text(encoding="utf-8")
    assert f"<td><code>{IDS02[0]}</code></td>" in page and "http" not in page.replace('lang="en"', "")
    import re

    tried, right = map(int, re.search(f"<code>{CODE}</code></td><td class=\"n\">(\\d+)</td><td class=\"n\">(\\d+)",
                                      page).groups())
    counted = [r for r in rows if r.exercise == CODE and r.correct in ("0", "1")]
    assert right == len({r.student for r in counted if r.correct == "1"})
    assert tried == len({r.student for r in counted if not r.message.startswith("not attempted")})


def test_zz_regrading_one_student_replaces_only_their_rows(hostile_class):
    # (named to run last: it rewrites the gradebook of the class above)
    from course.classroom.grade import ROSTER, grade_class, read_gradebook

    root, rows, *_ = hostile_class
    roster = root.parent / "roster.csv"
    again = grade_class(root, workers=2, roster=roster, student=" S2401012",
                        limits=Limits(cell_timeout=60, notebook_timeout=200, memory=400 << 20, processes=48))
    assert read_gradebook(root / "gradebook.csv") == again
    others = [r for r in rows if r.student != "s2401012" and r.exercise != ROSTER]
    assert [r for r in again if r.student != "s2401012" and r.exercise != ROSTER] == others
    mine = sorted((r.notebook, r.exercise, r.correct) for r in rows if r.student == "s2401012")
    assert sorted((r.notebook, r.exercise, r.correct) for r in again if r.student == "s2401012") == mine
    assert {r.student for r in again if r.exercise == ROSTER} == {r.student for r in rows if r.exercise == ROSTER}
