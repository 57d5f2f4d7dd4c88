"""A machine in the courses' energy terms (issue 27, item 2): [energy] (power and C_E) and [strokes].

References: closed forms written out here (the work per cycle P Φ/ω, the triangles' crossings
with the mean torque), and a published solution that is off, with why.
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


def test_khurmi_16_3_power_and_coefficient_of_fluctuation_of_energy():
    solution = flyopt.solve(flyopt.load(TEXTBOOK / "khurmi-16-3.toml"))
    omega = 90 * RPM
    work = 300e3 * 2 * math.pi / omega  # 200 kJ a turn
    assert solution.analysis.work_per_cycle == pytest.approx(work, rel=1e-12)
    assert solution.analysis.power == pytest.approx(300e3, rel=1e-12)
    assert solution.analysis.a_max == pytest.approx(0.1 * work, rel=1e-12)
    mass = solution.design.best.mass
    assert mass == pytest.approx(0.1 * work / (2.0**2 * omega**2 * 0.01), rel=1e-9)
    assert round(mass) == 5629
    # the published solution's 5495.84 kg is the same formula with ω rounded to 9.5 rad/s, W to
    # 198.42 kN·m and ΔE to 19.84 kN·m, as it writes them
    work_rounded = round(300 / 9.5 * 2 * math.pi, 2)
    assert work_rounded == 198.42
    swing_rounded = round(0.1 * work_rounded, 2) * 1e3
    assert round(swing_rounded / (2.0**2 * 9.5**2 * 0.01), 2) == 5495.84


def _triangles_reference(works, omega, delta):
    """A_max, the angles of the lowest and highest ΔE, J_F for strokes drawn as triangles against the mean torque."""
    mean = math.fsum(works) / (len(works) * math.pi)
    # ΔE at the crossings: only the positive triangle rises above the mean (the others are below zero)
    k = max(range(len(works)), key=lambda i: works[i])
    peak = 2 * works[k] / math.pi
    half = math.pi / 2
    x = half * mean / peak  # the crossing's distance from the stroke's start (and end)
    up, down = k * math.pi + x, (k + 1) * math.pi - x

    def excess(phi):  # ∫0^φ (M - mean)
        total = 0.0
        for i, w in enumerate(works):
            a, b = i * math.pi, (i + 1) * math.pi
            if phi <= a:
                break
            t = min(phi, b) - a
            height = 2 * w / math.pi
            rise = min(t, half)
            total += 0.5 * rise * height * rise / half
            if t > half:
                fall = t - half
                total += fall * height - 0.5 * fall * height * fall / half
        return total - mean * phi

    a_max = excess(down) - excess(up)
    return a_max, up, down, a_max / (omega**2 * delta)


def test_four_triangles_against_the_closed_form():
    solution = flyopt.solve(flyopt.load(TEXTBOOK / "four-triangles.toml"))
    a_max, low, high, j = _triangles_reference([-1050.0, -4200.0, 10650.0, -1500.0], 200 * RPM, 0.04)
    analysis = solution.analysis
    assert analysis.a_max == pytest.approx(a_max, rel=1e-12)
    assert analysis.angle_omega_min == pytest.approx(low, rel=1e-12)
    assert analysis.angle_omega_max == pytest.approx(high, rel=1e-12)
    assert analysis.j_required == pytest.approx(j, rel=1e-12)
    assert solution.design.best.mass == pytest.approx(j / 0.75**2, rel=1e-9)  # thin rim, k = 0.75 m


def test_strokes_as_multiples_of_the_cycles_work():
    """20 kW at 300 rpm, four-stroke, expansion three times compression, triangles, ±2 %: the same
    engine as energies (W = 20 kW · 4π / ω = 8 kJ: compression −4 kJ, expansion +12 kJ)."""
    base = {"machine": {"speed": "300 rpm", "delta": 0.04}}
    multiples = from_dict({**base, "strokes": {"work": [0, -0.5, 1.5, 0], "power": "20 kW"}})
    energies = from_dict({**base, "strokes": {"work": ["0 J", "-4 kJ", "12 kJ", "0 J"]}})
    a, b = flyopt.solve(multiples, design_flywheel=False), flyopt.solve(energies, design_flywheel=False)
    assert a.analysis.a_max == pytest.approx(b.analysis.a_max, rel=1e-12)
    a_max, _, _, j = _triangles_reference([0.0, -4000.0, 12000.0, 0.0], 300 * RPM, 0.04)
    assert a.analysis.j_required == pytest.approx(j, rel=1e-12)


def test_rectangles():
    scene = from_dict(
        {"machine": {"speed": "100 rpm", "delta": 0.05}, "strokes": {"work": ["3 kJ", "-1 kJ"], "shape": "rectangle"}}
    )
    analysis = flyopt.solve(scene, design_flywheel=False).analysis
    # torque 3000/π then -1000/π against the mean 2000/(2π): ΔE rises by (3000 - 1000) over the first half turn
    assert analysis.a_max == pytest.approx(2000.0, rel=1e-12)
    assert math.degrees(analysis.cycle_angle) == pytest.approx(360.0, rel=1e-15)


BASE = {"machine": {"speed": "100 rpm", "delta": 0.05}}


@pytest.mark.parametrize(
    ("extra", "field", "words"),
    [
        ({"energy": {"fluctuation": 0.1}}, "energy.power", "is needed"),
        (
            {"energy": {"power": "1 kW", "work_per_cycle": "1 kJ", "fluctuation": 0.1}},
            "energy.work_per_cycle",
            "not both",
        ),
        ({"energy": {"power": "1 kW", "fluctuation": -0.1}}, "energy.fluctuation", "positive"),
        ({"energy": {"power": "-1 kW", "fluctuation": 0.1}}, "energy.power", "positive"),
        ({"energy": {"power": "1 kW", "fluctuation": 0.1}, "torque": {}}, "energy", "[torque]"),
        ({"energy": {"power": "1 kW", "fluctuation": 0.1}, "strokes": {}}, "strokes", "not both"),
        ({"strokes": {"work": ["1 kJ"]}}, "strokes.work", "2 to"),
        ({"strokes": {"work": ["1 kJ", 0.5]}}, "strokes.work", "every one"),
        ({"strokes": {"work": [0.5, 0.6], "power": "1 kW"}}, "strokes.work", "add to 1"),
        ({"strokes": {"work": [0.5, 0.5]}}, "strokes.power", "is needed"),
        ({"strokes": {"work": ["-1 kJ", "-1 kJ"]}}, "strokes.work", "positive work"),
        ({"strokes": {"work": ["1 kJ", "1 kJ"], "power": "1 kW"}}, "strokes.power", "only for"),
        ({"strokes": {"work": ["1 kJ", "1 kJ"], "shape": "circle"}}, "strokes.shape", "not known"),
    ],
)
def test_bad_energy_terms_are_refused_in_one_line(extra, field, words):
    with pytest.raises(SceneError) as err:
        from_dict({**BASE, **extra})
    assert err.value.field == field and words in str(err.value)


def test_a_cycle_that_disagrees_with_the_strokes_is_refused():
    with pytest.raises(SceneError) as err:
        from_dict(
            {"machine": {"speed": "100 rpm", "delta": 0.05, "cycle": "360 deg"}, "strokes": {"work": ["1 kJ"] * 4}}
        )
    assert err.value.field == "machine.cycle" and "720" in str(err.value)


@pytest.mark.parametrize(
    "machine",
    [
        {"speed": "1e9 rpm"},
        {"speed": "1e-9 rpm"},
        {"speed": -5},
        {"speed": "0 rpm"},
        {"speed": "fast"},
        {"speed": "1500 kg"},
        {"cycle": "-1 deg"},
        {"cycle": "0 deg"},
        {"speed": "1e9 rpm", "cycle": "-1 deg"},  # both wrong: the loader names the speed first
    ],
)
def test_the_machines_speed_and_cycle_are_refused_as_any_scene_refuses_them(machine):
    """[energy] reads machine.speed and machine.cycle (W = P Φ / ω_m) by the loader's own reading: the same
    field and the same words as a scene of torque curves with the same [machine] (its speed's range
    included, which the energy terms once left to the loader after they had used the speed)."""
    machine = {"speed": "100 rpm", "delta": 0.05, **machine}
    refusals = []
    for rest in ({"energy": {"power": "1 kW", "fluctuation": 0.1}}, {"torque": {"net": {"areas": ["1 kJ", "-1 kJ"]}}}):
        with pytest.raises(SceneError) as err:
            from_dict({"machine": machine, **rest})
        refusals.append((err.value.field, str(err.value)))
    assert refusals[0] == refusals[1]
