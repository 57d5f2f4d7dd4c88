"""Every scalar quantity a section reads is held to its dimension's magnitudes (flyopt.units.MAGNITUDES).

An outside audit of hostile inputs set one field of each shipped scene at a
time to 1e300 or 1e-320 in its unit. Fields without a range of their own were
read as given and failed deep in the computation, exit 1 with a message that
named no field: "float division by zero" (a train's shaft of 1e-320 mm, a
safety factor of 1e308), "Array must not contain infs or NaNs" (a shaft step
at 1e-300 mm), "Singular matrix", or an IPOPT that did not converge. Each is
now refused at load in one line naming the field and what is allowed, and a
field with a range of its own keeps its own words.
"""

import math
import shutil

import pytest
from conftest import PROBLEMS

from flyopt.cli.main import main
from flyopt.units import DIMENSIONS, MAGNITUDES, quantity

#: (scene, text in it, the text instead, field refused): the audit's findings.
FOUND = [
    ("engine-members.toml", 'mass = "1.2 kg"', 'mass = "1e300 kg"', "member[0].mass"),
    ("engine-members.toml", 'crank = "0.06 m"', 'crank = "1e-320 m"', "mechanism.crank"),
    ("four-cylinder-engine.toml", 'rod_mass = "0.45 kg"', 'rod_mass = "1e300 kg"', "engine.rod_mass"),
    (
        "four-cylinder-engine-shaft.toml",
        'rod_inertia = "0.0012 kg*m^2"',
        'rod_inertia = "1e300 kg*m^2"',
        "engine.rod_inertia",
    ),
    (
        "motor-press-drive-train.toml",
        'length = "150 mm", diameter = "38 mm"',
        'length = "150 mm", diameter = "1e-320 mm"',
        "shaft[1].train[1].diameter",
    ),
    (
        "motor-press-drive-train.toml",
        'length = "150 mm", diameter = "38 mm"',
        'length = "1e-300 mm", diameter = "38 mm"',
        "shaft[1].train[1].length",
    ),
    (
        "motor-press-drive-train.toml",
        'inertia = "1.2 kg*m^2" }',
        'inertia = "1e-320 kg*m^2" }',
        "shaft[1].train[4].inertia",
    ),
    ("punch-press-drive-shaft.toml", 'force = "4 kN"', 'force = "1e300 kN"', "shaft[1].loads[0].force"),
    ("punch-press-drive-shaft.toml", '{ to = "100 mm"', '{ to = "1e-300 mm"', "shaft[1].segments[0].to"),
    ("punch-press-drive-shaft.toml", '{ to = "640 mm"', '{ to = "1e300 mm"', "shaft[1].segments[2].to"),
    # [drive] and [[motor_option]] are read by name, not through a section's table: held to the same sizes
    ("press-drive.toml", 'max_startup = "15 s"', 'max_startup = "1e-320 s"', "drive.max_startup"),
    (
        "press-drive.toml",
        '[drive]\nmotors = "iec_4pole"',
        '[[motor_option]]\nname = "m"\nrated_power = "1e300 kW"\nrated_speed = "1440 rpm"\n'
        'synchronous_speed = "1500 rpm"\nrotor_inertia = "0.05 kg*m^2"\n[drive]',
        "motor_option[0].rated_power",
    ),
]


def _scene(tmp_path, name, old, new):
    for data in PROBLEMS.glob("*.csv"):  # the tables scenes name, beside it
        shutil.copy(data, tmp_path / data.name)
    text = (PROBLEMS / name).read_text(encoding="utf-8")
    assert old in text, old
    path = tmp_path / "scene.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.mark.parametrize("name, old, new, field", FOUND, ids=[case[3] for case in FOUND])
def test_a_quantity_beyond_its_dimensions_magnitudes_is_refused_naming_the_field(
    tmp_path, capsys, name, old, new, field
):
    path = _scene(tmp_path, name, old, new)
    assert main(["solve", str(path), "-q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert f": {field}: " in err and "is out of range (allowed: a size of " in err, err


def test_the_shipped_value_of_each_field_still_loads(tmp_path):
    """Each field above, as shipped, is within its dimension's magnitudes: the rule refuses none of them."""
    import flyopt

    for name in sorted({case[0] for case in FOUND}):
        flyopt.load(PROBLEMS / name)


@pytest.mark.parametrize(
    "value, refused",
    [(0.0, False), (1e-6, False), (-1e-6, False), (1e3, False), (-1e3, False), (9.99e-7, True), (-1.001e3, True)],
)
def test_a_length_is_held_to_a_micron_to_a_kilometre_in_size_or_zero(value, refused):
    """The bounds themselves: 0, or a size from a micron to a kilometre, either sign (a sign is the field's)."""
    from flyopt.errors import SceneError
    from flyopt.io.fields import check_scale

    if refused:
        with pytest.raises(SceneError, match=r"^mechanism.offset: .* is out of range \(allowed: a size of 1e-06"):
            check_scale(value, "length", "mechanism.offset", f"{value} m")
    else:
        check_scale(value, "length", "mechanism.offset", f"{value} m")


def test_a_tiny_offset_is_refused_by_check(tmp_path, capsys):
    path = _scene(tmp_path, "slider-crank-press.toml", "[mechanism]", '[mechanism]\noffset = "1e-9 m"')
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "mechanism.offset: '1e-9 m' is out of range" in err, err


def test_a_field_with_a_range_of_its_own_keeps_its_words(tmp_path, capsys):
    """machine.delta's own range is narrower than a plain number's magnitudes: its words, not the general rule's."""
    path = _scene(tmp_path, "shear-press.toml", "delta = 0.05", "delta = 1e-300")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "machine.delta: must lie between 1e-06 and 2" in err and "a size of" not in err, err


def test_a_safety_factor_beyond_any_design_is_refused(tmp_path, capsys):
    """A safety factor of 1e308 divided by zero (exit 1); 1e9 left IPOPT at its iteration limit (exit 1)."""
    for value in ("1e308", "1e9", "101"):
        path = _scene(tmp_path, "press-arms-wheel.toml", "safety_factor = 5", f"safety_factor = {value}")
        assert main(["check", str(path)]) == 2
        err = capsys.readouterr().err
        assert "design.safety_factor" in err and "allowed: 1 to 100" in err, err


def test_every_dimension_has_magnitudes_that_its_example_lies_within():
    """Each dimension's bounds are ordered, and the example a missing field's message gives lies within them."""
    import re

    assert set(MAGNITUDES) == set(DIMENSIONS)
    for dimension, (low, high, why) in MAGNITUDES.items():
        assert 0 <= low < high < math.inf and why, dimension
        example = re.search(r"e\.g\. '([^']+)'", DIMENSIONS[dimension][2])
        if example:
            value = quantity(example.group(1), dimension, "example")
            assert low <= abs(value) <= high, (dimension, example.group(1))


@pytest.mark.parametrize(
    "old, new, words",
    [  # fields with a range of their own: their words for a value beyond it, and a small one they allow read
        ("critical_margin = 0.1", "critical_margin = 2e9", "critical_margin: must be a share in [0, 1)"),
        ("critical_margin = 0.1", "critical_margin = 1e-10", None),
        ("critical_margin = 0.1", "critical_margin = 0.1\ndamping_ratio = 1e-10", None),
        ("critical_margin = 0.1", "critical_margin = 0.1\nsafety_factor = 500", "safety_factor: 500 is out of range"),
        ("critical_margin = 0.1", "critical_margin = 0.1\nsafety_factor = 100", None),
    ],
)
def test_a_described_shafts_fields_keep_their_own_ranges(tmp_path, capsys, old, new, words):
    """An outside review found these read through the general sizes first: a margin of 2e9 said "a size of
    1e-09 to 1e+09" for a share, and a damping ratio of 1e-10, which the field allows, was refused. A shaft's
    factor of safety is held to 1-100 as the design's and a material's are."""
    path = _scene(tmp_path, "four-cylinder-engine-shaft.toml", old, new)
    code = main(["check", str(path)])
    err = capsys.readouterr().err
    if words is None:
        assert code == 0, err
    else:
        assert code == 2 and words in err and "a size of" not in err, err


def test_a_tiny_angle_is_an_angle():
    """An angle divides nothing: however small, it is read (1e-13 deg of a crank position was refused)."""
    from flyopt.io.fields import check_scale

    check_scale(1e-15, "angle", "position.angle", "1e-13 deg")
