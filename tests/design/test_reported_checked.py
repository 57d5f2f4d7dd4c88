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
