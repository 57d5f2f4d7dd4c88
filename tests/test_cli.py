"""The command line as a user runs it: output, JSON fields, exit codes, one-line errors."""

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from conftest import PROBLEMS, assert_published
from flyopt.cli.main import main

JSON_FIELDS = {"a_max", "work_per_cycle", "driving_torque", "resisting_torque", "power", "omega_mean",
               "omega_max", "omega_min", "angle_omega_max", "angle_omega_min", "j_required",
               "flywheel_needed", "energy_chain", "shafts", "motor_power"}


def run(*args):
    return subprocess.run([sys.executable, "-m", "flyopt", *map(str, args)], capture_output=True, text=True,
                          timeout=120)


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
    for words in ("A_max", "1,256.33 J", "kg·m²", "72.6493 kW", "Energy indicator diagram", "ω_min"):
        assert words in out.stdout


def test_check_ok(capsys):
    assert main(["check", str(PROBLEMS / "compressor.toml")]) == 0
    assert "ok" in capsys.readouterr().out


@pytest.mark.parametrize("text, words", [
    ('[machine]\nspeed = "1500 m"\ndelta = 0.05\n[torque.net]\nareas = [1, -1]\n', "machine.speed: '1500 m' has the wrong dimension"),
    ('[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.net]\nareas = [1, -2]\n', "torque: non-periodic fluctuation"),
    ('[machine]\nspeed = "1500 rpm"\ndelta = 3\n[torque.net]\nareas = [1, -1]\n', "machine.delta: must lie between 0 and 2"),
    ('[machine\n', "not valid TOML"),
])
@pytest.mark.parametrize("command", ["solve", "check"])
def test_bad_input_is_one_line_exit_2_no_traceback(tmp_path, text, words, command):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    out = run(command, path, "--json") if command == "solve" else run(command, path)
    assert out.returncode == 2
    assert out.stdout == ""                       # nothing half-written
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in out.stderr
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
    out = subprocess.run([exe, "solve", str(PROBLEMS / "example1-net-areas.toml"), "--json"],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0
    assert math.isclose(json.loads(out.stdout)["a_max"], 1600.0)
