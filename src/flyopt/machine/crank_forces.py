"""Forces in a slider-crank engine at one crank position (docs/flywheel-design.md, section 17).

The courses' question (Khurmi & Gupta, Theory of Machines, ch. 15): at the crank angle θ from
the inner dead centre, with the net gas pressure on the piston and the reciprocating mass,
find the piston effort, the force in the connecting rod, the thrust on the cylinder walls, the
tangential and radial forces on the crank pin and the turning moment on the crankshaft.

With n = l/r and the rod's obliquity β (sin β = sin θ / n), exactly:

- the piston's distance from the inner dead centre x = r [(1 − cos θ) + (n − √(n² − sin² θ))],
  its velocity v = ω r (sin θ + sin 2θ / (2 √(n² − sin² θ))) and acceleration
  a = ω² r (cos θ + (n² cos 2θ + sin⁴ θ) / (n² − sin² θ)^{3/2}) (towards the crank positive;
  the courses' a ≈ ω² r (cos θ + cos 2θ / n) drops the higher harmonics);
- the gas force F_L = p π d²/4, the inertia force F_I = m_R a, the piston effort
  F_P = F_L − F_I (+ m_R g for a vertical engine with its cylinder above the crank: the weight
  acts towards the crank on either stroke), the rod force F_Q = F_P / cos β, the thrust F_N = F_P tan β, on the crank pin
  F_T = F_Q sin(θ + β) and F_R = F_Q cos(θ + β), and the turning moment T = F_T r.

The turning moment also follows from the power balance T ω = F_P v (no friction), which the
tests use as an independent check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from flyopt.units import G_STANDARD

ORIENTATIONS = ("horizontal", "vertical")


@dataclass(frozen=True)
class CrankPosition:
    """A slider-crank engine at one crank position (a scene's [position]), SI.

    Attributes
    ----------
    angle : float
        θ from the inner dead centre (the piston farthest from the crankshaft) [rad].
    crank, rod : float
        r and l [m], l > r.
    bore : float or None
        d [m]; with ``pressure`` gives the gas force.
    pressure : float
        Net gas pressure on the piston [Pa] (the courses' "net load": the difference across it).
    gas_force : float or None
        The gas force itself [N], in place of bore and pressure.
    reciprocating_mass : float
        m_R [kg].
    orientation : {"horizontal", "vertical"}
        A vertical engine (cylinder above the crank) adds the reciprocating parts' weight.
    """

    angle: float
    crank: float
    rod: float
    reciprocating_mass: float
    pressure: float = 0.0
    bore: float | None = None
    gas_force: float | None = None
    orientation: str = "horizontal"


@dataclass(frozen=True)
class CrankForces:
    """The forces at the position (all SI; + towards the crank along the line of stroke)."""

    position: CrankPosition
    omega: float
    obliquity: float
    displacement: float
    velocity: float
    acceleration: float
    gas_force: float
    inertia_force: float
    weight: float
    piston_effort: float
    rod_force: float
    thrust: float
    tangential_force: float
    radial_force: float
    turning_moment: float

    def to_dict(self) -> dict[str, Any]:
        """The fields of ``flyopt solve --json`` for a [position] (SI)."""
        out = {k: v for k, v in self.__dict__.items() if k != "position"}
        p = self.position
        out.update(
            angle=p.angle,
            crank=p.crank,
            rod=p.rod,
            bore=p.bore,
            pressure=p.pressure if p.gas_force is None else None,
            reciprocating_mass=p.reciprocating_mass,
            orientation=p.orientation,
        )
        return out


def crank_forces(position: CrankPosition, omega: float) -> CrankForces:
    """The slider-crank's kinematics and forces at ``position`` turning at ``omega`` [rad/s] (see the module)."""
    theta, r, n = position.angle, position.crank, position.rod / position.crank
    s, c = math.sin(theta), math.cos(theta)
    root = math.sqrt(n * n - s * s)
    beta = math.asin(s / n)
    displacement = r * ((1.0 - c) + (n - root))
    velocity = omega * r * (s + s * c / root)
    acceleration = omega * omega * r * (c + (n * n * math.cos(2.0 * theta) + s**4) / root**3)
    if position.gas_force is not None:
        gas = position.gas_force
    else:
        bore = position.bore or 0.0
        gas = position.pressure * math.pi * bore * bore / 4.0
    inertia = position.reciprocating_mass * acceleration
    weight = position.reciprocating_mass * G_STANDARD if position.orientation == "vertical" else 0.0
    effort = gas - inertia + weight
    rod = effort / math.cos(beta)
    return CrankForces(
        position=position,
        omega=omega,
        obliquity=beta,
        displacement=displacement,
        velocity=velocity,
        acceleration=acceleration,
        gas_force=gas,
        inertia_force=inertia,
        weight=weight,
        piston_effort=effort,
        rod_force=rod,
        thrust=effort * math.tan(beta),
        tangential_force=rod * math.sin(theta + beta),
        radial_force=rod * math.cos(theta + beta),
        turning_moment=rod * math.sin(theta + beta) * r,
    )
