"""The balance of a flywheel: the ISO 21940-11 permissible residual unbalance.

:func:`permissible_unbalance` gives the residual unbalance a finished rigid
rotor may keep for a balance quality grade G = e_per Omega. Every argument and
result here is SI: kg, rad/s, m, kg*m (the grade in mm/s, as the standard
names it).

References
----------
.. [3] ISO 21940-11:2016 (formerly ISO 1940-1), Mechanical vibration -- Rotor
   balancing -- Part 11: Procedures and tolerances for rotors with rigid
   behaviour.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from flyopt.validate import positive

__all__ = ["BALANCE_GRADE", "PermissibleUnbalance", "permissible_unbalance", "unbalance"]

#: ISO 21940-11 balance quality grade of a flywheel [mm/s] (crankshaft drives and flywheels: G6.3).
BALANCE_GRADE = 6.3


class PermissibleUnbalance(NamedTuple):
    """ISO 21940-11 permissible residual unbalance of a rotor, SI."""

    e_per: float
    """Permissible specific unbalance (eccentricity of the centre of mass) [m]."""
    u_per: float
    """Permissible residual unbalance, e_per m [kg*m]."""


def permissible_unbalance(mass: float, omega_max: float, grade: float = BALANCE_GRADE) -> PermissibleUnbalance:
    """Permissible residual unbalance of a rigid rotor for a balance quality grade.

    Parameters
    ----------
    mass : float
        Rotor mass, m [kg].
    omega_max : float
        Maximum service angular speed, Omega [rad/s]; for a flywheel the
        highest speed of its shaft over the cycle.
    grade : float
        Balance quality grade G [mm/s]; default :data:`BALANCE_GRADE`, G 6.3, the grade whose
        examples in ISO 1940's table include flywheels (as reproduced by
        balancemaster.com, "ISO balancing grades").

    Returns
    -------
    PermissibleUnbalance
        (e_per [m], u_per [kg*m]).

    Raises
    ------
    ValueError
        If an argument is not a positive finite number.

    Notes
    -----
    ISO 21940-11 [3]_ defines the grade as the product of the permissible
    specific unbalance and the maximum service angular speed,
    G = e_per Omega, in mm/s; so e_per = G / Omega and U_per = e_per m. In SI,
    e_per = G 1e-3 / Omega [m]. In the standard's units,
    U_per [g*mm] = 1000 G m / Omega = 9549 G m / n with n in rev/min. U_per is
    for the whole rotor; the standard allocates it to the correction planes.

    Examples
    --------
    G 6.3 at 3000 rev/min (Omega = 314.16 rad/s), 100 kg:
    e_per = 20.05 um, U_per = 2.005e-3 kg*m (2005 g*mm).
    """
    mass = positive(mass, "mass [kg]")
    omega_max = positive(omega_max, "omega_max [rad/s]")
    grade = positive(grade, "grade [mm/s]")
    e_per, u_per = unbalance(mass, omega_max, grade)
    return PermissibleUnbalance(e_per=e_per, u_per=u_per)


def unbalance(mass: Any, omega_max: Any, grade: float = BALANCE_GRADE) -> tuple[Any, Any]:
    """(e_per [m], U_per [kg*m]) of :func:`permissible_unbalance`, unchecked, for floats or arrays.

    The formula itself, for callers whose arguments are already checked (arrays of designs).
    """
    e_per = grade * 1e-3 / omega_max
    return e_per, e_per * mass
