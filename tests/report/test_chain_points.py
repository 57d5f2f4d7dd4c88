"""The points of an energy chain of net areas, which have no angle, are named one way in every output.

khurmi-16-14-book-rim's text said "ω_max / ω_min at  the end of area 1 / area 0" two lines above its own
table, which names the same points "after area 1" and "start" (and marks them ω_max and ω_min); the energy
diagram's legend said "at the end of area 0". The fact, the table and the legend now name a point as the table
does. The extremes are found here from the JSON's chain (ω_min where ΔE is least, ω_max where it is largest,
for a constant inertia), not from the text.
"""

import json
import re

from conftest import PROBLEMS

SCENE = PROBLEMS / "textbook" / "khurmi-16-14-book-rim.toml"


def test_the_extremes_of_net_areas_are_named_as_the_energy_table_names_them(main_cli, close_figures):
    import flyopt
    from flyopt.report import plots

    status, out, _ = main_cli("solve", SCENE, "--json")
    assert status == 0
    chain = json.loads(out)["energy_chain"]
    assert all(e["angle"] is None for e in chain)  # net areas: points by their index alone
    top = max(chain, key=lambda e: e["delta_e"])["index"]
    bottom = min(chain, key=lambda e: e["delta_e"])["index"]
    assert (top, bottom) == (1, 0)  # the swing up after the first area, from the cycle's start

    status, text, _ = main_cli("solve", SCENE)
    assert status == 0
    lines = text.splitlines()
    start = lines.index("Energy indicator diagram (excess work from the cycle start):") + 3  # title, head, rule
    rows = {}
    for line in lines[start:]:
        if not line.strip():
            break
        cells = re.split(r"\s{2,}", line.strip())
        rows[cells[-1] if len(cells) == 3 else None] = cells[0]
    assert len(rows) == 3
    fact = next(line for line in lines if line.lstrip().startswith("ω_max / ω_min at"))
    assert fact.split("at", 1)[1].strip() == f"{rows['ω_max']} / {rows['ω_min']}"
    assert rows["ω_min"] == "start" and rows["ω_max"] == f"after area {top}"

    scene = flyopt.load(SCENE)
    ax = plots.plot_energy(scene, flyopt.analyse(scene))
    legend = [t.get_text() for legend in ax.figure.legends for t in legend.get_texts()]
    legend += [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else []
    for name in ("ω_max", "ω_min"):
        said = [w for w in legend if w.startswith(f"{name}:")]
        assert len(said) == 1 and said[0].endswith(f"({rows[name]})"), legend
