"""The display units (flyopt.report.display) against pint's own conversions."""

import pint
import pytest

from flyopt.report import display
from flyopt.units import DIMENSIONS

UREG = pint.UnitRegistry()

#: The pint spelling of each label.
PINT = {"N·m": "N*m", "kN·m": "kN*m", "lbf·ft": "lbf*ft", "ft·lbf": "ft*lbf", "kg·m²": "kg*m**2",
        "lb·ft²": "lb*ft**2", "N·m²": "N*m**2", "lbf·ft²": "lbf*ft**2", "kg/m³": "kg/m**3", "lb/in³": "lb/in**3",
        "m²": "m**2", "mm²": "mm**2", "in²": "in**2", "kg·m": "kg*m", "g·mm": "g*mm", "oz·in": "oz*in"}
#: The SI unit of each dimension (flyopt.units.DIMENSIONS, and the outputs' own for unbalance).
SI = {name: entry[1] for name, entry in DIMENSIONS.items()} | {"unbalance": "kg*m"}


@pytest.mark.parametrize("dimension", sorted(display.UNITS))
@pytest.mark.parametrize("system", display.SYSTEMS)
def test_every_factor_is_pints(dimension, system):
    name, factor = display.unit(dimension, system)
    if dimension == "dimensionless":
        assert (name, factor) == ("-", 1.0)
        return
    si = SI[dimension] or "dimensionless"
    assert factor == pytest.approx(UREG.Quantity(1.0, PINT.get(name, name)).to(si).magnitude, rel=1e-15)


def test_si_is_the_base_units_and_engineering_the_designers():
    assert all(display.unit(d, "si")[1] == 1.0 for d in display.UNITS)
    assert [display.label(d) for d in ("length", "angular_speed", "torque", "energy", "stress", "power")] == \
        ["mm", "rpm", "kN·m", "kJ", "MPa", "kW"]
    assert display.quantity_text(0.7441, "length") == "744.1 mm"
    assert display.quantity_text(157.07963267948966, "angular_speed", "imperial") == "1,500 rpm"
    assert display.quantity_text(None, "length") == "-"


def test_an_unknown_system_or_dimension_is_named():
    with pytest.raises(ValueError, match="allowed: engineering, si, imperial"):
        display.unit("length", "cgs")
    with pytest.raises(ValueError, match="no display unit for dimension 'colour'"):
        display.unit("colour")
