"""``flyopt solve --units si|engineering|imperial``: the text report in the reader's units (issue 15, part 4).

References, independent of flyopt.report.display:

- the units of each system are written out here (:data:`UNITS`), as the issue
  names them: the SI base units; mm, rpm, kN·m, kJ, MPa (engineering, with kW,
  kg, kg·m², m/s); in, rpm, lbf·ft, psi (imperial, with hp, lb, lb·ft², ft/s);
- every number the report prints is read back from the text and compared with
  the analysis's or the design's SI value (what ``--json`` writes) converted
  by pint in the test.

Tolerance: a number printed to d significant digits lies within half a unit of
its d-th digit, a relative 0.5·10^(1−d) of the value (6 digits: 5e-6, 4 digits,
the default since issue 29: 5e-4); :func:`close` allows that and nothing more.

In the engineering system torque, energy, power and force take the SI prefix each
value needs (issue 29): the test accepts any of :data:`PREFIXED`'s labels there,
checks the rule itself (the number shown is at least 1 and below 1000, or below 1
in the unprefixed unit), and converts what is printed with pint from the label
printed.

The scenes are solved once per module (about 8 s) and the command line's
report is built from that solution for each system (flyopt.pipeline.solve is
replaced by the cached solution, so what is tested is the command's own
formatting path); the JSON test runs the real command three times.
"""

import json
import math
import re

import pytest
from conftest import PROBLEMS, ROOT, run_flyopt, unit_registry

import flyopt
import flyopt.pipeline
from flyopt.cli.main import main

SYSTEMS = ("engineering", "si", "imperial")
SCENES = ("shear-press", "punch-press-wheel", "four-cylinder-engine", "motor-press")

#: The unit of each dimension in each system, as the report must label it.
UNITS = {
    "si": {
        "angle": "rad",
        "angular_speed": "rad/s",
        "torque": "N·m",
        "energy": "J",
        "inertia": "kg·m²",
        "flywheel_moment": "N·m²",
        "length": "m",
        "mass": "kg",
        "speed": "m/s",
        "stress": "Pa",
        "power": "W",
        "time": "s",
        "unbalance": "kg·m",
        "eccentricity": "m",
    },
    "engineering": {
        "angle": "deg",
        "angular_speed": "rpm",
        "torque": "kN·m",
        "energy": "kJ",
        "inertia": "kg·m²",
        "flywheel_moment": "N·m²",
        "length": "mm",
        "mass": "kg",
        "speed": "m/s",
        "stress": "MPa",
        "power": "kW",
        "time": "s",
        "unbalance": "g·mm",
        "eccentricity": "µm",
    },
    "imperial": {
        "angle": "deg",
        "angular_speed": "rpm",
        "torque": "lbf·ft",
        "energy": "ft·lbf",
        "inertia": "lb·ft²",
        "flywheel_moment": "lbf·ft²",
        "length": "in",
        "mass": "lb",
        "speed": "ft/s",
        "stress": "psi",
        "power": "hp",
        "time": "s",
        "unbalance": "oz·in",
        "eccentricity": "in",
    },
}
#: Engineering: the labels a prefixed dimension may carry, the unprefixed one first (written out here, as
#: issue 29 names them: 36.1 N·m, not 0.0361 kN·m; 1.256 kJ).
PREFIXED = {
    "torque": ("N·m", "kN·m", "MN·m"),
    "energy": ("J", "kJ", "MJ", "GJ"),
    "power": ("W", "kW", "MW"),
    "force": ("N", "kN", "MN"),
}

#: The significant figures of the report by default (``--digits``).
DIGITS = 4


def allowed(dimension, system):
    """The labels a quantity of ``dimension`` may carry in ``system``."""
    if system == "engineering" and dimension in PREFIXED:
        return PREFIXED[dimension]
    return (UNITS[system][dimension],)


def in_nominal(number, label, dimension, system):
    """A number printed in ``label`` in the system's nominal unit of the dimension (:data:`UNITS`), by pint."""
    assert label in allowed(dimension, system), f"{label!r} is no unit of {dimension} in {system}"
    nominal = UNITS[system][dimension]
    if label == nominal:
        return number
    return unit_registry().Quantity(number, PINT.get(label, label)).to(PINT.get(nominal, nominal)).magnitude


def prefix_fits(number, label, dimension, system):
    """Whether a prefixed label is the one the number needs: 1 <= |number| < 1000, or below 1 unprefixed."""
    if system != "engineering" or dimension not in PREFIXED or number == 0:
        return True
    if label == PREFIXED[dimension][0]:
        return abs(number) < 1000
    return 1 <= abs(number) < 1000


#: The SI unit of each dimension, as pint spells it.
SI = {
    "angle": "rad",
    "angular_speed": "rad/s",
    "torque": "N*m",
    "energy": "J",
    "inertia": "kg*m**2",
    "flywheel_moment": "N*m**2",
    "length": "m",
    "mass": "kg",
    "speed": "m/s",
    "stress": "Pa",
    "power": "W",
    "time": "s",
    "unbalance": "kg*m",
    "eccentricity": "m",
}
#: pint's spelling of a label.
PINT = {
    "deg": "degree",
    "N·m": "N*m",
    "kN·m": "kN*m",
    "MN·m": "MN*m",
    "lbf·ft": "lbf*ft",
    "ft·lbf": "ft*lbf",
    "kg·m²": "kg*m**2",
    "lb·ft²": "lb*ft**2",
    "N·m²": "N*m**2",
    "lbf·ft²": "lbf*ft**2",
    "kg·m": "kg*m",
    "g·mm": "g*mm",
    "oz·in": "oz*in",
}

#: A printed number: optional sign, thousands grouped by commas, optional exponent.
NUM = r"[-+−]?[0-9][0-9,]*(?:\.[0-9]+)?(?:e[-+][0-9]+)?"


def value(text):
    """The float of a printed number ("1,256.33" -> 1256.33, "−1" -> -1)."""
    return float(text.replace(",", "").replace("−", "-"))


def expected(si_value, dimension, system):
    """An SI value in the system's unit, converted by pint."""
    name = UNITS[system][dimension]
    return unit_registry().Quantity(si_value, SI[dimension]).to(PINT.get(name, name)).magnitude


def close(printed, si_value, dimension, system, digits=DIGITS):
    """Whether a number printed to ``digits`` significant digits is the SI value converted (see the docstring)."""
    want = expected(si_value, dimension, system)
    return math.isclose(printed, want, rel_tol=0.5 * 10 ** (1 - digits) * (1 + 1e-9), abs_tol=1e-300)


def quantity(text, dimension, system):
    """The number of "<number> <label>" at the start of ``text`` in the system's nominal unit, after checking
    that the label is one of the system's and, for a prefixed one, the one the number needs."""
    match = re.match(rf"({NUM}) (\S+)", text)
    assert match, f"no '<number> <unit>' at {text!r}"
    label = match.group(2).rstrip(",;)")
    assert label in allowed(dimension, system), f"{text!r}: expected a unit of {allowed(dimension, system)} ({system})"
    number = value(match.group(1))
    assert prefix_fits(number, label, dimension, system), f"{text!r}: another prefix is the one it needs"
    return in_nominal(number, label, dimension, system)


def fact(text, name):
    """The value of a report line '  name    value'."""
    match = re.search(rf"^  {re.escape(name)}\s{{2,}}(.+)$", text, re.M)
    assert match, f"no line {name!r} in the report"
    return match.group(1)


def table(text, title):
    """The table under the line starting with ``title``: (header cells, rows of cells), cut at the rule's columns."""
    lines = text.splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith(title))
    block = []
    for line in lines[start + 1 :]:
        if not line.strip() or not line.startswith("  ") or line.startswith("  ("):  # "(stress: ...)" ends one
            break
        block.append(line)
    rule = block[1]
    assert set(rule.strip()) <= {"-", " "}, rule
    spans = [m.span() for m in re.finditer(r"-+", rule)]
    cells = [
        [line[a:b].strip() if k < len(spans) - 1 else line[a:].strip() for k, (a, b) in enumerate(spans)]
        for line in block
        if not set(line.strip()) <= {"-", " "}
    ]
    return cells[0], cells[1:]


def heading_unit(cell):
    """ "mass [kg]" -> ("mass", "kg"); "rank" -> ("rank", None)."""
    match = re.fullmatch(r"(.*?) \[(.+)\]", cell)
    return (match.group(1), match.group(2)) if match else (cell, None)


# --------------------------------------------------------------------------
# The report of each scene in each system, from one solution per scene
# --------------------------------------------------------------------------


@pytest.fixture(scope="module")
def solutions():
    return {name: flyopt.solve(flyopt.load(PROBLEMS / f"{name}.toml"), verify_design=True) for name in SCENES}


@pytest.fixture
def report(solutions, monkeypatch, capsys):
    """report(scene, system or None) -> the text ``flyopt solve SCENE --verify [--units SYSTEM]`` prints."""

    def solved(scene, *, design_flywheel, model, verify_design, design_method):
        assert (design_flywheel, model, verify_design, design_method) == (True, None, True, "auto")
        return next(s for s in solutions.values() if s.analysis.title == scene.title)

    monkeypatch.setattr(flyopt.pipeline, "solve", solved)

    def make(name, system):
        args = ["solve", str(PROBLEMS / f"{name}.toml"), "--verify"] + (["--units", system] if system else [])
        assert main(args) == 0
        return capsys.readouterr().out

    return make


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize("name", SCENES)
def test_the_analysis_in_the_chosen_units(name, system, solutions, report):
    """ω_m, the speed range, A_max, J_F, GD², torques, work, power, the ΔE chain and the shafts' table."""
    text = report(name, system)
    a = solutions[name].analysis
    assert close(quantity(fact(text, "mean speed"), "angular_speed", system), a.omega_mean, "angular_speed", system)
    # "speed range" was the analysis' extremes, the allowed range or an achieved one by the model: it is named
    # now, the allowed one ω_m (1 ± δ/2) (issue 29)
    low, high = re.fullmatch(rf"({NUM}) to (.+)", fact(text, "allowed speed range")).groups()
    assert close(value(low), a.omega_mean * (1 - a.delta / 2), "angular_speed", system)
    assert close(quantity(high, "angular_speed", system), a.omega_mean * (1 + a.delta / 2), "angular_speed", system)
    assert close(quantity(fact(text, "cycle"), "angle", system), a.cycle_angle, "angle", system)
    assert close(quantity(fact(text, "A_max"), "energy", system), a.a_max, "energy", system)
    assert close(quantity(fact(text, "work per cycle"), "energy", system), a.work_per_cycle, "energy", system)
    assert close(quantity(fact(text, "driving torque (mean)"), "torque", system), a.driving_torque, "torque", system)
    assert close(quantity(fact(text, "mean driving power"), "power", system), a.power, "power", system)
    assert close(quantity(fact(text, "motor power"), "power", system), a.motor_power, "power", system)
    j_f = fact(text, "required flywheel J_F")
    assert close(quantity(j_f, "inertia", system), a.j_required, "inertia", system)
    gd2 = re.search(r"\(GD² (.+)\)", j_f).group(1)
    assert close(quantity(gd2, "flywheel_moment", system), a.gd2_required, "flywheel_moment", system)

    head, rows = table(text, "Energy indicator diagram")
    assert heading_unit(head[0]) == ("angle", UNITS[system]["angle"])
    title, energy = heading_unit(head[1])
    assert title == "ΔE" and energy in allowed("energy", system)
    assert len(rows) == len(a.energy_chain)
    scale = max(abs(p["delta_e"]) for p in a.energy_chain)
    # one unit for the column, the one its largest value needs
    assert prefix_fits(max(abs(value(row[1])) for row in rows), energy, "energy", system)
    for row, point in zip(rows, a.energy_chain):
        assert close(value(row[0]), point["angle"], "angle", system)
        if abs(point["delta_e"]) <= 1e-12 * scale:  # round-off of the chain's close is printed as 0
            assert row[1] == "0"
        else:
            assert close(in_nominal(value(row[1]), energy, "energy", system), point["delta_e"], "energy", system)

    head, rows = table(text, "Flywheel needed on each shaft")
    assert [heading_unit(c) for c in head] == [
        ("shaft", None),
        ("speed ratio", None),
        ("speed", UNITS[system]["angular_speed"]),
        ("J", UNITS[system]["inertia"]),
        ("GD²", UNITS[system]["flywheel_moment"]),
    ]
    for row, shaft in zip(rows, a.shafts, strict=True):
        assert row[0] == shaft.name
        assert close(value(row[2]), shaft.omega, "angular_speed", system)
        assert close(value(row[3]), shaft.j_required, "inertia", system)

    if len(a.models) > 1:
        head, rows = table(text, "Models (J_F")
        assert heading_unit(head[1]) == ("J_F", UNITS[system]["inertia"])
        for row, model in zip(rows, a.models, strict=True):
            assert close(value(row[1]), model["j_required"], "inertia", system)

    v = solutions[name].verification
    line = text.splitlines()[
        text.splitlines().index(next(x for x in text.splitlines() if x.startswith("Verification ("))) + 1
    ]
    mean = re.search(r"mean (.+?);", line).group(1)
    assert close(quantity(mean, "angular_speed", system), v.omega_mean, "angular_speed", system)
    flywheel = re.search(r"flywheel (.+) at the reference shaft", line).group(1)
    assert close(quantity(flywheel, "inertia", system), v.j_flywheel, "inertia", system)


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize("name", SCENES)
def test_the_design_in_the_chosen_units(name, system, solutions, report):
    """Mass, the diameters, H x B, J, rim speed, ρv², the parts, the stresses, burst, unbalance, key, ranking."""
    text = report(name, system)
    design = solutions[name].design
    best = design.best
    assert close(quantity(fact(text, "mass"), "mass", system), best.mass, "mass", system)
    if best.geometry == "disc":  # a disc has no rim: its outer diameter, bore and width
        assert "rim H x B" not in text and "mean / inner" not in text
        outer = fact(text, "outer diameter / bore" if best.bore else "outer diameter").split(" / ")[0]
        assert close(
            quantity(outer, "length", system) if not best.bore else value(outer), best.dims.d_outer, "length", system
        )
        assert close(quantity(fact(text, "disc width B"), "length", system), best.dims.b, "length", system)
    else:
        outer, mean, inner = fact(text, "outer / mean / inner diameter").split(" / ")
        assert close(value(outer), best.dims.d_outer, "length", system)
        assert close(value(mean), best.dims.d_mean, "length", system)
        assert close(quantity(inner, "length", system), best.dims.d_inner, "length", system)
        h, b = fact(text, "rim H x B").split(" x ", 1)
        assert close(value(h), best.dims.h, "length", system) and close(
            quantity(b, "length", system), best.dims.b, "length", system
        )
    rim = fact(text, "rim speed")
    assert close(quantity(rim, "speed", system), best.stresses.rim_speed, "speed", system)
    assert close(
        quantity(re.search(r"ρv² (.+)", rim).group(1), "stress", system), best.stresses.hoop_stress, "stress", system
    )
    j = fact(text, "inertia")
    assert close(quantity(j, "inertia", system), best.j_flywheel, "inertia", system)

    head, rows = table(text, "Parts of the wheel")
    assert [heading_unit(c)[1] for c in head] == [
        None,
        UNITS[system]["length"],
        UNITS[system]["length"],
        UNITS[system]["mass"],
        UNITS[system]["inertia"],
        None,
    ]
    for row, part in zip(rows, best.parts.items):
        r_inner, r_outer = row[1].split(" – ")
        assert close(value(r_inner), part["r_inner"], "length", system)
        assert close(value(r_outer), part["r_outer"], "length", system)
        assert close(value(row[3]), part["mass"], "mass", system)

    omega = re.search(r"^Stress check at ω_max = (.+) on its shaft:$", text, re.M).group(1)
    assert close(quantity(omega, "angular_speed", system), design.omega * best.speed_ratio, "angular_speed", system)
    head, rows = table(text, "Stress check at ω_max")
    assert [heading_unit(c) for c in head] == [
        ("part", None),
        ("stress", UNITS[system]["stress"]),
        ("at r", UNITS[system]["length"]),
        ("allowable", UNITS[system]["stress"]),
        ("utilisation", None),
        ("strength", UNITS[system]["stress"]),
        ("at wall", UNITS[system]["length"]),
    ]
    for row, part in zip(rows, best.stresses.stress["parts"], strict=True):
        assert row[0] == part["part"]
        assert close(value(row[1]), part["stress"], "stress", system)
        assert close(value(row[2]), part["radius"], "length", system)
        assert close(value(row[3]), part["allowable"], "stress", system)
    mean_hoop = fact(text, "mean hoop stress")
    assert close(quantity(mean_hoop, "stress", system), best.stresses.stress["mean_hoop"], "stress", system)
    if best.stresses.burst_speed is not None and math.isfinite(best.stresses.burst_speed):
        burst = fact(text, "burst speed")
        assert close(quantity(burst, "angular_speed", system), best.stresses.burst_speed, "angular_speed", system)

    balance = next(line for line in text.splitlines() if line.startswith("Permissible unbalance"))
    u_per, e_per = re.fullmatch(r".*G6\.3 at ω_max\): (.+) \(e_per (.+)\)", balance).groups()
    assert close(quantity(u_per, "unbalance", system), best.stresses.unbalance_permissible, "unbalance", system)
    assert close(
        quantity(e_per, "eccentricity", system),
        best.stresses.unbalance_permissible / best.mass,
        "eccentricity",
        system,
        4,
    )
    if best.parts.key:
        key = text.splitlines()[[k for k, x in enumerate(text.splitlines()) if x.startswith("Key (DIN")][0] + 1]
        torque = re.search(r"peak torque (.+?): bearing pressure (.+?) \(allowable", key)
        assert close(quantity(torque.group(1), "torque", system), best.parts.key["torque"], "torque", system)
        assert close(
            quantity(torque.group(2), "stress", system), best.parts.key["bearing_pressure"], "stress", system, 4
        )

    head, rows = table(text, "Every combination")
    units = dict(heading_unit(c) for c in head)
    assert (units["mass"], units["D_outer"], units["H"], units["B"], units["v"]) == (
        UNITS[system]["mass"],
        UNITS[system]["length"],
        UNITS[system]["length"],
        UNITS[system]["length"],
        UNITS[system]["speed"],
    )
    column = {heading_unit(c)[0]: k for k, c in enumerate(head)}
    for row, candidate in zip(rows, design.candidates, strict=True):
        if candidate.feasible:
            assert close(value(row[column["mass"]]), candidate.mass, "mass", system)
            assert close(value(row[column["D_outer"]]), candidate.dims.d_outer, "length", system)
            assert close(value(row[column["v"]]), candidate.stresses.rim_speed, "speed", system)


# --------------------------------------------------------------------------
# Every number has its unit's label, and the system's
# --------------------------------------------------------------------------

#: Table columns that carry a unit (the title's dimension), and those that are dimensionless or text.
COLUMN_DIMENSION = {
    "J_F": "inertia",
    "angle": "angle",
    "ΔE": "energy",
    "speed": "angular_speed",
    "J": "inertia",
    "GD²": "flywheel_moment",
    "r_inner – r_outer": "length",
    "thickness": "length",
    "mass": "mass",
    "inertia": "inertia",
    "stress": "stress",
    "at r": "length",
    "allowable": "stress",
    "strength": "stress",
    "at wall": "length",
    "D_outer": "length",
    "H": "length",
    "B": "length",
    "v": "speed",
    "P": "power",
    "start": "time",
    "wheel": "mass",
    "total": "mass",
}
PLAIN_COLUMNS = {
    "model",
    "vs exact",
    "achieved δ",
    "note",
    "point",
    "",
    "shaft",
    "speed ratio",
    "part",
    "share of J",
    "utilisation",
    "rank",
    "material",
    "arms",
    "binding",
    "motor",
    "ratio",
    "limit",
    "RMS/rated",
    "r",
    "verdict",
}
#: Report lines whose numbers are dimensionless by their name.
PLAIN_FACTS = (
    "allowed δ",
    "material / shaft",
    "binding",
    "solved by",
    "safety on strength",
    "motor ratio",
    "flywheel shaft",
)
#: Blocks of prose written by the design itself (flyopt.design), shown as it wrote them: none. (The sensitivities
#: of the mass, the reasons of the infeasible and pruned combinations, the design's notes and the shaft check's
#: places are filled in the reader's units, flyopt.said, and checked here as every other line.)
PROSE_BLOCKS = ()
#: Lines that carry the design's prose (none: the drive's note no longer prints a number).
PROSE_LINES = ()
#: Dimensionless numbers inside a line: ratios, counts, percentages, tolerances, standards' names.
PLAIN_NUMBERS = [
    rf"efficiency {NUM}",
    rf"H/B {NUM}",
    rf"safety factor {NUM}",
    rf"\({NUM} cycles\)",
    rf"\({NUM} x ω_max\)",
    rf"{NUM} %",
    rf"achieved δ {NUM} against (the allowed )?{NUM}",
    rf"δ = {NUM}(, within the allowed {NUM})?",  # the δ a machine gives with no flywheel (issue 29)
    rf"tolerance {NUM}",
    rf"area {NUM}",
    rf"{NUM} cylinders?",
    rf"{NUM}-stroke",
    r"ISO 21940-11",
    r"G6\.3",
    r"DIN 6885-1",
    r"EN-GJ[LS]-[0-9]+(?:-[0-9]+)?",  # a material's standard name (EN 1561, EN 1563)
    r"[0-9]+ x [0-9]+ key",  # a DIN 6885-1 key by its designation
    rf"at most {NUM} d\b",  # a key's longest, in seat diameters
    r"m >= 4 J/D²",  # the designer's lower bound, as a formula
    r"bore: [0-9]+ x [0-9]+,",
    r"[0-9]+ x [0-9]+ mm section",  # the key's DIN 6885-1 section, named in mm as the standard names it
    rf"{NUM} iterations",
    rf"ratio [-+−]?{NUM}",
    rf"δ \+{NUM}",
    rf"arms: {NUM}",
    rf"{NUM} dimensions rounded",
    rf"the {NUM} corners",
    rf"\({NUM} solves\)",
    rf"r_f = {NUM} x",
    rf"\({NUM} wheels on the grid",
    # a sensitivity's dimensionless step: δ's (and the e.g. of it), a castability section ratio's
    rf"delta: \+{NUM} \(e\.g\. {NUM} to {NUM}\)",
    rf"\+{NUM} on the allowed {NUM}",
    rf"{NUM} quadratic triangles",
    rf"(hub|web|arms|rim|disc)-(hub|web|arms|rim|disc) {NUM}",  # a junction's factor or section ratio
    rf"\(at most {NUM}\)",  # the section ratio castability allows
    rf"δ +allowed {NUM}; (δ {NUM} by the periodic simulation|held by the inertia|δ {NUM} at the stall limit \(the smallest flywheel that runs steadily\))",  # the answer's δ line
    r"\(2V/A\)",  # the equivalent thickness the ratios compare
]


def unlabelled_numbers(text, system, names=()):
    """Lines of the report, each with what is left of it where a number has no unit of ``system``.

    A number counts as labelled when a unit of the system follows it (or a
    list of numbers joined by "/", "to", "x", "of" or commas that ends in
    one), when it stands in a table column whose heading carries the system's
    unit of that column's dimension, or when it is dimensionless by the
    patterns above. ``names`` (a motor's "5.5 kW") are names, not quantities.
    """
    labels = sorted(
        set(UNITS[system].values()) | {u for d in UNITS[system] for u in allowed(d, system)}, key=len, reverse=True
    )
    labelled = re.compile(
        rf"{NUM}(?:(?:\s*(?:/|to|x|–|of)\s*|,\s+){NUM})*\s+(?:" + "|".join(map(re.escape, labels)) + r")(?![\w/²³·])"
    )
    lines = text.splitlines()
    left = []
    k = 2  # after the title and the model's line
    while k < len(lines):
        line = lines[k]
        if line.startswith(PROSE_BLOCKS):
            while k < len(lines) and lines[k].strip():
                k += 1
            continue
        if line.startswith(PROSE_LINES):
            k += 1
            continue
        if k + 1 < len(lines) and lines[k + 1].startswith("  -") and set(lines[k + 1].strip()) <= {"-", " "}:
            k = _check_table(lines, k, system, left)  # a table: header, rule, rows
            continue
        k += 1
        if re.match(rf"  ({'|'.join(map(re.escape, PLAIN_FACTS))})\s{{2,}}", line):
            continue
        for name in names:
            line = line.replace(name, "<name>")
        rest = labelled.sub("", line)
        for pattern in PLAIN_NUMBERS:
            rest = re.sub(pattern, "", rest)
        if re.search(r"[0-9]", rest):
            left.append((line, rest))
    return left


def _check_table(lines, k, system, left):
    """Check a table's headings and cells; returns the index after it."""
    rule = lines[k + 1]
    spans = [m.span() for m in re.finditer(r"-+", rule)]

    def cells(line):
        return [line[a:b].strip() if j < len(spans) - 1 else line[a:].strip() for j, (a, b) in enumerate(spans)]

    head = [heading_unit(c) for c in cells(lines[k])]
    end = k + 2
    while end < len(lines) and lines[end].startswith("  ") and lines[end].strip() and not lines[end].startswith("  ("):
        end += 1
    for j, (title, unit) in enumerate(head):
        if title in PLAIN_COLUMNS:
            assert unit is None, f"{lines[k]!r}: a dimensionless column has a unit"
            continue
        assert title in COLUMN_DIMENSION, f"{lines[k]!r}: column {title!r} is neither a quantity nor plain"
        if unit not in allowed(COLUMN_DIMENSION[title], system):
            left.append((lines[k], f"column {title!r} in {unit!r}"))
        for line in lines[k + 2 : end]:
            cell = cells(line)[j]
            if cell and not re.fullmatch(rf"-+|{NUM}( – {NUM})?|infeasible|cannot win|none", cell):
                left.append((line, cell))
    return end


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize("name", SCENES)
def test_every_number_has_its_systems_unit(name, system, report):
    text = report(name, system)
    assert unlabelled_numbers(text, system) == []


def test_the_label_check_finds_a_number_without_its_unit(report):
    """The check above can fail: another system's unit, a bare number and a wrong heading are each found."""
    text = report("shear-press", "engineering")
    assert unlabelled_numbers(text, "engineering") == []
    assert unlabelled_numbers(text, "si") != [] and unlabelled_numbers(text, "imperial") != []
    for old, new in (("mean 1,500 rpm;", "mean 1,500;"), ("1.256 kJ", "926.6 ft·lbf"), ("mass [kg]", "mass [lb]")):
        assert old in text
        assert unlabelled_numbers(text.replace(old, new), "engineering") != [], new


# --------------------------------------------------------------------------
# The command line: the default, the JSON, bad values, the report code
# --------------------------------------------------------------------------


def test_the_default_is_engineering(report):
    """Engineering units by default: those of the plots and the engineering report (issue 15)."""
    assert report("punch-press-wheel", None) == report("punch-press-wheel", "engineering")


def test_the_json_is_si_whatever_the_units(main_cli):
    """--json ignores --units: the same document, byte for byte, with A_max in J as the analysis gives it."""
    scene = PROBLEMS / "shear-press.toml"
    outputs = {system: main_cli("solve", scene, "--json", "--units", system) for system in SYSTEMS}
    outputs[None] = main_cli("solve", scene, "--json")
    assert {status for status, _, _ in outputs.values()} == {0}
    assert len({out for _, out, _ in outputs.values()}) == 1
    document = json.loads(outputs[None][1])
    assert document["a_max"] == flyopt.analyse(flyopt.load(scene)).a_max and document["units"]["a_max"] == "J"


def test_an_unknown_unit_system_is_refused(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["solve", str(PROBLEMS / "shear-press.toml"), "--units", "cgs"])
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and "Traceback" not in err
    assert "argument --units: invalid choice: 'cgs'" in err and all(s in err for s in SYSTEMS)


def test_the_help_says_the_json_stays_si(capsys):
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    words = " ".join(capsys.readouterr().out.split())
    assert "--units {engineering,si,imperial}" in words and "--json ignores it: the JSON is always SI" in words


def test_the_report_code_has_no_conversion_of_its_own():
    """One table of display units: the report's modules convert nothing themselves."""
    for path in ("src/flyopt/report/text.py", "src/flyopt/report/drive.py"):
        source = (ROOT / path).read_text(encoding="utf-8")
        for pattern in (
            r"rad_s_to_rpm",
            r"\b1e6\b",
            r"\b1e3\b",
            r"\* ?1000\b",
            r"/ ?1000\b",
            r"math\.degrees",
            r"\b_mm\(",
            r"\b_mpa\(",
            r"30 / math\.pi",
        ):
            assert not re.search(pattern, source), (path, pattern)


# --------------------------------------------------------------------------
# The drive
# --------------------------------------------------------------------------


def _drive(solution):
    """A drive result assembled from the drive's own types (designing one takes a minute: the real one,
    press-drive, is in the slow test). Its numbers are placeholders chosen apart from each other."""
    from flyopt.drive.codesign import DriveCheck, DriveDesign, MotorRun
    from flyopt.drive.relaxation import Relaxation
    from flyopt.machine.catalogue import CatalogueMotor

    motor = CatalogueMotor(
        name="5.5 kW",
        rated_power=5500.0,
        rated_speed=151.8,
        synchronous_speed=157.1,
        rotor_inertia=0.022,
        breakdown_ratio=2.7,
        mass=40.0,
    )
    run = MotorRun(
        motor=motor,
        feasible=True,
        motor_ratio=24.0,
        j_flywheel=812.5,
        limit="thermal",
        j_delta=790.0,
        rms_torque=30.5,
        mean_torque=20.25,
        rated_torque=36.23,
        omega_mean=6.28,
        delta=0.1,
        startup_time=5.125,
        flywheel_ratio=24.0,
        wheel=solution.design.best,
        motor_mass=40.0,
        wheel_mass=17.5,
        total_mass=57.5,
        objective=57.5,
    )
    relaxation = Relaxation(
        5000.0,
        23.5,
        22.0,
        800.0,
        57.0,
        "Solve_Succeeded",
        sensitivities={"max_outer_diameter": -20.0, "rim_speed": -0.75, "delta": -30.0},
    )
    drive = DriveDesign(
        status="designed",
        objective="mass",
        best=run,
        relaxation=relaxation,
        note="relaxation",
        runs=(run, MotorRun(motor=motor, feasible=False, reason="too small: ...", refusal="too small")),
    )
    check = DriveCheck(
        verification=solution.verification, rms_torque=30.5, rated_torque=36.23, startup_time=5.125, flagged=False
    )
    return drive, check


@pytest.mark.parametrize("system", SYSTEMS)
def test_the_drive_in_the_chosen_units(system, solutions):
    from flyopt.report.drive import drive_report

    drive, check = _drive(solutions["punch-press-wheel"])
    text = "\n".join(drive_report(drive, check, units=system))
    run = drive.best
    motor = re.search(r"5\.5 kW: (.+?) at (.+?) \(rated torque (.+?), rotor (.+?)\)", text)
    assert close(quantity(motor.group(1), "power", system), 5500.0, "power", system)
    assert close(quantity(motor.group(2), "angular_speed", system), 151.8, "angular_speed", system)
    assert close(quantity(motor.group(3), "torque", system), drive.best.motor.rated_torque, "torque", system)
    assert close(quantity(motor.group(4), "inertia", system), 0.022, "inertia", system)
    flywheel = fact(text, "flywheel")
    assert close(quantity(flywheel, "inertia", system), run.j_flywheel, "inertia", system)
    assert close(
        quantity(re.search(r"δ alone needs (.+)\)", flywheel).group(1), "inertia", system),
        run.j_delta,
        "inertia",
        system,
    )
    assert close(quantity(fact(text, "RMS torque"), "torque", system), run.rms_torque, "torque", system)
    assert close(quantity(fact(text, "start-up"), "time", system), run.startup_time, "time", system)
    total = re.search(r"= (.+)$", fact(text, "masses")).group(1)
    assert close(quantity(total, "mass", system), run.total_mass, "mass", system)
    # relaxing the envelope by a round step of the system's length: +100 mm, +0.1 m or +4 in
    step = {"engineering": ("100 mm", 0.1), "si": ("0.1 m", 0.1), "imperial": ("4 in", 4 * 0.0254)}[system]
    saved = re.search(rf"envelope \+{re.escape(step[0])}: (.+?)(;| \(relaxed)", fact(text, "binding limits"))
    assert saved, fact(text, "binding limits")
    assert close(quantity(saved.group(1), "mass", system), -20.0 * step[1], "mass", system)
    rim_step = {"engineering": ("1 m/s", 1.0), "si": ("1 m/s", 1.0), "imperial": ("1 ft/s", 0.3048)}[system]
    saved = re.search(rf"safe rim speed \+{re.escape(rim_step[0])}: (.+?)(;| \(relaxed)", text)
    assert close(quantity(saved.group(1), "mass", system), -0.75 * rim_step[1], "mass", system)
    head, rows = table(text, "Every motor size solved")
    power = dict(heading_unit(c) for c in head)["P"]
    assert power == {"engineering": "kW", "si": "W", "imperial": "hp"}[system]  # 5.5 kW, the largest of its column
    assert close(in_nominal(value(rows[0][1]), power, "power", system), 5500.0, "power", system)
    assert close(value(rows[0][3]), run.j_flywheel, "inertia", system)
    assert close(value(rows[0][9]), run.total_mass, "mass", system)
    assert unlabelled_numbers(text, system, names=["5.5 kW"]) == []


def test_the_drive_torques_take_their_prefix(solutions):
    """A 36.23 N·m motor's torques were "0.03623 kN·m" (issue 29: press-drive's "0.0361 kN·m"): each is in
    N·m now, and "RMS torque 30.5 of 36.23 N·m" shares one unit."""
    from flyopt.report.drive import drive_report

    drive, check = _drive(solutions["punch-press-wheel"])
    text = "\n".join(drive_report(drive, check, units="engineering"))
    assert "kN·m" not in text
    assert "rated torque 36.23 N·m" in text and "RMS torque 30.5 of 36.23 N·m" in text, text


@pytest.fixture(scope="module")
def refused_drive(tmp_path_factory):
    """press-drive with a start-up of 1 ms allowed: every motor size refused, by each of the reasons a size
    can have (too weak for the mean torque, a start-up too long), solved once (2 s)."""
    text = (PROBLEMS / "press-drive.toml").read_text(encoding="utf-8")
    changed = re.sub(r"(?m)^max_startup = .*$", "max_startup = 0.001", text)
    assert changed != text
    path = tmp_path_factory.mktemp("drive") / "press-drive-1ms.toml"
    path.write_text(changed, encoding="utf-8")
    scene = flyopt.load(path)
    return scene, flyopt.solve(scene), path


@pytest.mark.parametrize("system", SYSTEMS)
def test_a_refused_motors_reasons_are_in_the_readers_units(system, refused_drive):
    """Was: under --units imperial each refused motor's verdict and the drive's INFEASIBLE line said "its mean
    torque 28.2 N·m exceeds its rated torque 5.069 N·m" among lbf·ft and hp. Each torque and time of a reason,
    read back in SI, is the motor's own (rated torque P/ω of the catalogue; the mean load torque of the analysis
    over the motor ratio; the run-up time), in the text and in the report's table."""
    from flyopt.analysis import analyse
    from flyopt.report.builder import ReportInputs, build
    from flyopt.report.document import Table
    from flyopt.report.drive import drive_report

    scene, solution, _ = refused_drive
    drive = solution.drive
    assert drive.status == "infeasible" and not any(run.feasible for run in drive.runs)
    load = analyse(scene).driving_torque
    text = "\n".join(drive_report(drive, None, units=system))
    names = [run.motor.name for run in drive.runs] + [m.name for m in scene.drive.motors if m.name]
    assert unlabelled_numbers(text, system, names=names) == []
    infeasible = next(line for line in text.splitlines() if line.startswith("  INFEASIBLE: "))
    document = build(ReportInputs("", "", (), scene, solution), system, figures=False)
    runs_table = next(
        b for section in document.sections for b in section.blocks if isinstance(b, Table) and b.name == "drive_runs"
    )
    _, rows = table(text, "Every motor size solved")
    said = {"text": {row[0]: row[-1] for row in rows}, "report": {row[0]: row[-1] for row in runs_table.rows}}
    kinds = set()
    for where, verdicts in said.items():
        for run in drive.runs:
            verdict = verdicts[run.motor.name]
            mean = re.fullmatch(
                r"thermal: its mean torque (.+?) exceeds its rated torque (.+?)"
                r"( whatever the flywheel|, and its RMS torque stays above that for any flywheel)",
                verdict,
            )
            late = re.fullmatch(r"start-up: (.+?) from rest, over max_startup (.+)", verdict)
            assert mean or late, (where, verdict)
            if mean:
                kinds.add("thermal")
                rated = run.motor.rated_power / run.motor.rated_speed
                assert close(quantity(mean.group(2), "torque", system), rated, "torque", system), (where, verdict)
                if mean.group(3) == " whatever the flywheel":  # refused before any cycle: the work balance's torque
                    given = load / (run.motor_ratio * scene.efficiency)
                    assert close(quantity(mean.group(1), "torque", system), given, "torque", system), (where, verdict)
                else:  # refused by its periodic run: the motor torque's mean over time, above the rated one
                    assert quantity(mean.group(1), "torque", system) > expected(rated, "torque", system)
            else:
                kinds.add("start-up")
                assert close(quantity(late.group(1), "time", system), run.startup_time, "time", system)
                assert close(quantity(late.group(2), "time", system), 0.001, "time", system)
            assert f"{run.motor.name}: {verdict}" in infeasible  # the INFEASIBLE line, in the same words
    assert kinds == {"thermal", "start-up"}


@pytest.mark.parametrize("system", SYSTEMS)
def test_an_infeasible_drives_answer_is_one_sentence(system, refused_drive, main_cli, tmp_path):
    """Was: the text's answer line, the report's summary verdict (and the app's card) and `flyopt plot`'s refusal
    each printed the drive's message whole, every one of the 18 refused sizes' reasons (some 1,500 characters,
    its torques in N·m under --units imperial). Each now says how many sizes each kind of reason refused and
    the first and last of them, in the catalogue's order; the drive's section and its table give each reason."""
    from flyopt.drive.codesign import refused_in_short
    from flyopt.report.builder import ReportInputs, build
    from flyopt.report.card import card_of
    from flyopt.report.drive import drive_report
    from flyopt.report.text import answer_report

    scene, solution, path = refused_drive
    drive = solution.drive
    short = refused_in_short(drive)
    assert answer_report(solution, system)[0] == f"Answer: no drive: {short}"
    verdict = card_of(build(ReportInputs("", "", (), scene, solution), system, figures=False)).verdict
    assert verdict.startswith(f"No feasible drive: {short}. "), verdict
    # the sizes of each kind, read from the table of sizes (the catalogue's order) by its verdicts' first words
    _, rows = table("\n".join(drive_report(drive, None, units=system)), "Every motor size solved")
    by_kind: dict = {}
    for row in rows:
        kind = (
            "thermal" if row[-1].startswith("thermal: ") else "start-up" if row[-1].startswith("start-up: ") else None
        )
        by_kind.setdefault(kind, []).append(row[0])
    assert set(by_kind) == {"thermal", "start-up"} and len(rows) == 18, by_kind
    assert [r.refusal for r in drive.runs] == [k for k, names in by_kind.items() for _ in names]
    listed = "; ".join(f"{kind}: {len(names)} sizes, {names[0]} … {names[-1]}" for kind, names in by_kind.items())
    assert short == (
        f"no motor size of the catalogue drives the machine within the limits ({listed}); each size's reason is "
        "in the drive's table of sizes"
    )
    if system == "imperial":
        status, _, err = main_cli("plot", path, "--what", "speed", "-o", tmp_path / "x.png", "--units", system)
        assert status == 3 and short in err and not (tmp_path / "x.png").exists(), err


def test_each_kind_of_refusal_is_named():
    """The short verdict counts the sizes by the kind each refusal was written with (:attr:`MotorRun.refusal`),
    not by its words: a reason without a kind's prefix (the ratio that does not settle, the wheel that does not
    fit) was "other" when the kind was read from them; one size and two sizes read as such. A run whose kind
    and reason disagree is not made."""
    from flyopt.drive.codesign import (
        NO_MOTOR,
        NO_WHEEL,
        NO_WHEEL_KIND,
        NOT_SETTLED,
        DriveDesign,
        MotorRun,
        refused_in_short,
    )
    from flyopt.machine.catalogue import CatalogueMotor

    def size(name, power):
        return CatalogueMotor(
            name=name, rated_power=power, rated_speed=150.0, synchronous_speed=157.0, rotor_inertia=0.01,
            breakdown_ratio=2.5, mass=20.0,
        )  # fmt: skip

    late = "start-up: 1 s from rest, over max_startup 0.5 s"
    runs = (
        MotorRun(motor=size("A", 1e3), feasible=False, reason=NO_WHEEL, refusal=NO_WHEEL_KIND),
        MotorRun(
            motor=size("B", 2e3),
            feasible=False,
            reason="the flywheel and the motor ratio did not settle together",
            refusal=NOT_SETTLED,
        ),
        MotorRun(motor=size("C", 3e3), feasible=False, reason=NO_WHEEL, refusal=NO_WHEEL_KIND),
        MotorRun(motor=size("D", 4e3), feasible=False, reason=late, refusal="start-up"),
        MotorRun(motor=size("E", 5e3), feasible=False, reason=late, refusal="start-up"),
    )
    drive = DriveDesign(status="infeasible", objective="mass", best=None, runs=runs, message=f"{NO_MOTOR}: ...")
    assert refused_in_short(drive) == (
        f"{NO_MOTOR} (no wheel: 2 sizes, A and C; not settled: 1 size, B; start-up: 2 sizes, D and E); each size's "
        "reason is in the drive's table of sizes"
    )
    other = DriveDesign(status="infeasible", objective="mass", best=None, runs=runs, message="the drive needs a load")
    assert refused_in_short(other) == "the drive needs a load"
    for wrong in (
        dict(feasible=False, reason=late),  # refused without a kind
        dict(feasible=False, reason=late, refusal="thermal"),  # a kind its reason does not begin with
        dict(feasible=True, reason="", refusal="start-up"),  # feasible with a kind
        dict(feasible=True, reason=late),  # feasible with a reason
        dict(feasible=False, reason=late, refusal="bogus"),  # a kind that is none
        dict(feasible=False, reason=late, refusal=NO_WHEEL_KIND),  # no wheel, with another reason
        dict(feasible=False, reason="", refusal=NOT_SETTLED),  # refused without a reason
        dict(feasible=False, reason=late, refusal=NOT_SETTLED),  # not settled, with a kind's prefix
        dict(feasible=False, reason="thermal: ", refusal="thermal"),  # a kind's prefix and no words
    ):
        with pytest.raises(ValueError, match="a size is refused with a kind of reason"):
            MotorRun(motor=size("F", 6e3), **wrong)


@pytest.fixture(scope="module")
def thin_drive_shaft(tmp_path_factory):
    """punch-press-drive-shaft with its flywheel shaft 34 mm throughout: no motor size's wheel is carried (2 s)."""
    text = (PROBLEMS / "punch-press-drive-shaft.toml").read_text(encoding="utf-8")
    changed = re.sub(r'diameter = "5[05] mm"', 'diameter = "34 mm"', text)
    assert changed.count('"34 mm"') == 3
    path = tmp_path_factory.mktemp("drive") / "thin.toml"
    path.write_text(changed, encoding="utf-8")
    scene = flyopt.load(path)
    return scene, flyopt.solve(scene)


@pytest.mark.parametrize("system", SYSTEMS)
def test_a_motor_refused_for_its_shaft_says_so_in_the_readers_units(system, thin_drive_shaft):
    """Was: "shaft: at ratio 8: ... this 92.62 kg wheel ... slope at bearing A (50 mm)" among lb and in. The
    bearing's place read back is the scene's 50 mm; the wheel's mass is written in the system's unit."""
    from flyopt.report.drive import drive_report

    scene, solution = thin_drive_shaft
    text = "\n".join(drive_report(solution.drive, None, units=system))
    _, rows = table(text, "Every motor size solved")
    refused = [row[-1] for row in rows if row[-1].startswith("shaft: ")]
    assert refused, text
    for verdict in refused:
        wheel = re.search(r"this (.+?) wheel", verdict).group(1)
        quantity(wheel, "mass", system)  # a mass in the system's unit (the check fails on another unit)
        place = re.search(r"at bearing A \((.+?)\)", verdict)
        assert place, verdict
        assert close(quantity(place.group(1), "length", system), 0.050, "length", system), verdict


@pytest.mark.slow
@pytest.mark.parametrize("system", ["imperial"])
def test_press_drive_end_to_end(system, main_cli):
    """The real drive of problems/press-drive.toml (about a minute): its report against its JSON."""
    scene = PROBLEMS / "press-drive.toml"
    status, out, _ = main_cli("solve", scene, "--json")
    document = json.loads(out)
    status_text, text, _ = main_cli("solve", scene, "--units", system)
    assert status == status_text
    best = document["drive"]["best"]
    assert close(quantity(fact(text, "RMS torque"), "torque", system), best["rms_torque"], "torque", system)
    assert close(quantity(fact(text, "flywheel"), "inertia", system), best["j_required"], "inertia", system)
    total = re.search(r"= (.+?)(;|$)", fact(text, "masses")).group(1)
    assert close(quantity(total, "mass", system), best["total_mass"], "mass", system)
    relaxed = re.match(r"(.+?), motor ratio", fact(text, "relaxation")).group(1)
    assert close(quantity(relaxed, "power", system), document["drive"]["relaxation"]["rated_power"], "power", system)
    # every catalogue size's name: a size the walk left unsolved is named in the drive's note, not in its runs
    names = [run["motor"]["name"] for run in document["drive"]["runs"]] + [
        m.name for m in flyopt.load(scene).drive.motors if m.name
    ]
    assert unlabelled_numbers(text, system, names=names) == []


def test_round_off_prints_as_zero():
    """The energy chain closes at the cycle's end: four-cylinder-engine's text printed its round-off
    (-3.69482e-16 kJ at 720 deg, issue 29); a value within 1e-12 of its column's scale prints as 0, and a
    real small value does not."""

    from conftest import PROBLEMS

    from flyopt.report.display import denoised

    assert denoised([0.0, 9000.0, -3.7e-13, -9000.0]) == [0.0, 9000.0, 0.0, -9000.0]
    assert denoised([1e-3, 1.0]) == [1e-3, 1.0] and denoised([1e-20]) == [1e-20] and denoised([]) == []
    run = run_flyopt("solve", str(PROBLEMS / "four-cylinder-engine.toml"))
    assert run.returncode == 0 and not re.search(r"\de-1\d", run.stdout), run.stdout
    assert re.search(r"\n  720\s+0\s*\n", run.stdout)


def test_the_shaft_check_says_its_places_in_the_readers_units(main_cli):
    """Was: under --units imperial the shaft check's table and its binding line said "at bearing A (60 mm)", "at
    the shoulder at 520 mm" and "22 x 14, 110 mm long" among inches and psi. The places are the scene's (bearings
    at 60 and 620 mm, the 80 mm body ending at 520 mm) and the key's length the design's, each converted here."""
    status, out, err = main_cli("solve", PROBLEMS / "punch-press-shaft.toml", "--units", "imperial")
    assert status == 0, err
    status, raw, err = main_cli("solve", PROBLEMS / "punch-press-shaft.toml", "--json")
    key_length = json.loads(raw)["design"]["key"]["length"]
    section = out[out.index("Shaft check:") :].split("\n\n")[0]
    inches = unit_registry().Quantity

    def inch(metres):
        return f"{inches(metres, 'm').to('inch').magnitude:.4g} in"

    for expected in (
        f"at the shoulder at {inch(0.520)}",
        f"at bearing A ({inch(0.060)})",
        f"at bearing B ({inch(0.620)})",
        f"22 x 14, {inch(key_length)} long, at the wheel seat",
        f"binding: key 22 x 14, {inch(key_length)} long",
    ):
        assert expected in section, expected
    assert not re.search(r"[0-9] ?(mm|m|kg|MPa|N·m)\b", section), section


def test_a_shaft_that_refuses_a_wheel_says_why_in_the_readers_units(main_cli, write_scene):
    """Was: with a pinion's mesh force of 40 kN (12 kN given) the shaft refuses every wheel, and under --units
    imperial each reason said "the shaft cannot carry this 148.2 kg wheel: fatigue factor of safety at the shoulder
    at 520 mm: 1.385 < 1.5; slope at bearing B (620 mm): 0.001339 > 0.001 rad". The masses are the JSON's, the
    places the scene's, the slope's limit its 0.001 rad, each converted here."""
    text = (PROBLEMS / "punch-press-shaft.toml").read_text(encoding="utf-8")
    assert 'force = "12 kN"' in text
    scene = write_scene(text.replace('force = "12 kN"', 'force = "40 kN"'), "weak-shaft.toml")
    status, out, err = main_cli("solve", scene, "--units", "imperial")
    assert status == 3, err
    status, raw, err = main_cli("solve", scene, "--json")
    candidates = json.loads(raw)["design"]["candidates"]
    ureg = unit_registry()
    reasons = [line for line in out.splitlines() if "the shaft cannot carry this" in line and line.startswith("  - ")]
    assert len(reasons) == sum("cannot carry" in c["reason"] for c in candidates) >= 2
    for line in reasons:
        (candidate,) = [c for c in candidates if line[4:].startswith(c["reason"].split(": the shaft")[0] + ": ")]
        pounds = ureg.Quantity(candidate["mass"], "kg").to("lb").magnitude
        assert f"the shaft cannot carry this {float(f'{pounds:.4g}'):,.4g} lb wheel: " in line
        assert f"at the shoulder at {ureg.Quantity(0.52, 'm').to('inch').magnitude:.4g} in" in line
        assert f"slope at bearing B ({ureg.Quantity(0.62, 'm').to('inch').magnitude:.4g} in)" in line
        assert f"> {ureg.Quantity(0.001, 'rad').to('deg').magnitude:.3g} deg" in line
        assert not re.search(r"[0-9] ?(mm|m|kg|rad|N·m|MPa)\b", line), line
