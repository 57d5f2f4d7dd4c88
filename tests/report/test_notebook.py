"""Results in a notebook (issue 29): the answer card, the ranking as a DataFrame, sweep files back in their units.

Every number is checked against ``flyopt solve --json``'s (the JSON document of the same solve) or against
the values the sweep was given in, not against the functions that show them.
"""

from __future__ import annotations

import html
import json
import math
import re
import subprocess
import sys

import pandas as pd
import pytest

import flyopt
from flyopt.outputs.documents import solution_json
from tests.conftest import PROBLEMS, ROOT

NUM = r"[0-9][0-9,]*(?:\.[0-9]+)?"


def _shown_equal(shown: str, value: float) -> bool:
    """A number printed to four significant figures is the JSON's value so rounded."""
    digits = 4 - 1 - math.floor(math.log10(abs(value))) if value else 0
    return math.isclose(float(shown.replace(",", "")), round(value, digits), rel_tol=1e-12, abs_tol=1e-12)


@pytest.fixture(scope="module")
def punch_press():
    path = PROBLEMS / "punch-press.toml"
    solution = flyopt.solve(flyopt.load(path))
    return solution, json.loads(solution_json(solution, str(path)))


def _cells(card: str) -> dict[str, str]:
    """The card's rows: label -> value, as a reader sees them (sub- and superscripts as plain text)."""
    return {
        html.unescape(re.sub(r"<[^>]+>", "", re.sub(r"<sub>(.*?)</sub>", r"_\1", k))): html.unescape(v)
        for k, v in re.findall(r"<th[^>]*>(.*?)</th><td[^>]*>([^<]*)</td>", card)
    }


def _named(card: str) -> dict[str, str]:
    """The card's values by the JSON field of their first number (``data-name``)."""
    return {k: html.unescape(v) for k, v in re.findall(r'<td[^>]* data-name="(\w+)">([^<]*)</td>', card)}


def test_the_answer_card_shows_the_jsons_numbers(punch_press):
    solution, data = punch_press
    design = data["design"]
    card = solution._repr_html_()
    assert card.startswith('<div class="card flyopt-answer ok">') and card.endswith("</div>")
    assert f"<b>{html.escape(data['title'])}</b>: status <b>designed</b>" in card
    verdict = html.unescape(re.search(r"<p>(.*?)</p>", card).group(1))
    assert _shown_equal(re.search(rf", ({NUM}) kg, outer diameter", verdict).group(1), design["mass"])
    named = _named(card)
    for field, scale, unit in (("mass", 1, "kg"), ("d_outer", 1e3, "mm"), ("h", 1e3, "mm"), ("rim_speed", 1, "m/s")):
        assert _shown_equal(re.match(rf"({NUM}) {unit}", named[field]).group(1), design[field] * scale), field
    assert _shown_equal(re.search(rf"× ({NUM}) mm", named["h"]).group(1), design["b"] * 1e3)
    assert _shown_equal(re.match(rf"({NUM}) kg·m²", named["j_flywheel"]).group(1), design["j_flywheel"])
    assert _shown_equal(re.match(rf"({NUM}) kg·m²", named["j_required"]).group(1), data["j_required"])
    assert named["delta"].startswith(f"{data['delta']:g} ")
    cells = _cells(card)
    assert cells["chosen wheel"].startswith("rim of cast steel on the motor shaft")


def test_the_card_is_in_the_units_asked_for(punch_press):
    solution, data = punch_press
    from flyopt.report.notebook import answer_card

    imperial = _named(answer_card(solution, "imperial"))
    inches = float(re.match(rf"({NUM}) in", imperial["d_outer"]).group(1).replace(",", ""))
    assert inches == pytest.approx(data["design"]["d_outer"] / 0.0254, rel=1e-3)
    assert re.match(rf"{NUM} lb$", imperial["mass"])
    six = _named(answer_card(solution, "engineering", digits=6))["mass"]
    assert six == f"{data['design']['mass']:.6g} kg"


def test_an_analysis_shows_the_card_of_the_cycle(punch_press):
    """``flyopt.analyse`` (the cycle without a design) shows the card a solution shows, without the wheel: its rows
    are the solution's of the same cycle, status "analysed"."""
    solution, data = punch_press
    card = flyopt.analyse(solution.scene)._repr_html_()
    assert "status <b>analysed</b>" in card and html.escape(data["title"]) in card
    cells, whole = _cells(card), _cells(solution._repr_html_())
    assert cells == {k: v for k, v in whole.items() if k in cells}
    assert {"model", "A_max", "required flywheel J_F"} <= set(cells) and "mass" not in cells
    named = _named(card)
    assert _shown_equal(re.match(rf"({NUM}) kJ", named["a_max"]).group(1), data["a_max"] / 1e3)
    verdict = html.unescape(re.search(r"<p>(.*?)</p>", card).group(1))
    assert _shown_equal(re.search(rf"a flywheel of ({NUM}) kg·m²", verdict).group(1), data["j_required"])


def test_the_card_escapes_what_the_scene_says(tmp_path):
    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    title = re.search(r'^title = "(.*)"$', text, re.M).group(0)
    path = tmp_path / "hostile.toml"
    path.write_text(text.replace(title, 'title = "<script>alert(1)</script> & co"'), encoding="utf-8")
    card = flyopt.solve(flyopt.load(path))._repr_html_()
    assert "<script>" not in card and "&lt;script&gt;alert(1)&lt;/script&gt; &amp; co" in card


def test_a_machine_that_needs_no_flywheel_has_a_card_that_says_so():
    card = flyopt.solve(flyopt.load(PROBLEMS / "conveyor.toml"))._repr_html_()
    verdict = html.unescape(re.search(r"<p>(.*?)</p>", card).group(1))
    assert verdict.startswith("No flywheel is needed: the machine's own inertia keeps δ within")
    assert "status <b>not needed</b>" in card and "mass" not in _cells(card)


def test_the_ranking_as_a_frame_is_the_jsons_candidates_with_their_units(punch_press):
    solution, data = punch_press
    candidates = data["design"]["candidates"]
    frame = solution.design.to_frame()
    assert len(frame) == len(candidates) == 9
    for column in ("mass", "d_outer", "h", "b", "rim_speed", "j_flywheel", "speed_ratio"):
        assert [None if math.isnan(v) else v for v in frame[column]] == [c[column] for c in candidates], column
    assert list(frame["material"]) == [c["material"] for c in candidates]
    assert list(frame["binding"]) == [",".join(c["binding"]) for c in candidates]
    assert frame["feasible"].dtype == bool and "parts" not in frame and "stress" not in frame
    units = frame.attrs["flyopt"]["units"]
    assert (units["mass"], units["d_outer"], units["j_flywheel"], units["rim_speed"]) == ("kg", "m", "kg*m**2", "m/s")
    shown = solution.design.to_frame("engineering")
    mm = [math.nan if c["d_outer"] is None else c["d_outer"] * 1e3 for c in candidates]
    assert any(math.isnan(v) for v in mm)  # an infeasible combination has no size: NaN, not 0
    assert shown["d_outer"].tolist() == pytest.approx(mm, rel=1e-15, nan_ok=True)
    assert shown.attrs["flyopt"]["units"]["d_outer"] == "mm" and shown.attrs["flyopt"]["si_units"]["d_outer"] == "m"


def test_the_ranking_shows_in_a_notebook_with_the_jsons_numbers(punch_press):
    solution, data = punch_press
    table = solution.design._repr_html_()
    header = re.findall(r"<th>([^<]*)</th>", table)
    body = table[table.index("<tbody>") :]
    rows = [re.findall(r"<td>([^<]*)</td>", row) for row in re.findall(r"<tr>(.*?)</tr>", body, re.S)]
    assert header[:5] == ["material", "shaft", "feasible", "mass [kg]", "d_outer [mm]"]
    candidates = data["design"]["candidates"]
    assert len(rows) == len(candidates)
    for row, candidate in zip(rows, candidates):
        cell = dict(zip(header, row))
        assert cell["shaft"] == candidate["shaft"]
        if candidate["mass"] is None:
            assert cell["mass [kg]"] == cell["d_outer [mm]"] == "-"
        else:
            assert _shown_equal(cell["mass [kg]"], candidate["mass"])
            assert _shown_equal(cell["d_outer [mm]"], candidate["d_outer"] * 1e3)
            # the JSON's names in words, one for one (rim_speed -> "rim speed"): no code name reaches the reader
            words = cell["binding, or why not"].split(", ")
            assert len(words) == len(candidate["binding"]) and all("_" not in w for w in words)
    assert rows[0][0] == "cast steel"  # the material's name for people, as the text writes it


def test_a_result_shows_itself_without_the_public_names():
    """The views are found when the result came from flyopt.pipeline directly; import flyopt stays light."""
    code = (
        "import sys\n"
        "import flyopt\n"
        "assert 'flyopt.report.notebook' not in sys.modules\n"
        "from flyopt.io.scene import load\n"
        "from flyopt.pipeline import solve\n"
        f"print(solve(load({str(PROBLEMS / 'shear-press.toml')!r}))._repr_html_()[:30])\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True, timeout=120
    ).stdout
    assert out.startswith('<div class="card flyopt-answer')


# --------------------------------------------------------------------------
# A sweep's file in the units it was given in
# --------------------------------------------------------------------------

RPM = [50.0, 60.0, 70.0]


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    scene = flyopt.load(PROBLEMS / "punch-press.toml")
    paths = {kind: folder / f"study.{kind}" for kind in ("parquet", "csv")}
    for path in paths.values():
        flyopt.sweep(scene, {"speed": "50,60,70rpm", "design.max_width": "150mm"}, workers=1, output=path)
    return paths


def test_pandas_alone_reads_the_speed_in_si(swept):
    """What the file holds: SI (the reason read_results offers the user's units)."""
    frame = pd.read_parquet(swept["parquet"])
    assert frame["speed"].tolist() == pytest.approx([n * 2 * math.pi / 60 for n in RPM], rel=1e-15)


@pytest.mark.parametrize("kind", ["parquet", "csv"])
def test_read_results_gives_a_sweep_back_in_the_units_it_was_given_in(swept, kind):
    si = flyopt.read_results(swept[kind])
    frame = flyopt.read_results(swept[kind], units="input")
    assert frame["speed"].tolist() == pytest.approx(RPM, rel=1e-14)
    assert frame["design.max_width"].tolist() == pytest.approx([150.0] * 3, rel=1e-14)
    meta = frame.attrs["flyopt"]
    assert meta["sweep"]["vary"]["speed"]["unit"] == "rpm" and meta["sweep"]["vary"]["design.max_width"]["unit"] == "mm"
    assert (meta["units"]["speed"], meta["si_units"]["speed"], meta["shown_in"]) == ("rpm", "rad/s", "input")
    assert (meta["units"]["design.max_width"], meta["units"]["mass"], meta["units"]["d_outer"]) == ("mm", "kg", "m")
    assert frame["mass"].tolist() == si["mass"].tolist() and frame["d_outer"].tolist() == si["d_outer"].tolist()
    assert meta["scene_digest"] == si.attrs["flyopt"]["scene_digest"]  # the rest of the metadata kept


def test_read_results_in_a_unit_system(swept):
    si = flyopt.read_results(swept["parquet"])
    frame = flyopt.read_results(swept["parquet"], columns=["speed", "d_outer", "status"], units="engineering")
    assert frame["speed"].tolist() == pytest.approx(RPM, rel=1e-14)
    assert frame["d_outer"].tolist() == pytest.approx((si["d_outer"] * 1e3).tolist(), rel=1e-15)
    assert frame["status"].tolist() == si["status"].tolist()
    assert (frame.attrs["flyopt"]["units"]["d_outer"], frame.attrs["flyopt"]["units"]["speed"]) == ("mm", "rpm")
    labelled = flyopt.to_units(si[["speed", "mass", "status"]], "imperial", labels=True)
    assert list(labelled.columns) == ["speed [rpm]", "mass [lb]", "status"]
    assert labelled["mass [lb]"].tolist() == pytest.approx((si["mass"] / 0.45359237).tolist(), rel=1e-15)


def test_units_refused_in_one_line(swept):
    frame = flyopt.read_results(swept["parquet"], units="engineering")
    with pytest.raises(ValueError, match=r"already in 'engineering' units"):
        flyopt.to_units(frame, "si")
    with pytest.raises(ValueError, match=r"units 'metric' is not known \(allowed: input, engineering, si, imperial\)"):
        flyopt.read_results(swept["parquet"], units="metric")
    with pytest.raises(ValueError, match=r"'input' needs a sweep's table"):
        flyopt.to_units(pd.DataFrame({"mass": [1.0]}), "input")


def test_a_trade_off_in_the_engineers_units():
    """The studies' tables are DataFrames already: to_units shows them in a unit system, their units in attrs."""
    table = flyopt.material_tradeoff(flyopt.load(PROBLEMS / "punch-press.toml"))
    shown = flyopt.to_units(table, "engineering", labels=True)
    assert shown["d_outer [mm]"].tolist() == pytest.approx((table["d_outer"] * 1e3).tolist(), rel=1e-15)
    assert (
        shown["mass [kg]"].tolist() == table["mass"].tolist()
        and shown["material"].tolist() == table["material"].tolist()
    )
    assert shown.attrs["flyopt"]["units"]["rim_speed"] == "m/s" and "flyopt" not in table.attrs  # the table untouched


def test_a_drive_s_card_names_its_motor_once_and_its_rating_on_its_own_row():
    """press-drive: the card said 'motor 132S-4 5.5 kW: 5.5 kW'; the catalogue's name, then the rated power
    from the JSON as the card writes a power."""
    from flyopt.report import display

    path = PROBLEMS / "press-drive.toml"
    solution = flyopt.solve(flyopt.load(path))
    motor = json.loads(solution_json(solution, str(path)))["drive"]["best"]["motor"]
    cells = _cells(solution._repr_html_())
    assert cells["motor"] == motor["name"]
    assert cells["rated power"] == display.quantity_text(motor["rated_power"], "power", "engineering")


#: Values as a user writes them, with their unit, each read into SI by flyopt's own reader: whole, decimal, of
#: one figure and of fifteen (the most a double keeps), small and large; a study's fields (the columns that are
#: not results).
WRITTEN = {
    "speed": ("rpm", ["1500", "750", "2999.5", "0.3", "1234.56789012345", "60"]),
    "design.max_outer_diameter": ("mm", ["1200", "0.7", "592.2", "1000.00000000001", "3", "25.4"]),
    "design.max_width": ("mm", ["96.1", "1", "0.1", "1e3", "45", "2.5"]),
    "design.d_mean": ("mm", ["19.5", "7", "0.35", "210", "123456.789012345", "1"]),
}


def test_a_table_in_the_users_units_shows_what_was_written_and_keeps_every_other_figure():
    """SI values read from what a user wrote ("1500rpm" is 157.07963267948966 rad/s) and shown again in those
    units are the decimals written: 1500 rpm was 1500.0000000000002, the conversion's round-off. A result equal
    to a value written (a diameter at its envelope, a front's outer_diameter beside its d_outer) is shown equal
    to it; any other moves by no more than the round-off, a few units in the last place; missing values stay
    missing in the column's own dtype."""
    import numpy as np

    from flyopt.units import quantity

    dimensions = {"speed": "angular_speed"}
    si = pd.DataFrame(
        {
            name: [quantity(f"{text} {unit}", dimensions.get(name, "length"), name) for text in texts]
            for name, (unit, texts) in WRITTEN.items()
        }
    )
    assert si["speed"][0] / (np.pi / 30) == 1500.0000000000002  # the round-off taken off
    shown = flyopt.to_units(si, "engineering")
    for name, (unit, texts) in WRITTEN.items():
        assert shown.attrs["flyopt"]["units"][name] == unit
        assert shown[name].tolist() == [float(text) for text in texts], name  # exactly: no figure lost, none added
    envelope = quantity("0.57 m", "length", "design.max_outer_diameter")
    designed = pd.DataFrame(
        {
            "design.max_outer_diameter": [envelope] * 5,
            "d_outer": pd.array([envelope, 0.4816964485754085, 1 / 3, None, np.inf], dtype="Float64"),
            "outer_diameter": [envelope, 0.4816964485754085, 1 / 3, np.nan, np.inf],
        }
    )
    assert envelope / 1e-3 == 569.9999999999999  # what a result at the envelope showed beside 570.0
    got = flyopt.to_units(designed, "engineering")
    assert got["d_outer"].dtype == "Float64" and got["d_outer"].isna().tolist() == [False, False, False, True, False]
    assert got.loc[0, "d_outer"] == got.loc[0, "outer_diameter"] == got.loc[0, "design.max_outer_diameter"] == 570.0
    exact = designed["outer_diameter"].to_numpy() / 1e-3
    values = got["outer_diameter"].to_numpy()
    assert np.isnan(values[3]) and values[4] == np.inf
    finite = np.isfinite(exact)
    assert (np.abs(values[finite] - exact[finite]) <= 4 * np.spacing(exact[finite])).all()
    assert got["d_outer"].tolist()[:3] == values[:3].tolist()


def test_the_round_off_taken_off_is_that_of_pythons_own_fifteen_figures():
    """display.without_conversion_noise, in numpy over a whole column, against Python's own decimal of 15
    figures (``float(f"{x:.15g}")``, kept where within 4 ulp, sizes 1e-8 to 1e37) one value at a time: random
    values over 44 decades, decimals of 1 to 15 figures converted to and from rpm and mm, values halfway between
    two decimals, and values about every power of ten (a review found 41,000 of 300,000 of those wrong)."""
    import math

    import numpy as np

    from flyopt.report.display import without_conversion_noise

    def reference(value):
        if not math.isfinite(value) or value == 0.0 or not 1e-8 <= abs(value) < 1e37:
            return value
        shorter = float(f"{value:.15g}")
        return shorter if abs(shorter - value) <= 4 * math.ulp(value) else value

    rng = np.random.default_rng(7)
    written = [float(f"{d:.{k}g}") for d, k in zip(rng.uniform(0, 1e4, 20000), rng.integers(1, 16, 20000))]
    values = np.concatenate(
        [
            rng.normal(size=20000) * 10.0 ** rng.integers(-8, 36, 20000),
            np.array(written) * (math.pi / 30) / (math.pi / 30),
            np.array(written) * 1e-3 / 1e-3,
            [82000270.57036075, -8.022875453678814e16, 0.0, -0.0, math.inf, -math.inf, math.nan, 1e-9, 1e40],
            # about the powers of ten, where log10 may give the next decade: 40 ulp either side of each
            [p + k * np.spacing(p) for p in (float(f"1e{e}") for e in range(-9, 39)) for k in range(-40, 41)],
            [999999999999998.9, 9.999999999999994e32, 5.000000000000001e36, 9.999999999999999e-9],
        ]
    )
    got = without_conversion_noise(values)
    expected = np.array([reference(float(v)) for v in values])
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))  # bit for bit, the sign of 0 and nan too
    assert (got != values).sum() > 1000  # the noise was there to take off


def test_a_cards_colour_is_the_answer_sections():
    """The card is red where the report's answer section warns, in any of its paragraphs (the courses' rim over
    its allowable at omega_max: a second paragraph, which the card ignored), and green for a calculation that
    holds (its status, "calculated", was missing from the good ones: every calculation's card was red)."""
    from conftest import PROBLEMS

    from flyopt.report.card import card_html, solution_card

    book = solution_card(flyopt.solve(flyopt.load(PROBLEMS / "textbook" / "khurmi-16-14-book-rim.toml")))
    assert "OVER" in " ".join(row.value for row in book.rows)
    assert book.warned and not book.good and card_html(book).startswith('<div class="card flyopt-answer bad">')
    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.card import card_of

    document = build(collect(PROBLEMS / "textbook" / "khurmi-16-21.toml"), figures=False)
    try:
        calculation = card_of(document)
    finally:
        document.close()
    assert calculation.status == "calculated" and calculation.good
    assert card_html(calculation).startswith('<div class="card flyopt-answer ok">')
