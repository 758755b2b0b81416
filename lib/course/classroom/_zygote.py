"""The warm worker of ``make grade``: Python with the course imported once, forking one child per sandbox.

Started by :class:`course.classroom.sandbox._Zygote` (as the grader's user, outside every sandbox, with the
sandbox's environment and no path of the class in its memory), it imports what every notebook imports
(numpy, sympy, the course, IPython's shell) and then waits on a socket. For each job it forks a child that

1. joins the whole-sandbox cgroup of the job and takes its resource limits;
2. enters a sandbox that **bubblewrap has already made** for the job (:func:`enter`): the network, IPC,
   UTS, cgroup, PID and mount namespaces of the sandbox's first program, its root folder, then the uid of
   the sandbox (supplementary groups cleared; every capability of the grader gone), then the sandbox's
   user namespace, whose capabilities it drops at once (bounding set, ambient set, ``no_new_privs``,
   ``capset`` to nothing). This is what ``nsenter --all --root --setuid`` does; bwrap's own
   ``--userns``/``--pidns`` options join namespaces the same way;
3. forks again (a PID namespace takes effect for children), and that grandchild, in a session of its own,
   runs the job's entry (:mod:`~course.classroom._cells` or :mod:`~course.classroom._callee`) with the
   pipes the grader sent. The child waits for it and writes its exit status to the grader.

The zygote never runs student code and never reads a submission; its children only do so after step 2.
"""

from __future__ import annotations

import ctypes
import json
import os
import resource
import signal
import socket
import struct
import sys
from typing import Any

_libc = ctypes.CDLL(None, use_errno=True)

#: Namespaces joined before the uid changes (as the grader's root), in this order; the user namespace last.
_NAMESPACES = (("ipc", 0x08000000), ("uts", 0x04000000), ("net", 0x40000000), ("cgroup", 0x02000000),
               ("pid", 0x20000000), ("mnt", 0x00020000))
_CLONE_NEWUSER = 0x10000000
_PR_SET_PDEATHSIG, _PR_CAPBSET_DROP, _PR_SET_NO_NEW_PRIVS, _PR_CAP_AMBIENT = 1, 24, 38, 47
_PR_CAP_AMBIENT_CLEAR_ALL = 4
_LINUX_CAPABILITY_VERSION_3 = 0x20080522


def _ok(rc: int, what: str) -> None:
    if rc != 0:
        err = ctypes.get_errno()
        raise OSError(err, f"{what}: {os.strerror(err)}")


def enter(target: int, uid: int) -> None:
    """Enter the sandbox whose first program has PID ``target`` (outside), as ``uid``, with no capability.

    Runs as root in a single-threaded process (a fork). Afterwards the process sees the sandbox's files,
    processes and network only, is ``uid`` outside and inside, and can never gain a privilege again."""
    fds = {name: os.open(f"/proc/{target}/ns/{name}", os.O_RDONLY | os.O_CLOEXEC) for name, _ in _NAMESPACES}
    user = os.open(f"/proc/{target}/ns/user", os.O_RDONLY | os.O_CLOEXEC)
    root = os.open(f"/proc/{target}/root", os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    try:
        for name, flag in _NAMESPACES:
            _ok(_libc.setns(fds[name], flag), f"joining the sandbox's {name} namespace")
        os.fchdir(root)  # the sandbox's root folder (bwrap pivoted it), as nsenter --root does
        os.chroot(".")
        os.setgroups([])
        os.setresgid(uid, uid, uid)
        os.setresuid(uid, uid, uid)  # from root to a uid of its own: every capability outside is gone
        if os.getresuid() != (uid, uid, uid) or os.getgroups():
            raise OSError("the sandbox's uid could not be taken")
        _ok(_libc.setns(user, _CLONE_NEWUSER), "joining the sandbox's user namespace")
    finally:
        for fd in (*fds.values(), user, root):
            os.close(fd)
    # joining a user namespace gives every capability in it: drop them all, for good
    for cap in range(64):
        if _libc.prctl(_PR_CAPBSET_DROP, cap, 0, 0, 0) != 0 and ctypes.get_errno() == 22:  # EINVAL: no such cap
            break
    _libc.prctl(_PR_CAP_AMBIENT, _PR_CAP_AMBIENT_CLEAR_ALL, 0, 0, 0)
    _ok(_libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0), "setting no_new_privs")
    header = struct.pack("Ii", _LINUX_CAPABILITY_VERSION_3, 0)
    data = bytes(24)  # two (effective, permitted, inheritable) triples, all empty
    _ok(_libc.capset(ctypes.c_char_p(header), ctypes.c_char_p(data)), "dropping the capabilities")
    os.chdir("/home/student")


def _capabilities_left() -> list[str]:
    with open("/proc/self/status", encoding="ascii") as f:
        return [ln for ln in f if ln.startswith(("CapEff", "CapPrm", "CapBnd", "CapAmb")) and
                int(ln.split()[1], 16) != 0]


def _child(job: dict[str, Any], fds: list[int], sock: socket.socket) -> int:
    """In the forked child (root, outside): join the cgroup, take the limits, enter, fork the runner, wait."""
    sock.close()
    stdin, stdout, status = fds
    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
    me = str(os.getpid())
    for path in job["cgroup"]:
        with open(path, "w") as fh:
            fh.write(me)
    for name, soft, hard in job["rlimits"]:
        resource.setrlimit(getattr(resource, name), (soft, hard))
    enter(int(job["target"]), int(job["uid"]))
    pid = os.fork()
    if pid == 0:  # the sandboxed program: in the sandbox's PID namespace (and its /proc)
        try:
            if _capabilities_left():
                os._exit(72)
            os.setsid()
            _libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
            os.dup2(stdin, 0)
            os.dup2(stdout, 1)
            null = os.open("/dev/null", os.O_WRONLY)
            os.dup2(null, 2)
            os.closerange(3, 1 << 16)
            with open(".environment.json", encoding="utf-8") as f:  # (sandbox.ENV_FILE, in the scratch folder)
                env = json.load(f)
            os.environ.clear()
            os.environ.update({str(k): str(v) for k, v in env.items()})
            sys.argv = [job["entry"], *job["args"]]
            _run(job["entry"], job["args"])
            sys.stdout.flush()
            os._exit(0)
        except SystemExit as exc:
            os._exit(exc.code if isinstance(exc.code, int) else 1)
        except BaseException as exc:
            try:
                os.write(2, f"{type(exc).__name__}: {exc}"[:300].encode())
            except OSError:
                pass
            os._exit(70)
    for fd in (stdin, stdout):
        os.close(fd)
    _, code = os.waitpid(pid, 0)
    os.write(status, json.dumps({"status": code}).encode())
    return 0


def _run(entry: str, args: list[str]) -> None:
    if entry == "cells":
        from course.classroom import _cells

        _cells.main(args[0], args[1], float(args[2]))
    elif entry == "callee":
        from course.classroom import _callee

        _callee.main()
    else:
        raise ValueError(f"unknown entry {entry!r}")


def preload() -> None:
    """Import what the notebooks and the runners import, once for every sandbox of this worker."""
    import IPython.core.interactiveshell  # noqa: F401
    import numpy  # noqa: F401
    import sympy  # noqa: F401

    import course.classroom._callee
    import course.classroom._cells  # noqa: F401
    from course import exercises  # noqa: F401


def main() -> None:
    sock = socket.socket(fileno=int(sys.argv[1]))
    preload()
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # children are reaped by the kernel
    sock.sendall(b"R")  # ready
    while True:
        try:
            msg, fds, _, _ = socket.recv_fds(sock, 1 << 16, 3)
        except OSError:
            return
        if not msg:
            return
        job = json.loads(msg)
        if len(fds) != 3:
            for fd in fds:
                os.close(fd)
            continue
        pid = os.fork()
        if pid == 0:
            try:
                code = _child(job, fds, sock)
            except BaseException as exc:  # say why, on the status pipe, then die
                try:
                    os.write(fds[2], json.dumps({"error": f"{type(exc).__name__}: {exc}"[:300]}).encode())
                except OSError:
                    pass
                code = 71
            os._exit(code)
        for fd in fds:
            os.close(fd)


if __name__ == "__main__":
    main()
