"""The textbook's flywheel for a machine of varying inertia: the crank effort at the mean speed.

The courses (e.g. Khurmi & Gupta, *Theory of Machines*, turning-moment
diagrams of engines) add the inertia torque of the reciprocating parts at the
mean speed to the gas torque and size the flywheel on a constant inertia. flyopt
sizes such a machine exactly (the energy-mass method, docs/flywheel-design.md,
section 6) and keeps this method to compare with the book.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from flyopt.cycle.indicator import EnergyIndicator, energy_indicator, required_inertia
from flyopt.cycle.torque import TorqueSum
from flyopt.machine.engine import InertiaTorque

if TYPE_CHECKING:  # annotations only
    from flyopt.machine.reduce import Machine


@dataclass(frozen=True)
class TextbookRequirement:
    """The flywheel of the textbook's method: the crank effort at the mean speed on a constant inertia.

    Attributes
    ----------
    j_required : float
        J_F = A_max/(ω_m² δ) − mean J_e [kg*m^2] (zero or negative: none needed).
    a_max : float
        A_max of the crank effort at the mean speed against the resisting torque [J].
    omega_mean, delta : float
        [rad/s], [-].
    j_machine_mean : float
        Cycle mean of J_e, the constant inertia the method puts in its place [kg*m^2].
    indicator : flyopt.cycle.indicator.EnergyIndicator
        Its energy indicator diagram.
    """

    j_required: float
    a_max: float
    omega_mean: float
    delta: float
    j_machine_mean: float
    indicator: EnergyIndicator


def textbook_requirement(
    machine: Machine, omega_mean: float | None = None, delta: float | None = None
) -> TextbookRequirement:
    """The flywheel the textbook's "inertia torque at the mean speed" method asks for.

    The textbook (e.g. Khurmi & Gupta, *Theory of Machines*, turning-moment
    diagrams of engines) adds to the gas torque the inertia torque of the
    reciprocating parts at the mean speed, −½ J_e'(φ) ω_m² here with exact
    kinematics, treats that crank effort as a torque curve on a constant
    inertia, and sizes the flywheel by the constant-inertia method
    (docs/flywheel-design.md, section 5) with the cycle mean of J_e in place
    of J_c, as flyopt does wherever it compares that method with a variable
    J_e. The exact answer is the energy–mass method (section 6), which keeps
    J_e(φ) varying; the difference is of second order in the fluctuation.

    Parameters
    ----------
    machine : flyopt.machine.reduce.Machine
    omega_mean : float, optional
        ω_m [rad/s]; default the machine's (the scene's) mean speed.
    delta : float, optional
        δ [-]; default the machine's.

    Returns
    -------
    TextbookRequirement
    """
    omega = machine.omega_mean if omega_mean is None else float(omega_mean)
    delta = machine.delta if delta is None else float(delta)

    def build() -> TextbookRequirement:
        balanced = machine.angle_only(omega)
        driving = balanced.driving
        if machine.variable_inertia:
            driving = TorqueSum([driving, InertiaTorque(machine.j_machine, omega)], "crank effort at the mean speed")
        indicator = energy_indicator(driving, balanced.resisting, machine.cycle_angle)
        j_mean = machine.j_mean()
        return TextbookRequirement(
            required_inertia(indicator.a_max, omega, delta, j_mean), indicator.a_max, omega, delta, j_mean, indicator
        )

    return machine.memo(("textbook", omega, delta), build)
