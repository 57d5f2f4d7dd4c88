"""The structural check of many bare wheels at once: a rim, a thin rim or a disc without a bore.

A bare wheel is one free annulus (or a solid disc), so its check is closed
form: :func:`flyopt.design.strength.check_wheel` takes its maxima at the
inner edge, and :func:`flyopt.design.wheel_design.structure_fields` adds its
parts, rim speed, hoop stress and permissible unbalance. A ranking of the
closed-form designs (:func:`flyopt.design.design_flywheel`, ``method="auto"``)
checks every candidate it reports, a few at a time; one at a time, that check
was about half of the ranking's time, all of it Python's per-call overhead.

:func:`structures` runs the same check over the candidates of a ranking in
one pass: the arithmetic on numpy arrays through the same functions the
scalar check calls (:func:`flyopt.design.wheel.parts`,
:func:`flyopt.design.wheel.stress_state`, :mod:`flyopt.design.stress`,
:mod:`flyopt.design.geometry`, :func:`flyopt.design.balance.unbalance`), so
each number is made by the same operations in the same order and is the
same float; the material's strengths by the one rule,
:func:`flyopt.design.strength.allowables`, per candidate. A candidate that
leaves the closed form's ground (a material without Poisson's ratio, a
section outside its strength table, a rim grown to a disc) is checked by
:func:`~flyopt.design.wheel_design.structure_fields` itself, which writes
the note that says why. ``tests/design/test_bare_check.py`` holds the two
equal, float for float, over random designs and every shipped material.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.design import balance, geometry, strength, stress, wheel, wheel_design
from flyopt.design.result import Parts, Stresses
from flyopt.names import Geometry

if TYPE_CHECKING:  # annotations only
    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec

__all__ = ["covers", "structures"]


def covers(geometry_name: str, dims: wheel.Dims) -> bool:
    """Whether :func:`structures` checks a wheel in closed form: a bare geometry without a bore."""
    return geometry_name in geometry.BARE and dims.bore == 0


def _finite_or_none(x: float) -> float | None:
    return x if math.isfinite(x) else None


def structures(
    materials: Sequence[Material],
    geometry_name: str,
    dims: Sequence[wheel.Dims],
    omega: Sequence[float],
    torque: Sequence[float],
    spec: DesignSpec,
) -> list[wheel_design.Structure]:
    """The structure of each of many designed bare wheels, as :func:`~flyopt.design.wheel_design.structure_fields`.

    Parameters
    ----------
    materials : sequence of Material
        Per wheel.
    geometry_name : {"rim", "thin_rim", "disc"}
        The geometry of every wheel.
    dims : sequence of flyopt.design.wheel.Dims
        Per wheel, floats, without a bore.
    omega, torque : sequence of float
        Per wheel: the highest speed of its shaft [rad/s] and the peak torque on it [N*m].
    spec : DesignSpec
        For its safety factor.

    Returns
    -------
    list of flyopt.design.wheel_design.Structure
        In the order given, each equal to ``structure_fields(material,
        geometry_name, dims, omega, torque, spec, 0.0)``.
    """
    n = len(dims)
    if n == 0:
        return []
    if any(not covers(geometry_name, d) for d in dims):
        raise ValueError(f"the closed-form check covers {sorted(geometry.BARE)} without a bore")
    # a rim whose inner diameter is exactly 0 is a solid disc to the scalar check (its c2 is the plain
    # zero there, so r = 0 is never divided by); it is left to that check
    plain = [
        k
        for k in range(n)
        if materials[k].poisson_ratio is not None
        and (geometry_name == Geometry.DISC or dims[k].d_outer - 2.0 * dims[k].h != 0.0)
    ]
    out: list[Any] = [None] * n
    if plain:
        _check_plain(out, plain, materials, geometry_name, dims, omega, torque, spec)
    for k in range(n):  # outside the closed form's ground: the scalar check, which says why in a note
        if out[k] is None:
            out[k] = wheel_design.structure_fields(materials[k], geometry_name, dims[k], omega[k], torque[k], spec, 0.0)
    return out


def _check_plain(out, index, materials, geometry_name, dims, omega, torque, spec):
    """Fill ``out[k]`` for each k of ``index`` whose strengths the material gives (the rest stay None)."""
    mats = [materials[k] for k in index]
    ds = [dims[k] for k in index]
    rho = np.array([m.density for m in mats])
    nu = np.array([m.poisson_ratio for m in mats], dtype=float)
    w = np.array([omega[k] for k in index], dtype=float)
    t = np.array([torque[k] for k in index], dtype=float)
    many = wheel.Dims(
        d_outer=np.array([d.d_outer for d in ds], dtype=float),
        h=np.array([d.h for d in ds], dtype=float),
        b=np.array([d.b for d in ds], dtype=float),
    )
    # structure_fields: the parts, their mass, the rim speed, the hoop stress and the unbalance
    (part,) = wheel.parts(geometry_name, many, rho)
    mass = wheel.wheel_mass([part])
    u_per = balance.unbalance(mass, w, balance.BALANCE_GRADE)[1]
    speed = geometry.rim_speed(w, many.d_outer)
    hoop = geometry.hoop_stress(rho, speed)
    # strength.check_wheel of one free disc: sigma_t, von Mises and the largest principal stress at
    # the inner edge, sigma_r at sqrt(a b) (see check_wheel)
    state = wheel.stress_state(geometry_name, many, rho, nu, w, t)
    (coefficients,) = state.coefficients
    a, b = state.radii
    sr, st = stress.disc_stresses(coefficients, rho, nu, w, a)
    mean_hoop = stress.mean_hoop_stress([coefficients], state.radii, state.thicknesses, rho, nu, w)
    columns: tuple[Any, ...] = (
        part.mass,
        part.inertia,
        part.r_inner,
        part.r_outer,
        part.thickness,
        u_per,
        speed,
        hoop,
        sr,
        st,
    )
    columns += (mean_hoop, a, b)
    rows = zip(*(c.tolist() if np.ndim(c) else [float(c)] * len(index) for c in columns))
    (name,) = state.names
    for j, (k, m, row) in enumerate(zip(index, mats, rows)):
        p_mass, p_inertia, r_inner, r_outer, thickness, unbalance, v, sigma_v = row[:8]
        sr_k, st_k, mean_k, a_k, b_k = row[8:]
        try:
            ((allowable, strength_k, wall),) = strength.allowables(m, geometry_name, ds[j], spec.safety_factor).values()
            tensile = m.strength(wall)[0]
        except ValueError:  # a section outside the strength table: the scalar check writes the note
            continue
        ductile = bool(m.ductile)
        omega_k = float(omega[k])
        # powers of floats, as the scalar check takes them (numpy's square and square root may round differently)
        vm_k = stress.von_mises(sr_k, st_k)
        radial_k = (3.0 + m.poisson_ratio) / 8.0 * m.density * omega_k**2 * (b_k - a_k) ** 2
        governing = vm_k if ductile else max(sr_k, st_k)
        safety = strength_k / governing if governing > 0 else math.inf
        if ductile:
            burst = (
                stress.burst_speed_ductile(omega_k, mean_k, tensile) if tensile is not None and mean_k > 0 else math.inf
            )
        else:
            burst = (
                stress.burst_speed_brittle(omega_k, governing, tensile)
                if tensile is not None and governing > 0
                else math.inf
            )
        burst = float(burst)
        check = {
            "max_principal": max(st_k, sr_k),
            "von_mises": vm_k,
            "hoop_max": st_k,
            "radial_max": radial_k,
            "where": {"part": name, "radius": a_k},
            "parts": [
                {
                    "part": name,
                    "stress": governing,
                    "radius": a_k,
                    "allowable": allowable,
                    "strength": strength_k,
                    "wall": wall,
                }
            ],
            "mean_hoop": mean_k,
        }
        items = (
            {
                "name": part.name,
                "mass": p_mass,
                "inertia": p_inertia,
                "r_inner": r_inner,
                "r_outer": r_outer,
                "thickness": thickness,
            },
        )
        stresses = Stresses(
            rim_speed=v,
            hoop_stress=sigma_v,
            safety_factor=m.allowable_stress / sigma_v if m.allowable_stress else None,
            unbalance_permissible=unbalance,
            stress=check,
            allowable_stress=allowable,
            strength_safety=_finite_or_none(safety),
            burst_speed=_finite_or_none(burst),
            speed_margin=_finite_or_none(burst / omega_k),
        )
        out[k] = wheel_design.Structure(Parts(items, None), stresses, ())
