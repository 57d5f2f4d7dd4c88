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
from flyopt.io.sweep_spec import OPTION_MAXIMUMS, OPTION_MINIMUMS

__all__ = ["RESULTS", "main"]

RESULTS = Path("benchmarks") / "results"
"""Where a full run writes by default (relative to the working directory): the committed results."""


def _parser(parser_class: type[argparse.ArgumentParser] = argparse.ArgumentParser) -> argparse.ArgumentParser:
    parser = parser_class(
        prog="flyopt bench",
        description="Speed against error: time every way of getting an answer and its error against a "
        "reference of known accuracy; print the Markdown summary and write CSV, PNG and "
        "Markdown.",
    )
    parser.add_argument(
        "--output-dir",
        type=Path,
        default=None,
        metavar="DIR",
        help=f"directory for the results (default: {RESULTS.as_posix()} for a full run; "
        f"a --quick run writes no files unless this is given)",
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="a few seconds: fewer samples, scenes and repeats; a smoke run that only "
        "prints its summary unless --output-dir is given",
    )
    parser.add_argument("--hard", action="store_true", help="run the generated hard set instead (hard.md and hard.csv)")
    parser.add_argument(
        "--sections", default=None, help=f"comma-separated sections to run (default all: {','.join(SECTIONS)})"
    )
    parser.add_argument("--seed", type=int, default=None, help="seed of the random scenes (default 1)")
    parser.add_argument("--repeats", type=int, default=None, help="timed repeats per measurement")
    parser.add_argument("--scenes", type=int, default=None, help="random design scenes")
    parser.add_argument("--hard-scenes", type=int, default=None, help="random design scenes of the hard set")
    parser.add_argument("--no-pin", dest="pin", action="store_false", help="do not pin the process to one CPU")
    return parser


def _output_dir(args, parser, default):
    """The folder the run writes into, made ready before the run; None for a quick run without one.

    A full run writes into ``default`` unless ``--output-dir`` is given; a
    ``--quick`` run is a smoke run and writes only into an ``--output-dir``
    it is given, never over the committed results. A folder that cannot be
    written is refused (exit 2) before anything runs.
    """
    folder = args.output_dir if args.output_dir is not None else (None if args.quick else default)
    if folder is None:
        return None
    if folder.exists() and not folder.is_dir():
        parser.error(f"argument --output-dir: {folder} is a file, not a directory")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        parser.error(f"argument --output-dir: cannot create {folder}: {err.strerror or err}")
    if not os.access(folder, os.W_OK):
        parser.error(f"argument --output-dir: {folder} is not writable")
    return folder


def main(
    argv: list[str] | None = None,
    *,
    default_output_dir: Path = RESULTS,
    program: str = "flyopt bench",
    parser_class: type[argparse.ArgumentParser] = argparse.ArgumentParser,
) -> int:
    """Entry point of ``flyopt bench``; returns the exit status (0 done).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``flyopt bench`` (default: ``sys.argv[1:]``).
    default_output_dir : Path, optional
        Where a full run writes without ``--output-dir`` (default
        ``benchmarks/results`` of the working directory).
    program : str, optional
        How the run was started, for the "Command:" line of the results.
    parser_class : type, optional
        The argument parser: ``flyopt bench`` gives the command line's own, which says a bad option in one
        line (:class:`flyopt.cli.exits.OneLineParser`; the bench is below the command line and does not
        import it).

    Returns
    -------
    int
        0 when the run is done. Bad arguments exit through argparse (status 2).
    """
    parser = _parser(parser_class)
    args = parser.parse_args(argv)
    for name in ("repeats", "scenes", "hard_scenes"):
        value = getattr(args, name)
        if value is not None and value < 1:
            parser.error(f"--{name.replace('_', '-')} must be >= 1, got {value}")
    low, high = OPTION_MINIMUMS["seed"], OPTION_MAXIMUMS["seed"]  # the random scenes' seed, as a sweep's
    if args.seed is not None and not low <= args.seed <= high:
        parser.error(f"--seed must be between {low} and {high}, got {args.seed}")
    if args.hard_scenes is not None and not args.hard:
        parser.error("--hard-scenes: counts the hard set's scenes, which run with --hard alone")
    if args.hard and args.sections is not None:
        parser.error("--sections: the hard set (--hard) has no sections")
    sections = None
    if args.sections is not None:
        sections = [s.strip() for s in args.sections.split(",") if s.strip()]
        if not sections:
            parser.error(f"--sections names no section; allowed are {', '.join(SECTIONS)}")
        unknown = [s for s in sections if s not in SECTIONS]
        if unknown:
            parser.error(f"section {unknown[0]!r} not recognised; allowed are {', '.join(SECTIONS)}")
    out = _output_dir(args, parser, default_output_dir)
    config = Config.make(
        args.quick, seed=args.seed, repeats=args.repeats, scenes=args.scenes, hard_scenes=args.hard_scenes
    )
    here = str(Path.cwd()) + os.sep
    command = program + " " + " ".join(a.replace(here, "") for a in (argv if argv is not None else sys.argv[1:]))
    pinning, previous = pin_one_core() if args.pin else ("not pinned (--no-pin)", None)

    def progress(text):
        print(text, file=sys.stderr, flush=True)

    try:
        header = machine_header(pinning)
        if args.hard:
            cycle_rows, design_rows = run_hard(config, progress)
            text = hard_summary(cycle_rows, design_rows, header, command.strip())
            if out is not None:
                write_hard_csv(out / "hard.csv", cycle_rows, design_rows)
                (out / "hard.md").write_text(text, encoding="utf-8")
        else:
            rows = run(config, sections, progress)
            text = summary(rows, header, command.strip())
            if out is not None:
                plot(out / "speed_error.png", rows)
                write_csv(out / "speed_error.csv", rows)
                (out / "speed_error.md").write_text(text, encoding="utf-8")
    finally:
        if previous is not None:
            os.sched_setaffinity(0, previous)
    if out is None:
        progress("a --quick run writes no files; give --output-dir DIR to keep them")
    print(text)
    return 0
