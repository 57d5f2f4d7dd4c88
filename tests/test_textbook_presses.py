"""Presses stated in the book's terms (issue 27, item 4): Khurmi & Gupta 16.19 and 16.22 in problems/textbook/.

The published answers at the book's rounding, and the closed forms written out in each scene's
header comment (the flywheel supplies the stroke's energy less what the motor gives during the
punch, m = 2 A_max / (k² (ω1² − ω2²))).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import flyopt
from flyopt.errors import SceneError
from flyopt.io.scene import from_dict

TEXTBOOK = Path(__file__).resolve().parent.parent / "problems" / "textbook"
RPM = math.pi / 30


def _solve(name):
    return flyopt.solve(flyopt.load(TEXTBOOK / name))


def test_khurmi_16_19_motor_and_flywheel():
    solution = _solve("khurmi-16-19.toml")
    assert round(solution.analysis.motor_power / 1e3, 1) == 3.0  # the book: 3 kW
    mass = solution.design.best.mass
    assert round(mass) == 618  # the book: 618 kg
    a_max = 15e3 * (1 - 2 / 5)
    assert solution.analysis.a_max == pytest.approx(a_max, rel=1e-12)
    assert mass == pytest.approx(2 * a_max / (0.5**2 * ((225 * RPM) ** 2 - (200 * RPM) ** 2)), rel=1e-9)


def test_khurmi_16_22_energy_per_sheared_area():
    solution = _solve("khurmi-16-22.toml")
    energy = 6e6 * math.pi * 0.040 * 0.015  # 6 J/mm² over the sheared area π d t
    assert solution.analysis.work_per_cycle == pytest.approx(energy, rel=1e-12)
    a_max = energy * (1 - 0.1 / 2)
    assert solution.analysis.a_max == pytest.approx(a_max, rel=1e-12)
    mass = solution.design.best.mass
    assert round(mass) == 327  # the book: 327 kg
    assert mass == pytest.approx(2 * a_max / (1.0**2 * ((160 * RPM) ** 2 - (140 * RPM) ** 2)), rel=1e-9)


PRESS = {
    "strokes_per_minute": 30,
    "working_time": "0.1 s",
    "flywheel_speed": "160 rpm",
    "flywheel_speed_min": "140 rpm",
}


@pytest.mark.parametrize(
    ("changes", "field", "words"),
    [
        (
            {"punching": {"thickness": "15 mm", "hole_diameter": "40 mm"}},
            "press.punching.shear_strength",
            "exactly one",
        ),
        (
            {
                "punching": {
                    "thickness": "15 mm",
                    "hole_diameter": "40 mm",
                    "shear_strength": "300 MPa",
                    "energy_per_area": "6 J/mm^2",
                }
            },
            "press.punching.energy_per_area",
            "exactly one",
        ),
        (
            {"punching": {"thickness": "15 mm", "hole_diameter": "40 mm", "energy_per_area": "-6 J/mm^2"}},
            "press.punching.energy_per_area",
            "positive",
        ),
        (
            {"punching": {"thickness": "15 mm", "hole_diameter": "40 mm", "energy_per_area": "6 J"}},
            "press.punching.energy_per_area",
            "",
        ),
        ({"energy_per_stroke": "1 kJ", "strokes_per_hour": 720}, "press.strokes_per_hour", "exactly one"),
        ({"energy_per_stroke": "1 kJ", "working_time": None, "stroke": "100 mm"}, "press.stroke", "punching"),
        (
            {
                "punching": {"thickness": "15 mm", "hole_diameter": "40 mm", "energy_per_area": "6 J/mm^2"},
                "working_time": None,
                "stroke": "5 mm",
            },
            "press.stroke",
            "clear the plate",
        ),
        (
            {
                "punching": {"thickness": "15 mm", "hole_diameter": "40 mm", "energy_per_area": "6 J/mm^2"},
                "stroke": "100 mm",
            },
            "press.stroke",
            "exactly one",
        ),
        (
            {"energy_per_stroke": "1 kJ", "strokes_per_minute": None, "strokes_per_hour": 0},
            "press.strokes_per_hour",
            "positive",
        ),
    ],
)
def test_bad_press_data_is_refused_in_one_line(changes, field, words):
    press = {**PRESS, **changes}
    press = {k: v for k, v in press.items() if v is not None}
    with pytest.raises(SceneError) as err:
        from_dict({"press": press})
    assert err.value.field == field and words in str(err.value)


def test_khurmi_16_20_punching_time_from_the_punch_stroke():
    solution = _solve("khurmi-16-20.toml")
    energy = 7e6 * math.pi * 0.038 * 0.032  # 7 J/mm² over the sheared area π d t
    assert solution.analysis.power == pytest.approx(energy / 10.0, rel=1e-12)  # one hole every 10 s
    assert round(solution.analysis.power / 1e3, 3) == 2.674
    a_max = energy * (1 - 0.032 / (2 * 0.100))  # punching t/(2 s) of the period
    assert solution.analysis.a_max == pytest.approx(a_max, rel=1e-12)
    # design.rim_speed = 25 m/s pins D_m = 2 v / ω_m, so the thin rim's m = J ω_m² / v² = A_max / (v² δ): the book's
    best = solution.design.best
    assert best.mass == pytest.approx(a_max / (25.0**2 * 0.03), rel=1e-9)
    assert best.dims.d_mean * solution.analysis.omega_mean * best.speed_ratio / 2 == pytest.approx(25.0, rel=1e-12)
    assert round(a_max / (25.0**2 * 0.03)) == 1198


@pytest.mark.parametrize(
    ("punching", "field"),
    [
        ({"thickness": 1e-300, "hole_diameter": "40 mm", "energy_per_area": "6 J/mm^2"}, "press.punching.thickness"),
        (
            {"thickness": "15 mm", "hole_diameter": "1e9 m", "energy_per_area": "6 J/mm^2"},
            "press.punching.hole_diameter",
        ),
        (
            {"thickness": "15 mm", "hole_diameter": "40 mm", "energy_per_area": "1e-300 J/m^2"},
            "press.punching.energy_per_area",
        ),
        ({"thickness": "0.001 mm", "cut_length": "0.001 mm", "energy_per_area": "0.001 J/m^2"}, "press.punching"),
    ],
)
def test_a_punch_too_small_or_too_large_is_refused_in_words(punching, field):
    """The hostile corpus found it: a plate 1e-300 m thick made a stroke of no energy and the designer failed
    inside; every length, strength and energy of a press is bounded, and so is the stroke's energy."""
    with pytest.raises(SceneError) as err:
        from_dict({"press": {**PRESS, "punching": punching}})
    assert err.value.field == field and "out of range" in str(err.value)


_SCENE = {"machine": {"speed": "120 rpm", "delta": 0.05}, "torque": {"net": {"areas": ["10 kJ", "-10 kJ"]}}}


@pytest.mark.parametrize(
    ("design", "field", "words"),
    [
        ({"geometry": "rim", "radius_of_gyration": "0.5 m"}, "design.radius_of_gyration", 'geometry = "thin_rim"'),
        ({"radius_of_gyration": "0.5 m"}, "design.radius_of_gyration", 'geometry = "thin_rim"'),
        (
            {"geometry": "thin_rim", "radius_of_gyration": "0.5 m", "d_mean": "1 m"},
            "design.radius_of_gyration",
            "give one of them",
        ),
        ({"geometry": "thin_rim", "radius_of_gyration": "-1 m"}, "design.radius_of_gyration", "positive"),
        ({"geometry": "thin_rim", "rim_speed": "0 m/s"}, "design.rim_speed", "positive"),
        ({"geometry": "thin_rim", "rim_speed": "1e9 m/s"}, "design.rim_speed", "out of range"),
        ({"geometry": "thin_rim", "rim_speed": "25 m/s", "d_mean": "1 m"}, "design", "give one of them"),
        ({"geometry": "disc", "rim_speed": "25 m/s"}, "design", "bare rim"),
        ({"geometry": "rim", "rim_speed": "25 m/s", "criterion": "stress"}, "design", "give d_mean"),
    ],
)
def test_a_flywheel_by_its_radius_of_gyration_or_rim_speed_is_refused_in_words(design, field, words):
    with pytest.raises(SceneError) as err:
        from_dict({**_SCENE, "design": design})
    assert err.value.field == field and words in str(err.value)


def test_a_rim_speed_pins_each_shafts_mean_diameter_and_a_radius_of_gyration_the_mass():
    """v = 25 m/s at the mean speed of each shaft: D_m = 2 v / (ω_m i), so every shaft needs the same thin-rim mass,
    m = A_max / (v² δ); k = 0.5 m gives m = J_F / k²."""
    shafts = [{"name": "main", "speed_ratio": 1.0}, {"name": "fast", "speed_ratio": 3.0}]
    scene = from_dict(
        {**_SCENE, "shaft": shafts, "design": {"geometry": "thin_rim", "rim_speed": "25 m/s", "hb_ratio": 0.5}}
    )
    solution = flyopt.solve(scene)
    a_max, omega = 10e3, 120 * RPM
    designs = [c for c in solution.design.candidates if c.feasible]
    assert {c.shaft for c in designs} == {"main", "fast"}
    for c in designs:
        assert c.dims.d_mean == pytest.approx(2 * 25.0 / (omega * c.speed_ratio), rel=1e-12)
        assert c.mass == pytest.approx(a_max / (25.0**2 * 0.05), rel=1e-9)
    by_k = flyopt.solve(from_dict({**_SCENE, "design": {"geometry": "thin_rim", "radius_of_gyration": "0.5 m"}}))
    assert by_k.design.best.mass == pytest.approx(a_max / (omega**2 * 0.05) / 0.5**2, rel=1e-9)
