"""One operation, not a cycle ([operation], issue 27 item 5): Khurmi & Gupta 16.21, the riveting machine.

The published answers at the book's rounding and the energy balance written out by hand.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import jsonschema
import pytest
from conftest import run_flyopt

import flyopt
from flyopt.errors import SceneError
from flyopt.io.scene import from_dict
from flyopt.outputs.documents import calculation_document, json_text, schema
from flyopt.pipeline import solve, solve_operation

SCENE = Path(__file__).resolve().parent.parent / "problems" / "textbook" / "khurmi-16-21.toml"
RPM = math.pi / 30


def test_khurmi_16_21_speed_after_a_rivet_and_rivets_a_minute():
    result = solve_operation(flyopt.load(SCENE))
    assert round(result.omega_after / RPM, 1) == 257.6  # the book: 257.6 rpm
    assert round(60 * result.operation_rate) == 18  # the book: 18 rivets a minute
    j = 150 * 0.6**2
    omega2 = math.sqrt((300 * RPM) ** 2 - 2 * (10e3 - 3e3 * 1.0) / j)  # ½ J (ω₁² − ω₂²) = E − P τ
    assert result.omega_after == pytest.approx(omega2, rel=1e-14)
    assert result.recovery_time == pytest.approx(7e3 / 3e3, rel=1e-14)
    assert result.shortest_interval == pytest.approx(10e3 / 3e3, rel=1e-14)  # τ + t_r = E / P
    assert result.delta == pytest.approx((300 * RPM - omega2) / ((300 * RPM + omega2) / 2), rel=1e-14)


def test_the_json_is_its_own_kind_and_meets_the_schema():
    document = json.loads(
        json_text(calculation_document("operation", "t", str(SCENE), solve_operation(flyopt.load(SCENE)).to_dict()))
    )
    assert document["kind"] == "operation"
    assert [e.message for e in jsonschema.Draft202012Validator(schema()).iter_errors(document)] == []
    assert set(document["units"]) >= {"omega_after", "recovery_time", "operation_rate"}


def test_a_speed_beyond_delta_exits_4_and_a_cycle_solve_is_refused(tmp_path):
    scene = tmp_path / "tight.toml"
    scene.write_text(SCENE.read_text().replace('speed = "300 rpm"', 'speed = "300 rpm"\ndelta = 0.1'))
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 4 and "does NOT hold" in run.stdout
    with pytest.raises(SceneError) as err:
        solve(flyopt.load(SCENE))
    assert err.value.field == "operation"


BASE = {"machine": {"speed": "300 rpm"}, "flywheel": {"inertia": "54 kg*m^2"}}
GOOD = {"energy": "10 kJ", "duration": "1 s", "motor_power": "3 kW"}


@pytest.mark.parametrize(
    ("changes", "field", "words"),
    [
        ({"operation": {**GOOD, "energy": "-1 kJ"}}, "operation.energy", "positive"),
        ({"operation": {**GOOD, "duration": "1 m"}}, "operation.duration", "time"),
        ({"operation": {"energy": "10 kJ", "duration": "1 s"}}, "operation.motor_power", ""),
        ({"operation": GOOD, "flywheel": None}, "operation", "[flywheel]"),
        ({"operation": GOOD, "torque": {"net": {"areas": ["1 J", "-1 J"]}}}, "operation", "[torque]"),
        ({"operation": GOOD, "design": {}}, "operation", "[design]"),
    ],
)
def test_bad_operation_is_refused_in_one_line(changes, field, words):
    data = {k: v for k, v in {**BASE, **changes}.items() if v is not None}
    with pytest.raises(SceneError) as err:
        from_dict(data)
    assert err.value.field == field and words in str(err.value)


def test_a_flywheel_too_small_for_the_operation_is_refused(tmp_path):
    scene = tmp_path / "stall.toml"
    scene.write_text(SCENE.read_text().replace('mass = "150 kg"', 'mass = "1 kg"'))
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 2 and "would stop" in run.stderr and len(run.stderr.strip().splitlines()) == 1
