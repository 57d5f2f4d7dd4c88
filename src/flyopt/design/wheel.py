"""The whole wheel: its parts, their mass and inertia, and their stresses.

A flywheel that can be built is more than its rim. flyopt knows five
geometries (:data:`flyopt.design.geometry.GEOMETRIES`); each is a list of
parts, and every part counts in the inertia and in the mass:

=========  ==========================================================
geometry   parts (inner to outer)
=========  ==========================================================
thin_rim   rim (inertia m D_m^2/4, the textbook's, which errs safe)
rim        rim (the exact annulus)
disc       disc: solid, or an annulus from the bore to D
rim_web    hub (bore to d_hub, length l_hub), web (d_hub to the rim's
           inner diameter, thickness t_web), rim (width B); no bore:
           the web runs to the centre and there is no hub
rim_arms   hub, n arms of elliptical section (major axis a in the plane
           of rotation, minor axis a/2), rim
=========  ==========================================================

Dimensions of a wheel (:class:`Dims`, SI): outer diameter ``d_outer``,
radial rim thickness ``h``, rim width ``b``, web thickness ``t_web``, hub
diameter ``d_hub`` and length ``l_hub``, arm major axis ``arm_major``, arm
count ``n_arms`` and the bore ``bore`` (0: none). For a disc ``h`` is the
radial extent (D - bore)/2; a bored disc designed whole stands on a hub
(``d_hub``, ``l_hub``): the seat's key needs a hub's length, not a plate's.

Every function is arithmetic only, so the same code gives floats, numpy
arrays and CasADi expressions (the design NLP, :mod:`flyopt.design.wheel_nlp`,
builds on it). Stresses come from :mod:`flyopt.design.stress`.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 9, 10 and 13.
.. [2] R. S. Khurmi and J. K. Gupta, A Textbook of Machine Design, chapter
   22 (flywheel): rim, arms of elliptical section with minor axis half the
   major, hub.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, fields
from typing import Any, NamedTuple

from flyopt.design import geometry
from flyopt.names import Geometry

__all__ = ["Dims", "Part", "ARM_MINOR_RATIO", "parts", "has_hub", "wheel_mass", "wheel_inertia", "steps"]

#: Minor over major axis of an arm's elliptical section (the texts' proportion, [2]).
ARM_MINOR_RATIO = 0.5


@dataclass(frozen=True)
class Dims:
    """The dimensions of a wheel [m] (``n_arms`` a count); what a geometry does not use is 0.

    Plain floats or CasADi symbols (the NLP builds its rows from the same arithmetic), hence ``Any``.
    """

    d_outer: Any
    h: Any
    b: Any
    bore: Any = 0.0
    t_web: Any = 0.0
    d_hub: Any = 0.0
    l_hub: Any = 0.0
    arm_major: Any = 0.0
    n_arms: int = 0

    @property
    def d_mean(self) -> Any:
        """Mean rim diameter D_m = D_outer - H [m]."""
        return self.d_outer - self.h

    @property
    def d_inner(self) -> Any:
        """Inner rim diameter D_outer - 2 H [m] (the bore for a disc)."""
        return self.d_outer - 2.0 * self.h

    def to_dict(self) -> dict[str, Any]:
        """The dimensions by field name."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class Part:
    """One part of a wheel.

    Attributes
    ----------
    name : str
        "rim", "web", "hub", "arms" or "disc".
    mass : float or expression
        [kg] (all arms together for "arms").
    inertia : float or expression
        About the axis [kg*m^2].
    r_inner, r_outer : float or expression
        Radial extent [m].
    thickness : float or expression
        Axial thickness [m] (rim width, web thickness, hub length; the arms' minor axis).
    """

    name: str
    mass: Any
    inertia: Any
    r_inner: Any
    r_outer: Any
    thickness: Any


def _annulus(name, density, r_inner, r_outer, thickness, thin=False):
    """An annulus of constant thickness: m = pi rho t (r_o^2 - r_i^2), J = m (r_o^2 + r_i^2)/2
    (``thin``: J = m r_mean^2, the thin-rim model)."""
    d_mean, h = r_outer + r_inner, r_outer - r_inner  # an annulus is a rim of D_m and H
    mass = geometry.rim_mass(d_mean, h, thickness, density)
    inertia = geometry.thin_rim_inertia(mass, d_mean) if thin else geometry.rim_inertia(mass, d_mean, h)
    return Part(name, mass, inertia, r_inner, r_outer, thickness)


def parts(geometry_name: str, dims: Dims, density: Any) -> list[Part]:
    """The parts of a wheel, inner to outer.

    Parameters
    ----------
    geometry_name : str
        One of :data:`flyopt.design.geometry.GEOMETRIES`.
    dims : Dims
    density : float or expression
        rho [kg/m^3].

    Returns
    -------
    list of Part

    Notes
    -----
    The arms run from the hub's outer radius to the rim's inner radius, each
    of area A = pi a (a/2)/4: m = n rho A (r_i - r_h), J = n rho A (r_i^3 - r_h^3)/3
    (slender bars; their own width across the radius is neglected in J).
    """
    r_o = dims.d_outer / 2.0
    r_i = dims.d_inner / 2.0
    r_bore = dims.bore / 2.0
    if geometry_name == Geometry.DISC:
        if has_hub(dims):
            r_h = dims.d_hub / 2.0
            return [_annulus("hub", density, r_bore, r_h, dims.l_hub), _annulus("disc", density, r_h, r_o, dims.b)]
        return [_annulus("disc", density, r_bore, r_o, dims.b)]
    rim = _annulus("rim", density, r_i, r_o, dims.b, thin=geometry_name == Geometry.THIN_RIM)
    if geometry_name in (Geometry.RIM, Geometry.THIN_RIM):
        return [rim]
    r_h = dims.d_hub / 2.0
    if geometry_name == Geometry.RIM_WEB:
        if _zero(dims.bore):
            return [_annulus("web", density, 0.0, r_i, dims.t_web), rim]
        return [_annulus("hub", density, r_bore, r_h, dims.l_hub), _annulus("web", density, r_h, r_i, dims.t_web), rim]
    if geometry_name == Geometry.RIM_ARMS:
        area = math.pi * dims.arm_major * (ARM_MINOR_RATIO * dims.arm_major) / 4.0
        n = dims.n_arms
        arms = Part(
            "arms",
            n * density * area * (r_i - r_h),
            n * density * area * (r_i**3 - r_h**3) / 3.0,
            r_h,
            r_i,
            ARM_MINOR_RATIO * dims.arm_major,
        )
        return [_annulus("hub", density, r_bore, r_h, dims.l_hub), arms, rim]
    raise ValueError(f"geometry {geometry_name!r} not known")


def has_hub(dims: Dims) -> bool:
    """Whether a wheel has a hub: a bore and a hub diameter (a web, arms, or a disc the NLP designs whole)."""
    return not _zero(dims.bore) and dims.d_hub is not None and not _zero(dims.d_hub)


def _zero(value):
    """Whether a structural value (the bore, a plain number) is zero; symbols are never asked."""
    return isinstance(value, (int, float)) and value == 0


def wheel_mass(wheel_parts: Iterable[Part]) -> Any:
    """Total mass of the parts [kg]."""
    total = 0.0
    for part in wheel_parts:
        total = total + part.mass
    return total


def wheel_inertia(wheel_parts: Iterable[Part]) -> Any:
    """Total inertia of the parts about the axis [kg*m^2]."""
    total = 0.0
    for part in wheel_parts:
        total = total + part.inertia
    return total


def steps(geometry_name: str, dims: Dims) -> tuple[list[Any], list[Any], bool, list[str]]:
    """The wheel as a stepped disc for the plane-stress solver: (radii, thicknesses, solid, names).

    For ``rim_arms`` only the hub is a disc (the rim and the arms follow the
    texts' beam models), so this returns the hub alone.

    Returns
    -------
    radii : list
        Edge radii r_0 < ... < r_N [m] (r_0 = 0 for a solid centre).
    thicknesses : list
        Axial thickness of each step [m].
    solid : bool
        The centre is solid (no bore).
    names : list of str
        The part each step belongs to.
    """
    r_o = dims.d_outer / 2.0
    r_i = dims.d_inner / 2.0
    r_bore = dims.bore / 2.0
    solid = _zero(dims.bore)
    if geometry_name == Geometry.DISC:
        if has_hub(dims):
            return [r_bore, dims.d_hub / 2.0, r_o], [dims.l_hub, dims.b], False, ["hub", "disc"]
        return [r_bore, r_o], [dims.b], solid, ["disc"]
    if geometry_name in (Geometry.RIM, Geometry.THIN_RIM):
        return [r_i, r_o], [dims.b], False, ["rim"]
    r_h = dims.d_hub / 2.0
    if geometry_name == Geometry.RIM_WEB:
        if solid:
            return [0.0, r_i, r_o], [dims.t_web, dims.b], True, ["web", "rim"]
        return [r_bore, r_h, r_i, r_o], [dims.l_hub, dims.t_web, dims.b], False, ["hub", "web", "rim"]
    if geometry_name == Geometry.RIM_ARMS:
        return [r_bore, r_h], [dims.l_hub], solid, ["hub"]
    raise ValueError(f"geometry {geometry_name!r} not known")


def walls(geometry_name: str, dims: Dims) -> dict[str, Any]:
    """The wall thickness of every part, the section its strength depends on [m].

    A casting's strength falls with its wall thickness (EN 1561, EN 1563:
    the relevant wall thickness of the section). Rim: the smaller of H and
    B; web: its thickness; hub: the smaller of its radial wall and its
    length; arms: the minor axis; disc: the smaller of B and its radial
    extent. Floats only (used between solves, never inside the NLP).

    A part of no radial extent (within :data:`NO_EXTENT` of its outer radius:
    the rim sitting on the hub, an optimum where no web or arm length pays)
    is no section across its radius: its wall is its thickness, so that the
    strength table is read at a size the casting has, not at round-off.

    Returns
    -------
    dict of str to float
    """
    out = {}
    for part in parts(geometry_name, dims, 1.0):
        if part.name == "arms":
            out["arms"] = float(part.thickness)
        else:
            extent = float(part.r_outer - part.r_inner)
            no_extent = extent <= NO_EXTENT * float(part.r_outer)
            out[part.name] = float(part.thickness) if no_extent else float(min(part.thickness, extent))
    return out


#: A part's radial extent at or below this share of its outer radius is none (:func:`walls`): an optimum
#: that closes a gap meets it to the solver's round-off (1e-16 m from an active-set solve, 1e-12 m from
#: an interior point one), never to a machinable size.
NO_EXTENT = 1e-9


class StressState(NamedTuple):
    """The stress state of a wheel at one speed (see :func:`stress_state`)."""

    beams: list[
        tuple[str, Any, Any, Any]
    ]  # (part, r, sr, st) of the parts the texts treat as beams (rim_arms: rim, arms)
    radii: list[Any]  # edge radii of the stepped-disc parts [m]
    thicknesses: list[Any]  # their axial thicknesses [m]
    names: list[str]  # the part of each step
    coefficients: list[tuple[Any, Any]]  # (c1, c2) of each step (flyopt.design.stress.disc_coefficients)


def stress_state(geometry_name: str, dims: Dims, density: Any, poisson: Any, omega: Any, torque: Any) -> StressState:
    """The stresses of a wheel at speed omega: its disc parts exactly, its arms' parts by the texts.

    Parameters
    ----------
    geometry_name : str
    dims : Dims
    density, poisson : float or expression
        rho [kg/m^3], nu [-].
    omega : float or expression
        Speed of the wheel [rad/s] (its highest of the cycle, for a design check).
    torque : float or expression
        Peak torque the wheel exchanges with its shaft [N*m] (the arms bend under it).

    Returns
    -------
    StressState
        The disc parts (rim, web, hub, disc) by the exact stepped-disc
        solution (:func:`flyopt.design.stress.disc_coefficients`); for
        ``rim_arms`` the rim by the texts' combined hoop and bending stress
        (a hoop stress at the mean radius) and the arms by their root stress
        (a radial stress at the hub), and the hub as a free annulus pulled
        at its rim by the arms.

    Notes
    -----
    Arithmetic only: the NLP samples symbolic wheels (:func:`stress_samples`);
    :mod:`flyopt.design.strength` finds the exact maxima of a solved one.
    """
    from flyopt.design import stress

    radii, thicknesses, solid, names = steps(geometry_name, dims)
    beams = []
    traction = 0.0
    if geometry_name == Geometry.RIM_ARMS:
        r_mean = dims.d_mean / 2.0
        r_inner = dims.d_inner / 2.0
        r_hub = dims.d_hub / 2.0
        minor = ARM_MINOR_RATIO * dims.arm_major
        area = stress.arm_section_area(dims.arm_major, minor)
        rim = stress.rim_combined_stress(
            stress.rim_hoop_stress(density, omega, r_mean),
            stress.rim_bending_stress(density, omega, r_mean, dims.h, dims.n_arms),
        )
        pull = stress.arm_pull(density, area, dims.b * dims.h, omega, r_mean, r_inner, r_hub, dims.n_arms)
        arm = stress.arm_stress(
            stress.arm_bending_stress(torque, dims.n_arms, r_mean, r_hub, dims.arm_major, minor), pull, area
        )
        traction = stress.arm_hub_traction(dims.n_arms, pull, r_hub, dims.l_hub)
        beams = [("arms", r_hub, arm, 0.0), ("rim", r_mean, 0.0, rim)]
    coefficients = stress.disc_coefficients(
        radii, thicknesses, density, poisson, omega, solid=solid, outer_traction=traction
    )
    return StressState(beams, radii, thicknesses, names, coefficients)


def stress_samples(
    geometry_name: str, dims: Dims, density: Any, poisson: Any, omega: Any, torque: Any, fractions: Iterable[float]
) -> list[tuple[str, Any, Any, Any]]:
    """Radial and hoop stress at sample points of every part (see :func:`stress_state`).

    ``fractions`` (0..1 of each disc part's radial extent) say where to sample
    the disc parts; the beams of ``rim_arms`` come once each.

    Returns
    -------
    list of (part, r, sr, st)
        Part name, radius [m], sigma_r and sigma_t [Pa].
    """
    from flyopt.design import stress

    state = stress_state(geometry_name, dims, density, poisson, omega, torque)
    samples = list(state.beams)
    radii = state.radii
    for k, c in enumerate(state.coefficients):
        for f in fractions:
            r = radii[k] + f * (radii[k + 1] - radii[k])
            sr, st = stress.disc_stresses(c, density, poisson, omega, r)
            samples.append((state.names[k], r, sr, st))
    return samples
