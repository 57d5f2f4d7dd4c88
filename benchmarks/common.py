"""What every benchmark script of this folder does the same way: pin to one core, read the host's load.

The scripts run as ``python benchmarks/bench_X.py``, so this folder is on their path and they import
it as ``common``.
"""

import os


def pin_one_core():
    """Pin the process (and so its children) to one CPU; return a description of what was done."""
    if hasattr(os, "sched_setaffinity"):
        cpu = min(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpu})
        return f"pinned to CPU {cpu} (os.sched_setaffinity)"
    return "not pinned (os.sched_setaffinity unavailable)"


def load_average(separator=" "):
    """The host's load averages over 1, 5 and 15 minutes, as text ("unknown" where the OS has none)."""
    return separator.join(f"{x:.2f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "unknown"
