"""One operation, not a cycle: a load that comes once (a rivet, a single stroke) against a motor and a flywheel.

The courses' riveting machine (Khurmi & Gupta, example 16.21): the operation takes
the energy E over the time τ while the motor goes on giving its power P; the flywheel
gives up the difference, ΔE = E − P τ, so its speed falls from ω₁ to
ω₂ = √(ω₁² − 2 ΔE / J). After the operation the motor, no longer loaded, refills the
flywheel in t_r = ΔE / P, and it can sustain at most P / E operations a second (60 P / E a minute) (it must
supply each operation's whole energy; the shortest interval τ + t_r = E / P says the
same). docs/flywheel-design.md, section 16.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from flyopt.errors import SceneError


@dataclass(frozen=True)
class Operation:
    """A load that comes once (a scene's [operation]), SI.

    Attributes
    ----------
    energy : float
        The work of one operation E [J].
    duration : float
        The time τ it takes [s].
    motor_power : float
        The power P the motor gives throughout, loaded or not [W].
    """

    energy: float
    duration: float
    motor_power: float


@dataclass(frozen=True)
class OperationResult:
    """What one operation does to the speed, and how often the motor can repeat it (SI)."""

    operation: Operation
    inertia: float  # J at the reference shaft, machine and flywheel [kg*m^2]
    omega_before: float  # ω₁ [rad/s]
    omega_after: float  # ω₂ [rad/s]
    energy_from_motor: float  # P τ [J]
    energy_from_flywheel: float  # ΔE = E − P τ [J] (0 when the motor alone suffices)
    speed_drop: float  # (ω₁ − ω₂) / ω₁ [-]
    delta: float  # (ω₁ − ω₂) / ((ω₁ + ω₂)/2) [-]
    recovery_time: float  # t_r = ΔE / P [s]
    shortest_interval: float  # τ + t_r [s]
    operation_rate: float  # P / E, the most operations a second the motor sustains [1/s]
    delta_allowed: float | None = None
    holds: bool | None = None  # δ within machine.delta, where one is given

    def to_dict(self) -> dict[str, Any]:
        """The fields of ``flyopt solve --json`` for an [operation] (SI)."""
        out = {k: v for k, v in self.__dict__.items() if k != "operation"}
        out["energy"] = self.operation.energy
        out["duration"] = self.operation.duration
        out["motor_power"] = self.operation.motor_power
        return out


def one_operation(
    operation: Operation, inertia: float, omega_before: float, delta_allowed: float | None = None
) -> OperationResult:
    """The speed after one operation and the rate the motor sustains (see the module).

    Raises
    ------
    SceneError
        Field ``flywheel``: the flywheel's kinetic energy above standstill, ½ J ω₁², is less than
        what the operation takes from it (the machine would stop before the operation ends).
    """
    from_motor = operation.motor_power * operation.duration
    from_flywheel = max(operation.energy - from_motor, 0.0)
    kinetic = 0.5 * inertia * omega_before * omega_before
    if from_flywheel >= kinetic:
        raise SceneError(
            "flywheel",
            f"holds {kinetic:.6g} J at the speed before the operation, and the operation takes "
            f"{from_flywheel:.6g} J from it (E − P τ): the machine would stop; a larger flywheel or motor is needed",
        )
    omega_after = math.sqrt(omega_before * omega_before - 2.0 * from_flywheel / inertia)
    drop = (omega_before - omega_after) / omega_before
    delta = 2.0 * (omega_before - omega_after) / (omega_before + omega_after)
    recovery = from_flywheel / operation.motor_power
    return OperationResult(
        operation=operation,
        inertia=inertia,
        omega_before=omega_before,
        omega_after=omega_after,
        energy_from_motor=from_motor,
        energy_from_flywheel=from_flywheel,
        speed_drop=drop,
        delta=delta,
        recovery_time=recovery,
        shortest_interval=operation.duration + recovery,
        operation_rate=operation.motor_power / operation.energy,
        delta_allowed=delta_allowed,
        holds=None if delta_allowed is None else delta <= delta_allowed,
    )
