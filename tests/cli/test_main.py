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
