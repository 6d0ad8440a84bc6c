"""SIGALRM that interrupts a controller call past its deadline (see `guard.py`).

On POSIX, in the main thread (where pytest and pytest-xdist's workers run items), a real-time
interval timer interrupts the call with `TimeUp`; elsewhere `Alarm` does nothing and a call is
judged when it returns. The process's own SIGALRM handler and timer are restored on removal, and
a timer someone else set (pytest-timeout's, say) keeps its deadline meanwhile.
"""

from __future__ import annotations

import signal
import threading
import time
from types import FrameType
from typing import Any

# A controller that catches the interruption and carries on is interrupted again this often.
AGAIN = 0.5  # s


class TimeUp(BaseException):
    """Raised inside a controller call that overran: a `BaseException`, so that the
    controller's own `except Exception` does not swallow it."""


class Alarm:
    """SIGALRM to interrupt a controller call that overruns, on POSIX in the main thread.

    A timer someone else set (pytest-timeout's, say) keeps its deadline: ours fires at the
    earlier of the two, and a signal that is theirs goes to their handler.
    """

    def __init__(self) -> None:
        self.usable = (
            hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
        )
        self._previous: Any = None
        self._outer: tuple[float, float] | None = None  # their deadline (monotonic s), interval
        self._ours: float | None = None  # our deadline, monotonic s, while a call runs

    def install(self) -> None:
        """Take SIGALRM, pausing a timer someone else set until `remove` or a call's end."""
        if signal.getsignal(signal.SIGALRM) is None:
            # A handler set outside Python could not be put back: leave it, and judge each
            # call when it returns.
            self.usable = False
        if not self.usable:
            return
        self._previous = signal.signal(signal.SIGALRM, self._ring)
        delay, interval = signal.setitimer(signal.ITIMER_REAL, 0.0)
        self._outer = (time.monotonic() + delay, interval) if delay > 0.0 else None
        self._set()

    def remove(self) -> None:
        """Give SIGALRM back to its handler, and its timer the time it had left."""
        if not self.usable or self._previous is None:
            return
        self._ours = None
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, self._previous)
        self._previous = None
        if self._outer is not None:
            deadline, interval = self._outer
            signal.setitimer(signal.ITIMER_REAL, max(deadline - time.monotonic(), 1e-6), interval)

    def arm(self, seconds: float) -> None:
        """Interrupt the call about to start after `seconds`."""
        if self.usable:
            self._ours = time.monotonic() + max(seconds, 0.0)
            self._set()

    def disarm(self) -> None:
        if self.usable:
            self._ours = None
            self._set()

    def _set(self) -> None:
        """The timer at the earlier deadline, ours or theirs; off if there is neither."""
        now = time.monotonic()
        deadlines = [(self._ours, AGAIN)] if self._ours is not None else []
        if self._outer is not None:
            deadlines.append(self._outer)
        if not deadlines:
            signal.setitimer(signal.ITIMER_REAL, 0.0)
            return
        deadline, interval = min(deadlines, key=lambda pair: pair[0])
        signal.setitimer(signal.ITIMER_REAL, max(deadline - now, 1e-6), interval)

    def _ring(self, signum: int, frame: FrameType | None) -> None:
        now = time.monotonic()
        if self._outer is not None and now >= self._outer[0]:
            self._pass_on(signum, frame, now)
        elif self._ours is not None and now >= self._ours:
            raise TimeUp

    def _pass_on(self, signum: int, frame: FrameType | None, now: float) -> None:
        """Their timer fired: hand the signal to their handler, and keep their interval."""
        assert self._outer is not None
        interval = self._outer[1]
        self._outer = (now + interval, interval) if interval > 0.0 else None
        self._set()
        if callable(self._previous):
            self._previous(signum, frame)
        elif self._previous == signal.SIG_DFL:
            signal.signal(signal.SIGALRM, signal.SIG_DFL)
            signal.raise_signal(signal.SIGALRM)
