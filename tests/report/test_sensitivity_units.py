"""The sensitivities of the mass in the reader's units (issue 29: units that drift between and within outputs).

Was: ``flyopt solve --units imperial`` wrote every quantity in lb, in and psi but the sensitivities as the
design wrote them, "+10 mm of outer diameter changes the mass by -1.14 kg". The step is the design's in the
reader's unit rounded to one figure (10 mm is 0.4 in, 1 MPa 100 psi). The references are the design's own
multipliers (``dmass_dlimit``) converted by the exact definitions of the units here: 1 in = 0.0254 m, 1 lb =
0.45359237 kg, 1 psi = 1 lbf/in² with 1 lbf = 0.45359237 kg × 9.80665 m/s².
"""

import re

import pytest
from conftest import PROBLEMS

LB = 0.45359237
INCH = 0.0254
PSI = LB * 9.80665 / INCH**2


@pytest.fixture(scope="module")
def press_arms_wheel():
    """(the design's sensitivities, {units: the text's sensitivity lines}) of press-arms-wheel, solved once: its
    envelope, its arms' stress, its inertia and δ bind."""
    import flyopt
    from flyopt.report.text import wheel_report

    solution = flyopt.solve(flyopt.load(PROBLEMS / "press-arms-wheel.toml"))
    best = solution.design.best
    lines = {}
    for units in ("engineering", "imperial"):
        text = "\n".join(wheel_report(best, solution.analysis.omega_max, units))
        block = text.split("How the mass moves with each limit (first order):\n", 1)[1].split("\n\n", 1)[0]
        lines[units] = [line[4:] for line in block.splitlines()]
    return [dict(e) for e in best.limits.sensitivities], lines


def _figures(value, digits=4):
    return float(f"{value:.{digits - 1}e}")


def test_imperial_sensitivities_are_in_inches_pounds_and_psi(press_arms_wheel):
    entries, lines = press_arms_wheel
    by_limit = {e["limit"]: e for e in entries}
    assert {"max_outer_diameter", "stress_arms", "inertia", "delta"} <= set(by_limit)
    assert len(lines["imperial"]) == len(entries)
    said = dict(zip([e["limit"] for e in entries], lines["imperial"]))
    assert not any(re.search(r"\d (kg|mm|MPa|m/s)\b", line) for line in lines["imperial"]), lines["imperial"]
    envelope = by_limit["max_outer_diameter"]
    # 10 mm of outer diameter is 0.3937 in: quoted as 0.4 in, its mass change in lb from the multiplier
    shown = re.search(
        r": \+([\d.]+) in of outer diameter changes the mass by ([-+][\d.,]+) lb$", said["max_outer_diameter"]
    )
    assert shown, said["max_outer_diameter"]
    assert float(shown.group(1)) == 0.4
    assert float(shown.group(2).replace(",", "")) == _figures(envelope["dmass_dlimit"] * 0.4 * INCH / LB)
    stress = re.search(r": \+([\d.,]+) psi allowable changes the mass by ([-+][\d.,]+) lb$", said["stress_arms"])
    assert stress, said["stress_arms"]
    assert float(stress.group(1).replace(",", "")) == 100.0  # 1 MPa is 145.04 psi
    assert float(stress.group(2)) == _figures(by_limit["stress_arms"]["dmass_dlimit"] * 100 * PSI / LB)
    delta = re.search(r"changes the mass by ([-+][\d.,]+) lb \(central", said["delta"])
    assert delta and float(delta.group(1)) == _figures(by_limit["delta"]["dmass_dlimit"] * 0.01 / LB)


def test_engineering_quotes_the_designs_own_step_with_four_figures(press_arms_wheel):
    """In engineering units the step is the design's (+10 mm, +1 MPa) and the mass's change its multiplier
    times that step, to the report's four figures, where the results' ``text`` gives three."""
    entries, lines = press_arms_wheel
    assert len(lines["engineering"]) == len(entries)
    steps = {"max_outer_diameter": ("+10 mm", 0.010), "stress_arms": ("+1 MPa", 1e6), "delta": ("+0.01", 0.01)}
    for entry, line in zip(entries, lines["engineering"]):
        mass = re.search(r"(?:by|adds) ([-+][\d.,]+) kg", line)
        assert mass, line
        if entry["limit"] in steps:
            words, step = steps[entry["limit"]]
            assert words in line and float(mass.group(1)) == _figures(entry["dmass_dlimit"] * step), line


@pytest.fixture(scope="module")
def shaft_check():
    """punch-press-shaft's check of its described shaft, solved once."""
    import flyopt

    (report,) = flyopt.solve(flyopt.load(PROBLEMS / "punch-press-shaft.toml")).shaft_checks
    return report


@pytest.mark.parametrize("units, label, per", [("engineering", "kg", 1.0), ("imperial", "lb", LB)])
def test_a_shafts_binding_limit_moves_per_the_readers_unit_of_mass(shaft_check, units, label, per):
    """Was: "d(utilisation)/d(wheel mass) 0.000295 per kg" in the imperial text and report alike (two copies of
    the sentence). Now per lb there: the shaft's d(utilisation)/d(m) [1/kg] times the kilograms of a pound."""
    from flyopt.report.shaft import shaft_report

    report = shaft_check
    (line,) = [line for line in shaft_report([report], units) if "d(utilisation)/d(wheel mass)" in line]
    shown = re.search(rf"d\(utilisation\)/d\(wheel mass\) ([\d.e+-]+) per {label}$", line)
    assert shown, line
    assert float(shown.group(1)) == float(f"{report.sensitivity * per:.2e}")
