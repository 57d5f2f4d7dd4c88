"""Flywheel geometry: mass, moment of inertia and rim speed.

Pure formulas. Every function uses only arithmetic, so it works unchanged on
floats, numpy arrays and CasADi ``SX``/``MX`` expressions; none checks its
arguments (the callers that take user input do).

Nomenclature (SI)
-----------------
d_mean   mean rim diameter D_m [m]
h        radial thickness of the rim H [m]
b        axial width B [m]
d_outer  outer diameter D_1 = D_m + H [m]
d_inner  inner diameter D_2 = D_m - H [m]
density  rho [kg/m^3]
mass     m [kg]
omega    angular speed of the shaft that carries the flywheel [rad/s]

Models
------
thin_rim   J = m D_m^2 / 4                      (the textbook model)
rim        J = m (D_1^2 + D_2^2) / 8 = m (D_m^2 + H^2) / 4   (exact annulus)
disc       J = m D^2 / 8,  m = pi D^2 B rho / 4
and for both rim models m = pi D_m H B rho. A disc is the annulus with
D_2 = 0, i.e. D_m = H = D / 2.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 9 and 10.
"""

from __future__ import annotations

import math
from typing import Any

from flyopt.names import Geometry

# The functions here take floats, numpy arrays and CasADi symbols alike (one formula for
# the closed forms, the checks and the NLPs): their arguments and results are typed Any.

__all__ = [
    "GEOMETRIES",
    "BARE",
    "WHEELS",
    "rim_mass",
    "rim_inertia",
    "thin_rim_inertia",
    "disc_mass",
    "disc_inertia",
    "outer_diameter",
    "inner_diameter",
    "rim_speed",
    "outer_diameter_for_rim_speed",
    "hoop_stress",
    "wheel_inertia",
]

#: The bare wheels of the textbook: one body, sized by a closed form where it is exact.
BARE: dict[str, str] = {
    Geometry.THIN_RIM: "thin rim, J = m D_m^2/4 (textbook model; slightly low, errs safe)",
    Geometry.RIM: "exact annulus, J = m (D_m^2 + H^2)/4",
    Geometry.DISC: "solid disc, J = m D^2/8, m = pi D^2 B rho/4 (an annulus when it has a bore)",
}
#: Whole wheels: a rim carried on a web or on arms, with a hub on the shaft
#: (flyopt.design.wheel holds their parts).
WHEELS: dict[str, str] = {
    Geometry.RIM_WEB: "rim, web and hub: a stepped disc, every part counted in J and mass",
    Geometry.RIM_ARMS: "rim on n elliptical arms and a hub, every part counted in J and mass",
}
#: Geometry model names understood by flyopt, with their inertia formula.
GEOMETRIES = {**BARE, **WHEELS}


def rim_mass(d_mean: Any, h: Any, b: Any, density: Any) -> Any:
    """Mass of a rim (annulus).

    Parameters
    ----------
    d_mean : float or array or casadi expression
        Mean diameter D_m [m].
    h : float or array or casadi expression
        Radial thickness H [m].
    b : float or array or casadi expression
        Axial width B [m].
    density : float or array or casadi expression
        Density rho [kg/m^3].

    Returns
    -------
    mass : same type as the inputs
        m = pi D_m H B rho [kg].

    References
    ----------
    .. [1] flyopt domain notes, docs/flywheel-design.md, section 9.
    """
    return math.pi * d_mean * h * b * density


def rim_inertia(mass: Any, d_mean: Any, h: Any) -> Any:
    """Moment of inertia of a rim, exact annulus.

    Parameters
    ----------
    mass : float or array or casadi expression
        Rim mass m [kg].
    d_mean : float or array or casadi expression
        Mean diameter D_m [m].
    h : float or array or casadi expression
        Radial thickness H [m].

    Returns
    -------
    j : same type as the inputs
        J = m (D_1^2 + D_2^2)/8 = m (D_m^2 + H^2)/4 [kg*m^2].

    References
    ----------
    .. [1] flyopt domain notes, docs/flywheel-design.md, section 9.
    """
    return mass * (d_mean * d_mean + h * h) / 4.0


def thin_rim_inertia(mass: Any, d_mean: Any) -> Any:
    """Moment of inertia of a rim in the thin-rim approximation.

    Parameters
    ----------
    mass : float or array or casadi expression
        Rim mass m [kg].
    d_mean : float or array or casadi expression
        Mean diameter D_m [m].

    Returns
    -------
    j : same type as the inputs
        J = m D_m^2 / 4 [kg*m^2]; below the exact annulus value by
        m H^2/4, so neglecting it (and the hub and arms) errs on the safe side.

    References
    ----------
    .. [1] flyopt domain notes, docs/flywheel-design.md, section 9.
    """
    return mass * d_mean * d_mean / 4.0


def disc_mass(d: Any, b: Any, density: Any) -> Any:
    """Mass of a solid disc.

    Parameters
    ----------
    d : float or array or casadi expression
        Diameter D [m].
    b : float or array or casadi expression
        Axial width B [m].
    density : float or array or casadi expression
        Density rho [kg/m^3].

    Returns
    -------
    mass : same type as the inputs
        m = pi D^2 B rho / 4 [kg].
    """
    return math.pi * d * d * b * density / 4.0


def disc_inertia(mass: Any, d: Any) -> Any:
    """Moment of inertia of a solid disc.

    Parameters
    ----------
    mass : float or array or casadi expression
        Disc mass m [kg].
    d : float or array or casadi expression
        Diameter D [m].

    Returns
    -------
    j : same type as the inputs
        J = m D^2 / 8 [kg*m^2].
    """
    return mass * d * d / 8.0


def outer_diameter(d_mean: Any, h: Any) -> Any:
    """Outer diameter of a rim, D_1 = D_m + H [m]."""
    return d_mean + h


def inner_diameter(d_mean: Any, h: Any) -> Any:
    """Inner diameter of a rim, D_2 = D_m - H [m] (a rim needs D_2 > 0)."""
    return d_mean - h


def rim_speed(omega: Any, d_outer: Any) -> Any:
    """Peripheral speed at the outer diameter.

    Parameters
    ----------
    omega : float or array or casadi expression
        Angular speed of the shaft that carries the flywheel [rad/s].
    d_outer : float or array or casadi expression
        Outer diameter D_1 [m].

    Returns
    -------
    v : same type as the inputs
        v = omega D_1 / 2 [m/s].
    """
    return omega * d_outer / 2.0


def outer_diameter_for_rim_speed(max_rim_speed: Any, omega: Any) -> Any:
    """Largest outer diameter a rim speed limit allows, D_1 = 2 v_max / omega [m].

    Parameters
    ----------
    max_rim_speed : float or array or casadi expression
        Safe rim speed v_max [m/s].
    omega : float or array or casadi expression
        Angular speed of the shaft that carries the flywheel [rad/s].
    """
    return 2.0 * max_rim_speed / omega


def hoop_stress(density: Any, rim_speed: Any) -> Any:
    """Hoop stress of a thin rotating ring, sigma = rho v^2 [Pa].

    Parameters
    ----------
    density : float or array or casadi expression
        Density rho [kg/m^3].
    rim_speed : float or array or casadi expression
        Peripheral speed v [m/s].

    References
    ----------
    .. [1] flyopt domain notes, docs/flywheel-design.md, section 10.
    """
    return density * rim_speed * rim_speed


def wheel_inertia(geometry_name: str, density: Any, d_mean: Any, h: Any, b: Any) -> Any:
    """Inertia of a wheel of one of the GEOMETRIES from its dimensions [kg*m^2].

    Parameters
    ----------
    geometry_name : {"rim", "thin_rim", "disc"}
    density : float or ndarray
        rho [kg/m^3].
    d_mean, h, b : float or ndarray
        Mean diameter, radial thickness and axial width [m]; for a disc
        d_mean = h = D/2 (the convention of flyopt.design.result.Candidate).

    Returns
    -------
    float or ndarray
        J on the wheel's own shaft [kg*m^2].
    """
    if geometry_name == Geometry.DISC:
        d = 2.0 * d_mean
        return disc_inertia(disc_mass(d, b, density), d)
    mass = rim_mass(d_mean, h, b, density)
    if geometry_name == Geometry.THIN_RIM:
        return thin_rim_inertia(mass, d_mean)
    return rim_inertia(mass, d_mean, h)
