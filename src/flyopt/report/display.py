"""Units of the user's choice for what people read: the text report, the plots, the engineering report.

flyopt computes and writes its files in SI (docs/nomenclature.md; the JSON
and the tables stay SI whatever is shown). What a person reads may be in one
of three systems (``--units``):

- ``si``: the SI base units (rad, rad/s, N·m, J, m, Pa, W, ...);
- ``engineering`` (the default of reports and plots): the machine designer's
  units, mm, rpm, MPa, kg, and N·m, J, W, N with the prefix each value needs
  (the table below holds kN·m, kJ, kW, kN: the unit where no value chooses,
  a diagram's axis);
- ``imperial``: in, rpm, lbf·ft, psi, hp, lb.

How a number is written (:func:`number`, the one way; :func:`quantity_text` and
the field helpers call it):

- **Significant figures:** :data:`DEFAULT_DIGITS` (4) unless the reader asks
  for others (``--digits``, 1 to :data:`MAX_DIGITS`, checked by
  :func:`check_digits`); every caller passes its ``digits`` down, there is no
  global setting.
- **Round-off is 0:** a value within :data:`NOISE_RTOL` (1e-12) of its scale
  is written "0", never "-0". The scale is the largest magnitude of the same
  quantity beside it (``among``: the column of a table, :func:`column`, or a
  range's ends), or the scale a caller of :func:`number` names; a value alone
  is its own scale, so nothing is hidden that was not compared with something.
- **Prefixes per value (engineering system only):** torque, energy, power and
  force take the SI prefix that puts the shown number at 1 or more and below
  1000 (36.1 N·m, 1.256 kJ, 5.5 kW, 68.72 kN; below 1 the base unit, 0.5 J),
  :data:`PREFIXED`. Every other dimension keeps its one unit of the system:
  lengths in mm (drawings are dimensioned in mm), stresses in MPa (strengths
  are tabled in MPa = N/mm²), speeds in rpm, masses in kg, inertias in kg·m²,
  unbalance in g·mm and µm (ISO 21940-11). The ``si`` system keeps the SI base
  units (its numbers are the JSON's) and ``imperial`` its customary units. A
  table keeps one unit per column, chosen from the column's largest magnitude
  (:func:`column`, :func:`heading`).
- **Worked equations** of the engineering report carry :data:`GUARD_DIGITS`
  more figures than the rest (:func:`worked_digits`), so that their arithmetic
  checks to the figures of the answer.

Every factor is pint's own (``Quantity(1, unit).to(SI).magnitude``), written
out so that showing a number loads no unit library; tests/report/test_display.py
checks each against pint. One table, by dimension (the dimensions of
:data:`flyopt.units.DIMENSIONS` and :data:`flyopt.outputs.results.OUTPUT_DIMENSIONS`):
a quantity is shown as ``value_SI / factor`` followed by its label.
An output field is shown by its name (:func:`field_text`, :func:`heading`),
its dimension read from flyopt.outputs.results' table of every field flyopt
writes (:func:`dimension_of`), the table behind the JSON's ``units`` map.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:  # the command-line parser reads this module's tables: numpy stays unloaded for it
    import numpy as np
    import numpy.typing as npt

#: A value shown in a unit: a number, or an array of them.
Shown = TypeVar("Shown", float, "npt.NDArray[np.floating]")
T = TypeVar("T")

#: The unit systems, the default first for reports.
SYSTEMS = ("engineering", "si", "imperial")

#: The default for what people read.
DEFAULT = "engineering"
#: Not a system: a sweep's table with its varied fields in the units they were given in (``300,600rpm``: rpm),
#: as :func:`flyopt.report.notebook.to_units` and ``flyopt sweep --units`` take it.
INPUT_UNITS = "input"

#: dimension -> system -> (label, factor: SI value of one displayed unit).
UNITS = {
    "angle": {
        "si": ("rad", 1.0),
        "engineering": ("deg", 0.017453292519943295),
        "imperial": ("deg", 0.017453292519943295),
    },
    "angular_speed": {
        "si": ("rad/s", 1.0),
        "engineering": ("rpm", 0.10471975511965977),
        "imperial": ("rpm", 0.10471975511965977),
    },
    "angular_acceleration": {
        "si": ("rad/s²", 1.0),
        "engineering": ("rad/s²", 1.0),
        "imperial": ("rad/s²", 1.0),
    },
    "acceleration": {"si": ("m/s²", 1.0), "engineering": ("m/s²", 1.0), "imperial": ("ft/s²", 0.3048)},
    "torque": {"si": ("N·m", 1.0), "engineering": ("kN·m", 1000.0), "imperial": ("lbf·ft", 1.3558179483314004)},
    "energy": {"si": ("J", 1.0), "engineering": ("kJ", 1000.0), "imperial": ("ft·lbf", 1.3558179483314004)},
    "inertia": {"si": ("kg·m²", 1.0), "engineering": ("kg·m²", 1.0), "imperial": ("lb·ft²", 0.04214011009380480)},
    "flywheel_moment": {
        "si": ("N·m²", 1.0),
        "engineering": ("N·m²", 1.0),
        "imperial": ("lbf·ft²", 0.41325331065141085),
    },
    "length": {"si": ("m", 1.0), "engineering": ("mm", 0.001), "imperial": ("in", 0.0254)},
    "mass": {"si": ("kg", 1.0), "engineering": ("kg", 1.0), "imperial": ("lb", 0.45359237)},
    "density": {"si": ("kg/m³", 1.0), "engineering": ("kg/m³", 1.0), "imperial": ("lb/in³", 27679.904710203125)},
    "speed": {"si": ("m/s", 1.0), "engineering": ("m/s", 1.0), "imperial": ("ft/s", 0.3048)},
    "stress": {"si": ("Pa", 1.0), "engineering": ("MPa", 1e6), "imperial": ("psi", 6894.7572931683635)},
    "power": {"si": ("W", 1.0), "engineering": ("kW", 1000.0), "imperial": ("hp", 745.6998715822701)},
    "force": {"si": ("N", 1.0), "engineering": ("kN", 1000.0), "imperial": ("lbf", 4.4482216152605)},
    "area": {"si": ("m²", 1.0), "engineering": ("mm²", 1e-6), "imperial": ("in²", 0.00064516)},
    "time": {"si": ("s", 1.0), "engineering": ("s", 1.0), "imperial": ("s", 1.0)},
    "unbalance": {"si": ("kg·m", 1.0), "engineering": ("g·mm", 1e-6), "imperial": ("oz·in", 0.0007200778873750002)},
    # the specific unbalance e = U/m of ISO 21940-11 (a length; g·mm/kg is µm), for the report's e_per
    "eccentricity": {"si": ("m", 1.0), "engineering": ("µm", 1e-6), "imperial": ("in", 0.0254)},
    "dimensionless": {"si": ("-", 1.0), "engineering": ("-", 1.0), "imperial": ("-", 1.0)},
    # a drive train's springs (flyopt.machine.drive_train): a shaft's or a coupling's twist, a belt span's stretch
    "torsional_stiffness": {
        "si": ("N·m/rad", 1.0),
        "engineering": ("N·m/rad", 1.0),
        "imperial": ("lbf·ft/rad", 1.3558179483314004),
    },
    "stiffness": {"si": ("N/m", 1.0), "engineering": ("N/m", 1.0), "imperial": ("lbf/in", 175.12683524647636)},
}


#: Significant figures of a number written for people, unless the reader asks otherwise (``--digits``).
DEFAULT_DIGITS = 4
#: Significant figures of a limit's utilisation (value over allowed), wherever one is shown: three, so that
#: a binding 0.9949 reads 0.995 in the text, the tables and the diagrams alike.
UTILISATION_DIGITS = 3


#: A results column in words, where an axis, a chart or a read-out names it for people (the files keep the
#: column's own name): a Pareto front's ``outer_diameter`` and a sweep's ``d_outer`` are both the wheel's
#: outer diameter D. Other columns are named as they are.
COLUMN_WORDS = {
    "mass": "mass",
    "d_outer": "outer diameter D",
    "outer_diameter": "outer diameter D",
    "d_mean": "mean diameter D_m",
    "b": "axial width B",
    "h": "radial thickness H",
    "cost": "cost",
    "delta": "allowed δ",
    "motor_power": "motor power",
    "rim_speed": "rim speed",
    "j_flywheel": "flywheel inertia J′ (on its shaft)",
    "j_required": "required inertia J_F",
    "material": "material",
    "best_material": "material",
    "best_shaft": "shaft",
}


#: The heading of a design's sensitivities wherever they are shown (the text's block, the report's table): each is
#: the slope at the design (a multiplier, or a central difference for δ) times a round step, a first-order
#: estimate of what that step would change (a re-solve at δ + 0.01 may differ by a fifth), which it says.
SENSITIVITY_HEADING = "How the mass moves with each limit (first order)"

#: A sensitivity's ``unit`` (its JSON entry's) and the dimension its step is shown in.
SENSITIVITY_DIMENSIONS = {"m": "length", "m/s": "speed", "Pa": "stress", "kg*m^2": "inertia", "-": "dimensionless"}


def sensitivity_text(entry: Mapping[str, Any], system: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A binding limit's sensitivity (an entry of a design's ``sensitivities``) in the system's units: its
    sentence with the limit's step and the mass's change each in its unit and signed. The step is the design's
    in the system's unit rounded to one significant figure, so that it reads as a round amount and is exact
    at any ``digits`` (10 mm is +0.4 in, 1 MPa +100 psi, 1 m/s +3 ft/s; in engineering units the design's own
    10 mm, 1 MPa, 1 m/s), and the mass's change is the sensitivity times that step: "the envelope binds: +0.4 in
    of outer diameter changes the mass by -2.546 lb". The text as written where the entry has no sentence (a
    result of an older flyopt) or a unit not known here."""
    sentence, step = entry.get("sentence"), entry.get("step")
    dimension = SENSITIVITY_DIMENSIONS.get(str(entry.get("unit")))
    if sentence is None or step is None or dimension is None:
        return str(entry["text"])

    def signed(value: float, dimension: str) -> str:
        text = quantity_text(value, dimension, system, digits)
        return text if text.startswith("-") else f"+{text}"

    if "{step}" not in str(sentence):  # a step said in words (1 % of the inertia): the design's change of mass
        return str(sentence).format(dmass=signed(float(entry["dmass"]), "mass"))
    factor = unit(dimension, system, abs(float(step)), digits)[1]
    shown = float(f"{float(step) / factor:.0e}") * factor  # one significant figure in the shown unit
    dmass = float(entry["dmass_dlimit"]) * shown
    return str(sentence).format(step=signed(shown, dimension), dmass=signed(dmass, "mass"))


def said_text(text: str, system: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A sentence of the design layer (a reason, a limit's place: :class:`flyopt.said.Said`) in the system's
    units, each of its quantities by :func:`quantity_text` at ``digits`` figures, as every other number of the
    output (the string as written, which the JSON carries, mixes m, mm and kg·m² at three or four figures); a
    plain string as it is."""
    from flyopt.said import Said

    if not isinstance(text, Said) or not hasattr(text, "template"):  # (a Said made without flyopt.said.said)
        return str(text)
    return text.template.format(
        **{name: quantity_text(value, dimension, system, digits) for name, (value, dimension, _) in text.values.items()}
    )


def column_words(column: str) -> str:
    """A results column as people read it (:data:`COLUMN_WORDS`), else the column's own name."""
    return COLUMN_WORDS.get(column, column)


def for_people(table: Any, names: Mapping[str, str]) -> Any:
    """A study's table (a pandas DataFrame, changed in place and returned) as people read it: its materials by
    their names for people (``names``: key -> :attr:`flyopt.design.materials.Material.display_name`) and its
    binding limits in words (:func:`flyopt.design.check.binding_label`), as ``flyopt solve`` writes them: the
    printed tables of ``flyopt tradeoff`` and ``pareto`` and the app's. Files, JSON and the CSV ``flyopt sweep``
    prints keep the keys (they are data)."""
    from flyopt.design.check import binding_label

    for c in ("material", "best_material"):
        if c in table:
            table[c] = [names.get(m, m) if isinstance(m, str) else m for m in table[c]]
    for c in ("binding", "limit"):
        if c in table:
            table[c] = [
                ", ".join(binding_label(n) for n in v.split(",") if n) if isinstance(v, str) else v for v in table[c]
            ]
    return table


def chain_point(index: int) -> str:
    """A point of the energy chain of net areas, which has no angle, by where it lies: "start" (index 0, the
    cycle's start) or "after area k". The one naming of the text, the report's table and the energy diagram."""
    return "start" if index == 0 else f"after area {index}"


def mode_shape(shape: Sequence[float]) -> str:
    """A mode's shape, its amplitudes signed to two decimals ("+1.00, -0.43, +0.00"): a node's amplitude of
    -0.001 is "+0.00", never "-0.00"."""
    return ", ".join("+0.00" if f"{v:+.2f}" == "-0.00" else f"{v:+.2f}" for v in shape)


def share(utilisation: float) -> str:
    """A utilisation as a percentage to one decimal, "89.5 %"."""
    return f"{100 * utilisation:.1f} %"


def share_of_allowable(utilisation: float) -> str:
    """A stress as a share of its allowable, "89.5 % of its allowable", and ", OVER" where it exceeds it: the
    card's, the text's and the stress diagram's one wording (one decimal)."""
    return f"{share(utilisation)} of its allowable" + (", OVER" if utilisation > 1.0 + 1e-9 else "")


def rim_speed_answer(rim_speed: float, limit: float, book: Any, quantity: Callable[[float, str], T]) -> list[str | T]:
    """The rim speed against its limit in the answer (the text's line, the card's row), as parts: "48.3 m/s of
    50 m/s"; for a rim sized by the courses' criterion (``book``, :class:`flyopt.design.result.BookRim`, else None)
    the speed that criterion checks, at the mean diameter and the mean speed, against it, and the rim's own at
    the outer diameter at ω_max beside it (section 20). ``quantity(value, name)`` shows a value of the JSON
    field ``name``."""
    if book is None:
        return [quantity(rim_speed, "rim_speed"), " of ", quantity(limit, "rim_speed_limit")]
    return [
        quantity(book.mean_rim_speed, "rim_speed"),
        " of ",
        quantity(limit, "rim_speed_limit"),
        " at the mean diameter and speed (criterion mean_rim_speed), ",
        quantity(rim_speed, "rim_speed"),
        " at the outer diameter at ω_max",
    ]


#: The most significant figures a reader may ask for: a double carries 15 to 17.
MAX_DIGITS = 15

#: The engineering prefixes, by factor: the largest that leaves the shown number at 1 or more is taken.
PREFIXES = (("G", 1e9), ("M", 1e6), ("k", 1e3))

#: system -> dimension -> its SI unit's label, for the dimensions whose unit is chosen per value with
#: an SI prefix of :data:`PREFIXES` (36.1 N·m, 1.256 kJ). The one place this is decided (module docstring).
PREFIXED = {
    "engineering": {
        "torque": "N·m",
        "energy": "J",
        "power": "W",
        "force": "N",
        "torsional_stiffness": "N·m/rad",
        "stiffness": "N/m",
    }
}


#: Figures a worked equation carries beyond the report's own, as a hand calculation carries guard figures:
#: its substituted numbers then give its result to the figures the report shows (4 by default, 6 in a step).
GUARD_DIGITS = 2


def worked_digits(digits: int) -> int:
    """The significant figures of a worked equation's numbers in a report of ``digits`` figures."""
    return min(digits + GUARD_DIGITS, MAX_DIGITS)


def check_digits(digits: int) -> int:
    """``digits`` if it is a count of significant figures flyopt writes (1 to :data:`MAX_DIGITS`); ValueError naming
    the allowed range otherwise."""
    if isinstance(digits, bool) or not isinstance(digits, int) or not 1 <= digits <= MAX_DIGITS:
        raise ValueError(f"digits must be a whole number from 1 to {MAX_DIGITS}, not {digits!r}")
    return digits


def check_system(system: str) -> str:
    """``system`` if it is known; ValueError naming the allowed ones otherwise."""
    if system not in SYSTEMS:
        raise ValueError(f"unit system {system!r} is not known (allowed: {', '.join(SYSTEMS)})")
    return system


def unit(
    dimension: str, system: str = DEFAULT, magnitude: float | None = None, digits: int = DEFAULT_DIGITS
) -> tuple[str, float]:
    """(label, factor) of a dimension in a system: shown value = SI value / factor.

    ``magnitude`` is the largest SI magnitude the unit is to show (a value, or a column's largest): a
    dimension of :data:`PREFIXED` then takes the largest prefix that leaves it, written to ``digits``
    figures, at 1 or more (1,256 J is 1.256 kJ; 999.96 J to 4 figures is 1 kJ, not "1,000 J"); below 1, or
    0, the SI unit. Without a magnitude (an axis drawn before its data is known) the table's one unit.
    """
    check_system(system)
    try:
        fixed = UNITS[dimension][system]
    except KeyError:
        raise ValueError(f"no display unit for dimension {dimension!r} (known: {', '.join(UNITS)})") from None
    base = PREFIXED.get(system, {}).get(dimension)
    if base is None or magnitude is None or not math.isfinite(magnitude):
        return fixed
    rounded = abs(float(f"{magnitude:.{digits - 1}e}"))  # as it will be written: 999.96 is 1,000 at 4 figures
    for prefix, factor in PREFIXES:
        if rounded >= factor:
            return f"{prefix}{base}", factor
    return base, 1.0


def label(dimension: str, system: str = DEFAULT) -> str:
    """The unit's label, e.g. "mm"."""
    return unit(dimension, system)[0]


def show(value: Shown | None, dimension: str, system: str = DEFAULT) -> Shown | None:
    """An SI value (number or numpy array) in the system's unit of its dimension (None stays None)."""
    if value is None:
        return None
    return value / unit(dimension, system)[1]


def quantity_text(
    value: float | None,
    dimension: str,
    system: str = DEFAULT,
    digits: int = DEFAULT_DIGITS,
    among: Sequence[float | None] | None = None,
    prefixed: bool = True,
) -> str:
    """ "<number> <label>" with ``digits`` significant figures ("-" for None, "inf"/"nan" as such).

    A dimension of :data:`PREFIXED` takes the prefix the value needs (36.1 N·m, 1.256 kJ). ``among``: the
    SI values the value is read beside (a range's two ends, a column), whose largest magnitude chooses their
    one unit and is the scale under which a value is round-off, written 0 (:func:`number`). ``prefixed``
    False: the system's one unit of the dimension (a diagram's label, read against its axis).
    """
    if value is None:
        return "-"
    value = float(value)
    magnitude: float | None = largest(among) if among is not None else abs(value) if prefixed else None
    return _writer(dimension, system, digits, magnitude, among is not None)(value)


def quantity_format(
    dimension: str, system: str = DEFAULT, digits: int = DEFAULT_DIGITS, among: Sequence[float | None] | None = None
) -> Callable[[float | None], str]:
    """:func:`quantity_text` (``prefixed`` False) of many values read beside the same ``among``, its unit and
    scale found once: a diagram's read-out of every point it draws (1441 angles of the energy–mass curve)."""
    return _writer(dimension, system, digits, largest(among) if among is not None else None, among is not None)


def _writer(
    dimension: str, system: str, digits: int, magnitude: float | None, scaled: bool
) -> Callable[[float | None], str]:
    """How :func:`quantity_text` writes a value in the unit ``magnitude`` chooses (and, ``scaled``, as round-off
    against it): the one formatter of a quantity, for one value or many."""
    name, factor = unit(dimension, system, magnitude, digits)
    scale = magnitude / factor if scaled and magnitude is not None else None

    def write(value: float | None) -> str:
        if value is None:
            return "-"
        shown = float(value) / factor
        text = number(shown, digits, scale) if math.isfinite(shown) else str(shown)
        return text if name == "-" else f"{text} {name}"

    return write


#: A value within this fraction of its scale (its column's largest magnitude, or the scale its caller
#: names) is round-off, and is written 0.
NOISE_RTOL = 1e-12


def _is_noise(value: float, scale: float) -> bool:
    """Whether a finite ``value`` is within :data:`NOISE_RTOL` of ``scale`` (0 itself is not noise, it is 0)."""
    return math.isfinite(value) and math.isfinite(scale) and abs(value) <= NOISE_RTOL * abs(scale)


def without_noise(value: float, scale: float) -> float:
    """``value``, or 0 where it is round-off of ``scale`` (within :data:`NOISE_RTOL` of it): a difference of two
    large numbers (a cycle's works) shown as the 0 it is, in the unit 0 takes."""
    return 0.0 if _is_noise(value, scale) else value


#: Significant figures a double holds exactly (C's DBL_DIG): every decimal of 15 figures a user writes reads
#: back as itself.
CONVERSION_DIGITS = 15
#: The round-off a conversion of units leaves, in units in the last place: the SI value is the given one times
#: a factor and the shown one that over a factor, each product and each factor rounded once (about 1 ulp where
#: the two factors are the same double; "1500rpm", read in rad/s and shown in rpm, was 1500.0000000000002,
#: 1 ulp above 1500). Four covers two factors that differ in their last bit.
CONVERSION_ULPS = 4


def without_conversion_noise(values: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Values converted out of SI for a table of data (``flyopt sweep --units``,
    :func:`flyopt.report.notebook.to_units`), without the conversion's round-off: each the decimal of
    :data:`CONVERSION_DIGITS` figures nearest to it where that lies within :data:`CONVERSION_ULPS` units in the
    last place (1500.0000000000002 is 1500.0), else the value as it is: ``float(f"{value:.15g}")`` kept within
    4 ulp. So every value a user wrote (15 figures or fewer) reads back as written, and no other moves by more
    than the conversion's own round-off: the data keeps every figure it has (a report's text is rounded by
    :func:`number`). inf, nan and 0 as they are, and sizes below 10⁻⁸ or from 10³⁷ up.

    Array in, array out, in numpy (a sweep's table has 10⁶ rows a column): the 15-figure mantissa n of each
    value, n × 10^-k by one rounding (a power of ten up to 10²² is exact, so the decimal's double is the
    correctly rounded one, as ``float`` reads it); n ± 1 are tried too, since the product that finds n is
    rounded once itself. Where the vector arithmetic cannot tell what Python's formatting would do (a value
    within a millionth of a millionth of a power of ten, whose decade ``log10`` may round into the next, or
    halfway between two decimals), that value is formatted by Python itself.
    """
    import numpy as np

    x = np.array(values, dtype=float, ndmin=1)
    size = np.abs(x)
    with np.errstate(all="ignore"):
        ok = np.isfinite(x) & (size >= 1e-8) & (size < 1e37)
        decade = np.log10(np.where(ok, size, 1.0))
        shift = (CONVERSION_DIGITS - 1) - np.floor(decade)  # decimals to the 15th figure: -22 to 22
        powers = np.array([float(f"1e{k}") for k in range(23)])  # 10**0 .. 10**22, each exact (read, not pow)
        power = powers[np.clip(np.abs(np.where(ok, shift, 0)), 0, 22).astype(np.intp)]
        up = shift >= 0
        mantissa = np.rint(np.where(up, x * power, x / power))
        best, gap, ties = x, np.full_like(x, np.inf), np.zeros(x.shape, dtype=bool)
        for n in (mantissa, mantissa - 1.0, mantissa + 1.0):
            decimal = np.where(up, n / power, n * power)
            distance = np.abs(decimal - x)
            ties = (distance == gap) | (ties & (distance > gap))
            closer = distance < gap
            best, gap = np.where(closer, decimal, best), np.minimum(distance, gap)
        keep = ok & (gap <= CONVERSION_ULPS * np.spacing(size))
        # a decade log10 may have put in the next: near a power of ten, but not that power itself
        nearest = np.array([float(f"1e{k}") for k in range(-8, 38)])[
            np.clip(np.rint(decade) + 8, 0, 45).astype(np.intp)
        ]
        unsure = ok & ((keep & ties) | ((np.abs(decade - np.rint(decade)) < 1e-12) & (size != nearest)))
    best = np.where(keep, best, x)
    if unsure.any():  # Python's own decimal of 15 figures, kept within 4 ulp, once for each such value
        found, where = np.unique(x[unsure], return_inverse=True)
        own = [float(f"{value:.{CONVERSION_DIGITS}g}") for value in found.tolist()]
        fixed = [a if abs(a - b) <= CONVERSION_ULPS * math.ulp(b) else b for a, b in zip(own, found.tolist())]
        best[unsure] = np.array(fixed)[where]
    return best


def number(value: float | None, digits: int = DEFAULT_DIGITS, scale: float | None = None) -> str:
    """A number with ``digits`` significant figures, no exponent for everyday sizes ("-" for None).

    The one way flyopt writes a number for people (the text report, plots'
    labels); thousands are grouped ("1,256.33"), trailing zeros dropped. A
    whole number longer than ``digits`` is rounded to them (23,053,542 Pa to
    6 digits is "23,053,500"), so that no digit is printed that was not asked for.
    A value within :data:`NOISE_RTOL` of ``scale`` (the largest magnitude of the
    same quantity beside it) is round-off and written "0"; "-0" is never written.
    """
    if value is None:
        return "-"
    if not math.isfinite(value):
        return str(value)  # inf, -inf, nan: say so rather than fail
    if value == 0 or (scale is not None and _is_noise(value, scale)):
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    if -4 <= magnitude < 9:
        decimals = digits - 1 - magnitude
        if decimals > 0:
            return f"{value:,.{decimals}f}".rstrip("0").rstrip(".")
        return f"{round(value, decimals):,.0f}"
    return f"{value:.{digits - 1}e}"


def one_in(delta: float, digits: int = DEFAULT_DIGITS) -> str:
    """δ as "1/N" (the books' way: 0.05 is 1/20), "" for a δ of 0 (a machine whose torques balance at every angle
    keeps its speed with any wheel) or less: the one place flyopt writes that reciprocal."""
    return f"1/{number(1 / delta, digits)}" if delta > 0 else ""


def dimension_of(name: str) -> str:
    """The dimension of an output field (``a_max``: "energy", ``d_outer``: "length", a part's ``inertia``).

    From flyopt.outputs.results' one table of the fields flyopt writes (QUANTITIES
    and the sweep inputs), so that the JSON's ``units`` map and what people
    read cannot disagree. ValueError for a name that is no quantity.
    """
    from flyopt.outputs import quantities

    dimension = quantities.dimension_of(name)
    if dimension is None:
        raise ValueError(f"{name!r} is not a quantity of flyopt.outputs.results (no dimension to show it in)")
    return dimension


def field_text(
    value: float | None,
    name: str,
    system: str = DEFAULT,
    digits: int = DEFAULT_DIGITS,
    among: Sequence[float | None] | None = None,
) -> str:
    """An output field's SI value as "<number> <label>" in ``system`` (:func:`quantity_text` by its name)."""
    return quantity_text(value, dimension_of(name), system, digits, among)


def denoised(values: Sequence[float]) -> list[float]:
    """A column of numbers with its round-off shown as 0: every value within :data:`NOISE_RTOL` of the column's
    largest magnitude (an energy chain that closes at -3.7e-16 kJ of a 9 kJ cycle closes at 0)."""
    scale = largest(values)
    return [0.0 if _is_noise(v, scale) else v for v in values]


def largest(values: Sequence[float | None]) -> float:
    """The largest finite magnitude of a column (0 for none): its scale, and what chooses its unit (a
    :class:`Column`'s, found when it was made)."""
    if isinstance(values, Column):
        return values.magnitude
    return max((abs(float(v)) for v in values if v is not None and math.isfinite(v)), default=0.0)


class Column(Sequence["float | None"]):
    """A column's SI values with their largest magnitude (:func:`largest`) found once: given as ``among`` to each
    of its cells, a table of n rows costs n steps, not n² (a 25,000-row torque table's energy chain took
    `flyopt solve` 13 s, 50,000 rows 73 s)."""

    __slots__ = ("magnitude", "values")

    def __init__(self, values: Iterable[float | None]) -> None:
        self.values: list[float | None] = list(values)
        self.magnitude: float = largest(self.values)

    def __len__(self) -> int:
        return len(self.values)

    def __getitem__(self, index: Any) -> Any:
        return self.values[index]

    def __iter__(self) -> Iterator[float | None]:
        return iter(self.values)


def field_number(
    value: float | None,
    name: str,
    system: str = DEFAULT,
    digits: int = DEFAULT_DIGITS,
    among: Sequence[float | None] | None = None,
) -> str:
    """The number alone of :func:`field_text`: for a table whose heading carries the unit ("-" for None).

    ``among`` is the column the value stands in (SI values, the value among them): its largest magnitude
    chooses the column's one unit (the same as :func:`heading` given the column) and is the scale under
    which a value is round-off. Without it, the system's one unit of the dimension (as :func:`heading`
    and :func:`label` without values): a number alone never chooses a prefix its heading does not say.
    """
    if value is None:
        return "-"
    value = float(value)
    magnitude = largest(among) if among is not None else None
    factor = unit(dimension_of(name), system, magnitude, digits)[1]
    return number(value / factor, digits, None if magnitude is None else magnitude / factor)


def column(
    values: Sequence[float | None], name: str, system: str = DEFAULT, digits: int = DEFAULT_DIGITS
) -> tuple[str, list[str]]:
    """A table's column of an output field: (its unit's label, its numbers in that unit).

    One unit for the column, chosen from its largest magnitude (:func:`unit`); each value written with
    ``digits`` figures, round-off against that magnitude written 0, None as "-".
    """
    values = Column(values)
    return (
        unit(dimension_of(name), system, values.magnitude, digits)[0],
        [field_number(v, name, system, digits, values) for v in values],
    )


def heading(
    title: str,
    name: str,
    system: str = DEFAULT,
    among: Sequence[float | None] | None = None,
    digits: int = DEFAULT_DIGITS,
) -> str:
    """A table heading with the unit of the field ``name``: "mass [kg]" (the title alone if dimensionless).

    ``among``: the column's SI values, whose largest magnitude chooses a prefixed unit (:func:`column`);
    without them the system's one unit of the dimension.
    """
    magnitude = largest(among) if among is not None else None
    text = unit(dimension_of(name), system, magnitude, digits)[0]
    return title if text == "-" else f"{title} [{text}]"


def rounded_rank_note(continuous_mass: str) -> str:
    """The ranking table's note where its first row is the rounded wheel: the ranking compares continuous optima
    (the text and the report say it in these words); ``continuous_mass`` the winner's continuous mass as shown."""
    return (
        "the first row is the chosen wheel as rounded to the manufacturing step (design.round_to); the ranking "
        f"compares continuous optima: the chosen wheel's continuous optimum is {continuous_mass}, any other row is "
        "its combination's"
    )


def thin_wall_answer(thin: Mapping[str, Any], quantity: Callable[[float, str], T]) -> list[str | T]:
    """A bare wheel thinner than the wall asked of it (the design's ``parts.thin_wall``,
    :func:`flyopt.design.castability.too_thin`) in the answer (the text's line, the card's row), as parts: its
    thinnest section, the wall asked and by whom, and that it cannot be made (cast) as sized.
    ``quantity(value, name)`` shows a value of the JSON field ``name``."""
    from flyopt.design.castability import too_thin_to_cast, who_asks

    made = "not castable as sized" if too_thin_to_cast(thin) else "too thin to make as sized"
    return [
        f"{thin['thinnest_part']} ",
        quantity(thin["thinnest_wall"], "thinnest_wall"),
        ", thinner than the ",
        quantity(thin["min_wall"], "min_wall"),
        f" {who_asks(thin)} at this size: {made} (see the notes)",
    ]


def thin_wall_words(thin: Mapping[str, Any]) -> str:
    """What the one-sentence answer adds for a bare wheel thinner than the wall asked of it."""
    from flyopt.design.castability import too_thin_to_cast

    return f"; as sized, its {thin['thinnest_part']} is too thin {'to cast' if too_thin_to_cast(thin) else 'to make'}"


def key_answer(key: Mapping[str, Any], material: str, quantity: Callable[[float, str], T]) -> list[str | T]:
    """The hub's key in the answer (the text's line, the card's row), as parts: its DIN 6885-1 section (in mm, as
    the standard names it), its length, the torque it is checked at (the peak of the flywheel the cycle requires:
    a described shaft's check gives the wheel as built its own), its verdict and the pressure against the
    allowable; or, where the hub's
    material (``material``, its name for people) gives no allowable, the key's shear against the key steel's and
    the pressure said to be unchecked. ``quantity(value, name)`` shows a value of the JSON field ``name``."""
    from flyopt.design.key import key_verdict

    parts: list[str | T] = [
        f"{key['size']} mm section, ",
        quantity(key["length"], "length"),
        " long, at ",
        quantity(key["torque"], "torque"),
        ": ",
    ]
    pressure: list[str | T] = ["bearing pressure ", quantity(key["bearing_pressure"], "bearing_pressure")]
    if key["allowable_pressure"] is not None:
        return [
            *parts,
            f"{key_verdict(key)}, ",
            *pressure,
            " of ",
            quantity(key["allowable_pressure"], "allowable_pressure"),
        ]
    return [
        *parts,
        "shear ",
        quantity(key["shear"], "shear"),
        " of ",
        quantity(key["allowable_shear"], "allowable_shear"),
        "; ",
        *pressure,
        f" not checked ({material} gives no bearing_pressure)",
    ]
