"""Every number of a built-in strength table is named in the entry's own source.

materials.toml promises that each number cites where it comes from: a row
added without its figure in the ``source`` string (a value recalled, or one
copied from another grade) fails here. The check is textual: each row's
thickness bound [mm], R_m and R_p0.2 [MPa] must appear as numbers in the
source text of its entry.
"""

import re

import pytest

from flyopt.design.materials import builtin_materials

MATERIALS = builtin_materials(default_only=False)


def _numbers(text):
    """The numbers written in ``text`` (1100-1300 gives 1100 and 1300; 2.5 stays 2.5)."""
    return {float(n) for n in re.findall(r"\d+(?:\.\d+)?", text)}


@pytest.mark.parametrize("name", sorted(n for n, m in MATERIALS.items() if m.strength_by_thickness))
def test_every_table_figure_is_in_the_source(name):
    material = MATERIALS[name]
    cited = _numbers(material.source)
    for row in material.strength_by_thickness:
        figures = [round(row.max_thickness * 1e3, 6), row.tensile_strength / 1e6]
        if row.yield_strength is not None:
            figures.append(row.yield_strength / 1e6)
        missing = [f for f in figures if f not in cited]
        assert not missing, f"{name}: row {row} has {missing} not named in its source"
