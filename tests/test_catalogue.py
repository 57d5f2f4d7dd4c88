"""The motor catalogue shipped as data (flyopt/data/motors.toml), checked against physics and the IEC tables.

Every figure of the catalogue is a source's; these tests check that the
figures agree with one another and with what the standards require: the
printed rated torque is P_n/ω_n to the source's rounding (or the source's own
9550 P/n, shown), the slip is a few per cent, the synchronous speed is
120 f/p, the rotor inertia and the mass grow with the frame, an IE3 motor
meets the IE3 minimum efficiency of IEC 60034-30-1 (typed below from the
standard and checked against the standard's own interpolation formula), and
the torque model built from a size (flyopt.machine.motor.InductionMotor)
gives the catalogue's rated torque at its rated speed.
"""

import math
import re
import sys
from importlib import resources

import pytest
from numpy.testing import assert_allclose

from conftest import assert_published
from flyopt.machine.catalogue import (RATING_TOLERANCE, Catalogue, CatalogueMotor, MotorDataError, catalogue,
                                      catalogue_names, read_catalogues)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

IE3_50HZ_4POLE = {0.75: 82.5, 1.1: 84.1, 1.5: 85.3, 2.2: 86.7, 3: 87.7, 4: 88.6, 5.5: 89.6, 7.5: 90.4,
                  11: 91.4, 15: 92.1, 18.5: 92.6, 22: 93.0, 30: 93.6, 37: 93.9, 45: 94.2, 55: 94.6}
"""Minimum efficiency [%] of IE3, 4 poles, 50 Hz, by rated output [kW]: IEC 60034-30-1:2014, Table 3
(the same figures as Regulation (EU) 2019/1781, Annex I, and UK SI 2021/745, Schedule 16, Table 22;
0.75 to 7.5 kW also as reproduced in Siemens' 'Efficiency classes and efficiencies according to
IEC 60034-30' table). Its rows are the IEC 60072-1 output steps."""

INTERPOLATION_50HZ_4POLE = {"IE2": (0.0278, -1.9247, 10.4395, 80.9761),
                            "IE3": (0.0773, -1.8951, 9.2984, 83.7025)}
"""Coefficients (A, B, C, D) of eta = A x^3 + B x^2 + C x + D [%], x = log10(P [kW]), 0.75 to 200 kW,
4 poles: UK SI 2021/745, Schedule 16, Table 28 (IEC 60034-30-1's interpolation for outputs between
the table's rows)."""

PRINTED_TORQUE = {"80M 0.75 kW": "P/omega", "180L 22 kW": "9550 P/n"}
"""How each source computed the rated torque it prints (see test_printed_rated_torque_...)."""


def _raw_sizes():
    """The [[iec_4pole.motor]] tables as the data file writes them (the printed figures, as text)."""
    text = resources.files("flyopt").joinpath("data", "motors.toml").read_text(encoding="utf-8")
    return {entry["name"]: entry for entry in tomllib.loads(text)["iec_4pole"]["motor"]}


def _printed(text, unit):
    """The number of a figure printed with its unit: '1445 rpm' -> '1445'."""
    match = re.fullmatch(rf"\s*([0-9.]+)\s*{re.escape(unit)}\s*", text)
    assert match, f"{text!r} is not a number in {unit}"
    return match.group(1)


def _ie(klass, kw):
    a, b, c, d = INTERPOLATION_50HZ_4POLE[klass]
    x = math.log10(kw)
    return ((a * x + b) * x + c) * x + d


SIZES = catalogue("iec_4pole").motors


# -- the standard's table ------------------------------------------------------------


@pytest.mark.parametrize("kw", sorted(IE3_50HZ_4POLE))
def test_the_typed_ie3_table_is_the_standards_interpolation_rounded(kw):
    """A typing error in IE3_50HZ_4POLE would show here: the same standard's formula rounds to every row."""
    assert round(_ie("IE3", kw), 1) == IE3_50HZ_4POLE[kw]


# -- every size --------------------------------------------------------------------


def test_the_catalogue_is_known_by_name_and_read_once():
    assert "iec_4pole" in catalogue_names()
    assert catalogue("iec_4pole") is catalogue("iec_4pole")
    assert [m.rated_power for m in SIZES] == sorted(m.rated_power for m in SIZES)


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_every_size_cites_its_source_and_gives_no_unsourced_price(motor):
    assert motor.source.strip()
    assert motor.price is None      # no price source is on file; see the data file's header
    assert catalogue("iec_4pole").unpriced == catalogue("iec_4pole").names


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_rated_power_is_an_iec_output_step(motor):
    assert any(math.isclose(motor.rated_power, kw * 1e3, rel_tol=1e-15) for kw in IE3_50HZ_4POLE)


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_synchronous_speed_is_120_f_over_p(motor):
    n0 = 120 * 50 / 4                                         # rpm, 50 Hz, 4 poles
    assert_allclose(motor.synchronous_speed, n0 * 2 * math.pi / 60, rtol=1e-15)


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_rated_speed_lies_below_synchronous_with_the_printed_slip(motor):
    n = float(_printed(_raw_sizes()[motor.name]["rated_speed"], "rpm"))
    assert 0 < motor.rated_speed < motor.synchronous_speed
    assert_allclose(motor.slip, (1500 - n) / 1500, rtol=1e-12)
    assert 0.01 < motor.slip < 0.06       # standard 4-pole motors of 0.75-55 kW run at 1-6 % slip


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_printed_rated_torque_is_power_over_rated_speed(motor):
    """The printed M_n against P_n/ω_n, to the last printed digit (conftest.assert_published).

    80M 0.75 kW: 750 W / (1445 rpm * 2π/60) = 750 / 151.320 = 4.9564 N*m, printed 5.0: agrees.
    180L 22 kW: 22000 W / (1465 rpm * 2π/60) = 22000 / 153.414 = 143.4024 N*m, printed 143.41,
    off by 0.008, more than the printed rounding (0.005). The data sheet uses the shop formula
    M = 9550 P/n (kW, rpm): 9550 * 22 / 1465 = 143.4130, which rounds to 143.41. The constant 9550
    rounds 30000/π = 9549.297, so it overstates every torque by 9550/9549.297 - 1 = 7.4e-5; flyopt
    uses P_n/ω_n.
    """
    raw = _raw_sizes()[motor.name]
    printed = _printed(raw["rated_torque"], "N*m")
    kw = float(_printed(raw["rated_power"], "kW"))
    rpm = float(_printed(raw["rated_speed"], "rpm"))
    exact = kw * 1e3 / (rpm * 2 * math.pi / 60)
    assert_allclose(motor.rated_torque, exact, rtol=1e-14)
    assert motor.published_rated_torque == float(printed)
    convention = PRINTED_TORQUE[motor.name]      # a new size must say how its source computes M_n
    if convention == "P/omega":
        assert_published(exact, printed)
    else:
        assert convention == "9550 P/n"
        assert_published(9550 * kw / rpm, printed)
        with pytest.raises(AssertionError):
            assert_published(exact, printed)
        assert_allclose(9550 * kw / rpm / exact - 1, 9550 / (30000 / math.pi) - 1, rtol=1e-9)


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
@pytest.mark.parametrize("model", ["linear", "kloss"])
def test_the_torque_model_gives_the_rated_torque_at_rated_speed(motor, model):
    characteristic = motor.motor()
    assert_allclose(characteristic.torque(motor.rated_speed, model), motor.rated_power / motor.rated_speed,
                    rtol=1e-12)
    assert abs(characteristic.torque(motor.synchronous_speed, model)) < 1e-12 * motor.rated_torque
    assert characteristic.breakdown_ratio == motor.breakdown_ratio


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_kloss_start_is_below_the_catalogue_locked_rotor_torque(motor):
    """The simplified Kloss curve through (ω_n, M_n) with M_b/M_n = k starts with
    M(s=1)/M_n = 2k/(1/s_b + s_b), s_b = s_n (k + sqrt(k^2 - 1)): well under a deep-bar rotor's
    locked-rotor torque, so run-up times from it err long (flyopt.machine.motor's note)."""
    k, s_n = motor.breakdown_ratio, motor.slip
    s_b = s_n * (k + math.sqrt(k * k - 1))
    kloss_start = 2 * k / (1 / s_b + s_b)
    assert_allclose(motor.motor().starting_torque() / motor.rated_torque, kloss_start, rtol=1e-12)
    assert kloss_start < motor.locked_rotor_ratio


def _frame_key(frame):
    match = re.fullmatch(r"(\d+)([SML])", frame)
    assert match, frame
    return int(match.group(1)), "SML".index(match.group(2))


def test_rotor_inertia_and_mass_grow_with_the_frame():
    by_frame = sorted(SIZES, key=lambda m: _frame_key(m.frame))
    assert [m.name for m in by_frame] == [m.name for m in SIZES]      # bigger output, bigger frame
    for small, big in zip(by_frame, by_frame[1:]):
        assert small.rotor_inertia < big.rotor_inertia
        assert small.mass < big.mass


@pytest.mark.parametrize("motor", SIZES, ids=lambda m: m.name)
def test_efficiency_agrees_with_the_stated_ie_class(motor):
    """IE3 sizes meet the IE3 minimum for their output; an IE1 size stays below IE2's (or it would be IE2)."""
    kw = motor.rated_power / 1e3
    percent = motor.efficiency * 100
    assert motor.efficiency_class in ("IE1", "IE3"), "no IEC table is typed here for this class"
    if motor.efficiency_class == "IE3":
        assert percent >= IE3_50HZ_4POLE[kw] - 1e-9
    else:
        assert percent < round(_ie("IE2", kw), 1)


# -- the neighbouring sizes of a continuous rating -------------------------------------


def _size(kw, rpm=1450.0):
    w = 2 * math.pi / 60
    return CatalogueMotor(f"{kw} kW", kw * 1e3, rpm * w, 1500 * w, 0.01 * kw, breakdown_ratio=2.5)


LADDER = Catalogue("ladder", tuple(_size(kw) for kw in (7.5, 1.1, 4.0, 2.2)))


@pytest.mark.parametrize("rating, below, above", [
    (3e3, "2.2 kW", "4.0 kW"),
    (4e3, "2.2 kW", "4.0 kW"),                       # a size itself is "at or above"
    (4e3 * (1 + 0.1 * RATING_TOLERANCE), "2.2 kW", "4.0 kW"),   # round-off above a size is that size
    (4e3 * (1 - 0.1 * RATING_TOLERANCE), "2.2 kW", "4.0 kW"),
    (4e3 * (1 + 1e-6), "4.0 kW", "7.5 kW"),
    (500.0, None, "1.1 kW"),
    (1.1e3, None, "1.1 kW"),
    (7.5e3, "4.0 kW", "7.5 kW"),
    (10e3, "7.5 kW", None),
])
def test_neighbours_are_the_size_at_or_above_and_the_one_below(rating, below, above):
    found = LADDER.neighbours(rating)
    assert (found.below.name if found.below else None, found.above.name if found.above else None) == (below, above)


def test_neighbours_in_the_shipped_catalogue():
    found = catalogue("iec_4pole").neighbours(5e3)
    assert (found.below.name, found.above.name) == ("80M 0.75 kW", "180L 22 kW")


@pytest.mark.parametrize("rating", [0.0, -1.0, math.nan, math.inf, True, "5 kW", None])
def test_neighbours_refuse_a_rating_that_is_not_a_power(rating):
    with pytest.raises(ValueError, match="positive finite power"):
        LADDER.neighbours(rating)


# -- what the catalogue refuses ------------------------------------------------------


@pytest.mark.parametrize("name, match", [
    ("iec_4pol", r"not known; did you mean 'iec_4pole'\? \(known: iec_4pole\)"),
    ("nema", r"not known \(known: iec_4pole\)"),
    (4, r"not known"),
])
def test_an_unknown_catalogue_is_refused_listing_the_known(name, match):
    with pytest.raises(ValueError, match=match):
        catalogue(name)


def test_a_catalogue_has_one_size_per_rating_and_per_name():
    with pytest.raises(MotorDataError, match="same rated power") as err:
        Catalogue("c", (_size(4.0), _size(2.2), CatalogueMotor("other", 4e3, 150.0, 157.0, 0.04)))
    assert (err.value.field, err.value.index) == ("rated_power", 2)
    with pytest.raises(MotorDataError, match="given twice") as err:
        Catalogue("c", (_size(4.0), _size(2.2), _size(4.0)))
    assert (err.value.field, err.value.index) == ("name", 2)
    with pytest.raises(MotorDataError, match="no motor"):
        Catalogue("c", ())


@pytest.mark.parametrize("change, field", [
    ({"rated_power": 0.0}, "rated_power"),
    ({"rated_speed": 160.0}, "rated_speed"),          # above synchronous (157.08 rad/s)
    ({"rotor_inertia": -0.01}, "rotor_inertia"),
    ({"breakdown_ratio": 1.0}, "breakdown_ratio"),
    ({"efficiency": 92.0}, "efficiency"),
    ({"price": -1.0}, "price"),
    ({"mass": math.nan}, "mass"),
    ({"efficiency_class": "IE9"}, "efficiency_class"),
    ({"name": ""}, "name"),
])
def test_a_size_out_of_range_names_its_field(change, field):
    values = {"name": "m", "rated_power": 4e3, "rated_speed": 150.0, "synchronous_speed": 50 * math.pi,
              "rotor_inertia": 0.01} | change
    with pytest.raises(MotorDataError) as err:
        CatalogueMotor(**values)
    assert err.value.field == field


GOOD = """
[c]
description = "d"
[[c.motor]]
name = "a"
rated_power = "4 kW"
rated_speed = "1440 rpm"
synchronous_speed = "1500 rpm"
rotor_inertia = "0.01 kg*m^2"
source = "s"
"""


@pytest.mark.parametrize("old, new, match", [
    ('source = "s"\n', "", r"motor\[0\] has no source"),
    ('source = "s"', 'source = " "', r"motor\[0\]\.source must cite"),
    ('name = "a"', 'name = "a"\npoles = 4', r"motor\[0\] has unknown keys \['poles'\]"),
    ('"1440 rpm"', '"1500 rpm"', r"motor\[0\]\.rated_speed: .*must be below the synchronous speed"),
    ('"4 kW"', '"4 kg"', r"motor\[0\]\.rated_power: .*wrong dimension"),
    ('description = "d"', 'description = "d"\nprice = 3', r" has unknown keys \['price'\]"),
    ('source = "s"', 'source = "s"\n[[c.motor]]\nname = "b"\nrated_power = "4 kW"\nrated_speed = "1440 rpm"\n'
                     'synchronous_speed = "1500 rpm"\nrotor_inertia = "0.01 kg*m^2"\nsource = "s"',
     r"motor\[1\]: motor 'b' has the same rated power"),
    ("[[c.motor]]", "[[c.other]]", r"unknown keys \['other'\]"),
])
def test_the_data_file_reader_names_the_file_the_size_and_the_field(old, new, match):
    assert old in GOOD, "test bug: the snippet is not in the text"
    with pytest.raises(ValueError, match=r"^motors\.toml: catalogue 'c'.*" + match):
        read_catalogues(GOOD.replace(old, new, 1), origin="motors.toml")


def test_the_data_file_reader_reads_a_good_text():
    (only,) = read_catalogues(GOOD).values()
    assert_allclose(only.motors[0].rated_speed, 1440 * math.pi / 30, rtol=1e-15)
