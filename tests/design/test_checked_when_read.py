"""A design whose structural check is made when first read (Design.checked_when_read) cannot be told from one
built with its check made at once: the same fields, equality, repr, order of its fields, copies and pickles.

The default ranking leaves each textbook design's check (:func:`flyopt.design.wheel_design.structure_fields`)
until its parts, stresses or provenance are read; every consumer reads them through the attributes, so a
deferred design must behave in every way as the design built eagerly from the same check. The reference here
is that eager design, built from the check's own output with the dataclass's constructor.
"""

import copy
import dataclasses
import json
import pickle

import pytest

from flyopt.design import Design, DesignSpec, MountShaft, design_flywheel, wheel, wheel_design
from flyopt.design.materials import builtin_materials
from flyopt.design.result import CHECKED_FIELDS, Dimensions, Limits, Provenance

MATERIAL = builtin_materials()["cast_steel"]
DIMS = wheel.Dims(d_outer=1.2, h=0.15, b=0.1)
OMEGA = 60.0
SPEC = DesignSpec("rim")
FIELDS = dict(
    material="cast_steel",
    shaft="crankshaft",
    speed_ratio=1.0,
    geometry="rim",
    reason="designed; binding: inertia",
    mass=300.0,
    cost=None,
    j_flywheel=40.0,
    j_at_reference=40.0,
    objective=300.0,
    dims=Dimensions(d_mean=1.05, d_outer=1.2, d_inner=0.9, h=0.15, b=0.1),
    limits=Limits(j_required_on_shaft=40.0, binding=("inertia",)),
)
PROVENANCE = Provenance(solver_status="closed_form", iterations=0, solve_time=1e-5, notes=("given",))


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
    return Design(**FIELDS, parts=s.parts, stresses=s.stresses, provenance=provenance)


@pytest.mark.parametrize("first", ["parts", "stresses", "provenance", "eq", "repr", "pickle", "deepcopy", "replace"])
def test_a_deferred_design_is_the_eager_one_whatever_is_read_first(first):
    check = _Check()
    deferred = Design.checked_when_read(check, PROVENANCE, **FIELDS)
    eager = _eager()
    assert check.calls == 0 and deferred.mass == 300.0 and check.calls == 0  # the ranking's fields: no check
    if first in CHECKED_FIELDS:
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
    else:
        assert dataclasses.replace(deferred, reason="r") == dataclasses.replace(eager, reason="r")
    assert check.calls == 1
    # once checked, it holds exactly the eager design's fields, in their declared order, and checks no more
    assert vars(deferred) == vars(eager) and list(vars(deferred)) == [f.name for f in dataclasses.fields(Design)]
    assert deferred == eager and repr(deferred) == repr(eager)
    assert deferred.to_dict(timings=True) == eager.to_dict(timings=True)
    assert deferred.provenance.notes[0] == "given" and check.calls == 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        deferred.parts = None  # type: ignore[misc]


def test_a_deferred_design_has_no_other_attributes():
    deferred = Design.checked_when_read(_Check(), PROVENANCE, **FIELDS)
    with pytest.raises(AttributeError, match="not_a_field"):
        deferred.not_a_field  # noqa: B018
    assert not hasattr(deferred, "not_a_field")
    assert "_check" in vars(deferred)  # still unchecked: a missing name does not make the check


def test_a_ranking_pickled_to_another_process_carries_every_check():
    """A sweep's worker sends its DesignResult pickled: each candidate arrives checked, equal to the
    candidate read where it was made."""
    shafts = [MountShaft("reference", 1.0), MountShaft("faster", 3.0)]
    materials = [builtin_materials()[m] for m in ("cast_iron", "cast_steel")]
    result = design_flywheel(40.0, 60.0, shafts, materials, SPEC)
    designs = [c for c in result.candidates if isinstance(c, Design)]
    assert len(designs) >= 2
    assert all("_check" in vars(c) for c in designs)  # the ranking checked none
    shipped = pickle.loads(pickle.dumps(result))  # (repr: a NaN read from a pickle is not the NaN sent)
    assert repr(shipped) == repr(result) and json.dumps(shipped.to_dict()) == json.dumps(result.to_dict())
    for c, s in zip(result.candidates, shipped.candidates):
        assert repr(c) == repr(s) and list(vars(c)) == list(vars(s))
        assert "_check" not in vars(s)
        assert not isinstance(s, Design) or s.stresses.stress  # checked, with its stress fields


def test_a_check_made_meanwhile_is_not_made_again():
    """Two readers that both find a design unchecked (two threads of the app) make the check once each at
    most, and the second finds it made: no error, the same fields."""
    check = _Check()
    deferred = Design.checked_when_read(check, PROVENANCE, **FIELDS)
    make = deferred._make_check  # the method the first read calls, taken before it runs
    assert deferred.parts == _eager().parts
    make()  # the second reader, which saw the design unchecked, comes after the first
    assert check.calls == 1 and vars(deferred) == vars(_eager())
