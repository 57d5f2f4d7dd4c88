"""An electric drive reduced to the motor shaft, in the electric-drive texts' terms (GD², n in rpm).

A motor drives a load through reduction stages, each with its speed ratio j_k (speed in over
speed out) and efficiency η_k, and a flywheel moment GD²_k on the shaft after it
(docs/flywheel-design.md, section 3 and section 18). Reduced to the motor shaft:

- the load torque T_L' = T_L / (j η), j = Π j_k, η = Π η_k, and the motor's output power
  P_L / η;
- the flywheel moment by equal kinetic energy, GD² = GD²_M + Σ GD²_k / (j_1 ⋯ j_k)², the one
  flyopt uses everywhere (no efficiency: kinetic energy has none);
- the texts' convention for the torque that accelerates the drive, with each stage's losses
  folded into the load-side terms, GD²_η = GD²_M + Σ GD²_k / ((j_1 ⋯ j_k)² η_1 ⋯ η_k): the
  motor also supplies the losses of the power that accelerates what lies beyond them;
- the accelerating torque T_a = GD²_η / (4 g) · dω/dt = GD²_η / 375 · dn/dt (the texts' 375 is
  4 g · 60 / 2π = 374.7 rounded, with g = 9.81 m/s² and n in rpm, dn/dt in rpm/s), and the motor's
  torque T_M = T_L' + T_a while it accelerates the loaded drive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from flyopt.units import inertia_from_gd2


@dataclass(frozen=True)
class Stage:
    """One reduction stage: its ratio (speed in / speed out), its efficiency, the GD² on the shaft after it [N*m²]."""

    ratio: float
    efficiency: float
    gd2: float


@dataclass(frozen=True)
class ElectricDrive:
    """A scene's [electric_drive], SI (speeds in rad/s, dω/dt in rad/s²)."""

    motor_speed: float  # the scene's machine.speed: the motor shaft is the reference
    motor_gd2: float
    stages: tuple[Stage, ...]
    load_torque: float
    acceleration: float | None = None  # dω/dt of the motor shaft [rad/s²]


@dataclass(frozen=True)
class ReducedDrive:
    """The drive reduced to the motor shaft (SI; GD² in N·m²)."""

    drive: ElectricDrive
    shaft_speeds: tuple[float, ...]  # ω after each stage [rad/s]
    load_speed: float
    total_ratio: float
    efficiency: float
    load_power: float
    motor_power: float
    load_torque_at_motor: float
    gd2_total: float  # equal kinetic energy
    gd2_with_losses: float  # the texts' convention for the accelerating torque
    inertia_total: float  # J = GD² / (4 g) [kg*m^2]
    inertia_with_losses: float
    accelerating_torque: float | None
    motor_torque: float | None

    def to_dict(self) -> dict[str, Any]:
        """The fields of ``flyopt solve --json`` for an [electric_drive] (SI)."""
        out = {k: v for k, v in self.__dict__.items() if k not in ("drive", "shaft_speeds")}
        out["shaft_speeds"] = list(self.shaft_speeds)
        d = self.drive
        out.update(
            motor_speed=d.motor_speed,
            motor_gd2=d.motor_gd2,
            load_torque=d.load_torque,
            motor_acceleration=d.acceleration,
            stages=[{"ratio": s.ratio, "efficiency": s.efficiency, "gd2": s.gd2} for s in d.stages],
        )
        return out


def reduce_drive(drive: ElectricDrive) -> ReducedDrive:
    """The drive at the motor shaft (see the module)."""
    ratio, efficiency = 1.0, 1.0
    gd2, gd2_eta = drive.motor_gd2, drive.motor_gd2
    speeds = []
    for stage in drive.stages:
        ratio *= stage.ratio
        efficiency *= stage.efficiency
        gd2 += stage.gd2 / ratio**2
        gd2_eta += stage.gd2 / (ratio**2 * efficiency)
        speeds.append(drive.motor_speed / ratio)
    load_speed = drive.motor_speed / ratio
    load_power = drive.load_torque * load_speed
    at_motor = drive.load_torque / (ratio * efficiency)
    accelerating = motor = None
    if drive.acceleration is not None:
        accelerating = inertia_from_gd2(gd2_eta) * drive.acceleration
        motor = at_motor + accelerating
    return ReducedDrive(
        drive=drive,
        shaft_speeds=tuple(speeds),
        load_speed=load_speed,
        total_ratio=ratio,
        efficiency=efficiency,
        load_power=load_power,
        motor_power=load_power / efficiency,
        load_torque_at_motor=at_motor,
        gd2_total=gd2,
        gd2_with_losses=gd2_eta,
        inertia_total=inertia_from_gd2(gd2),
        inertia_with_losses=inertia_from_gd2(gd2_eta),
        accelerating_torque=accelerating,
        motor_torque=motor,
    )
