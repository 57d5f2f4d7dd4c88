"""Motor catalogues: induction motors of standard sizes, shipped as data.

The catalogues live in the package data file ``flyopt/data/motors.toml``,
every figure with its source and written with its unit as the source prints
it; nothing numeric about a motor is written in this module. A size is a
:class:`CatalogueMotor` (its nameplate and catalogue figures in SI), a
catalogue a :class:`Catalogue` (its sizes in increasing rated power). The
torque-speed physics is :class:`flyopt.machine.motor.InductionMotor`'s, which
:meth:`CatalogueMotor.motor` returns: the linear characteristic near the
rated point and the Kloss curve through the catalogue's breakdown torque
(docs/flywheel-design.md, section 7).

A scene's own motors ([[motor_option]], :mod:`flyopt.io.drive`) are read with
the same fields (:data:`QUANTITIES`, :data:`TEXTS`) into the same classes, so a
drive design treats a catalogue and a user's list alike.

References
----------
.. [1] IEC 60034-30-1:2014, Rotating electrical machines - Part 30-1:
   Efficiency classes of line operated AC motors (IE code).
.. [2] IEC 60072-1, Dimensions and output series for rotating electrical
   machines - Part 1: Frame numbers 56 to 400.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, NamedTuple

from flyopt._toml import tomllib
from flyopt.errors import SceneError, shorten
from flyopt.machine.motor import InductionMotor, plate_rpm
from flyopt.names import hint
from flyopt.units import quantity
from flyopt.validate import number

__all__ = [
    "QUANTITIES",
    "TEXTS",
    "REQUIRED",
    "EFFICIENCY_CLASSES",
    "RATING_TOLERANCE",
    "MotorDataError",
    "CatalogueMotor",
    "Catalogue",
    "Neighbours",
    "catalogue",
    "catalogue_names",
    "read_catalogues",
]

_DATA_FILE = "motors.toml"

QUANTITIES = {
    "rated_power": "power",
    "rated_speed": "angular_speed",
    "synchronous_speed": "angular_speed",
    "rotor_inertia": "inertia",
    "breakdown_ratio": "dimensionless",
    "locked_rotor_ratio": "dimensionless",
    "efficiency": "dimensionless",
    "mass": "mass",
    "price": "dimensionless",
}
"""The numeric fields of a motor, each with its dimension for :func:`flyopt.units.quantity`.

``price`` is a plain number in the currency of the materials' cost per kg."""

TEXTS = ("name", "frame", "efficiency_class", "source")
"""The text fields of a motor."""

REQUIRED = ("rated_power", "rated_speed", "synchronous_speed", "rotor_inertia")
"""The fields every motor must give: its nameplate point and its rotor's inertia."""

EFFICIENCY_CLASSES = ("IE1", "IE2", "IE3", "IE4", "IE5")
"""The IE codes of IEC 60034-30-1 (IE5 named, without limits, in its 2014 edition)."""

RATING_TOLERANCE = 1e-9
"""Relative tolerance under which a continuous rating counts as a size's rated power [-].

A relaxed optimum that lands on a size (7.5 kW to round-off) takes that size
as the one at or above it, not the next; two sizes of one catalogue must
differ by more than this."""


class MotorDataError(ValueError):
    """A motor's figure is out of its range; ``field`` names it (empty: the motor as a whole).

    Parameters
    ----------
    field : str
        The field of :class:`CatalogueMotor` at fault, e.g. ``"rated_speed"``.
    message : str
        What is wrong and what is allowed.
    index : int or None
        Position of the motor in the sequence given to :class:`Catalogue`, for a
        fault between two motors (a name or a rating given twice).
    """

    def __init__(self, field: str, message: str, index: int | None = None) -> None:
        self.field, self.message, self.index = field, message, index
        super().__init__(message)


def _number(value, field, name, *, minimum=0.0, strict=True, below=None, allowed=None):
    """``value`` as a finite float above ``minimum`` (and under ``below``), else MotorDataError."""
    try:
        return number(
            value, f"motor {shorten(name)}: {field}", minimum=minimum, strict=strict, below=below, allowed=allowed
        )
    except ValueError as err:
        raise MotorDataError(field, str(err)) from None


@dataclass(frozen=True)
class CatalogueMotor:
    """One three-phase induction motor of a catalogue, in SI.

    Parameters
    ----------
    name : str
        A label, unique in its catalogue.
    rated_power : float
        P_n, shaft output at the rated point [W].
    rated_speed : float
        ω_n at rated output [rad/s].
    synchronous_speed : float
        ω_0 [rad/s], above ω_n.
    rotor_inertia : float
        J of the rotor [kg*m^2].
    breakdown_ratio : float or None
        M_b/M_n > 1 [-]; None where the source gives none (the motor's Kloss
        curve then takes :data:`flyopt.machine.motor.DEFAULT_BREAKDOWN_RATIO`,
        as a scene's own motor does).
    locked_rotor_ratio : float or None
        Starting torque over rated torque, M_l/M_n [-].
    efficiency : float or None
        At rated output, a fraction in (0, 1) [-].
    efficiency_class : str or None
        IE code of IEC 60034-30-1 (:data:`EFFICIENCY_CLASSES`).
    frame : str or None
        IEC 60072-1 frame, e.g. ``"132M"``.
    mass : float or None
        [kg].
    price : float or None
        In the currency of the materials' cost per kg; None where no source gives one.
    published_rated_torque : float or None
        M_n as the source prints it [N*m], kept as a check of the other
        figures; :attr:`rated_torque` is P_n/ω_n.
    source : str
        Where the figures come from.

    Raises
    ------
    MotorDataError
        A figure out of its range; ``field`` names it.
    """

    name: str
    rated_power: float
    rated_speed: float
    synchronous_speed: float
    rotor_inertia: float
    breakdown_ratio: float | None = None
    locked_rotor_ratio: float | None = None
    efficiency: float | None = None
    efficiency_class: str | None = None
    frame: str | None = None
    mass: float | None = None
    price: float | None = None
    published_rated_torque: float | None = None
    source: str = field(default="", repr=False)

    def __post_init__(self) -> None:
        name = self.name
        if not isinstance(name, str) or not name.strip():
            raise MotorDataError("name", f"a motor's name must be a non-empty string, got {shorten(name)}")

        def set_(key, value):
            object.__setattr__(self, key, value)

        for key in ("rated_power", "rated_speed", "synchronous_speed", "rotor_inertia"):
            set_(key, _number(getattr(self, key), key, name))
        optional: dict[str, dict[str, Any]] = {
            "breakdown_ratio": {
                "minimum": 1.0,
                "allowed": "a finite number > 1 (M_b/M_n; the pull-out torque exceeds the rated torque)",
            },
            "locked_rotor_ratio": {},
            "efficiency": {"below": 1.0, "allowed": "a fraction in (0, 1), e.g. 0.92 or '92 %'"},
            "mass": {},
            "price": {"strict": False},
            "published_rated_torque": {},
        }
        for key, limits in optional.items():
            if getattr(self, key) is not None:
                set_(key, _number(getattr(self, key), key, name, **limits))
        if not self.rated_speed < self.synchronous_speed:
            raise MotorDataError(
                "rated_speed",
                f"motor {shorten(name)}: the rated speed "
                f"({plate_rpm(self.rated_speed)}) must be below the synchronous speed "
                f"({plate_rpm(self.synchronous_speed)}): an induction motor runs with slip",
            )
        if self.efficiency_class is not None and self.efficiency_class not in EFFICIENCY_CLASSES:
            raise MotorDataError(
                "efficiency_class",
                f"motor {shorten(name)}: {shorten(self.efficiency_class)} "
                f"is not an IE code of IEC 60034-30-1 (allowed: {', '.join(EFFICIENCY_CLASSES)})",
            )
        for key in ("frame", "source"):
            value = getattr(self, key)
            if value is not None and not isinstance(value, str):
                raise MotorDataError(key, f"motor {shorten(name)}: {key} must be a string, got {shorten(value)}")
        try:
            self.motor()  # what the torque model refuses, the catalogue refuses
        except ValueError as err:
            raise MotorDataError("", f"motor {shorten(name)}: {err}") from None

    @property
    def rated_torque(self) -> float:
        """M_n = P_n/ω_n [N*m]."""
        return self.rated_power / self.rated_speed

    @property
    def slip(self) -> float:
        """Rated slip s_n = (ω_0 − ω_n)/ω_0 [-]."""
        return (self.synchronous_speed - self.rated_speed) / self.synchronous_speed

    def motor(self) -> InductionMotor:
        """The motor's torque-speed characteristic, :class:`~flyopt.machine.motor.InductionMotor`.

        Its ``torque(omega, model)`` gives either model, the linear line
        (``"linear"``) or the Kloss curve (``"kloss"``) through this size's
        breakdown ratio (docs/flywheel-design.md, section 7); both pass
        through the rated point (ω_n, P_n/ω_n).
        """
        return InductionMotor(self.rated_power, self.rated_speed, self.synchronous_speed, self.breakdown_ratio)


class Neighbours(NamedTuple):
    """The catalogue sizes on either side of a continuous rating.

    Attributes
    ----------
    below : CatalogueMotor or None
        The largest size rated below the rating (None: the rating is at or
        below the smallest size).
    above : CatalogueMotor or None
        The smallest size rated at or above the rating (None: the rating
        exceeds the largest size).
    """

    below: CatalogueMotor | None
    above: CatalogueMotor | None


@dataclass(frozen=True)
class Catalogue:
    """Motor sizes in increasing rated power, one size per rating.

    Parameters
    ----------
    name : str
        The catalogue's name (``"iec_4pole"``), or ``"motor_option"`` for a
        scene's own list.
    motors : sequence of CatalogueMotor
        In any order; kept sorted by rated power.
    description, source : str

    Raises
    ------
    MotorDataError
        No motor, a name given twice, or two sizes of one rated power (within
        :data:`RATING_TOLERANCE`): ``index`` is the later one's position in
        ``motors``.
    """

    name: str
    motors: tuple[CatalogueMotor, ...]
    description: str = field(default="", repr=False)
    source: str = field(default="", repr=False)

    def __post_init__(self) -> None:
        motors = tuple(self.motors)
        if not motors:
            raise MotorDataError("", f"catalogue {shorten(self.name)} has no motor")
        for k, motor in enumerate(motors):
            if not isinstance(motor, CatalogueMotor):
                raise MotorDataError("", f"catalogue {shorten(self.name)}: entry {k} is not a CatalogueMotor", index=k)
            for j in range(k):
                other = motors[j]
                if other.name == motor.name:
                    raise MotorDataError("name", f"motor {shorten(motor.name)} is given twice", index=k)
                if abs(other.rated_power - motor.rated_power) <= RATING_TOLERANCE * motor.rated_power:
                    raise MotorDataError(
                        "rated_power",
                        f"motor {shorten(motor.name)} has the same rated power "
                        f"({motor.rated_power:.6g} W) as {shorten(other.name)}: a catalogue has "
                        "one size per rating",
                        index=k,
                    )
        object.__setattr__(self, "motors", tuple(sorted(motors, key=lambda m: m.rated_power)))

    def __iter__(self) -> Iterator[CatalogueMotor]:
        return iter(self.motors)

    def __len__(self) -> int:
        return len(self.motors)

    @property
    def names(self) -> tuple[str, ...]:
        """The sizes' names, in increasing rated power."""
        return tuple(m.name for m in self.motors)

    @property
    def unpriced(self) -> tuple[str, ...]:
        """Names of the sizes without a price (a design by cost needs every one)."""
        return tuple(m.name for m in self.motors if m.price is None)

    def neighbours(self, rating: float) -> Neighbours:
        """The sizes next to a continuous rating: the one at or above it and the one below.

        Parameters
        ----------
        rating : float
            A continuous rated power [W], e.g. a relaxed optimum's.

        Returns
        -------
        Neighbours
            ``(below, above)``; a rating within :data:`RATING_TOLERANCE` of a
            size's rated power counts as that size (``above``).

        Raises
        ------
        ValueError
            ``rating`` is not a positive finite number.
        """
        if isinstance(rating, bool) or not isinstance(rating, (int, float)) or not math.isfinite(rating) or rating <= 0:
            raise ValueError(f"a rating must be a positive finite power [W], got {shorten(rating)}")
        threshold = float(rating) * (1.0 - RATING_TOLERANCE)
        above = next((m for m in self.motors if m.rated_power >= threshold), None)
        below = next((m for m in reversed(self.motors) if m.rated_power < threshold), None)
        return Neighbours(below, above)


# -- the package data --------------------------------------------------------------

_CATALOGUE_KEYS = {"description", "source", "motor"}
_MOTOR_KEYS = set(QUANTITIES) | set(TEXTS) | {"rated_torque"}


def read_catalogues(text: str, origin: str = f"flyopt/data/{_DATA_FILE}") -> dict[str, Catalogue]:
    """The catalogues of a motors TOML text, checked.

    Parameters
    ----------
    text : str
        The file's text, as ``flyopt/data/motors.toml``.
    origin : str
        The file, for messages.

    Returns
    -------
    dict of str to Catalogue

    Raises
    ------
    ValueError
        Not TOML, an unknown or missing key, a size without a source, a
        figure out of its range or of the wrong unit; the message names the
        file, the catalogue, the size and the field.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{origin}: not valid TOML: {err}") from None
    catalogues = {}
    for name, table in data.items():
        where = f"{origin}: catalogue {name!r}"
        if not isinstance(table, dict):
            raise ValueError(f"{where} must be a table, got {shorten(table)}")
        unknown = sorted(set(table) - _CATALOGUE_KEYS)
        if unknown:
            raise ValueError(f"{where} has unknown keys {unknown}; allowed are {sorted(_CATALOGUE_KEYS)}")
        entries = table.get("motor")
        if not isinstance(entries, list) or not entries:
            raise ValueError(f"{where} has no [[{name}.motor]] sizes")
        motors = [_motor_from_table(entry, f"{where}, motor[{k}]") for k, entry in enumerate(entries)]
        try:
            catalogues[name] = Catalogue(
                name, tuple(motors), str(table.get("description", "")), str(table.get("source", ""))
            )
        except MotorDataError as err:
            raise ValueError(f"{where}, motor[{err.index}]: {err.message}") from None
    return catalogues


def _motor_from_table(entry: Any, where: str) -> CatalogueMotor:
    """A CatalogueMotor from one [[NAME.motor]] table of unit strings; ValueError naming ``where`` and the field."""
    if not isinstance(entry, dict):
        raise ValueError(f"{where} must be a table, got {shorten(entry)}")
    unknown = sorted(set(entry) - _MOTOR_KEYS)
    if unknown:
        raise ValueError(f"{where} has unknown keys {unknown}; allowed are {sorted(_MOTOR_KEYS)}")
    for key in (*REQUIRED, "name", "source"):
        if key not in entry:
            raise ValueError(f"{where} has no {key}" + (" (every size cites its source)" if key == "source" else ""))
    values: dict[str, Any] = {}
    try:
        for key, dimension in QUANTITIES.items():
            if key in entry:
                values[key] = quantity(entry[key], dimension, key)
        if "rated_torque" in entry:
            values["published_rated_torque"] = quantity(entry["rated_torque"], "torque", "rated_torque")
    except SceneError as err:
        raise ValueError(f"{where}.{err.field}: {err.message}") from None
    if not isinstance(entry["source"], str) or not entry["source"].strip():
        raise ValueError(f"{where}.source must cite where the figures come from")
    texts = {key: entry[key] for key in TEXTS if key in entry}
    try:
        return CatalogueMotor(**texts, **values)
    except MotorDataError as err:
        raise ValueError(f"{where}{'.' + err.field if err.field else ''}: {err.message}") from None


@functools.lru_cache(maxsize=1)
def _load():
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    return read_catalogues(text)


def catalogue_names() -> tuple[str, ...]:
    """The names of the catalogues shipped with flyopt, sorted."""
    return tuple(sorted(_load()))


def catalogue(name: str) -> Catalogue:
    """A motor catalogue shipped with flyopt, read once from ``flyopt/data/motors.toml``.

    Parameters
    ----------
    name : str
        E.g. ``"iec_4pole"``.

    Returns
    -------
    Catalogue

    Raises
    ------
    ValueError
        No catalogue has that name; the message lists the known ones.
    """
    catalogues = _load()
    if isinstance(name, str) and name in catalogues:
        return catalogues[name]
    raise ValueError(
        f"motor catalogue {shorten(name)} is not known{hint(name, catalogues)} (known: {', '.join(catalogue_names())})"
    )
