"""A study (sweep, Pareto front, trade-off) designs wheels alone on the machine the scene gives: it refuses what
would change that machine, or a scene whose answer is no wheel designed alone, in one line; where it runs, a
point is the design ``flyopt solve`` gives for the scene edited to that point (a second path, not the sweep's)."""

import json

import pytest
from conftest import PROBLEMS

from flyopt import read_results

MOTOR_PRESS = (PROBLEMS / "motor-press.toml").read_text(encoding="utf-8")


def _refused(status, out, err):
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def test_the_ratio_of_the_motors_shaft_is_not_swept(main_cli, tmp_path):
    """motor-press's motor reaches the crank through the motor shaft's ratio (M(i ω) i η): a sweep of that ratio
    analysed the scene's own ratio at every point and reported designs its scene does not give (17.55 kg where
    solve gives 15.64 kg at a ratio of 31.6)."""
    out = tmp_path / "r.parquet"
    line = _refused(
        *main_cli("sweep", PROBLEMS / "motor-press.toml", "--vary", "shaft.motor.speed_ratio=1:1e6:log5", "-o", out)
    )
    assert "--vary shaft.motor.speed_ratio: shaft 'motor' carries the motor" in line
    assert "[drive] ratios" in line
    assert list(tmp_path.iterdir()) == []


def test_the_ratio_of_a_bare_shaft_swept_on_a_motor_driven_press_is_solve_at_each_ratio(main_cli, write_scene):
    scene = MOTOR_PRESS.replace(
        '[[shaft]]\nname = "motor"',
        '[[shaft]]\nname = "intermediate"\nspeed_ratio = 6.0\n\n[[shaft]]\nname = "motor"',
    ).replace("[design]\n", '[design]\nshafts = ["intermediate"]\n')
    assert scene.count('name = "intermediate"') == 1 and 'shafts = ["intermediate"]' in scene
    swept = write_scene(scene, "swept.toml")
    out = swept.parent / "s.csv"
    status, _, err = main_cli("sweep", swept, "--vary", "shaft.intermediate.speed_ratio=4,8", "-o", out, "-q")
    assert status == 0, err
    frame = read_results(out)
    for ratio in (4, 8):
        path = write_scene(scene.replace("speed_ratio = 6.0", f"speed_ratio = {ratio}.0"), f"r{ratio}.toml")
        status, text, err = main_cli("solve", path, "--json")
        assert status == 0, err
        design = json.loads(text)["design"]
        (row,) = frame[frame["shaft.intermediate.speed_ratio"] == ratio].itertuples()
        assert row.status == "designed" and row.best_shaft == "intermediate"
        assert row.mass == pytest.approx(design["mass"], rel=1e-9)
        assert row.j_required == pytest.approx(json.loads(text)["j_required"], rel=1e-9)


def _with_existing_wheel(text):
    """shear-press with a wheel that exists on a shaft of its own (and no [design]: the wheel is given)."""
    text = text[: text.index("[design]")]
    return text + '[[shaft]]\nname = "slow"\nspeed_ratio = 0.5\n\n[flywheel]\ninertia = "0.5 kg*m^2"\nshaft = "slow"\n'


@pytest.mark.parametrize(
    "command",
    [["sweep", "--vary", "delta=0.01:0.02:2"], ["pareto"], ["tradeoff"]],
    ids=["sweep", "pareto", "tradeoff"],
)
def test_a_study_of_a_wheel_that_exists_or_of_a_drive_is_refused(main_cli, write_scene, command):
    """A study designed a wheel as if the scene gave neither: for a [flywheel] that exists a new wheel of the
    whole J_F, the wheel given left out; for press-drive every point infeasible at the crank, where solve designs
    the motor, its ratio and the wheel together."""
    given = write_scene(_with_existing_wheel((PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")))
    status, _, err = main_cli("solve", given)
    assert status == 4, err  # the scene itself is sound: solve analyses the wheel given (0.125 kg m^2 falls short)
    line = _refused(*main_cli(command[0], given, *command[1:]))
    assert "flywheel: gives a flywheel that exists" in line and "remove [flywheel] to design one" in line
    line = _refused(*main_cli(command[0], PROBLEMS / "press-drive.toml", *command[1:]))
    assert "drive: designs the motor, its ratio and the wheel together" in line
    assert "flyopt pareto --objectives mass,motor_power" in line


def test_the_torque_scale_of_a_motor_driven_scene_is_refused_before_a_point(main_cli):
    """It stopped at the first point with "torque.scale: cannot scale a torque of type MotorTorque" (no --vary,
    and a class's name)."""
    line = _refused(*main_cli("sweep", PROBLEMS / "motor-press.toml", "--vary", "torque.scale=1,2"))
    assert line.startswith("flyopt: error: --vary torque.scale: scales the scene's torque tables and expressions")
    assert "its driving torque is a motor's characteristic, which depends on speed" in line
    assert "MotorTorque" not in line


def test_a_shaft_diameter_outside_the_size_factors_fit_is_quoted_as_a_number(main_cli, write_scene):
    """The message ended "got array(1.e-06)"."""
    text = (PROBLEMS / "punch-press-shaft.toml").read_text(encoding="utf-8")
    old = 'segments = [{ to = "120 mm", diameter = "60 mm" }'
    assert old in text
    path = write_scene(text.replace(old, 'segments = [{ to = "120 mm", diameter = "0.001 mm" }'))
    line = _refused(*main_cli("check", path))
    assert line.endswith("diameter [m] must lie within Shigley's Eq. (6-20), 0.00279 to 0.254 m, got 1e-06")
