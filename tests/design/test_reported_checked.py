"""Every candidate a ranking reports carries its structural check, the one its dimensions give.

The ranking reports every feasible candidate (``DesignResult.candidates``,
printed whole by ``flyopt solve --json`` and the report), so each must carry
its parts, stresses, burst speed and unbalance: a check skipped for the
losers, or made on other dimensions, fails here (one made when a candidate
is first read, Design.checked_when_read, is made here). Reference: the one-at-a-time
check, :func:`flyopt.design.wheel_design.structure_fields`, of the reported
dimensions.
"""

import math
import random

import pytest

from flyopt.design import Design, DesignSpec, MountShaft, design_flywheel, wheel, wheel_design
from flyopt.design.materials import builtin_materials

MATERIALS = list(builtin_materials(default_only=False).values())


def _scenes(rng, geometry_name, count):
    for _ in range(count):
        omega = 10 ** rng.uniform(math.log10(50), math.log10(3000)) * math.pi / 30
        shafts = [
            MountShaft("reference", 1.0),
            MountShaft("slower", 10 ** rng.uniform(-1.0, 0.0)),
            MountShaft("faster", 10 ** rng.uniform(0.0, 1.0)),
        ]
        width = 10 ** rng.uniform(-1.5, 0.0) if rng.random() < 0.5 or geometry_name == "disc" else None
        spec = DesignSpec(geometry_name, hb_ratio=(1.5, 2.0), max_width=width, safety_factor=3.0)
        yield 10 ** rng.uniform(-3, 3), omega, shafts, rng.sample(MATERIALS, 3), spec


@pytest.mark.parametrize("method", ["auto", "closed_form"])
@pytest.mark.parametrize("geometry_name", ["rim", "thin_rim", "disc"])
def test_every_reported_candidate_carries_its_structural_check(method, geometry_name):
    rng = random.Random(f"{method}-{geometry_name}")
    reported = checked = 0
    for j, omega, shafts, materials, spec in _scenes(rng, geometry_name, 25):
        result = design_flywheel(j, omega, shafts, materials, spec, method=method)
        by_name = {m.name: m for m in materials}
        speed = {s.name: omega * s.speed_ratio for s in shafts}
        rows = result.to_dict()["design"]["candidates"]
        assert len(rows) == len(result.candidates)
        for candidate, row in zip(result.candidates, rows):
            if not isinstance(candidate, Design):
                continue
            reported += 1
            d = candidate.dims
            dims = wheel.Dims(d_outer=d.d_outer, h=d.d_outer / 2.0 if geometry_name == "disc" else d.h, b=d.b)
            ref = wheel_design.structure_fields(
                by_name[candidate.material], geometry_name, dims, speed[candidate.shaft], 0.0, spec, 0.0
            )
            assert candidate.parts == ref.parts and candidate.stresses == ref.stresses, candidate.reason
            assert candidate.parts.items
            # checked, or the check says why not (a section beyond the material's strength table)
            assert candidate.stresses.stress or any("not computed" in note for note in candidate.provenance.notes)
            checked += bool(candidate.stresses.stress)
            assert candidate.stresses.unbalance_permissible > 0
            # and what is printed is that check
            assert row["stress"] == ref.stresses.stress and row["parts"] == list(ref.parts.items)
    assert reported > 50 and checked > reported // 2


@pytest.mark.parametrize("geometry_name", ["rim", "thin_rim", "disc"])
def test_every_reported_design_says_what_binds_as_its_dimensions_show(geometry_name):
    """Each design's description (its reason, limits and provenance) is made when first read; what it says is
    checked here against the scene itself: the inertia on its shaft J_F / r^2, its outer-diameter cap
    min(2 v_max / (omega r), envelope) from the material's rim speed limit, and what its dimensions meet. The
    lightest wheel of a free mean diameter sits at its cap (J grows with D faster than the mass does) and gives
    exactly the inertia asked for."""
    rng = random.Random(f"binding-{geometry_name}")
    materials = [builtin_materials()[m] for m in ("cast_iron", "cast_steel")]
    designs = 0
    for _ in range(20):
        j, omega = 10 ** rng.uniform(-2, 3), 10 ** rng.uniform(math.log10(50), math.log10(3000)) * math.pi / 30
        shafts = [MountShaft("reference", 1.0), MountShaft("faster", 10 ** rng.uniform(0.0, 1.0))]
        envelope = 2 * 36.0 / omega * rng.uniform(0.5, 1.5) if rng.random() < 0.5 else None
        spec = DesignSpec(
            geometry_name, max_outer_diameter=envelope, max_width=0.5 if geometry_name == "disc" else None
        )
        result = design_flywheel(j, omega, shafts, materials, spec)
        ratio = {s.name: s.speed_ratio for s in shafts}
        display = {m.name: m.display_name for m in materials}
        for c in result.candidates:
            if not isinstance(c, Design):
                continue
            designs += 1
            # the ranking described none of its designs; but a disc at its cap has mass 8 J' / D^2 = 8 J_F / C^2 on
            # every shaft: the rule then breaks the tie on the rim speed, which the structural check gives
            assert "_make" in vars(c) or geometry_name == "disc"
            r, v_max = ratio[c.shaft], {"cast_iron": 36.0, "cast_steel": 50.0}[c.material]
            cap_speed = 2.0 * v_max / (omega * r)
            cap = min(cap_speed, envelope or math.inf)
            lim = c.limits
            assert lim.j_required_on_shaft == pytest.approx(j / r**2, rel=1e-14)
            assert lim.d_outer_limit == pytest.approx(cap, rel=1e-14) and lim.rim_speed_limit == v_max
            assert c.dims.d_outer == pytest.approx(cap, rel=1e-9) and c.j_flywheel == pytest.approx(j / r**2)
            assert "inertia" in lim.binding
            assert ("rim_speed" in lim.binding) == (cap_speed <= (envelope or math.inf) * (1 + 1e-9))
            assert ("max_outer_diameter" in lim.binding) == (
                envelope is not None and envelope <= cap_speed * (1 + 1e-9)
            )
            shaft = c.shaft if c.shaft.endswith("shaft") else f"{c.shaft} shaft"
            assert c.reason == f"{display[c.material]} on the {shaft}: designed; binding: {', '.join(lim.binding)}"
            assert c.provenance.solver_status == "closed_form" and c.provenance.iterations == 0
            assert "_make" not in vars(c)
    assert designs > 40


def test_a_design_by_ipopt_says_how_it_was_found_when_read():
    """IPOPT's designs are described when read as the closed form's are: the solver's status and its iteration
    count (IPOPT takes at least one), and the inertia binding (the wheel gives what is asked)."""
    shafts = [MountShaft("reference", 1.0), MountShaft("faster", 3.0)]
    materials = [builtin_materials()[m] for m in ("cast_iron", "cast_steel")]
    result = design_flywheel(40.0, 60.0, shafts, materials, DesignSpec("rim"), method="ipopt")
    designs = [c for c in result.candidates if isinstance(c, Design)]
    assert len(designs) >= 2
    for c in designs:
        assert "_make" in vars(c)
        assert c.provenance.solver_status == "Solve_Succeeded" and c.provenance.iterations > 0
        assert "inertia" in c.limits.binding and c.reason.endswith(", ".join(c.limits.binding))


def test_a_rim_the_books_way_says_its_mean_diameter_binds():
    """Under criterion mean_rim_speed the rim's mean diameter is pinned where it reaches v_max at the mean speed,
    D_m = 2 v_max / omega_m (docs/flywheel-design.md, section 20): the description says so."""
    omega_mean = 80.0
    spec = DesignSpec("rim", criterion="mean_rim_speed")
    cast_iron = builtin_materials()["cast_iron"]
    result = design_flywheel(
        50.0, omega_mean * 1.02, [MountShaft("crank", 1.0)], [cast_iron], spec, omega_mean=omega_mean
    )
    (c,) = result.candidates
    assert c.dims.d_mean == pytest.approx(2.0 * 36.0 / omega_mean, rel=1e-14)
    assert "mean_rim_speed" in c.limits.binding and c.reason.endswith("mean_rim_speed")
