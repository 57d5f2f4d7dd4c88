"""The [drive] section and [[motor_option]] tables: the drive designed with the flywheel.

A scene with [drive] asks flyopt to choose the motor and the flywheel's speed
ratio together with the wheel (:mod:`flyopt.drive.codesign`;
docs/flywheel-design.md, sections 7 and 8). This module reads and checks that
request into a :class:`DriveSpec`; every wrong value is a
:class:`~flyopt.errors.SceneError` naming the field (``drive.ratio``,
``motor_option[1].rated_speed``) and what is allowed.

Example::

    [drive]
    motors = "iec_4pole"      # a catalogue shipped with flyopt (flyopt/data/motors.toml)
    ratio = [2, 8]            # range of the flywheel shaft's speed ratio to the crank
    objective = "mass"        # or "cost": motor price + wheel cost
    max_startup = "12 s"      # run-up from rest on the motor's Kloss curve
    thermal = true            # the motor's RMS torque over the cycle within its rating

or, instead of ``motors``, the scene's own motors::

    [[motor_option]]
    name = "7.5 kW"
    rated_power = "7.5 kW"
    rated_speed = "1455 rpm"
    synchronous_speed = "1500 rpm"
    rotor_inertia = "0.03 kg*m^2"
    breakdown_ratio = 3.1     # optional, as are locked_rotor_ratio, efficiency,
    price = 620               # efficiency_class, frame, mass, price and source
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_count, check_line, check_magnitude, check_scale
from flyopt.io.shaft_section import RATIO_RANGE
from flyopt.machine.catalogue import QUANTITIES, REQUIRED, TEXTS, Catalogue, CatalogueMotor, MotorDataError, catalogue
from flyopt.units import quantity

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence
    from typing import Unpack  # Python 3.11; the annotations are never evaluated

    from flyopt.design.materials import Material
    from flyopt.machine.transmission import Shaft

__all__ = ["DriveSpec", "drive_spec", "OBJECTIVES", "DRIVE_KEYS", "MOTOR_OPTION_KEYS"]

OBJECTIVES = ("mass", "cost")
"""Objectives of a drive design: motor mass plus wheel mass, or motor price plus wheel cost."""

DRIVE_KEYS = ("motors", "ratio", "ratios", "objective", "max_startup", "thermal", "description")
"""Keys of the [drive] table."""

MOTOR_OPTION_KEYS = (*QUANTITIES, *TEXTS, "description")
"""Keys of a [[motor_option]] table: a catalogue size's fields (:mod:`flyopt.machine.catalogue`)."""

_OPTIONS = "motor_option"
MAX_OPTIONS = 64
"""Most [[motor_option]] tables, and most fixed ``ratios``, a drive may try: each pair is a periodic solution
(the IEC catalogue has 18 motors)."""


@dataclass(frozen=True)
class DriveSpec:
    """What the drive design may choose, and its objective and limits.

    Attributes
    ----------
    motors : Catalogue
        The sizes to choose from, in increasing rated power: a shipped
        catalogue (its name) or the scene's [[motor_option]] tables (named
        ``"motor_option"``).
    ratio_range : tuple of float or None
        (min, max) of the flywheel shaft's speed ratio to the crank,
        r = ω_flywheel/ω_crank, designed continuously [-]; None with ``ratios``.
    ratios : tuple of float or None
        Fixed ratios r to choose among, increasing [-]; None with ``ratio_range``.
    objective : {"mass", "cost"}
        Motor mass plus wheel mass, or motor price plus wheel cost.
    max_startup : float or None
        Longest run-up from rest [s]; None: not limited.
    thermal : bool
        The motor's RMS torque over the cycle must stay within its rated torque.

    Notes
    -----
    The spelling cannot be ambiguous: ``ratio = [2, 8]`` is always a range
    (exactly two numbers, min < max), ``ratios = [2, 3.5, 5]`` always a list
    of fixed choices (one or more); a scene gives one of the two. The
    transmission's efficiency from the motor to the crank is the scene's own
    (``machine.efficiency``, or the [[shaft]] turning at the crank's speed),
    not a second figure here.
    """

    motors: Catalogue
    ratio_range: tuple[float, float] | None = None
    ratios: tuple[float, ...] | None = None
    objective: str = "mass"
    max_startup: float | None = None
    thermal: bool = True

    def __post_init__(self) -> None:
        if (self.ratio_range is None) == (self.ratios is None):
            raise ValueError("a drive gives either a ratio range or fixed ratios, not both or neither")

    def ratio_choice(self) -> tuple[str, Unpack[tuple[float, ...]]]:
        """``("range", lo, hi)`` for a ratio designed continuously, ``("fixed", r1, r2, ...)`` for fixed ratios."""
        if self.ratios is not None:
            return ("fixed", *self.ratios)
        lo, hi = self.ratio_bounds()
        return ("range", lo, hi)

    def ratio_bounds(self) -> tuple[float, float]:
        """The smallest and largest ratio the drive may take [-]."""
        if self.ratios is not None:
            return min(self.ratios), max(self.ratios)
        if self.ratio_range is None:  # pragma: no cover - __post_init__ refuses a drive with neither
            raise ValueError("a drive gives either a ratio range or fixed ratios")
        return self.ratio_range


def drive_spec(
    raw_drive: object,
    raw_motor_options: object,
    shafts: Sequence[Shaft],
    materials: Mapping[str, Material] | None = None,
) -> DriveSpec:
    """Read and check a scene's [drive] table and [[motor_option]] tables.

    Parameters
    ----------
    raw_drive : dict or None
        The [drive] table as TOML reads it (None: the scene has none).
    raw_motor_options : list or None
        The [[motor_option]] tables (None: the scene has none).
    shafts : tuple of flyopt.io.scene.Shaft
        The scene's [[shaft]] tables. Nothing here depends on them: the
        flywheel's shaft is the one the drive designs, at its own ratio.
    materials : mapping of str to Material, optional
        The materials the flywheel design may use, when the caller knows them:
        with ``objective = "cost"`` each must have a cost per kg.

    Returns
    -------
    DriveSpec

    Raises
    ------
    SceneError
        A field is missing, unknown or wrong; the message names it and what is
        allowed.
    """
    if raw_drive is None:
        raise SceneError(
            "drive",
            "is missing: [[motor_option]] tables are the motors of a [drive] section (ratio, objective, ...); add one",
        )
    table = Table(raw_drive, "drive", DRIVE_KEYS).data
    motors = _motors(table, raw_motor_options)
    ratio_range, ratios = _ratios(table)
    objective = _objective(table, motors, materials)
    max_startup = None
    if "max_startup" in table:
        max_startup = quantity(table["max_startup"], "time", "drive.max_startup")
        if not max_startup > 0:
            raise SceneError(
                "drive.max_startup", f"must be a positive time (e.g. '12 s'), got {shorten(table['max_startup'])}"
            )
        check_scale(max_startup, "time", "drive.max_startup", table["max_startup"])
    thermal = table.get("thermal", True)
    if not isinstance(thermal, bool):
        raise SceneError("drive.thermal", f"must be true or false, got {shorten(thermal)}")
    return DriveSpec(motors, ratio_range, ratios, objective, max_startup, thermal)


def _motors(table, raw_options):
    """The Catalogue the drive chooses from: ``drive.motors`` or the [[motor_option]] tables, exactly one."""
    if "motors" in table and raw_options is not None:
        raise SceneError("drive.motors", "give either a catalogue (drive.motors) or [[motor_option]] tables, not both")
    if "motors" in table:
        name = table["motors"]
        if not isinstance(name, str):
            raise SceneError(
                "drive.motors",
                f'must be the name of a motor catalogue (a string, e.g. "iec_4pole"), got {shorten(name)}',
            )
        try:
            return catalogue(name)
        except ValueError as err:
            raise SceneError("drive.motors", f"{err}; or give [[motor_option]] tables of your own") from None
    if raw_options is None:
        raise SceneError(
            "drive.motors", 'is missing: name a motor catalogue (motors = "iec_4pole") or give [[motor_option]] tables'
        )
    if not isinstance(raw_options, list) or not raw_options:
        raise SceneError(
            _OPTIONS,
            "must be an array of tables: [[motor_option]] with rated_power, rated_speed, "
            "synchronous_speed and rotor_inertia",
        )
    check_count(raw_options, _OPTIONS, MAX_OPTIONS, "[[motor_option]] tables")
    motors = [_motor_option(item, k) for k, item in enumerate(raw_options)]
    try:
        return Catalogue(_OPTIONS, tuple(motors), "the scene's [[motor_option]] tables")
    except MotorDataError as err:
        raise SceneError(f"{_OPTIONS}[{err.index}].{err.field}", err.message) from None


def _motor_option(raw, k):
    """One [[motor_option]] table as a CatalogueMotor."""
    where = f"{_OPTIONS}[{k}]"
    table = Table(raw, where, MOTOR_OPTION_KEYS).data
    for key in REQUIRED:
        if key not in table:
            raise SceneError(f"{where}.{key}", f"is missing: a motor option gives at least {', '.join(REQUIRED)}")
    values: dict[str, Any] = {}
    for key, dimension in QUANTITIES.items():
        if key in table:  # each held to its dimension's sizes, as a section's Table holds its fields
            values[key] = quantity(table[key], dimension, f"{where}.{key}")
            check_scale(values[key], dimension, f"{where}.{key}", table[key])
    texts = {key: table[key] for key in TEXTS if key in table}
    if isinstance(texts.get("name"), str):
        check_line(texts["name"], f"{where}.name")
    texts.setdefault("name", where)
    try:
        return CatalogueMotor(**texts, **values)
    except MotorDataError as err:
        raise SceneError(f"{where}.{err.field}" if err.field else where, err.message) from None


def _ratios(table):
    """(ratio_range, ratios): one of ``ratio = [min, max]`` or ``ratios = [r, ...]``."""
    if "ratio" in table and "ratios" in table:
        raise SceneError(
            "drive.ratios",
            "give either ratio = [min, max] (a range the design chooses in) or "
            "ratios = [r1, r2, ...] (fixed choices), not both",
        )
    if "ratio" in table:
        raw = table["ratio"]
        if not isinstance(raw, list) or len(raw) != 2:
            fixed = (
                f"; for fixed ratios write ratios = [{raw}]"
                if not isinstance(raw, list)
                else "; for fixed ratios write ratios = [...]"
            )
            raise SceneError(
                "drive.ratio",
                f"must be a range [min, max] of the flywheel shaft's speed ratio to "
                f"the crank, got {shorten(raw)}{fixed}",
            )
        low, high = (quantity(v, "dimensionless", f"drive.ratio[{k}]") for k, v in enumerate(raw))
        if not low > 0:
            raise SceneError("drive.ratio", f"must be a range of positive ratios 0 < min < max, got {shorten(raw)}")
        if not low < high:
            raise SceneError("drive.ratio", f"must be a range 0 < min < max (min first), got {shorten(raw)}")
        for k, value in enumerate((low, high)):
            check_magnitude(
                value, f"drive.ratio[{k}]", raw[k], *RATIO_RANGE, "", "the range of a [[shaft]] speed_ratio"
            )
        return (low, high), None
    if "ratios" in table:
        raw = table["ratios"]
        if not isinstance(raw, list) or not raw:
            raise SceneError(
                "drive.ratios", f"must be a non-empty list of fixed speed ratios (e.g. [2, 3.5, 5]), got {shorten(raw)}"
            )
        check_count(raw, "drive.ratios", MAX_OPTIONS, "ratios")
        ratios = []
        for k, v in enumerate(raw):
            r = quantity(v, "dimensionless", f"drive.ratios[{k}]")
            if not r > 0:
                raise SceneError(f"drive.ratios[{k}]", f"must be a positive ratio, got {shorten(v)}")
            check_magnitude(r, f"drive.ratios[{k}]", v, *RATIO_RANGE, "", "the range of a [[shaft]] speed_ratio")
            if r in ratios:
                raise SceneError(f"drive.ratios[{k}]", f"the ratio {shorten(v)} is given twice")
            ratios.append(r)
        return None, tuple(sorted(ratios))
    raise SceneError(
        "drive.ratio",
        "is missing: give ratio = [min, max] (the range of the flywheel shaft's "
        "speed ratio to the crank) or ratios = [r1, r2, ...] (fixed choices)",
    )


def _objective(table, motors, materials):
    """The objective, and for "cost" a price for every motor and a cost per kg for every material."""
    objective = table.get("objective", "mass")
    if objective not in OBJECTIVES:
        raise SceneError("drive.objective", f"{shorten(objective)} is not known (allowed: {', '.join(OBJECTIVES)})")
    if objective == "mass":
        massless = tuple(m.name for m in motors if m.mass is None)
        if massless:
            raise SceneError(
                "drive.objective",
                f"'mass' is the motor's mass plus the wheel's, and none is given "
                f"for {shorten(', '.join(massless), 200)} (give mass = ...)",
            )
        return objective
    unpriced = motors.unpriced
    if unpriced:
        if motors.name == _OPTIONS:
            raise SceneError(
                "drive.objective",
                f"'cost' needs a price for every motor option; none is given for "
                f"{shorten(', '.join(unpriced), 200)} (give price = ...)",
            )
        raise SceneError(
            "drive.objective",
            f"'cost' needs a price for every motor; the catalogue "
            f"{shorten(motors.name)} gives none for {len(unpriced)} of its "
            f"{len(motors)} sizes (no price source is on file): give "
            '[[motor_option]] tables with prices, or objective = "mass"',
        )
    if materials is not None:
        missing = [name for name, material in materials.items() if material.cost is None]
        if missing:
            raise SceneError(
                "drive.objective",
                f"'cost' needs a cost per kg for every material the flywheel may "
                f"be made of; none is given for {shorten(', '.join(missing), 200)}",
            )
    return objective
