"""A design whose structural check and description are made when first read (Design.checked_when_read) cannot be
told from one built with them made at once: the same fields, equality, repr, order of its fields, copies and
pickles.

The default ranking leaves each textbook design's check (:func:`flyopt.design.wheel_design.structure_fields`) and
its description (what binds, its limits, how it was found) until its parts, stresses, provenance, reason or limits
are read; every consumer reads them through the attributes, so a deferred design must behave in every way as the
design built eagerly from the same calls. The reference here is that eager design, built from their own output
with the dataclass's constructor.
"""

import copy
import dataclasses
import json
import math
import pickle

import pytest

from flyopt.design import Design, DesignSpec, MountShaft, design_flywheel, designer, wheel, wheel_design
from flyopt.design.materials import builtin_materials
from flyopt.design.result import DEFERRABLE_FIELDS, Candidate, Dimensions, Limits, Provenance

MATERIAL = builtin_materials()["cast_steel"]
DIMS = wheel.Dims(d_outer=1.2, h=0.15, b=0.1)
OMEGA = 60.0
SPEC = DesignSpec("rim")
FIELDS = dict(
    material="cast_steel",
    shaft="crankshaft",
    speed_ratio=1.0,
    geometry="rim",
    mass=300.0,
    cost=None,
    j_flywheel=40.0,
    j_at_reference=40.0,
    objective=300.0,
    dims=Dimensions(d_mean=1.05, d_outer=1.2, d_inner=0.9, h=0.15, b=0.1),
)
REASON = "designed; binding: inertia"
LIMITS = Limits(j_required_on_shaft=40.0, binding=("inertia",))
PROVENANCE = Provenance(solver_status="closed_form", iterations=0, solve_time=1e-5, notes=("given",))


class _Describe:
    """A design's description, counting its calls."""

    calls = 0

    def __call__(self):
        self.calls += 1
        return REASON, LIMITS, PROVENANCE


class _Check:
    """The structural check of DIMS, counting its calls."""

    calls = 0

    def __call__(self):
        self.calls += 1
        s = wheel_design.structure_fields(MATERIAL, "rim", DIMS, OMEGA, 0.0, SPEC, 0.0)
        return s.parts, s.stresses, s.notes


def _eager():
    s = wheel_design.structure_fields(MATERIAL, "rim", DIMS, OMEGA, 0.0, SPEC, 0.0)
    provenance = dataclasses.replace(PROVENANCE, notes=PROVENANCE.notes + s.notes)
    return Design(**FIELDS, reason=REASON, limits=LIMITS, parts=s.parts, stresses=s.stresses, provenance=provenance)


def _read_first(deferred, eager, first, deferred_fields, changes):
    """Read ``deferred`` first by ``first`` (one of its deferred fields, or an operation that reads every field) and
    check what it gives against ``eager``'s."""
    if first in deferred_fields:
        assert getattr(deferred, first) == getattr(eager, first)
    elif first == "eq":
        assert deferred == eager
    elif first == "repr":
        assert repr(deferred) == repr(eager)
    elif first == "pickle":
        shipped = pickle.loads(pickle.dumps(deferred))  # (repr: a NaN read from a pickle is not the NaN sent)
        assert repr(shipped) == repr(eager) and list(vars(shipped)) == list(vars(eager))
    elif first == "deepcopy":
        assert copy.deepcopy(deferred) == eager
    elif first == "replace":
        assert dataclasses.replace(deferred, **changes) == dataclasses.replace(eager, **changes)
    else:
        assert first == "to_dict" and deferred.to_dict() == eager.to_dict()


@pytest.mark.parametrize("first", [*DEFERRABLE_FIELDS, "eq", "repr", "pickle", "deepcopy", "replace", "to_dict"])
def test_a_deferred_design_is_the_eager_one_whatever_is_read_first(first):
    check, describe = _Check(), _Describe()
    deferred = Design.checked_when_read(check, describe, **FIELDS)
    eager = _eager()
    assert deferred.mass == 300.0 and deferred.dims == FIELDS["dims"] and deferred.objective == 300.0
    assert check.calls == describe.calls == 0  # the ranking's fields: neither made
    _read_first(deferred, eager, first, DEFERRABLE_FIELDS, {"mass": 1.0})
    assert check.calls == describe.calls == 1
    # once checked, it holds exactly the eager design's fields, in their declared order, and checks no more
    assert vars(deferred) == vars(eager) and list(vars(deferred)) == [f.name for f in dataclasses.fields(Design)]
    assert deferred == eager and repr(deferred) == repr(eager)
    assert deferred.to_dict(timings=True) == eager.to_dict(timings=True)
    assert deferred.provenance.notes[0] == "given" and check.calls == describe.calls == 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        deferred.parts = None  # type: ignore[misc]


def test_a_deferred_design_has_no_other_attributes():
    deferred = Design.checked_when_read(_Check(), _Describe(), **FIELDS)
    with pytest.raises(AttributeError, match="not_a_field"):
        deferred.not_a_field  # noqa: B018
    assert not hasattr(deferred, "not_a_field")
    assert "_make" in vars(deferred)  # still unchecked: a missing name does not make the check


def test_a_ranking_pickled_to_another_process_carries_every_check():
    """A sweep's worker sends its DesignResult pickled: each candidate arrives checked, equal to the
    candidate read where it was made."""
    shafts = [MountShaft("reference", 1.0), MountShaft("faster", 3.0)]
    materials = [builtin_materials()[m] for m in ("cast_iron", "cast_steel")]
    result = design_flywheel(40.0, 60.0, shafts, materials, SPEC)
    designs = [c for c in result.candidates if isinstance(c, Design)]
    assert len(designs) >= 2
    assert all("_make" in vars(c) for c in designs)  # the ranking checked none
    shipped = pickle.loads(pickle.dumps(result))  # (repr: a NaN read from a pickle is not the NaN sent)
    assert repr(shipped) == repr(result) and json.dumps(shipped.to_dict()) == json.dumps(result.to_dict())
    for c, s in zip(result.candidates, shipped.candidates):
        assert repr(c) == repr(s) and list(vars(c)) == list(vars(s))
        assert "_make" not in vars(s)
        assert not isinstance(s, Design) or s.stresses.stress  # checked, with its stress fields


def test_a_check_made_meanwhile_is_not_made_again():
    """Two readers that both find a design unchecked (two threads of the app) make the check once each at
    most, and the second finds it made: no error, the same fields."""
    check = _Check()
    deferred = Design.checked_when_read(check, _Describe(), **FIELDS)
    make = deferred._make_deferred  # the method the first read calls, taken before it runs
    assert deferred.parts == _eager().parts
    make()  # the second reader, which saw the design unchecked, comes after the first
    assert check.calls == 1 and vars(deferred) == vars(_eager())


# An infeasible combination's reason in numbers and the cap it needs (Candidate.explained_when_read): the
# ranking needs only that it gives no design; the text, the JSON and the report read the explanation.

INFEASIBLE_SHAFTS = [MountShaft("reference", 1.0), MountShaft("slower", 0.2), MountShaft("faster", 4.0)]
INFEASIBLE_SPEC = DesignSpec("rim", max_outer_diameter=1.0)
INFEASIBLE_MATERIALS = [builtin_materials()[m] for m in ("cast_iron", "cast_steel")]


def _infeasible_ranking():
    return design_flywheel(300.0, 30.0, INFEASIBLE_SHAFTS, INFEASIBLE_MATERIALS, INFEASIBLE_SPEC)


class _Explain:
    """The explanation of an infeasible combination, counting its calls."""

    calls = 0

    def __init__(self, combo):
        self.combo = combo

    def __call__(self):
        self.calls += 1
        return designer._explained(self.combo, INFEASIBLE_SPEC)


def _slower_cast_iron():
    """The cast-iron combination on the slower shaft, decided as the ranking decides it (its J_max set)."""
    combos = designer.combinations(
        300.0, 30.0, None, None, INFEASIBLE_SHAFTS, [True] * 3, INFEASIBLE_MATERIALS, INFEASIBLE_SPEC
    )
    for order, combo, _ in combos:
        if combo.material.name == "cast_iron" and combo.shaft.name == "slower":
            decided = designer._Decided()
            designer._decide_textbook(order, combo, INFEASIBLE_SPEC, True, None, decided)
            assert decided.infeasible and not decided.pending
            return combo
    raise AssertionError("no such combination")


@pytest.mark.parametrize("first", ["reason", "limits", "eq", "repr", "pickle", "deepcopy", "replace", "to_dict"])
def test_an_infeasible_combination_explained_when_read_is_the_one_explained_at_once(first):
    combo = _slower_cast_iron()
    explain = _Explain(combo)
    deferred = Candidate.explained_when_read("cast_iron", combo.shaft, "rim", explain)
    made = designer._explained(combo, INFEASIBLE_SPEC)
    eager = Candidate.infeasible("cast_iron", combo.shaft, "rim", made["reason"], limits=made["limits"])
    assert explain.calls == 0 and not deferred.feasible and deferred.material == "cast_iron"
    _read_first(deferred, eager, first, ("reason", "limits"), {"n_arms": 3})
    assert explain.calls == 1
    assert vars(deferred) == vars(eager) and list(vars(deferred)) == [f.name for f in dataclasses.fields(Candidate)]
    assert deferred.reason == eager.reason and explain.calls == 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        deferred.reason = "r"  # type: ignore[misc]


def test_the_ranking_explains_no_infeasible_combination_until_it_is_read():
    result = _infeasible_ranking()
    infeasible = [c for c in result.candidates if not c.feasible]
    assert len(infeasible) >= 2 and result.best is not None
    assert all("_make" in vars(c) for c in infeasible)  # the ranking explained none
    for c in infeasible:
        assert c.reason.startswith(f"{c.material.replace('_', ' ')} on the {c.shaft} shaft: ")
        assert "_make" not in vars(c)  # made by that read, with the limits
        # the cap it names is where the largest rim first gives the inertia: with no width limit, a rim down to
        # the bore (D_i = 0, H = D_o/2) at H/B 1.5, whose exact annulus gives J = m D_o^2 / 8 with
        # m = rho (pi/4) D_o^2 B, B = D_o / 3: J = rho pi D_o^5 / 96 (independent of the closed form's search)
        needed = c.limits.d_outer_needed
        rho = builtin_materials()[c.material].density
        assert needed > c.limits.d_outer_limit and f"{needed:.3g} m" in c.reason
        assert rho * math.pi * needed**5 / 96.0 == pytest.approx(c.limits.j_required_on_shaft, rel=1e-12)
        assert c.limits.j_required_on_shaft > c.limits.j_max > 0


def test_a_candidate_defers_only_the_fields_that_can_be_made_later():
    with pytest.raises(TypeError, match="mass"):
        Candidate.made_when_read(dict, ("mass",), material="m", shaft="s", speed_ratio=1.0, geometry="rim")


def test_a_reader_that_finds_the_fields_made_meanwhile_reads_them():
    """A thread that found ``reason`` missing enters the descriptor; another thread makes the fields before it
    looks again: it reads them (it raised AttributeError, which ``getattr(c, name, default)`` would swallow)."""
    deferred = Candidate.explained_when_read("cast_iron", INFEASIBLE_SHAFTS[0], "rim", _Explain(_slower_cast_iron()))
    descriptor = vars(Candidate)["reason"]
    made = deferred.reason  # the other thread's read
    assert descriptor.__get__(deferred, Candidate) is made


def test_threads_reading_the_same_candidates_make_each_once():
    import sys
    import threading

    class Counting:
        def __init__(self):
            self.calls = 0

        def __call__(self):
            self.calls += 1
            return {"reason": "r", "limits": Limits(j_required_on_shaft=1.0)}

    makes = [Counting() for _ in range(2000)]
    candidates = [Candidate.explained_when_read("cast_iron", INFEASIBLE_SHAFTS[0], "rim", m) for m in makes]
    errors = []

    def read():
        try:
            for c in candidates:
                assert c.reason == "r" and c.limits.j_required_on_shaft == 1.0
        except Exception as err:  # noqa: BLE001 -- counted, and the test fails on any
            errors.append(err)

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads as often as the interpreter can
    try:
        threads = [threading.Thread(target=read) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)
    assert errors == [] and [m.calls for m in makes] == [1] * len(makes)


def test_a_make_that_leaves_a_deferred_field_unmade_is_said():
    c = Candidate.made_when_read(lambda: {"reason": "r"}, ("reason", "limits"), **_identity())
    with pytest.raises(TypeError, match=r"not all made: \['limits'\]"):
        c.reason  # noqa: B018


@pytest.mark.parametrize(
    "fields, deferred, words",
    [
        ({"not_a_field": 1}, ("reason",), r"unknown fields \['not_a_field'\]"),
        ({"reason": "r"}, ("reason", "limits"), r"both given and deferred \['reason'\]"),
        ({"material": None}, ("reason",), r"missing fields \['material'\]"),
    ],
)
def test_a_candidate_made_when_read_refuses_what_its_constructor_refuses(fields, deferred, words):
    """made_when_read builds a candidate without calling __init__: it refuses what __init__ refuses (the
    reference), an unknown field, a field given twice and a missing one, naming them."""
    given = {**_identity(), **fields}
    given = {name: value for name, value in given.items() if value is not None}
    with pytest.raises(TypeError):
        Candidate(**dict.fromkeys(deferred, "r"), **given)  # what __init__ does with the same fields
    with pytest.raises(TypeError, match=words):
        Candidate.made_when_read(lambda: {}, deferred, **given)


def test_a_candidate_made_when_read_takes_the_constructors_defaults():
    """Every field not given takes its default, a factory's made afresh for each candidate, in declared order:
    once made it is the candidate __init__ builds from the same fields."""
    made = [Candidate.made_when_read(lambda: {"reason": "r"}, ("reason",), **_identity()) for _ in range(2)]
    eager = Candidate(**_identity(), reason="r")
    assert list(vars(made[0])) == [name for name in vars(eager) if name != "reason"] + ["_make"]  # before made
    for c in made:
        assert c == eager and vars(c) == vars(eager) and list(vars(c)) == list(vars(eager))
    assert made[0].limits is not made[1].limits and made[0].provenance is not made[1].provenance  # made afresh
    assert Candidate.made_when_read(lambda: {"reason": "r"}, ["reason"], **_identity()) == eager  # any sequence


def _identity():
    return dict(material="cast_iron", shaft="reference", speed_ratio=1.0, geometry="rim", feasible=False)
