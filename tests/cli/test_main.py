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


def test_a_key_with_a_terminal_escape_is_said_with_the_escape_shown_not_sent(tmp_path):
    """A key written "ge\\u001b[31mom" was echoed raw in the refusal: an ESC that starts a terminal sequence
    on the user's screen. Every refusal line shows such a character as its escape."""
    path = tmp_path / "scene.toml"
    path.write_text(
        '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.net]\nareas = [1, -1]\n[design]\n"ge\\u001b[31mom" = 3\n',
        encoding="utf-8",
    )
    for command in ("check", "solve"):
        run = subprocess.run([sys.executable, "-m", "flyopt", command, str(path)], capture_output=True, timeout=60)
        assert run.returncode == 2 and b"\x1b" not in run.stderr, run.stderr
        assert b"design.ge\\x1b[31mom: unknown key" in run.stderr, run.stderr


@pytest.mark.parametrize("command", [["new", "press"], ["solve", str(PROBLEMS / "shear-press.toml")]])
def test_an_output_that_ends_in_a_separator_names_a_folder_and_nothing_is_written(tmp_path, command):
    """`flyopt new press -o a/` wrote the template as the file `a`: a name ending in "/" is a folder's."""
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", *command, "-o", "a/"], capture_output=True, text=True, timeout=60, cwd=tmp_path
    )
    assert run.returncode == 2 and "'a/' names a folder" in run.stderr and len(run.stderr.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_closed_stdout_is_no_traceback(tmp_path):
    """`flyopt solve scene >&-` ended in AttributeError: 'NoneType' object has no attribute 'flush'."""
    shear = str(PROBLEMS / "shear-press.toml")
    run = subprocess.run(
        ["bash", "-c", f'"{sys.executable}" -m flyopt solve "{shear}" >&-'], capture_output=True, text=True, timeout=60
    )
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr


def test_a_character_beyond_16_bits_is_spelled_as_python_escapes_it():
    from flyopt.cli.console import fit_streams  # noqa: F401 (registers the handler)

    assert "φ ω \U0001f600 \u2202".encode("ascii", errors="flyopt.ascii") == b"phi omega \\U0001f600 \\u2202"


def test_an_output_named_dash_is_refused_not_written(tmp_path):
    """`flyopt new press -o -` wrote a file named "-" (an outside audit): read by many tools as stdout, it is
    refused here, saying how stdout is had."""
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "new", "press", "-o", "-"], capture_output=True, text=True, cwd=tmp_path
    )
    assert run.returncode == 2 and "'-' is no file's name" in run.stderr and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("option", [["--x", "speed"], ["--by", "material"]])
def test_a_scene_diagram_refuses_the_options_of_a_results_table(tmp_path, option):
    """`flyopt plot scene.toml --what energy --x speed` drew the energy diagram and ignored --x (an outside
    audit): the option chooses a results table's column, and is refused for a scene's diagram."""
    out = tmp_path / "e.png"
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "plot", str(PROBLEMS / "shear-press.toml"), "--what", "energy", *option]
        + ["-o", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert f"{option[0]}: choose the columns of a results table" in run.stderr and not out.exists()


@pytest.mark.parametrize(
    ("command", "name"),
    [
        (["new", "press"], "a\nb.toml"),
        (["solve", str(PROBLEMS / "shear-press.toml")], "r\tx.json"),
        (["sweep", str(PROBLEMS / "shear-press.toml"), "--vary", "machine.delta=0.01:0.1:3"], "s\x1b[31m.csv"),
        (["new", "press"], "a\u2028b.toml"),  # a line separator: splitlines() splits there
        (["new", "press"], "a\udc9bb.toml"),  # the byte 0x9b of a name that is no UTF-8: an 8-bit terminal's CSI
    ],
)
def test_an_output_with_a_control_character_is_refused(main_cli, tmp_path, monkeypatch, command, name):
    """`[sweep] output = "a\\nb.csv"` (and `-o` alike) wrote a file whose name was two lines, and said so in two."""
    monkeypatch.chdir(tmp_path)
    status, _out, err = main_cli(*command, "-o", name)
    assert status == 2 and "holds the control character" in err and len(err.splitlines()) == 1, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("folder", ["", "nowhere/"])
def test_an_output_name_longer_than_the_file_system_takes_is_refused_in_its_words(main_cli, tmp_path, folder):
    """`flyopt new press -o <300 characters>.toml` said the system's "File name too long", naming no option."""
    name = tmp_path / f"{folder}{'x' * 300}.toml"
    status, _out, err = main_cli("new", "press", "-o", name)
    assert status == 2 and err.startswith("flyopt: error: -o/--output: the file name 'xxx"), err
    assert "is 305 bytes long: the file system takes at most 255" in err and len(err.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_a_sweep_output_whose_parts_folder_would_be_too_long_is_refused(main_cli, tmp_path, monkeypatch):
    """A 251-byte table name fits, but its `.parts` folder (257 bytes) did not: the sweep ended in the system's
    "File name too long" after the folder's name, not the option's."""
    monkeypatch.chdir(tmp_path)
    name = "x" * 247 + ".csv"
    status, _out, err = main_cli(
        "sweep", PROBLEMS / "shear-press.toml", "--vary", "machine.delta=0.01:0.1:3", "-o", name
    )
    assert status == 2 and err.startswith("flyopt: error: --output: the file name 'xxx"), err
    assert "is 257 bytes long with the '.parts' flyopt writes beside it" in err
    assert list(tmp_path.iterdir()) == []
