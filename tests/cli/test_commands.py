"""The command line as a user runs it: output, JSON fields, exit codes, one-line errors."""

import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import PROBLEMS, assert_published, run_flyopt
from numpy.testing import assert_allclose

import flyopt
from flyopt.cli.main import main
from flyopt.errors import ExpressionError, Interrupted, NonPeriodicCycle, SceneError, SolverFailed
from flyopt.pipeline import verify

JSON_FIELDS = {
    "a_max",
    "work_per_cycle",
    "driving_torque",
    "resisting_torque",
    "power",
    "omega_mean",
    "omega_max",
    "omega_min",
    "angle_omega_max",
    "angle_omega_min",
    "j_required",
    "flywheel_needed",
    "energy_chain",
    "shafts",
    "motor_power",
}


def run(*args):
    """``flyopt ARGS`` in this process (the tests of pipes, the console script and runs in two processes start
    their own)."""
    return run_flyopt(*args)


def process(*args):
    """``python -m flyopt ARGS`` in a process of its own (its own hash seed, its own imports)."""
    return subprocess.run(
        [sys.executable, "-m", "flyopt", *map(str, args)], capture_output=True, text=True, timeout=120
    )


def test_solve_json_shear_press():
    out = run("solve", PROBLEMS / "shear-press.toml", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert JSON_FIELDS <= set(data)
    assert_published(data["a_max"], "1256.33")
    assert_published(data["j_required"], "1.0183")
    assert_published(data["power"] / 1000, "72.65")
    assert data["flywheel_needed"] is True
    assert [e["delta_e"] for e in data["energy_chain"]][0] == 0.0
    assert data["shafts"][0]["name"] == "motor"
    assert_allclose(data["omega_max"] - data["omega_min"], 0.05 * data["omega_mean"], rtol=1e-14)


def test_solve_text_report_shows_units():
    out = run("solve", PROBLEMS / "shear-press.toml")
    assert out.returncode == 0, out.stderr
    # engineering units, the report's default, to four figures (1,256.33 J, 72,649.3 W)
    for words in ("A_max", "1.256 kJ", "kg·m²", "72.65 kW", "Energy indicator diagram", "ω_min"):
        assert words in out.stdout


def test_check_ok(capsys):
    assert main(["check", str(PROBLEMS / "compressor.toml")]) == 0
    assert "ok" in capsys.readouterr().out


@pytest.mark.parametrize(
    "text, words",
    [
        (
            '[machine]\nspeed = "1500 m"\ndelta = 0.05\n[torque.net]\nareas = [1, -1]\n',
            "machine.speed: '1500 m' has the wrong dimension",
        ),
        (
            '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.net]\nareas = [1, -2]\n',
            "torque: non-periodic fluctuation",
        ),
        (
            '[machine]\nspeed = "1500 rpm"\ndelta = 3\n[torque.net]\nareas = [1, -1]\n',
            "machine.delta: must lie between 1e-06 and 2",
        ),
        ("[machine\n", "not valid TOML"),
    ],
)
@pytest.mark.parametrize("command", ["solve", "check"])
def test_bad_input_is_one_line_exit_2_no_traceback(tmp_path, text, words, command):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    out = run(command, path, "--json") if command == "solve" else run(command, path)
    assert out.returncode == 2
    assert out.stdout == ""  # nothing half-written
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in out.stderr
    placed = {"machine.speed": 2, "machine.delta": 3}  # a field's line: check FILE:LINE: field: ..., solve the same
    field = words.split(":")[0]
    if field in placed:
        prefix = "" if command == "check" else "flyopt: error: "
        assert lines[0].startswith(f"{prefix}{path}:{placed[field]}: ")
    else:
        assert lines[0].startswith(f"flyopt: error: {path}: ")
    assert words in lines[0]


def test_missing_file_exit_2():
    out = run("solve", "does-not-exist.toml")
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "cannot read the file" in out.stderr


def test_console_script_is_installed():
    # the script of *this* interpreter's environment, not whatever is first on PATH
    beside = Path(sys.executable).parent / "flyopt"
    exe = str(beside) if beside.exists() else shutil.which("flyopt")
    assert exe, "the flyopt console script is not installed beside this Python"
    out = subprocess.run(
        [exe, "solve", str(PROBLEMS / "example1-net-areas.toml"), "--json"], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0
    assert math.isclose(json.loads(out.stdout)["a_max"], 1600.0)


# --------------------------------------------------------------------------
# One exit-code table, one error handler
# --------------------------------------------------------------------------


def _raiser(err):
    def run(*args, **kwargs):
        raise err

    return run


@pytest.mark.parametrize(
    "err, status, words",
    [
        (SceneError("machine.delta", "must lie between 1e-06 and 2", "s.toml"), 2, "s.toml: machine.delta: must lie"),
        (NonPeriodicCycle(-3.0, 100.0, "s.toml"), 2, "s.toml: torque: non-periodic"),
        (ExpressionError("unknown name 'x'"), 2, "SCENE: unknown name 'x'"),
        (SolverFailed("IPOPT: Maximum_Iterations_Exceeded after 3000 iterations"), 1, "SCENE: IPOPT: Maximum"),
        (ZeroDivisionError("float division by zero"), 1, "SCENE: float division by zero"),
        (OverflowError("math range error"), 1, "SCENE: math range error"),
        (ValueError("math domain error"), 1, "SCENE: math domain error"),
        (Interrupted("stopped after 3 of 8 chunks: continue with --resume"), 130, "SCENE: stopped after 3"),
        (KeyboardInterrupt(), 130, "SCENE: interrupted"),
        (FileNotFoundError(2, "No such file or directory", "out/x.csv"), 2, "out/x.csv: No such file"),
    ],
)
def test_every_error_is_one_line_with_its_exit_status(monkeypatch, capsys, err, status, words):
    import flyopt.cli.scene

    monkeypatch.setattr(flyopt.cli.scene, "run_check", _raiser(err))
    assert main(["check", "SCENE"]) == status
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert captured.err.startswith(f"flyopt: error: {words}")


def test_an_unexpected_error_keeps_its_traceback(monkeypatch):
    # a bug is not an input error: it is not hidden behind a one-line message
    import flyopt.cli.scene

    monkeypatch.setattr(flyopt.cli.scene, "run_check", _raiser(TypeError("a bug")))
    with pytest.raises(TypeError, match="a bug"):
        main(["check", "SCENE"])


def test_a_long_message_stays_one_short_line(monkeypatch, capsys):
    import flyopt.cli.scene

    huge = SceneError("machine.speed", "'" + "9" * 1_000_000 + "' is not a speed", "s.toml")
    monkeypatch.setattr(flyopt.cli.scene, "run_check", _raiser(huge))
    assert main(["check", "SCENE"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and len(err) < 1100


def test_interrupted_sweep_exits_130(monkeypatch, capsys):
    import flyopt.studies.sweep

    monkeypatch.setattr(
        flyopt.studies.sweep, "sweep", _raiser(Interrupted("stopped: continue with --resume (out.csv.parts)"))
    )
    assert main(["sweep", str(PROBLEMS / "shear-press.toml"), "--vary", "delta=0.05,0.1"]) == 130
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--resume" in err


@pytest.mark.parametrize("command", ["solve", "check", "plot", "sweep", "pareto", "tradeoff", "bench"])
def test_every_command_is_in_the_one_tree(command):
    out = run(command, "--help")
    assert out.returncode == 0 and f"flyopt {command}" in out.stdout, out.stderr


def test_bench_options_are_bench_own():
    out = run("bench", "--help")
    assert out.returncode == 0 and "--quick" in out.stdout and "--hard" in out.stdout


@pytest.mark.parametrize(
    "args, said",
    [
        (["--quick", "--seed", "-1"], "--seed must be between 0 and"),  # was "expected non-negative integer", 1
        (["--quick", "--seed", "abc"], "argument --seed: invalid int value"),  # was the usage block and the error
        (["--quick", "--repeats", "0"], "--repeats must be >= 1"),
        (["--quick", "--sections", ","], "--sections names no section"),  # ran every section
        (["--quick", "--hard-scenes", "5"], "--hard-scenes: counts the hard set's scenes"),  # ignored
        (["--quick", "--hard", "--sections", "cycle"], "--sections: the hard set (--hard) has no sections"),
    ],
)
def test_bench_refuses_a_bad_option_in_one_line_before_running(args, said, tmp_path):
    """An outside audit: flyopt bench's refusals were argparse's (the usage, then the error), a negative seed
    failed inside the run (exit 1, no option named), and options it did not use were dropped."""
    out = run("bench", *args, "--output-dir", tmp_path)  # were a refusal lost, a quick run into tmp_path
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert out.stderr.startswith("flyopt bench: error: ") and said in out.stderr, out.stderr


def test_unknown_option_of_a_command_is_refused():
    out = run("solve", PROBLEMS / "shear-press.toml", "--quick")
    assert out.returncode == 2 and "unrecognized arguments: --quick" in out.stderr
    assert "Traceback" not in out.stderr


# --------------------------------------------------------------------------
# stdout closed early: `flyopt solve ... | head`
# --------------------------------------------------------------------------


@pytest.mark.parametrize("args", [["solve"], ["solve", "--json"]])
def test_closed_stdout_exits_quietly_141(args):
    scene = PROBLEMS / "shear-press.toml"
    with subprocess.Popen(
        [sys.executable, "-m", "flyopt", args[0], str(scene), *args[1:]], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    ) as proc:
        proc.stdout.close()  # the reader is gone before a byte is written
        err = proc.stderr.read()
        proc.wait(timeout=120)
    assert proc.returncode == 141  # 128 + SIGPIPE, what the shell reports for `yes | head`
    assert err == b""  # no "Broken pipe", no traceback


def test_reader_that_stops_early_gets_the_start_of_the_report():
    scene = PROBLEMS / "shear-press.toml"
    with subprocess.Popen(
        [sys.executable, "-m", "flyopt", "solve", str(scene)], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    ) as proc:
        first = proc.stdout.readline()
        proc.stdout.close()
        err = proc.stderr.read()
        proc.wait(timeout=120)
    assert first.startswith(b"Shear press") and b"Traceback" not in err and b"Broken pipe" not in err
    assert proc.returncode in (0, 141)  # 0 when the whole report fit in the pipe before it closed


# --------------------------------------------------------------------------
# A machine that needs no flywheel
# --------------------------------------------------------------------------


def test_verify_a_machine_that_needs_no_flywheel():
    # conveyor: steady torques, A_max = 0 and no inertia at all; nothing fluctuates
    out = run("solve", PROBLEMS / "conveyor.toml", "--verify", "--json")
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr
    verification = json.loads(out.stdout)["verification"]
    assert verification["achieved_delta"] == 0.0 and verification["flagged"] is False


@pytest.mark.slow
def test_pareto_of_delta_on_a_motor_press_ends_where_no_flywheel_is_needed():
    """Regression (issue 11): the δ front of problems/motor-press.toml runs out to where the motor's slip alone
    holds δ and the dynamic model probes J_F ~ 1e-10 kg·m²; it failed after 50 s with "math domain error" and a
    traceback. The whole front is found. Its last point needs no flywheel: its δ is above the δ the machine
    reaches with a vanishing flywheel (quasi-static on the motor's curve, 0.5676 by the CVODES simulation), and
    every point with a flywheel lies below it. (The front once ran on to δ = 1 with flywheels of 1e-10
    kg·m², which the cubic's overshoot between grid nodes had asked for.) The light end is checked by the
    independent CVODES simulation."""
    from flyopt.machine.reduce import reduce
    from flyopt.sizing import periodic

    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "flyopt",
            "pareto",
            str(PROBLEMS / "motor-press.toml"),
            "--objectives",
            "mass,delta",
            "--json",
        ],
        capture_output=True,
        text=True,
        timeout=1800,
    )
    assert out.returncode == 0 and "Traceback" not in out.stderr, out.stderr[-2000:]
    front = json.loads(out.stdout)["rows"]  # the JSON document of the front: its rows
    delta = [row["delta"] for row in front]
    mass = [row["mass"] for row in front]
    assert all(b > a for a, b in zip(delta, delta[1:])) and all(b < a for a, b in zip(mass, mass[1:]))
    scene = flyopt.load(PROBLEMS / "motor-press.toml")
    machine = reduce(scene)
    vanishing = periodic.verify(
        machine.net_torque(), machine.j_machine, machine.cycle_angle, scene.omega_mean, 0.5, 1e-9, machine.knots()
    ).achieved_delta
    assert mass[-1] == 0 and delta[-1] >= vanishing
    assert all(m > 0 for m in mass[:-1]) and delta[-2] < vanishing
    scene = scene.replace(delta=delta[-2])
    solution = flyopt.solve(scene)
    assert solution.design.best.mass == pytest.approx(mass[-2], rel=1e-9)
    check = verify(scene, solution.analysis, solution.design)
    assert not check.flagged and check.achieved_delta == pytest.approx(delta[-2], rel=1e-5)


@pytest.mark.parametrize(
    ("scene", "changes", "status", "why"),
    [
        ("conveyor", {}, 0, "no flywheel needed"),  # steady torques: J_F = 0, nothing to trade
        ("punch-press", {'"1.2 m"': '"0.1 m"'}, 3, "no material and shaft"),  # no wheel fits a 0.1 m envelope
    ],
)
def test_an_empty_pareto_front_under_json_is_one_json_document(main_cli, write_scene, scene, changes, status, why):
    """flyopt pareto --json of a scene without a front: stdout is one JSON document (it was a line of text),
    which the output schema accepts: the front's two objectives, no rows, and why there are none; the exit
    status is the one the text gives (0 nothing to trade, 3 no design)."""
    import jsonschema

    from flyopt.outputs.documents import schema

    text = (PROBLEMS / f"{scene}.toml").read_text(encoding="utf-8")
    for old, new in changes.items():
        assert old in text
        text = text.replace(old, new)
    path = write_scene(text)
    said, words, _ = main_cli("pareto", path)
    assert said == status and why in words
    got, out, err = main_cli("pareto", path, "--json")
    assert got == status and err == ""
    document = json.loads(out)
    assert list(jsonschema.Draft202012Validator(schema()).iter_errors(document)) == []
    assert document["kind"] == "pareto" and document["objectives"] == ["mass", "outer_diameter"]
    assert document["rows"] == [] and why in document["message"]
    assert [c["name"] for c in document["columns"]] == ["mass", "outer_diameter"]
    assert document["units"] == {"mass": "kg", "outer_diameter": "m"}


@pytest.mark.parametrize("suffix", [".csv", ".parquet", ".json"])
def test_an_empty_pareto_front_is_written_to_the_file_asked_for_and_plot_says_it_has_no_rows(
    main_cli, tmp_path, suffix
):
    """flyopt pareto -o FILE of a scene without a front wrote nothing and left an earlier run's front in FILE,
    which flyopt plot then drew as this scene's. The file is written as a front with rows is, without rows and
    with the reason in its metadata; flyopt plot of it says so in one line (exit 2)."""
    import flyopt

    out = tmp_path / f"front{suffix}"
    out.write_text("an earlier run's front\n")
    status, stdout, stderr = main_cli("pareto", PROBLEMS / "conveyor.toml", "-o", out)
    assert status == 0 and stderr == "" and "no flywheel needed" in stdout and f"wrote {out}" in stdout
    if suffix == ".json":
        document = json.loads(out.read_text(encoding="utf-8"))
        assert document["rows"] == [] and "no flywheel needed" in document["message"]
        return
    back = flyopt.read_results(out)
    assert back.empty and list(back.columns) == ["mass", "outer_diameter"]
    assert "no flywheel needed" in back.attrs["flyopt"]["message"]
    status, stdout, stderr = main_cli("plot", out, "--what", "pareto", "-o", tmp_path / "front.png")
    assert status == 2 and stdout == "" and stderr.count("\n") == 1
    assert f"{out}: no rows to plot: no flywheel needed" in stderr
    assert not (tmp_path / "front.png").exists()


@pytest.mark.parametrize(
    "table, words",
    [
        (
            '[sweep]\nseed = -1\n[sweep.vary]\ndelta = "0.01:0.1:3"\n',
            "sweep.seed: must be a whole number from 0 to 9223372036854775807",
        ),
        ('[sweep.vary]\nspeed = "1500 m"\n', "sweep.vary.speed: '1500 m' has the wrong dimension"),
        ('[sweep.vary]\ndeltaa = "0.1,0.2"\n', "sweep.vary.deltaa: unknown sweep field"),
    ],
)
def test_check_refuses_the_sweep_table_that_sweep_refuses(tmp_path, capsys, table, words):
    path = tmp_path / "s.toml"
    path.write_text((PROBLEMS / "shear-press.toml").read_text() + "\n" + table)
    assert main(["sweep", str(path), "--no-progress"]) == 2
    from_sweep = capsys.readouterr().err
    assert main(["check", str(path)]) == 2
    from_check = capsys.readouterr()
    # the same error on the same line: check's FILE:LINE: field: message, sweep's one line of every command
    assert from_check.out == "" and from_check.err.count("\n") == 1
    assert re.match(rf"{re.escape(str(path))}:\d+: ", from_check.err)
    assert from_sweep == f"flyopt: error: {from_check.err}"
    assert words in from_check.err


def test_check_accepts_a_good_sweep_table(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text((PROBLEMS / "shear-press.toml").read_text() + '\n[sweep.vary]\ndelta = "0.01:0.1:3"\n')
    assert main(["check", str(path)]) == 0
    assert "ok" in capsys.readouterr().out


@pytest.mark.parametrize(
    "args, words",
    [
        (["--vary", "delta=0.1,0.2", "--vary", "delta=0.3"], "--vary delta: is varied twice"),
        (["--vary", "envelope=0.5,0.6m", "--vary", "design.max_outer_diameter=0.7m"], "is varied twice"),
        (
            ["--vary", "delta=0.1,0.2", "--seed", "-1", "--samples", "2"],
            "--seed: must be a whole number from 0 to 9223372036854775807",
        ),
    ],
)
def test_sweep_command_line_errors_name_the_option(capsys, args, words):
    assert main(["sweep", str(PROBLEMS / "shear-press.toml"), *args, "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err


def _keys(value):
    if isinstance(value, dict):
        return set(value) | set().union(*(_keys(v) for v in value.values()))
    if isinstance(value, list):
        return set().union(*(_keys(v) for v in value))
    return set()


def test_json_is_the_same_on_every_run_and_timings_only_when_asked():
    # by IPOPT every feasible combination of the punch press has a wall-clock time; the first run in a process of
    # its own, with its own hash seed (an order taken from a set would differ), the others in this one
    scene = PROBLEMS / "punch-press.toml"
    first, second = (
        process("solve", scene, "--json", "--design-method", "ipopt"),
        run("solve", scene, "--json", "--design-method", "ipopt"),
    )
    assert first.returncode == second.returncode == 0, first.stderr
    assert first.stdout == second.stdout
    assert "solve_time" not in _keys(json.loads(first.stdout))
    timed = run("solve", scene, "--json", "--design-method", "ipopt", "--timings")
    assert timed.returncode == 0, timed.stderr
    candidates = json.loads(timed.stdout)["design"]["candidates"]
    solved = [c for c in candidates if c["solver_status"]]
    assert "solve_time" in _keys(candidates) and solved and all(c["solve_time"] > 0 for c in solved)


# slow (the default run's five minutes): the default run reports the same title in process, where the tests'
# filterwarnings = error makes any warning a failure and stderr must be empty
# (tests/report/test_document.py::test_a_hostile_title_reaches_the_page_escaped_and_every_figure_is_drawn)
@pytest.mark.slow
@pytest.mark.parametrize("suffix", ["html", "pdf"])
def test_a_quiet_report_of_a_hostile_title_writes_nothing_to_stderr(tmp_path, suffix):
    # -q leaves only errors: a title of emoji and format characters put 30 "Glyph missing" warnings of
    # matplotlib on stderr (and "$\frac$" in it stopped the report with exit 1). Run as a user runs it, in
    # a fresh interpreter whose warnings are Python's defaults. (A control character, NUL, BEL or ESC, is
    # refused at load since 7e5fe3e: a title is one line of text; tests/io/test_names_one_line.py.)
    scene = tmp_path / "scene.toml"
    scene.write_text(
        'title = "a\\u200bb\\u2066c\\ue000d\\u202eevil \\U0001F525 \\u2603 $\\\\frac$"\n'
        '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n'
        '[torque.resisting]\npoints = [["0 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]\n'
        '[torque.driving]\nconstant = "unknown"\n',
        encoding="utf-8",
    )
    out = tmp_path / f"r.{suffix}"
    env = {**os.environ, "PYTHONWARNINGS": "", "MPLCONFIGDIR": str(tmp_path / "mpl")}
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "report", str(scene), "-o", str(out), "-q"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert (run.returncode, run.stderr, run.stdout) == (0, "", "")
    assert out.stat().st_size > 10_000


NEGATIVE_WORK = {
    # the load gives work over the whole cycle: the unknown driving constant came out -0.375 kN·m and the
    # report printed a motor power of -58.9 kW, divided by the efficiency as if the motor drove
    "torque.resisting": '[torque.resisting]\npoints = [["0 deg", "-1600 N*m"], ["90 deg", "-200 N*m"], '
    '["360 deg", "-200 N*m"]]\n[torque.driving]\nconstant = "unknown"\n',
    # a driving torque that takes work out: the resisting constant balancing it came out negative
    "torque.driving": '[torque.driving]\npoints = [["0 deg", "-1600 N*m"], ["90 deg", "-200 N*m"], '
    '["360 deg", "-200 N*m"]]\n[torque.resisting]\nconstant = "unknown"\n',
    "torque": '[torque.driving]\nconstant = "-100 N*m"\n[torque.resisting]\nconstant = "-100 N*m"\n',
}


@pytest.mark.parametrize("command", ["solve", "check"])
@pytest.mark.parametrize("field", sorted(NEGATIVE_WORK))
def test_a_cycle_of_negative_work_is_refused_in_one_line(field, command, main_cli, write_scene):
    scene = write_scene('title = "t"\n[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n' + NEGATIVE_WORK[field])
    status, out, err = main_cli(command, scene)
    assert status == 2 and out == ""
    assert err.count("\n") == 1
    assert f"{field}: the work per cycle is negative" in err
    assert "[torque.driving]" in err and "braking" in err


def test_a_load_that_gives_work_only_in_part_of_the_cycle_is_not_refused(main_cli, write_scene):
    # a return stroke that helps (negative resisting torque over part of the cycle) is an ordinary machine
    scene = write_scene(
        'title = "t"\n[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n'
        '[torque.resisting]\npoints = [["0 deg", "1600 N*m"], ["180 deg", "-200 N*m"], ["360 deg", "-200 N*m"]]\n'
        '[torque.driving]\nconstant = "unknown"\n'
    )
    status, out, err = main_cli("solve", scene, "--json")
    assert status == 0, err
    assert json.loads(out)["motor_power"] > 0


def test_sweep_prints_its_csv_in_the_units_asked_for_naming_them_and_files_stay_si(main_cli, tmp_path):
    """flyopt sweep --units (issue 29: pareto, tradeoff, sweep and the plots follow --units): the CSV on stdout
    in the system asked for, each quantity's unit in its column's name; 'input' gives the varied field in the
    unit it was given in; a file written with -o stays SI (its metadata names the units)."""
    import io

    import pandas as pd

    import flyopt

    scene, vary = PROBLEMS / "shear-press.toml", "speed=1000:2000:3rpm"
    status, out, _ = main_cli("sweep", scene, "--vary", vary, "--no-progress")
    assert status == 0
    si = pd.read_csv(io.StringIO(out))
    np_speed = [1000 * math.pi / 30, 1500 * math.pi / 30, 2000 * math.pi / 30]  # the grid, rad/s by hand
    assert si["speed"].tolist() == pytest.approx(np_speed, rel=1e-12)
    for units, speed, length in (("engineering", "rpm", ("mm", 1e3)), ("imperial", "rpm", ("in", 1 / 0.0254))):
        status, out, _ = main_cli("sweep", scene, "--vary", vary, "--units", units, "--no-progress")
        assert status == 0
        shown = pd.read_csv(io.StringIO(out))
        assert shown[f"speed [{speed}]"].tolist() == pytest.approx([1000, 1500, 2000], rel=1e-12)
        name = f"d_outer [{length[0]}]"
        assert shown[name].tolist() == pytest.approx((si["d_outer"] * length[1]).tolist(), rel=1e-12)
    status, out, _ = main_cli("sweep", scene, "--vary", vary, "--units", "input", "--no-progress")
    shown = pd.read_csv(io.StringIO(out))
    assert shown["speed [rpm]"].tolist() == pytest.approx([1000, 1500, 2000], rel=1e-12)
    assert shown["d_outer"].tolist() == pytest.approx(si["d_outer"].tolist(), rel=1e-15)  # the rest SI
    written = tmp_path / "s.csv"
    status, _, _ = main_cli("sweep", scene, "--vary", vary, "--units", "imperial", "-o", written, "--quiet")
    assert status == 0
    back = flyopt.read_results(written)
    assert back["speed"].tolist() == pytest.approx(np_speed, rel=1e-12) and "speed [rpm]" not in back


def test_a_sweep_of_one_speed_in_rpm_prints_it_as_given_and_counts_one_point(main_cli):
    """flyopt sweep --vary machine.speed=1500rpm --units engineering (issue: a reviewer's first run): the CSV's
    speed cell is the 1500 written, not 1500.0000000000002 (the round trip rad/s to rpm); a designed length
    keeps its figures (mm from m to 1e-15); the summary and the progress line count "1 point" ("1 points"),
    and "4 designs"."""
    import csv
    import io

    scene = PROBLEMS / "slider-crank-press.toml"
    status, out, err = main_cli("sweep", scene, "--vary", "machine.speed=1500rpm", "--units", "engineering")
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 1 and rows[0]["speed [rpm]"] == "1500.0"
    status, out_si, _ = main_cli("sweep", scene, "--vary", "machine.speed=1500rpm", "--no-progress")
    si = next(csv.DictReader(io.StringIO(out_si)))
    assert float(rows[0]["d_outer [mm]"]) == pytest.approx(float(si["d_outer"]) * 1e3, rel=1e-15, abs=0)
    summary = [line for line in err.splitlines() if line.startswith("flyopt sweep: done:")]
    assert len(summary) == 1 and summary[0].startswith("flyopt sweep: done: 1 point (1 designed,"), err
    designs = int(si["n_combinations"])  # every combination of the point designed
    assert f"; {designs} design{'s' if designs != 1 else ''} in " in summary[0], summary[0]
    assert re.search(r"\b1 points\b", err) is None and " 1/1 point (" in err, err


@pytest.mark.parametrize(("name", "json_words"), [("front.json", True), ("scene.toml", False)])
def test_a_results_diagram_of_a_file_that_is_not_results_says_what_it_reads(main_cli, tmp_path, name, json_words):
    """flyopt plot front.json --what pareto (pareto -o writes a JSON table, plot does not read it) said
    "--what: unknown diagram 'pareto'", a diagram it lists among its own."""
    path = tmp_path / name
    path.write_text("{}\n" if name.endswith(".json") else (PROBLEMS / "conveyor.toml").read_text(encoding="utf-8"))
    status, stdout, stderr = main_cli("plot", path, "--what", "pareto", "-o", tmp_path / "p.png")
    assert status == 2 and stdout == "" and stderr.count("\n") == 1
    assert f"{path}: --what pareto draws the results of flyopt sweep or pareto, a .csv or .parquet file" in stderr
    assert ("write them with -o FILE.csv" in stderr) == json_words and "unknown diagram" not in stderr


@pytest.mark.parametrize(
    "scene, args, said",
    [
        ("shear-press.toml", ["--timings"], "--timings: adds each design solve's time to the JSON"),
        ("shear-press.toml", ["--no-design", "--design-method", "ipopt"], "--design-method: chooses how"),
        ("textbook/seed-004-lathe-power.toml", ["--verify"], "--verify: "),
        ("textbook/seed-004-lathe-power.toml", ["--model", "dynamic"], "--model: "),
        ("textbook/seed-004-lathe-power.toml", ["--design-method", "ipopt"], "--design-method: "),
        ("textbook/seed-004-lathe-power.toml", ["--no-design"], "--no-design: "),
    ],
)
def test_solve_refuses_an_option_it_would_drop(scene, args, said, tmp_path):
    """An outside audit: these gave output byte-identical to the command without them (--verify on a
    calculation: the user expects a simulation and got none). With -o the file is left as it was (an outside
    review: the refusal, returned as exit status 2, emptied it and said "wrote")."""
    out = run("solve", PROBLEMS / scene, *args)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and said in out.stderr, out.stderr
    if "lathe" in scene:
        assert "is one calculation (power_chain)" in out.stderr
    assert out.stdout == ""
    kept = tmp_path / "kept.txt"
    kept.write_text("precious", encoding="utf-8")
    out = run("solve", PROBLEMS / scene, *args, "-o", kept)
    assert out.returncode == 2 and said in out.stderr and "wrote" not in out.stdout + out.stderr
    assert kept.read_text(encoding="utf-8") == "precious"


@pytest.mark.parametrize(
    "args, said",
    [
        (["--force"], "--force: replaces the file -o/--output names, which is not given"),
        (["-o", "scene.json"], "a scene is written as TOML, to a .toml file"),
    ],
)
def test_new_refuses_what_it_would_drop_or_misname(args, said, tmp_path, monkeypatch):
    """An outside audit: `new press --force` printed the template as without it, and `-o x.json` wrote TOML into a
    .json file (every other output checks its suffix)."""
    monkeypatch.chdir(tmp_path)
    out = run("new", "press", *args)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and said in out.stderr, out.stderr
    assert out.stdout == "" and list(tmp_path.iterdir()) == []


def test_check_writes_a_title_s_acting_characters_as_their_escapes(tmp_path):
    """An outside audit: check's "ok (TITLE)" printed a title's U+202E (right-to-left override, which turns
    the rest of the terminal's line around) and U+200B raw, where solve and report write their escapes."""
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    title = next(line for line in text.splitlines() if line.startswith("title = "))
    path = tmp_path / "bidi.toml"
    path.write_text(text.replace(title, 'title = "abc\\u202Edef\\u200Bghi"'), encoding="utf-8")
    out = run("check", path)
    assert out.returncode == 0, out.stderr
    assert "\u202e" not in out.stdout and "\u200b" not in out.stdout
    assert "ok (abc\\u202edef\\u200bghi)" in out.stdout
