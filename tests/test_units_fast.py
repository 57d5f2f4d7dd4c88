"""The built-in unit table reads the common forms exactly as pint does, and nothing else.

flyopt.units reads "1500 rpm", "3.5 kN*m" or "mm^2" from a table of pint's
own factors instead of importing pint (half a second at start-up). Every entry
and every spelling is checked here against pint itself, bit for bit: the table
is an optimization and must never change a number or a message.
"""

import math
import subprocess
import sys

import pytest
from conftest import PROBLEMS
from hypothesis import given, settings
from hypothesis import strategies as st

from flyopt import units
from flyopt.errors import SceneError

ENTRIES = [(dim, unit) for dim, table in units.FAST_UNITS.items() for unit in table]

MAGNITUDES = [
    "0",
    "1",
    "-1",
    "+2",
    "7",
    "1500",
    "123456789012345678901",
    "0.1",
    "-0.0",
    "3.5",
    ".5",
    "7.",
    "2.5e3",
    "1E-3",
    "1e-300",
    "1.7976931348623157e308",
    "0.30000000000000004",
    "01.5",
    "6e0",
]


def same(a, b):
    """Equal floats, the sign of zero included."""
    return (
        type(a) is type(b)
        and (a == b or (math.isnan(a) and math.isnan(b)))
        and math.copysign(1.0, a) == math.copysign(1.0, b)
    )


def pint_value(text, dimension):
    """What pint makes of the text (flyopt's path through pint), or the error it raises."""
    try:
        return units._pint_number(text, dimension, "f")
    except (SceneError, OverflowError) as err:
        return type(err)


@pytest.mark.parametrize("dimension, unit", ENTRIES, ids=[f"{d}:{u}" for d, u in ENTRIES])
def test_every_entry_is_pints_factor_for_every_magnitude(dimension, unit):
    for magnitude in MAGNITUDES:
        for text in (f"{magnitude} {unit}", f" {magnitude}\t{unit} "):
            fast = units._table_number(text, dimension)
            assert fast is not None, text
            assert same(fast, pint_value(text, dimension)), (text, fast, pint_value(text, dimension))
    if unit.startswith("/"):  # "/min" alone is no quantity: pint says why
        assert units._table_number(unit, dimension) is None and pint_value(unit, dimension) is SceneError
    else:  # the unit alone is one of it
        assert same(units._table_number(unit, dimension), pint_value(unit, dimension))


@pytest.mark.parametrize(
    "text, dimension",
    [
        ("5%", "dimensionless"),
        ("5 %", "dimensionless"),
        ("1500/min", "angular_speed"),
        ("1500 /min", "angular_speed"),
        ("1500 1/min", "angular_speed"),
        ("0.05", "dimensionless"),
        ("1500", "angular_speed"),
        ("-0", "torque"),
        ("-0 N*m", "torque"),
        ("25 Hz", "angular_speed"),
        ("1500 min^-1", "angular_speed"),
        ("%", "dimensionless"),
    ],
)
def test_short_spellings_match_pint(text, dimension):
    fast = units._table_number(text, dimension)
    assert fast is not None
    assert same(fast, pint_value(text, dimension))


@pytest.mark.parametrize(
    "text, dimension",
    [
        ("1500 m", "angular_speed"),  # a unit of another dimension: pint says what is wrong
        ("50 %", "angular_speed"),
        ("90 deg", "torque"),
        ("1500rpm", "angular_speed"),
        ("0150 rpm", "angular_speed"),  # not a Python number: pint reads it as it reads it
        ("00 rpm", "angular_speed"),
        ("1_500 rpm", "angular_speed"),
        ("nan rpm", "angular_speed"),
        ("inf", "dimensionless"),
        ("10**3 kg", "mass"),
        ("1 m^0.5 * m^1.5", "area"),
        ("2 kg*m^(2)", "inertia"),
        ("1500 RPM", "angular_speed"),
        ("1500 rpm rpm", "angular_speed"),
        ("1500 rpm\n", "torque"),
        ("١٥٠٠ rpm", "angular_speed"),
        ("1500\u00a0rpm", "angular_speed"),
        ("0.5 rad/rad", "dimensionless"),
        ("1500 rpm # fast", "angular_speed"),
        ("- 5 N*m", "torque"),
        ("1e5e3 m", "length"),
    ],
)
def test_anything_else_goes_to_pint(text, dimension):
    assert units._table_number(text, dimension) is None


NUMBERS = st.one_of(
    st.integers(-(10**20), 10**20).map(str),
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.floats(-1e6, 1e6, allow_nan=False).map(lambda x: f"{x:.6f}"),
    st.floats(1e-30, 1e30).map(lambda x: f"{x:.3e}"),
)


@settings(max_examples=300, deadline=None)
@given(number=NUMBERS, entry=st.sampled_from(ENTRIES), blank=st.sampled_from([" ", "  ", "\t"]))
def test_random_numbers_match_pint(number, entry, blank):
    dimension, unit = entry
    text = f"{number}{blank}{unit}"
    fast = units._table_number(text, dimension)
    assert fast is not None, text
    assert same(fast, pint_value(text, dimension)), text


@pytest.mark.parametrize(
    "text, dimension",
    [("1e400 rpm", "angular_speed"), ("-1e400 N*m", "torque"), ("1e400", "dimensionless"), ("9e307 kN", "force")],
)
def test_beyond_the_floats_is_refused_as_before(text, dimension):
    """A number beyond the floats becomes infinite either way, and is refused as not finite."""
    assert math.isinf(units._table_number(text, dimension))
    assert same(units._table_number(text, dimension), pint_value(text, dimension))
    with pytest.raises(SceneError, match="must be finite"):
        units.quantity(text, dimension, "f")


def test_problem_scenes_load_without_pint():
    """Every scene in problems/ is read from the table: pint is never imported."""
    code = (
        "import sys; from pathlib import Path; from flyopt.io.scene import load\n"
        f"for p in sorted(Path({str(PROBLEMS)!r}).glob('*.toml')): load(p)\n"
        "print('pint' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"


def test_a_wrong_unit_still_says_what_pint_says():
    with pytest.raises(SceneError, match=r"machine.speed: '1500 m' has the wrong dimension: expected a rotational"):
        units.quantity("1500 m", "angular_speed", "machine.speed")
    with pytest.raises(SceneError, match=r"cannot read '1500 rpn' as a rotational speed"):
        units.quantity("1500 rpn", "angular_speed", "machine.speed")
