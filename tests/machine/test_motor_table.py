"""A motor given by its torque–speed table, inline or from a CSV file (issue 12).

The reference: a table whose rows lie on an induction motor's linear line (or
a DC motor's line) is that same function, so the dynamic model must give the
analysis of the parametric motor; the CSV file gives the inline table's
analysis exactly; a malformed table is refused in one line naming the file
and the line.
"""

import json
import math
import re

import casadi as ca
import numpy as np
import pytest
from conftest import PROBLEMS, run_flyopt, unplaced
from numpy.testing import assert_allclose

import flyopt
from flyopt.machine.motor import DCMotor, InductionMotor, TableMotor

RPM = math.pi / 30
MOTOR_PRESS = (PROBLEMS / "motor-press.toml").read_text(encoding="utf-8")
INDUCTION_LINE = next(line for line in MOTOR_PRESS.splitlines() if line.startswith("motor = {"))
INDUCTION = InductionMotor(5500.0, 1440 * RPM, 1500 * RPM)


def scene_with(tmp_path, motor, csv_text=None, name="press.toml"):
    if csv_text is not None:
        (tmp_path / "motor.csv").write_text(csv_text, encoding="utf-8")
    path = tmp_path / name
    path.write_text(MOTOR_PRESS.replace(INDUCTION_LINE, motor), encoding="utf-8")
    return path


def line_rows(rpms):
    """Rows [rpm, N*m] on the induction motor's linear line (exact within round-off)."""
    return [(r, float(INDUCTION.torque(r * RPM))) for r in rpms]


def inline_motor(rows):
    points = ", ".join(f"[{a!r}, {t!r}]" for a, t in rows)
    return f'motor = {{ kind = "table", speed_unit = "rpm", unit = "N*m", shaft = "motor", points = [{points}] }}'


def solve_json(path, *options):
    run = run_flyopt("solve", str(path), "--json", *options)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def test_a_table_on_the_induction_line_is_the_induction_motor(tmp_path):
    """Four rows on the line, the last beyond synchronous speed (the generator side): the same machine."""
    rows = line_rows([0.0, 700.0, 1500.0, 1600.0])
    assert rows[2][1] == 0.0 and rows[3][1] < 0
    table = flyopt.analyse(flyopt.load(scene_with(tmp_path, inline_motor(rows))))
    reference = flyopt.analyse(flyopt.load(PROBLEMS / "motor-press.toml"))
    assert table.model == reference.model == "dynamic"
    for name in ("j_required", "omega_mean", "omega_max", "omega_min", "a_max", "power"):
        assert_allclose(getattr(table, name), getattr(reference, name), rtol=1e-9, err_msg=name)


def test_a_table_on_the_dc_line_is_the_dc_motor_start_up_included(tmp_path):
    dc = 'motor = { kind = "dc", no_load_speed = "1500 rpm", stall_torque = "120 N*m", shaft = "motor" }'
    table = inline_motor([(0.0, 120.0), (1500.0, 0.0)])
    a = flyopt.analyse(flyopt.load(scene_with(tmp_path, dc, name="dc.toml")), extras=("startup",))
    b = flyopt.analyse(flyopt.load(scene_with(tmp_path, table, name="table.toml")), extras=("startup",))
    for name in ("j_required", "omega_mean", "omega_max", "omega_min"):
        assert_allclose(getattr(b, name), getattr(a, name), rtol=1e-9, err_msg=name)
    assert_allclose(b.startup.time, a.startup.time, rtol=1e-6)
    assert b.startup.method.endswith("the motor's torque-speed table")


def test_a_csv_motor_table_is_the_inline_table(tmp_path):
    rows = line_rows([0.0, 300.0, 900.0, 1440.0, 1500.0, 1550.0])
    csv = "speed [rpm],torque [N*m]\n" + "".join(f"{a!r},{t!r}\n" for a, t in rows)
    from_file = scene_with(
        tmp_path,
        'motor = { kind = "table", speed_unit = "rpm", unit = "N*m", shaft = "motor", points_file = "motor.csv" }',
        csv,
        name="file.toml",
    )
    written = scene_with(tmp_path, inline_motor(rows), name="inline.toml")
    a, b = solve_json(from_file, "--no-design"), solve_json(written, "--no-design")
    a.pop("scene"), b.pop("scene")
    assert a == b


def test_the_table_is_one_expression_for_numpy_and_casadi():
    motor = TableMotor([0.0, 50.0, 140.0, 157.0], [300.0, 280.0, 120.0, -10.0])
    w = np.array([-5.0, 0.0, 25.0, 50.0, 100.0, 140.0, 150.0, 157.0, 170.0])
    expected = np.interp(w, motor.speeds, motor.torques)
    expected[0] = 300.0 + 5.0 * 20.0 / 50.0  # the first segment, extended
    expected[-1] = -10.0 + 13.0 * (-130.0 / 17.0)  # the last segment, extended
    assert_allclose(motor.torque(w), expected, rtol=1e-13, atol=1e-12)
    x = ca.SX.sym("w")
    f = ca.Function("f", [x], [motor.torque(x)])
    assert_allclose([float(f(v)) for v in w], motor.torque(w), rtol=1e-15, atol=1e-12)
    assert motor.no_load_speed == pytest.approx(140.0 + 17.0 * 120.0 / 130.0, rel=1e-15)
    assert motor.largest_torque == 300.0 and motor.stall_torque == 300.0


def test_a_motor_too_weak_for_the_load_is_refused(tmp_path):
    path = scene_with(tmp_path, inline_motor([(0.0, 20.0), (1500.0, 0.0)]))
    run = run_flyopt("check", str(path))
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert "torque.driving: the motor's largest torque on the reference shaft" in run.stderr
    assert "(the largest of its table), is below the mean load" in run.stderr


FILE_MOTOR = 'motor = { kind = "table", speed_unit = "rpm", unit = "N*m", shaft = "motor", points_file = "motor.csv" }'


@pytest.mark.parametrize(
    "csv_text, match",
    [
        (
            "speed,torque\n0,900\n1600,500\n1500,0\n",
            r"speeds must increase: .*motor\.csv line 4 \(157\.08 rad/s\) comes after 167\.552 rad/s",
        ),
        (
            "0,900\n1500,0\n1500,-5\n",
            r"speeds must increase: .*motor\.csv line 3 \(157\.08 rad/s\) comes after 157\.08 rad/s",
        ),
        (
            "0,900\n100,800\n",
            r"the torque at the last row \(.*motor\.csv line 2, 10\.472 rad/s\) is 800 N\*m: the table "
            r"must reach the motor's no-load speed",
        ),
        (
            "speed,torque\n0,900\n",
            r"a table needs at least two rows of speed,torque \(the first at rest\); only line 2",
        ),
        ("0,900\n1500\n", r"motor\.csv line 2: expected 2 columns, speed and torque separated by a comma, got 1"),
        (
            "0,900\n1500,zero\n",
            r"motor\.csv line 2, column 2: 'zero' is not a number \(allowed: a plain number, "
            r"the torque in N\*m\)",
        ),
        ("10,900\n1500,0\n", r"the table starts at 1\.0472 rad/s \(.*motor\.csv line 1\); it must start at rest"),
        (
            "0,900\n1500,-10\n1600,0\n",
            r"the torque rises over the last segment \(.*motor\.csv line 2 to "
            r".*motor\.csv line 3\)",
        ),
    ],
)
def test_a_malformed_motor_table_is_refused_in_one_line(tmp_path, csv_text, match):
    path = scene_with(tmp_path, FILE_MOTOR, csv_text)
    run = run_flyopt("solve", str(path))
    assert "Traceback" not in run.stderr
    assert run.returncode == 2 and run.stdout == "" and len(run.stderr.splitlines()) == 1, run.stderr
    assert unplaced(run.stderr, path).startswith(f"flyopt: error: {path}: torque.driving.motor.points_file: "), (
        run.stderr
    )
    assert re.search(match, run.stderr), run.stderr


def test_a_missing_motor_file_and_both_forms_are_refused(tmp_path):
    path = scene_with(tmp_path, FILE_MOTOR)
    run = run_flyopt("check", str(path))
    assert run.returncode == 2 and "motor.csv: No such file or directory" in run.stderr, run.stderr
    both = FILE_MOTOR.replace(" }", ", points = [[0, 900], [1500, 0]] }")
    run = run_flyopt("check", str(scene_with(tmp_path, both)))
    assert run.returncode == 2 and "torque.driving.motor: a motor table needs exactly one of points" in run.stderr


def test_table_motor_refuses_what_is_not_a_curve():
    with pytest.raises(ValueError, match="starts at rest"):
        TableMotor([1.0, 2.0], [5.0, 0.0])
    with pytest.raises(ValueError, match="must increase"):
        TableMotor([0.0, 2.0, 2.0], [5.0, 1.0, 0.0])
    with pytest.raises(ValueError, match="no-load speed"):
        TableMotor([0.0, 2.0], [5.0, 1.0])
    assert DCMotor(10.0, 5.0).torque(2.0) == TableMotor([0.0, 10.0], [5.0, 0.0]).torque(2.0)
