"""Bad values of [drive] and [[motor_option]] (issue 14, part 4): exit 2, one line naming the file and the field.

Every field is tried with what an engineer might mistype: an unknown
catalogue, a ratio range reversed, empty or non-positive, a range where fixed
ratios were meant, a time without a time unit, a motor faster than its
synchronous speed, an efficiency in per cent without the '%', a cost
objective without prices. The good scenes are read back field by field.
"""

import math

import pytest
from numpy.testing import assert_allclose
from test_input_failures import BASE, assert_refused, cli  # noqa: F401 (cli is a fixture)

import flyopt
from flyopt.errors import SceneError
from flyopt.io.drive import drive_spec
from flyopt.machine.catalogue import catalogue

DRIVE = """
[drive]
motors = "iec_4pole"
ratio = [2, 8]
objective = "mass"
max_startup = "12 s"
thermal = true
"""
OPTIONS = """
[[motor_option]]
name = "small"
rated_power = "4 kW"
rated_speed = "1440 rpm"
synchronous_speed = "1500 rpm"
rotor_inertia = "0.012 kg*m^2"
breakdown_ratio = 3.0
price = 400

[[motor_option]]
name = "big"
rated_power = "7.5 kW"
rated_speed = "1455 rpm"
synchronous_speed = "1500 rpm"
rotor_inertia = "0.03 kg*m^2"
price = 620
"""
GOOD = BASE + DRIVE
#: A wheel material with a price, the only one the design may use: a drive by cost needs it.
PRICED_WHEEL = """
[[material]]
name = "priced_iron"
density = "7200 kg/m^3"
max_rim_speed = "36 m/s"
cost = "2.1 1/kg"

[design]
materials = ["priced_iron"]
"""
GOOD_OPTIONS = BASE + DRIVE.replace('motors = "iec_4pole"\n', "") + OPTIONS

DRIVE_CASES = [
    ('motors = "iec_4pole"', 'motors = "iec_2pole"', "drive.motors", r"not known.*\(known: iec_4pole\)"),
    ('motors = "iec_4pole"', 'motors = "iec_4pol"', "drive.motors", r"did you mean 'iec_4pole'"),
    ('motors = "iec_4pole"', "motors = 4", "drive.motors", "name of a motor catalogue"),
    ('motors = "iec_4pole"\n', "", "drive.motors", "is missing"),
    ("ratio = [2, 8]", "ratio = [8, 2]", "drive.ratio", "min < max"),
    ("ratio = [2, 8]", "ratio = [4, 4]", "drive.ratio", "min < max"),
    ("ratio = [2, 8]", "ratio = [0, 8]", "drive.ratio", "positive"),
    ("ratio = [2, 8]", "ratio = [-2, 8]", "drive.ratio", "positive"),
    ("ratio = [2, 8]", "ratio = [2, 4, 8]", "drive.ratio", r"range \[min, max\].*ratios = \[\.\.\.\]"),
    ("ratio = [2, 8]", "ratio = 4", "drive.ratio", r"for fixed ratios write ratios = \[4\]"),
    ("ratio = [2, 8]", 'ratio = [2, "8 m"]', "drive.ratio[1]", "wrong dimension"),
    ("ratio = [2, 8]", "ratio = [2, 8]\nratios = [3]", "drive.ratios", "not both"),
    ("ratio = [2, 8]\n", "", "drive.ratio", "is missing"),
    ("ratio = [2, 8]", "ratios = []", "drive.ratios", "non-empty list"),
    ("ratio = [2, 8]", "ratios = [2, 2]", "drive.ratios[1]", "given twice"),
    ("ratio = [2, 8]", "ratios = [3, 0]", "drive.ratios[1]", "positive"),
    ('objective = "mass"', 'objective = "price"', "drive.objective", r"not known \(allowed: mass, cost\)"),
    (
        'objective = "mass"',
        'objective = "cost"',
        "drive.objective",
        r"needs a price for every motor; the catalogue 'iec_4pole' gives none",
    ),
    ('max_startup = "12 s"', 'max_startup = "12 m"', "drive.max_startup", "wrong dimension: expected a time"),
    ('max_startup = "12 s"', 'max_startup = "0 s"', "drive.max_startup", "positive time"),
    ('max_startup = "12 s"', "max_startup = -3", "drive.max_startup", "positive time"),
    ("thermal = true", 'thermal = "yes"', "drive.thermal", "true or false"),
    ("thermal = true", "thermal = true\nspeed = 3", "drive.speed", "unknown key"),
    (
        "[drive]",
        '[[motor_option]]\nrated_power = "4 kW"\nrated_speed = "1440 rpm"\nsynchronous_speed = "1500 rpm"\n'
        'rotor_inertia = "0.01 kg*m^2"\n[drive]',
        "drive.motors",
        "not both",
    ),
]

OPTION_CASES = [
    ('rated_power = "4 kW"\n', "", "motor_option[0].rated_power", "is missing"),
    ('rotor_inertia = "0.03 kg*m^2"\n', "", "motor_option[1].rotor_inertia", "is missing"),
    ('rated_power = "4 kW"', 'rated_power = "4 kg"', "motor_option[0].rated_power", "wrong dimension"),
    (
        'rated_speed = "1440 rpm"',
        'rated_speed = "1520 rpm"',
        "motor_option[0].rated_speed",
        r"rated speed \(1520 rpm\) must be below the synchronous speed \(1500 rpm\)",
    ),
    (
        'rated_speed = "1440 rpm"',
        "rated_speed = 1440",
        "motor_option[0].rated_speed",  # rad/s, not rpm
        "must be below the synchronous speed",
    ),
    ('rotor_inertia = "0.012 kg*m^2"', 'rotor_inertia = "-0.012 kg*m^2"', "motor_option[0].rotor_inertia", "> 0"),
    ("breakdown_ratio = 3.0", "breakdown_ratio = 0.9", "motor_option[0].breakdown_ratio", "> 1"),
    (
        "breakdown_ratio = 3.0",
        "breakdown_ratio = 3.0\nefficiency = 92",
        "motor_option[0].efficiency",
        r"fraction in \(0, 1\)",
    ),
    (
        "breakdown_ratio = 3.0",
        'breakdown_ratio = 3.0\nefficiency_class = "IE9"',
        "motor_option[0].efficiency_class",
        "not an IE code",
    ),
    ("breakdown_ratio = 3.0", "breakdown_ratio = 3.0\nmass = 0", "motor_option[0].mass", "> 0"),
    ("price = 400", "price = -400", "motor_option[0].price", ">= 0"),
    ("price = 400", 'price = "400 EUR"', "motor_option[0].price", "cannot read"),
    ('name = "small"', 'name = "small"\npoles = 4', "motor_option[0].poles", "unknown key"),
    ('name = "small"', 'name = ""', "motor_option[0].name", "non-empty string"),
    ('name = "big"', 'name = "small"', "motor_option[1].name", "given twice"),
    ('rated_power = "7.5 kW"', 'rated_power = "4 kW"', "motor_option[1].rated_power", "same rated power"),
]


@pytest.mark.parametrize("old, new, field, match", DRIVE_CASES)
@pytest.mark.parametrize("command", ["check", "solve"])
def test_bad_drive_field_is_refused_in_one_line(tmp_path, cli, command, old, new, field, match):
    assert old in GOOD, "test bug: the snippet is not in the scene"
    path = tmp_path / "scene.toml"
    path.write_text(GOOD.replace(old, new, 1))
    assert_refused(cli(command, path), path, field, match)


@pytest.mark.parametrize("old, new, field, match", OPTION_CASES)
@pytest.mark.parametrize("command", ["check", "solve"])
def test_bad_motor_option_is_refused_in_one_line(tmp_path, cli, command, old, new, field, match):
    assert old in GOOD_OPTIONS, "test bug: the snippet is not in the scene"
    path = tmp_path / "scene.toml"
    path.write_text(GOOD_OPTIONS.replace(old, new, 1))
    assert_refused(cli(command, path), path, field, match)


@pytest.mark.parametrize(
    "text, field, match",
    [
        (BASE.replace('title = "t"', 'title = "t"\ndrive = 3'), "drive", "must be a table"),
        (BASE + OPTIONS, "drive", r"is missing: \[\[motor_option\]\] tables are the motors of a \[drive\]"),
        (
            BASE.replace('title = "t"', 'title = "t"\nmotor_option = 3') + DRIVE.replace('motors = "iec_4pole"\n', ""),
            "motor_option",
            "array of tables",
        ),
        (
            GOOD_OPTIONS.replace("price = 620\n", "").replace('objective = "mass"', 'objective = "cost"'),
            "drive.objective",
            r"'cost' needs a price for every motor option; none is given for 'big'",
        ),
    ],
)
def test_bad_drive_section_is_refused_in_one_line(tmp_path, cli, text, field, match):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    assert_refused(cli("check", path), path, field, match)


# -- good scenes, read back ----------------------------------------------------------


def test_a_drive_on_the_catalogue_is_read(tmp_path, cli):
    path = tmp_path / "scene.toml"
    path.write_text(GOOD)
    result = cli("check", path)
    assert result.returncode == 0, result.stderr
    spec = flyopt.load(path).drive
    assert spec.motors is catalogue("iec_4pole")
    assert (spec.ratio_range, spec.ratios, spec.objective, spec.max_startup, spec.thermal) == (
        (2.0, 8.0),
        None,
        "mass",
        12.0,
        True,
    )


def test_the_drive_defaults_and_fixed_ratios(write_scene):
    text = (
        GOOD.replace("ratio = [2, 8]", "ratios = [5, 2, 3.5]")
        .replace('objective = "mass"\n', "")
        .replace('max_startup = "12 s"\n', "")
        .replace("thermal = true\n", "")
    )
    spec = flyopt.load(write_scene(text)).drive
    assert (spec.ratio_range, spec.ratios, spec.objective, spec.max_startup, spec.thermal) == (
        None,
        (2.0, 3.5, 5.0),
        "mass",
        None,
        True,
    )


@pytest.mark.parametrize("written, seconds", [('"0.2 min"', 12.0), ('"500 ms"', 0.5), ("12", 12.0), ('"12"', 12.0)])
def test_max_startup_takes_any_time_unit_and_plain_seconds(write_scene, written, seconds):
    spec = flyopt.load(write_scene(GOOD.replace('"12 s"', written))).drive
    assert_allclose(spec.max_startup, seconds, rtol=1e-15)


def test_motor_options_are_read_in_si_and_sorted_by_rating(tmp_path, cli):
    text = GOOD_OPTIONS.replace('objective = "mass"', 'objective = "cost"') + PRICED_WHEEL
    path = tmp_path / "scene.toml"
    path.write_text(text.replace('name = "small"\n', ""))  # a nameless option is named by its table
    result = cli("check", path)
    assert result.returncode == 0, result.stderr
    spec = flyopt.load(path).drive
    assert spec.objective == "cost" and spec.motors.name == "motor_option"
    small, big = spec.motors
    assert (small.name, big.name) == ("motor_option[0]", "big")
    rpm = math.pi / 30
    assert_allclose(
        [small.rated_power, small.rated_speed, small.synchronous_speed, small.rotor_inertia],
        [4e3, 1440 * rpm, 1500 * rpm, 0.012],
        rtol=1e-15,
    )
    assert (small.breakdown_ratio, small.price, big.breakdown_ratio, big.price) == (3.0, 400.0, None, 620.0)
    assert_allclose(small.rated_torque, 4e3 / (1440 * rpm), rtol=1e-15)


def test_a_cost_objective_needs_every_material_priced():
    """With the design's materials known, "cost" refuses one without a cost per kg (Material.cost)."""
    from flyopt.design.materials import builtin_materials, make_material

    options = [
        {
            "name": "m",
            "rated_power": "4 kW",
            "rated_speed": "1440 rpm",
            "synchronous_speed": "1500 rpm",
            "rotor_inertia": "0.012 kg*m^2",
            "price": 400,
        }
    ]
    raw = {"ratio": [2, 8], "objective": "cost"}
    unpriced = builtin_materials()
    assert unpriced["cast_iron"].cost is None
    with pytest.raises(SceneError, match=r"drive\.objective: 'cost' needs a cost per kg .*cast_iron") as err:
        drive_spec(raw, options, (), materials=unpriced)
    assert err.value.field == "drive.objective"
    priced = {"grey": make_material("grey", density=7200.0, max_rim_speed=36.0, cost=2.1)}
    assert drive_spec(raw, options, (), materials=priced).objective == "cost"


def test_a_mass_objective_needs_every_motor_mass(tmp_path, cli):
    """objective = "mass" adds the motor's mass to the wheel's: an option without one is refused by name."""
    path = tmp_path / "scene.toml"
    path.write_text(GOOD_OPTIONS)  # the options give prices, not masses
    assert_refused(
        cli("check", path),
        path,
        "drive.objective",
        r"'mass' is the motor's mass plus the wheel's, and none is given for 'small, big'",
    )


def test_a_cost_objective_refuses_unpriced_wheel_materials_from_the_scene(tmp_path, cli):
    """The scene's own design materials reach the drive's check: the textbook pair has no price."""
    path = tmp_path / "scene.toml"
    path.write_text(GOOD_OPTIONS.replace('objective = "mass"', 'objective = "cost"'))
    assert_refused(
        cli("check", path),
        path,
        "drive.objective",
        r"'cost' needs a cost per kg for every material the flywheel may be made of; "
        r"none is given for 'cast_iron, cast_steel'",
    )
