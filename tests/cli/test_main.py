"""flyopt.cli.main: the one argparse tree; a bad option is one line, exit status 2 (issue 25, item 9).

argparse's own ``error`` prints the whole usage block (5 to 7 lines for the
commands with many options) before the one line that matters.
"""

import subprocess
import sys

import pytest
from conftest import PROBLEMS

SCENE = str(PROBLEMS / "punch-press.toml")
WHEEL = str(PROBLEMS / "punch-press-wheel.toml")


@pytest.mark.parametrize(
    "args, says",
    [
        (["solve", SCENE, "--units", "furlongs"], "argument --units: invalid choice: 'furlongs'"),
        (["sweep", SCENE, "--vary", "delta=0.01:0.1", "--samples", "0"], "--samples"),
        (["pareto", WHEEL, "--points", "-5"], "--points"),
        (["pareto", WHEEL, "--range", "-1:0.5m"], "write a value that starts with '-' as --option=VALUE"),
        (["frobnicate", SCENE], "invalid choice: 'frobnicate'"),
        ([], "the following arguments are required: COMMAND"),
        (["solve", SCENE, "--no-such-option"], "unrecognized arguments: --no-such-option"),
    ],
)
def test_a_bad_option_is_one_line_with_exit_status_2(args, says):
    run = subprocess.run([sys.executable, "-m", "flyopt", *args], capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert run.stdout == ""
    lines = run.stderr.splitlines()
    assert len(lines) == 1, run.stderr
    assert lines[0].startswith("flyopt") and ": error: " in lines[0] and says in lines[0], lines[0]
    assert "usage:" not in run.stderr


@pytest.mark.parametrize("encoding", ["ascii", "latin-1"])
def test_a_console_that_cannot_show_the_symbols_gets_them_in_ascii(encoding):
    """A console without UTF-8 (LC_ALL=C in a container, PYTHONIOENCODING=ascii) ended every report in
    "'ascii' codec can't encode character '\\xb7'", exit 1. What it cannot show is spelled in ASCII."""
    import os

    env = {**os.environ, "PYTHONIOENCODING": encoding}
    shear = str(PROBLEMS / "shear-press.toml")
    run = subprocess.run([sys.executable, "-m", "flyopt", "solve", shear], capture_output=True, timeout=120, env=env)
    assert run.returncode == 0, run.stderr[-2000:]
    text = run.stdout.decode(encoding)  # all of it in the console's encoding
    assert "Answer: cast steel rim, 12.81 kg, on the motor shaft" in text
    if encoding == "ascii":
        assert "1.018 kg*m^2 on its shaft" in text and "allowed delta" in text and "\\u" not in text, text
    else:  # latin-1 has the middle dot and the square: only what it lacks is spelled
        assert "1.018 kg·m² on its shaft" in text and "allowed delta" in text, text
    bad = subprocess.run(
        [sys.executable, "-m", "flyopt", "check", str(PROBLEMS / "no-such.toml")], capture_output=True, env=env
    )
    assert bad.returncode == 2 and len(bad.stderr.decode(encoding).splitlines()) == 1
