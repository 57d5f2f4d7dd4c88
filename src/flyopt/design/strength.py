"""The strength of a designed wheel: every part's governing stress found exactly, its burst speed and balance.

This is the independent check of a design (the NLP writes its stress rows at
a few radii; here the maximum of each disc part is found in closed form,
:func:`flyopt.design.stress.max_stresses_per_step`), and the source of
the stress fields of every design flyopt reports, whichever criterion sized it.

The allowable stress of a part is the material's
(:meth:`flyopt.design.materials.Material.allowable`) at the part's wall
thickness (:func:`flyopt.design.wheel.walls`): a casting is weaker in a
thick section (EN 1561, EN 1563). Ductile materials are judged by the von
Mises stress against yield, brittle ones by the largest principal stress
against the tensile strength.

Burst speed: for a ductile wheel where the mean hoop stress of its radial
section reaches the tensile strength, for a brittle one where the governing
stress does; both scale with omega^2 (:func:`flyopt.design.stress.burst_speed`).

Balance: the permissible residual unbalance of ISO 21940-11 grade G6.3,
e_per = G / Omega, U_per = e_per m (:func:`flyopt.design.balance.permissible_unbalance`).

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, section 13.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from flyopt.design import stress, wheel
from flyopt.names import Geometry

if TYPE_CHECKING:
    from flyopt.design.materials import Material

__all__ = ["PartStress", "StrengthCheck", "allowables", "check_wheel", "profile"]


@dataclass(frozen=True)
class PartStress:
    """The governing stress of one part at the checked speed."""

    part: str
    stress: float  # von Mises (ductile) or largest principal (brittle) [Pa]
    radius: float  # where [m]
    allowable: float  # [Pa]
    strength: float  # yield (ductile) or tensile (brittle) strength at the part's wall [Pa]
    wall: float  # the wall thickness the strength was taken at [m]


@dataclass(frozen=True)
class StrengthCheck:
    """The stress check of a wheel at its highest speed (SI)."""

    parts: tuple[PartStress, ...]  # PartStress per stressed part
    max_principal: float
    von_mises: float
    hoop_max: float
    radial_max: float
    where: dict[str, Any]  # {"part", "radius"} of the governing stress (the smallest margin)
    allowable_stress: float  # the governing part's allowable
    strength_safety: float  # min over parts of strength / governing stress
    burst_speed: float  # [rad/s] on the wheel's shaft
    speed_margin: float  # burst_speed / omega
    mean_hoop: float  # mean hoop stress of the radial section [Pa]

    def utilisation(self) -> float:
        """The largest governing stress over allowable of any part [-]."""
        return max(p.stress / p.allowable for p in self.parts)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready plain Python."""
        return {
            "max_principal": self.max_principal,
            "von_mises": self.von_mises,
            "hoop_max": self.hoop_max,
            "radial_max": self.radial_max,
            "where": dict(self.where),
            "parts": [
                {
                    "part": p.part,
                    "stress": p.stress,
                    "radius": p.radius,
                    "allowable": p.allowable,
                    "strength": p.strength,
                    "wall": p.wall,
                }
                for p in self.parts
            ],
        }


def _poisson_ratio(material: Material) -> float:
    """The material's Poisson's ratio ν, which the exact stress check needs; a ValueError naming it otherwise."""
    if material.poisson_ratio is None:
        raise ValueError(f"material {material.name}: the stress check needs its poisson_ratio [-], and none is given")
    return material.poisson_ratio


def _strength_thickness(material, part_wall, all_walls):
    """The thickness a part's strength is read at: its own wall for a casting, the wheel's thickest
    section for a heat-treated forging (the material's ``section_rule``)."""
    if getattr(material, "thickness_rule", "part") == "wheel":
        return max(all_walls.values())
    return part_wall


def allowables(
    material: Material,
    geometry_name: str,
    dims: wheel.Dims,
    safety_factor: float | None = None,
    stress_factors: Mapping[str, float] | None = None,
) -> dict[str, tuple[float, float, float]]:
    """Allowable stress and strength of every stressed part of a wheel.

    Parameters
    ----------
    material : flyopt.design.materials.Material
    geometry_name : str
    dims : flyopt.design.wheel.Dims
        Floats.
    safety_factor : float or None
        The design's factor on strength (None: the material's default).
    stress_factors : mapping or None
        Part -> factor >= 1 on the modelled stress (the FE check's concentration,
        :attr:`flyopt.design.spec.DesignSpec.stress_factors`): that part's allowable is divided by it,
        so that the model's stress times the factor stays within the material's allowable.

    Returns
    -------
    dict of str to (allowable [Pa], strength [Pa], wall [m])
    """
    walls = wheel.walls(geometry_name, dims)
    factors = stress_factors or {}
    out = {}
    for part, wall in walls.items():
        thickness = _strength_thickness(material, wall, walls)
        allowable = material.allowable(thickness=thickness, safety_factor=safety_factor) / factors.get(part, 1.0)
        tensile, yield_ = material.strength(thickness)
        strength = yield_ if material.ductile and yield_ is not None else tensile
        out[part] = (allowable, strength if strength is not None else math.nan, wall)
    return out


def check_wheel(
    material: Material,
    geometry_name: str,
    dims: wheel.Dims,
    omega: float,
    torque: float,
    safety_factor: float | None = None,
    stress_factors: Mapping[str, float] | None = None,
) -> StrengthCheck:
    """Every part's governing stress at omega, the burst speed and the margins.

    Parameters
    ----------
    material : Material
        Needs ``poisson_ratio``; strengths for the burst speed.
    geometry_name : str
    dims : Dims
        Floats.
    omega : float
        The highest speed of the wheel's shaft over the cycle [rad/s].
    torque : float
        The peak torque the wheel exchanges with its shaft [N*m].
    safety_factor : float or None
    stress_factors : mapping or None
        As :func:`allowables`: each part's allowable divided by its factor.

    Returns
    -------
    StrengthCheck
    """
    rho, nu = material.density, _poisson_ratio(material)
    ductile = bool(material.ductile)
    measure = "von_mises" if ductile else "largest_principal"
    state = wheel.stress_state(geometry_name, dims, rho, nu, omega, torque)
    limits = allowables(material, geometry_name, dims, safety_factor, stress_factors)
    worst: dict[str, tuple[float, float]] = {}
    hoop, radial, vm, principal = -math.inf, -math.inf, -math.inf, -math.inf

    def note(part, value, r):
        if part not in worst or value > worst[part][0]:
            worst[part] = (value, r)

    for part, r, sr, st in state.beams:
        sr, st = float(sr), float(st)
        note(part, stress.von_mises(sr, st) if ductile else max(sr, st), float(r))
        hoop, radial = max(hoop, st), max(radial, sr)
        vm, principal = max(vm, stress.von_mises(sr, st)), max(principal, sr, st)
    coefficients = [
        (float(c1), 0.0 if isinstance(c2, (int, float)) and c2 == 0 else float(c2)) for c1, c2 in state.coefficients
    ]
    radii = [float(r) for r in state.radii]
    single = len(coefficients) == 1 and not state.beams
    if single:
        # one free disc (a bare rim, a disc with or without a bore), exactly (Timoshenko & Goodier,
        # art. 32): sigma_t >= sigma_r >= 0 and sigma_t falls outwards, so sigma_t, von Mises
        # (sqrt(st^2 - sr (st - sr)) <= st) and the largest principal stress all peak at the inner
        # edge, where sigma_r = 0 (or, solid, sigma_r = sigma_t); sigma_r peaks at r = sqrt(a b) at
        # (3+nu)/8 rho w^2 (b - a)^2 (at the centre of a solid disc, a = 0)
        a, b = radii
        sr, st = (float(v) for v in stress.disc_stresses(coefficients[0], rho, nu, omega, a))
        note(state.names[0], float(stress.von_mises(sr, st)) if ductile else max(sr, st), a)
        hoop, principal = st, max(st, sr)
        vm = float(stress.von_mises(sr, st))
        radial = (3.0 + nu) / 8.0 * rho * omega**2 * (b - a) ** 2
    elif coefficients:
        # a stepped disc: each measure's maximum over each step, in closed form (the governing
        # measure's per part, every measure's for the report)
        found = stress.max_stresses_per_step(
            coefficients, radii, rho, nu, omega, ("von_mises", "largest_principal", "hoop", "radial")
        )
        for step_max in found[measure]:
            note(state.names[step_max.step], step_max.value, step_max.radius)
        vm = max(vm, *(f.value for f in found["von_mises"]))
        principal = max(principal, *(f.value for f in found["largest_principal"]))
        hoop = max(hoop, *(f.value for f in found["hoop"]))
        radial = max(radial, *(f.value for f in found["radial"]))
    if coefficients:
        mean_hoop = float(
            stress.mean_hoop_stress(coefficients, radii, [float(t) for t in state.thicknesses], rho, nu, omega)
        )
    if geometry_name == Geometry.RIM_ARMS:  # the rim carries the hoop load of an arms wheel
        mean_hoop = float(stress.rim_hoop_stress(rho, omega, dims.d_mean / 2.0))
    parts = tuple(
        PartStress(part, value, r, limits[part][0], limits[part][1], limits[part][2])
        for part, (value, r) in worst.items()
    )
    governing = max(parts, key=lambda p: p.stress / p.allowable)
    safety = min(p.strength / p.stress for p in parts if p.stress > 0) if any(p.stress > 0 for p in parts) else math.inf
    tensile = [
        material.strength(
            p.wall if getattr(material, "thickness_rule", "part") != "wheel" else max(q.wall for q in parts)
        )[0]
        for p in parts
    ]
    if ductile:
        rim_tensile = min(t for t in tensile if t is not None) if any(t is not None for t in tensile) else None
        burst = (
            float(stress.burst_speed_ductile(omega, mean_hoop, rim_tensile))
            if rim_tensile is not None and mean_hoop > 0
            else math.inf
        )
    else:
        burst = min(
            (
                float(stress.burst_speed_brittle(omega, p.stress, t))
                for p, t in zip(parts, tensile)
                if t is not None and p.stress > 0
            ),
            default=math.inf,
        )
    return StrengthCheck(
        parts=parts,
        max_principal=principal,
        von_mises=vm,
        hoop_max=hoop,
        radial_max=radial,
        where={"part": governing.part, "radius": governing.radius},
        allowable_stress=governing.allowable,
        strength_safety=safety,
        burst_speed=burst,
        speed_margin=burst / omega,
        mean_hoop=mean_hoop,
    )


def profile(
    material: Material, geometry_name: str, dims: wheel.Dims, omega: float, torque: float, points: int = 200
) -> tuple[list[tuple[str, NDArray[np.float64], Any, Any, Any]], list[tuple[str, float, float, float]]]:
    """sigma_r, sigma_t and von Mises over the radius of the disc parts, for plots.

    Returns
    -------
    list of (part, r, sr, st, vm) arrays, one per disc part; and the beams' (part, r, sr, st).
    """
    rho, nu = material.density, _poisson_ratio(material)
    state = wheel.stress_state(geometry_name, dims, rho, nu, omega, torque)
    out = []
    for k, c in enumerate(state.coefficients):
        c = (float(c[0]), 0.0 if isinstance(c[1], (int, float)) and c[1] == 0 else float(c[1]))
        r = np.linspace(float(state.radii[k]), float(state.radii[k + 1]), points)
        sr, st = stress.disc_stresses(c, rho, nu, omega, r)
        out.append((state.names[k], r, sr, st, stress.von_mises(sr, st)))
    return out, [(p, float(r), float(sr), float(st)) for p, r, sr, st in state.beams]
