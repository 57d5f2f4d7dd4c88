"""What every benchmark script of this folder does the same way: pin to one core, read the host's load.

The scripts run as ``python benchmarks/bench_X.py``, so this folder is on their path and they import
it as ``common``.
"""

import csv
import json
import os
import statistics
import subprocess
import sys
import time

#: The environment of every timed process: this one's, but bytecode is written (``PYTHONDONTWRITEBYTECODE``
#: dropped), so that a warm-up leaves the .pyc files an installed package has and no timed run compiles the
#: sources (some 0.25 s of flyopt's modules: a start-up read 3.5x numpy's with it, 2x without).
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def pin_one_core():
    """Pin the process (and so its children) to one CPU; return a description of what was done."""
    if hasattr(os, "sched_setaffinity"):
        cpu = min(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpu})
        return f"pinned to CPU {cpu} (os.sched_setaffinity)"
    return "not pinned (os.sched_setaffinity unavailable)"


def median_time(call, repeat, warm=1, clock=time.perf_counter):
    """(median, min, max) seconds of ``call()`` over ``repeat`` runs, after ``warm`` untimed ones: wall seconds, or
    by ``clock=time.process_time`` the process's CPU seconds (the work itself, which other processes on a shared
    core do not add to as they do to the wall time)."""
    for _ in range(warm):
        call()
    times = []
    for _ in range(repeat):
        start = clock()
        call()
        times.append(clock() - start)
    return statistics.median(times), min(times), max(times)


def load_average(separator=" "):
    """The host's load averages over 1, 5 and 15 minutes, as text ("unknown" where the OS has none)."""
    return separator.join(f"{x:.2f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "unknown"


#: A scene whose resisting torque is a table (``{title}``, ``{points}``: the table's TOML lines), the one the
#: table benchmarks (bench_tables, bench_exact) time.
TABLE_SCENE = """title = "{title}"
[machine]
speed = "300 rpm"
delta = 0.05
inertia = "5 kg*m^2"
[torque.driving]
constant = "unknown"
[torque.resisting]
unit = "N*m"
angle_unit = "deg"
{points}
"""


def write_results(folder, name, text, rows, fields=None):
    """Write a benchmark's ``NAME.md`` (``text``) and ``NAME.csv`` (``rows``: dicts, or sequences with ``fields``)."""
    folder.mkdir(exist_ok=True)
    (folder / f"{name}.md").write_text(text, encoding="utf-8")
    with open(folder / f"{name}.csv", "w", newline="", encoding="utf-8") as f:
        if fields is not None and rows and not isinstance(rows[0], dict):
            writer = csv.writer(f)
            writer.writerow(fields)
            writer.writerows(rows)
            return
        dict_writer = csv.DictWriter(f, fieldnames=list(fields or rows[0]))
        dict_writer.writeheader()
        dict_writer.writerows(rows)


def run_child(code, src, *args):
    """Run ``python -c code args...`` in a child process with the source folder ``src`` first on its path (another
    flyopt tree, for a baseline); return the last line of its output read as JSON."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    done = subprocess.run(
        [sys.executable, "-c", code, *(str(a) for a in args)], env=env, capture_output=True, text=True, check=True
    )
    return json.loads(done.stdout.strip().splitlines()[-1])
