"""One name per material (issue 29): the reasons a combination is infeasible name its material, and the design
that beats it, by the material's name for people (``Material.display_name``), never by its library key.

Through ``flyopt solve``'s text: punch-press-wheel, whose pruned combinations name the winner ("more than the
27.38 kg of gjs keyed on the motor shaft"), and the engine-with-shaft scene with a 20 % critical-speed margin,
where every combination is refused by its shaft's post-check.
"""

from __future__ import annotations

import re

from conftest import PROBLEMS


def _infeasible_lines(out: str) -> list[str]:
    return [line for line in out.splitlines() if re.match(r"\s+- .* on the .*: ", line)]


def test_the_pruned_reasons_name_the_winner_by_its_display_name(main_cli):
    path = PROBLEMS / "punch-press-wheel.toml"
    status, out, _err = main_cli("solve", path)
    assert status == 0
    pruned = [line for line in _infeasible_lines(out) if "cannot win" in line]
    assert pruned, out
    for line in pruned:
        assert line.endswith("of gjs keyed on the motor shaft"), line
    assert "gjs_keyed" not in out


def test_the_shafts_refusals_name_the_materials_by_their_display_names(main_cli, write_scene):
    text = (PROBLEMS / "four-cylinder-engine-shaft.toml").read_text(encoding="utf-8")
    path = write_scene(text.replace("critical_margin = 0.1", "critical_margin = 0.2"))
    status, out, _err = main_cli("solve", path)
    assert status == 3  # every combination refused by the shaft: no feasible flywheel
    refused = _infeasible_lines(out)  # cast iron by its shaft, cast steel keyed by its key (no key of at most 1.5 d)
    assert {line.split(" on the ")[0].strip(" -") for line in refused} == {"cast iron", "cast steel keyed"}
    assert any("the shaft cannot carry" in line for line in refused)
    for key in ("cast_iron", "cast_steel_keyed"):
        assert key not in out, key
