"""The display units (flyopt.report.display) against pint's own conversions."""

from pathlib import Path

import pytest
from conftest import unit_registry

from flyopt.report import display
from flyopt.units import DIMENSIONS

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


#: The pint spelling of each label.
PINT = {
    "N·m": "N*m",
    "kN·m": "kN*m",
    "lbf·ft": "lbf*ft",
    "ft·lbf": "ft*lbf",
    "kg·m²": "kg*m**2",
    "lb·ft²": "lb*ft**2",
    "N·m²": "N*m**2",
    "lbf·ft²": "lbf*ft**2",
    "kg/m³": "kg/m**3",
    "lb/in³": "lb/in**3",
    "m²": "m**2",
    "mm²": "mm**2",
    "in²": "in**2",
    "kg·m": "kg*m",
    "g·mm": "g*mm",
    "oz·in": "oz*in",
    "rad/s²": "rad/s**2",
    "m/s²": "m/s**2",
    "ft/s²": "ft/s**2",
}
#: The SI unit of each dimension (flyopt.units.DIMENSIONS, and the outputs' own for unbalance;
#: the specific unbalance e_per = U/m of ISO 21940-11 is a length).
SI = {name: entry[1] for name, entry in DIMENSIONS.items()} | {
    "unbalance": "kg*m",
    "eccentricity": "m",
    "angular_acceleration": "rad/s**2",
    "acceleration": "m/s**2",
}


@pytest.mark.parametrize("dimension", sorted(display.UNITS))
@pytest.mark.parametrize("system", display.SYSTEMS)
def test_every_factor_is_pints(dimension, system):
    name, factor = display.unit(dimension, system)
    if dimension == "dimensionless":
        assert (name, factor) == ("-", 1.0)
        return
    si = SI[dimension] or "dimensionless"
    assert factor == pytest.approx(unit_registry().Quantity(1.0, PINT.get(name, name)).to(si).magnitude, rel=1e-15)


def test_si_is_the_base_units_and_engineering_the_designers():
    assert all(display.unit(d, "si")[1] == 1.0 for d in display.UNITS)
    assert [display.label(d) for d in ("length", "angular_speed", "torque", "energy", "stress", "power")] == [
        "mm",
        "rpm",
        "kN·m",
        "kJ",
        "MPa",
        "kW",
    ]
    assert display.quantity_text(0.7441, "length") == "744.1 mm"
    assert display.quantity_text(157.07963267948966, "angular_speed", "imperial") == "1,500 rpm"
    assert display.quantity_text(None, "length") == "-"


def test_an_unknown_system_or_dimension_is_named():
    with pytest.raises(ValueError, match="allowed: engineering, si, imperial"):
        display.unit("length", "cgs")
    with pytest.raises(ValueError, match="no display unit for dimension 'colour'"):
        display.unit("colour")


@pytest.mark.parametrize(
    "value, digits, text",
    [
        (1256.33, 6, "1,256.33"),
        (1500.0, 6, "1,500"),
        (0.000123456789, 6, "0.000123457"),
        # a whole number longer than the digits asked for is rounded to them, not printed whole
        (23053542.3, 6, "23,053,500"),
        (5120982.0, 4, "5,121,000"),
        (999999.7, 6, "1,000,000"),
        (-1858.78, 6, "-1,858.78"),
        (1e9, 6, "1.00000e+09"),
        (0.0, 6, "0"),
        (None, 6, "-"),
    ],
)
def test_numbers_carry_the_digits_asked_for(value, digits, text):
    assert display.number(value, digits) == text


def test_a_field_is_shown_in_the_dimension_the_json_gives_it():
    """dimension_of reads flyopt.outputs.results' table: the JSON's unit and the shown one are one dimension."""
    from flyopt.outputs.quantities import unit_of

    for name in (
        "a_max",
        "d_outer",
        "hoop_stress",
        "omega_mean",
        "inertia",
        "rated_power",
        "unbalance_permissible",
        "delta",
        "gd2_required",
        "startup_time",
    ):
        dimension = display.dimension_of(name)
        si = SI[dimension] or "dimensionless"
        assert unit_registry().Quantity(1.0, unit_of(name)).to(si).magnitude == pytest.approx(1.0, rel=1e-15), name
    assert display.field_text(1256.33, "a_max") == "1.256 kJ"  # four figures by default (issue 29)
    assert display.field_text(0.6, "d_outer", "imperial") == "23.62 in"
    assert display.field_number(0.6, "d_outer") == "600" and display.field_number(None, "d_outer") == "-"
    assert display.heading("D_outer", "d_outer", "si") == "D_outer [m]"
    assert display.heading("achieved δ", "achieved_delta") == "achieved δ"
    with pytest.raises(ValueError, match="'material' is not a quantity"):
        display.dimension_of("material")


def test_a_drive_trains_stiffnesses_in_each_system():
    """A spring of the torsional train in each system: 1 lbf·ft = 1.3558179483314004 N·m (exact: 0.3048 m ×
    4.4482216152605 N), 1 lbf/in = 4.4482216152605 N / 0.0254 m; engineering takes the prefix the value needs."""
    assert display.quantity_text(1.093e5, "torsional_stiffness", "engineering") == "109.3 kN·m/rad"
    assert display.quantity_text(6.043e6, "torsional_stiffness", "engineering") == "6.043 MN·m/rad"
    assert display.quantity_text(1e5, "torsional_stiffness", "imperial") == "73,760 lbf·ft/rad"
    assert display.quantity_text(2.4e6, "stiffness", "engineering") == "2.4 MN/m"
    assert display.quantity_text(4.4482216152605 / 0.0254 * 250.0, "stiffness", "imperial") == "250 lbf/in"
    assert display.quantity_text(250.0, "stiffness", "si") == "250 N/m"


def test_a_mode_shape_never_writes_minus_zero():
    """motor-press-drive-train's mode 4 read '+0.00, +0.00, -0.00, ...': a node's tiny negative amplitude."""
    from flyopt.report.display import mode_shape

    assert mode_shape([1.0, -0.43, -0.001, 0.004, -0.005, 0.0]) == "+1.00, -0.43, +0.00, +0.00, -0.01, +0.00"


def test_round_off_of_a_scale_is_zero_and_a_difference_above_it_stays():
    """display.without_noise: 1e-12 of the scale (NOISE_RTOL) and less is round-off, written 0; more is kept.
    press-drive's works of 15 kJ a cycle left -1.819e-12 J (by hand: 1.2e-16 of them)."""
    assert display.without_noise(-1.819e-12, 15e3) == 0.0
    assert display.without_noise(1e-3, 15e3) == 1e-3  # 6.7e-8 of the scale: a real difference
    assert display.without_noise(0.0, 0.0) == 0.0 and display.without_noise(5.0, 0.0) == 5.0


@pytest.mark.slow  # 6 s: press-drive's drive designed and its report's document built
def test_the_cycle_balance_is_zero_where_it_is_round_off_of_the_work():
    """press-drive's report said 'W_d − W_r = -1.819e-12 J' where every other report said 0: the difference of
    two works of a few kJ, round-off under 1e-12 of them (display.NOISE_RTOL)."""
    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Paragraph

    inputs = collect(PROBLEMS / "press-drive.toml")
    document = build(inputs, "engineering", figures=False)
    said = [
        "".join(getattr(part, "text", part) for part in block.text)
        for section in document.sections
        for block in section.blocks
        if isinstance(block, Paragraph) and "The cycle balances" in str(block.text)
    ]
    assert len(said) == 1 and "W_d − W_r = 0 J " in said[0], said
    document.close()
