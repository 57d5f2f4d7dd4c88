"""Whole-wheel combinations left undesigned because a bound shows they cannot win (issue 13).

The designer takes the whole-wheel combinations in the order of a lower bound
on their objective (m >= 4 J/D_cap², a cost of that mass times the price, an
outer diameter of at least the solid cylinder's within the width limit) and
does not solve one whose bound exceeds a design already found. Checked here
against designing every combination (``prune = False``) on random problems of
every whole-wheel geometry and objective:

- the winner is the same combination with the same design;
- every designed combination's objective is at least its bound (the bound is
  a bound: checked on the designs themselves, not on the bound's formula);
- every pruned combination is, designed, either infeasible or worse than the
  winner, and its reported bound is at most its designed objective;
- the infeasible ones are the same either way, in the same order (but for
  those pruned before IPOPT could find them infeasible).
"""

import dataclasses
import math

import numpy as np
import pytest

from flyopt.design import DesignSpec, MountShaft, design_flywheel, wheel_design, wheel_nlp
from flyopt.design.combination import Combination
from flyopt.design.materials import make_material
from flyopt.design.rank import TIE_RTOL
from flyopt.errors import SolverFailed


def _materials(rng, cost):
    """Two or three ductile or brittle materials of random strength and density (and a price, for "cost")."""
    out = []
    for k in range(int(rng.integers(2, 4))):
        ductile = bool(rng.random() < 0.6)
        tensile = rng.uniform(250e6, 600e6)
        out.append(
            make_material(
                f"m{k}",
                rng.uniform(6900.0, 7900.0),
                poisson_ratio=rng.uniform(0.22, 0.3),
                tensile_strength=tensile,
                yield_strength=tensile * rng.uniform(0.55, 0.8) if ductile else None,
                ductile=ductile,
                safety_factor=rng.uniform(3.0, 6.0),
                elastic_modulus=170e9,
                max_rim_speed=rng.uniform(30.0, 60.0),
                min_wall=0.006,
                cost=rng.uniform(1.0, 5.0) if cost else None,
            )
        )
    return out


def random_problem(seed):
    """(j_required, omega, shafts, materials, spec): several shafts of several speeds and seats."""
    rng = np.random.default_rng(seed)
    geometry = ("rim_web", "rim_arms", "disc", "rim")[seed % 4]
    objective = ("mass", "mass", "cost", "outer_diameter")[(seed // 4) % 4]
    criterion = "stress" if geometry in ("disc", "rim") or rng.random() < 0.7 else "rim_speed"
    omega = rng.uniform(40.0, 120.0)
    shafts = [
        MountShaft("slow", 1.0, rng.uniform(0.08, 0.12)),
        MountShaft("middle", rng.uniform(2.0, 4.0), rng.uniform(0.05, 0.08)),
        MountShaft("fast", rng.uniform(6.0, 12.0), rng.uniform(0.03, 0.05)),
    ]
    # an inertia a 1 m wheel of about 100 kg gives on the slow shaft
    j = rng.uniform(10.0, 40.0)
    spec = DesignSpec(
        geometry=geometry,
        criterion=criterion,
        objective=objective,
        hb_ratio=(0.5, 2.0),
        max_outer_diameter=rng.uniform(0.9, 1.6),
        max_width=rng.uniform(0.15, 0.3) if objective == "outer_diameter" or rng.random() < 0.5 else math.inf,
        arms=(4, 6) if geometry == "rim_arms" else (4, 6, 8),
    )
    return j, omega, shafts, _materials(rng, objective == "cost"), spec


#: How far below its bound a design's objective may sit: the bound holds where the NLP's rows hold, and a
#: converged SQP meets an active row (the inertia's, log J >= log J_required) to its tol_pr, from either side
#: (its DAQP steps leave the last iterate 1e-12 on either side of an active row; IPOPT stops inside them).
BELOW_BOUND = wheel_nlp.SQP_OPTIONS["tol_pr"]


def _key(c):
    return (c.material, c.shaft, c.n_arms)


def compare(seed):
    j, omega, shafts, materials, spec = random_problem(seed)
    torque = 2.0 * j * omega  # some torque for the arms and the key
    pruned = design_flywheel(j, omega, shafts, materials, spec, torque=torque)
    full = design_flywheel(j, omega, shafts, materials, dataclasses.replace(spec, prune=False), torque=torque)
    assert not any(c.provenance.pruned for c in full.candidates)
    assert pruned.status == full.status
    by_key = {_key(c): c for c in full.candidates}
    assert set(by_key) == {_key(c) for c in pruned.candidates}
    if full.best is not None:
        assert _key(pruned.best) == _key(full.best)
        assert pruned.best.mass == full.best.mass and pruned.best.dims.d_outer == full.best.dims.d_outer
    # the bound holds on every design, whichever run made it
    for c in full.candidates:
        combo = Combination(
            material=next(m for m in materials if m.name == c.material),
            shaft=next(s for s in shafts if s.name == c.shaft),
            omega=omega * c.speed_ratio,
            j_shaft=c.limits.j_required_on_shaft,
            j_reference=j,
            cap_speed=math.inf,
            cap=c.limits.d_outer_limit,
        )
        bound, _why = wheel_design.objective_bound(combo, spec)
        if c.feasible:
            assert c.objective >= bound * (1.0 - BELOW_BOUND), (c.reason, c.objective, bound)
    for c in pruned.candidates:
        twin = by_key[_key(c)]
        if c.provenance.pruned:
            assert c.provenance.objective_bound > pruned.best.objective * (1.0 + TIE_RTOL)
            assert "cannot win" in c.reason
            if twin.feasible:
                assert twin.objective >= c.provenance.objective_bound * (1.0 - BELOW_BOUND)
                assert twin.objective > full.best.objective * (1.0 + TIE_RTOL)
        else:
            assert c.feasible == twin.feasible and c.reason == twin.reason
    left_out = {_key(c) for c in pruned.candidates if c.provenance.pruned}
    assert [_key(c) for c in pruned.candidates if not c.feasible and not c.provenance.pruned] == [
        _key(c) for c in full.candidates if not c.feasible and _key(c) not in left_out
    ]
    return sum(c.provenance.pruned for c in pruned.candidates)


FAST_SEEDS = range(16)


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
def test_pruning_keeps_the_winner_and_prunes_only_losers():
    """16 random problems (4 geometries x 4 objective slots): same winner, sound bounds; some pruned."""
    pruned = [compare(seed) for seed in FAST_SEEDS]
    assert sum(pruned) >= 10, pruned  # the bound does prune (the slow shaft's wheels, mostly)


@pytest.mark.slow
def test_pruning_keeps_the_winner_slow():
    for seed in range(16, 240):
        compare(seed)


def test_objective_bound_is_the_thin_ring_and_the_solid_cylinder():
    """The bound's three forms against their geometry: a thin ring at the cap gives exactly J with
    the bounding mass, and a solid cylinder of the width limit at the bounding diameter gives J."""
    material = make_material("steel", 7800.0, max_rim_speed=50.0, cost=3.0)
    combo = Combination(
        material=material,
        shaft=MountShaft("s", 2.0),
        omega=100.0,
        j_shaft=12.0,
        j_reference=48.0,
        cap_speed=1.0,
        cap=0.8,
    )
    mass, _ = wheel_design.objective_bound(combo, DesignSpec(geometry="rim_web", max_outer_diameter=0.8))
    assert mass * 0.4**2 == pytest.approx(12.0, rel=1e-15)  # J of a thin ring of radius D/2
    cost, _ = wheel_design.objective_bound(combo, DesignSpec(geometry="rim_web", objective="cost"))
    assert cost == pytest.approx(3.0 * mass, rel=1e-15)
    spec = DesignSpec(geometry="rim_web", objective="outer_diameter", max_width=0.2)
    d, _ = wheel_design.objective_bound(combo, spec)
    assert math.pi * 7800.0 * 0.2 * d**4 / 32.0 == pytest.approx(12.0, rel=1e-14)
    assert wheel_design.objective_bound(combo, DesignSpec(geometry="rim_web", objective="outer_diameter"))[0] == 0.0


def _steel(allowable):
    return make_material(
        "steel",
        7850.0,
        allowable_stress=allowable,
        poisson_ratio=0.3,
        tensile_strength=500e6,
        yield_strength=300e6,
        ductile=True,
    )


def test_stress_cap_against_the_published_disc_figures():
    """Issue 13's figures (steel rho 7850, nu 0.3, R 0.5 m, 3000 rpm): a solid disc peaks at 79.90 MPa
    at its centre, so at that allowable the cap is D = 1 m; an annulus's hoop stress at the bore is at
    least (3+nu)/4 rho w^2 b^2, 160.13 MPa less its a² term, so its cap is 2 b of that stress."""
    omega = 3000.0 * 2.0 * math.pi / 60.0
    shaft = MountShaft("s", 1.0)

    def cap(allowable, geometry, bore):
        combo = Combination(
            material=_steel(allowable),
            shaft=shaft,
            omega=omega,
            j_shaft=1.0,
            j_reference=1.0,
            cap_speed=math.inf,
            cap=math.inf,
        )
        return wheel_design.stress_cap(combo, DesignSpec(geometry=geometry, criterion="stress"), bore)

    assert cap(79.90e6, "disc", 0.0) == pytest.approx(1.0, rel=1e-4)  # the published 4 digits
    without_a2 = 3.3 / 4.0 * 7850.0 * omega**2 * 0.25  # (3+nu)/4 rho w^2 b^2 [Pa]
    with_a2 = without_a2 + 0.7 / 4.0 * 7850.0 * omega**2 * 0.05**2  # + (1-nu)/4 rho w^2 a^2
    assert with_a2 == pytest.approx(160.13e6, rel=5e-5)  # the published hoop stress
    assert cap(without_a2, "disc", 0.1) == pytest.approx(1.0, rel=1e-14)
    assert cap(without_a2, "rim", 0.0) == pytest.approx(1.0, rel=1e-14)  # a rim is an annulus
    assert cap(without_a2, "rim_web", 0.1) == math.inf  # no closed form: no cap
    combo = Combination(
        material=_steel(without_a2),
        shaft=shaft,
        omega=omega,
        j_shaft=1.0,
        j_reference=1.0,
        cap_speed=math.inf,
        cap=math.inf,
    )
    assert wheel_design.stress_cap(combo, DesignSpec(geometry="rim"), 0.0) == math.inf  # rim speed criterion


def test_a_rim_the_stress_bound_refuses_ipopt_finds_infeasible():
    """The stress bound's proof against IPOPT: a rim asked for 1.05 times the inertia the bound allows is
    refused without a solve, and the wheel NLP itself, given the same problem, finds no rim."""
    material, omega, width = _steel(60e6), 300.0, 0.1
    spec = DesignSpec(geometry="rim", criterion="stress", hb_ratio=(0.5, 2.0), max_width=width)
    combo = Combination(
        material=material,
        shaft=MountShaft("s", 1.0),
        omega=omega,
        j_shaft=1.0,
        j_reference=1.0,
        cap_speed=math.inf,
        cap=math.inf,
    )
    d = wheel_design.stress_cap(combo, spec, 0.0)
    j_sup = math.pi * 7850.0 * min(width, d / 1.0) * d**4 / 32.0
    combo.j_shaft = 1.05 * j_sup
    result = design_flywheel(combo.j_shaft, omega, [MountShaft("s", 1.0)], [material], spec)
    assert result.status == "infeasible" and "its stress allows" in result.candidates[0].reason
    structure = wheel_nlp.WheelStructure("rim", "stress", True, False, 0, False, True, False, "mass")
    problem = wheel_nlp.WheelProblem(
        j_shaft=combo.j_shaft,
        omega=omega,
        density=7850.0,
        poisson=0.3,
        torque=0.0,
        bore=0.0,
        allowable={"rim": 60e6},
        envelope=math.inf,
        max_width=width,
        max_rim_speed=math.nan,
        hb_ratio=(0.5, 2.0),
        d_mean=None,
        min_wall=0.0,
    )
    with pytest.raises(SolverFailed) as err:
        wheel_nlp.solve(wheel_nlp.get_model(structure), problem, "rim")
    assert err.value.status == "Infeasible_Problem_Detected"
