"""flyopt.bench.design: the structural check timed beside the default ranking is the one the ranking made.

The design section reports how much of the time of the default ranking read
whole (``flyopt-auto-read``: every reported candidate's structural check, made
when first read) is that check, by making it again on each reported design;
the check it times must be the check each design carries (the same parts,
stresses and notes), or the share it reports means nothing.
"""

from flyopt.bench.design import random_design_scenes, structural_checks
from flyopt.design import Design, design_flywheel


def test_the_timed_check_is_the_check_each_reported_design_carries():
    checked = 0
    for scene in random_design_scenes(12, 5):
        result = design_flywheel(
            scene["j_required"], scene["omega_mean"], scene["shafts"], scene["materials"], scene["spec"]
        )
        designs = [c for c in result.candidates if isinstance(c, Design)]
        again = structural_checks(result, scene["omega_mean"], scene["materials"])()
        assert len(again) == len(designs)
        for structure, design in zip(again, designs):
            assert structure.parts == design.parts
            assert structure.stresses == design.stresses
            assert structure.notes == design.provenance.notes
            checked += 1
    assert checked > 20
