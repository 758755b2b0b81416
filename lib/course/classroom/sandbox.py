"""Running a student's code: a bubblewrap sandbox per notebook, its own uid, whole-sandbox limits.

Each sandbox (:func:`start`) is made with Debian's ``bubblewrap`` (``bwrap``, the
sandbox Flatpak uses; chosen because it is small, packaged everywhere and needs
no daemon). When the grader runs as root, a sandbox gets:

* **a uid of its own**: the grader takes a free uid from a private range
  (:data:`UID_BASE`, held by a lock file for the sandbox's lifetime), switches
  to it with ``setpriv --reuid --regid --clear-groups`` and only then starts
  ``bwrap``, which makes the user namespace. That uid owns nothing on the
  machine but the sandbox's scratch folder;
* **namespaces** (``--unshare-all``): no network (only its own loopback), its
  own PID namespace (``--die-with-parent``: when the sandbox's first process
  ends, the kernel kills every process in it, however it was started), its own
  IPC and hostname; no further user namespaces (``--disable-userns``), a new
  session (``--new-session``);
* **a filesystem of its own**: an empty root with read-only binds of ``/usr``,
  the Python installation, the virtual environment and the course's ``lib``
  folder (bound first, in a mount namespace of the sandbox's own, on the empty
  folders of :data:`VIEWS`, so that the sandbox's uid needs no right on the
  folders above them, such as a private ``/root``), a fresh ``/proc`` of
  its own PID namespace, a minimal ``/dev``, a size-limited ``tmpfs`` at
  ``/tmp`` and the scratch folder at ``/home/student`` (working directory,
  ``HOME``); everything else read-only. The submissions, the gradebook, other scratch folders and the
  grader's processes are not in it. Its command line goes through a pipe
  (``--args``): the sandbox's own ``/proc`` shows only ``bwrap --args N -- <the program run>``;
* **limits for the whole sandbox** through a cgroup of its own (v1 ``memory``,
  ``pids`` and ``freezer`` hierarchies, or the v2 unified hierarchy with the
  ``memory`` and ``pids`` controllers): memory (swap included where the kernel
  counts it, tmpfs pages included) and the number of processes and threads.
  At the end the cgroup is frozen, every process in it killed and the cgroup
  removed. Resource limits are the second line: CPU seconds, address space per
  process, processes of its uid (the uid is the sandbox's alone, so this is a
  whole-sandbox count too), size of a written file, no core files;
* an **audit hook** (:data:`GUARD`, run first in every sandboxed Python) that
  reports attempts to write outside the scratch folder or to start programs
  (``.sandbox_events``), so that the gradebook can say what a notebook tried.
  The hook is a reporter; the barrier is the sandbox.

**Warm sandboxes** (:func:`start_warm`, what ``make grade`` uses for notebooks and function answers): the
sandbox above is made exactly as for :func:`start`, around a placeholder program (:data:`HOLDER`); instead of
a fresh Python, a fork of this grading process's warm worker (:mod:`~course.classroom._zygote`, which
imported numpy, sympy, the course and IPython once) joins its cgroup and limits, enters its namespaces and
root, takes its uid, enters its user namespace and drops every capability, and runs the program there. Every
property above holds per notebook: bubblewrap made the sandbox, the program is the sandbox's uid with no
capability and ``no_new_privs``, sees only the sandbox's processes, files and (no) network, and dies with
the sandbox's cgroup.

:func:`isolation` says whether all this is possible here. If it is not (no
``bwrap``, not root, no cgroup hierarchy the grader may write, user namespaces
disabled), ``make grade`` refuses to grade and prints why; ``UNSAFE=1`` grades
anyway, as the grader's own user with only the resource limits and the hook,
and every gradebook row then says so.

>>> Limits().cell_timeout
30.0
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import resource
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

__all__ = ["GUARD", "MARKER", "HOME", "Isolation", "Limits", "SandboxedFunction", "WarmProcess", "isolation",
           "kill_tree", "make_scratch", "probe_isolation", "start", "start_warm", "stop_warm", "unsafe_allowed"]

#: Start of every message of the audit hook (the grader finds attempts by it).
MARKER = "[grading sandbox]"

#: Name of the file, in the scratch folder, where the audit hook notes refused operations.
EVENTS = ".sandbox_events"

#: Where the scratch folder is inside a sandbox (its working directory and HOME).
HOME = "/home/student"

#: First uid of the range the sandboxes run as (uids nobody else on a Debian machine uses); :data:`UID_COUNT` uids.
UID_BASE = 2_100_000_000
UID_COUNT = 10_000

#: Name of the cgroup folder (under each hierarchy) holding one cgroup per running sandbox.
CGROUP_PARENT = "jacobians-grade"

#: Environment variable that allows grading without isolation (``make grade UNSAFE=1`` sets it).
UNSAFE_ENV = "JACOBIANS_GRADE_UNSAFE"

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
    """Time and size limits of a sandboxed run (seconds, bytes; ``memory`` and ``processes`` for the whole
    sandbox, the others per process)."""

    cell_timeout: float = 30.0
    notebook_timeout: float = 300.0
    memory: int = 2 << 30
    processes: int = 256
    address_space: int = 6 << 30
    file_size: int = 64 << 20
    tmp_size: int = 256 << 20


@dataclass(frozen=True)
class Isolation:
    """Whether sandboxes can be made here (``ok``), why not (``reason``), and the cgroup version used."""

    ok: bool
    reason: str | None = None
    cgroup: str | None = None
    #: the machine has all a sandbox needs (root, bwrap, setpriv, a cgroup) and the test sandbox still failed:
    #: a fault of the grader on this machine, never a reason to skip its tests
    broken: bool = False


def unsafe_allowed() -> bool:
    """Whether the instructor asked to grade without isolation (``UNSAFE=1``)."""
    return os.environ.get(UNSAFE_ENV, "") not in ("", "0")


@cache
def isolation() -> Isolation:
    """Whether this machine can make the sandboxes of the module docstring; checked once by making one."""
    return probe_isolation()


def probe_isolation() -> Isolation:
    """:func:`isolation`, checked now (not cached)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return Isolation(False, "the grader is not root, so it cannot give each notebook a uid and a cgroup of "
                                "its own (run it as root: sudo make grade ...)")
    for tool, package in (("bwrap", "bubblewrap"), ("setpriv", "util-linux")):
        if shutil.which(tool) is None:
            return Isolation(False, f"{tool} is missing (apt-get install {package})")
    kind, why = _cgroup_kind()
    if kind is None:
        return Isolation(False, why)
    probe = Isolation(True, None, kind)
    parent = Path(tempfile.mkdtemp(prefix="jacobians-probe-"))
    try:
        parent.chmod(0o711)
        scratch = make_scratch(parent, isolate=True)
        proc = _spawn([sys.executable, "-P", "-c", "import os; "
                       f"assert not os.path.exists('/sys/fs/cgroup') and os.getuid() >= {UID_BASE}; "
                       "import nbclient, ipykernel, numpy, course.classroom.answer_data"],
                      scratch, Limits(), cpu_seconds=120, env={}, pipes=False, how=probe, stderr=True)
        try:
            _, err = proc.communicate(timeout=120)
            rc = proc.returncode
        except subprocess.TimeoutExpired:
            err, rc = b"timed out", -1
        kill_tree(proc)
        remove_scratch(scratch)
    except OSError as exc:
        return Isolation(False, f"a test sandbox could not be made ({exc})")
    finally:
        shutil.rmtree(parent, ignore_errors=True)
    if rc != 0:
        last = (err or b"").decode("utf-8", "replace").strip().splitlines()[-1:] or ["no message"]
        return Isolation(False, f"a test sandbox failed (bwrap or Python inside it: {last[0][:200]}); "
                                "are user namespaces allowed (sysctl kernel.unprivileged_userns_clone)?",
                         broken=True)
    return probe


# --------------------------------------------------------------------------- cgroups
_V1 = ("memory", "pids", "freezer")


#: Where the cgroup hierarchies are mounted.
CGROUP_ROOT = Path("/sys/fs/cgroup")


def _cgroup_kind(root: Path = CGROUP_ROOT) -> tuple[str | None, str]:
    if all(os.access(root / h, os.W_OK) and (root / h / "cgroup.procs").exists() for h in _V1):
        return "v1", ""
    if (root / "cgroup.controllers").exists():
        have = (root / "cgroup.controllers").read_text().split()
        if {"memory", "pids"} <= set(have) and os.access(root, os.W_OK):
            return "v2", ""
        return None, ("the cgroup v2 hierarchy lacks the memory or pids controller, or is not writable, so "
                      "memory and processes cannot be limited for a whole sandbox")
    return None, ("no writable cgroup hierarchy with memory and pids limits (v1 memory, pids and freezer "
                  "under /sys/fs/cgroup, or v2), so memory and processes cannot be limited for a whole sandbox")


class _Cgroup:
    """One cgroup per sandbox (in each v1 hierarchy, or one v2 folder): limits, joining, killing, removing."""

    def __init__(self, kind: str, name: str, limits: Limits, root: Path = CGROUP_ROOT) -> None:
        self.kind = kind
        if kind == "v1":
            self.dirs = {h: root / h / CGROUP_PARENT / name for h in _V1}
            for d in self.dirs.values():
                d.mkdir(parents=True, exist_ok=True)
            mem = self.dirs["memory"]
            (mem / "memory.limit_in_bytes").write_text(str(limits.memory))
            if (mem / "memory.memsw.limit_in_bytes").exists():  # no swap beyond the limit
                (mem / "memory.memsw.limit_in_bytes").write_text(str(limits.memory))
            (self.dirs["pids"] / "pids.max").write_text(str(limits.processes))
        else:
            parent = root / CGROUP_PARENT
            parent.mkdir(exist_ok=True)
            for d in (root, parent):
                (d / "cgroup.subtree_control").write_text("+memory +pids")
            d = parent / name
            d.mkdir(exist_ok=True)
            self.dirs = {"unified": d}
            (d / "memory.max").write_text(str(limits.memory))
            if (d / "memory.swap.max").exists():
                (d / "memory.swap.max").write_text("0")
            (d / "pids.max").write_text(str(limits.processes))
        self.procs = [str(d / "cgroup.procs") for d in self.dirs.values()]

    def pids(self) -> list[int]:
        d = self.dirs.get("pids") or self.dirs["unified"]
        try:
            return [int(x) for x in (d / "cgroup.procs").read_text().split()]
        except (OSError, ValueError):
            return []

    def _freeze(self, on: bool) -> None:
        try:
            if self.kind == "v1":
                (self.dirs["freezer"] / "freezer.state").write_text("FROZEN" if on else "THAWED")
            elif (self.dirs["unified"] / "cgroup.freeze").exists():
                (self.dirs["unified"] / "cgroup.freeze").write_text("1" if on else "0")
        except OSError:
            pass

    def kill(self) -> None:
        """Kill every process of the sandbox (frozen first, so none can fork while it is killed); remove it."""
        kill_file = self.dirs.get("unified", Path("/nonexistent")) / "cgroup.kill"
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            pids = self.pids()
            if not pids:
                break
            if kill_file.exists():
                kill_file.write_text("1")
            else:
                self._freeze(True)
                for pid in pids:
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
                self._freeze(False)  # killed processes die only when thawed
            time.sleep(0.01)
        for d in self.dirs.values():
            for _ in range(200):
                try:
                    d.rmdir()
                    break
                except OSError as exc:
                    if exc.errno == errno.ENOENT:
                        break
                    time.sleep(0.01)

    def memory_peak(self) -> int | None:
        d = self.dirs.get("memory") or self.dirs["unified"]
        for name in ("memory.max_usage_in_bytes", "memory.peak"):
            try:
                return int((d / name).read_text())
            except (OSError, ValueError):
                continue
        return None

    def hit_limits(self) -> list[str]:
        """What the sandbox ran into: ``"memory"`` and/or ``"processes"``."""
        out = []
        try:
            if self.kind == "v1":
                mem = self.dirs["memory"]
                control = dict(ln.split() for ln in (mem / "memory.oom_control").read_text().splitlines())
                if int(control.get("oom_kill", 0)) or int((mem / "memory.failcnt").read_text()):
                    out.append("memory")
                if int((self.dirs["pids"] / "pids.events").read_text().split()[-1]) > 0:
                    out.append("processes")
            else:
                d = self.dirs["unified"]
                events = dict(ln.split() for ln in (d / "memory.events").read_text().splitlines())
                if int(events.get("oom_kill", 0)) or int(events.get("max", 0)):
                    out.append("memory")
                if int((d / "pids.events").read_text().split()[-1]) > 0:
                    out.append("processes")
        except (OSError, ValueError, IndexError):
            pass
        return out


# --------------------------------------------------------------------------- uids and scratch folders
@dataclass
class _Scratch:
    uid: int
    lock: int  # an open, flock-ed file descriptor: the uid is this folder's while it is open


_SCRATCH: dict[str, _Scratch] = {}


def _uid_lock_dir() -> Path:
    d = Path("/run/jacobians-grade-uids") if os.access("/run", os.W_OK) else \
        Path(tempfile.gettempdir()) / "jacobians-grade-uids"
    d.mkdir(mode=0o700, exist_ok=True)
    return d


def _take_uid() -> _Scratch:
    folder = _uid_lock_dir()
    start_at = (os.getpid() * 7919 + int(time.monotonic() * 1000)) % UID_COUNT
    for k in range(UID_COUNT):
        uid = UID_BASE + (start_at + k) % UID_COUNT
        fd = os.open(folder / str(uid), os.O_CREAT | os.O_RDWR | os.O_CLOEXEC, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            continue
        return _Scratch(uid, fd)
    raise RuntimeError(f"all {UID_COUNT} sandbox uids are in use")


def make_scratch(parent: Path, *, isolate: bool | None = None) -> Path:
    """A new empty folder under ``parent`` for one sandbox: owned by a uid of its own (when isolating, by
    default when :func:`isolation` is possible), readable by nobody else. Give it back with
    :func:`remove_scratch`."""
    path = Path(tempfile.mkdtemp(prefix="nb-", dir=parent))
    (path / "tmp").mkdir()
    if isolation().ok if isolate is None else isolate:
        held = _take_uid()
        _SCRATCH[str(path)] = held
        for p in (path, path / "tmp"):
            os.chown(p, held.uid, held.uid)
    path.chmod(0o700)
    return path


def scratch_owner(scratch: Path) -> int | None:
    """The uid of ``scratch``'s sandbox (None without isolation)."""
    held = _SCRATCH.get(str(scratch))
    return held.uid if held else None


def remove_scratch(scratch: Path) -> None:
    """Delete ``scratch`` and give its uid back (after its sandboxes were killed)."""
    shutil.rmtree(scratch, ignore_errors=True)
    held = _SCRATCH.pop(str(scratch), None)
    if held:
        os.close(held.lock)


def sandbox_home(scratch: Path) -> str:
    """The scratch folder's path as the sandboxed process sees it."""
    return HOME if _SCRATCH.get(str(scratch)) else str(scratch)


def _lib_dir() -> str:
    return str(Path(__file__).resolve().parent.parent.parent)  # the folder holding course/ and jacobians/


def _environment(home: str, extra: dict[str, str]) -> dict[str, str]:
    env = {
        "PATH": os.path.dirname(sys.executable) + os.pathsep + "/usr/local/bin:/usr/bin:/bin",
        "HOME": home, "USER": "student", "LOGNAME": "student", "TMPDIR": home + "/tmp",
        "IPYTHONDIR": home + "/.ipython", "MPLCONFIGDIR": home + "/.matplotlib",
        "JUPYTER_RUNTIME_DIR": home + "/.jupyter", "JUPYTER_CONFIG_DIR": home + "/.jupyter",
        "XDG_CACHE_HOME": home + "/.cache", "PYTHONPATH": _lib_dir(), "PYTHONDONTWRITEBYTECODE": "1",
        "PYDEVD_DISABLE_FILE_VALIDATION": "1", "MPLBACKEND": "Agg", "LANG": "C.UTF-8", "OMP_NUM_THREADS": "1",
        "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
    }
    if os.environ.get(FIXTURE_ENV):  # the tests' made-up chapter: the graded notebooks must load it too
        env[FIXTURE_ENV] = "1"
    env.update(extra)
    return env


#: The variable that registers the grading tests' made-up chapter (:data:`course.exercises.fixture.ENV`), passed
#: into the sandbox when the grader has it.
FIXTURE_ENV = "COURSE_FIXTURE_CHAPTER"


def _limiter(limits: Limits, cpu_seconds: float, cgroup: _Cgroup | None, uid: int | None) -> Callable[[], None]:
    procs = cgroup.procs if cgroup else []

    def apply() -> None:  # runs in the child, as root, before exec (then setpriv, then bwrap)
        me = str(os.getpid())
        for f in procs:
            with open(f, "w") as fh:
                fh.write(me)
        cpu = int(cpu_seconds) + 5
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
        resource.setrlimit(resource.RLIMIT_AS, (limits.address_space, limits.address_space))
        resource.setrlimit(resource.RLIMIT_FSIZE, (limits.file_size, limits.file_size))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        if uid is not None:  # the uid is this sandbox's alone: a count of its processes (threads not counted;
            nproc = 2 * limits.processes  # the cgroup, which counts both, is the first barrier)
            resource.setrlimit(resource.RLIMIT_NPROC, (nproc, nproc))
    return apply


#: Empty folders where each sandbox's first process, in a mount namespace of its own, binds the folders the
#: sandbox needs (the Python installation may sit under a private home such as /root/.pyenv, which the
#: sandbox's uid cannot traverse; bwrap, started as that uid, binds them from here).
VIEWS = Path("/run/jacobians-grade-view")


def _needed() -> list[str]:
    """The folders outside ``/usr`` that the sandboxed Python needs, each once (its symlinked path too)."""
    out: list[str] = []
    for folder in (sys.base_prefix, sys.prefix, _lib_dir()):
        for path in (os.path.realpath(folder), os.path.abspath(folder)):
            if not path.startswith("/usr/") and path not in out:
                out.append(path)
    return out


def _views() -> Path:
    base = VIEWS if os.access("/run", os.W_OK) else Path(tempfile.gettempdir()) / "jacobians-grade-view"
    base.mkdir(mode=0o755, exist_ok=True)
    base.chmod(0o755)
    for k in range(len(_needed())):
        (base / str(k)).mkdir(mode=0o755, exist_ok=True)
    return base


def _binds(scratch: Path, views: Path, limits: Limits) -> list[str]:
    """bwrap's filesystem arguments (see the module docstring)."""
    args = ["--ro-bind", "/usr", "/usr"]
    for top in ("/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"):
        if os.path.islink(top):
            args += ["--symlink", os.readlink(top), top]
        elif os.path.isdir(top):
            args += ["--ro-bind", top, top]
    for f in ("/etc/ld.so.cache", "/etc/localtime", "/etc/nsswitch.conf"):
        if os.path.exists(f):
            args += ["--ro-bind", f, f]
    # /tmp before the views: a Python or a checkout that lives under /tmp (a clone in /tmp, a CI runner's
    # temp folder) is bound on top of the sandbox's own tmpfs, not hidden by it
    args += ["--proc", "/proc", "--dev", "/dev", "--size", str(limits.tmp_size), "--tmpfs", "/tmp"]
    for k, folder in enumerate(_needed()):
        args += ["--ro-bind", str(views / str(k)), folder]
    args += ["--bind", str(scratch), HOME, "--chdir", HOME, "--remount-ro", "/"]
    return args


_CLONE_NEWNS, _MS_BIND, _MS_REC, _MS_PRIVATE = 0x00020000, 4096, 16384, 1 << 18


def _mount_views(views: Path) -> Callable[[], None]:
    """In the child (root, before exec): a private mount namespace with the needed folders bound on the views."""
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    pairs = [(src.encode(), str(views / str(k)).encode()) for k, src in enumerate(_needed())]

    def apply() -> None:
        if libc.unshare(_CLONE_NEWNS) != 0 or libc.mount(b"none", b"/", None, _MS_REC | _MS_PRIVATE, None) != 0:
            raise OSError(ctypes.get_errno(), "unshare of the mount namespace failed")
        for src, dst in pairs:
            if libc.mount(src, dst, None, _MS_BIND | _MS_REC, None) != 0:
                raise OSError(ctypes.get_errno(), f"bind of {src.decode()} failed")
    return apply


@dataclass
class _Running:
    cgroup: _Cgroup | None


_RUNNING: dict[int, _Running] = {}


def start(argv: list[str], scratch: Path, limits: Limits, *, cpu_seconds: float, env: dict[str, str] | None = None,
          pipes: bool = False) -> subprocess.Popen[bytes]:
    """Start ``argv`` sandboxed in ``scratch`` (see the module docstring); stdout/stdin piped if ``pipes``.

    Raises RuntimeError when isolation is impossible and ``UNSAFE`` was not given."""
    how = isolation()
    if not how.ok and not unsafe_allowed():
        raise RuntimeError(f"cannot grade safely here: {how.reason}")
    return _spawn(argv, scratch, limits, cpu_seconds=cpu_seconds, env=env or {}, pipes=pipes,
                  how=how if how.ok else None)


def _spawn(argv: list[str], scratch: Path, limits: Limits, *, cpu_seconds: float, env: dict[str, str],
           pipes: bool, how: Isolation | None, stderr: bool = False) -> subprocess.Popen[bytes]:
    held = _SCRATCH.get(str(scratch))
    streams: dict[str, Any] = {
        "stdin": subprocess.PIPE if pipes else subprocess.DEVNULL,
        "stdout": subprocess.PIPE if pipes else subprocess.DEVNULL,
        "stderr": subprocess.PIPE if stderr else subprocess.DEVNULL}
    if how is None or held is None:  # UNSAFE: the grader's own user, resource limits, the hook
        proc = subprocess.Popen(argv, cwd=scratch, env=_environment(str(scratch), env), start_new_session=True,
                                preexec_fn=_limiter(limits, cpu_seconds, None, None), close_fds=True, **streams)
        _RUNNING[proc.pid] = _Running(None)
        return proc
    assert how.cgroup is not None
    views = _views()
    cgroup = _Cgroup(how.cgroup, str(held.uid), limits)
    limit, mount = _limiter(limits, cpu_seconds, cgroup, held.uid), _mount_views(views)

    def prepare() -> None:
        limit()
        mount()

    r = -1
    try:
        bargs = ["--unshare-all", "--unshare-user", "--disable-userns", "--die-with-parent", "--new-session",
                 "--cap-drop", "ALL", "--hostname", "sandbox", *_binds(scratch, views, limits)]
        r, w = os.pipe()
        with os.fdopen(w, "wb") as fh:  # (a pipe holds 64 KB; the arguments are a few hundred bytes)
            fh.write(b"".join(a.encode() + b"\0" for a in bargs))
        cmd = ["setpriv", f"--reuid={held.uid}", f"--regid={held.uid}", "--clear-groups", "--",
               "bwrap", "--args", str(r), "--", *argv]
        proc = subprocess.Popen(cmd, cwd="/", env=_environment(HOME, env), start_new_session=True,
                                preexec_fn=prepare, close_fds=True, pass_fds=(r,), **streams)
    except BaseException:
        cgroup.kill()
        raise
    finally:
        if r >= 0:
            os.close(r)
    _RUNNING[proc.pid] = _Running(cgroup)
    return proc


#: Name of the file, in the scratch folder, that gives a warm sandbox's program its environment.
ENV_FILE = ".environment.json"

#: The program that holds a warm sandbox open (process 2 of its PID namespace): it says it runs, then sleeps
#: until the sandbox is killed.
HOLDER = ["/bin/sh", "-c", "echo ready; exec sleep 100000"]


class _Zygote:
    """This grader process's warm worker (:mod:`~course.classroom._zygote`), started on first use."""

    def __init__(self) -> None:
        import socket

        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self.proc = subprocess.Popen(
            [sys.executable, "-P", "-m", "course.classroom._zygote", str(theirs.fileno())], cwd="/",
            env=_environment(HOME, {"HOME": "/nonexistent", "IPYTHONDIR": "/nonexistent",
                                    "MPLCONFIGDIR": "/nonexistent"}),
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, pass_fds=(theirs.fileno(),), close_fds=True,
            preexec_fn=_die_with_parent)
        theirs.close()
        self.sock = ours
        ours.settimeout(300)
        if ours.recv(1) != b"R":
            raise RuntimeError("the warm worker of make grade did not start")
        ours.settimeout(None)
        self.owner = os.getpid()

    def send(self, job: dict[str, Any], fds: list[int]) -> None:
        import socket

        socket.send_fds(self.sock, [json.dumps(job).encode()], fds)

    def close(self) -> None:
        self.sock.close()
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


_ZYGOTE: dict[int, _Zygote] = {}


def _die_with_parent() -> None:
    import ctypes

    ctypes.CDLL(None).prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG


def _zygote() -> _Zygote:
    z = _ZYGOTE.get(os.getpid())  # (a forked grader process starts its own)
    if z is None or z.proc.poll() is not None:
        z = _ZYGOTE[os.getpid()] = _Zygote()
    return z


def stop_warm() -> None:
    """Stop this process's warm worker, if it started one."""
    z = _ZYGOTE.pop(os.getpid(), None)
    if z is not None:
        z.close()


class WarmProcess:
    """A program of the warm worker running in a bubblewrap sandbox of its own (:func:`start_warm`).

    ``stdin``/``stdout`` are pipes to it when asked for; :meth:`wait` waits for it to end (not for what it
    left running: :func:`kill_tree` ends the whole sandbox)."""

    def __init__(self, box: subprocess.Popen[bytes], status: int, stdin: Any, stdout: Any) -> None:
        self.box = box
        self.pid = box.pid
        self.stdin, self.stdout = stdin, stdout
        self._status = status
        self.returncode: int | None = None
        self.error: str | None = None

    def wait(self, timeout: float | None = None) -> int:
        if self.returncode is None:
            ready = select.select([self._status], [], [], timeout)[0]
            if not ready:
                raise subprocess.TimeoutExpired("sandboxed program", timeout or 0)
            data = os.read(self._status, 4096)
            try:
                reply = json.loads(data) if data else {}
            except ValueError:
                reply = {}
            self.error = reply.get("error")
            status = reply.get("status")
            self.returncode = (os.waitstatus_to_exitcode(status) if isinstance(status, int) else -9)
        return self.returncode

    def communicate(self, timeout: float | None = None) -> tuple[bytes, bytes]:
        out = self.stdout.read() if self.stdout is not None else b""
        self.wait(timeout)
        return out, b""

    def close(self) -> None:
        for stream in (self.stdin, self.stdout):
            if stream is not None:
                stream.close()
        try:
            os.close(self._status)
        except OSError:
            pass
        self._status = -1


def start_warm(entry: str, args: list[str], scratch: Path, limits: Limits, *, cpu_seconds: float,
               env: dict[str, str] | None = None, pipes: bool = False) -> WarmProcess | subprocess.Popen[bytes]:
    """Run ``entry`` (``"cells"``: :mod:`~course.classroom._cells`; ``"callee"``: :mod:`~course.classroom._callee`)
    with ``args`` in a new sandbox, forked from the warm worker instead of started afresh.

    The sandbox is the one :func:`start` makes (bubblewrap, a uid of its own, a cgroup of its own), holding
    :data:`HOLDER`; the warm worker's child enters it (:func:`course.classroom._zygote.enter`) and runs the
    entry there. Without isolation (``UNSAFE=1``) the entry is started afresh as :func:`start` does."""
    how = isolation()
    module = {"cells": "course.classroom._cells", "callee": "course.classroom._callee"}[entry]
    held = _SCRATCH.get(str(scratch))
    if not how.ok or held is None:
        return start([sys.executable, "-P", "-m", module, *args], scratch, limits, cpu_seconds=cpu_seconds,
                     env=env, pipes=pipes)
    box = _spawn(HOLDER, scratch, limits, cpu_seconds=cpu_seconds, env={}, pipes=True, how=how)
    try:
        assert box.stdout is not None
        if not select.select([box.stdout], [], [], 60)[0] or box.stdout.readline() != b"ready\n":
            raise RuntimeError("the sandbox did not start (bwrap)")
        cgroup = _RUNNING[box.pid].cgroup
        assert cgroup is not None
        target = _holder_pid(cgroup.pids())
        if target is None:
            raise RuntimeError("the sandbox's first program was not found in its cgroup")
        if pipes:
            in_r, in_w = os.pipe()  # the grader writes, the program reads
            out_r, out_w = os.pipe()  # the program writes, the grader reads
            mine, theirs = [in_w, out_r], [in_r, out_w]
        else:
            mine, theirs = [], [os.open(os.devnull, os.O_RDONLY), os.open(os.devnull, os.O_WRONLY)]
        status_r, status_w = os.pipe()
        cpu = int(cpu_seconds) + 5
        rlimits = [("RLIMIT_CPU", cpu, cpu + 5), ("RLIMIT_AS", limits.address_space, limits.address_space),
                   ("RLIMIT_FSIZE", limits.file_size, limits.file_size), ("RLIMIT_CORE", 0, 0),
                   ("RLIMIT_NPROC", 2 * limits.processes, 2 * limits.processes)]
        # the environment goes through the scratch folder, so that nothing of a student ever passes through
        # the warm worker's memory (which every later fork inherits): the job holds numbers and paths only
        envfile = scratch / ENV_FILE
        envfile.write_text(json.dumps(_environment(HOME, env or {})), encoding="utf-8")
        os.chown(envfile, held.uid, held.uid)
        job = {"entry": entry, "args": args, "uid": held.uid, "target": target, "cgroup": cgroup.procs,
               "rlimits": rlimits}
        try:
            _zygote().send(job, [theirs[0], theirs[1], status_w])
        finally:
            for fd in (*theirs, status_w):
                os.close(fd)
        stdin = os.fdopen(mine[0], "wb") if pipes else None
        stdout = os.fdopen(mine[1], "rb", buffering=0) if pipes else None
    except BaseException:
        kill_tree(box)
        raise
    return WarmProcess(box, status_r, stdin, stdout)


def _holder_pid(pids: list[int]) -> int | None:
    """Of the processes of a sandbox's cgroup, the one that is process 2 of the sandbox's PID namespace."""
    for pid in pids:
        try:
            with open(f"/proc/{pid}/status", encoding="ascii") as f:
                for line in f:
                    if line.startswith("NSpid:"):
                        parts = line.split()
                        if len(parts) >= 3 and parts[-1] == "2":
                            return pid
        except OSError:
            continue
    return None


def limits_hit(proc: subprocess.Popen[bytes] | WarmProcess) -> list[str]:
    """The whole-sandbox limits ``proc``'s sandbox ran into (call before :func:`kill_tree`)."""
    run = _RUNNING.get(proc.pid)
    return run.cgroup.hit_limits() if run and run.cgroup else []


def kill_tree(proc: subprocess.Popen[bytes] | WarmProcess) -> None:
    """Kill every process of ``proc``'s sandbox (its cgroup; without isolation its process group) and wait."""
    if isinstance(proc, WarmProcess):
        kill_tree(proc.box)
        for stream in (proc.box.stdin, proc.box.stdout):
            if stream is not None:
                stream.close()
        proc.close()
        return
    run = _RUNNING.pop(proc.pid, None)
    if run and run.cgroup:
        run.cgroup.kill()
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover
        pass


class SandboxedFunction:
    """A student's function answer, called in a sandboxed process; the grader only sees data.

    Calling it sends the arguments as :mod:`~course.classroom.answer_data` data and
    returns the decoded result, or raises an exception of the same name as the
    one the student's code raised. After a timeout or a broken pipe the process
    is killed and later calls raise ``RuntimeError``.
    """

    def __init__(self, answer: Any, scratch: Path, limits: Limits, *, call_timeout: float = 10.0,
                 seed: str | int | None = None, warm: bool = True) -> None:
        from .answer_data import encode  # noqa: F401  (imported for its side effect: numpy loaded once)

        self.__name__ = answer.name
        self.answer = answer
        self.call_timeout = call_timeout
        self._proc: subprocess.Popen[bytes] | WarmProcess | None = start_warm(
            "callee", [], scratch, limits, cpu_seconds=limits.notebook_timeout, pipes=True) if warm else start(
            [sys.executable, "-P", "-m", "course.classroom._callee"], scratch, limits,
            cpu_seconds=limits.notebook_timeout, pipes=True)
        spec = {"name": answer.name, "source": answer.source, "helpers": answer.helpers, "imports": answer.imports,
                "constants": answer.constants, "library": answer.library, "seed": seed}
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
        from .answer_data import decode, encode

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
