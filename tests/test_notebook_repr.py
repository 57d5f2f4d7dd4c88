"""In a notebook (issue 29): a Solution shows its answer card, a design's ranking comes as a DataFrame with units."""

from __future__ import annotations

import json
import math
import re

import pytest

import flyopt
from flyopt.outputs.documents import solution_json
from tests.conftest import PROBLEMS


@pytest.fixture(scope="module")
def solved():
    path = PROBLEMS / "punch-press-wheel.toml"
    solution = flyopt.solve(flyopt.load(path))
    return solution, json.loads(solution_json(solution, str(path)))


def test_the_answer_card_is_the_answer_with_the_jsons_numbers(solved):
    solution, data = solved
    card = solution._repr_html_()
    assert card.startswith("<table class='flyopt-answer'>") and card.endswith("</table>")
    mass = re.search(r"wheel with a web, ([0-9.]+) kg, on the motor shaft", card).group(1)
    assert float(mass) == pytest.approx(round(data["design"]["mass"], 2), abs=1e-12)  # 4 significant figures
    assert [h for h in re.findall(r"<th[^>]*>([^<]*)</th>", card)] == ["size", "J", "limits", "δ"]


def test_the_card_escapes_what_the_scene_says(tmp_path):
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    title = re.search(r'^title = "(.*)"$', text, re.M).group(0)
    path = tmp_path / "hostile.toml"
    path.write_text(text.replace(title, 'title = "<script>alert(1)</script> & co"'), encoding="utf-8")
    card = flyopt.solve(flyopt.load(path))._repr_html_()
    assert "<script>" not in card and "&lt;script&gt;alert(1)&lt;/script&gt; &amp; co" in card


def test_the_ranking_as_a_frame_is_the_jsons_candidates_with_their_units(solved):
    solution, data = solved
    frame = solution.design.to_frame()
    candidates = data["design"]["candidates"]
    assert len(frame) == len(candidates)
    for column in ("mass", "d_outer"):  # the same floats, in SI; a wheel that cannot win has none (NaN)
        assert [None if math.isnan(v) else v for v in frame[column]] == [c[column] for c in candidates]
    assert any(c["mass"] is None for c in candidates)  # the NaN case is exercised
    assert frame["material"][0] == solution.design.material_name(candidates[0]["material"])
    assert frame["binding"][0] == ", ".join(candidates[0]["binding"])
    units = frame.attrs["flyopt"]["units"]
    assert (units["mass"], units["d_outer"], units["j_flywheel"], units["rim_speed"]) == ("kg", "m", "kg*m**2", "m/s")
