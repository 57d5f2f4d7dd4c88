"""Stresses in a flywheel: stepped rotating discs, rims on arms, burst speed.

Pure arithmetic. Every formula uses only ``+ - * /`` and integer powers (and
:func:`sqrt`, written ``x ** 0.5``, where a square root cannot be avoided), so
the same code runs on Python floats, numpy arrays (broadcasting) and CasADi
``SX``/``MX`` expressions: the design NLP calls it with symbolic radii,
thicknesses and speeds. No function branches on a value that may be symbolic;
the only Python-level decisions are on arguments documented as plain Python
(the number of steps, the ``solid`` flag, the number of arms) and on the
structural zero ``c2 = 0.0`` of a solid centre. Only
:func:`max_stress_per_step`, the check, needs floats.

Sign conventions: tension is positive; ``bore_pressure`` is a pressure on the
bore (positive compresses it, sigma_r(r_0) = -bore_pressure); ``outer_traction``
is the radial stress applied at the outer edge (positive pulls outwards,
sigma_r(r_N) = outer_traction).

Nomenclature (SI)
-----------------
radii           edge radii r_0 < r_1 < ... < r_N of a stepped disc [m]
thickness       axial thickness t_i of step i, between r_i and r_{i+1} [m]
density         rho [kg/m^3]
poisson         Poisson's ratio nu [-]
elastic_modulus E [Pa]
omega           angular speed [rad/s]
c1, c2          constants of integration of a step [Pa], [Pa*m^2]
sr, st          radial and hoop (tangential) stress sigma_r, sigma_t [Pa]
mean_radius     mean rim radius R [m]
radial_thickness radial thickness of the rim H [m]
n_arms          number of arms n [-]
major, minor    axes of an arm's elliptical section, a (in the plane of
                rotation) and b_a (axial) [m]

The stepped disc (turbine-disc method)
--------------------------------------
In a step of constant thickness the plane-stress rotating-disc equations
(equilibrium d(r sigma_r)/dr - sigma_t + rho omega^2 r^2 = 0 and
compatibility of the strains of one radial displacement u) give [1]_

    sigma_r = c1 - c2 / r^2 - (3 + nu)/8 rho omega^2 r^2
    sigma_t = c1 + c2 / r^2 - (1 + 3 nu)/8 rho omega^2 r^2.

At a thickness step the radial displacement u = r/E (sigma_t - nu sigma_r)
and the radial force per radian t r sigma_r are continuous [2]_. With the one
unknown at the inner edge (sigma_t at a bore, c1 at a solid centre) every
constant is an affine function of it; the outer edge condition fixes it. This
is the transfer (propagation) method of turbine-disc design [2]_, and it needs
no matrix solve.

References
----------
.. [1] S. P. Timoshenko and J. N. Goodier, Theory of Elasticity, 3rd ed.,
   McGraw-Hill, 1970, article 32 "Rotating disks of uniform thickness"
   (the solid disc and the disc with a hole).
.. [2] S. P. Timoshenko, Strength of Materials, Part II, 3rd ed., Van
   Nostrand, 1956, "Rotating disks of variable thickness" (a disc divided
   into portions of constant thickness, with the radial force and the
   radial displacement continuous at each change of thickness); the same
   step-by-step scheme of turbine design in I. Malkin, "Design and
   calculation of steam-turbine disk wheels", Trans. ASME APM-56-8 (1934).
.. [3] R. G. Budynas and J. K. Nisbett, Shigley's Mechanical Engineering
   Design, 9th ed., McGraw-Hill, 2011, "Stresses in rotating rings".
.. [4] R. S. Khurmi and J. K. Gupta, A Textbook of Machine Design, S. Chand,
   2005, chapter 22 "Flywheel": "Stresses in a flywheel rim", "Stresses in
   flywheel arms" and "Design of flywheel arms".
"""

from __future__ import annotations

import math
import numbers
from collections import namedtuple
from collections.abc import Sequence
from typing import Any

import numpy as np

from flyopt.names import unknown

# The formulas here take floats, numpy arrays and CasADi expressions alike (the exact check, the
# sweeps and the wheel NLP share them): their arguments and results are typed Any.

__all__ = [
    "sqrt",
    "disc_coefficients",
    "disc_stresses",
    "disc_edge_stresses",
    "von_mises_squared",
    "von_mises",
    "principal_stresses",
    "radial_displacement",
    "mean_hoop_stress",
    "annulus_stresses",
    "annulus_bore_hoop_stress",
    "annulus_max_radial_stress",
    "annulus_max_radial_stress_radius",
    "annulus_mean_hoop_stress",
    "solid_disc_stresses",
    "solid_disc_centre_stress",
    "thin_ring_hoop_stress",
    "MEASURES",
    "StepMaximum",
    "max_stress_per_step",
    "rim_hoop_stress",
    "rim_bending_stress",
    "rim_combined_stress",
    "arm_section_area",
    "arm_section_modulus",
    "arm_bending_moment",
    "arm_bending_stress",
    "arm_centrifugal_force",
    "rim_segment_force",
    "arm_pull",
    "arm_stress",
    "arm_hub_traction",
    "burst_speed",
    "burst_speed_ductile",
    "burst_speed_brittle",
]


def sqrt(x: Any) -> Any:
    """Square root as ``x ** 0.5``: floats, numpy arrays and CasADi alike.

    Parameters
    ----------
    x : float or array or casadi expression
        A non-negative quantity (a negative Python float gives a complex
        number, a negative numpy value nan).
    """
    return x**0.5


def _is_structural_zero(value):
    """Whether ``value`` is the plain number 0 (never true of a symbol or an array)."""
    if type(value) is float or type(value) is int:  # the common case, without the ABC's isinstance (a tenth of a check)
        return value == 0
    return isinstance(value, numbers.Real) and value == 0


def _items(sequence):
    """The entries of a list/tuple, a numpy array (along axis 0) or a CasADi column."""
    if isinstance(sequence, (list, tuple)):
        return list(sequence)
    return [sequence[i] for i in range(sequence.shape[0])]


def _spin_factors(density, poisson, omega):
    """(alpha, beta) = ((3 + nu)/8, (1 + 3 nu)/8) * rho omega^2 [Pa/m^2]."""
    k = density * omega * omega
    return (3.0 + poisson) / 8.0 * k, (1.0 + 3.0 * poisson) / 8.0 * k


def disc_coefficients(
    radii: Sequence[Any],
    thickness: Sequence[Any],
    density: Any,
    poisson: Any,
    omega: Any,
    *,
    solid: bool = False,
    bore_pressure: Any = 0.0,
    outer_traction: Any = 0.0,
) -> list[tuple[Any, Any]]:
    """Constants (c1, c2) of every step of a stepped rotating disc.

    Parameters
    ----------
    radii : sequence of N + 1 floats, arrays or casadi expressions
        Edge radii r_0 < r_1 < ... < r_N [m] (a list, a tuple, a numpy array
        whose axis 0 runs over the edges, or a CasADi column). With
        ``solid=True`` r_0 must be 0 and is not used.
    thickness : sequence of N floats, arrays or casadi expressions
        Axial thickness t_i of step i, between r_i and r_{i+1} [m].
    density : float or array or casadi expression
        rho [kg/m^3].
    poisson : float or array or casadi expression
        Poisson's ratio nu [-].
    omega : float or array or casadi expression
        Angular speed [rad/s].
    solid : bool, keyword-only
        Plain Python: True for a solid centre (c2_0 = 0, no bore).
    bore_pressure : float or array or casadi expression, keyword-only
        Pressure on the bore [Pa]: sigma_r(r_0) = -bore_pressure (a shrink
        fit's contact pressure; 0, a free bore). Must be the plain 0 with
        ``solid=True``.
    outer_traction : float or array or casadi expression, keyword-only
        Radial stress applied at the outer edge [Pa]: sigma_r(r_N) =
        outer_traction; positive pulls outwards (a hub loaded by arms).

    Returns
    -------
    list of (c1, c2)
        One pair per step, in the order of ``thickness``: c1 [Pa] and c2
        [Pa*m^2] of the step's stress field (see :func:`disc_stresses`). A
        solid centre's c2 is the plain 0.0.

    Raises
    ------
    ValueError
        If the number of radii is not one more than the number of
        thicknesses, or if a solid centre is given a bore radius or a bore
        pressure that is a non-zero number.

    Notes
    -----
    In step i [1]_

        sigma_r = c1_i - c2_i / r^2 - alpha r^2,  alpha = (3 + nu)/8 rho omega^2
        sigma_t = c1_i + c2_i / r^2 - beta r^2,   beta = (1 + 3 nu)/8 rho omega^2,

    so from the stresses at one radius r of the step

        c1 = (sigma_r + sigma_t + (alpha + beta) r^2) / 2
        c2 = r^2 (sigma_t - sigma_r + (beta - alpha) r^2) / 2.

    At the interface r_i between steps i-1 and i [2]_ the radial force per
    radian and, the material being the same, the radial displacement
    u = r/E (sigma_t - nu sigma_r) are continuous:

        t_{i-1} sigma_r^- = t_i sigma_r^+
        sigma_t^+ = sigma_t^- + nu (sigma_r^+ - sigma_r^-).

    Starting from sigma_r(r_0) = -bore_pressure and the unknown
    x = sigma_t(r_0) (a solid centre: c1_0 = x, c2_0 = 0) every quantity is
    p + q x; carried to the outer edge, sigma_r(r_N) = P + Q x =
    outer_traction gives x = (outer_traction - P)/Q. Q depends on the
    geometry alone and is positive for a real disc.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    .. [2] Timoshenko, Strength of Materials, Part II, 3rd ed., 1956,
       "Rotating disks of variable thickness".
    """
    radii = _items(radii)
    thickness = _items(thickness)
    if len(radii) != len(thickness) + 1 or not thickness:
        raise ValueError(
            f"a stepped disc needs N + 1 edge radii for N >= 1 thicknesses; got {len(radii)} radii "
            f"and {len(thickness)} thicknesses"
        )
    if solid:
        if isinstance(radii[0], numbers.Real) and radii[0] != 0:
            raise ValueError(f"a solid centre starts at r_0 = 0; got r_0 = {radii[0]!r} (pass solid=False for a bore)")
        if not _is_structural_zero(bore_pressure):
            raise ValueError(f"a solid centre has no bore to press; got bore_pressure = {bore_pressure!r}")
    alpha, beta = _spin_factors(density, poisson, omega)

    # Affine quantities p + q x are pairs (p, q).
    def coefficients_at(r, sr, st):
        r2 = r * r
        c1 = ((sr[0] + st[0] + (alpha + beta) * r2) / 2.0, (sr[1] + st[1]) / 2.0)
        c2 = (r2 * (st[0] - sr[0] + (beta - alpha) * r2) / 2.0, r2 * (st[1] - sr[1]) / 2.0)
        return c1, c2

    def stresses_at(r, c1, c2):
        r2 = r * r
        if _is_structural_zero(c2[0]) and _is_structural_zero(c2[1]):
            sr = (c1[0] - alpha * r2, c1[1])
            st = (c1[0] - beta * r2, c1[1])
        else:
            sr = (c1[0] - c2[0] / r2 - alpha * r2, c1[1] - c2[1] / r2)
            st = (c1[0] + c2[0] / r2 - beta * r2, c1[1] + c2[1] / r2)
        return sr, st

    if solid:
        steps = [((0.0, 1.0), (0.0, 0.0))]
    else:
        steps = [coefficients_at(radii[0], (-bore_pressure, 0.0), (0.0, 1.0))]
    for i in range(1, len(thickness)):
        sr_minus, st_minus = stresses_at(radii[i], *steps[-1])
        ratio = thickness[i - 1] / thickness[i]
        sr_plus = (ratio * sr_minus[0], ratio * sr_minus[1])
        st_plus = (
            st_minus[0] + poisson * (sr_plus[0] - sr_minus[0]),
            st_minus[1] + poisson * (sr_plus[1] - sr_minus[1]),
        )
        steps.append(coefficients_at(radii[i], sr_plus, st_plus))
    sr_outer, _ = stresses_at(radii[-1], *steps[-1])
    x = (outer_traction - sr_outer[0]) / sr_outer[1]
    result = []
    for c1, c2 in steps:
        c2_value = 0.0 if (_is_structural_zero(c2[0]) and _is_structural_zero(c2[1])) else c2[0] + c2[1] * x
        result.append((c1[0] + c1[1] * x, c2_value))
    return result


def disc_stresses(coefficients: Any, density: Any, poisson: Any, omega: Any, r: Any) -> tuple[Any, Any]:
    """Radial and hoop stress at radius r of one step of a rotating disc.

    Parameters
    ----------
    coefficients : (c1, c2)
        The step's constants from :func:`disc_coefficients`, c1 [Pa] and c2
        [Pa*m^2]. A c2 that is the plain number 0 (a solid centre) drops the
        c2/r^2 terms, so r = 0 may be evaluated.
    density : float or array or casadi expression
        rho [kg/m^3].
    poisson : float or array or casadi expression
        Poisson's ratio nu [-].
    omega : float or array or casadi expression
        Angular speed [rad/s].
    r : float or array or casadi expression
        Radius in that step [m].

    Returns
    -------
    sr, st : same type as the inputs
        sigma_r and sigma_t [Pa].

    Notes
    -----
    sigma_r = c1 - c2/r^2 - (3 + nu)/8 rho omega^2 r^2,
    sigma_t = c1 + c2/r^2 - (1 + 3 nu)/8 rho omega^2 r^2 [1]_.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    c1, c2 = coefficients
    alpha, beta = _spin_factors(density, poisson, omega)
    r2 = r * r
    if _is_structural_zero(c2):
        return c1 - alpha * r2, c1 - beta * r2
    return c1 - c2 / r2 - alpha * r2, c1 + c2 / r2 - beta * r2


def disc_edge_stresses(
    coefficients: Any, radii: Any, density: Any, poisson: Any, omega: Any
) -> list[tuple[tuple[Any, Any], tuple[Any, Any]]]:
    """Stresses at both edges of every step (where an NLP constrains them).

    Parameters
    ----------
    coefficients : list of (c1, c2)
        From :func:`disc_coefficients`.
    radii : sequence of N + 1 floats, arrays or casadi expressions
        Edge radii r_0 ... r_N [m], as given to :func:`disc_coefficients`.
    density, poisson, omega
        rho [kg/m^3], nu [-], angular speed [rad/s].

    Returns
    -------
    list of ((sr_in, st_in), (sr_out, st_out))
        For step i the stresses [Pa] at r_i (its side of the interface) and
        at r_{i+1}.

    Notes
    -----
    The edges are not always where a step's stresses peak: sigma_r of a
    free annulus peaks inside it, at r = (c2/alpha)^(1/4)
    (:func:`annulus_max_radial_stress_radius`); :func:`max_stress_per_step`
    finds the true maxima for a check.
    """
    radii = _items(radii)
    return [
        (disc_stresses(c, density, poisson, omega, radii[i]), disc_stresses(c, density, poisson, omega, radii[i + 1]))
        for i, c in enumerate(coefficients)
    ]


def von_mises_squared(sr: Any, st: Any) -> Any:
    """Square of the plane-stress von Mises stress [Pa^2] (no square root, for an NLP).

    Parameters
    ----------
    sr, st : float or array or casadi expression
        Radial and hoop stress [Pa] (principal: no shear in an axisymmetric
        disc; sigma_z = 0).

    Notes
    -----
    sigma_vm^2 = sigma_r^2 - sigma_r sigma_t + sigma_t^2.

    References
    ----------
    .. [1] Budynas and Nisbett, Shigley's Mechanical Engineering Design, 9th
       ed., 2011, "Distortion-energy theory for ductile materials" (von
       Mises stress in plane stress).
    """
    return sr * sr - sr * st + st * st


def von_mises(sr: Any, st: Any) -> Any:
    """Plane-stress von Mises stress [Pa], sqrt(sigma_r^2 - sigma_r sigma_t + sigma_t^2).

    See :func:`von_mises_squared`.
    """
    return sqrt(von_mises_squared(sr, st))


def principal_stresses(sr: Any, st: Any) -> tuple[Any, Any]:
    """The in-plane principal stresses of an axisymmetric disc [Pa].

    Parameters
    ----------
    sr, st : float or array or casadi expression
        Radial and hoop stress [Pa].

    Returns
    -------
    (sr, st)
        sigma_r and sigma_t themselves: with no shear in an axisymmetric
        disc they are principal, the third being sigma_z = 0 (plane stress).
        No ``max`` is taken, so that it stays smooth on symbols: a caller
        that limits the largest principal stress constrains both.
    """
    return sr, st


def radial_displacement(sr: Any, st: Any, r: Any, elastic_modulus: Any, poisson: Any) -> Any:
    """Radial displacement of a point of a disc in plane stress [m].

    Parameters
    ----------
    sr, st : float or array or casadi expression
        Radial and hoop stress at r [Pa].
    r : float or array or casadi expression
        Radius [m].
    elastic_modulus : float or array or casadi expression
        Young's modulus E [Pa].
    poisson : float or array or casadi expression
        Poisson's ratio nu [-].

    Returns
    -------
    u : same type as the inputs
        u = r epsilon_t = r/E (sigma_t - nu sigma_r) [m] (e.g. the growth of
        a bore at speed, which loosens a shrink fit).

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    return r / elastic_modulus * (st - poisson * sr)


def mean_hoop_stress(coefficients: Any, radii: Any, thickness: Any, density: Any, poisson: Any, omega: Any) -> Any:
    """Mean hoop stress over the radial section of a stepped disc [Pa].

    Parameters
    ----------
    coefficients : list of (c1, c2)
        From :func:`disc_coefficients`.
    radii : sequence of N + 1 floats, arrays or casadi expressions
        Edge radii r_0 ... r_N [m].
    thickness : sequence of N floats, arrays or casadi expressions
        Step thicknesses [m].
    density, poisson, omega
        rho [kg/m^3], nu [-], angular speed [rad/s].

    Returns
    -------
    sigma_mean : same type as the inputs
        integral(sigma_t t dr) / integral(t dr) over r_0 ... r_N [Pa]: the
        hoop force on a diametral section over its area. A ductile disc
        bursts when it reaches the tensile strength [1]_.

    Notes
    -----
    Per step, exactly,

        integral_a^b sigma_t dr = c1 (b - a) + c2 (b - a)/(a b)
                                  - (1 + 3 nu)/8 rho omega^2 (b^3 - a^3)/3,

    the c2 term absent for a solid centre. Equilibrium of half the disc gives
    the same integral without the elastic solution (a check used by the
    tests): integral(sigma_t t dr) = [t r sigma_r]_{r_0}^{r_N}
    + rho omega^2 integral(t r^2 dr).

    References
    ----------
    .. [1] E. L. Robinson, "Bursting tests of steam-turbine disk wheels",
       Trans. ASME 66 (1944): model discs with and without a bore burst when
       the average hoop stress reached, for a good alloy steel somewhat
       exceeded, the ordinary tensile strength, so the criterion is a
       reasonable, slightly conservative estimate for ductile discs; A.
       Nadai, Theory of Flow and Fracture of Solids, vol. II, McGraw-Hill,
       1963 (rotating discs, plastic burst).
    """
    radii = _items(radii)
    thickness = _items(thickness)
    _, beta = _spin_factors(density, poisson, omega)
    force = 0.0
    area = 0.0
    for i, (c1, c2) in enumerate(coefficients):
        a, b, t = radii[i], radii[i + 1], thickness[i]
        integral = c1 * (b - a) - beta * (b * b * b - a * a * a) / 3.0
        if not _is_structural_zero(c2):
            integral = integral + c2 * (b - a) / (a * b)
        force = force + t * integral
        area = area + t * (b - a)
    return force / area


# ---------------------------------------------------------------- closed forms


def annulus_stresses(
    inner_radius: Any, outer_radius: Any, density: Any, poisson: Any, omega: Any, r: Any
) -> tuple[Any, Any]:
    """Stresses in a free rotating annulus of uniform thickness [Pa].

    Parameters
    ----------
    inner_radius, outer_radius : float or array or casadi expression
        a < b [m].
    density, poisson, omega
        rho [kg/m^3], nu [-], angular speed [rad/s].
    r : float or array or casadi expression
        Radius, a <= r <= b [m].

    Returns
    -------
    sr, st : same type as the inputs
        sigma_r, sigma_t [Pa], both edges free.

    Notes
    -----
    sigma_r = (3 + nu)/8 rho omega^2 (b^2 + a^2 - a^2 b^2/r^2 - r^2)
    sigma_t = (3 + nu)/8 rho omega^2 (b^2 + a^2 + a^2 b^2/r^2
              - (1 + 3 nu)/(3 + nu) r^2) [1]_.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32; Budynas and Nisbett, Shigley's, 9th ed., "Stresses in
       rotating rings".
    """
    a2, b2, r2 = inner_radius * inner_radius, outer_radius * outer_radius, r * r
    scale = (3.0 + poisson) / 8.0 * density * omega * omega
    sr = scale * (b2 + a2 - a2 * b2 / r2 - r2)
    st = scale * (b2 + a2 + a2 * b2 / r2 - (1.0 + 3.0 * poisson) / (3.0 + poisson) * r2)
    return sr, st


def annulus_bore_hoop_stress(inner_radius: Any, outer_radius: Any, density: Any, poisson: Any, omega: Any) -> Any:
    """Hoop stress at the bore of a free rotating annulus, its largest stress [Pa].

    Notes
    -----
    sigma_t(a) = (3 + nu)/4 rho omega^2 [b^2 + (1 - nu)/(3 + nu) a^2] [1]_;
    as a -> 0 it tends to twice the solid disc's centre stress.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    return (
        (3.0 + poisson)
        / 4.0
        * density
        * omega
        * omega
        * (outer_radius * outer_radius + (1.0 - poisson) / (3.0 + poisson) * inner_radius * inner_radius)
    )


def annulus_max_radial_stress(inner_radius: Any, outer_radius: Any, density: Any, poisson: Any, omega: Any) -> Any:
    """Largest radial stress of a free rotating annulus [Pa].

    Notes
    -----
    sigma_r,max = (3 + nu)/8 rho omega^2 (b - a)^2, at r = sqrt(a b) [1]_.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    gap = outer_radius - inner_radius
    return (3.0 + poisson) / 8.0 * density * omega * omega * gap * gap


def annulus_max_radial_stress_radius(inner_radius: Any, outer_radius: Any) -> Any:
    """Where the radial stress of a free rotating annulus peaks, r = sqrt(a b) [m]."""
    return sqrt(inner_radius * outer_radius)


def annulus_mean_hoop_stress(inner_radius: Any, outer_radius: Any, density: Any, omega: Any) -> Any:
    """Mean hoop stress over the section of a free rotating annulus [Pa].

    Notes
    -----
    By equilibrium of half the annulus (the radial stress vanishing at both
    edges), sigma_mean = rho omega^2 (b^3 - a^3)/(3 (b - a))
    = rho omega^2 (a^2 + a b + b^2)/3, independent of nu; a -> b gives the
    thin ring rho v^2, a = 0 the solid disc rho omega^2 b^2/3.
    """
    a, b = inner_radius, outer_radius
    return density * omega * omega * (a * a + a * b + b * b) / 3.0


def solid_disc_stresses(radius: Any, density: Any, poisson: Any, omega: Any, r: Any) -> tuple[Any, Any]:
    """Stresses in a free rotating solid disc of uniform thickness [Pa].

    Notes
    -----
    sigma_r = (3 + nu)/8 rho omega^2 (b^2 - r^2),
    sigma_t = (3 + nu)/8 rho omega^2 b^2 - (1 + 3 nu)/8 rho omega^2 r^2 [1]_.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    k = density * omega * omega
    b2, r2 = radius * radius, r * r
    return (3.0 + poisson) / 8.0 * k * (b2 - r2), ((3.0 + poisson) * b2 - (1.0 + 3.0 * poisson) * r2) / 8.0 * k


def solid_disc_centre_stress(radius: Any, density: Any, poisson: Any, omega: Any) -> Any:
    """Stress at the centre of a free rotating solid disc, its largest [Pa].

    Notes
    -----
    sigma_r(0) = sigma_t(0) = (3 + nu)/8 rho omega^2 b^2 [1]_.

    References
    ----------
    .. [1] Timoshenko and Goodier, Theory of Elasticity, 3rd ed., 1970,
       article 32.
    """
    return (3.0 + poisson) / 8.0 * density * omega * omega * radius * radius


def thin_ring_hoop_stress(density: Any, rim_speed: Any) -> Any:
    """Hoop stress of a thin rotating ring, sigma = rho v^2 [Pa].

    Parameters
    ----------
    density : float or array or casadi expression
        rho [kg/m^3].
    rim_speed : float or array or casadi expression
        Speed of the ring's mean radius, v = omega R [m/s].

    Notes
    -----
    The hoop tension of a ring of section A balances the centrifugal load
    rho A omega^2 R per unit length: F = rho A omega^2 R^2 [1]_.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter 22,
       "Stresses in a flywheel rim".
    """
    from flyopt.design.geometry import hoop_stress

    return hoop_stress(density, rim_speed)


# --------------------------------------------------------------- numeric check

#: Stress measures :func:`max_stress_per_step` can maximise.
MEASURES = {
    "von_mises": "plane-stress von Mises stress, sqrt(sr^2 - sr st + st^2)",
    "largest_principal": "largest in-plane principal stress, max(sr, st)",
    "radial": "radial stress sr",
    "hoop": "hoop stress st",
}

StepMaximum = namedtuple("StepMaximum", ["value", "step", "radius"])
StepMaximum.__doc__ = """The largest stress measure in one step: value [Pa], step index, radius [m]."""


def max_stress_per_step(
    coefficients: Any, radii: Any, density: Any, poisson: Any, omega: Any, measure: str = "von_mises"
) -> list[StepMaximum]:
    """Maximum of a stress measure over each step, in closed form (floats only).

    An independent check of constraints written at chosen radii. In a step,
    with u = r^2, sigma_r = c1 - c2/u - alpha u and sigma_t = c1 + c2/u - beta u
    (:func:`disc_stresses`), so each measure's stationary points are roots of
    a polynomial in u: sigma_r at u^2 = c2/alpha, sigma_t at u^2 = -c2/beta, and
    von Mises, whose square is R(u)/u^2 with R = P^2 - P Q + Q^2 (P = u sigma_r,
    Q = u sigma_t, quadratics), where u R'(u) - 2 R(u) = 0, a quartic. The largest
    principal stress max(sigma_r, sigma_t) peaks where one of the two does. The
    maximum over a step is the largest of the measure at its edges and at the
    real roots inside it (every candidate is a true value of the measure in the
    step, so a spurious root cannot raise it; the roots are refined by Newton).

    Parameters
    ----------
    coefficients : list of (c1, c2)
        From :func:`disc_coefficients`, evaluated on floats.
    radii : sequence of N + 1 floats
        Edge radii [m].
    density, poisson, omega : float
        rho [kg/m^3], nu [-], angular speed [rad/s].
    measure : {"von_mises", "largest_principal", "radial", "hoop"}
        What to maximise; see :data:`MEASURES`.

    Returns
    -------
    list of StepMaximum
        For every step, (value [Pa], step index, radius [m]) of the maximum;
        where the edge and an interior point tie, the inner edge.

    Raises
    ------
    ValueError
        For an unknown measure (naming the closest one).
    """
    return max_stresses_per_step(coefficients, radii, density, poisson, omega, (measure,))[measure]


def max_stresses_per_step(
    coefficients: Any, radii: Any, density: Any, poisson: Any, omega: Any, measures: Sequence[str]
) -> dict[str, list[StepMaximum]]:
    """:func:`max_stress_per_step` of several measures at once, by measure: each step's stresses at its
    edges are found once for all of them (a whole wheel's strength check asks for all four)."""
    for measure in measures:
        if measure not in MEASURES:
            raise ValueError(f"stress measure {unknown(measure, MEASURES)}")
    density, poisson, omega = float(density), float(poisson), float(omega)
    alpha, beta = _spin_factors(density, poisson, omega)

    def at(c, r):
        sr, st = disc_stresses(c, density, poisson, omega, r)
        return float(sr), float(st)

    radii = [float(r) for r in _items(radii)]
    steps = [(float(c[0]), 0.0 if _is_structural_zero(c[1]) else float(c[1])) for c in coefficients]
    edges = [(at(c, radii[i]), at(c, radii[i + 1])) for i, c in enumerate(steps)]
    found: dict[str, list[StepMaximum]] = {}
    for measure in measures:
        # von Mises: every step's stationarity quartic, their roots found together (one eigvals call per size)
        if measure == "von_mises":
            quartics = [_von_mises_quartic(c, alpha, beta, radii[i + 1] ** 2) for i, c in enumerate(steps)]
            roots = _roots(quartics)
        else:
            quartics, roots = [None] * len(steps), [None] * len(steps)
        result = []
        for i, c in enumerate(steps):
            low, high = radii[i], radii[i + 1]
            best = StepMaximum(_measured(measure, *edges[i][0]), i, low)
            for r in _stationary_radii(c, alpha, beta, low, high, measure, quartics[i], roots[i]):
                v = _measured(measure, *at(c, r))
                if v > best.value:
                    best = StepMaximum(v, i, r)
            v = _measured(measure, *edges[i][1])
            if v > best.value:
                best = StepMaximum(v, i, high)
            result.append(best)
        found[measure] = result
    return found


def _measured(measure: str, sr: float, st: float) -> float:
    """A stress measure (:data:`MEASURES`) of a radial and a hoop stress [Pa]."""
    if measure == "von_mises":
        return float(von_mises(sr, st))
    if measure == "radial":
        return sr
    if measure == "hoop":
        return st
    return max(sr, st)


def _von_mises_quartic(c, alpha, beta, u_high):
    """The stationarity polynomial of von Mises in a step (ascending powers of s = u / u_high, its
    highest zero powers dropped; d_poly[2] == 0), see :func:`max_stress_per_step`."""
    c1, c2 = c
    if u_high <= 0.0:
        return []
    # in s = u / u_high (order one): P = u sigma_r / u_high = -a s^2 + c1 s - k and Q = u sigma_t / u_high
    # = -b s^2 + c1 s + k; R = P^2 - P Q + Q^2 = sum r_j s^j and s R' - 2 R = sum (j - 2) r_j s^j, a quartic
    a, b, k = alpha * u_high, beta * u_high, c2 / u_high
    p, q = (-k, c1, -a), (k, c1, -b)
    r = [
        sum(p[i] * p[j - i] - p[i] * q[j - i] + q[i] * q[j - i] for i in range(max(0, j - 2), min(j, 2) + 1))
        for j in range(5)
    ]
    d_poly = [(j - 2) * r[j] for j in range(5)]  # ascending powers of s; d_poly[2] == 0
    while d_poly and d_poly[-1] == 0.0:
        d_poly.pop()
    return d_poly


def _roots(polynomials):
    """``numpy.roots`` of each polynomial (ascending powers), the companion matrices' eigenvalues found in
    one ``numpy.linalg.eigvals`` call per size: each matrix is the one numpy.roots builds (its first row
    -p[1:] / p[0] of the coefficients trimmed of zeros at both ends, ones below the diagonal, a zero root
    for each zero trimmed from the low end), and LAPACK solves each of a stack alone, so the roots are
    numpy.roots' own (a stress check asks for three or four quartics; one numpy.roots call each cost most
    of the check)."""
    out: list[Any] = [()] * len(polynomials)
    by_size: dict[int, list[tuple[int, list[list[float]], int]]] = {}
    for k, poly in enumerate(polynomials):
        low, high = 0, len(poly)
        while low < high and poly[low] == 0.0:
            low += 1
        while high > low and poly[high - 1] == 0.0:
            high -= 1
        if high == low:  # the zero polynomial: numpy.roots gives no roots
            continue
        p = poly[low:high][::-1]  # descending, as numpy.roots takes it
        n = len(p) - 1
        if n == 0:
            out[k] = np.zeros(low)
            continue
        first = [-c / p[0] for c in p[1:]]
        companion = [first] + [[1.0 if j == i else 0.0 for j in range(n)] for i in range(n - 1)]
        by_size.setdefault(n, []).append((k, companion, low))
    for group in by_size.values():
        values = np.linalg.eigvals(np.array([m for _, m, _ in group]))
        for (k, _, zeros), found in zip(group, values):
            out[k] = np.concatenate([found, np.zeros(zeros, dtype=found.dtype)]) if zeros else found
    return out


def _stationary_radii(c, alpha, beta, low, high, measure, d_poly=None, roots=None):
    """The radii strictly inside (low, high) where a measure of a step is stationary (see max_stress_per_step);
    for von Mises its quartic (:func:`_von_mises_quartic`) and that quartic's roots (:func:`_roots`) when
    found already."""
    c1, c2 = c
    u_low, u_high = low * low, high * high
    if u_high <= u_low:
        return []
    found = []
    if measure in ("radial", "largest_principal") and c2 > 0 and alpha > 0:
        found.append(math.sqrt(c2 / alpha))
    if measure in ("hoop", "largest_principal") and c2 < 0 and beta > 0:
        found.append(math.sqrt(-c2 / beta))
    if measure == "von_mises":
        if d_poly is None:
            d_poly = _von_mises_quartic(c, alpha, beta, u_high)
        if roots is None:
            roots = _roots([d_poly])[0] if len(d_poly) > 1 else ()
        padded = d_poly + [0.0] * (5 - len(d_poly))
        dd_poly = [j * padded[j] for j in range(1, 5)]
        for root in roots:
            if abs(root.imag) > 1e-6 * max(abs(root), 1e-300):
                continue
            s = float(root.real)
            for _ in range(3):  # Newton on the stationarity polynomial, from the eigenvalue's root
                slope = sum(c * s**j for j, c in enumerate(dd_poly))
                if slope == 0.0:
                    break
                step = sum(c * s**j for j, c in enumerate(d_poly)) / slope
                s -= step
                if abs(step) <= 1e-16 * abs(s):
                    break
            found.append(s * u_high)
    return [math.sqrt(u) for u in found if u_low < u < u_high]


# ------------------------------------------------------------- rim with arms


def rim_hoop_stress(density: Any, omega: Any, mean_radius: Any) -> Any:
    """Hoop stress of a rim free of its arms, rho v^2 with v = omega R [Pa].

    See :func:`thin_ring_hoop_stress`; the rim's mean radius R [m] sets v.
    """
    return thin_ring_hoop_stress(density, omega * mean_radius)


def rim_bending_stress(density: Any, omega: Any, mean_radius: Any, radial_thickness: Any, n_arms: Any) -> Any:
    """Bending stress in a rim held by its arms [Pa].

    Parameters
    ----------
    density : float or array or casadi expression
        rho [kg/m^3].
    omega : float or array or casadi expression
        Angular speed [rad/s].
    mean_radius : float or array or casadi expression
        Mean rim radius R [m].
    radial_thickness : float or array or casadi expression
        Radial thickness of the rim H [m] (the depth of the beam).
    n_arms : float or array or casadi expression
        Number of arms n [-].

    Returns
    -------
    sigma_b : same type as the inputs
        sigma_b = 2 pi^2 rho omega^2 R^3/(n^2 H) = 19.74 rho v^2 R/(n^2 H)
        [Pa], v = omega R.

    Notes
    -----
    The rim between two arms is taken as a straight beam fixed at both ends
    (arms that do not stretch), of span l = 2 pi R/n, under its own
    centrifugal load w = rho B H omega^2 R per unit length. The largest
    moment, at the arms, is M = w l^2/12; with Z = B H^2/6,

        sigma_b = M/Z = 6 rho B H omega^2 R (2 pi R/n)^2 / (12 B H^2)
                = 2 pi^2 rho omega^2 R^3 / (n^2 H),

    the width B cancelling. Khurmi writes it 19.74 rho v^2 R/(n^2 t) [1]_
    (t = H, 19.74 = 2 pi^2). It is an upper bound: the arms do stretch, which
    is why the texts combine it with the hoop stress in
    :func:`rim_combined_stress`.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter 22,
       "Stresses in a flywheel rim": "Tensile bending stress caused by
       restraint of the arms".
    """
    return 2.0 * math.pi**2 * density * omega * omega * mean_radius**3 / (n_arms * n_arms * radial_thickness)


def rim_combined_stress(hoop_stress: Any, bending_stress: Any) -> Any:
    """Resultant rim stress of the machine-design texts, 0.75 sigma_t + 0.25 sigma_b [Pa].

    Parameters
    ----------
    hoop_stress : float or array or casadi expression
        sigma_t of the free rim, :func:`rim_hoop_stress` [Pa].
    bending_stress : float or array or casadi expression
        sigma_b of the rim fixed at rigid arms, :func:`rim_bending_stress` [Pa].

    Notes
    -----
    sigma = 3/4 sigma_t + 1/4 sigma_b. The two limits are a free ring (arms
    infinitely stretchable, sigma_t only) and a rim on rigid arms (bending
    only); real arms stretch so that, empirically, three quarters of the
    hoop stress and one quarter of the bending stress act together. The
    factors are used by Khurmi [1]_ and attributed to the older American
    texts (D. S. Kimball and J. H. Barr, Elements of Machine Design, Wiley,
    1909; also M. F. Spotts, Design of Machine Elements); flyopt has not
    checked those originals, only Khurmi's use. de Castro [2]_ derives the
    rim and spoke stresses by Castigliano's theorems and discusses where
    these design formulas come from.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter 22,
       "Stresses in a flywheel rim".
    .. [2] P. M. S. T. de Castro, "Bi-material flywheels and Castigliano's
       theorems: a case study", Journal of Mechanics and Structures (FEUP).
    """
    return 0.75 * hoop_stress + 0.25 * bending_stress


def arm_section_area(major: Any, minor: Any) -> Any:
    """Area of an arm's elliptical section, pi a b_a / 4 [m^2].

    Parameters
    ----------
    major : float or array or casadi expression
        Major axis a, in the plane of rotation [m] (full length, not the
        semi-axis).
    minor : float or array or casadi expression
        Minor axis b_a, axial [m]; the texts take b_a = a/2 [1]_.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter 22,
       "Design of flywheel arms".
    """
    return math.pi * major * minor / 4.0


def arm_section_modulus(major: Any, minor: Any) -> Any:
    """Section modulus of an elliptical arm bending in the plane of rotation [m^3].

    Parameters
    ----------
    major : float or array or casadi expression
        Major axis a, in the plane of rotation [m].
    minor : float or array or casadi expression
        Minor axis b_a, axial [m].

    Returns
    -------
    z : same type as the inputs
        Z = pi b_a a^2 / 32 [m^3].

    Notes
    -----
    About the axial (minor-axis) direction the ellipse has
    I = pi b_a a^3 / 64 and its extreme fibre is at a/2, so Z = I/(a/2) [1]_.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter 22,
       "Design of flywheel arms".
    """
    return math.pi * minor * major * major / 32.0


def arm_bending_moment(torque: Any, n_arms: Any, arm_end_radius: Any, hub_radius: Any) -> Any:
    """Bending moment at the hub end of each arm from the torque [N*m].

    Parameters
    ----------
    torque : float or array or casadi expression
        Torque the rim exchanges with the shaft, T [N*m] (the largest of the
        cycle: the maximum torque on the shaft [1]_).
    n_arms : float or array or casadi expression
        Number of arms n [-].
    arm_end_radius : float or array or casadi expression
        Radius where the arm's tangential force acts, R_e [m]. The texts use
        the rim's mean radius R [1]_; the rim's inner radius R - H/2 is
        where the arm actually ends.
    hub_radius : float or array or casadi expression
        Radius of the hub, where the arm is fixed, r [m].

    Returns
    -------
    m : same type as the inputs
        M = T/(n R_e) (R_e - r) = T/n (1 - r/R_e) [N*m].

    Notes
    -----
    Each arm is a cantilever fixed at the hub, carrying at its end the
    tangential force T/(n R_e) that passes its share of the torque. With
    R_e = R this is Khurmi's M = T/(R n) (R - r) [1]_. Since M grows with
    R_e, the texts' R_e = R (mean radius) is the larger, conservative value;
    it also ignores that the rim restrains the arm's end (a cantilever, not
    a guided beam), again on the safe side. The designer uses R_e = R.

    References
    ----------
    .. [1] Khurmi and Gupta, A Textbook of Machine Design, 2005, chapter
       22, "Stresses in flywheel arms".
    """
    return torque / n_arms * (arm_end_radius - hub_radius) / arm_end_radius


def arm_bending_stress(torque: Any, n_arms: Any, arm_end_radius: Any, hub_radius: Any, major: Any, minor: Any) -> Any:
    """Bending stress at the hub end of an elliptical arm, M/Z [Pa].

    See :func:`arm_bending_moment` (M) and :func:`arm_section_modulus` (Z).
    """
    return arm_bending_moment(torque, n_arms, arm_end_radius, hub_radius) / arm_section_modulus(major, minor)


def arm_centrifugal_force(density: Any, arm_area: Any, omega: Any, arm_end_radius: Any, hub_radius: Any) -> Any:
    """Tension at the root of an arm from its own centrifugal load [N].

    Parameters
    ----------
    density : float or array or casadi expression
        rho [kg/m^3].
    arm_area : float or array or casadi expression
        Section of the arm A_arm [m^2] (uniform).
    omega : float or array or casadi expression
        Angular speed [rad/s].
    arm_end_radius, hub_radius : float or array or casadi expression
        The arm runs from the hub radius r to R_e [m].

    Returns
    -------
    f : same type as the inputs
        F = integral_r^{R_e} rho A_arm omega^2 s ds
          = rho A_arm omega^2 (R_e^2 - r^2)/2 [N].
    """
    return density * arm_area * omega * omega * (arm_end_radius * arm_end_radius - hub_radius * hub_radius) / 2.0


def _sin_pi_over(n):
    """sin(pi/n) for a plain number or a numpy array of numbers of arms."""
    if isinstance(n, numbers.Real):
        return math.sin(math.pi / float(n))  # float(n): exact for any count of arms
    return np.sin(np.pi / np.asarray(n, dtype=float))


def rim_segment_force(density: Any, rim_area: Any, omega: Any, mean_radius: Any, n_arms: Any) -> Any:
    """Resultant centrifugal force of the rim segment one arm carries [N].

    Parameters
    ----------
    density : float or array or casadi expression
        rho [kg/m^3].
    rim_area : float or array or casadi expression
        Rim section B H [m^2].
    omega : float or array or casadi expression
        Angular speed [rad/s].
    mean_radius : float or array or casadi expression
        Mean rim radius R [m].
    n_arms : int or numpy array of ints
        Number of arms n, a plain number (not symbolic: it enters through
        sin(pi/n)).

    Returns
    -------
    f : same type as the inputs
        F = 2 rho A_rim omega^2 R^2 sin(pi/n) [N].

    Notes
    -----
    The segment of angle 2 pi/n centred on an arm carries the load
    rho A_rim omega^2 R per unit length; its resultant along the arm is
    integral_{-pi/n}^{pi/n} rho A_rim omega^2 R^2 cos(theta) d theta. It is a
    conservative bound on what the arm carries: a continuous rim balances
    its own centrifugal load by hoop tension (a free ring needs no arms),
    so the arm takes only the part its restraint adds; charging the whole
    resultant is the case of a rim cut between the arms.
    """
    return 2.0 * density * rim_area * omega * omega * mean_radius * mean_radius * _sin_pi_over(n_arms)


def arm_pull(
    density: Any,
    arm_area: Any,
    rim_area: Any,
    omega: Any,
    mean_radius: Any,
    arm_end_radius: Any,
    hub_radius: Any,
    n_arms: Any,
) -> Any:
    """Radial pull of one arm at the hub: its own centrifugal load plus the rim's share [N].

    The sum of :func:`arm_centrifugal_force` and :func:`rim_segment_force`
    (a conservative bound, see there); ``n_arms`` is a plain number.
    """
    return arm_centrifugal_force(density, arm_area, omega, arm_end_radius, hub_radius) + rim_segment_force(
        density, rim_area, omega, mean_radius, n_arms
    )


def arm_stress(bending_stress: Any, pull: Any, arm_area: Any) -> Any:
    """Largest stress at the root of an arm, sigma_b + F/A [Pa].

    Parameters
    ----------
    bending_stress : float or array or casadi expression
        :func:`arm_bending_stress` [Pa].
    pull : float or array or casadi expression
        Radial tension at the root, :func:`arm_pull` [N].
    arm_area : float or array or casadi expression
        :func:`arm_section_area` [m^2].

    Notes
    -----
    The bending stress is tensile on one side of the arm, where it adds to
    the uniform tension F/A.
    """
    return bending_stress + pull / arm_area


def arm_hub_traction(n_arms: Any, pull: Any, hub_radius: Any, hub_length: Any) -> Any:
    """The arms' pull on the hub spread over its outer surface [Pa].

    Parameters
    ----------
    n_arms : float or array or casadi expression
        Number of arms n [-].
    pull : float or array or casadi expression
        Pull of one arm at the hub, :func:`arm_pull` [N].
    hub_radius : float or array or casadi expression
        Outer radius of the hub r_hub [m].
    hub_length : float or array or casadi expression
        Axial length of the hub L_hub [m].

    Returns
    -------
    traction : same type as the inputs
        n F/(2 pi r_hub L_hub) [Pa], the ``outer_traction`` to give
        :func:`disc_coefficients` for the hub as a free annulus from the bore
        to r_hub of thickness L_hub.

    Notes
    -----
    Smearing n point loads into a uniform traction is the axisymmetric
    approximation; near each arm the hub sees more.
    """
    return n_arms * pull / (2.0 * math.pi * hub_radius * hub_length)


# ----------------------------------------------------------------- burst speed


def burst_speed(omega: Any, stress: Any, strength: Any) -> Any:
    """Speed at which a stress that scales with omega^2 reaches a strength [rad/s].

    Parameters
    ----------
    omega : float or array or casadi expression
        Speed at which ``stress`` was evaluated [rad/s].
    stress : float or array or casadi expression
        The governing stress at omega, positive [Pa].
    strength : float or array or casadi expression
        The strength it must reach [Pa].

    Returns
    -------
    omega_burst : same type as the inputs
        omega sqrt(strength/stress) [rad/s].

    Notes
    -----
    Valid only when every load scales with omega^2 (centrifugal loads,
    arms' pull): no fit pressure, no torque. Then sigma(omega_b) =
    sigma(omega) (omega_b/omega)^2 = strength.
    """
    return omega * sqrt(strength / stress)


def burst_speed_ductile(omega: Any, mean_hoop: Any, tensile_strength: Any) -> Any:
    """Burst speed of a ductile disc: the mean hoop stress reaches the tensile strength [rad/s].

    Parameters
    ----------
    omega : float or array or casadi expression
        Speed at which ``mean_hoop`` was evaluated [rad/s].
    mean_hoop : float or array or casadi expression
        :func:`mean_hoop_stress` at omega [Pa].
    tensile_strength : float or array or casadi expression
        Ultimate tensile strength sigma_u [Pa].

    Notes
    -----
    omega_b = omega sqrt(sigma_u/sigma_mean) (see :func:`burst_speed`) [1]_.

    References
    ----------
    .. [1] Robinson, Trans. ASME 66 (1944); Nadai, Theory of Flow and
       Fracture of Solids, vol. II, 1963 (see :func:`mean_hoop_stress`).
    """
    return burst_speed(omega, mean_hoop, tensile_strength)


def burst_speed_brittle(omega: Any, largest_principal: Any, tensile_strength: Any) -> Any:
    """Burst speed of a brittle disc: the largest principal stress reaches the tensile strength [rad/s].

    Parameters
    ----------
    omega : float or array or casadi expression
        Speed at which ``largest_principal`` was evaluated [rad/s].
    largest_principal : float or array or casadi expression
        The largest principal stress anywhere in the wheel at omega [Pa]
        (e.g. from :func:`max_stress_per_step` with
        ``measure="largest_principal"``).
    tensile_strength : float or array or casadi expression
        Tensile strength sigma_u [Pa] (e.g. of cast iron).

    Notes
    -----
    omega_b = omega sqrt(sigma_u/sigma_1,max), the maximum-normal-stress
    criterion of brittle fracture (see :func:`burst_speed`).

    References
    ----------
    .. [1] Budynas and Nisbett, Shigley's Mechanical Engineering Design, 9th
       ed., 2011, "Maximum-normal-stress theory for brittle materials".
    """
    return burst_speed(omega, largest_principal, tensile_strength)
