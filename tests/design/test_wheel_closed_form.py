"""The disc under the stress criterion: its closed form against IPOPT, design and sensitivities.

Two independent methods: the exact closed form (the widest disc the hoop
stress at the bore, or at the centre, and the envelope allow, m = 2 J/(a^2+b^2),
with its derivatives written out) and IPOPT on the wheel NLP (stress rows at
nine radii, multipliers of the binding limits). They must agree on the mass
(IPOPT's tolerance 1e-10 on log m: 1e-9 relative) and on every reported
sensitivity (1e-6: the multipliers of a converged solve).
"""

import itertools

import pytest

from flyopt.design import DesignSpec, MountShaft, design_flywheel
from flyopt.design.castability import Overrides
from flyopt.design.materials import make_material

DUCTILE = make_material(
    "gjs", 7100, tensile_strength=400e6, yield_strength=250e6, ductile=True, safety_factor=4, poisson_ratio=0.28
)
BRITTLE = make_material("gjl", 7200, tensile_strength=250e6, ductile=False, safety_factor=8, poisson_ratio=0.26)
CASES = list(itertools.product([DUCTILE, BRITTLE], [0.0, 0.06, 0.15], [10.0, 1.0], [5.0, 50.0, 500.0]))


@pytest.mark.parametrize("material, bore, envelope, j", CASES)
def test_disc_closed_form_agrees_with_ipopt(material, bore, envelope, j):
    # without castability (the materials' keys name iron processes, whose minimum wall the closed form does
    # not cover; a disc at that wall is IPOPT's: tests/design/test_castability.py)
    spec = DesignSpec(
        geometry="disc",
        criterion="stress",
        bore=bore,
        max_outer_diameter=envelope,
        castability=Overrides("none"),
    )
    shafts = [MountShaft("s", 1.0)]
    exact = design_flywheel(j, 160.0, shafts, [material], spec)
    solved = design_flywheel(j, 160.0, shafts, [material], spec, method="ipopt")
    assert exact.status == solved.status
    if exact.best is None:
        return
    assert exact.best.provenance.solver_status == "closed_form"
    assert solved.best.provenance.solver_status in ("Solve_Succeeded", "Solved_To_Acceptable_Level")
    assert exact.best.mass == pytest.approx(solved.best.mass, rel=1e-9)
    assert exact.best.dims.d_outer == pytest.approx(solved.best.dims.d_outer, rel=1e-8)
    by_limit = {s["limit"]: s["dmass_dlimit"] for s in solved.best.limits.sensitivities}
    assert {s["limit"] for s in exact.best.limits.sensitivities} == set(by_limit)
    for s in exact.best.limits.sensitivities:
        assert s["dmass_dlimit"] == pytest.approx(by_limit[s["limit"]], rel=1e-6)
