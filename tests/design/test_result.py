"""flyopt.design.result: a Candidate's nested records and its flat JSON."""

import json

import pytest

from flyopt.design.result import (
    CANDIDATE_FIELDS,
    DESIGN_FIELDS,
    SEARCH_FIELDS,
    Candidate,
    Design,
    Dimensions,
    Limits,
    Parts,
    Provenance,
    Stresses,
)
from flyopt.design.wheel import Dims

#: The candidate JSON's keys in their order, written out here, not read from the code (CANDIDATE_FIELDS is read
#: off to_dict itself): a key renamed, dropped or moved is a change of the JSON its readers see.
JSON_KEYS = (
    "material",
    "shaft",
    "speed_ratio",
    "geometry",
    "feasible",
    "reason",
    "d_mean",
    "d_outer",
    "d_inner",
    "h",
    "b",
    "hb_ratio",
    "mass",
    "rim_speed",
    "hoop_stress",
    "safety_factor",
    "cost",
    "j_flywheel",
    "j_at_reference",
    "binding",
    "objective",
    "j_required_on_shaft",
    "d_outer_limit",
    "rim_speed_limit",
    "j_max",
    "d_outer_needed",
    "solver_status",
    "iterations",
    "solve_time",
    "n_arms",
    "t_web",
    "d_hub",
    "l_hub",
    "arm_major",
    "arm_minor",
    "bore",
    "parts",
    "stress",
    "allowable_stress",
    "strength_safety",
    "burst_speed",
    "speed_margin",
    "unbalance_permissible",
    "key",
    "thin_wall",
    "sensitivities",
    "castability",
    "notes",
    "pruned",
    "objective_bound",
)

IDENTITY = dict(material="cast_iron", shaft="crankshaft", speed_ratio=1.0, geometry="rim_arms")

#: A whole wheel with arms, a bore and a key: every record holds something.
DESIGN = Design(
    **IDENTITY,
    reason="designed; binding: inertia",
    n_arms=6,
    bore=0.05,
    mass=120.0,
    cost=240.0,
    j_flywheel=30.0,
    j_at_reference=30.0,
    objective=120.0,
    dims=Dimensions(d_mean=0.9, d_outer=1.0, d_inner=0.8, h=0.1, b=0.2, d_hub=0.12, l_hub=0.1, arm_major=0.06),
    parts=Parts(({"name": "rim", "mass": 100.0},), {"size": "14x9"}),
    stresses=Stresses(rim_speed=30.0, hoop_stress=6.5e6, safety_factor=3.0, burst_speed=float("inf")),
    limits=Limits(j_required_on_shaft=29.0, d_outer_limit=1.2, rim_speed_limit=40.0, binding=("inertia",)),
    provenance=Provenance(solver_status="Solve_Succeeded", iterations=12, solve_time=0.5, notes=("a note",)),
)


def test_to_dict_is_flat_in_the_order_of_candidate_fields():
    """The JSON of a candidate keeps the flat keys, in their order, as before the records (timings aside)."""
    infeasible = Candidate(**IDENTITY, feasible=False, reason="too heavy", limits=Limits(j_max=3.0))
    assert CANDIDATE_FIELDS == JSON_KEYS
    for c in (DESIGN, infeasible):
        assert tuple(c.to_dict(timings=True)) == CANDIDATE_FIELDS
        assert tuple(c.to_dict()) == tuple(name for name in CANDIDATE_FIELDS if name != "solve_time")
    assert set(DESIGN_FIELDS) <= set(CANDIDATE_FIELDS)
    # the fields left out of the top-level "design" name keys of the JSON (a renamed one would stay in it)
    assert SEARCH_FIELDS <= set(CANDIDATE_FIELDS)


def test_to_dict_reads_each_record():
    out = DESIGN.to_dict(timings=True)
    assert (out["d_outer"], out["hb_ratio"], out["arm_minor"], out["t_web"]) == (1.0, 0.5, 0.03, None)
    assert (out["n_arms"], out["bore"], out["key"], out["parts"]) == (
        6,
        0.05,
        {"size": "14x9"},
        [{"name": "rim", "mass": 100.0}],
    )
    assert (out["rim_speed"], out["burst_speed"], out["binding"], out["notes"]) == (30.0, None, ["inertia"], ["a note"])
    assert (out["solver_status"], out["solve_time"], out["pruned"]) == ("Solve_Succeeded", 0.5, False)
    json.dumps(out, allow_nan=False)  # inf became None


def test_infeasible_candidate_reports_none_for_what_it_lacks():
    out = Candidate(
        **IDENTITY, feasible=False, reason="no", provenance=Provenance(pruned=True, objective_bound=2.0)
    ).to_dict()
    assert all(out[name] is None for name in ("d_outer", "d_mean", "rim_speed", "key", "stress", "arm_minor"))
    assert (out["parts"], out["binding"], out["sensitivities"], out["notes"]) == ([], [], [], [])
    assert (out["pruned"], out["objective_bound"], out["j_max"]) == (True, 2.0, None)  # NaN j_max: not computed


def test_a_design_is_feasible_and_has_its_records():
    assert DESIGN.feasible
    with pytest.raises(TypeError, match="dims"):
        Design(**IDENTITY, reason="", mass=1.0, j_flywheel=1.0, j_at_reference=1.0, objective=1.0,
               parts=Parts(), stresses=Stresses(rim_speed=1.0, hoop_stress=1.0))  # fmt: skip


def test_dimensions_give_the_wheel_dims_with_zero_for_absent_parts():
    dims = DESIGN.dims.wheel(DESIGN.n_arms, DESIGN.bore)
    assert dims == Dims(
        d_outer=1.0, h=0.1, b=0.2, bore=0.05, t_web=0.0, d_hub=0.12, l_hub=0.1, arm_major=0.06, n_arms=6
    )
    rim = Dimensions(d_mean=0.9, d_outer=1.0, d_inner=0.8, h=0.1, b=0.2).wheel()
    assert (rim.bore, rim.t_web, rim.d_hub, rim.l_hub, rim.arm_major, rim.n_arms) == (0.0, 0.0, 0.0, 0.0, 0.0, 0)


@pytest.mark.parametrize("record", [Dimensions, Parts, Stresses, Limits, Provenance, Candidate, Design])
def test_records_are_built_as_their_dataclass_declares_them(record):
    """The records' __init__ takes the dataclass's own parameters, in order, with its defaults; a default
    factory gives a new object each time; the record stays frozen."""
    import dataclasses
    import inspect

    params = list(inspect.signature(record.__init__).parameters.values())[1:]
    assert [p.name for p in params] == [f.name for f in dataclasses.fields(record)]
    for p, f in zip(params, dataclasses.fields(record)):
        assert (p.kind == p.KEYWORD_ONLY) == f.kw_only
        if f.default is not dataclasses.MISSING:
            assert p.default is f.default
        elif f.default_factory is dataclasses.MISSING:
            assert p.default is p.empty
    required = {p.name: 1.0 for p in params if p.default is p.empty}
    one, two = record(**required), record(**required)
    assert list(vars(one)) == [f.name for f in dataclasses.fields(record)]
    for f in dataclasses.fields(record):
        if f.default_factory is not dataclasses.MISSING:
            assert getattr(one, f.name) == f.default_factory() and getattr(one, f.name) is not getattr(two, f.name)
    with pytest.raises(dataclasses.FrozenInstanceError):
        one.__setattr__(params[0].name, 2.0)
    with pytest.raises(TypeError):
        record(**required, not_a_field=1.0)


def test_an_infeasible_candidate_takes_its_identity_from_the_shaft():
    from flyopt.design.spec import MountShaft

    c = Candidate.infeasible(
        "cast_iron", MountShaft("motor", 3.5), "rim", "too heavy", n_arms=4, limits=Limits(j_max=2.0)
    )
    assert (c.material, c.shaft, c.speed_ratio, c.geometry, c.feasible, c.reason) == (
        "cast_iron",
        "motor",
        3.5,
        "rim",
        False,
        "too heavy",
    )
    assert (c.n_arms, c.limits.j_max, c.dims, c.bore) == (4, 2.0, None, None)
