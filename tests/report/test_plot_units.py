"""The diagrams name a quantity in the unit the text names it in (issue 29): each axis of a torque, an energy, a
power or a force takes its prefix from what it draws, by the rule every number flyopt writes follows (one prefix
per axis, as one per table column), and ``flyopt plot --digits`` writes its labels to the figures asked for.

slider-crank-press: A_max 536.683 J (its committed JSON, tests/data/golden) is "536.7 J" in the text; the energy
diagram wrote "0.5367 kJ" on a kJ axis. Its resisting torque peaks at 1.34 kN·m, so its torque axis is in kN·m
and its areas (233.5 J, 536.7 J, 303.2 J) in J.
"""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd
import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.report import plots

SRC = Path(__file__).resolve().parents[2] / "src" / "flyopt" / "report" / "plots"


@pytest.fixture(scope="module")
def slider_crank():
    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    return scene, flyopt.analyse(scene)


def _texts(ax):
    figure = ax.figure
    words = [t.get_text() for t in ax.texts] + [ax.get_title(), ax.get_ylabel()]
    words += [t.get_text() for legend in figure.legends for t in legend.get_texts()]
    return words


def test_the_energy_diagram_names_a_max_as_the_text_does(slider_crank):
    import matplotlib.pyplot as plt

    scene, analysis = slider_crank
    ax = plots.plot_energy(scene, analysis)
    try:
        assert ax.get_ylabel() == "excess work ΔE [J]"
        words = _texts(ax)
        assert "A_max = 536.7 J" in words  # the dimension right of the plot
        assert "A_max = 536.7 J" in ax.get_title()
        assert any(w.startswith("ΔE largest: ΔE = 233.5 J") for w in words), words
        # drawn in J: the curve's extremes on the axis are the chain's, in J
        top = max(max(line.get_ydata()) for line in ax.get_lines() if len(line.get_ydata()) > 2)
        assert top == pytest.approx(233.5, abs=0.1)
    finally:
        plt.close(ax.figure)


@pytest.mark.parametrize(
    "units, torque, area, driving",
    [("engineering", "kN·m", "−536.7 J", "0.2456 kN·m"), ("si", "N·m", "−536.7 J", "245.6 N·m")],
)
def test_the_turning_moment_diagram_takes_one_prefix_per_quantity(slider_crank, units, torque, area, driving):
    import matplotlib.pyplot as plt

    scene, analysis = slider_crank
    ax = plots.plot_turning_moment(scene, analysis, units=units)
    try:
        assert ax.get_ylabel() == f"torque at the reference shaft [{torque}]"
        words = _texts(ax)
        assert area in words, words  # the area labels, read beside the text's A_max
        assert "A_max = 536.7 J" in ax.get_title()
        assert any(w.startswith(f"driving M_d = {driving}") for w in words), words
    finally:
        plt.close(ax.figure)


def test_plot_digits_reach_the_labels(monkeypatch, main_cli, tmp_path, capsys):
    """``flyopt plot --digits 6``: A_max 536.683 J written to six figures, as ``solve --digits 6`` writes it."""
    drawn = {}

    def keep(ax, output, **options):
        drawn["ax"] = ax

    monkeypatch.setattr(plots, "save", keep)
    status, out, err = main_cli(
        "plot", PROBLEMS / "slider-crank-press.toml", "--what", "energy", "--digits", "6", "-o", tmp_path / "e.png"
    )
    assert status == 0, err
    ax = drawn["ax"]
    try:
        assert "A_max = 536.683 J" in _texts(ax)
    finally:
        import matplotlib.pyplot as plt

        plt.close(ax.figure)
    from flyopt.cli.main import main

    with pytest.raises(SystemExit) as refused:  # argparse's one line, exit 2, as solve's --digits 0
        main(["plot", str(PROBLEMS / "slider-crank-press.toml"), "--what", "energy", "--digits", "0", "-o", "e.png"])
    assert refused.value.code == 2 and "--digits" in capsys.readouterr().err


def test_a_results_axis_takes_its_columns_prefix():
    """A sweep's power column of some hundreds of watts is drawn in W, as the text writes 436.3 W (it was kW)."""
    import matplotlib.pyplot as plt

    frame = pd.DataFrame({"delta": [0.05, 0.1, 0.2], "motor_power": [436.3, 512.0, 640.9], "status": ["designed"] * 3})
    ax = plots.plot_sweep(frame, "delta", "motor_power")
    try:
        assert ax.get_ylabel() == "motor power [W]"
        assert list(ax.get_lines()[0].get_ydata()) == pytest.approx([436.3, 512.0, 640.9])
    finally:
        plt.close(ax.figure)


def test_no_diagram_draws_a_prefixed_quantity_in_a_fixed_unit():
    """Every diagram that puts a torque, an energy, a power or a force on an axis or a label does it through its
    axis' Scale (standard.scale): none asks the system's one unit of those dimensions (standard.show, q,
    axis_label or unit with the dimension named)."""
    fixed = re.compile(r"standard\.(?:show|q|axis_label|unit)\([^()]*?[\"'](?:torque|energy|power|force)[\"']")
    found = [
        f"{path.name}: {match.group(0)}"
        for path in sorted(SRC.glob("*.py"))
        for match in fixed.finditer(path.read_text(encoding="utf-8"))
    ]
    assert found == []
