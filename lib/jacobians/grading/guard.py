"""How a student's function is run: with a time guard, and every exception turned into a sentence.

>>> run_guarded(lambda x: 2 * x, (21,))
(True, 42)
>>> run_guarded(lambda: 1 / 0, ())
(False, 'your function raised ZeroDivisionError: division by zero')
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable
from types import FrameType
from typing import Any

__all__ = ["TIME_LIMIT", "run_guarded"]

#: Seconds a student's function may run on one test input.
TIME_LIMIT = 2.0


class _TimeUp(BaseException):
    pass


def _alarm(signum: int, frame: FrameType | None) -> None:
    raise _TimeUp()


def run_guarded(fn: Callable[..., Any], args: tuple[Any, ...], limit: float = TIME_LIMIT) -> tuple[bool, Any]:
    """Call ``fn(*args)``; return ``(True, value)`` or ``(False, message)``.

    Never raises (but KeyboardInterrupt). The time guard uses SIGALRM, so it
    only works in the main thread of a POSIX process; elsewhere the call runs
    unguarded.
    """
    use_alarm = hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    old: Any = None
    if use_alarm:
        try:
            old = signal.signal(signal.SIGALRM, _alarm)
            signal.setitimer(signal.ITIMER_REAL, limit)
        except Exception:  # pragma: no cover - signals unavailable
            use_alarm = False
    try:
        return True, fn(*args)
    except _TimeUp:
        return False, f"your function did not finish within {limit:g} s (an endless loop?)"
    except RecursionError:
        return False, "your function recursed too deeply (RecursionError)"
    except SystemExit:
        return False, "your function called exit()"
    except Exception as exc:  # anything the student's code raises
        text = str(exc).splitlines()[0][:200] if str(exc) else ""
        return False, f"your function raised {type(exc).__name__}" + (f": {text}" if text else "")
    finally:
        if use_alarm:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old if old is not None else signal.SIG_DFL)
