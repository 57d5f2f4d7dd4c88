"""Ctrl-C while a sweep's chunks run: noted at once, acted on where it is safe.

The parent notes Ctrl-C and acts on it where that is safe (between saves,
while it waits for workers; a chunk it computes itself at once), never
half-way through saving a chunk or inside the process pool's bookkeeping.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from types import FrameType

__all__ = ["POLL_SECONDS", "Stop", "ctrl_c"]

#: How often the process and Dask loops look at finished chunks, at Ctrl-C and
#: at the Dask workers [s].
POLL_SECONDS = 0.1


class Stop:
    """Ctrl-C while chunks run: noted by the signal handler, acted on where it is safe.

    A :class:`KeyboardInterrupt` raised wherever the main thread happens to be
    can land inside a process pool's bookkeeping (holding a lock the shutdown
    then waits for: a hang), inside ``logging`` or half-way through saving a
    chunk. So the handler only notes the request, and the loops look at it
    between chunks and while they wait. Only a chunk computed in this process
    (serial mode) is stopped at once: that is plain computation, and waiting
    for it to finish could take minutes.
    """

    def __init__(self) -> None:
        self.requested = False
        self._at_once = False

    def handler(self, signum: int, frame: FrameType | None) -> None:
        """The SIGINT handler: note the request; stop at once inside :meth:`at_once`."""
        self.requested = True
        if self._at_once:
            self._at_once = False
            raise KeyboardInterrupt

    def check(self) -> None:
        """Raise :class:`KeyboardInterrupt` here if Ctrl-C was pressed."""
        if self.requested:
            raise KeyboardInterrupt

    @contextmanager
    def at_once(self) -> Iterator[None]:
        """A block that Ctrl-C stops at once (the computation of a serial chunk)."""
        self.check()
        self._at_once = True
        try:
            yield
        finally:
            self._at_once = False


@contextmanager
def ctrl_c() -> Iterator[Stop]:
    """Hand Ctrl-C to a :class:`Stop` for the duration (main thread only)."""
    stop = Stop()
    if threading.current_thread() is not threading.main_thread():
        yield stop  # signals reach the main thread only; nothing to catch here
        return
    previous = signal.signal(signal.SIGINT, stop.handler)
    try:
        yield stop
    finally:
        signal.signal(signal.SIGINT, previous)
