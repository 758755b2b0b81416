"""Running a student's code: a separate process, an unprivileged user, a scratch folder, limits.

What a sandboxed process gets (:func:`start`):

* its own session (so the whole process group can be killed), with the scratch
  folder as working directory, ``HOME`` and ``TMPDIR``;
* when the grader runs as root, the user ``nobody`` (no supplementary groups):
  the submissions folder and the gradebook, owned by the instructor, are then
  out of its reach by file permissions;
* resource limits: CPU seconds, address space, size of a written file, no core
  files;
* an audit hook (:data:`GUARD`, run first in the kernel) that refuses to open a
  file for writing outside the scratch folder, to delete, rename or create
  anything there, or to start a program, and notes each attempt in
  ``.sandbox_events`` so the gradebook can say so. The hook is a reporter; the
  user and the permissions are the barrier (a hook can be dodged with ctypes).

The kernel has the network (the course needs none; a container would remove it).

>>> Limits().cell_timeout
30.0
"""

from __future__ import annotations

import json
import os
import pwd
import resource
import select
import signal
import subprocess
import sys
import sysconfig
import tempfile
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

__all__ = ["GUARD", "MARKER", "Limits", "SandboxedFunction", "kill_tree", "make_scratch", "sandbox_ids",
           "sandbox_python", "start", "warning"]

#: Start of every message of the audit hook (the grader finds attempts by it).
MARKER = "[grading sandbox]"

#: Environment variable holding a unique token per sandboxed process tree (to find strays after a run).
RUN_ENV = "JACOBIANS_SANDBOX_RUN"

#: Name of the file, in the scratch folder, where the audit hook notes refused operations.
EVENTS = ".sandbox_events"

#: The code the grader runs first in a student's kernel: the audit hook (see the module docstring).
GUARD = r'''
def _jacobians_sandbox_guard():
    import os, sys
    root = os.path.realpath(os.getcwd())
    log = os.open(os.path.join(root, ".sandbox_events"), os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
    allowed = (root + os.sep, "/dev/null", "/dev/shm/")
    write_flags = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC
    paths_of = {"os.remove": 1, "os.rmdir": 1, "os.mkdir": 1, "os.chmod": 1, "os.chown": 1, "os.truncate": 1,
                "os.utime": 1, "shutil.rmtree": 1, "os.rename": 2, "os.replace": 2, "os.link": 2,
                "os.symlink": 2, "shutil.copyfile": 2, "shutil.copytree": 2, "shutil.move": 2}
    programs = ("os.system", "os.exec", "os.posix_spawn", "os.spawn", "subprocess.Popen", "os.fork",
                "os.forkpty", "pty.spawn")

    def outside(p):
        if isinstance(p, int) or p is None:
            return False
        try:
            real = os.path.realpath(os.fsdecode(p))
        except Exception:
            return True
        return not (real + os.sep).startswith(allowed[0]) and not real.startswith(allowed[1:])

    def refuse(what, path):
        note = "%s %s is not allowed: %s" % ("[grading sandbox]", what, path)
        try:
            os.write(log, (note.replace("\n", " ") + "\n").encode("utf-8", "replace"))
        except OSError:
            pass
        raise PermissionError(note)

    def hook(event, args):
        if event == "open":
            path, mode, flags = (tuple(args) + (None, None, None))[:3]
            writing = (isinstance(flags, int) and flags & write_flags) or (
                isinstance(mode, str) and any(c in mode for c in "wax+"))
            if writing and outside(path):
                refuse("writing outside the scratch folder", os.fsdecode(path))
        elif event in paths_of:
            for p in tuple(args)[:paths_of[event]]:
                if outside(p):
                    refuse("changing files outside the scratch folder (" + event + ")", p)
        elif event in programs or event.startswith("os.exec") or event.startswith("os.spawn"):
            refuse("starting a program (" + event + ")", str(tuple(args)[:1])[:200])

    sys.addaudithook(hook)


_jacobians_sandbox_guard()
del _jacobians_sandbox_guard
'''


@dataclass(frozen=True)
class Limits:
    """Time and size limits of a sandboxed run (seconds, bytes)."""

    cell_timeout: float = 30.0
    notebook_timeout: float = 300.0
    memory: int = 6 << 30
    file_size: int = 64 << 20


def sandbox_ids() -> tuple[int, int] | None:
    """``(uid, gid)`` the student's code runs as: ``nobody`` when the grader is root and ``nobody`` can run
    Python with the course (see :func:`sandbox_python`), else None (the grader's own user)."""
    return _sandbox()[1]


def sandbox_python() -> list[str]:
    """The interpreter of sandboxed processes, and the folders it needs on ``PYTHONPATH``.

    As root, the grader's own interpreter when ``nobody`` can run it; otherwise
    (an interpreter under a private home, as pyenv puts it) the interpreter
    named by ``JACOBIANS_SANDBOX_PYTHON`` or the system's ``/usr/bin/pythonX.Y``
    of the same version, given the grader's ``site-packages``. If none works for
    ``nobody``, the student's code runs as the grader's user, and
    :func:`warning` says so.
    """
    return _sandbox()[0]


def warning() -> str | None:
    """Why the sandbox could not drop to an unprivileged user (None when it could, or need not)."""
    return _sandbox()[2]


def _nobody() -> tuple[int, int] | None:
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return None
    try:
        pw = pwd.getpwnam("nobody")
    except KeyError:  # pragma: no cover - every Debian has nobody
        return None
    return pw.pw_uid, pw.pw_gid


@cache
def _sandbox() -> tuple[list[str], tuple[int, int] | None, str | None]:
    ids = _nobody()
    if ids is None:
        return [sys.executable, _lib_dir()], None, None
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = sysconfig.get_paths()["purelib"]
    candidates = [[sys.executable, _lib_dir()]]
    named = os.environ.get("JACOBIANS_SANDBOX_PYTHON")
    for exe in ([named] if named else []) + [f"/usr/bin/{version}", f"/usr/local/bin/{version}"]:
        if exe and os.path.exists(exe):
            candidates.append([exe, _lib_dir(), site])
    for cand in candidates:
        env = {"PATH": "/usr/bin:/bin", "PYTHONPATH": os.pathsep.join(cand[1:]), "HOME": "/",
               "PYTHONDONTWRITEBYTECODE": "1"}
        try:
            ok = subprocess.run([cand[0], "-c", "import nbclient, ipykernel, numpy, course.classroom.answers"],
                                env=env, cwd="/", user=ids[0], group=ids[1], extra_groups=[], timeout=120,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0
        except (OSError, subprocess.SubprocessError):
            ok = False
        if ok:
            return cand, ids, None
    return ([sys.executable, _lib_dir()], None,
            "the user nobody cannot run Python with the course here (set JACOBIANS_SANDBOX_PYTHON); "
            "the students' code runs as the grader's own user, guarded only by the audit hook and the hashes")


def make_scratch(parent: Path) -> Path:
    """A new empty folder under ``parent`` owned by the sandbox user, readable by nobody else."""
    path = Path(tempfile.mkdtemp(prefix="nb-", dir=parent))
    ids = sandbox_ids()
    (path / "tmp").mkdir()
    if ids:
        for p in (path, path / "tmp"):
            os.chown(p, *ids)
    path.chmod(0o700)
    return path


def _lib_dir() -> str:
    return str(Path(__file__).resolve().parent.parent.parent)  # the folder holding course/ and jacobians/


#: The run token of each started process, by pid (the process may be gone when its strays are looked for).
_TOKENS: dict[int, str] = {}


def _environment(scratch: Path, extra: dict[str, str]) -> dict[str, str]:
    python = sandbox_python()
    bin_dir = os.path.dirname(python[0])
    env = {
        "PATH": bin_dir + os.pathsep + "/usr/local/bin:/usr/bin:/bin",
        "HOME": str(scratch), "TMPDIR": str(scratch / "tmp"), "IPYTHONDIR": str(scratch / ".ipython"),
        "MPLCONFIGDIR": str(scratch / ".matplotlib"), "JUPYTER_RUNTIME_DIR": str(scratch / ".jupyter"),
        "JUPYTER_CONFIG_DIR": str(scratch / ".jupyter"), "XDG_CACHE_HOME": str(scratch / ".cache"),
        "PYTHONPATH": os.pathsep.join(python[1:]), "PYTHONDONTWRITEBYTECODE": "1",
        "PYDEVD_DISABLE_FILE_VALIDATION": "1",
        "MPLBACKEND": "Agg", "LANG": "C.UTF-8", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
        "MKL_NUM_THREADS": "1", RUN_ENV: uuid.uuid4().hex,
    }
    env.update(extra)
    return env


def _limiter(limits: Limits, cpu_seconds: float) -> Callable[[], None]:
    def apply() -> None:  # runs in the child before exec
        cpu = int(cpu_seconds) + 5
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
        resource.setrlimit(resource.RLIMIT_AS, (limits.memory, limits.memory))
        resource.setrlimit(resource.RLIMIT_FSIZE, (limits.file_size, limits.file_size))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def start(argv: list[str], scratch: Path, limits: Limits, *, cpu_seconds: float, env: dict[str, str] | None = None,
          pipes: bool = False) -> subprocess.Popen[bytes]:
    """Start ``argv`` sandboxed in ``scratch`` (see the module docstring); stdout/stdin piped if ``pipes``."""
    ids = sandbox_ids()
    kwargs: dict[str, Any] = {}
    if ids:
        kwargs.update(user=ids[0], group=ids[1], extra_groups=[])
    environment = _environment(scratch, env or {})
    proc = subprocess.Popen(
        argv, cwd=scratch, env=environment, start_new_session=True,
        preexec_fn=_limiter(limits, cpu_seconds), close_fds=True,
        stdin=subprocess.PIPE if pipes else subprocess.DEVNULL,
        stdout=subprocess.PIPE if pipes else subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kwargs)
    _TOKENS[proc.pid] = environment[RUN_ENV]
    return proc


def kill_tree(proc: subprocess.Popen[bytes]) -> None:
    """Kill ``proc``'s process group, then any process still carrying its run token (one that left the group)."""
    token = _TOKENS.pop(proc.pid, None)
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover
        pass
    if token:
        _kill_marked(token)


def _kill_marked(token: str) -> None:
    needle = f"{RUN_ENV}={token}".encode()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if needle in (entry / "environ").read_bytes().split(b"\0"):
                os.kill(int(entry.name), signal.SIGKILL)
        except (OSError, ValueError):
            continue


class SandboxedFunction:
    """A student's function answer, called in a sandboxed process; the grader only sees data.

    Calling it sends the arguments as :mod:`~course.classroom.answers` data and
    returns the decoded result, or raises an exception of the same name as the
    one the student's code raised. After a timeout or a broken pipe the process
    is killed and later calls raise ``RuntimeError``.
    """

    def __init__(self, answer: Any, scratch: Path, limits: Limits, *, call_timeout: float = 10.0) -> None:
        from .answers import encode  # noqa: F401  (imported for its side effect: numpy loaded once)

        self.__name__ = answer.name
        self.answer = answer
        self.call_timeout = call_timeout
        self._proc: subprocess.Popen[bytes] | None = start(
            [sandbox_python()[0], "-m", "course.classroom._callee"], scratch, limits,
            cpu_seconds=limits.notebook_timeout, pipes=True)
        spec = {"name": answer.name, "source": answer.source, "helpers": answer.helpers, "imports": answer.imports,
                "constants": answer.constants, "library": answer.library}
        self.error: str | None = None
        reply = self._ask(spec, timeout=60.0)
        if "error" in reply:
            self.error = str(reply["error"])[:300]

    def _ask(self, message: dict[str, Any], timeout: float) -> dict[str, Any]:
        proc = self._proc
        if proc is None or proc.stdin is None or proc.stdout is None:
            raise RuntimeError("the sandbox of this function was stopped after an earlier failure")
        busy = True
        try:
            proc.stdin.write(json.dumps(message).encode() + b"\n")
            proc.stdin.flush()
            deadline = time.monotonic() + timeout
            buf = b""
            while not buf.endswith(b"\n"):
                left = deadline - time.monotonic()
                ready = select.select([proc.stdout], [], [], max(left, 0))[0] if left > 0 else []
                if not ready:
                    raise TimeoutError(f"your function did not finish within {timeout:g} s")
                chunk = os.read(proc.stdout.fileno(), 1 << 20)
                if not chunk:
                    raise RuntimeError("your function ended its process (it crashed or called exit)")
                buf += chunk
                if len(buf) > 64 << 20:
                    raise RuntimeError("your function returned more than 64 MB")
            busy = False
            reply = json.loads(buf)
            return reply if isinstance(reply, dict) else {"error": "malformed reply"}
        finally:
            if busy:  # interrupted (the checker's time guard, a timeout, a crash): never reuse the process
                self.close()

    def __call__(self, *args: Any) -> Any:
        from .answers import decode, encode

        if self.error:
            raise _named_error("NameError" if "NameError" in self.error else "RuntimeError", self.error)
        reply = self._ask({"args": [encode(a) for a in args]}, timeout=self.call_timeout)
        if "raised" in reply:
            name, text = reply["raised"]
            raise _named_error(str(name), str(text))
        if "error" in reply:
            raise RuntimeError(str(reply["error"])[:300])
        return decode(reply.get("ok"))

    def close(self) -> None:
        if self._proc is not None:
            kill_tree(self._proc)
            for stream in (self._proc.stdin, self._proc.stdout):
                if stream is not None:
                    stream.close()
            self._proc = None


def _named_error(name: str, text: str) -> Exception:
    safe = "".join(c for c in name if c.isalnum() or c == "_")[:60] or "Exception"
    cls: type[Exception] = type(safe, (Exception,), {})
    return cls(text[:300])
