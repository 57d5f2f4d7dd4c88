"""The structural check of many bare wheels at once equals the one-at-a-time check, float for float.

Reference: :func:`flyopt.design.wheel_design.structure_fields` (the check of
every design flyopt reports), called on each wheel alone. The batch must give
the same floats (compared by ``repr``, so any difference in the last bit
fails), the same notes where it hands a wheel back to that check, and the same
values whatever the other wheels of the batch are.
"""

import math
import random

import pytest

from flyopt.design import DesignSpec, balance, bare_check, wheel, wheel_design
from flyopt.design.materials import builtin_materials, make_material

MATERIALS = list(builtin_materials(default_only=False).values()) + [
    make_material("no_poisson", 7000.0, 30.0),  # no Poisson's ratio: stresses not computed (a note)
    make_material("given_allowable", 7800.0, allowable_stress=80e6, poisson_ratio=0.3),
    make_material(
        "ductile",
        7800.0,
        poisson_ratio=0.3,
        tensile_strength=500e6,
        yield_strength=300e6,
        ductile=True,
        safety_factor=3,
    ),
    make_material("brittle", 7100.0, poisson_ratio=0.25, tensile_strength=200e6, ductile=False, safety_factor=4),
]


def _random_batch(rng, geometry_name):
    n = rng.randint(1, 8)
    materials, dims = [], []
    for _ in range(n):
        materials.append(rng.choice(MATERIALS))
        d = 10 ** rng.uniform(-1.5, 0.7)
        b = 10 ** rng.uniform(-2.5, -0.3)  # up to 0.5 m: beyond the end of some strength tables
        h = d / 2.0 if geometry_name == "disc" or rng.random() < 0.1 else d * rng.uniform(0.01, 0.5)
        dims.append(wheel.Dims(d_outer=d, h=h, b=b))
    omega = [10 ** rng.uniform(0.5, 3.0) for _ in range(n)]
    torque = [rng.choice([0.0, 150.0]) for _ in range(n)]
    return materials, dims, omega, torque


@pytest.mark.parametrize("geometry_name", ["rim", "thin_rim", "disc"])
@pytest.mark.parametrize("safety_factor", [None, 2.5])
def test_batch_equals_one_at_a_time_check(geometry_name, safety_factor):
    rng = random.Random(f"{geometry_name}-{safety_factor}")
    spec = DesignSpec(geometry_name, safety_factor=safety_factor)
    seen_notes = seen_burst = 0
    for _ in range(150):
        materials, dims, omega, torque = _random_batch(rng, geometry_name)
        got = bare_check.structures(materials, geometry_name, dims, omega, torque, spec)
        assert len(got) == len(dims)
        for k, structure in enumerate(got):
            ref = wheel_design.structure_fields(materials[k], geometry_name, dims[k], omega[k], torque[k], spec, 0.0)
            assert repr(structure) == repr(ref), (materials[k].name, dims[k], omega[k])
            seen_notes += bool(ref.notes)
            seen_burst += ref.stresses.burst_speed is not None
    assert seen_notes and seen_burst  # both grounds were exercised: handed back with a note, and checked


def test_batch_of_none_and_refusals():
    spec = DesignSpec("rim")
    assert bare_check.structures([], "rim", [], [], [], spec) == []
    with pytest.raises(ValueError, match="without a bore"):
        bare_check.structures(
            MATERIALS[:1], "rim", [wheel.Dims(d_outer=1.0, h=0.2, b=0.1, bore=0.05)], [1.0], [0.0], spec
        )
    with pytest.raises(ValueError, match="without a bore"):
        bare_check.structures(MATERIALS[:1], "rim_web", [wheel.Dims(d_outer=1.0, h=0.2, b=0.1)], [1.0], [0.0], spec)


def test_unbalance_formula_is_the_checked_one():
    # ISO 21940-11 example of permissible_unbalance's docstring: G 6.3, 3000 rev/min, 100 kg
    omega = 3000 * math.pi / 30
    checked = balance.permissible_unbalance(100.0, omega)
    assert balance.unbalance(100.0, omega) == (checked.e_per, checked.u_per)
    assert checked.u_per == pytest.approx(2.005e-3, rel=1e-3)
