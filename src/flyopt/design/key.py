"""The parallel key of a flywheel's hub: its DIN 6885-1 section, its standard length and its check.

A flywheel sits on its shaft by a hub and, usually, a parallel key. This
module sizes and checks that key:

* :func:`key_for_shaft` -- the DIN 6885-1 key section for a shaft seat;
* :func:`key_length_for_hub` -- the longest standard key that fits a hub
  and its seat (at most :func:`max_key_length` long);
* :func:`check_key` and :func:`hub_length_for_key` -- the key's bearing
  pressure and shear at a torque, and the shortest hub that carries it.

The DIN 6885-1 table, the longest key a seat takes and the key steel live in the package data file
``flyopt/data/keys.toml`` with their sources (the table in mm, as the
standard prints it); this module converts them to SI on loading. Every
argument and result here is SI: m, N*m, Pa.

References
----------
.. [1] DIN 6885-1 (1968, 2021), Drive type fastenings without taper action;
   parallel keys, keyways, deep pattern. Sources of each number in
   ``flyopt/data/keys.toml``.
.. [2] ingenieurkurse.de, Maschinenelemente 1, "Festigkeitsberechnung einer
   Passfederverbindung": tau = F_u / (b l_t), p = F_u / ((h - t1) l_t),
   l_t = l - b for a round-ended key.
.. [3] Budynas, Nisbett, Shigley's Mechanical Engineering Design, section
   7-7: a key no longer than about 1.5 shaft diameters.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from typing import Any

from flyopt._toml import tomllib
from flyopt.said import said
from flyopt.validate import positive

__all__ = [
    "FIT_ATOL",
    "LIMIT_RTOL",
    "Key",
    "KeyCheck",
    "KeySteel",
    "check_key",
    "hub_length_for_key",
    "key_for_shaft",
    "key_length_for_hub",
    "key_steel",
    "key_table",
    "key_verdict",
    "max_key_length",
    "standard_key_lengths",
]

_DATA_FILE = "keys.toml"
_ORIGIN = f"flyopt/data/{_DATA_FILE}"
_COLUMNS = ["d_over", "d_up_to", "b", "h", "t1", "t2", "l_min", "l_max"]

LIMIT_RTOL = 1e-12
"""Relative round-off allowed on a limit: a pressure or stress within this
fraction above its allowable still passes (a design may sit exactly at its
limit, as flyopt's rim speed limit is an allowed maximum)."""

FIT_ATOL = 1e-9
"""Round-off allowed when a key is fitted into a hub [m]: a key fits a hub
that is at most 1 nm shorter, so a hub length computed in metres is not
refused the standard key of its own nominal length."""


def _positive(value, name, unit):
    """``value`` as a float, or ValueError naming ``name`` unless finite and > 0."""
    return positive(value, f"{name} [{unit}]")


# --------------------------------------------------------------------------
# data
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Key:
    """A DIN 6885-1 parallel key section and the shaft seats it serves, all in SI.

    Parameters
    ----------
    b : float
        Key width [m].
    h : float
        Key height [m].
    t1 : float
        Keyway depth in the shaft [m].
    t2 : float
        Keyway depth in the hub (clearance on the key's back) [m].
    d_over, d_up_to : float
        The shaft seats of this section: d_over < d <= d_up_to [m] (the
        standard's "over ... up to and including").
    l_min, l_max : float
        Shortest and longest standard length of this section [m].
    lengths : tuple of float
        The standard key lengths of this section, l_min to l_max [m].
    """

    b: float
    h: float
    t1: float
    t2: float
    d_over: float
    d_up_to: float
    l_min: float
    l_max: float
    lengths: tuple[float, ...]

    @property
    def size(self) -> str:
        """The section as the standard names it, b x h in mm, e.g. ``"14 x 9"``."""
        return f"{self.b * 1e3:g} x {self.h * 1e3:g}"

    @property
    def hub_flank_height(self) -> float:
        """Height of the key's flank in the hub, h - t1 [m]."""
        return self.h - self.t1


@dataclass(frozen=True)
class KeySteel:
    """The key material and its strengths.

    Parameters
    ----------
    name : str
        Material designation, e.g. ``"C45+C"``.
    yield_strength : float
        S_y [Pa].
    tensile_strength : float
        S_ut [Pa].
    shear_yield_strength : float
        S_sy = k S_y by the distortion-energy theory, k = 0.577 [Pa].
    source : str
        Where the numbers come from.
    """

    name: str
    yield_strength: float
    tensile_strength: float
    shear_yield_strength: float
    source: str


def _mm(value, what):
    """A length of the data file [mm] in metres; ``value / 1000`` is the
    correctly rounded metre value of the printed millimetres."""
    number = float(value)
    if not math.isfinite(number) or number <= 0.0:
        raise ValueError(f"{_ORIGIN}: {what} must be a positive length in mm, got {value!r}")
    return number / 1000.0


@functools.lru_cache(maxsize=1)
def _load():
    """Read and check the key table and the key steel of ``keys.toml`` once: (keys, lengths, steel)."""
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    table = data["din_6885_1"]
    if table.get("unit") != "mm" or table.get("columns") != _COLUMNS:
        raise ValueError(f"{_ORIGIN}: din_6885_1 must give unit = 'mm' and columns = {_COLUMNS}")
    lengths_mm = [float(x) for x in table["lengths"]]
    if lengths_mm != sorted(set(lengths_mm)):
        raise ValueError(f"{_ORIGIN}: din_6885_1.lengths must increase strictly")
    lengths = tuple(_mm(x, "a standard key length") for x in lengths_mm)
    keys: list[Key] = []
    for index, row in enumerate(table["rows"]):
        if len(row) != len(_COLUMNS):
            raise ValueError(
                f"{_ORIGIN}: din_6885_1.rows[{index}] has {len(row)} values, "
                f"expected {len(_COLUMNS)} ({', '.join(_COLUMNS)})"
            )
        values = dict(zip(_COLUMNS, row))
        for end in ("l_min", "l_max"):
            if float(values[end]) not in lengths_mm:
                raise ValueError(
                    f"{_ORIGIN}: din_6885_1.rows[{index}]: {end} = {values[end]} mm "
                    f"is not in the series of standard lengths"
                )
        si = {name: _mm(values[name], f"din_6885_1.rows[{index}].{name}") for name in _COLUMNS}
        if not (si["d_over"] < si["d_up_to"] and si["t1"] < si["h"] and si["l_min"] <= si["l_max"]):
            raise ValueError(
                f"{_ORIGIN}: din_6885_1.rows[{index}] = {row!r} is inconsistent "
                f"(need d_over < d_up_to, t1 < h, l_min <= l_max)"
            )
        if keys and si["d_over"] != keys[-1].d_up_to:
            raise ValueError(
                f"{_ORIGIN}: din_6885_1.rows[{index}] starts over {values['d_over']} mm, "
                f"the row before ends at {keys[-1].d_up_to * 1e3:g} mm"
            )
        lengths_of_row = tuple(x for x in lengths if si["l_min"] <= x <= si["l_max"])
        keys.append(Key(lengths=lengths_of_row, **si))

    ratio = float(data["key_length"]["max_to_shaft_ratio"])
    if not (math.isfinite(ratio) and ratio > 0.0):
        raise ValueError(f"{_ORIGIN}: key_length.max_to_shaft_ratio must be a positive number, got {ratio!r}")
    for key in keys:
        if key.l_min > ratio * key.d_over:
            raise ValueError(
                f"{_ORIGIN}: the {key.size} key's shortest length {key.l_min * 1e3:g} mm exceeds "
                f"key_length.max_to_shaft_ratio = {ratio:g} times its smallest seat ({key.d_over * 1e3:g} mm)"
            )

    steel_table = data["key_steel"]
    yield_strength = float(steel_table["yield_strength"])
    steel = KeySteel(
        name=steel_table["name"],
        yield_strength=yield_strength,
        tensile_strength=float(steel_table["tensile_strength"]),
        shear_yield_strength=float(steel_table["shear_yield_ratio"]) * yield_strength,
        source=steel_table["source"],
    )
    return tuple(keys), lengths, steel, ratio


def key_table() -> tuple[Key, ...]:
    """The DIN 6885-1 key sections of ``flyopt/data/keys.toml``, smallest shaft first.

    Returns
    -------
    tuple of Key
        In SI units [m].
    """
    return _load()[0]


def standard_key_lengths() -> tuple[float, ...]:
    """The series of standard key lengths of DIN 6885-1 [m], shortest first.

    Returns
    -------
    tuple of float
    """
    return _load()[1]


def key_steel() -> KeySteel:
    """The key steel (C45+C) and its strengths, from ``flyopt/data/keys.toml``.

    Returns
    -------
    KeySteel
        Its ``shear_yield_strength`` is the default allowable key shear of
        :func:`check_key`.

    Notes
    -----
    S_y is that of AISI 1045 cold drawn (the equivalent of C45+C) in Shigley's
    Table A-20, and S_sy = 0.577 S_y by the distortion-energy theory; the
    data file gives the sources.
    """
    return _load()[2]


def max_key_length(d: float) -> float:
    """The longest key a shaft seat takes: ``key_length.max_to_shaft_ratio`` (1.5) times d [m].

    Parameters
    ----------
    d : float
        Shaft seat diameter [m].

    Returns
    -------
    float
        1.5 d [m]. A standard key is at most this long (:func:`key_length_for_hub`).

    Notes
    -----
    The shaft twists under the torque, so a long key bears mostly at the end
    where the torque enters; Shigley keeps a key below about 1.5 d and adds
    keys beyond it [3]_. DIN 6885-1's l_max (up to 4.7 d) is the longest key
    the standard lists, not the longest that carries load. The ratio and its
    sources are in ``flyopt/data/keys.toml``.
    """
    return _load()[3] * _positive(d, "shaft diameter d", "m")


def _seat_lengths(key: Key, d: float) -> tuple[float, ...]:
    """The standard lengths of section ``key`` a seat of diameter ``d`` [m] takes: at most :func:`max_key_length`
    (up to :data:`FIT_ATOL`)."""
    longest = max_key_length(d) + FIT_ATOL
    return tuple(length for length in key.lengths if length <= longest)


# --------------------------------------------------------------------------
# the key
# --------------------------------------------------------------------------


def key_for_shaft(d: float) -> Key:
    """The DIN 6885-1 parallel key section for a shaft seat.

    Parameters
    ----------
    d : float
        Shaft seat diameter [m].

    Returns
    -------
    Key
        The section whose row holds ``d``: d_over < d <= d_up_to.

    Raises
    ------
    ValueError
        If ``d`` is not a positive finite number, or lies outside the table
        (the message names the diameter and the table's range).

    Notes
    -----
    The standard's rows read "over ... up to and including": d = 50 mm takes
    the 14 x 9 key of the row over 44 up to 50 mm, d = 50.001 mm the 16 x 10
    of the next. Boundaries compare exactly in metres, against the table's
    millimetres divided by 1000.
    """
    d = _positive(d, "shaft diameter d", "m")
    keys = key_table()
    for key in keys:
        if key.d_over < d <= key.d_up_to:
            return key
    raise ValueError(
        said(
            "shaft diameter d = {d} is outside the DIN 6885-1 table of " + _ORIGIN + ", which covers shafts over "
            "{low} up to and including {high}",
            d=(d, "length", f"{d!r} m ({d * 1e3:g} mm)"),
            low=(keys[0].d_over, "length", f"{keys[0].d_over * 1e3:g} mm"),
            high=(keys[-1].d_up_to, "length", f"{keys[-1].d_up_to * 1e3:g} mm"),
        )
    )


def key_length_for_hub(key: Key, hub_length: float, d: float) -> float:
    """The longest standard length of a key section that fits in a hub and its seat.

    Parameters
    ----------
    key : Key
        The key section (:func:`key_for_shaft`).
    hub_length : float
        Length of the hub [m].
    d : float
        Shaft seat diameter [m]: the key is at most :func:`max_key_length` (1.5 d).

    Returns
    -------
    float
        The longest standard length l <= min(hub_length, 1.5 d) of the
        section, at most its l_max [m].

    Raises
    ------
    ValueError
        If the hub is shorter than the section's shortest standard key.

    Notes
    -----
    A key fits a hub up to :data:`FIT_ATOL` (1 nm) shorter than itself, so
    that a hub length computed in metres keeps the key of its nominal
    length. The key is taken as long as the hub and the seat allow: in a hub
    longer than 1.5 d the key (and the shaft's keyseat) is shorter than the
    hub [3]_, whose keyway is cut through.
    """
    hub_length = _positive(hub_length, "hub_length", "m")
    fitting = [length for length in _seat_lengths(key, d) if length <= hub_length + FIT_ATOL]
    if not fitting:
        raise ValueError(
            said(
                "hub length {hub} is shorter than the shortest standard " + key.size + " key, {shortest}",
                hub=(hub_length, "length", f"{hub_length!r} m ({hub_length * 1e3:g} mm)"),
                shortest=(key.l_min, "length", f"{key.l_min * 1e3:g} mm"),
            )
        )
    return fitting[-1]


@dataclass(frozen=True)
class KeyCheck:
    """The key of a hub checked at a torque; all SI.

    Parameters
    ----------
    key : Key
        The key section.
    torque : float
        Torque the joint transmits [N*m].
    d : float
        Shaft seat diameter [m].
    hub_length : float
        Hub length [m].
    length : float
        Standard key length used, the longest that fits in the hub and is at most 1.5 d [m].
    effective_length : float
        Bearing length of the form A key, l - b [m].
    pressure : float
        Bearing pressure on the hub's keyway flank, 2 T / (d (h - t1) l_eff) [Pa].
    shear : float
        Shear stress in the key, 2 T / (d b l_eff) [Pa].
    allowable_pressure : float or None
        Allowable bearing pressure of the hub material [Pa]; None where the hub's material gives none (the
        pressure is computed, and only the key's shear is checked).
    allowable_shear : float
        Allowable shear stress of the key [Pa].
    """

    key: Key
    torque: float
    d: float
    hub_length: float
    length: float
    effective_length: float
    pressure: float
    shear: float
    allowable_pressure: float | None
    allowable_shear: float

    @property
    def pressure_ratio(self) -> float:
        """pressure / allowable_pressure [-]; nan where no allowable pressure is given (not checked)."""
        return math.nan if self.allowable_pressure is None else self.pressure / self.allowable_pressure

    @property
    def shear_ratio(self) -> float:
        """shear / allowable_shear [-]."""
        return self.shear / self.allowable_shear

    @property
    def governing(self) -> str:
        """``"pressure"`` or ``"shear"``: the check nearer its limit (the shear where the pressure is not checked)."""
        return "pressure" if self.pressure_ratio >= self.shear_ratio else "shear"

    @property
    def ok(self) -> bool:
        """Whether both stay within their allowables (up to :data:`LIMIT_RTOL`; the shear alone where no
        allowable pressure is given)."""
        return _within(self.pressure, self.allowable_pressure) and _within(self.shear, self.allowable_shear)


def key_verdict(key: Mapping[str, Any]) -> str:
    """A designed key's verdict in words, the one wording the text, the report and the answer use.

    Parameters
    ----------
    key : mapping
        The design's key (``Candidate.parts.key``: ``shear`` and ``ok`` as :func:`check_key` filled them).

    Returns
    -------
    str
        "OK", "NOT OK", "shear OK, bearing pressure not checked" (the hub's material gives no allowable
        pressure: ``ok`` is None) or "not checked" (no torque to check it at: ``shear`` is None).
    """
    if key.get("shear") is None:
        return "not checked"
    if key.get("ok") is None:
        return "shear OK, bearing pressure not checked"
    return "OK" if key["ok"] else "NOT OK"


def _within(value, allowable):
    """``value`` within ``allowable`` up to :data:`LIMIT_RTOL`; any value where no allowable is given (None)."""
    return allowable is None or value <= allowable * (1.0 + LIMIT_RTOL)


def _key_stresses(torque, d, key, length):
    """(l_eff, pressure, shear) of a form A key of length ``length``."""
    effective_length = length - key.b
    force = 2.0 * torque / d
    return (effective_length, force / (key.hub_flank_height * effective_length), force / (key.b * effective_length))


def _allowables(allowable_pressure, allowable_shear):
    if allowable_pressure is not None:
        allowable_pressure = _positive(allowable_pressure, "allowable_pressure", "Pa")
    if allowable_shear is None:
        allowable_shear = key_steel().shear_yield_strength
    else:
        allowable_shear = _positive(allowable_shear, "allowable_shear", "Pa")
    return allowable_pressure, allowable_shear


def check_key(
    torque: float, d: float, hub_length: float, allowable_pressure: float | None, allowable_shear: float | None = None
) -> KeyCheck:
    """Check the DIN 6885-1 form A key of a hub at a torque.

    Parameters
    ----------
    torque : float
        Largest torque the joint transmits, T [N*m] (e.g.
        :func:`flyopt.sizing.peak_torque.flywheel_peak_torque`).
    d : float
        Shaft seat diameter [m].
    hub_length : float
        Hub length [m]; the key is the longest standard one that fits, at most 1.5 d
        (:func:`key_length_for_hub`).
    allowable_pressure : float or None
        Allowable bearing pressure of the hub material [Pa]; the hub, usually
        the weaker part, gives it. None where the hub's material gives none:
        the pressure is computed but not checked, the key's shear is.
    allowable_shear : float, optional
        Allowable shear stress of the key [Pa]. By default the shear yield
        strength of the key steel C45+C, S_sy = 0.577 S_y (:func:`key_steel`):
        the limit itself, with no safety factor; pass S_sy / n for a design
        factor n.

    Returns
    -------
    KeyCheck
        Key, length, pressures and stresses; ``ok`` tells whether it passes.

    Raises
    ------
    ValueError
        If an argument is not a positive finite number, the shaft is outside
        the key table, or the hub is shorter than the section's shortest key.

    Notes
    -----
    The circumferential force at the seat is F = 2 T / d. A form A (round-
    ended) key bears along its straight part only, l_eff = l - b [2]_. The
    key's flank stands h - t1 high in the hub's keyway, so

        p = 2 T / (d (h - t1) l_eff),    tau = 2 T / (d b l_eff)

    as in [2]_; mechanixcalc.com's DIN 6885 calculator, after Roloff/Matek,
    also bears on h - t1 (one key, load share 1; Roloff/Matek itself was not at
    hand). Some texts take the hub's flank as t2 (strokeforge.tech) or h/2
    (Shigley, Khurmi) instead; h - t1 is the height the key offers the hub.
    Chamfers of key and keyway are neglected.
    """
    torque = _positive(torque, "torque", "N*m")
    d = _positive(d, "shaft diameter d", "m")
    hub_length = _positive(hub_length, "hub_length", "m")
    allowable_pressure, allowable_shear = _allowables(allowable_pressure, allowable_shear)
    key = key_for_shaft(d)
    length = key_length_for_hub(key, hub_length, d)
    effective_length, pressure, shear = _key_stresses(torque, d, key, length)
    return KeyCheck(
        key=key,
        torque=torque,
        d=d,
        hub_length=hub_length,
        length=length,
        effective_length=effective_length,
        pressure=pressure,
        shear=shear,
        allowable_pressure=allowable_pressure,
        allowable_shear=allowable_shear,
    )


def hub_length_for_key(
    torque: float, d: float, allowable_pressure: float | None, allowable_shear: float | None = None
) -> float:
    """The shortest hub whose DIN 6885-1 key passes :func:`check_key`.

    Parameters
    ----------
    torque : float
        Largest torque the joint transmits [N*m].
    d : float
        Shaft seat diameter [m].
    allowable_pressure : float or None
        Allowable bearing pressure of the hub material [Pa]; None: the shear alone sets the length.
    allowable_shear : float, optional
        Allowable shear stress of the key [Pa]; default as in :func:`check_key`.

    Returns
    -------
    float
        The shortest standard key length l of the section for which both
        the pressure and the shear stay within their allowables: a hub of
        exactly this length passes :func:`check_key` [m]. A lower bound on the
        hub length.

    Raises
    ------
    ValueError
        If an argument is not a positive finite number, the shaft is outside
        the table, or even the longest key the seat takes (the section's
        longest standard length up to 1.5 d) cannot carry the torque.

    Notes
    -----
    Without rounding the key would need l = b + l_eff with
    l_eff = max(2 T / (d (h - t1) p_allow), 2 T / (d b tau_allow)). But the key
    is a standard length, and a hub of length L holds the longest standard
    key l <= L, so the check is a step function of L: a hub between two
    standard lengths carries no more than one of the shorter length. The
    shortest passing hub is therefore the shortest standard length l >= b +
    l_eff (and >= the section's l_min); there the pressure is at most the
    allowable, and equal to it only when b + l_eff falls on a standard length.
    Any hub at least this long passes (a hub longer than 1.5 d holds the
    same key of at most 1.5 d); any shorter one fails. The answer is found
    by running the same check over the lengths the seat takes, so the two
    functions cannot disagree.
    """
    torque = _positive(torque, "torque", "N*m")
    d = _positive(d, "shaft diameter d", "m")
    allowable_pressure, allowable_shear = _allowables(allowable_pressure, allowable_shear)
    length, why = _hub_length_or_why(torque, d, allowable_pressure, allowable_shear)
    if length is None:
        raise ValueError(why)
    return length


@functools.lru_cache(maxsize=256)
def _hub_length_or_why(
    torque: float, d: float, allowable_pressure: float | None, allowable_shear: float
) -> tuple[float | None, str | None]:
    """(:func:`hub_length_for_key`'s answer, None), or (None, why no key carries the torque), of checked
    arguments. Kept per arguments: a design screens every combination's hub at the same torque and seat,
    a dozen calls a sweep point."""
    key = key_for_shaft(d)
    lengths = _seat_lengths(key, d)
    for length in lengths:
        _, pressure, shear = _key_stresses(torque, d, key, length)
        if _within(pressure, allowable_pressure) and _within(shear, allowable_shear):
            return length, None
    _, pressure, shear = _key_stresses(torque, d, key, lengths[-1])
    against = (
        "not checked"
        if allowable_pressure is None
        else said("against {allowed}", allowed=(allowable_pressure, "stress", f"{allowable_pressure / 1e6:.4g} MPa"))
    )
    return None, (
        said("torque {torque}: even the longest ", torque=(torque, "torque", f"{torque:.4g} N·m"))
        + key.size
        + said(
            " key the d = {d} seat takes ({length}, at most 1.5 d) is overloaded (pressure {pressure} ",
            d=(d, "length", f"{d * 1e3:g} mm"),
            length=(lengths[-1], "length", f"{lengths[-1] * 1e3:g} mm"),
            pressure=(pressure, "stress", f"{pressure / 1e6:.4g} MPa"),
        )
        + against
        + said(
            ", shear {shear} against {allowed}); use a larger shaft seat, a stronger hub material or another "
            "shaft-hub joint",
            shear=(shear, "stress", f"{shear / 1e6:.4g} MPa"),
            allowed=(allowable_shear, "stress", f"{allowable_shear / 1e6:.4g} MPa"),
        )
    )
