"""The command line of ``flyopt bench``: its options and :func:`main`.

Named ``cli`` rather than ``main`` so that the function
``flyopt.bench.main`` never shadows a module of the same name.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from flyopt.bench.hard import run_hard
from flyopt.bench.output import hard_summary, plot, summary, write_csv, write_hard_csv
from flyopt.bench.sections import SECTIONS, run
from flyopt.bench.timing import Config, machine_header, pin_one_core

__all__ = ["main"]


def _parser():
    parser = argparse.ArgumentParser(
        prog="flyopt bench",
        description="Speed against error: time every way of getting an answer and its error against a "
                    "reference of known accuracy; write CSV, PNG and Markdown.")
    parser.add_argument("--out", type=Path, default=Path("benchmarks") / "results",
                        help="directory for the results (default: benchmarks/results)")
    parser.add_argument("--quick", action="store_true", help="a few seconds: fewer samples, scenes and repeats")
    parser.add_argument("--hard", action="store_true",
                        help="run the generated hard set instead (writes hard.md and hard.csv)")
    parser.add_argument("--sections", default=None,
                        help=f"comma-separated sections to run (default all: {','.join(SECTIONS)})")
    parser.add_argument("--seed", type=int, default=None, help="seed of the random scenes (default 1)")
    parser.add_argument("--repeats", type=int, default=None, help="timed repeats per measurement")
    parser.add_argument("--scenes", type=int, default=None, help="random design scenes")
    parser.add_argument("--hard-scenes", type=int, default=None, help="random design scenes of the hard set")
    parser.add_argument("--no-pin", dest="pin", action="store_false", help="do not pin the process to one CPU")
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``flyopt bench``; returns the exit status (0 done, 2 bad arguments)."""
    parser = _parser()
    args = parser.parse_args(argv)
    for name in ("repeats", "scenes", "hard_scenes"):
        value = getattr(args, name)
        if value is not None and value < 1:
            parser.error(f"--{name.replace('_', '-')} must be >= 1, got {value}")
    sections = None
    if args.sections:
        sections = [s.strip() for s in args.sections.split(",") if s.strip()]
        unknown = [s for s in sections if s not in SECTIONS]
        if unknown:
            parser.error(f"section {unknown[0]!r} not recognised; allowed are {', '.join(SECTIONS)}")
    config = Config.make(args.quick, seed=args.seed, repeats=args.repeats, scenes=args.scenes,
                         hard_scenes=args.hard_scenes)
    here = str(Path.cwd()) + os.sep
    command = "flyopt bench " + " ".join(a.replace(here, "") for a in (argv if argv is not None else sys.argv[1:]))
    pinning, previous = pin_one_core() if args.pin else ("not pinned (--no-pin)", None)

    def progress(text):
        print(text, file=sys.stderr, flush=True)

    try:
        args.out.mkdir(parents=True, exist_ok=True)
        header = machine_header(pinning)
        if args.hard:
            cycle_rows, design_rows = run_hard(config, progress)
            text = hard_summary(cycle_rows, design_rows, header, command.strip())
            write_hard_csv(args.out / "hard.csv", cycle_rows, design_rows)
            (args.out / "hard.md").write_text(text, encoding="utf-8")
        else:
            rows = run(config, sections, progress)
            write_csv(args.out / "speed_error.csv", rows)
            plot(args.out / "speed_error.png", rows)
            text = summary(rows, header, command.strip())
            (args.out / "speed_error.md").write_text(text, encoding="utf-8")
    finally:
        if previous is not None:
            os.sched_setaffinity(0, previous)
    print(text)
    return 0
