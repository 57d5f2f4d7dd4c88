"""The equivalents of a mechanism at one position (docs/flywheel-design.md, section 17).

The courses' question (seed 000, calculations 6 and 7; every chapter on the
equivalent member): at one position of the mechanism, reduce its members to
one shaft, with no speed and no cycle: the velocity ratios of each member,
the equivalent inertia and the equivalent moment of its forces and torques.
flyopt answers it with the cycle's own reduction (:mod:`flyopt.machine.mechanism`),
evaluated at the reference shaft's angle φ:

    J_e(φ) = J_c + Σ_i [ J_Si (ω_i/ω)² + m_i (v_Si/ω)² ],
    M_e(φ) = Σ_i [ T_i (ω_i/ω) + F_i (v_i/ω) cos α_i ]      (positive drives).

The books also reduce to another member k (the "equivalent member"), by the
same kinetic energy and the same power:

- a member that turns at that position (|ω_k/ω| > :data:`STILL`): J_k = J_e (ω/ω_k)² and
  M_k = M_e |ω/ω_k|, positive driving (M_k ω_k has the sign of M_e ω); at
  a point at r from its axis the equivalent force P = M_k / r and mass J_k / r²;
- a member that only translates there (ω_k = 0, v_k ≠ 0: a slider; a lever at its dead point): the
  equivalent mass m_k = J_e (ω/v_k)² and force F_k = M_e |ω/v_k| at its centre.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from flyopt.errors import SceneError, shorten
from flyopt.machine.kinematics import GearTrain, SliderCrank
from flyopt.machine.linkages import Linkage
from flyopt.machine.mechanism import Member, equivalent_inertia, equivalent_torque

TWO_PI = 2.0 * math.pi

#: |ω_k/ω| (and v_k/ω against the members' largest) at or below which a member stands still at the
#: position: a dead point's ratio is round-off (cos 120° is not −1/2 in floating point).
STILL = 1e-12

#: The sense of the equivalent moment: it drives the shaft (acts in its sense of rotation) or resists it.
SENSES = ("driving", "resisting", "none")


@dataclass(frozen=True)
class MechanismPosition:
    """What a scene's [position] beside [[member]]s asks (SI).

    Attributes
    ----------
    angle : float or None
        φ of the reference shaft [rad], within the cycle; None when nothing
        varies with the angle (the equivalents are then those at any angle).
    input_angle : float or None
        The mechanism's input angle ψ as the scene gave it (``angle`` is then
        the φ that puts the input there), or None.
    reduce_to : str or None
        The member the equivalents are also reduced to.
    force_at : float or None
        r [m]: the equivalent force at a point this far from ``reduce_to``'s axis.
    """

    angle: float | None
    input_angle: float | None = None
    reduce_to: str | None = None
    force_at: float | None = None


@dataclass(frozen=True)
class MemberAt:
    """One member at the position: its velocity ratios and its parts of J_e and M_e.

    Attributes
    ----------
    name : str
    velocity_ratio : float
        |v_S|/ω of its centre of mass [m/rad].
    angular_ratio : float
        ω_k/ω [-] (signed: negative turns against the reference shaft).
    inertia_share, torque_share : float
        J_S (ω_k/ω)² + m (v_S/ω)² [kg*m^2] and its load's equivalent moment [N*m] (+ drives).
    """

    name: str
    velocity_ratio: float
    angular_ratio: float
    inertia_share: float
    torque_share: float


@dataclass(frozen=True)
class ReducedTo:
    """The equivalents reduced to another member (the books' equivalent member), SI.

    ``turns``: the member turns at the position, and ``equivalent_inertia`` [kg*m^2] and
    ``equivalent_moment`` [N*m] are about its axis; with ``radius`` (force_at),
    ``equivalent_force`` and ``equivalent_mass`` are at that point. Otherwise it only
    translates, and ``equivalent_mass`` [kg] and ``equivalent_force`` [N] are at its centre.
    Moments and forces are positive driving.
    """

    member: str
    velocity_ratio: float
    angular_ratio: float
    turns: bool
    equivalent_inertia: float | None
    equivalent_moment: float | None
    radius: float | None
    equivalent_force: float | None
    equivalent_mass: float | None


@dataclass(frozen=True)
class PositionEquivalents:
    """The equivalents at the position (:func:`equivalents_at`), SI.

    Attributes
    ----------
    position : MechanismPosition
    angle : float
        φ where they were evaluated [rad].
    input_angle : float or None
        The mechanism's input angle ψ at φ, in [0, 2π) [rad] (None for a gear train or no mechanism).
    members : tuple of MemberAt
    j_constant : float
        J_c, the inertia at the reference shaft that is not a member's (machine.inertia, [[shaft]]).
    equivalent_inertia, equivalent_moment : float
        J_e [kg*m^2] and M_e [N*m] at the reference shaft (M_e the right limit where a load steps).
    sense : str
        "driving", "resisting" or "none" (:data:`SENSES`).
    reduced : ReducedTo or None
    """

    position: MechanismPosition
    angle: float
    input_angle: float | None
    members: tuple[MemberAt, ...]
    j_constant: float
    equivalent_inertia: float
    equivalent_moment: float
    sense: str
    reduced: ReducedTo | None

    def to_dict(self) -> dict[str, Any]:
        """The fields of ``flyopt solve --json`` for a [position] beside [[member]]s (SI)."""
        p = self.position
        return {
            "form": "equivalents",
            "angle": self.angle,
            "input_angle": self.input_angle,
            "j_constant": self.j_constant,
            "equivalent_inertia": self.equivalent_inertia,
            "equivalent_moment": self.equivalent_moment,
            "sense": self.sense,
            "members": [dict(m.__dict__) for m in self.members],
            "reduce_to": p.reduce_to,
            "reduced": None if self.reduced is None else dict(self.reduced.__dict__),
        }


def varies_with_angle(members: Sequence[Member]) -> bool:
    """Whether the members' J_e or loads change with the angle (else a position needs no angle)."""
    loads_constant = all(
        isinstance(load, (int, float)) or load is None for m in members for load in (m.force, m.torque)
    )
    return not (all(m.inertia_is_constant for m in members) and loads_constant)


def input_angle(mechanism: object, phi: float) -> float | None:
    """The mechanism's input angle ψ in [0, 2π) at the reference shaft's φ [rad] (None: it has none)."""
    if isinstance(mechanism, Linkage):
        return float(mechanism.own_angle(phi)) % TWO_PI
    if isinstance(mechanism, SliderCrank):
        return (phi - mechanism.phase) % TWO_PI
    return None


def reference_angle(mechanism: object, psi: float) -> float:
    """The first φ ≥ 0 of the reference shaft at which the mechanism's input stands at ψ [rad].

    The inverse of ψ = speed_ratio·φ − phase (:meth:`flyopt.machine.linkages.Linkage.own_angle`; a
    slider-crank's speed ratio is 1), modulo the mechanism's period.

    Raises
    ------
    ValueError
        For a gear train or no mechanism: they have no input angle.
    """
    if isinstance(mechanism, Linkage):
        return ((psi + mechanism.phase) / mechanism.speed_ratio) % mechanism.period
    if isinstance(mechanism, SliderCrank):
        return (psi + mechanism.phase) % TWO_PI
    what = "a gear train" if isinstance(mechanism, GearTrain) else "no [mechanism]"
    raise ValueError(f"{what} has no input angle (its ratios do not vary with it)")


def equivalents_at(
    position: MechanismPosition, members: Sequence[Member], j_constant: float = 0.0, mechanism: object = None
) -> PositionEquivalents:
    """The members reduced to the reference shaft at ``position`` and, if it asks, to another member.

    Parameters
    ----------
    position : MechanismPosition
    members : sequence of Member
    j_constant : float
        J_c at the reference shaft [kg*m^2].
    mechanism : SliderCrank, GearTrain, Linkage or None
        The scene's [mechanism], for its input angle ψ at φ.

    Raises
    ------
    SceneError
        ``position.angle`` where the members' ratios are not finite there (the mechanism cannot be
        assembled), ``position.reduce_to`` for a name that is no member or a member that stands still,
        ``position.force_at`` for a member that does not turn.
    """
    phi = 0.0 if position.angle is None else float(position.angle)
    at = np.array(phi)
    inertia, torque = equivalent_inertia(members, j_constant), equivalent_torque(members)
    rows = []
    with np.errstate(over="ignore", invalid="ignore"):  # a ratio that overflows is refused just below, in one line
        j_e, m_e = float(inertia(at)), float(torque(at))
        j_parts, m_parts = inertia.contributions(at), torque.contributions(at)
        for member in members:
            v, w = member.ratios(at)
            rows.append(
                MemberAt(member.name, _size(v), float(w), float(j_parts[member.name]), float(m_parts[member.name]))
            )
    numbers = [j_e, m_e, *(x for r in rows for x in (r.velocity_ratio, r.angular_ratio))]
    if not all(math.isfinite(x) for x in numbers):
        raise SceneError(
            "position.angle",
            f"the mechanism cannot be assembled at φ = {math.degrees(phi):.6g} deg (its velocity ratios are not finite)",
        )
    sense = "driving" if m_e > 0 else "resisting" if m_e < 0 else "none"
    reduced = None if position.reduce_to is None else _reduce(position, rows, j_e, m_e)
    return PositionEquivalents(
        position, phi, input_angle(mechanism, phi), tuple(rows), float(j_constant), j_e, m_e, sense, reduced
    )


def _size(v: Any) -> float:
    """|v| of a scalar or planar velocity ratio."""
    return math.hypot(float(v[0]), float(v[1])) if isinstance(v, tuple) else abs(float(v))


def _reduce(position: MechanismPosition, rows: Sequence[MemberAt], j_e: float, m_e: float) -> ReducedTo:
    """J_e and M_e reduced to the member ``position.reduce_to`` by equal kinetic energy and power."""
    name = position.reduce_to
    row = next((r for r in rows if r.name == name), None)
    if row is None:
        names = ", ".join(repr(r.name) for r in rows)
        raise SceneError("position.reduce_to", f"{shorten(name)} is not a [[member]] (the members: {names})")
    w, v = row.angular_ratio, row.velocity_ratio
    turns = abs(w) > STILL  # a lever at its limit position: ω_k/ω is round-off there, not a ratio
    moves = v > STILL * max(r.velocity_ratio for r in rows)
    if turns:
        j_k, m_k = j_e / (w * w), m_e / abs(w)
        r = position.force_at
        force = None if r is None else m_k / r
        mass = None if r is None else j_k / (r * r)
        return ReducedTo(row.name, v, w, True, j_k, m_k, r, force, mass)
    if position.force_at is not None:
        raise SceneError(
            "position.force_at",
            f"member {shorten(name)} does not turn at this position (ω/ω_1 = 0): its equivalent force is at its "
            "centre already (leave force_at out)",
        )
    if not moves:
        raise SceneError(
            "position.reduce_to",
            f"member {shorten(name)} stands still at this position (ω/ω_1 = 0 and v/ω_1 = 0): nothing can be reduced to it",
        )
    return ReducedTo(row.name, v, w, False, None, None, None, m_e / v, j_e / (v * v))
