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
