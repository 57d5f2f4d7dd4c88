"""The geometry section: inertia of the thin-rim and exact-annulus models, and what the thin rim costs.

Both models against the exact integral of r² dm over the annulus (rational
arithmetic, :func:`flyopt.bench.references.exact_annulus_inertia`) over
H/D_m, and at the optimal designs of the design section's random scenes.
flyopt builds no hub-and-arms model, so the annulus is the most detailed
model there is.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from flyopt.bench.design import random_design_scenes
from flyopt.bench.references import exact_annulus_inertia
from flyopt.bench.timing import Config, Row, measure, set_ratios
from flyopt.design import design_flywheel, geometry

__all__ = ["section_geometry"]


def section_geometry(config: Config) -> list[Row]:
    """Inertia of thin rim and exact annulus against the exact integral, over H/D_m."""
    rows = []
    density, d_mean = 7200.0, 1.0
    for ratio in (0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0):
        h = ratio * d_mean
        b = h / 1.5
        ref = exact_annulus_inertia(d_mean + h, d_mean - h, b, density)
        models = {
            "thin_rim": lambda: geometry.thin_rim_inertia(geometry.rim_mass(d_mean, h, b, density), d_mean),
            "rim": lambda: geometry.rim_inertia(geometry.rim_mass(d_mean, h, b, density), d_mean, h),
        }
        if ratio == 1.0:  # the annulus with no hole is the disc
            models["disc"] = lambda: geometry.disc_inertia(geometry.disc_mass(2 * h, b, density), 2 * h)
        for name, fn in models.items():
            value = fn()
            timing = measure(fn, config.repeats, config.min_time)
            err = abs(value - ref) / ref
            rows.append(
                Row.timed(
                    "geometry",
                    f"H/D_m={ratio:g}",
                    name,
                    f"H/D_m={ratio:g}",
                    timing,
                    error=err,
                    error_median=err,
                    reference="exact integral of r^2 dm over the annulus (rationals)",
                    note=f"J {value:.12g} vs {ref:.12g} kg*m^2"
                    + ("; thin rim is low (safe side)" if name == "thin_rim" else ""),
                )
            )
    rows += _geometry_at_designs(config)
    rows.append(
        Row(
            "geometry",
            "hub and arms",
            "rim-hub-arms",
            "not built",
            math.nan,
            math.nan,
            math.nan,
            0,
            0,
            verdicts_ok=0,
            verdicts_total=0,
            note="flyopt has no hub-and-arms model; the exact annulus is the most detailed model",
        )
    )
    set_ratios(rows, lambda r: r.method == "rim")
    return rows


def _geometry_at_designs(config):
    """Thin rim vs annulus at the optimal designs of the design scenes, and the mass it costs.

    Each scene is designed twice by flyopt (geometry rim and thin_rim, same
    limits); the thin-rim model's inertia error is taken at the exact-annulus
    optimum, and the mass penalty is the thin-rim winner's mass over the
    annulus winner's.
    """
    errors, penalties, times = [], [], []
    for scene in random_design_scenes(min(config.scenes, 20), config.seed):
        args = (scene["j_required"], scene["omega_mean"], scene["shafts"], scene["materials"])
        exact = design_flywheel(*args, replace(scene["spec"], geometry="rim")).best
        thin = design_flywheel(*args, replace(scene["spec"], geometry="thin_rim")).best
        if exact is None or thin is None:
            continue
        rho = next(m.density for m in scene["materials"] if m.name == exact.material)
        d_outer, h, b = exact.dims.d_outer, exact.dims.h, exact.dims.b
        ref = exact_annulus_inertia(d_outer, d_outer - 2 * h, b, rho)

        def thin_model(dims=exact.dims, rho=rho):
            return geometry.thin_rim_inertia(geometry.rim_mass(dims.d_mean, dims.h, dims.b, rho), dims.d_mean)

        times.append(measure(thin_model, max(3, config.repeats // 3), config.min_time).median)
        errors.append(abs(thin_model() - ref) / ref)
        penalties.append(thin.mass / exact.mass - 1.0)
    if not errors:
        return []
    t = float(np.median(times))
    return [
        Row(
            "geometry",
            "optimal designs",
            "thin_rim",
            f"{len(errors)} designs",
            t,
            float(np.quantile(times, 0.25)),
            float(np.quantile(times, 0.75)),
            max(3, config.repeats // 3),
            1,
            error=max(errors),
            error_median=float(np.median(errors)),
            reference="exact integral of r^2 dm over the annulus (rationals)",
            note=f"inertia error at the exact-annulus optima of the design scenes (worst; median "
            f"{np.median(errors):.2e}); designing with the thin-rim model costs {100 * np.median(penalties):.3g} % "
            f"more mass (median; worst {100 * max(penalties):.3g} %)",
        )
    ]
