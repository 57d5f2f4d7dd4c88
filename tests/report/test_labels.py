"""Area labels are placed after the figure's layout alone (no whole draw): where a draw would put them."""

from pathlib import Path

import numpy as np
import pytest

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


@pytest.mark.parametrize("scene", ["slider-crank-press", "motor-press"])
def test_lay_out_puts_the_axes_where_a_whole_draw_puts_them(scene):
    """The reference is matplotlib's own draw without rendering (what the labels were placed after before):
    the Axes' position and the map of its data to pixels must be the same, to the last bit. With its engine
    left in place (``keep`` False, as on a caller's figure), so that the draw lays the figure out again."""
    import matplotlib.pyplot as plt

    import flyopt
    from flyopt.report import plots
    from flyopt.report.plots.labels import lay_out

    loaded = flyopt.load(PROBLEMS / f"{scene}.toml")
    analysis = flyopt.analyse(loaded)
    ax = plots.plot_turning_moment(loaded, analysis)
    ax.figure.set_layout_engine("constrained")  # the engine the plot set aside once its labels were placed
    try:
        probe = np.array([[0.0, 0.0], [90.0, 0.5], [360.0, 1.0]])
        lay_out(ax, keep=False)
        laid, mapped = ax.get_position().bounds, ax.transData.transform(probe)
        ax.figure.draw_without_rendering()
        assert ax.get_position().bounds == laid
        np.testing.assert_array_equal(ax.transData.transform(probe), mapped)
    finally:
        plt.close(ax.figure)


def _sawtooth_scene(tmp_path, rows):
    """A torque table that crosses its mean at nearly every row: a thousand areas between the curves."""
    import flyopt

    points = ", ".join(f"[{360 * k / (rows - 1)!r}, {1000 + (k % 7) * (1 + k / rows)!r}]" for k in range(rows))
    path = tmp_path / "saw.toml"
    path.write_text(
        f'[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n[torque.resisting]\nangle_unit = "deg"\nunit = "N*m"\n'
        f'points = [{points}]\n[torque.driving]\nconstant = "unknown"\n',
        encoding="utf-8",
    )
    return flyopt.load(path)


def test_of_many_areas_the_largest_alone_are_labelled(tmp_path):
    """A table crossing its mean a thousand times gets MAX_AREA_LABELS labels, on its largest areas (each label
    was a search over the drawn points: thousands made `flyopt report` take minutes), and a few areas keep one
    each."""
    import matplotlib.pyplot as plt

    import flyopt
    from flyopt.report import plots
    from flyopt.report.plots.cycle import Torques
    from flyopt.report.plots.turning_moment import MAX_AREA_LABELS

    scene = _sawtooth_scene(tmp_path, 1200)
    analysis = flyopt.analyse(scene)
    areas = sorted((abs(a) for *_lr, a in Torques.of(scene, analysis).areas()), reverse=True)
    assert len(areas) > 5 * MAX_AREA_LABELS
    ax = plots.plot_turning_moment(scene, analysis)
    try:
        labels = [t for t in ax.texts if t.get_gid() == "area"]
        assert 0 < len(labels) <= MAX_AREA_LABELS
        energy = {t.get_text() for t in labels}
        assert len(energy) >= 1
    finally:
        plt.close(ax.figure)
    few = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    ax = plots.plot_turning_moment(few, flyopt.analyse(few))
    try:
        assert 0 < len([t for t in ax.texts if t.get_gid() == "area"]) < MAX_AREA_LABELS
    finally:
        plt.close(ax.figure)


def test_a_long_energy_chain_is_scanned_once_for_its_scale(tmp_path, monkeypatch, capsys):
    """`flyopt solve`'s energy-indicator table finds its columns' largest magnitude once (display.Column), not
    once for each of its cells: the values scanned stay within a few times the rows (it was rows² and took
    `flyopt solve` 13 s on a 25,000-row table)."""
    import flyopt
    from flyopt.cli.main import main
    from flyopt.report import display

    scene = _sawtooth_scene(tmp_path, 1200)
    rows = len(flyopt.analyse(scene).energy_chain)
    assert rows > 300
    scanned = {"values": 0}
    original = display.largest

    def counting(values):
        if not isinstance(values, display.Column):
            scanned["values"] += len(values)
        return original(values)

    monkeypatch.setattr(display, "largest", counting)
    assert main(["solve", str(tmp_path / "saw.toml")]) == 0
    assert capsys.readouterr().out.count("\n") > rows
    assert scanned["values"] <= 10 * rows, scanned


def test_a_column_gives_the_numbers_its_list_gives():
    """display.Column: the same unit and the same texts as the plain list of its values."""
    from flyopt.report import display

    values = [1234.5, -3.7e-16, None, 0.25, 98765.4]
    column = display.Column(values)
    assert display.largest(column) == display.largest(values) == 98765.4
    assert list(column) == values and len(column) == 5 and column[3] == 0.25
    for v in values:
        assert display.field_number(v, "energy", "engineering", 4, column) == display.field_number(
            v, "energy", "engineering", 4, values
        )
