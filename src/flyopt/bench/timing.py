"""How a run measures: its configuration, the timer, the row it records, the CPU it runs on.

Timing: ``time.perf_counter``; a warm-up call, then ``repeats`` timed
repeats of ``number`` calls each (``number`` grows until one repeat lasts
``min_time``); the figure is the median per call, the spread the 25th and
75th percentiles. The process is pinned to one CPU while it runs.
"""

from __future__ import annotations

import math
import os
import platform
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

__all__ = ["Config", "Timing", "Row", "measure", "once", "set_ratios", "pin_one_core", "machine_header"]
T = TypeVar("T")


@dataclass
class Config:
    """What a run measures and how hard it tries.

    Attributes
    ----------
    quick : bool
        A few seconds in all (smoke test): fewer samples, scenes and repeats.
    seed : int
        Seed of every random scene and table.
    repeats : int
        Timed repeats per measurement (cycle and geometry sections).
    design_repeats : int
        Timed repeats per design ranking.
    min_time : float
        Least duration of one timed repeat [s]; fast calls are looped.
    scenes : int
        Random design scenes.
    samples : tuple of int
        Sample counts of the sampled integration rules.
    grids : tuple of (int, int)
        Brute-force grid resolutions, (mean diameters, H/B values).
    table_points : int
        Points of the main cycle table.
    hard_scenes : int
        Random design scenes of the hard set.
    """

    quick: bool = False
    seed: int = 1
    repeats: int = 15
    design_repeats: int = 5
    min_time: float = 0.005
    scenes: int = 40
    samples: tuple[int, ...] = (64, 256, 1024, 4096, 16384, 100_000)
    grids: tuple[tuple[int, int], ...] = ((10, 3), (30, 3), (100, 5), (300, 5), (1000, 5), (3000, 10), (10000, 10))
    table_points: int = 10_000
    hard_scenes: int = 400

    @classmethod
    def make(cls, quick: bool = False, **overrides: Any) -> Config:
        """The full configuration, or the quick one; ``None`` overrides are ignored."""
        config = (
            cls(
                quick=True,
                repeats=3,
                design_repeats=2,
                min_time=0.001,
                scenes=3,
                samples=(64, 1024, 100_000),
                grids=((30, 3), (1000, 5)),
                table_points=2_000,
                hard_scenes=6,
            )
            if quick
            else cls()
        )
        for key, value in overrides.items():
            if value is not None:
                setattr(config, key, value)
        return config


@dataclass
class Timing:
    """Time per call [s]: median and quartiles over repeats."""

    median: float
    p25: float
    p75: float
    repeats: int
    number: int


def measure(fn: Callable[[], object], repeats: int, min_time: float = 0.0) -> Timing:
    """Time ``fn()`` per call: a warm-up, then ``repeats`` repeats of ``number`` calls.

    ``number`` doubles (or jumps) until one repeat lasts at least ``min_time``
    [s]; each repeat's time is divided by ``number``.
    """
    fn()
    number = 1
    while True:
        start = time.perf_counter()
        for _ in range(number):
            fn()
        elapsed = time.perf_counter() - start
        if elapsed >= min_time or number >= 1 << 20:
            break
        number *= max(2, min(100, int(1.2 * min_time / max(elapsed, 1e-9))))
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(number):
            fn()
        samples.append((time.perf_counter() - start) / number)
    q25, q75 = np.quantile(samples, [0.25, 0.75])
    return Timing(statistics.median(samples), float(q25), float(q75), repeats, number)


def once(fn: Callable[[], T]) -> tuple[T, Timing]:
    """One call of ``fn()``, timed: its value and a Timing of that single call.

    The figure of a smoke run (``--quick``) where one call takes seconds: no
    warm-up and no spread, so the time includes whatever the first call builds.
    """
    start = time.perf_counter()
    value = fn()
    elapsed = time.perf_counter() - start
    return value, Timing(elapsed, elapsed, elapsed, 1, 1)


@dataclass
class Row:
    """One method at one setting on one case: time, error, feasibility.

    Attributes
    ----------
    section, case, method, setting : str
        What was measured; ``setting`` is e.g. the sample count or grid size.
    time_median_s, time_p25_s, time_p75_s : float
        Time per solve [s]. For one case: median and quartiles over repeats.
        For a section aggregated over scenes (design): median and quartiles
        of the per-scene medians.
    repeats, number : int
        Timed repeats (per scene) and calls per repeat.
    time_ratio : float
        time_median_s over that of the section's reference method on the same
        case, measured in the same run (cycle: flyopt-exact; design:
        flyopt-ipopt; geometry: rim).
    error : float
        Relative error against the reference (design: worst over scenes of
        the winner's relative excess mass).
    error_median : float
        Median over scenes (equal to ``error`` for a single case).
    violation : float
        Largest relative constraint violation of a reported design [-].
    verdicts_ok, verdicts_total : int
        Combinations decided correctly (design), or 1/1 for a single result.
    failures : int
        Solves that gave no answer where there is one.
    reference : str
        What the error is measured against.
    note : str
        Failure reasons and remarks.
    """

    section: str
    case: str
    method: str
    setting: str
    time_median_s: float
    time_p25_s: float
    time_p75_s: float
    repeats: int
    number: int
    time_ratio: float = math.nan
    error: float = math.nan
    error_median: float = math.nan
    violation: float = 0.0
    verdicts_ok: int = 1
    verdicts_total: int = 1
    failures: int = 0
    reference: str = ""
    note: str = ""

    @classmethod
    def timed(cls, section: str, case: str, method: str, setting: str, timing: Timing, **values: Any) -> Row:
        return cls(
            section,
            case,
            method,
            str(setting),
            timing.median,
            timing.p25,
            timing.p75,
            timing.repeats,
            timing.number,
            **values,
        )


def set_ratios(rows: list[Row], is_reference: Callable[[Row], bool]) -> None:
    """Fill time_ratio = time / time of the reference row of the same case.

    ``is_reference(row)`` says which row of a case is its reference (one per case).
    """
    base = {r.case: r.time_median_s for r in rows if is_reference(r)}
    for r in rows:
        if r.case in base and base[r.case] > 0:
            r.time_ratio = r.time_median_s / base[r.case]


def pin_one_core() -> tuple[str, set[int] | None]:
    """Pin this process to one CPU; return (description, previous affinity or None)."""
    if hasattr(os, "sched_setaffinity"):
        previous = os.sched_getaffinity(0)
        cpu = min(previous)
        os.sched_setaffinity(0, {cpu})
        return f"pinned to CPU {cpu} (os.sched_setaffinity)", previous
    return "not pinned (os.sched_setaffinity unavailable)", None


def machine_header(pinning: str) -> str:
    """One line naming the machine, the pinning and the versions that the timings depend on."""
    import casadi as ca
    import scipy

    # casadi sets __version__ at run time, but the types mypy reads for it do not declare it
    casadi_version = ca.__version__  # type: ignore[attr-defined]

    return (
        f"Machine: {platform.platform()}, {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} CPUs, {pinning}; Python {platform.python_version()}, numpy "
        f"{np.__version__}, scipy {scipy.__version__}, CasADi {casadi_version} (IPOPT bundled)."
    )
