"""The mounting shaft checked with the wheel it carries and the cycle that sized it (issue 30, items 1 and 5).

One function, :func:`check_shaft`, joins the library modules of this package to a
shaft described as a part (:class:`flyopt.machine.shaft_layout.ShaftLayout`):

- **loads**: the wheel's weight m g and the pulls of the scene (stationary: a
  rotating shaft sees them as fully reversed bending, M_a); the wheel's permissible
  residual unbalance at the top speed, ISO 21940-11 (balance grade G = e_per omega,
  e.g. G 6.3 = 6.3 mm/s), F_u = m e_per omega_max^2 = m G omega_max (it turns with
  the shaft: a steady bending in the shaft, M_m); the torque the wheel exchanges
  with the shaft over the cycle, (J_F/J(phi)) (M_d - M_r)/r
  (:func:`flyopt.sizing.peak_torque.flywheel_torque_curve`), as a midrange
  T_m = (T_max + T_min)/2 and an alternating T_a = (T_max - T_min)/2, carried between
  the seat and ``torque_at``;
- **strength**: DE-Goodman fatigue and first-cycle yield (Shigley 9th ed. Eqs. (7-7),
  (7-15), (7-16); :mod:`~flyopt.design.shaft.strength`) at the keyseat of the wheel
  seat, each shoulder (Table 7-1's K_t, K_ts) and the plain sections at the bearings
  and loads;
- **deflection and slope** (:mod:`~flyopt.design.shaft.beam`): the slope at each
  bearing against ``max_slope`` and the wheel's deflection against ``max_deflection``
  (the two planes added as vectors, the unbalance's added in magnitude);
- **lateral critical speed** (:mod:`~flyopt.design.shaft.lateral`): the first
  forward critical speed of the beam FE with the wheel as a rigid disc (its
  gyroscopic effect included) against the running range omega_m r (1 -/+ delta/2);
- **torsional modes** (:mod:`~flyopt.design.shaft.torsional`, :mod:`~flyopt.design.shaft.train`):
  the drive train from the motor to the crank with the wheel at its place (by default the
  wheel and the inertia already on the shaft joined by the shaft between the seat and
  ``torque_at``), its modes against the orders of the cycle's net torque, and its forced
  response at the mean speed;
- **key**: where the train is modelled, the key the wheel was designed with, checked by the design's own rule
  (:func:`flyopt.design.key.check_key`) at the peak of the torque the train's forced response gives the
  wheel's own inertia, J_wheel theta''_wheel (the design sized it at the rigid body's peak).

Each limit is a :class:`ShaftLimit` with its value, the allowed value and the
utilisation (<= 1 holds). The check is a post-check of a designed wheel, not a
row of the NLP (docs/flywheel-design.md, section 26).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.design import key as din_key
from flyopt.design.balance import BALANCE_GRADE, permissible_unbalance
from flyopt.design.shaft import strength
from flyopt.design.shaft.beam import SteppedShaft, elastic_lines
from flyopt.design.shaft.lateral import GRAVITY, Disc, critical_speeds, rotor_model
from flyopt.design.shaft.torsional import TorsionalCheck, running_range_rpm, torsional_check
from flyopt.design.shaft.train import TrainResponse, key_torque, seat_torque, shaft_train, train_response
from flyopt.machine.torsion import TorqueOrders
from flyopt.said import said
from flyopt.units import rad_s_to_rpm, rpm_to_rad_s

if TYPE_CHECKING:
    from flyopt.design.materials import Material
    from flyopt.machine.shaft_layout import ShaftLayout

__all__ = [
    "ShaftLimit",
    "ShaftCheck",
    "KeySeat",
    "Section",
    "check_shaft",
    "separation_utilisation",
    "notch_factors",
    "notch_geometry",
]

#: The fatigue criterion of the check (Shigley 9th ed. Eq. (7-7)): DE-Goodman, the book's design choice.
CRITERION = "goodman"
#: Orders of the net torque at least this share of the largest are checked against the torsional modes.
SIGNIFICANT_ORDER = 0.05
#: Equal steps of the diagram along the shaft (the checked sections and breakpoints added to them).
DIAGRAM_POINTS = 121


@dataclass(frozen=True)
class ShaftLimit:
    """One limit of the shaft: its value, the allowed value and the utilisation (<= 1 holds).

    ``kind`` is one of fatigue, yield, slope, deflection, lateral, torsional, key; ``where`` says where. A key's
    limit is its governing stress (bearing pressure or shear, Pa) at ``torque``, the forced response's peak
    J_wheel theta''_wheel [N*m] (nan for the other kinds).
    """

    kind: str
    where: str
    value: float
    allowed: float
    utilisation: float
    unit: str
    torque: float = math.nan

    @property
    def holds(self) -> bool:
        """Whether the limit holds (utilisation <= 1)."""
        return self.utilisation <= 1.0

    def si(self, x: float) -> float:
        """``x``, a value of this limit in its :attr:`unit`, in SI (a critical speed's rpm in rad/s): as ``--json``
        and every reader shows it."""
        return rpm_to_rad_s(x) if self.unit == "rpm" else x

    def describe(self) -> str:
        """The limit in words and numbers, e.g. ``"fatigue at the keyseat (x = 300 mm): n 1.21 < 1.5"``, its
        quantities kept for the reader's units (:mod:`flyopt.said`)."""
        if self.kind in ("lateral", "torsional"):
            state = "clear of" if self.holds else "inside"
            return (
                f"{self.kind} critical speed ("
                + self.where
                + said(
                    f") {{value}} {state} the running range widened to {{allowed}}",
                    value=(self.si(self.value), DIMENSIONS[self.kind], f"{_fmt(self.value)} rpm"),
                    allowed=(self.si(self.allowed), DIMENSIONS[self.kind], f"{_fmt(self.allowed)} rpm"),
                )
            )
        relation = "<=" if self.holds else ">"
        if self.kind == "key":
            return (
                "key "
                + self.where
                + said(
                    f": {{value}} {relation} {{allowed}} at the train's peak torque on the wheel {{torque}}",
                    value=(self.value, DIMENSIONS["key"], _fmt(self.value / 1e6)),
                    allowed=(self.allowed, DIMENSIONS["key"], f"{_fmt(self.allowed / 1e6)} MPa"),
                    torque=(float(self.torque), "torque", f"{_fmt(float(self.torque))} N·m"),
                )
            )
        name = {"fatigue": "fatigue factor of safety", "yield": "first-cycle yield factor"}.get(self.kind, self.kind)
        if self.kind in ("fatigue", "yield"):
            relation = ">=" if self.holds else "<"
        dimension = DIMENSIONS[self.kind]
        if dimension == "dimensionless":  # a factor of safety: no unit
            return (
                f"{name} " + self.where + f": {_fmt(self.value)} {relation} {_fmt(self.allowed)} {self.unit}".rstrip()
            )
        return (
            f"{name} "
            + self.where
            + said(
                f": {{value}} {relation} {{allowed}}",
                value=(self.value, dimension, _fmt(self.value)),
                allowed=(self.allowed, dimension, f"{_fmt(self.allowed)} {self.unit}"),
            )
        )

    def to_dict(self) -> dict[str, Any]:
        """The limit for ``--json`` (SI): its value and the allowed one under the names of its quantity
        (:data:`JSON_NAMES`; a critical speed in rad/s)."""
        name = JSON_NAMES[self.kind]
        return {
            "kind": self.kind,
            "where": self.where,
            name: self.si(self.value),
            f"{name}_allowed": self.si(self.allowed),
            "utilisation": self.utilisation,
            **({"key_torque": self.torque} if self.kind == "key" else {}),
        }


#: The field of each kind of limit in ``--json`` (its allowed value is ``<name>_allowed``); units in
#: :data:`flyopt.outputs.quantities.QUANTITIES`.
JSON_NAMES = {
    "fatigue": "fatigue_factor",
    "yield": "yield_factor",
    "slope": "slope",
    "deflection": "deflection",
    "lateral": "critical_speed",
    "torsional": "critical_speed",
    "key": "key_stress",
}

#: The dimension of each kind of limit's value in SI (:meth:`ShaftLimit.si`), as the reader's units show it;
#: :data:`flyopt.outputs.quantities.QUANTITIES` gives its JSON field (:data:`JSON_NAMES`) the same one.
DIMENSIONS = {
    "fatigue": "dimensionless",
    "yield": "dimensionless",
    "slope": "angle",
    "deflection": "length",
    "lateral": "angular_speed",
    "torsional": "angular_speed",
    "key": "stress",
}


@dataclass(frozen=True)
class KeySeat:
    """The DIN 6885-1 key a wheel was designed with (:func:`flyopt.design.key.check_key`'s arguments, SI): the
    seat ``d`` [m], the key's standard ``length`` [m] (the longest that fits the hub, so a "hub" of exactly this
    length gives the same key back) and the allowables the design checked it against [Pa] (no pressure: None)."""

    d: float
    length: float
    allowable_pressure: float | None
    allowable_shear: float


def _fmt(x: float) -> str:
    return f"{x:.4g}" if math.isfinite(x) else str(x)


@dataclass(frozen=True)
class Section:
    """A section the strength is checked at: x [m], d [m], K_f, K_fs, the moments and torques [N*m], n_f, n_y."""

    x: float
    name: str
    diameter: float
    kf: float
    kfs: float
    ma: float
    mm: float
    ta: float
    tm: float
    fatigue: float
    yield_: float


@dataclass(frozen=True)
class ShaftCheck:
    """The shaft's checks with one wheel over one cycle (SI).

    Attributes
    ----------
    limits : tuple of ShaftLimit
        Every limit, the worst section of each kind.
    sections : tuple of Section
    weight, unbalance : float
        The wheel's weight and its permissible unbalance force at the top speed [N].
    torque_mean, torque_alternating : float
        T_m and T_a at the wheel's seat the fatigue and yield checks use [N*m]: where the drive train is
        modelled, those of the forced response's torque there, every order synthesised in time
        (:func:`~flyopt.design.shaft.train.seat_torque`); else those of the torque the wheel exchanges with
        the shaft as a rigid body.
    torque_alternating_rigid : float
        T_a of the rigid-body torque the wheel exchanges [N*m] (what the forced response replaces).
    torque_source : {"rigid body", "forced response"}
        Which of the two T_m and T_a are.
    key_torque : float
        Where the train is modelled, the peak of the torque the wheel's key carries by the forced response,
        J_wheel theta''_wheel [N*m] (:func:`~flyopt.design.shaft.train.key_torque`; the design sizes the key
        at the same torque, :func:`flyopt.design.shaft.cycle.key_torque_on`); nan where it is not.
    lateral_speed : float
        The first forward critical speed [rad/s] (nan: none found).
    speed_range_rpm : (float, float)
        The shaft's running range [rpm].
    torsional : TorsionalCheck or None
        None without an inertia on the shaft besides the wheel (no elastic mode).
    diagram : dict
        x [m] and along it M_a, M_m [N*m], T_max [N*m] and the utilisation of the plain section.
    response_inputs : tuple or None
        What :attr:`train` works out the forced response from (the built train, the excitation, the mean
        speed [rpm] and the damping ratio).
    """

    limits: tuple[ShaftLimit, ...]
    sections: tuple[Section, ...]
    weight: float
    unbalance: float
    torque_mean: float
    torque_alternating: float
    lateral_speed: float
    speed_range_rpm: tuple[float, float]
    torsional: TorsionalCheck | None
    diagram: dict[str, np.ndarray] = field(repr=False)
    response_inputs: tuple[Any, ...] | None = field(default=None, repr=False, compare=False)
    torque_alternating_rigid: float = math.nan
    torque_source: str = "rigid body"
    key_torque: float = math.nan

    @cached_property
    def train(self) -> TrainResponse | None:
        """The drive train's nodes, modes and shapes and its forced response at the mean speed (None without a
        torsional check). Worked out when first asked (the report and ``--json`` of the chosen wheel), not for
        every design the post-check screens: the limits do not depend on it."""
        if self.response_inputs is None or self.torsional is None:
            return None
        built, excitation, speed_rpm, zeta = self.response_inputs
        return train_response(built, self.torsional.modes, excitation, self.torsional.orders, speed_rpm, zeta)

    @property
    def binding(self) -> ShaftLimit:
        """The limit of largest utilisation."""
        return max(self.limits, key=lambda lim: lim.utilisation)

    @property
    def holds(self) -> bool:
        """Whether every limit holds."""
        return all(lim.holds for lim in self.limits)

    def failed(self) -> list[ShaftLimit]:
        """The limits that do not hold."""
        return [lim for lim in self.limits if not lim.holds]

    def to_dict(self) -> dict[str, Any]:
        """The check for ``--json`` (SI)."""
        return {
            "holds": self.holds,
            "binding": self.binding.to_dict(),
            "limits": [lim.to_dict() for lim in self.limits],
            "weight": self.weight,
            "unbalance_force": self.unbalance,
            "torque_mean": self.torque_mean,
            "torque_alternating": self.torque_alternating,
            "torque_alternating_rigid": self.torque_alternating_rigid,
            "torque_source": self.torque_source,
            **({"key_torque": self.key_torque} if math.isfinite(self.key_torque) else {}),
            "lateral_critical_speed": self.lateral_speed,
            "speed_range": [rpm_to_rad_s(v) for v in self.speed_range_rpm],
            "torsional_modes": (
                [] if self.torsional is None else [f * 2.0 * math.pi for f in self.torsional.modes.frequencies_hz]
            ),
            **({} if self.train is None else {"drive_train": self._train_dict()}),
        }

    def _train_dict(self) -> dict[str, Any]:
        """The drive train's nodes, modes, critical speeds of the orders present and forced response (SI)."""
        if self.train is None or self.torsional is None:
            return {}
        out = self.train.to_dict()
        out["critical_speeds"] = [
            {
                "mode": c.mode,
                "order": c.order,
                "critical_speed": rpm_to_rad_s(c.speed_rpm),
                "margin": c.margin,
                "in_range": c.in_range,
            }
            for c in self.torsional.critical
        ]
        return out


def separation_utilisation(critical_rpm: float, speed_range_rpm: tuple[float, float], margin: float) -> float:
    """Utilisation of a critical speed's separation from the running range widened by ``margin``.

    min(n_max (1 + m) / n_c, n_c / (n_min (1 - m))): below 1 when n_c lies above n_max (1 + m) or below
    n_min (1 - m), above 1 inside that band (the running range itself is inside it at any m >= 0).
    """
    low, high = speed_range_rpm
    if not critical_rpm > 0.0 or not math.isfinite(critical_rpm):
        return 0.0
    return min(high * (1.0 + margin) / critical_rpm, critical_rpm / (low * (1.0 - margin)))


@functools.lru_cache(maxsize=1024)
def notch_factors(kind: str, diameter: float, fillet: float | None, sut: float) -> tuple[float, float]:
    """K_f and K_fs of a notch, Shigley 9th ed. Table 7-1 (K_t, K_ts) with Eqs. (6-32), (6-34), (6-35).

    ``kind``: "keyseat" (r = 0.02 d) or "shoulder" (r = ``fillet``, or 0.02 d when sharp; Table 7-1's
    well-rounded factors once r/d >= 0.1, its sharp ones below, on the safe side). A pure function of its
    arguments, kept for the design's many wheels on one shaft (the same notches each time).
    """
    kt, kts, r_over_d = notch_geometry(kind, diameter, fillet)
    radius = r_over_d * diameter if fillet is None or kind == "keyseat" else fillet
    q = strength.notch_sensitivity(radius, sut, "bending")
    qs = strength.notch_sensitivity(radius, sut, "torsion")
    return float(strength.fatigue_concentration(kt, q)), float(strength.fatigue_concentration(kts, qs))


def notch_geometry(kind: str, diameter: float, fillet: float | None) -> tuple[float, float, float]:
    """(K_t, K_ts, r/d) of a notch of Shigley 9th ed. Table 7-1 at a section of ``diameter`` [m]: a keyseat's
    r = 0.02 d; a shoulder's r = ``fillet`` (r/d then of this diameter) or 0.02 d when sharp, its well-rounded
    factors once r/d >= 0.1, its sharp ones below. The one place the table's row and radius are chosen
    (:func:`notch_factors`; the seat's NLP, which writes r = (r/d) d on its d where the radius follows d)."""
    table = strength._data()["notch"]
    if kind == "keyseat":
        row = table["keyseat"]
        return float(row["kt"]), float(row["kts"]), float(row["r_over_d"])
    if kind != "shoulder":
        raise ValueError(f"notch kind {kind!r} is not known (allowed: keyseat, shoulder)")
    r_over_d = table["shoulder_sharp"]["r_over_d"] if fillet is None else fillet / diameter
    rounded = table["shoulder_rounded"]
    row = rounded if r_over_d >= rounded["r_over_d"] else table["shoulder_sharp"]
    return float(row["kt"]), float(row["kts"]), float(r_over_d)


def _plane_loads(layout: ShaftLayout, weight: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Positions and the forces in the vertical (y, up) and horizontal (z) planes of the stationary loads."""
    x = [layout.wheel_at] + [load.position for load in layout.loads]
    fy = [-weight] + [-load.force * math.cos(load.angle) for load in layout.loads]
    fz = [0.0] + [load.force * math.sin(load.angle) for load in layout.loads]
    return np.array(x), np.array(fy), np.array(fz)


def carries_torque(layout: ShaftLayout, x: np.ndarray) -> np.ndarray:
    low, high = sorted((layout.wheel_at, layout.torque_at))
    inside: np.ndarray = (x >= low - 1e-12) & (x <= high + 1e-12)
    return inside


def section_name(what: str, x: float) -> str:
    """A checked section by what is there and where along the shaft ("shoulder at 520 mm"; ``x`` [m]), its
    position kept for the reader's units (:mod:`flyopt.said`)."""
    return said(f"{what} at {{x}}", x=(x, "length", f"{x * 1e3:.0f} mm"))


def bearing_place(label: str, x: float) -> str:
    """Where a bearing's slope is checked ("at bearing A (60 mm)"; ``x`` [m]), its position kept likewise."""
    return said(f"at bearing {label} ({{x}})", x=(x, "length", f"{x * 1e3:.0f} mm"))


def _sections(layout: ShaftLayout) -> list[tuple[float, str, str | None, float]]:
    """(x, name, notch kind or None, d) of every section the strength is checked at."""
    out: list[tuple[float, str, str | None, float]] = [
        (layout.wheel_at, "keyseat at the wheel seat", "keyseat", layout.diameter_at(layout.wheel_at))
    ]
    for end, d0, d1 in zip(layout.steps[:-1], layout.diameters[:-1], layout.diameters[1:]):
        if d0 != d1:
            out.append((end, section_name("shoulder", end), "shoulder", min(d0, d1)))
    for x, name in [(b, "bearing") for b in layout.bearings] + [(load.position, "load") for load in layout.loads]:
        out.append((x, section_name(name, x), None, layout.diameter_at(x)))
    return out


def check_shaft(
    layout: ShaftLayout,
    material: Material,
    *,
    wheel_mass: float,
    wheel_inertia: float,
    wheel_width: float = 0.0,
    omega_mean: float,
    delta: float,
    torque_curve: Sequence[float] | np.ndarray,
    excitation: TorqueOrders | None = None,
    other_inertia: float = 0.0,
    speed_ratio: float = 1.0,
    materials: Mapping[str, Material] | None = None,
    key: KeySeat | None = None,
) -> ShaftCheck:
    """Check a described shaft carrying a wheel over the cycle.

    Parameters
    ----------
    layout : ShaftLayout
        The shaft as a part (its own material's name is resolved to ``material`` by the caller).
    material : Material
        The shaft's material: E, density, Poisson's ratio and S_ut, S_y at the section (t = d).
    wheel_mass, wheel_inertia : float
        m [kg] and J [kg*m^2] of the wheel about its axis.
    wheel_width : float
        Its axial width b [m], for the diametral inertia I_d = J/2 + m b^2/12 (a ring or a disc).
    omega_mean : float
        The shaft's mean speed [rad/s].
    delta : float
        The cycle's coefficient of fluctuation; the running range is omega_mean (1 -/+ delta/2).
    torque_curve : array
        The torque the wheel exchanges with this shaft over the cycle [N*m], with its sign
        (:func:`flyopt.sizing.peak_torque.flywheel_torque_curve`).
    excitation : TorqueOrders, optional
        The net torque's orders per revolution of this shaft; None: no torsional check. With a train (the
        layout's, or the two-inertia one ``other_inertia`` makes) it also gives the torque at the seat the
        fatigue check uses: the forced response's (:func:`~flyopt.design.shaft.train.seat_torque`), not the
        rigid body's ``torque_curve``.
    other_inertia : float
        The inertia already on the shaft [kg*m^2]: without a ``train`` in the layout, the second inertia of
        the two-inertia train at ``torque_at`` (:func:`~flyopt.design.shaft.train.default_train`; 0: no elastic
        torsional mode).
    speed_ratio : float
        The shaft's omega / omega_reference: the train's elements are reflected to this shaft by their
        ratios relative to it.
    materials : mapping of str to Material, optional
        The materials a train's shaft pieces name, other than the shaft's own.
    key : KeySeat, optional
        The key the wheel was designed with. Where the train is modelled (the seat's torque is the forced
        response's) it adds a limit "key": that key checked by :func:`flyopt.design.key.check_key` at the peak
        of the torque the wheel's own inertia takes, J_wheel theta''_wheel
        (:func:`~flyopt.design.shaft.train.key_torque`, which the design sized it at); without a train the
        design already checked it at the rigid body's peak, and no limit is added.

    Returns
    -------
    ShaftCheck
    """
    weight = wheel_mass * GRAVITY
    omega_max = omega_mean * (1.0 + 0.5 * delta)
    grade = BALANCE_GRADE if layout.balance_grade is None else layout.balance_grade * 1e3  # [mm/s]
    unbalance = permissible_unbalance(wheel_mass, omega_max, grade).u_per * omega_max**2  # U_per Omega^2
    torque = np.asarray(torque_curve, dtype=float)
    t_max, t_min = (float(torque.max()), float(torque.min())) if torque.size else (0.0, 0.0)
    t_mean, t_alt = 0.5 * (t_max + t_min), 0.5 * (t_max - t_min)
    speed_range = running_range_rpm(omega_mean, delta)
    torsional = response = seat = key_limit = keyed = None
    built = shaft_train(
        layout,
        material,
        wheel_inertia=wheel_inertia,
        speed_ratio=speed_ratio,
        other_inertia=other_inertia,
        materials=materials,
    )
    if excitation is not None and built is not None:
        torsional = torsional_check(built.model, excitation, speed_range, significant=SIGNIFICANT_ORDER)
        response = (built, excitation, rad_s_to_rpm(omega_mean), layout.damping_ratio)
        # the one rule of the alternating torque at the seat: the forced response's, where the train is modelled
        seat = seat_torque(built, excitation, rad_s_to_rpm(omega_mean), layout.damping_ratio, torsional.modes)
        # the one torque of the key, the design's too (flyopt.design.shaft.cycle.key_torque_on)
        keyed = key_torque(built, excitation, rad_s_to_rpm(omega_mean), layout.damping_ratio, torsional.modes)
        if keyed is not None and key is not None:
            key_limit = _key_limit(key, keyed.peak)
    t_alt_rigid = t_alt
    if seat is not None:
        t_mean, t_alt = seat.mean, seat.alternating
    e = float(material.elastic_modulus or 0.0)
    beam = SteppedShaft(layout.steps, layout.diameters, e, layout.bearings, density=material.density)

    sections = _sections(layout)
    xs = np.array([s[0] for s in sections])
    grid = np.unique(np.concatenate((np.linspace(0.0, layout.length, DIAGRAM_POINTS), xs)))
    px, fy, fz = _plane_loads(layout, weight)
    # the stationary loads in two planes and the unbalance at the wheel (px[0]), rotating: three cases, one grid
    fu = np.zeros_like(fy)
    fu[0] = unbalance
    line_y, line_z, line_u = elastic_lines(beam, px, np.stack((fy, fz, fu)), at=grid)
    ma_grid = np.hypot(line_y.moment, line_z.moment)
    mm_grid = np.abs(line_u.moment)
    torque_on = carries_torque(layout, grid)

    checked = _checked_sections(layout, material, sections, grid, ma_grid, mm_grid, torque_on, t_alt, abs(t_mean))

    n_req = layout.safety_factor
    worst_f = min(checked, key=lambda s: s.fatigue)
    worst_y = min(checked, key=lambda s: s.yield_)
    limits = [
        ShaftLimit("fatigue", "at the " + worst_f.name, worst_f.fatigue, n_req, n_req / worst_f.fatigue, ""),
        ShaftLimit("yield", "at the " + worst_y.name, worst_y.yield_, n_req, n_req / worst_y.yield_, ""),
    ]
    for label, b in zip(("A", "B"), layout.bearings):
        i = int(np.argmin(np.abs(grid - b)))
        slope = math.hypot(line_y.slope[i], line_z.slope[i]) + abs(line_u.slope[i])
        limits.append(
            ShaftLimit(
                "slope",
                bearing_place(label, b),
                slope,
                layout.max_slope,
                slope / layout.max_slope,
                "rad",
            )
        )
    w = int(np.argmin(np.abs(grid - layout.wheel_at)))
    deflection = math.hypot(line_y.deflection[w], line_z.deflection[w]) + abs(line_u.deflection[w])
    if layout.max_deflection is not None:
        limits.append(
            ShaftLimit(
                "deflection", "at the wheel", deflection, layout.max_deflection, deflection / layout.max_deflection, "m"
            )
        )

    i_d = 0.5 * wheel_inertia + wheel_mass * wheel_width**2 / 12.0
    disc = Disc(layout.wheel_at, wheel_mass, i_d, wheel_inertia)
    found = critical_speeds(rotor_model(beam, [disc]), whirl="forward", modes=1)
    lateral = float(found[0]) if found.size else math.nan
    lateral_rpm = rad_s_to_rpm(lateral) if found.size else math.inf
    limits.append(
        ShaftLimit(
            "lateral",
            "first forward whirl",
            lateral_rpm,
            _band_edge(lateral_rpm, speed_range, layout.critical_margin),
            separation_utilisation(lateral_rpm, speed_range, layout.critical_margin),
            "rpm",
        )
    )

    if torsional is not None and torsional.critical:
        util = [separation_utilisation(c.speed_rpm, speed_range, layout.critical_margin) for c in torsional.critical]
        worst = torsional.critical[int(np.argmax(util))]
        limits.append(
            ShaftLimit(
                "torsional",
                f"mode {worst.mode} at order {worst.order:.4g}",
                worst.speed_rpm,
                _band_edge(worst.speed_rpm, speed_range, layout.critical_margin),
                max(util),
                "rpm",
            )
        )

    if key_limit is not None:
        limits.append(key_limit)

    plain = _plain_utilisation(
        layout, material, beam.diameter_at(grid), ma_grid, mm_grid, torque_on, t_alt, abs(t_mean)
    )
    diagram = {
        "x": grid,
        "moment_alternating": ma_grid,
        "moment_mean": mm_grid,
        "torque": np.where(torque_on, abs(t_mean) + t_alt, 0.0),
        "utilisation": plain,
    }
    return ShaftCheck(
        tuple(limits),
        tuple(checked),
        weight,
        unbalance,
        t_mean,
        t_alt,
        lateral,
        speed_range,
        torsional,
        diagram,
        response,
        t_alt_rigid,
        "rigid body" if seat is None else "forced response",
        math.nan if keyed is None else keyed.peak,
    )


def _key_limit(key: KeySeat, torque: float) -> ShaftLimit | None:
    """The key's limit at ``torque`` [N*m] by the design's own rule (:func:`flyopt.design.key.check_key`, its
    governing stress against its allowable); None at no torque."""
    if not torque > 0.0:
        return None
    found = din_key.check_key(torque, key.d, key.length, key.allowable_pressure, key.allowable_shear)
    pressure = found.governing == "pressure"
    value, allowed = (
        (found.pressure, float(found.allowable_pressure or math.nan))
        if pressure
        else (found.shear, found.allowable_shear)
    )
    what = (
        "bearing pressure"
        if pressure
        else "shear"
        if found.allowable_pressure is not None
        else "shear; bearing pressure not checked"
    )
    where = said(
        f"{found.key.size}, {{length}} long, at the wheel seat ({what})",
        length=(found.length, "length", f"{found.length * 1e3:g} mm"),
    )
    return ShaftLimit("key", where, value, allowed, value / allowed, "Pa", torque)


def _band_edge(critical_rpm: float, speed_range_rpm: tuple[float, float], margin: float) -> float:
    """The nearer edge of the band the critical speed must stay out of [rpm]: n_max (1 + m) or n_min (1 - m)."""
    low, high = speed_range_rpm
    return high * (1.0 + margin) if critical_rpm >= math.sqrt(low * high) else low * (1.0 - margin)


def _strengths_along(layout: ShaftLayout, material: Material, d: np.ndarray) -> tuple[np.ndarray, ...]:
    """S_ut, S_y and S_e [Pa] at each diameter (each distinct diameter's strengths read once)."""
    sut, sy, se = np.empty(d.size), np.empty(d.size), np.empty(d.size)
    for di in np.unique(d):
        at = d == di
        sut[at], sy[at], se[at] = section_strengths(material, float(di), layout.finish)
    return sut, sy, se


@functools.lru_cache(maxsize=1024)
def section_strengths(material: Material, diameter: float, finish: str) -> tuple[float, float, float]:
    """S_ut, S_y (:func:`~flyopt.design.shaft.strength.shaft_strengths`) and S_e
    (:func:`~flyopt.design.shaft.strength.endurance_limit`) [Pa] of one round section: pure functions of the
    material, the diameter and the finish, so a design's many wheels on one shaft read them once."""
    sut, sy = strength.shaft_strengths(material, diameter)
    return sut, sy, strength.endurance_limit(sut, diameter, finish).se


def _checked_sections(layout, material, sections, grid, ma_grid, mm_grid, torque_on, ta, tm) -> list[Section]:
    """Fatigue and yield factors of every checked section, the equations evaluated on arrays (one call each)."""
    index = np.array([int(np.argmin(np.abs(grid - s[0]))) for s in sections])
    d = np.array([s[3] for s in sections])
    sut, sy, se = _strengths_along(layout, material, d)
    factors = [
        (1.0, 1.0) if kind is None else notch_factors(kind, di, layout.fillet, u)
        for (_, _, kind, di), u in zip(sections, sut)
    ]
    kf, kfs = np.array([f[0] for f in factors]), np.array([f[1] for f in factors])
    on = torque_on[index]
    t_a, t_m = np.where(on, ta, 0.0), np.where(on, tm, 0.0)
    ma, mm = ma_grid[index], mm_grid[index]
    n_f = np.atleast_1d(
        strength.fatigue_safety_factor(d, ma, t_a, mm, t_m, kf=kf, kfs=kfs, se=se, sut=sut, criterion=CRITERION)
    )
    n_y = np.atleast_1d(strength.yield_safety_factor(d, ma, t_a, mm, t_m, sy=sy, kf=kf, kfs=kfs))
    return [
        Section(
            x,
            name,
            float(d[k]),
            float(kf[k]),
            float(kfs[k]),
            float(ma[k]),
            float(mm[k]),
            float(t_a[k]),
            float(t_m[k]),
            float(n_f[k]),
            float(n_y[k]),
        )
        for k, (x, name, _, _) in enumerate(sections)
    ]


def _plain_utilisation(layout, material, d, ma, mm, torque_on, ta, tm) -> np.ndarray:
    """Fatigue utilisation n_required / n_f of the plain (un-notched) section of diameter d along the shaft."""
    sut, _, se = _strengths_along(layout, material, d)
    t_a, t_m = np.where(torque_on, ta, 0.0), np.where(torque_on, tm, 0.0)
    n = strength.fatigue_safety_factor(d, ma, t_a, mm, t_m, kf=1.0, kfs=1.0, se=se, sut=sut, criterion=CRITERION)
    out: np.ndarray = layout.safety_factor / np.asarray(n)
    return out
