"""Sections kept within the material's strength-by-thickness table (issue 13).

A casting's strength is given only up to the thickest section of its table
(EN-GJS-400-18: t <= 30 mm on file); beyond it flyopt extrapolates nothing.
Where the lightest wheel has a thicker section, the designer solves again with
that section capped at the table's end, trying each way a part's wall (the
smaller of its two section sizes) can be brought within it, and keeps the
lightest. Checked against a brute-force search of every rim on a dense grid of
outer diameters and radial thicknesses (the width then follows from the
inertia), which knows nothing of the branching.
"""

import math

import numpy as np
import pytest

from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.castability import Overrides
from flyopt.design.materials import builtin_materials

GJS = builtin_materials(default_only=False)["en_gjs_400_18"]
OMEGA, ENVELOPE, WIDTH, MIN_WALL, FACTOR = 12.0, 1.2, 0.05, 0.008, 5.0
SPEC = DesignSpec(
    geometry="rim",
    criterion="stress",
    safety_factor=FACTOR,
    max_outer_diameter=ENVELOPE,
    max_width=WIDTH,
    hb_ratio=(0.5, 2.0),
    min_wall=MIN_WALL,
)


def brute_force_rim(j):
    """The lightest rim on a 1,500 x 4,000 grid of (D_outer, H): B = 2 J / (pi rho (r_o^4 - r_i^4)), then every
    limit (width, H/B, min_wall, the table's 30 mm on min(H, B), the hoop stress at the bore) checked."""
    rho, nu = GJS.density, GJS.poisson_ratio
    allowable = GJS.allowable(thickness=0.03, safety_factor=FACTOR)
    d = np.linspace(0.5, ENVELOPE, 1500)[:, None]
    h = np.linspace(MIN_WALL, 0.25, 4000)[None, :]
    r_o, r_i = d / 2.0, d / 2.0 - h
    with np.errstate(invalid="ignore", divide="ignore"):
        b = 2.0 * j / (math.pi * rho * (r_o**4 - r_i**4))
        hoop = (3.0 + nu) / 4.0 * rho * OMEGA**2 * (r_o**2 + (1.0 - nu) / (3.0 + nu) * r_i**2)
        ok = (
            (r_i > 0)
            & (b <= WIDTH)
            & (b >= MIN_WALL)
            & (h / b >= 0.5)
            & (h / b <= 2.0)
            & (np.minimum(h, b) <= 0.03)
            & (hoop <= allowable)
        )
        mass = np.where(ok, rho * math.pi * (r_o**2 - r_i**2) * b, np.inf)
    return float(mass.min())


def test_a_rim_beyond_the_table_is_designed_within_it():
    """J = 14 kg m^2: the lightest rim (B at the 50 mm width limit) would have walls over 30 mm; capped,
    B = 30 mm and H = 56 mm; the mass is the grid's least to its resolution, and no lighter."""
    result = design_flywheel(14.0, OMEGA, [MountShaft("main", 1.0)], [GJS], SPEC)
    best = result.best
    assert result.status == "designed" and "strength_table" in best.limits.binding
    assert min(best.dims.h, best.dims.b) <= 0.03
    assert max(p["wall"] for p in best.stresses.stress["parts"]) <= 0.03
    reference = brute_force_rim(14.0)
    assert best.mass <= reference * (1.0 + 1e-9)  # at least as light as every grid rim
    assert best.mass >= reference * (1.0 - 2e-3)  # and no lighter than the grid's resolution allows


def test_a_rim_no_section_within_the_table_can_make_is_infeasible():
    """J = 16 kg m^2: no rim within 30 mm walls gives it (the grid finds none either); said in one line."""
    result = design_flywheel(16.0, OMEGA, [MountShaft("main", 1.0)], [GJS], SPEC)
    assert result.status == "infeasible"
    assert "strength table, which ends at 30 mm" in result.candidates[0].reason
    assert brute_force_rim(16.0) == math.inf


@pytest.mark.parametrize("geometry", ["rim_web", "rim_arms"])
def test_whole_wheels_keep_every_section_within_the_table(geometry):
    """Web and arms wheels heavy enough to want thick sections: every part's wall ends within the table.
    Without castability (process "none"): its section ratio would bind first on the arms wheel, and this
    tests the table's own limit."""
    spec = DesignSpec(
        castability=Overrides(process="none"),
        geometry=geometry,
        criterion="stress",
        safety_factor=FACTOR,
        max_outer_diameter=ENVELOPE,
        max_width=0.3,
        hb_ratio=(0.5, 2.0),
        min_wall=MIN_WALL,
        arms=(6,),
    )
    j = {"rim_web": 40.0, "rim_arms": 18.0}[geometry]
    result = design_flywheel(j, OMEGA, [MountShaft("main", 1.0, 0.05)], [GJS], spec, torque=500.0)
    assert result.status == "designed" and "strength_table" in result.best.limits.binding
    assert max(p["wall"] for p in result.best.stresses.stress["parts"]) <= 0.03
