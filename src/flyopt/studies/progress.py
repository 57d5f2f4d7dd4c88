"""The progress line of a sweep: points done, designs per second and an ETA on stderr."""

from __future__ import annotations

import math
import sys
import time
from typing import TextIO

from flyopt.said import counted

__all__ = ["Progress"]


class Progress:
    """A progress line with rate and ETA on stderr (a bar on a terminal)."""

    def __init__(
        self,
        total_points: int,
        total_chunks: int,
        enabled: bool,
        stream: TextIO | None = None,
        done_points: int = 0,
    ) -> None:
        self.total, self.chunks = total_points, total_chunks
        self.enabled = enabled
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.perf_counter()
        self.points, self.skipped, self.designs, self.done_chunks = 0, done_points, 0, 0
        self.last = 0.0

    def update(self, points: int, designs: int) -> None:
        """One more chunk done: ``points`` points, ``designs`` designs."""
        self.points += points
        self.designs += designs
        self.done_chunks += 1
        now = time.perf_counter()
        final = self.skipped + self.points >= self.total
        if self.enabled and (final or now - self.last > (0.2 if self.tty else 5.0)):
            self.last = now
            self._write(final)

    def close(self) -> None:
        """End the line on a terminal when the run stopped before the last chunk."""
        if self.enabled and self.tty and self.skipped + self.points < self.total:
            self._write(False)
            self.stream.write("\n")
            self.stream.flush()

    def _write(self, final: bool) -> None:
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        done = self.skipped + self.points
        rate = self.points / elapsed
        left = self.total - done
        eta = left / rate if rate > 0 else math.inf
        fraction = done / self.total if self.total else 1.0
        bar = "#" * int(24 * fraction) + "-" * (24 - int(24 * fraction))
        text = (
            f"sweep [{bar}] {done}/{counted(self.total, 'point')} ({100 * fraction:.0f} %), "
            f"{self.designs / elapsed:,.0f} designs/s, "
            f"{'done in ' + _clock(elapsed) if final else 'ETA ' + _clock(eta)}"
        )
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + text + end)
        self.stream.flush()


def _clock(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"
