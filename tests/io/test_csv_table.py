"""Tables from CSV files (``points_file``, a member's ``force_file``, ...) next to the scene (issue 12).

A CSV table gives the same curve, analysis and JSON as the same table written
inline, and every malformed CSV is refused with exit status 2 and one line
naming the scene, the field, the CSV file, the line and what is allowed.
"""

import json
import re

import numpy as np
import pytest
import tomllib
from conftest import PROBLEMS, ROOT, names_field, run_flyopt

import flyopt
from flyopt.io import csv_table

BASE = """
title = "t"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
angle_unit = "deg"
unit = "kN*m"
{table}
[torque.driving]
constant = "unknown"
"""

ROWS = [(0, 1.6), (45, 1.6), (90, 0.2), (90, 0.25), (200.5, 0.3), (360, 0.2)]
"""A resisting torque [deg, kN*m] with a vertical step at 90 deg."""


def inline(rows):
    return "points = [" + ", ".join(f"[{a!r}, {t!r}]" for a, t in rows) + "]"


def write(tmp_path, csv_text, table='points_file = "torque.csv"', name="scene.toml"):
    (tmp_path / "torque.csv").write_bytes(csv_text.encode("utf-8") if isinstance(csv_text, str) else csv_text)
    path = tmp_path / name
    path.write_text(BASE.format(table=table), encoding="utf-8")
    return path


def cli(*args, cwd=ROOT):
    return run_flyopt(*args, cwd=cwd)


def without_names(data):
    """The JSON of a solve without what names the scene (its file and title) and wall-clock times."""
    if isinstance(data, dict):
        return {k: without_names(v) for k, v in data.items() if k not in ("scene", "title", "solve_time")}
    if isinstance(data, list):
        return [without_names(v) for v in data]
    return data


# -- the same table, inline or from a file -------------------------------------------


@pytest.mark.parametrize(
    "csv_text",
    [
        "angle,torque\n" + "".join(f"{a},{t}\n" for a, t in ROWS),  # a header
        "".join(f"{a},{t}\n" for a, t in ROWS),  # none
        "angle [deg];torque, kN*m\r\n" + "".join(f"{a} , {t}\r\n" for a, t in ROWS),  # CRLF, blanks, a header with ;
        "# measured 2024\n\nangle,torque\n" + "".join(f"{a},{t}\n\n" for a, t in ROWS) + "# end\n",
        "".join(f"{a},{t}\n" for a, t in ROWS).rstrip("\n"),  # no newline at the end
        "\ufeffangle,torque\n" + "".join(f"{a},{t}\n" for a, t in ROWS),  # Excel's byte-order mark
    ],
)
def test_a_csv_table_is_the_inline_table(tmp_path, csv_text):
    from_file = flyopt.load(write(tmp_path, csv_text))
    written = flyopt.from_dict(tomllib.loads(BASE.format(table=inline(ROWS))))
    assert np.array_equal(from_file.resisting.angles, written.resisting.angles)
    assert np.array_equal(from_file.resisting.values, written.resisting.values)
    assert from_file.resisting.values[1] == 1600.0 and from_file.resisting.angles[-1] == 2 * np.pi
    a, b = flyopt.analyse(from_file).to_dict(), flyopt.analyse(written).to_dict()
    assert without_names(a) == without_names(b)


def test_the_problem_scene_from_csv_gives_the_inline_scenes_json():
    """problems/four-stroke-engine-csv.toml is four-stroke-engine.toml with its table in a CSV file."""
    runs = [
        cli("solve", PROBLEMS / name, "--json") for name in ("four-stroke-engine.toml", "four-stroke-engine-csv.toml")
    ]
    assert all(r.returncode == 0 for r in runs), [r.stderr for r in runs]
    inline_json, csv_json = (json.loads(r.stdout) for r in runs)
    assert csv_json["a_max"] > 0 and csv_json["design"]["status"] == "designed"
    assert without_names(inline_json) == without_names(csv_json)


def test_the_path_is_relative_to_the_scene_file_not_the_working_directory(tmp_path):
    sub = tmp_path / "scenes"
    sub.mkdir()
    path = write(sub, "".join(f"{a},{t}\n" for a, t in ROWS))
    run = cli("solve", path.relative_to(tmp_path), "--json", "--no-design", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["a_max"] == flyopt.analyse(flyopt.load(path)).a_max


def test_a_member_force_table_from_csv_is_the_inline_table(tmp_path):
    """engine-members.toml's gas force on the piston, moved to a CSV file: the same reduced machine."""
    text = (PROBLEMS / "engine-members.toml").read_text(encoding="utf-8")
    start = text.index("force = [")
    end = text.index("]\n", text.index("\n]", start)) + 2
    rows = tomllib.loads(text)["member"][0]["force"]
    (tmp_path / "gas.csv").write_text("angle,force\n" + "".join(f"{a!r},{f!r}\n" for a, f in rows))
    path = tmp_path / "engine.toml"
    path.write_text(text[:start] + 'force_file = "gas.csv"\n' + text[end:], encoding="utf-8")
    from_file, written = flyopt.load(path), flyopt.load(PROBLEMS / "engine-members.toml")
    (a0, f0), (a1, f1) = from_file.members[0].force, written.members[0].force
    assert np.array_equal(a0, a1) and np.array_equal(f0, f1) and len(a0) == len(rows) > 100
    assert without_names(flyopt.analyse(from_file).to_dict()) == without_names(flyopt.analyse(written).to_dict())


def test_the_fast_reading_gives_what_the_line_by_line_reading_gives():
    """A clean file is read in one pass over its fields; the line-by-line reader is the reference."""
    rng = np.random.default_rng(7)
    angles = np.sort(rng.uniform(0, 360, 500))
    values = rng.normal(0, 1e4, 500)
    for text in (
        "a,b\n" + "".join(f"{a!r},{v!r}\n" for a, v in zip(angles.tolist(), values.tolist())),
        "".join(f"{a:.3f}, {v:.6e}\r\n" for a, v in zip(angles, values)),
        "".join(f"{a!r},{v!r}\n" for a, v in zip(angles.tolist(), values.tolist())) + "\n\n  \n",
    ):
        fast, lines = csv_table.read_csv(text, "f", "t.csv", ("angle", "torque"), ("deg", "N*m"))
        slow, slow_lines = csv_table.read_csv_lines(text.split("\n"), "f", "t.csv", ("angle", "torque"), ("deg", "N*m"))
        assert isinstance(lines, range)  # the one-pass reading took it
        assert np.array_equal(fast, slow) and list(lines) == list(slow_lines)


# -- malformed files: exit 2, one line ------------------------------------------------


def assert_refused(run, scene, match):
    """Exit 2, nothing on stdout, one line naming the scene, the field and the CSV file, no traceback."""
    assert "Traceback" not in run.stderr, run.stderr[-2000:]
    assert run.returncode == 2, (run.returncode, run.stderr[-2000:])
    assert run.stdout == ""
    lines = run.stderr.splitlines()
    assert len(lines) == 1, run.stderr
    line = lines[0]
    assert names_field(line, scene, "torque.resisting.points_file"), line
    assert re.search(match, line), line


GOOD = "".join(f"{a},{t}\n" for a, t in ROWS)


@pytest.mark.parametrize(
    "csv_text, match",
    [
        (
            "0,1.6\n45\n90,0.2\n360,0.2\n",
            r"torque\.csv line 2: expected 2 columns, angle and torque separated by a comma, got 1: '45'",
        ),
        ("0,1.6,7\n360,0.2\n", r"torque\.csv line 1: expected 2 columns.*got 3"),
        ("0;1.6\n360;0.2\n", r"torque\.csv line 1: expected 2 columns, angle and torque separated by a comma"),
        (
            "angle,torque\n0,1.6\n45,1.6 kN*m\n360,0.2\n",
            r"torque\.csv line 3, column 2: '1\.6 kN\*m' is not a number \(allowed: a plain number, the torque in kN\*m\)",
        ),
        (
            "0,1.6\nforty,1.6\n360,0.2\n",
            r"torque\.csv line 2, column 1: 'forty' is not a number \(allowed: a plain number, the angle in deg\)",
        ),
        (
            "angle,torque\n0,1.6\n",
            r"torque\.csv: a table needs at least two rows of angle,torque .*only line 2 holds one",
        ),
        ("angle,torque\n", r"torque\.csv: a table needs at least two rows .*there is none"),
        ("", r"torque\.csv: a table needs at least two rows .*there is none"),
        (
            "0,1.6\n90,0.2\n45,1.6\n360,0.2\n",
            r"torque\.csv line 3: angles must not decrease: 45 deg comes after 90 deg on line 2",
        ),
        (
            "0,1.6\n90,0.2\n90,0.3\n90,0.4\n360,0.2\n",
            r"torque\.csv line 3: three rows at one angle \(90 deg, lines 2 to 4\); a vertical step is exactly two rows",
        ),
        (
            "0,1.6\n90,0.2\n350,0.2\n",
            r"torque\.csv lines 1 to 3: the table covers 0 to 350 deg but the cycle is 0 to 360 deg: the cycle does not close",
        ),
        ("0,1.6\n90,nan\n360,0.2\n", r"torque\.csv line 2, column 2: 'nan' is not finite"),
        ("0,1.6\n90,1e999\n360,0.2\n", r"torque\.csv line 2, column 2: '1e999' is not finite"),
        (b"0,1.6\n\xff\xfe,2\n", r"cannot read .*torque\.csv: not UTF-8 text"),
    ],
)
def test_a_malformed_csv_is_refused_in_one_line(tmp_path, csv_text, match):
    path = write(tmp_path, csv_text)
    for command in ("check", "solve"):
        assert_refused(cli(command, path), path, match)


def test_a_file_that_does_not_exist_is_refused_in_one_line(tmp_path):
    path = write(tmp_path, GOOD, table='points_file = "missing.csv"')
    assert_refused(cli("solve", path), path, r"cannot read .*missing\.csv: No such file or directory")
    path = write(tmp_path, GOOD, table='points_file = "."')
    assert_refused(cli("solve", path), path, r"cannot read .*: Is a directory")


@pytest.mark.parametrize(
    "table, field, match",
    [
        ("points_file = 3", "torque.resisting.points_file", r"must be the name of a CSV file \(a string\), got 3"),
        (
            'points_file = "torque.csv"\npoints = [[0, 1], [360, 1]]',
            "torque.resisting",
            r"give exactly one of points, points_file, constant, expression or motor \(the torque is given twice: "
            r"points, points_file\)",
        ),
    ],
)
def test_points_file_field_errors(tmp_path, table, field, match):
    path = write(tmp_path, GOOD, table=table)
    run = cli("check", path)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert names_field(run.stderr, path, field) and re.search(match, run.stderr), run.stderr


def test_a_member_table_given_twice_is_refused(tmp_path):
    text = (PROBLEMS / "engine-members.toml").read_text(encoding="utf-8")
    (tmp_path / "gas.csv").write_text("0,0\n720,0\n")
    path = tmp_path / "engine.toml"
    path.write_text(text.replace('\nforce_sense = "axial"', '\nforce_sense = "axial"\nforce_file = "gas.csv"'))
    run = cli("check", path)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert "member[0].force_file: give either force or force_file, not both" in run.stderr


def test_a_member_csv_error_names_the_member_field_and_line(tmp_path):
    text = (PROBLEMS / "slider-crank-press.toml").read_text(encoding="utf-8")
    assert "force = [" in text
    start = text.index("force = [")
    end = text.index("]]", start) + 2
    (tmp_path / "ram.csv").write_text("angle,force\n0,0\n140,x\n360,0\n")
    path = tmp_path / "press.toml"
    path.write_text(text[:start] + 'force_file = "ram.csv"' + text[end:], encoding="utf-8")
    run = cli("check", path)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert re.search(
        r"member\[\d\]\.force_file: .*ram\.csv line 3, column 2: 'x' is not a number "
        r"\(allowed: a plain number, the force in kN\)",
        run.stderr,
    ), run.stderr


def test_the_header_test_finds_a_letter_as_str_isalpha_does():
    """The header's letter test (upper and lower cases compared for ASCII) against Python's own ``isalpha`` of
    each character: every ASCII character alone and among digits, and non-ASCII letters and digits."""
    from flyopt.io.csv_table import _has_letter

    samples = [chr(k) for k in range(128)] + [f"0,{chr(k)}1.5" for k in range(128)]
    samples += ["angle,torque", "0,1.5", "", "1e5,2E-3", "φ,M", "٣,٤", "0,1\u00b5", "ß", "0,\u0301", "Ⅻ,1"]
    for text in samples:
        assert _has_letter(text) == any(c.isalpha() for c in text), repr(text)
