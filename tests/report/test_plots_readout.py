"""The read-outs the app shows under the pointer (flyopt.report.plots.readout): the recorded data-to-SVG
transform puts a data point where matplotlib drew it, and the texts are the curves' values at the abscissa.

Where matplotlib drew a point is read two ways, neither through the recorded transform: from the SVG it wrote
(a marker's ``<use x= y=>``), and from the Axes' own ``transData`` (display pixels at the figure's dpi, turned
into the SVG's points). The values are checked against the shear press's published torques
(docs/flywheel-design.md, worked example 2): M_r = 1600 N·m to 45°, falling linearly to 200 N·m at 90°, then
200 N·m; M_d = 462.5 N·m.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from conftest import PROBLEMS

from flyopt.report import display
from flyopt.report.html import svg_of
from flyopt.report.plots import readout, standard


@pytest.fixture(autouse=True)
def _closed():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def svg_point(figure, ax, x, y):
    """Where (x, y) is in the SVG's user units by matplotlib's own transData (display pixels at the dpi)."""
    px, py = ax.transData.transform((x, y))
    k = 72.0 / figure.dpi
    return px * k, figure.get_size_inches()[1] * 72.0 - py * k


@pytest.mark.parametrize("log", [False, True])
def test_the_transform_puts_a_point_where_matplotlib_drew_it(log):
    ax, _own = standard.axes(None)
    figure = standard.figure_of(ax)
    x = np.linspace(1.0, 50.0, 60)
    (line,) = ax.plot(x, x**1.5, color="tab:blue")
    ax.plot([7.0], [123.0], "s", color="red", ms=6, gid="probe")  # one marker: its place in the SVG
    if log:
        ax.set(xscale="log", yscale="log")
    ax.set_xlabel("x [mm]")
    readout.abscissa(ax, "x", standard.scale("length", "engineering"))
    readout.curve(line, "y", standard.scale("length", "engineering"))
    svg = svg_of(figure, "t")
    entry = readout.record(figure)["axes"][0]
    use = re.search(r'id="tprobe".*?<use [^>]*x="([-\d.]+)" y="([-\d.]+)"', svg, re.S)
    drawn = float(use.group(1)), float(use.group(2))
    assert readout.to_svg(entry, 7.0, 123.0) == pytest.approx(drawn, abs=0.01)  # the SVG writes 1/1000 pt
    for point in ((1.0, 1.0), (50.0, 300.0), (7.0, 123.0)):
        assert readout.to_svg(entry, *point) == pytest.approx(svg_point(figure, ax, *point), abs=1e-6)


def test_the_turning_moment_reads_the_published_torques():
    import flyopt
    from flyopt.report.plots import plot_turning_moment

    scene = flyopt.load(PROBLEMS / "shear-press.toml")
    solution = flyopt.solve(scene)
    ax = plot_turning_moment(scene, solution.analysis)
    figure = standard.figure_of(ax)
    svg_of(figure, "tm")  # laid out as the app draws it
    (entry,) = readout.record(figure)["axes"]
    assert len(entry["at"]) == readout.POINTS and entry["x"]["lim"] == [0.0, 360.0]
    torque = standard.scale("torque", "engineering", [1600.0])  # the axis' unit: kN·m

    def m_r(phi):
        return np.interp(phi, [0.0, 45.0, 90.0, 360.0], [1600.0, 1600.0, 200.0, 200.0])

    for i in range(0, readout.POINTS, 7):
        phi = entry["at"][i]
        rows = entry["rows"][i]
        assert rows[0] == f"φ = {display.quantity_text(np.radians(phi), 'angle', 'engineering')}"
        assert rows[1] == f"M_d = {torque.q(462.5)}"
        assert rows[2] == f"M_r = {torque.q(float(m_r(phi)))}"
        assert entry["values"][1][i] == pytest.approx(m_r(phi) / 1000.0, rel=1e-6)
    assert {entry["rows"][i][1] for i in range(readout.POINTS)} == {"M_d = 0.4625 kN·m"}


def test_curves_without_a_name_and_axes_without_an_abscissa_have_no_read_out():
    ax, _own = standard.axes(None)
    ax.plot([0, 1], [0, 1])
    readout.abscissa(ax, "x", standard.scale("length", "engineering"))
    figure = standard.figure_of(ax)
    svg_of(figure, "n")
    assert readout.record(figure)["axes"] == []
    other, _own = standard.axes(None)
    readout.curve(other.plot([0, 1], [0, 1])[0], "y", standard.scale("length", "engineering"))
    assert readout.record(standard.figure_of(other))["axes"] == []


def test_a_curve_in_pieces_reads_where_a_piece_is_and_nothing_in_a_gap():
    """A stress over the hub and over the rim: one curve, no value between them."""
    ax, _own = standard.axes(None)
    scale = standard.scale("stress", "engineering")
    readout.abscissa(ax, "r", standard.scale("length", "engineering"))
    readout.curve(ax.plot([0.0, 10.0], [5.0, 5.0])[0], "σ_t", scale)
    readout.curve(ax.plot([20.0, 30.0], [1.0, 3.0])[0], "σ_t", scale)
    figure = standard.figure_of(ax)
    svg_of(figure, "p")
    (entry,) = readout.record(figure)["axes"]
    for x, y, row in zip(entry["at"], entry["values"][0], entry["rows"]):
        if x <= 10.0:
            assert y == pytest.approx(5.0) and row[1] == "σ_t = 5 MPa"
        elif x < 20.0:
            assert y is None and row[1] is None
        else:
            assert y == pytest.approx(1.0 + 0.2 * (x - 20.0), rel=1e-6)
