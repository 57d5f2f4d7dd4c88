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


@pytest.mark.parametrize("log", [False, True])
def test_the_svg_writes_a_curve_to_two_decimals_where_the_read_out_puts_it(log):
    """The SVG's paths carry flyopt.report.html.PATH_DECIMALS (2) decimals of a point (matplotlib writes 6): each
    vertex of a curve's path is its data point through the recorded transform to within half the last digit
    kept, so that the page's guide and dots sit on the drawn curve (one point is 1/72 in)."""
    from flyopt.report.html import PATH_DECIMALS

    ax, _own = standard.axes(None)
    figure = standard.figure_of(ax)
    x = np.linspace(1.0, 50.0, 37)
    y = 3.0 + x**1.5 + np.sin(x)  # no point on a grid of round numbers
    (line,) = ax.plot(x, y, color="tab:blue", gid="curve")
    if log:
        ax.set(xscale="log", yscale="log")
    readout.abscissa(ax, "x", standard.scale("length", "engineering"))
    readout.curve(line, "y", standard.scale("length", "engineering"))
    svg = svg_of(figure, "r")
    entry = readout.record(figure)["axes"][0]
    data = re.search(r'<g id="rcurve">\s*<path d="([^"]+)"', svg).group(1)
    numbers = re.findall(r"-?\d+(?:\.\d+)?", data)
    assert max(len(n.partition(".")[2]) for n in numbers) == PATH_DECIMALS == 2
    vertices = np.array([float(n) for n in numbers]).reshape(-1, 2)
    assert len(vertices) == len(x)  # 37 points: too few to simplify
    expected = np.array([readout.to_svg(entry, a, b) for a, b in zip(x, y)])
    assert np.abs(vertices - expected).max() <= 0.5 * 10.0**-PATH_DECIMALS + 1e-9
    assert np.abs(vertices - expected).max() > 1e-4  # rounded indeed (matplotlib's six decimals are within 5e-7)


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


def test_named_points_sit_where_matplotlib_drew_them_and_carry_their_own_texts():
    """A scatter's offsets, a marker line's points and a LineCollection's pieces joined: each named point is
    recorded at its drawn place (the SVG's own ``<use>`` and transData), with its texts; a point outside the
    limits is left out, and more than MARKS points are thinned to every k-th."""
    from matplotlib.collections import LineCollection

    from flyopt.errors import BrokenInvariant

    ax, _own = standard.axes(None)
    figure = standard.figure_of(ax)
    dots = ax.scatter([2.0, 5.0, 40.0], [3.0, 8.0, 1.0], color="tab:green", gid="dots")
    readout.points(dots, [["a"], ["b", "b2"], ["c"]])
    (ring,) = ax.plot([7.0], [6.0], "o", mfc="white", mec="red", gid="ring")
    readout.points(ring, [["ring"]])
    n = 2 * readout.MARKS + 1
    t = np.linspace(0.0, 2.0 * np.pi, n)
    xy = np.column_stack([5.0 + 2.0 * np.cos(t), 5.0 + 2.0 * np.sin(t)])  # turns back in x: no curve of x
    pieces = [xy[a : b + 1] for a, b in zip(range(0, n - 1, 10), [*range(10, n - 1, 10), n - 1])]
    loop = LineCollection(pieces, color="black")
    ax.add_collection(loop)
    readout.points(loop, [[f"k = {k}"] for k in range(n)])
    with pytest.raises(BrokenInvariant, match="names 2 points of an artist that draws 3"):
        readout.points(dots, [["a"], ["b"]])
    ax.set(xlim=(0.0, 10.0), ylim=(0.0, 10.0))
    svg = svg_of(figure, "m")
    (entry,) = readout.record(figure)["axes"]
    assert entry["at"] == [] and entry["rows"] == []  # no abscissa named: points only
    marks = entry["marks"]
    assert marks["rows"][:3] == [["ring"], ["a"], ["b", "b2"]]  # the point at x = 40 is off the limits
    assert marks["colours"][:3] == ["#ff0000", "#2ca02c", "#2ca02c"]  # a ring by its edge
    assert marks["ranks"] == [0, 0, 0] + [1] * (len(marks["xy"]) - 3)  # markers before a line's points
    assert [r[0] for r in marks["rows"][3:]] == [f"k = {k}" for k in range(0, n, 3)]  # every third of 961
    for (x, y), rows in zip(marks["xy"][3:], marks["rows"][3:]):
        k = int(rows[0].split(" = ")[1])
        assert (x, y) == pytest.approx(tuple(xy[k]), rel=1e-6)
    use = re.search(r'id="mring".*?<use [^>]*x="([-\d.]+)" y="([-\d.]+)"', svg, re.S)
    assert readout.to_svg(entry, *marks["xy"][0]) == pytest.approx((float(use[1]), float(use[2])), abs=0.01)
    for x, y in marks["xy"][:3]:
        assert readout.to_svg(entry, x, y) == pytest.approx(svg_point(figure, ax, x, y), abs=1e-4)


def test_the_energy_mass_read_out_of_a_tangent_point_is_a_point_of_the_tangent():
    """Each tangent is the line through the true origin (−J_F, −E_0) of slope ω²/2 (ω_max or ω_min,
    docs/flywheel-design.md, section 6): the read-out's J_e and ΔE at its tangent point, read back from its texts
    (four figures), lie on that line; its φ is the model's angle of that extreme speed."""
    import flyopt
    from flyopt.report.plots import plot_energy_mass

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    analysis = flyopt.analyse(scene, model="energy_mass")
    em = analysis.requirement.detail
    ax = plot_energy_mass(scene, analysis)
    figure = standard.figure_of(ax)
    svg_of(figure, "em")
    entries = readout.record(figure)["axes"]
    near = next(e for e in entries if any(r[0].startswith("the tangent") for r in e["marks"]["rows"]))
    angle = standard.scale("angle", "engineering")
    for w, at, name in ((em.omega_max, em.phi_omega_max, "max"), (em.omega_min, em.phi_omega_min, "min")):
        (rows,) = [r for r in near["marks"]["rows"] if r[0] == f"the tangent of ω_{name} touches"]
        assert rows[1] == f"φ = {angle.q(at)}"
        j = float(re.fullmatch(r"J_e = ([-\d.]+) kg·m²", rows[2])[1])
        de = float(re.fullmatch(r"ΔE = ([-\d.]+) J", rows[3])[1])
        slope = (de + em.e0) / (j + em.j_required)
        assert slope == pytest.approx(0.5 * w**2, rel=2e-3)
    # every point of the coloured curve is where the SVG drew it, and says so: its texts are its position
    for (x, y), rows in list(zip(near["marks"]["xy"], near["marks"]["rows"]))[2::37]:
        assert float(rows[1].split()[2]) == pytest.approx(x, rel=6e-4)
        assert float(rows[2].split()[2]) == pytest.approx(y, rel=6e-4, abs=0.06)
        assert readout.to_svg(near, x, y) == pytest.approx(svg_point(figure, ax, x, y), abs=1e-4)


def test_the_cross_section_reads_the_radius_under_the_pointer_in_both_halves():
    """The axial section names its height r, its magnitude (the lower half is the same section mirrored): the
    grid's height nearest the rim's outer edge, as matplotlib placed that edge in the SVG, reads D/2 of the
    design (shear press, `flyopt solve`), to the grid's step, above the axis and below it."""
    import flyopt
    from flyopt.report.plots import plot_cross_section

    design = flyopt.solve(flyopt.load(PROBLEMS / "shear-press.toml")).design.best
    ax = plot_cross_section(design)
    figure = standard.figure_of(ax)
    svg_of(figure, "cs")
    (entry,) = readout.record(figure)["axes"]  # the drawing only: the front view (if any) names nothing
    assert entry["at"] == [] and entry["marks"]["xy"] == []
    across = entry["across"]
    r_o = design.dims.d_outer / 2.0 * 1000.0  # mm, the drawing's unit
    step = across["at"][1] - across["at"][0]
    for sign in (1.0, -1.0):
        edge = svg_point(figure, ax, 0.0, sign * r_o)[1]  # where matplotlib drew the rim's edge
        k = int(np.argmin([abs(readout.to_svg(entry, 0.0, y)[1] - edge) for y in across["at"]]))
        r = float(re.fullmatch(r"r = ([\d.,]+) mm", across["rows"][k])[1].replace(",", ""))
        last = 10.0 ** (np.floor(np.log10(r_o)) - 3)  # four figures' last digit
        assert abs(r - r_o) <= 0.5 * step + 0.5 * last, (r, r_o, step)
