"""An electric drive reduced to the motor shaft ([electric_drive], issue 27 item 9): the seed 004 examples.

References: the published answers of ../shared/seeds/004 at their rounding; the equal-kinetic-
energy reduction and the accelerating torque written again from the shafts' speeds and powers
(½ J ω_M² = Σ ½ J_k ω_k²; the motor supplies Σ J_k ω_k α_k / η_path,k to accelerate them).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import jsonschema
import pytest

import flyopt
from flyopt.errors import SceneError
from flyopt.io.scene import from_dict
from flyopt.outputs.documents import calculation_document, json_text, schema
from flyopt.pipeline import solve_calculation
from flyopt.units import G_STANDARD

TEXTBOOK = Path(__file__).resolve().parent.parent / "problems" / "textbook"
RPM = math.pi / 30


def test_seed_004_lathe_drive():
    drive = solve_calculation(flyopt.load(TEXTBOOK / "seed-004-lathe-drive.toml"))
    assert round(drive.load_power / 1e3, 3) == 3.796  # the text: 3.796 kW
    assert round(drive.motor_power / 1e3, 3) == 5.207  # 5.207 kW
    assert round(drive.gd2_with_losses, 3) == 4.769  # 4.769 N·m²
    # the text's 10.17 N·m is 4.769 · 800 / 375; flyopt's 4 g · 60 / 2π is 374.7 (g = 9.81)
    assert round(drive.gd2_with_losses * 800 / 375, 2) == 10.17
    assert drive.accelerating_torque == pytest.approx(drive.gd2_with_losses / (4 * G_STANDARD) * 800 * RPM, rel=1e-14)
    # independent: accelerating each shaft's J_k = GD²_k/(4 g) at α_k = α_M / (j_1 ⋯ j_k) through its losses
    alpha = 800 * RPM
    shafts = [(3.5, 1.0, 1.0), (2.0, 2.0, 0.9), (2.7, 3.0, 0.81), (9.0, 6.0, 0.729)]  # GD², j to the motor, η path
    power = sum(g / (4 * G_STANDARD) * (1450 * RPM / j) * (alpha / j) / eta for g, j, eta in shafts)
    assert drive.accelerating_torque == pytest.approx(power / (1450 * RPM), rel=1e-12)


def test_seed_004_two_stage_drive():
    drive = solve_calculation(flyopt.load(TEXTBOOK / "seed-004-hoist-drive.toml"))
    assert round(drive.load_torque_at_motor, 2) == 6.15  # the text: 6.15 N·m
    # equal kinetic energy at the shafts' own speeds
    omega = [2450 * RPM, 810 * RPM, 150 * RPM]
    energy = sum(0.5 * g / (4 * G_STANDARD) * w**2 for g, w in zip((14.7, 18.8, 120.0), omega))
    assert 0.5 * drive.inertia_total * omega[0] ** 2 == pytest.approx(energy, rel=1e-13)
    assert drive.accelerating_torque is None and drive.motor_torque is None


def test_the_json_is_its_own_kind_and_meets_the_schema():
    drive = solve_calculation(flyopt.load(TEXTBOOK / "seed-004-lathe-drive.toml"))
    document = json.loads(json_text(calculation_document("electric_drive", "t", "s.toml", drive.to_dict())))
    assert [e.message for e in jsonschema.Draft202012Validator(schema()).iter_errors(document)] == []
    assert document["units"]["motor_acceleration"] == "rad/s**2" and document["units"]["gd2_total"] == "N*m**2"


BASE = {"machine": {"speed": "1450 rpm"}}
STAGE = {"ratio": 2, "efficiency": 0.9, "gd2": "2 N*m^2"}


@pytest.mark.parametrize(
    ("section", "field", "words"),
    [
        ({"stages": []}, "electric_drive.stages", "1 to"),
        ({"stages": [{"efficiency": 0.9}]}, "electric_drive.stages[0].ratio", "exactly one"),
        ({"stages": [{**STAGE, "speed": "10 rpm"}]}, "electric_drive.stages[0].ratio", "exactly one"),
        ({"stages": [{**STAGE, "efficiency": 1.2}]}, "electric_drive.stages[0].efficiency", "(0, 1]"),
        ({"stages": [{**STAGE, "ratio": -2}]}, "electric_drive.stages[0].ratio", "positive"),
        ({"stages": [{**STAGE, "inertia": "1 kg*m^2"}]}, "electric_drive.stages[0].inertia", "not both"),
        ({"stages": [STAGE], "load_force": "1 kN"}, "electric_drive.load_radius", "is needed"),
        ({"stages": [STAGE], "load_torque": "1 N*m", "load_force": "1 kN"}, "electric_drive.load_force", "not both"),
        ({"stages": [STAGE], "acceleration": "800 rpm"}, "electric_drive.acceleration", ""),
        # a GD² or an inertia is held to the sizes of every other (flyopt.units.MAGNITUDES): the drive's own
        # range had no lower end, so 1e-300 was read
        ({"stages": [{**STAGE, "gd2": "1e-300 N*m^2"}]}, "electric_drive.stages[0].gd2", "4e-08 to 4e+13"),
        (
            {"stages": [{"ratio": 2, "efficiency": 0.9, "inertia": "1e-300 kg*m^2"}]},
            "electric_drive.stages[0].inertia",
            "1e-09 to 1e+12",
        ),
        ({"stages": [STAGE], "motor_inertia": "1e15 kg*m^2"}, "electric_drive.motor_inertia", "1e-09 to 1e+12"),
    ],
)
def test_bad_drive_is_refused_in_one_line(section, field, words):
    with pytest.raises(SceneError) as err:
        from_dict({**BASE, "electric_drive": section})
    assert err.value.field == field and words in str(err.value)


def test_a_drive_beside_a_cycle_is_refused():
    with pytest.raises(SceneError) as err:
        from_dict({**BASE, "electric_drive": {"stages": [STAGE]}, "torque": {"net": {"areas": ["1 J", "-1 J"]}}})
    assert err.value.field == "electric_drive" and "[torque]" in str(err.value)
