"""A corpus of hostile input, run against the ``flyopt`` command as an attacker would (issue 25).

Every case runs in a sandbox of its own, ``WORK/NAME/``: its folder
``a/scene/`` holds a scene (a problem scene of problems/ with one field made
hostile, or a scene written for the case) and whatever files it names;
``outside/`` beside it holds canary files that the case may not read (their
text must never appear in what flyopt prints) nor change. Each case runs
``python -m flyopt ...`` in a fresh interpreter, in its folder, with a
timeout, and must end:

- with exit status 0, 2 or 3 (1 means the input got past the checks and broke
  something inside; 130 or a kill means it hung),
- within ``--timeout`` seconds (default 10),
- with no traceback, and one line on stderr on error (``check``: one ``FILE:LINE:`` line per error), nothing on success,
- without quoting a canary file,
- without creating, changing or removing anything outside its folder,
- with nothing half-written: on an error, no new file in its folder.

    python tools/hostile.py                  # the whole corpus, a table of what failed
    python tools/hostile.py --list           # the cases, one line each
    python tools/hostile.py --only 'vary-*'  # the cases whose name matches
    python tools/hostile.py --json out.json  # every outcome, for a record

The generation is deterministic (``--seed``): the same corpus on every run.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import fnmatch
import hashlib
import json
import math
import os
import random
import re
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from flyopt._toml import tomllib

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
CANARY = "CANARY-7f3e2a-DO-NOT-PRINT"
ALLOWED_EXITS = (0, 2, 3)
QUIET = ("solve", "check", "plot", "report", "sweep", "pareto", "tradeoff")
"""The commands that take -q; the corpus runs them quiet."""


# --------------------------------------------------------------------------- TOML writing


def _toml_key(key: str) -> str:
    return key if key and all(c.isalnum() or c in "_-" for c in key) else json.dumps(key)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        # JSON's escapes are TOML basic-string escapes, but for characters beyond the BMP (JSON writes a
        # surrogate pair, which TOML refuses): those stay raw, as does everything but what TOML forbids raw
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def toml_text(document: dict[str, Any]) -> str:
    """``document`` as TOML text (tables as headers, lists of tables as ``[[...]]``)."""
    lines: list[str] = []

    def table(body: dict[str, Any], prefix: str) -> None:
        subtables = []
        for key, value in body.items():
            if isinstance(value, dict) and value:
                subtables.append((key, value, False))
            elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
                subtables.append((key, value, True))
            else:
                lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
        for key, value, is_array in subtables:
            name = f"{prefix}.{_toml_key(key)}" if prefix else _toml_key(key)
            if is_array:
                for item in value:
                    lines.append(f"\n[[{name}]]")
                    table(item, name)
            else:
                lines.append(f"\n[{name}]")
                table(value, name)

    table(document, "")
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- cases


@dataclass
class Case:
    """One hostile run: ``flyopt ARGS`` in the case's folder, after ``setup`` has filled it."""

    name: str
    args: list[str]
    files: dict[str, str | bytes] = field(default_factory=dict)
    setup: Callable[[Path, Path], None] | None = None
    """Called with (the case's folder, the outside folder) to make links, FIFOs, big files."""
    note: str = ""
    check: Callable[[Path], list[str]] | None = None
    """Called with the case's folder after the run: what is wrong with what it left."""


HOSTILE_VALUES: list[tuple[str, Any]] = [
    ("zero", 0),
    ("negative", -1),
    ("tiny", 1e-300),
    ("huge", 1e300),
    ("neg-huge", -1e300),
    ("nan", math.nan),
    ("inf", math.inf),
    ("bigint", 10**400),
    ("empty", ""),
    ("words", "lots"),
    ("wrong-unit", "5 furlong"),
    ("wrong-dimension", "5 kg"),
    ("long-text", "9" * 200_000),
    ("control", "\x00\x07\x1b[31m\u202e"),
    ("list", [1, 2, 3]),
    ("empty-list", []),
    ("table", {"a": 1}),
    ("bool", True),
    ("nested-list", [[[[1e308, -1e308]]]]),
    ("emoji", "\U0001f525 rpm"),
]


def leaves(document: Any, path: tuple[Any, ...] = ()) -> Iterator[tuple[tuple[Any, ...], Any]]:
    """Every scalar (and every list of scalars) of a TOML document, with its path."""
    if isinstance(document, dict):
        for key, value in document.items():
            yield from leaves(value, (*path, key))
    elif isinstance(document, list) and document and all(isinstance(v, (dict, list)) for v in document):
        for k, value in enumerate(document):
            yield from leaves(value, (*path, k))
    else:
        yield path, document


def set_path(document: Any, path: tuple[Any, ...], value: Any) -> None:
    for key in path[:-1]:
        document = document[key]
    document[path[-1]] = value


def scene_files(scene: Path) -> dict[str, str | bytes]:
    """The scene and the data files beside it that it names."""
    text = scene.read_text()
    files: dict[str, str | bytes] = {"scene.toml": text}
    for other in scene.parent.iterdir():
        if other.suffix == ".csv" and other.name in text:
            files[other.name] = other.read_bytes()
    return files


def field_mutations(rng: random.Random, per_scene: int) -> Iterator[Case]:
    """Each problem scene with one field made hostile; ``per_scene`` picked at random per scene."""
    for scene in sorted(PROBLEMS.rglob("*.toml")):  # the textbook gallery too
        document = tomllib.loads(scene.read_text())
        paths = [p for p, _ in leaves(document)]
        options = [(p, label, v) for p in paths for label, v in HOSTILE_VALUES]
        for path, label, value in rng.sample(options, min(per_scene, len(options))):
            mutated = tomllib.loads(scene.read_text())
            set_path(mutated, path, value)
            files = scene_files(scene)
            files["scene.toml"] = toml_text(mutated)
            where = ".".join(str(p) for p in path)
            command = rng.choice(["check", "solve"])
            yield Case(f"field-{scene.stem}-{where}-{label}-{command}", [command, "scene.toml"], files)


BASE = {
    "title": "hostile",
    "machine": {"speed": "1500 rpm", "delta": 0.05},
    "torque": {
        "resisting": {"points": [["0 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]},
        "driving": {"constant": "unknown"},
    },
}


def base(**changes: Any) -> dict[str, Any]:
    document = json.loads(json.dumps(BASE))
    for dotted, value in changes.items():
        set_path(document, tuple(dotted.split("__")), value)
    return document


def outside_file(name: str) -> Callable[[Path, Path], str]:
    return lambda case, outside: str(outside / name)


def file_attacks() -> Iterator[Case]:
    """Every ``*_file`` field pointed where it must not go."""
    csv = "angle,torque\n0 deg,1600 N*m\n90 deg,200 N*m\n360 deg,200 N*m\n"
    targets: list[tuple[str, str, Callable[[Path, Path], None] | None]] = [
        ("absolute-outside", "@OUTSIDE@/secret.csv", None),
        ("dotdot-outside", "../../outside/secret.csv", None),
        ("etc-passwd", "/etc/passwd", None),
        ("dev-zero", "/dev/zero", None),
        ("dev-urandom", "/dev/urandom", None),
        ("proc-self", "/proc/self/environ", None),
        ("fifo", "pipe.csv", lambda case, outside: os.mkfifo(case / "pipe.csv")),
        ("folder", "folder.csv", lambda case, outside: (case / "folder.csv").mkdir()),
        ("symlink-outside", "link.csv", lambda case, outside: (case / "link.csv").symlink_to(outside / "secret.csv")),
        ("symlink-inside", "link.csv", lambda case, outside: (case / "link.csv").symlink_to(case / "good.csv")),
        ("missing", "nothing-here.csv", None),
        ("sparse-1g", "sparse.csv", lambda case, outside: os.truncate(_touch(case / "sparse.csv"), 1 << 30)),
        ("long-line", "long.csv", lambda case, outside: (case / "long.csv").write_text("0," + "1" * 50_000_000)),
        ("many-rows", "rows.csv", lambda case, outside: _many_rows(case / "rows.csv", 10_000_000)),
        ("binary", "binary.csv", lambda case, outside: (case / "binary.csv").write_bytes(os.urandom(4096))),
        ("empty-name", "", None),
        ("nul-in-name", "a\x00b.csv", None),
        ("home", "~/secret.csv", None),
    ]
    for target, value, setup in targets:
        document = base(torque__resisting={"points_file": value})
        yield Case(
            f"file-points_file-{target}",
            ["check" if "rows" not in target else "solve", "scene.toml"],
            {"scene.toml": toml_text(document), "good.csv": csv},
            setup,
        )
    # The other *_file fields, pointed at a canary outside and at /dev/zero.
    others = {
        "pressure_file": {
            "title": "engine",
            "machine": {"speed": "1500 rpm", "delta": 0.05},
            "engine": {"cycle": "four_stroke", "bore": "100 mm", "stroke": "120 mm", "pressure_file": "X"},
        },
        "velocity_ratio_file": {
            "title": "members",
            "machine": {"speed": "60 rpm", "delta": 0.05},
            "member": [{"name": "slide", "mass": "100 kg", "velocity_ratio_file": "X"}],
        },
        "force_file": {
            "title": "press",
            "machine": {"speed": "60 rpm", "delta": 0.1},
            "press": {"force_file": "X", "stroke": "100 mm"},
        },
    }
    for name, document in others.items():
        for target, value in (("absolute-outside", "@OUTSIDE@/secret.csv"), ("dev-zero", "/dev/zero")):
            yield Case(f"file-{name}-{target}", ["check", "scene.toml"], {"scene.toml": _with(document, value)})


def _with(document: dict[str, Any], value: str) -> str:
    return toml_text(document).replace('"X"', json.dumps(value))


def _touch(path: Path) -> Path:
    path.touch()
    return path


def _many_rows(path: Path, rows: int) -> None:
    with open(path, "w") as out:
        out.write("angle,torque\n")
        block = "".join(f"{360 * k / rows} deg,{1000 + k % 7} N*m\n" for k in range(10_000))
        for _ in range(rows // 10_000):
            out.write(block)


def output_attacks() -> Iterator[Case]:
    """Every command's ``-o`` pointed at what is not a regular file."""
    good = toml_text(base())
    commands = {
        "solve": ["solve", "scene.toml", "--json", "-o"],
        "report": ["report", "scene.toml", "-o"],
        "plot": ["plot", "scene.toml", "--what", "turning_moment", "-o"],
        "tradeoff": ["tradeoff", "scene.toml", "-o"],
    }
    targets: list[tuple[str, str, Callable[[Path, Path], None] | None]] = [
        # Copies of /dev/full and /dev/null made in the case's folder (the same device numbers): a run
        # that renames over a device there does no harm to the machine's own /dev.
        ("dev-full", "full", lambda case, outside: os.mknod(case / "full", 0o666 | stat.S_IFCHR, os.makedev(1, 7))),
        ("dev-null", "null", lambda case, outside: os.mknod(case / "null", 0o666 | stat.S_IFCHR, os.makedev(1, 3))),
        ("folder", "out", lambda case, outside: (case / "out").mkdir()),
        ("fifo", "out", lambda case, outside: os.mkfifo(case / "out")),
        ("missing-folder", "nowhere/out", None),
        ("symlink-to-file", "out", lambda case, outside: (case / "out").symlink_to(case / "target")),
    ]
    suffix = {"solve": ".json", "report": ".html", "plot": ".svg", "tradeoff": ".csv"}
    for command, args in commands.items():
        for target, path, setup in targets:
            if target in ("folder", "fifo", "missing-folder", "symlink-to-file"):
                path = path + suffix[command]
                setup = _suffixed(setup, suffix[command]) if setup else None
            check = _still_a_device(path) if target.startswith("dev") else None
            if target == "symlink-to-file":
                check = _link_followed(path)
            yield Case(f"output-{command}-{target}", [*args, path], {"scene.toml": good}, setup, check=check)


def temporary_attacks() -> Iterator[Case]:
    """Links planted where an output's temporary file used to go, ``NAME.tmp-PID``, for the PIDs the
    run is likely to get (the next few thousand), each to a canary outside: a temporary opened by
    its name would write the canary (touched outside its folder) or replace the link."""
    good = toml_text(base())
    commands = {
        "solve": (["solve", "scene.toml", "--json", "-o"], "out.json"),
        "report": (["report", "scene.toml", "-o"], "out.html"),
        "plot": (["plot", "scene.toml", "--what", "turning_moment", "-o"], "out.svg"),
        "tradeoff": (["tradeoff", "scene.toml", "-o"], "out.csv"),
    }
    for command, (args, name) in commands.items():
        names = [name, name + ".json"] if name.endswith(".csv") else [name]
        yield Case(
            f"output-{command}-planted-temporary-links",
            [*args, name],
            {"scene.toml": good},
            _plant_temporary_links(names),
            check=_links_kept(names),
        )


PLANTED_PIDS = 5000
"""How many PIDs after the corpus's own get a planted link (the run's PID is among them unless
the machine started that many processes in between)."""


def _plant_temporary_links(names: list[str]) -> Callable[[Path, Path], None]:
    def setup(case: Path, outside: Path) -> None:
        first = os.getpid()
        for name in names:
            for pid in range(first, first + PLANTED_PIDS):
                (case / f"{name}.tmp-{pid}").symlink_to(outside / "secret.csv")

    return setup


def _links_kept(names: list[str]) -> Callable[[Path], list[str]]:
    def check(case: Path) -> list[str]:
        first = os.getpid()
        gone = [
            f"{name}.tmp-{pid}"
            for name in names
            for pid in range(first, first + PLANTED_PIDS)
            if not (case / f"{name}.tmp-{pid}").is_symlink()
        ]
        return [f"replaced or removed a planted link: {gone[:2]}"] if gone else []

    return check


def _still_a_device(name: str) -> Callable[[Path], list[str]]:
    def check(case: Path) -> list[str]:
        mode = (case / name).lstat().st_mode
        return [] if stat.S_ISCHR(mode) else [f"replaced the device {name} with a file"]

    return check


def _link_followed(name: str) -> Callable[[Path], list[str]]:
    def check(case: Path) -> list[str]:
        link = case / name
        if not link.is_symlink():
            return [f"replaced the symlink {name} instead of writing its target"]
        return [] if (case / "target").stat().st_size > 0 else [f"the target of {name} is empty"]

    return check


def _suffixed(setup: Callable[[Path, Path], None], suffix: str) -> Callable[[Path, Path], None]:
    def run(case: Path, outside: Path) -> None:
        scratch = case / ".setup"
        scratch.mkdir()
        setup(scratch, outside)
        made = next(scratch.iterdir())
        if made.is_symlink():
            (case / "target").touch()
            (case / f"{made.name}{suffix}").symlink_to(case / "target")
            made.unlink()
        else:
            made.rename(case / f"{made.name}{suffix}")
        scratch.rmdir()

    return run


def option_attacks() -> Iterator[Case]:
    """Options and scene fields with no sane bound, counts that are not counts."""
    good = toml_text(base())
    scene = {"scene.toml": good}
    wheel = scene_files(PROBLEMS / "punch-press-wheel.toml")
    cases = [
        ("vary-fractional-count", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:3.2", "-o", "s.csv"]),
        ("vary-zero-count", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:0", "-o", "s.csv"]),
        ("vary-huge-count", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:1000000000", "-o", "s.csv"]),
        ("vary-negative-count", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:-3", "-o", "s.csv"]),
        ("vary-nan", ["sweep", "scene.toml", "--vary", "machine.delta=nan:0.1:3", "-o", "s.csv"]),
        ("samples-zero", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1", "--samples", "0", "-o", "s.csv"]),
        ("samples-huge", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1", "--samples", "10**9"]),
        ("max-chunks-zero", ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:3", "--max-chunks", "0"]),
        (
            "scheduler-not-url",
            ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:3", "--scheduler", "not a url"],
        ),
        (
            "scheduler-bad-port",
            ["sweep", "scene.toml", "--vary", "machine.delta=0.01:0.1:3", "--scheduler", "tcp://x:99999"],
        ),
        ("units-furlongs", ["solve", "scene.toml", "--units", "furlongs"]),
        ("pareto-points-huge", ["pareto", "wheel.toml", "--points", "1000000000"]),
        ("pareto-points-negative", ["pareto", "wheel.toml", "--points", "-5"]),
        ("pareto-range-bad", ["pareto", "wheel.toml", "--range", "-1:0.5m"]),
        ("no-such-command", ["frobnicate", "scene.toml"]),
        ("no-such-scene", ["solve", "missing.toml"]),
        ("scene-is-folder", ["solve", "."]),
        ("scene-dev-zero", ["check", "/dev/zero"]),
        ("output-newline", ["solve", "scene.toml", "-o", "a\nb.json"]),
        ("output-name-300", ["new", "press", "-o", "x" * 300 + ".toml"]),
    ]
    for name, args in cases:
        files = dict(scene)
        if "wheel.toml" in args:
            files["wheel.toml"] = wheel["scene.toml"]
        yield Case(f"option-{name}", args, files)

    scenes = {
        "title-200k": base(title="T" * 200_000),
        "title-control": base(title="a\x00b\x07c\x1bd\u202eevil"),
        "title-emoji": base(title="\U0001f525 flywheel \u2603"),
        "negative-resisting": base(
            torque__resisting={"points": [["0 deg", "-1600 N*m"], ["90 deg", "-200 N*m"], ["360 deg", "-200 N*m"]]}
        ),
        "speed-huge": base(machine__speed="1e300 rpm"),
        "delta-one": base(machine__delta=1.0),
        "points-100k": base(
            torque__resisting={"points": [[f"{k * 360 / 100000} deg", "10 N*m"] for k in range(100000)]}
        ),
        "deep-nesting": None,
        # a torque falling by 1e6 N*m per rad/s, with no inertia and with a little: CVODES ran for minutes
        "speed-stiff": base(
            machine__speed="600 rpm",
            torque__resisting={"expression": "1000 + 500*sin(phi) + 1e6*(omega - 62.83)"},
        ),
        "speed-stiff-inertia": base(
            machine__speed="600 rpm",
            machine__inertia="1e-3 kg*m^2",
            torque__resisting={"expression": "1000 + 500*sin(phi) + 1e6*(omega - 62.83)"},
        ),
        "sweep-output-outside": base(
            sweep={"output": "../../outside/stolen.csv", "vary": {"machine.delta": "0.01:0.1:3"}}
        ),
        "sweep-output-absolute": base(
            sweep={"output": "@OUTSIDE@/stolen.csv", "vary": {"machine.delta": "0.01:0.1:3"}}
        ),
        "sweep-output-missing-folder": base(sweep={"output": "nowhere/s.csv", "vary": {"machine.delta": "0.01:0.1:3"}}),
        "sweep-output-newline": base(sweep={"output": "a\nb.csv", "vary": {"machine.delta": "0.01:0.1:3"}}),
    }
    for name, document in scenes.items():
        text = "a = " + "[" * 100_000 + "]" * 100_000 + "\n" if document is None else toml_text(document)
        command = "sweep" if name.startswith("sweep") else "solve"
        args = [command, "scene.toml"]
        if name.startswith("title"):
            args = ["report", "scene.toml", "-o", "r.html"]
        yield Case(f"scene-{name}-{command}", args, {"scene.toml": text})
        if command == "sweep":
            yield Case(f"scene-{name}-check", ["check", "scene.toml"], {"scene.toml": text})

    # The scene fields of the issue: ratios, start-up, motor tables, velocity ratios, walls, materials.
    drive = tomllib.loads((PROBLEMS / "press-drive.toml").read_text())
    if "drive" in drive:
        for name, value in (("ratio-huge", [1e6, 1e9]), ("ratio-inverted", [10.0, 1.0])):
            mutated = json.loads(json.dumps(drive))
            mutated["drive"]["ratio"] = value
            yield Case(f"scene-drive-{name}", ["solve", "scene.toml"], {"scene.toml": toml_text(mutated)})
        mutated = json.loads(json.dumps(drive))
        mutated["drive"]["max_startup"] = "1 ms"
        yield Case("scene-drive-startup-1ms", ["solve", "scene.toml"], {"scene.toml": toml_text(mutated)})
    # A press's working stroke made tiny (a press with a drive was seen to hang): each value on the
    # press without a drive and on the one whose drive is designed with the wheel.
    for stem in ("press-from-process", "press-drive"):
        press_doc = tomllib.loads((PROBLEMS / f"{stem}.toml").read_text())
        for label, key, value in (
            ("1e-9s", "working_time", "1e-9 s"),
            ("1ns", "working_time", "1 ns"),
            ("1e-300s", "working_time", "1e-300 s"),
            ("bare-1e-9", "working_time", 1e-9),
            ("1us", "working_time", "1 us"),
            ("1ms", "working_time", "1 ms"),
            ("1e-6rad", "working_angle", "1e-6 rad"),
        ):
            mutated = json.loads(json.dumps(press_doc))
            for other in ("working_time", "working_angle"):
                mutated["press"].pop(other, None)
            mutated["press"][key] = value
            for command in ("check", "solve"):
                yield Case(
                    f"scene-{stem}-{key.replace('_', '-')}-{label}-{command}",
                    [command, "scene.toml"],
                    {"scene.toml": toml_text(mutated)},
                )
    wheel_doc = tomllib.loads(wheel["scene.toml"])
    for name, change in (
        ("min-wall-5m", {"min_wall": "5 m"}),
        ("no-poisson", None),
    ):
        mutated = json.loads(json.dumps(wheel_doc))
        if change:
            mutated["design"].update(change)
        else:
            mutated["material"][0].pop("poisson_ratio", None)
            mutated["design"]["materials"] = [mutated["material"][0]["name"]]
        for command in ("check", "solve"):
            yield Case(f"scene-wheel-{name}-{command}", [command, "scene.toml"], {"scene.toml": toml_text(mutated)})


def corpus(seed: int, per_scene: int) -> list[Case]:
    rng = random.Random(seed)
    cases = [
        *file_attacks(),
        *output_attacks(),
        *temporary_attacks(),
        *option_attacks(),
        *field_mutations(rng, per_scene),
    ]
    names = [c.name for c in cases]
    duplicate = {n for n in names if names.count(n) > 1}
    for case in cases:  # two mutations may share a name (a field and a value picked twice): number them
        if case.name in duplicate:
            case.name += "-" + hashlib.sha1(repr(case.files).encode()).hexdigest()[:6]
    return cases


# --------------------------------------------------------------------------- running


@dataclass
class Outcome:
    name: str
    args: list[str]
    status: int | None
    seconds: float
    stderr: str
    problems: list[str]


def snapshot(folder: Path) -> dict[str, tuple[int, int, str]]:
    """Every entry under ``folder`` (not following links), with its kind, size and mtime."""
    seen: dict[str, tuple[int, int, str]] = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in dirnames + filenames:
            path = Path(dirpath) / name
            try:
                info = path.lstat()
            except FileNotFoundError:  # a file that came and went while we looked
                continue
            seen[str(path)] = (stat.S_IFMT(info.st_mode), info.st_size, str(info.st_mtime_ns))
    return seen


def everything_but(sandbox: Path, folder: Path) -> dict[str, tuple[int, int, str]]:
    """What a case may not change: everything in its sandbox but its own folder."""
    return {path: entry for path, entry in snapshot(sandbox).items() if not path.startswith(str(folder))}


def run_case(case: Case, work: Path, timeout: float) -> Outcome:
    # Each case in a sandbox of its own, WORK/NAME/, so that cases run side by side cannot be blamed
    # for each other: its folder is sandbox/a/scene, the canaries in sandbox/outside, which the
    # scene reaches as ../../outside.
    sandbox = work / case.name[:150]
    folder = sandbox / "a" / "scene"
    outside = sandbox / "outside"
    folder.mkdir(parents=True)
    prepare(outside)
    for name, content in case.files.items():
        if isinstance(content, str):
            content = content.replace("@OUTSIDE@", str(outside))
        target = folder / name
        target.write_bytes(content.encode() if isinstance(content, str) else content)
    if case.setup is not None:
        case.setup(folder, outside)
    args = [a.replace("@OUTSIDE@", str(outside)) for a in case.args]
    if args and args[0] in QUIET and "-q" not in args:
        args.append("-q")  # -q leaves only errors: anything on stderr after a success is a leak
    before_outside = everything_but(sandbox, folder)
    before_here = snapshot(folder)
    dev_before = {p: os.stat(p).st_mode for p in ("/dev/null", "/dev/full")}
    env = {**os.environ, "HOME": str(folder), "MPLCONFIGDIR": str(work / "mpl"), "PYTHONWARNINGS": ""}
    started = time.perf_counter()
    process = subprocess.Popen(
        [sys.executable, "-m", "flyopt", *args],
        cwd=folder,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        env=env,
        start_new_session=True,
    )
    try:
        out, err = process.communicate(timeout=timeout)
        status: int | None = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, err = process.communicate()
        status = None
    seconds = time.perf_counter() - started
    stdout, stderr = out.decode(errors="replace"), err.decode(errors="replace")
    problems: list[str] = []
    if status is None:
        problems.append(f"hang: killed after {timeout:g} s")
    elif status not in ALLOWED_EXITS:
        problems.append(f"exit {status}")
    if "Traceback" in stderr or "Traceback" in stdout:
        problems.append("traceback")
    lines = stderr.strip("\n").splitlines()
    # flyopt check lists every error of a scene, each as FILE:LINE: field: message (issue 29)
    placed = bool(args) and args[0] == "check" and all(re.match(r"[^:\n]+:\d+: ", line) for line in lines)
    if status == 0 and lines:
        problems.append(f"stderr on success ({len(lines)} lines)")
    elif status not in (0, None) and len(lines) > 1 and not placed:
        problems.append(f"{len(lines)} lines on stderr")
    if status == 2 and lines and not lines[0].startswith("flyopt") and not placed:
        problems.append("error line does not start with 'flyopt' (nor, from check, FILE:LINE:)")
    if CANARY in stdout or CANARY in stderr:
        problems.append("printed a canary from outside the scene's folder")
    if status is not None and seconds > timeout:
        problems.append(f"slow: {seconds:.1f} s")
    after_outside = everything_but(sandbox, folder)
    changed = [p for p in set(before_outside) | set(after_outside) if before_outside.get(p) != after_outside.get(p)]
    if changed:
        problems.append(f"touched outside its folder: {sorted(changed)[:3]}")
    for device, mode in dev_before.items():
        if os.stat(device).st_mode != mode:
            problems.append(f"replaced {device}")
            _restore_device(device)
    if case.check is not None and status is not None:
        problems.extend(case.check(folder))
    if status not in (0, None):
        new = sorted(set(snapshot(folder)) - set(before_here))
        if new:
            problems.append(f"left files after an error: {[Path(n).name for n in new][:3]}")
    shutil.rmtree(sandbox, ignore_errors=True)  # big files would fill the disk
    return Outcome(case.name, args, status, seconds, stderr.strip()[:300], problems)


def _restore_device(device: str) -> None:
    """Put back /dev/null or /dev/full if a run replaced it with a file (root can)."""
    numbers = {"/dev/null": (1, 3), "/dev/full": (1, 7)}[device]
    os.remove(device)
    os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(*numbers))
    os.chmod(device, 0o666)


def prepare(outside: Path) -> None:
    """The canary files a case must neither quote nor change."""
    outside.mkdir(parents=True)
    (outside / "secret.csv").write_text(f"angle,torque\n0 deg,{CANARY}\n360 deg,{CANARY}\n")
    (outside / "secret.toml").write_text(f'title = "{CANARY}"\n')


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=25)
    parser.add_argument("--per-scene", type=int, default=28, help="field mutations per problem scene")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds a case may take")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--only", help="run the cases whose name matches this glob")
    parser.add_argument("--list", action="store_true", help="list the cases and stop")
    parser.add_argument("--json", type=Path, help="write every outcome to this file")
    args = parser.parse_args(argv)
    cases = corpus(args.seed, args.per_scene)
    if args.only:
        cases = [c for c in cases if fnmatch.fnmatch(c.name, args.only)]
    if args.list:
        for case in cases:
            print(case.name, " ".join(case.args))
        return 0
    with tempfile.TemporaryDirectory(prefix="flyopt-hostile-") as tmp:
        work = Path(tmp)
        (work / "mpl").mkdir()
        # A timeout stretched by the number of jobs sharing the cores would hide a hang; the cases
        # run in parallel only up to the cores, and each is timed on its own.
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            outcomes = list(pool.map(lambda c: run_case(c, work, args.timeout), cases))
    failed = [o for o in outcomes if o.problems]
    for outcome in failed:
        print(f"FAIL {outcome.name}: {'; '.join(outcome.problems)}")
        print(f"     flyopt {' '.join(a[:60] for a in outcome.args)[:200]}")
        if outcome.stderr:
            print(f"     stderr: {outcome.stderr.splitlines()[-1][:200]}")
    slowest = max(outcomes, key=lambda o: o.seconds)
    print(
        f"{len(outcomes)} cases, {len(outcomes) - len(failed)} held, {len(failed)} failed; "
        f"slowest {slowest.seconds:.1f} s ({slowest.name})"
    )
    if args.json:
        args.json.write_text(json.dumps([o.__dict__ for o in outcomes], indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
