"""Benchmark of ``flyopt report`` (issue 26): the whole command, HTML and PDF, wall and CPU time.

Each case runs the command as a user does (``python -m flyopt report SCENE -o FILE``, a new
process: the interpreter's start, the imports, the one solve, the figures, the writing), the
cases of one repeat one after another, so that the host's load hits all alike; the figures are
medians over the repeats with their ranges. Beside them, in the same run:

* ``flyopt solve --verify`` of the same scene, the floor a report cannot go below (the same solve,
  without the report's extras, its figures and its writing);
* ``python -c "import numpy"``, the yardstick of the interpreter's start, and the import of
  matplotlib.pyplot, what every report pays before it draws (the two beside the solve: the report's floor);
* the report of slider-crank-press in this process after a warm-up, split into its phases
  (collect: the one solve; build: the document and its figures drawn; write: the figures rendered
  and the file written), CPU time.

With ``--baseline SRC`` (a ``src`` folder of another flyopt, for example the commit before
issue 26's changes, checked out with ``git worktree`` or ``git archive``) the reports are run with that
package too, in the same repeats: "before" and "after" measured side by side.

Targets (issue 26): the report of problems/slider-crank-press.toml in at most 1.5 s wall as HTML
and 2.5 s as PDF. Pinned to one core when the OS allows it (the child processes inherit it); with
``--cpus 2``, to two, as on an engineer's two-core machine (a report, HTML or PDF, draws its figures on both:
:mod:`flyopt.report.figure_cores`), each report timed on one of them alone too. The CPU times count the
report's workers. Writes ``benchmarks/results/report.md`` and ``report.csv`` beside this script.

Usage::

    python benchmarks/bench_report.py [--repeat 7] [--quick] [--baseline OTHER/src] [--cpus 2]
"""

import argparse
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from common import CHILD_ENV, load_average, pin_one_core, write_results

import flyopt

ROOT = Path(__file__).resolve().parent.parent
PROBLEMS = ROOT / "problems"
RESULTS = Path(__file__).resolve().parent / "results"
FLYOPT = [sys.executable, "-m", "flyopt"]

#: Issue 26's targets [s, wall] for slider-crank-press.
TARGETS = {"html": 1.5, "pdf": 2.5}
TARGET_SCENE = "slider-crank-press"
#: The other scene: the dynamic model, a motor on its curve (the heaviest solve of the shipped presses).
OTHER_SCENE = "motor-press"


def run_once(command, env=None, cpus=None):
    """(wall, CPU of the child and its workers) [s] of one run of ``command`` (in ``env``, default
    :data:`common.CHILD_ENV`; on ``cpus``, default this process's); it must succeed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(
        command,
        capture_output=True,
        cwd=ROOT,
        env=CHILD_ENV if env is None else env,
        preexec_fn=None if cpus is None else (lambda: os.sched_setaffinity(0, cpus)),
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 3, 4):
        raise RuntimeError(f"{' '.join(map(str, command))}: exit {done.returncode}\n{done.stderr.decode()}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cases(folder, baseline=None, one_cpu=None):
    """(name, scene, setting, command, env, cpus) of every process timed; the baseline's reports with its ``src``
    first; with ``one_cpu`` (a set of one CPU, when the run has more), each report again on that CPU alone."""
    out = []
    before = None
    if baseline is not None:
        before = dict(CHILD_ENV, PYTHONPATH=os.pathsep.join([str(baseline), os.environ.get("PYTHONPATH", "")]))
    for scene in (TARGET_SCENE, OTHER_SCENE):
        path = str(PROBLEMS / f"{scene}.toml")
        for kind in ("html", "pdf"):
            report = [*FLYOPT, "report", path, "-o"]
            out.append(("report", scene, kind, [*report, str(folder / f"{scene}.{kind}")], None, None))
            if one_cpu is not None:
                out.append(
                    ("report (one CPU)", scene, kind, [*report, str(folder / f"one-{scene}.{kind}")], None, one_cpu)
                )
            if before is not None:
                out.append(
                    (
                        "report (baseline)",
                        scene,
                        kind,
                        [*report, str(folder / f"baseline-{scene}.{kind}")],
                        before,
                        None,
                    )
                )
        out.append(("solve --verify", scene, "floor", [*FLYOPT, "solve", "--verify", path], None, None))
    out.append(("import numpy", "-", "yardstick", [sys.executable, "-c", "import numpy"], None, None))
    # what every report pays before it draws a figure: matplotlib's import (its own numpy with it)
    plotting = "import matplotlib; matplotlib.use('Agg'); import matplotlib.pyplot"
    out.append(("import matplotlib.pyplot", "-", "yardstick", [sys.executable, "-c", plotting], None, None))
    return out


def bench_commands(repeat, folder, baseline=None, one_cpu=None):
    """Rows of the whole-process times: median, min and max of wall and CPU time over the repeats."""
    todo = cases(folder, baseline, one_cpu)
    for _name, _scene, _setting, command, env, cpus in todo:  # a warm-up of each: the OS's file cache, the .pyc
        # files (written: see CHILD_ENV)
        run_once(command, env, cpus)
    times = {k: [] for k in range(len(todo))}
    for _ in range(repeat):
        for k, (_name, _scene, _setting, command, env, cpus) in enumerate(todo):
            times[k].append(run_once(command, env, cpus))
    rows = []
    for k, (name, scene, setting, _command, _env, _cpus) in enumerate(todo):
        walls, cpus = [w for w, _c in times[k]], [c for _w, c in times[k]]
        rows.append(
            {
                "section": name,
                "case": scene,
                "setting": setting,
                "wall_median_s": statistics.median(walls),
                "wall_min_s": min(walls),
                "wall_max_s": max(walls),
                "cpu_median_s": statistics.median(cpus),
                "note": "",
            }
        )
    for row in rows:
        if row["section"].startswith("report"):
            prefix = "baseline-" if "baseline" in row["section"] else "one-" if "one CPU" in row["section"] else ""
            size = (folder / f"{prefix}{row['case']}.{row['setting']}").stat().st_size
            row["note"] = f"{size / 1024:.0f} kB"
    after = {(r["case"], r["setting"]): r for r in rows if r["section"] == "report"}
    for row in rows:
        if row["section"] in ("report (baseline)", "report (one CPU)"):
            now = after[(row["case"], row["setting"])]
            row["note"] += (
                f"; now {row['wall_median_s'] / now['wall_median_s']:.2f}x faster in wall time, "
                f"{row['cpu_median_s'] / now['cpu_median_s']:.2f}x in CPU time"
            )
    return rows


def bench_phases(repeat, folder):
    """Rows of the report of slider-crank-press in this process, by phase: CPU time, median of ``repeat``."""
    from flyopt.cli import report
    from flyopt.report.builder import build

    path = PROBLEMS / f"{TARGET_SCENE}.toml"
    rows = []
    for kind in ("html", "pdf"):
        phases = {"collect": [], "build": [], "write": []}
        for k in range(repeat + 1):
            marks = [_now()]
            inputs = report.collect(path, "bench", pdf=kind == "pdf")
            marks.append(_now())
            document = build(inputs, "engineering", title_block=report._title_lines(inputs))
            marks.append(_now())
            try:
                report.write(document, folder / f"phases.{kind}", kind)
            finally:
                document.close()
            marks.append(_now())
            if k:  # the first run is the warm-up: imports, the font cache
                for name, (a, b) in zip(phases, zip(marks, marks[1:])):
                    phases[name].append((b[0] - a[0], b[1] - a[1]))
        for name, values in phases.items():
            walls, cpus = [w for w, _c in values], [c for _w, c in values]
            rows.append(
                {
                    "section": "in process",
                    "case": TARGET_SCENE,
                    "setting": f"{kind}: {name}",
                    "wall_median_s": statistics.median(walls),
                    "wall_min_s": min(walls),
                    "wall_max_s": max(walls),
                    "cpu_median_s": statistics.median(cpus),
                    "note": f"CPU min {min(cpus):.3f} s, max {max(cpus):.3f} s (this process and its workers)",
                }
            )
    return rows


def _now():
    """(wall, CPU of this process and of its finished children: the figures' workers) [s]."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime
    return time.perf_counter(), cpu


def seconds(value):
    return "" if value == "" else f"{value:.3f} s"


def summary(rows, header, repeat, baseline=None, cpus=1):
    found = {(r["section"], r["case"], r["setting"]): r for r in rows}
    command = f"python benchmarks/bench_report.py --repeat {repeat}" + (f" --baseline {baseline}" if baseline else "")
    command += f" --cpus {cpus}" if cpus != 1 else ""
    lines = [
        "# flyopt report: speed",
        "",
        f"Command: `{command}`",
        "",
        header,
        "",
        "Whole processes (`python -m flyopt report SCENE -o FILE`, as a user runs it), the cases of one repeat "
        "one after another; medians over the repeats with their ranges, CPU time of the process beside its wall "
        "time. The host is shared: its load averages are given at the start and the end of the run.",
        "",
        "## Targets (issue 26)",
        "",
        "| target | status | measured (median, range) |",
        "|---|---|---|",
    ]
    for kind, limit in TARGETS.items():
        for section, where in (
            ("report", f"on {cpus} CPU{'s' if cpus > 1 else ''}"),
            ("report (one CPU)", "on one CPU"),
        ):
            row = found.get((section, TARGET_SCENE, kind))
            if row is None:
                continue
            status = "met" if row["wall_median_s"] <= limit else "NOT met"
            lines.append(
                f"| flyopt report {TARGET_SCENE} -o x.{kind} <= {limit} s wall ({where}) | {status} | "
                f"{row['wall_median_s']:.3f} s ({row['wall_min_s']:.3f}–{row['wall_max_s']:.3f} s), "
                f"CPU {row['cpu_median_s']:.3f} s |"
            )
    solve = found[("solve --verify", TARGET_SCENE, "floor")]["wall_median_s"]
    numpy_only = found[("import numpy", "-", "yardstick")]["wall_median_s"]
    plotting = found[("import matplotlib.pyplot", "-", "yardstick")]["wall_median_s"]
    floor = solve + plotting - numpy_only
    lines += [
        "",
        f"Where the time goes: `solve --verify` of the same scene is {solve:.3f} s and importing matplotlib "
        f"{plotting - numpy_only:.3f} s beyond numpy, so a report that draws with matplotlib starts at about "
        f"{floor:.3f} s before its first figure; the rest is the figures (laid out and drawn) and the writing "
        "(the in-process phases below).",
    ]
    lines += [
        "",
        "## Every row",
        "",
        "| section | case | setting | wall median | wall min | wall max | CPU median | note |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['section']} | {r['case']} | {r['setting']} | {seconds(r['wall_median_s'])} | "
            f"{seconds(r['wall_min_s'])} | {seconds(r['wall_max_s'])} | {seconds(r['cpu_median_s'])} | {r['note']} |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--quick", action="store_true", help="3 repeats; writes nothing")
    parser.add_argument(
        "--baseline", type=Path, help="the src folder of another flyopt: its reports timed in the same repeats"
    )
    parser.add_argument(
        "--cpus",
        type=int,
        default=1,
        help="CPUs the reports may run on (default 1: pinned to one; 2: an engineer's two-core machine, the "
        "report's figures drawn on both, each report run on one CPU alone too)",
    )
    args = parser.parse_args(argv)
    repeat = 3 if args.quick else args.repeat
    one_cpu = None
    if args.cpus == 1:
        pinning = pin_one_core()
    else:
        available = sorted(os.sched_getaffinity(0))
        if len(available) < args.cpus:
            parser.error(f"--cpus {args.cpus}: this process may run on {len(available)} CPUs")
        chosen = set(available[: args.cpus])
        os.sched_setaffinity(0, chosen)
        one_cpu = {min(chosen)}
        pinning = (
            f"pinned to CPUs {', '.join(map(str, sorted(chosen)))} (os.sched_setaffinity); the rows 'one CPU' "
            f"run on CPU {min(chosen)} alone"
        )
    start_load = load_average()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        print("bench_report: whole processes", file=sys.stderr, flush=True)
        rows = bench_commands(repeat, folder, args.baseline, one_cpu)
        print("bench_report: in-process phases", file=sys.stderr, flush=True)
        rows += bench_phases(repeat, folder)
    header = (
        f"Machine: {platform.platform()}, {os.cpu_count()} CPUs, {pinning}; Python {platform.python_version()}, "
        f"numpy {np.__version__}, flyopt {flyopt.__version__}. Load averages (1, 5, 15 min) at the start "
        f"{start_load}, at the end {load_average()}. Every timed process writes and reads its bytecode (.pyc, as "
        f"an installed package has; PYTHONDONTWRITEBYTECODE was {'set here and dropped for them' if 'PYTHONDONTWRITEBYTECODE' in os.environ else 'not set'})."
    )
    text = summary(rows, header, repeat, args.baseline, args.cpus)
    if not args.quick:
        write_results(RESULTS, "report", text, rows)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
