"""Every diagram tells the truth for the model that ran (issue 15, part 1).

Each test asserts on what is drawn (marker positions, curve values, axis
limits, the place of legends and labels after the figure is laid out), and
each failed on the plots as they were before: the defect it guards is
named in its docstring. The references are independent of the plotting
code: published figures (docs/flywheel-design.md, section 12), closed forms
written here, a root found numerically, the energy–mass formula evaluated
on the drawn curve, a forward simulation.
"""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from conftest import PROBLEMS, assert_published

from flyopt.cli.main import main

pytestmark = pytest.mark.filterwarnings("error")


@pytest.fixture(autouse=True)
def _agg():
    import matplotlib

    matplotlib.use("Agg")
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


#: The Axes ``flyopt plot`` drew, by its arguments: several tests read the same diagram.
_DRAWN = {}


@pytest.fixture
def drawn(tmp_path):
    """Run ``flyopt plot`` and return the Axes it would save (nothing is written; drawn once per arguments)."""
    from flyopt.report import plots

    def draw(scene, what, *options):
        key = (scene, what, options)
        if key not in _DRAWN:
            kept = []
            with pytest.MonkeyPatch.context() as patch:
                patch.setattr(plots, "save", lambda ax, path, *a, **k: kept.append(ax) or Path(path))
                status = main(
                    ["plot", str(PROBLEMS / f"{scene}.toml"), "--what", what, *options, "-o", str(tmp_path / "x.png")]
                )
            assert status == 0
            ax = kept[-1]
            import matplotlib.pyplot as plt
            from matplotlib.backends.backend_agg import FigureCanvasAgg

            plt.close(ax.figure)  # kept by this cache, not by pyplot (which closes its figures after each test)
            FigureCanvasAgg(ax.figure)
            ax.figure.set_dpi(72)  # laid out at a low resolution: fast, and the geometry is the same
            ax.figure.canvas.draw()
            _DRAWN[key] = ax
        return _DRAWN[key]

    return draw


# --------------------------------------------------------------------------
# Helpers: what was drawn, and where it landed on the page
# --------------------------------------------------------------------------


def _gid(ax, gid):
    found = [a for a in ax.get_children() if a.get_gid() == gid]
    assert found, f"nothing drawn with gid {gid!r}"
    return found


def _line(ax, starts):
    found = [line for line in ax.lines if line.get_label().startswith(starts)]
    assert len(found) == 1, [line.get_label() for line in ax.lines]
    return found[0]


def _legend(ax):
    legend = ax.get_legend() or (ax.figure.legends[-1] if ax.figure.legends else None)
    assert legend is not None, "no legend"
    return legend


def _legend_text(ax):
    legend = _legend(ax)
    words = [t.get_text() for t in legend.get_texts()] + [legend.get_title().get_text()]
    return " ".join(" ".join(words).split())  # the wrapped lines joined again


def _pixels(line):
    """A line's points on the page, each segment cut in eight so that steps and long segments count."""
    xy = line.get_transform().transform(np.column_stack([np.asarray(d, dtype=float) for d in line.get_data()]))
    t = np.linspace(0.0, 1.0, 9)[:, None, None]
    return (xy[:-1] + t * (xy[1:] - xy[:-1])).reshape(-1, 2)


def _hits(box, points, margin=0.5):
    return bool(
        np.any(
            (points[:, 0] > box.x0 + margin)
            & (points[:, 0] < box.x1 - margin)
            & (points[:, 1] > box.y0 + margin)
            & (points[:, 1] < box.y1 - margin)
        )
    )


def _overlap(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def _assert_standard(ax):
    """The visual standard: everything drawn (titles, labels, legends, texts) inside the figure, the
    legend off the data, a unit on both axes."""
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    drawn = fig.get_tightbbox(renderer)  # [in]: the box around every visible artist
    width, height = fig.get_size_inches()
    tolerance = 1.0 / fig.dpi
    assert -tolerance <= drawn.x0 and drawn.x1 <= width + tolerance, (drawn, width)
    assert -tolerance <= drawn.y0 and drawn.y1 <= height + tolerance, (drawn, height)
    for axes in fig.axes:  # tick labels clear of each other
        for axis in (axes.xaxis, axes.yaxis):
            low, high = sorted(axis.get_view_interval())
            shown = [
                label.get_window_extent(renderer)
                for label, tick in zip(axis.get_ticklabels(), axis.get_ticklocs())
                if label.get_visible() and label.get_text() and low <= tick <= high
            ]
            assert not any(_overlap(a, b) for k, a in enumerate(shown) for b in shown[k + 1 :]), [
                label.get_text() for label in axis.get_ticklabels()
            ]
    legend = _legend(ax).get_window_extent(renderer)
    assert not _overlap(legend, ax.get_window_extent(renderer)), "the legend covers the data"
    for label in (ax.get_xlabel(), ax.get_ylabel()):
        assert label.endswith("]") and "[" in label, label


# --------------------------------------------------------------------------
# turning_moment
# --------------------------------------------------------------------------


@pytest.mark.parametrize("scene", ["slider-crank-press", "engine-members"])
def test_speed_extremes_and_the_ends_of_a_max_are_both_marked_and_explained(drawn, scene):
    """Was: ω_min marked at 264.9° on the slider-crank press, away from the crossing at 177.4° where the
    shading ends, with nothing to say why. Now both are marked, each at its own angle, and the legend
    says that with a variable J_e the speed extremes are the energy–mass tangent points."""
    import flyopt

    ax = drawn(scene, "turning_moment")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / f"{scene}.toml"), extras=("speed",))
    for gid, angle in (("omega_min", analysis.angle_omega_min), ("delta_e_min", analysis.angle_delta_e_min)):
        (mark,) = _gid(ax, gid)
        assert math.isclose(mark.get_xdata()[0], math.degrees(angle), rel_tol=1e-12)
    # the marks are where they should be, by a second computation: ω(φ) of the forward energy–mass
    # method (docs/flywheel-design.md, section 6), lowest within its grid's spacing; ΔE(φ) smallest
    speed = analysis.speed_curve()
    grid = np.degrees(np.max(np.diff(speed.phi)))
    assert abs(math.degrees(speed.phi[np.argmin(speed.omega)]) - _gid(ax, "omega_min")[0].get_xdata()[0]) <= grid
    from scipy.optimize import minimize_scalar

    ew = analysis.machine.angle_only()
    phi = np.linspace(0.0, analysis.cycle_angle, 3601)
    k = int(np.argmin(ew(phi)))
    lowest = minimize_scalar(
        lambda p: float(ew(np.array([p]))[0]),
        bounds=(phi[k - 1], phi[k + 1]),
        method="bounded",
        options={"xatol": 1e-10},
    )
    assert abs(math.degrees(lowest.x) - _gid(ax, "delta_e_min")[0].get_xdata()[0]) < 1e-6
    assert abs(analysis.angle_omega_min - analysis.angle_delta_e_min) > math.radians(0.3)  # they do differ
    assert "energy–mass tangents touch" in _legend_text(ax)
    _assert_standard(ax)


def test_slider_crank_press_published_angles(drawn):
    """The slider-crank press of the issue: ω_min at 264.9°, the end of the deficit at 177.4° (one decimal)."""
    ax = drawn("slider-crank-press", "turning_moment")
    assert_published(_gid(ax, "omega_min")[0].get_xdata()[0], "264.9")
    assert_published(_gid(ax, "delta_e_min")[0].get_xdata()[0], "177.4")
    assert "ω_min (energy–mass model): φ = 264.9 deg" in _legend_text(ax)


def test_motor_torque_is_drawn_along_the_periodic_solution(drawn):
    """Was: the motor drawn as a flat line at its mean. Now its characteristic along ω(φ).

    The motor of problems/motor-press.toml on the linear characteristic near its rated point
    (docs/flywheel-design.md, section 7): M = M_n (ω_0 − ω_M)/(ω_0 − ω_n), M_n = P/ω_n, at the motor
    speed ω_M = i ω, reduced to the crank as M' = M i η (section 3); 5.5 kW, 1440 and 1500 rpm, i = 24,
    η = 0.95 × 0.97 = 0.9215, written out here from the scene file.
    """
    import flyopt

    ax = drawn("motor-press", "turning_moment")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "motor-press.toml"))
    solution = analysis.requirement.detail.solution
    driving = _line(ax, "driving")
    phi_deg, torque_knm = (np.asarray(v, dtype=float) for v in driving.get_data())
    np.testing.assert_allclose(phi_deg, np.degrees(solution.phi), rtol=1e-12)
    rpm = 2 * math.pi / 60
    p_rated, w_rated, w_sync, ratio, efficiency = 5500.0, 1440 * rpm, 1500 * rpm, 24.0, 0.95 * 0.97
    motor = p_rated / w_rated * (w_sync - ratio * solution.omega) / (w_sync - w_rated)
    np.testing.assert_allclose(torque_knm * 1e3, motor * ratio * efficiency, rtol=1e-12)
    assert np.ptp(torque_knm) > 1.5  # from about 0.2 to 2.1 kN·m over the cycle: not a flat line
    # periodic with a constant inertia: ∫(M_d − M_r) dφ = ΔE over the cycle = 0, so the mean of the drawn
    # motor torque is the mean load, the balancing constant the analysis reports (trapezoids, 2049+ points)
    resisting = _line(ax, "resisting")
    phi = np.radians(phi_deg)
    mean_driving = np.trapezoid(torque_knm * 1e3, phi) / analysis.cycle_angle
    mean_resisting = np.trapezoid(np.asarray(resisting.get_ydata()) * 1e3, phi) / analysis.cycle_angle
    assert math.isclose(mean_driving, mean_resisting, rel_tol=1e-5)
    assert math.isclose(mean_driving, analysis.driving_torque, rel_tol=1e-5)
    (mean,) = _gid(ax, "mean_driving")
    assert math.isclose(mean.get_ydata()[0] * 1e3, analysis.driving_torque, rel_tol=1e-12)
    # the areas between the drawn curves are those of the periodic solution: E = ½ J ω² of machine and
    # flywheel (constant J) changes by them from crossing to crossing
    j_total = analysis.machine.j_machine + solution.j_flywheel
    energy = 0.5 * j_total * np.asarray(solution.omega) ** 2
    swing = (energy.max() - energy.min()) / 1e3
    labels = sorted(float(t.get_text().replace("−", "-").split()[0]) for t in _gid(ax, "area"))
    assert math.isclose(-labels[0], swing, rel_tol=2e-3)  # the deficit: ω from its highest to its lowest


def test_a_constant_solved_with_the_periodic_solution_is_drawn_with_its_correction(write_scene):
    """An unknown driving constant against a load that depends on speed: the periodic model holds the
    mean speed by correcting the balancing constant. The torques drawn must be those it integrated:
    the kinetic energy of the solution, ½ J ω² (constant J), changes by ∫(M_d − M_r) dφ of the drawn
    curves at every angle (the equation of motion, docs/flywheel-design.md, section 7)."""
    import flyopt
    from flyopt.report import plots

    scene = flyopt.load(
        write_scene("""title = "Balanced drive against a speed-dependent load"
[machine]
speed = "120 rpm"
delta = 0.1
inertia = "2 kg*m^2"
[torque.driving]
constant = "unknown"
[torque.resisting]
expression = "100 + 300*max(0, sin(phi))**2 + 2*omega"
unit = "N*m"
""")
    )
    analysis = flyopt.analyse(scene)
    solution = analysis.requirement.detail.solution
    assert analysis.model == "dynamic" and solution.torque_offset != 0.0
    ax = plots.plot_turning_moment(scene, analysis, units="si")
    phi = np.asarray(_line(ax, "driving").get_xdata())
    net = np.asarray(_line(ax, "driving").get_ydata()) - np.asarray(_line(ax, "resisting").get_ydata())
    from scipy.integrate import cumulative_trapezoid

    energy = 0.5 * (analysis.machine.j_machine + solution.j_flywheel) * np.asarray(solution.omega) ** 2
    swing = np.ptp(energy)
    np.testing.assert_allclose(
        cumulative_trapezoid(net, phi, initial=0.0), energy - energy[0], rtol=0, atol=2e-5 * swing
    )
    assert "(constant, solved with the periodic solution)" in _legend_text(ax)


@pytest.mark.parametrize(
    "scene", ["slider-crank-press", "four-cylinder-engine", "shear-press", "motor-press", "engine-members"]
)
def test_area_labels_sit_clear_of_the_curves(drawn, scene):
    """Was: 8 pt area labels centred between the curves' means, on the curves where the band is thin."""
    ax = drawn(scene, "turning_moment")
    renderer = ax.figure.canvas.get_renderer()
    labels = _gid(ax, "area")
    assert len(labels) >= 2
    curves = [_pixels(_line(ax, "driving")), _pixels(_line(ax, "resisting"))]
    boxes = [t.get_window_extent(renderer) for t in labels]
    for text, box in zip(labels, boxes):
        assert text.get_fontsize() >= 8.5
        assert not any(_hits(box, points) for points in curves), text.get_text()
        assert ax.get_window_extent(renderer).contains(box.x0, box.y0)
    for k, a in enumerate(boxes):
        assert not any(_overlap(a, b) for b in boxes[k + 1 :])
    _assert_standard(ax)


@pytest.mark.parametrize("scene", ["slider-crank-press", "compressor"])
def test_the_area_labels_are_drawn_in_the_layout_they_were_placed_in(tmp_path, scene):
    """Was: the areas' labels were placed by their pixels in the layout made for them (constrained layout,
    measured by the figure's Agg canvas), and every draw laid the figure out again, measured by its own
    renderer: the SVG's (and the PDF's, at 72 dpi) made the axes 6 pt taller under the labels placed for the
    shorter ones, and the layout was paid at each draw. Now the axes and the labels stay where they were
    placed, whatever draws the figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from flyopt.report import html, plots

    kept = []
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(plots, "save", lambda ax, path, *a, **k: kept.append(ax) or Path(path))
        status = main(
            ["plot", str(PROBLEMS / f"{scene}.toml"), "--what", "turning_moment", "-o", str(tmp_path / "x.png")]
        )
    assert status == 0
    ax = kept[-1]
    figure = ax.figure
    placed = ax.get_position().frozen()
    labels = _gid(ax, "area")
    assert labels
    at = [label.get_position() for label in labels]
    to_figure = ax.transData + figure.transFigure.inverted()
    where = to_figure.transform(at)  # the labels' anchors as fractions of the figure
    for draw in (lambda: html.svg_of(figure, "t-"), lambda: FigureCanvasAgg(figure).draw()):
        draw()
        assert ax.get_position().bounds == pytest.approx(placed.bounds, abs=1e-12)
        to_figure = ax.transData + figure.transFigure.inverted()
        np.testing.assert_allclose(to_figure.transform([label.get_position() for label in labels]), where, atol=1e-12)


def test_a_callers_figure_keeps_its_layout_for_what_it_adds_after_the_turning_moment():
    """A review's finding on the above: the layout kept for the labels was kept on a caller's own figure too
    (``ax=``), so that the panel and title it added after the diagram were not laid out (the second panel's
    legend ran out of the figure, to 1.22 of its width). A caller's figure keeps its engine."""
    import matplotlib.pyplot as plt
    from matplotlib.layout_engine import ConstrainedLayoutEngine

    import flyopt
    from flyopt.report import plots

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    analysis = flyopt.analyse(scene)
    figure, (left, right) = plt.subplots(1, 2, figsize=(14, 5), layout="constrained")
    plots.plot_turning_moment(scene, analysis, ax=left)
    assert isinstance(figure.get_layout_engine(), ConstrainedLayoutEngine)
    plots.plot_energy(scene, analysis, ax=right)
    figure.suptitle("A study")
    figure.canvas.draw()
    renderer, whole = figure.canvas.get_renderer(), figure.bbox
    for ax in (left, right):
        legend = ax.get_legend().get_window_extent(renderer)
        assert whole.x0 <= legend.x0 and legend.x1 <= whole.x1, (legend, whole)
    assert figure.get_suptitle() and not _overlap(
        figure._suptitle.get_window_extent(renderer), left.title.get_window_extent(renderer)
    )


def test_steady_conveyor_has_no_speed_marks_and_nothing_overlaps(drawn):
    """Was: conveyor's ω_max and ω_min printed on top of each other at φ = 0 (A_max = 0: no extremes)."""
    ax = drawn("conveyor", "turning_moment")
    renderer = ax.figure.canvas.get_renderer()
    assert not [a for a in ax.get_children() if (a.get_gid() or "").startswith(("omega", "delta_e"))]
    texts = [t for t in ax.texts if t.get_text()] + [ax.title]
    boxes = [t.get_window_extent(renderer) for t in texts]
    assert not any(_overlap(a, b) for k, a in enumerate(boxes) for b in boxes[k + 1 :])
    assert "does not fluctuate" in _legend_text(ax)
    # worked example 4: 5500 N on the 0.25 m drum, 1375 N·m, the driving torque solved equal to it
    assert "M_d = 1.375 kN·m (constant, solved from the work balance)" in _legend_text(ax)
    _assert_standard(ax)


@pytest.mark.parametrize(
    "units, shown, factor",
    [
        ("engineering", "0.4625 kN·m", 1e3),
        ("si", "462.5 N·m", 1.0),
        # 1 lbf·ft = 0.3048 m × 0.45359237 kg × 9.80665 m/s² (the exact definitions of ft, lb and g_n)
        ("imperial", "341.1 lbf·ft", 0.3048 * 0.45359237 * 9.80665),
    ],
)
def test_the_solved_torque_is_shown_in_the_chosen_units(drawn, units, shown, factor):
    """Was: the torque solved from the work balance never shown. The shear press: M_d = 462.5 N·m
    (docs/flywheel-design.md, section 12, example 2); every axis in the chosen units."""
    ax = drawn("shear-press", "turning_moment", "--units", units)
    assert f"M_d = {shown} (constant, solved from the work balance)" in _legend_text(ax)
    driving = _line(ax, "driving").get_ydata()
    np.testing.assert_allclose(driving * factor, 462.5, rtol=1e-12)
    assert ax.get_ylabel().endswith(f"[{shown.split(' ', 1)[1]}]")
    assert ax.get_xlabel() == ("crank angle φ [rad]" if units == "si" else "crank angle φ [deg]")
    assert ax.get_xlim()[1] == pytest.approx(2 * math.pi if units == "si" else 360.0, rel=1e-12)


def test_engine_dead_centres_and_strokes(drawn):
    """Was: a 720° engine without TDC, BDC or strokes. Cylinder 1 of problems/four-cylinder-engine.toml
    fires at 0 (its TDC at the start of intake, by the file): TDC 0, 360, 720, BDC 180, 540 and the
    strokes intake, compression, power, exhaust between them."""
    ax = drawn("four-cylinder-engine", "turning_moment")
    (top,) = [a for a in ax.child_axes if a.get_gid() == "dead_centres"]
    np.testing.assert_allclose(top.get_xticks(), [0, 180, 360, 540, 720], rtol=1e-12, atol=1e-12)
    assert [label.get_text() for label in top.get_xticklabels()] == ["TDC", "BDC", "TDC", "BDC", "TDC"]
    np.testing.assert_allclose(top.get_xticks(minor=True), [90, 270, 450, 630], rtol=1e-12)
    assert [label.get_text() for label in top.get_xticklabels(minor=True)] == [
        "intake",
        "compression",
        "power",
        "exhaust",
    ]
    np.testing.assert_allclose(ax.get_xlim(), (0.0, 720.0), rtol=1e-12)
    _assert_standard(ax)


def test_slider_crank_dead_centres_with_an_offset(write_scene):
    """The dead centres of a slider-crank with an offset e are where the slider stops: found here as the
    roots of v_B/ω (brentq), against the closed form the plot marks, (l ± r) sin ψ = ±e."""
    from scipy.optimize import brentq

    import flyopt
    from flyopt.report import plots

    text = (PROBLEMS / "slider-crank-press.toml").read_text()
    text = text.replace('rod = "0.45 m"', 'rod = "0.45 m"\noffset = "0.05 m"')
    scene = flyopt.load(write_scene(text))
    assert scene.mechanism.offset == 0.05
    ax = plots.plot_turning_moment(scene, flyopt.analyse(scene))
    (top,) = [a for a in ax.child_axes if a.get_gid() == "dead_centres"]
    labels = [label.get_text() for label in top.get_xticklabels()]
    assert labels == ["ODC", "IDC"]  # once each within the turn, now that they moved off 0
    v = scene.mechanism.slider_velocity_ratio
    outer = math.degrees(brentq(v, -0.5, 0.5, xtol=1e-15))
    inner = math.degrees(brentq(v, math.pi - 0.5, math.pi + 0.5, xtol=1e-15))
    np.testing.assert_allclose(top.get_xticks(), [outer, inner], rtol=0, atol=1e-9)
    assert outer > 5.0 and inner > 180.0 + 5.0  # the offset moves them (e/(l ± r) = 0.094, 0.135)


# --------------------------------------------------------------------------
# energy
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "scene, end", [("shear-press", 360.0), ("slider-crank-press", 360.0), ("four-cylinder-engine", 720.0)]
)
def test_energy_diagram_shares_the_turning_moment_axis(drawn, scene, end):
    """Was: the energy diagram's x axis ran from −18° to 378°, not lined up with the turning moment's."""
    energy = drawn(scene, "energy")
    turning = drawn(scene, "turning_moment")
    assert energy.get_xlim() == turning.get_xlim()
    np.testing.assert_allclose(energy.get_xlim(), (0.0, end), rtol=1e-12)
    _assert_standard(energy)


def test_energy_diagram_dimensions_a_max_off_the_curve_and_names_the_extremes(drawn):
    """Was: the A_max arrow drawn across the curve, ω_max and ω_min unnamed, no legend. The shear press:
    A_max = 1256.33 J (docs/flywheel-design.md, section 12, example 2)."""
    ax = drawn("shear-press", "energy")
    renderer = ax.figure.canvas.get_renderer()
    (arrow,) = _gid(ax, "a_max")
    (x_tip, y_tip), (x_tail, y_tail) = arrow.xy, arrow.xyann
    assert x_tip == x_tail > 1.0  # right of the plot, in axes coordinates
    assert_published(abs(y_tip - y_tail) * 1e3, "1256.33")
    curve = _pixels(_line(ax, "ΔE(φ)"))
    assert not _hits(arrow.arrow_patch.get_window_extent(renderer), curve)
    names = {t.get_text() for t in _gid(ax, "extreme_label")}
    assert names == {"ω_max", "ω_min"}
    for t in _gid(ax, "extreme_label"):
        assert not _hits(t.get_window_extent(renderer), curve)
    assert "A_max = 1.256 kJ" in {t.get_text() for t in ax.texts}
    _assert_standard(ax)


def test_energy_diagram_of_the_dynamic_model_holds_both_curves(drawn):
    """With a motor the diagram of the torques frozen at ω_m (the reported A_max) and ΔE along the
    periodic solution are both within the plot."""
    ax = drawn("motor-press", "energy")
    low, high = ax.get_ylim()
    for line in ax.lines:
        values = np.asarray(line.get_ydata(), dtype=float)
        if values.size > 2:
            assert low < values.min() and values.max() < high, line.get_label()
    _gid(ax, "along")
    _assert_standard(ax)


# --------------------------------------------------------------------------
# inertia_delta
# --------------------------------------------------------------------------


def _design_point_on_curve(ax):
    (curve,) = _gid(ax, "j_delta")
    (point,) = _gid(ax, "design_point")
    delta, j = (np.asarray(v, dtype=float) for v in curve.get_data())
    at = float(point.get_xdata()[0])
    k = int(np.argmin(np.abs(delta - at)))
    assert delta[k] == at  # the scene's own δ is one of the curve's points
    return j[k], float(point.get_ydata()[0]), delta, j


@pytest.mark.parametrize("scene", ["slider-crank-press", "motor-press", "engine-members", "shear-press"])
def test_inertia_delta_curve_passes_through_its_design_point(drawn, scene):
    """Was: the constant-inertia hyperbola drawn under the exact model's point, missing it by 11.2 %
    (slider-crank press), 4.7 % (motor press), 1.2 % (engine with members). The curve is now the
    model's own J_F at each δ, computed again at the scene's δ, so it meets the point to the models'
    accuracy."""
    ax = drawn(scene, "inertia_delta")
    on_curve, point, delta, _j = _design_point_on_curve(ax)
    assert math.isclose(on_curve, point, rel_tol=1e-6)
    assert delta.max() <= 0.5 and delta.min() > 0  # was: up to δ = 1.9
    assert "1/δ" not in ax.get_title()
    _assert_standard(ax)


def _largest(g, cycle, knots):
    """The largest value of the smooth-between-knots function ``g`` over [0, ``cycle``]: on 4,001 angles and the
    knots, then on 2,001 angles around each of the largest local maxima found there (a grid's error at a smooth
    extreme is of order h², h = 1.6e-6 rad here, below 1e-11 of the value; one at a knot is the knot's)."""
    coarse = np.union1d(np.linspace(0.0, cycle, 4001), knots)
    values = g(coarse)
    ahead, behind = np.r_[values[1:], -np.inf], np.r_[-np.inf, values[:-1]]
    tops = np.flatnonzero((values >= ahead) & (values > behind))  # a flat top counted once, at its start
    tops = tops[values[tops] >= values.max() - 1e-4 * max(np.abs(values).max(), 1e-300)]
    assert 0 < len(tops) <= 50, len(tops)
    fine = [np.linspace(coarse[max(i - 1, 0)], coarse[min(i + 1, len(coarse) - 1)], 2001) for i in tops]
    return float(max(values.max(), g(np.union1d(np.concatenate(fine), knots)).max()))


def test_inertia_delta_of_the_energy_mass_model_is_the_closed_form_of_section_6(drawn):
    """Off the design point: J_F(δ) by the energy–mass closed form (docs/flywheel-design.md, section 6)
    written here,
    J_F = (max[½ ω_min² J(φ) − ΔE] − min[½ ω_max² J(φ) − ΔE]) / (½ (ω_max² − ω_min²)),
    each extreme found on a grid refined around it (:func:`_largest`; the grid's error at an extreme is of
    order h², below 1e-11 here)."""
    import flyopt

    ax = drawn("slider-crank-press", "inertia_delta")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "slider-crank-press.toml"))
    _on, _point, delta, j = _design_point_on_curve(ax)
    machine, cycle = analysis.machine, analysis.cycle_angle
    knots, energy = machine.knots(), machine.angle_only()
    for k in (0, len(delta) // 3, len(delta) - 1):
        w_max, w_min = analysis.omega_mean * (1 + delta[k] / 2), analysis.omega_mean * (1 - delta[k] / 2)
        top = _largest(lambda phi: 0.5 * w_min**2 * machine.j_machine(phi) - energy(phi), cycle, knots)
        bottom = -_largest(lambda phi: energy(phi) - 0.5 * w_max**2 * machine.j_machine(phi), cycle, knots)
        closed = (top - bottom) / (0.5 * (w_max**2 - w_min**2))
        assert math.isclose(j[k], closed, rel_tol=1e-10), (delta[k], j[k], closed)  # agreed to 2e-12


def test_inertia_delta_of_the_dynamic_model_gives_its_delta_when_simulated(drawn):
    """Off the design point: the flywheel the curve gives at another δ, simulated forward (the periodic
    solution with that J_F, flyopt.sizing.choose.achieved_delta), runs at that δ."""
    import flyopt
    from flyopt.sizing.choose import achieved_delta

    ax = drawn("motor-press", "inertia_delta")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "motor-press.toml"))
    _on, _point, delta, j = _design_point_on_curve(ax)
    k = len(delta) // 4
    assert delta[k] < 0.5 * analysis.delta
    assert math.isclose(achieved_delta(analysis.machine, j[k]), delta[k], rel_tol=1e-6)


def test_inertia_delta_of_a_steady_conveyor_is_nothing_to_draw(tmp_path, capsys):
    """Conveyor (A_max = 0, constant inertia): no flywheel at any δ, said in one line, no crash."""
    out = tmp_path / "j.png"
    assert main(["plot", str(PROBLEMS / "conveyor.toml"), "--what", "inertia_delta", "-o", str(out)]) == 0
    assert "nothing to draw" in capsys.readouterr().out and not out.exists()


# --------------------------------------------------------------------------
# cross_section
# --------------------------------------------------------------------------


def _designed(name):
    import flyopt
    from flyopt.pipeline import design_scene

    scene = flyopt.load(name)
    return design_scene(scene, flyopt.analyse(scene)).best


def test_cross_section_draws_in_the_chosen_units_and_comments_an_odd_design():
    """Was: data in metres under labels in mm; a 1.41 kg ring 8 × 12 mm at Ø617 mm shown without a word.
    Now inches for imperial (1 in = 25.4 mm, exact), and a note says it is the bare rim, and slender."""
    from flyopt.report import plots

    best = _designed(PROBLEMS / "slider-crank-press.toml")
    ax = plots.plot_cross_section(best, units="imperial")
    rim = next(p for p in ax.patches if p.get_gid() == "rim+")
    assert math.isclose(rim.get_y() + rim.get_height(), best.dims.d_outer / 2 / 0.0254, rel_tol=1e-12)
    assert math.isclose(rim.get_width(), best.dims.b / 0.0254, rel_tol=1e-12)
    texts = {t.get_text() for t in ax.texts}
    assert f"Ø{best.dims.d_outer / 0.0254:.3f}".rstrip("0") in texts
    assert "dimensions in in" in ax.figure.get_suptitle()
    (note,) = [t for t in ax.figure.texts if t.get_gid() == "note"]
    words = " ".join(note.get_text().split())
    assert "The rim alone" in words and "A slender rim" in words
    # a bare rim is not designed to the castability rules, but its thinnest wall is checked (this one passes)
    assert best.limits.castability is None and best.parts.thin_wall is None
    assert "its thinnest wall is checked against its process where one is known" in words
    assert f"{best.dims.d_outer / min(best.dims.b, best.dims.h):.0f} times its thinnest side" in words
    # its binding limits in words, as the text and the report's tables name them (issue 29), not row names
    assert "binding: inertia" in words and not any(name in words for name in best.limits.binding if "_" in name)
    ax.figure.canvas.draw()
    box = note.get_window_extent()
    assert ax.figure.bbox.contains(box.x0, box.y0) and ax.figure.bbox.contains(box.x1, box.y1)
    assert not _overlap(box, ax.get_window_extent())


def test_a_slender_whole_wheels_note_says_its_castability_is_checked():
    """punch-press-wheel's slender rim (whole wheel, designed to the castability rules of issue 28): the note
    under its section said its casting was not checked while the report listed its walls and section ratios."""
    from flyopt.report import plots

    best = _designed(PROBLEMS / "punch-press-wheel.toml")
    assert best.limits.castability is not None
    ax = plots.plot_cross_section(best)
    (note,) = [t for t in ax.figure.texts if t.get_gid() == "note"]
    words = " ".join(note.get_text().split())
    assert "A slender rim" in words and "its castability (walls, section ratios) is checked" in words
    assert "casting" not in words


WHEELS = Path(__file__).parents[1] / "data" / "wheels"


@pytest.mark.parametrize(
    "source, size",
    [
        ("engine-rim", None),
        ("engine-disc", None),
        ("engine-rim_web", None),
        ("engine-rim_arms", None),
        ("slider-crank-press", None),
        # drawn on a small Axes of the caller's: the hub's diameters too short for their texts (which go
        # outside their lines) and the hub's length beside the arm's dimension used to collide
        ("engine-rim_arms", (6, 4)),
        ("slider-crank-press", (4, 6)),
    ],
)
def test_cross_section_texts_clear_each_other_and_the_arrows(source, size):
    """Was: the B arrow struck through its label. No text of the drawing overlaps another, an arrow or a line."""
    import matplotlib.pyplot as plt
    from matplotlib.text import Annotation

    from flyopt.report import plots

    path = WHEELS / f"{source}.toml" if source.startswith("engine") else PROBLEMS / f"{source}.toml"
    given = plt.subplots(figsize=size, layout="constrained")[1] if size else None
    ax = plots.plot_cross_section(_designed(path), ax=given)
    ax.figure.set_dpi(72)
    ax.figure.canvas.draw()
    renderer = ax.figure.canvas.get_renderer()
    texts = [t for t in ax.texts if t.get_text() and not isinstance(t, Annotation)]
    boxes = [t.get_window_extent(renderer) for t in texts]
    arrows = [
        a.arrow_patch.get_window_extent(renderer)
        for a in ax.texts
        if isinstance(a, Annotation) and a.arrow_patch is not None
    ]
    lines = [_pixels(line) for line in ax.lines]  # extension and dimension lines, the axis
    for k, (text, box) in enumerate(zip(texts, boxes)):
        assert not any(_overlap(box, other) for other in boxes[k + 1 :]), text.get_text()
        shrunk = box.padded(-1.0)
        assert not any(_overlap(shrunk, arrow) for arrow in arrows), text.get_text()
        assert not any(_hits(box, points, margin=1.0) for points in lines), text.get_text()


# --------------------------------------------------------------------------
# speed
# --------------------------------------------------------------------------


@pytest.mark.parametrize("scene", ["slider-crank-press", "motor-press"])
def test_speed_plot_has_the_mean_speed_and_the_achieved_delta(drawn, scene):
    """Was: no ω_m line, the legend over the data, the title giving the allowed δ. The slider-crank press
    runs at 120 strokes/min (its file); the motor press at the speed the motor's balance gives."""
    import flyopt

    ax = drawn(scene, "speed")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / f"{scene}.toml"), extras=("speed",))
    omega = np.asarray(_gid(ax, "model")[0].get_ydata(), dtype=float)
    (mean,) = _gid(ax, "omega_mean")
    shown = mean.get_ydata()[0]
    if scene == "slider-crank-press":
        assert math.isclose(shown, 120.0, rel_tol=1e-12)
    # ω_m = (ω_max + ω_min)/2 (docs/flywheel-design.md, section 2), within the curve's grid
    assert math.isclose(shown, 0.5 * (omega.max() + omega.min()), rel_tol=1e-5)
    achieved = (omega.max() - omega.min()) / shown
    from flyopt.report.display import number

    assert f"δ = {number(analysis.speed_curve().delta, 4)} achieved" in ax.get_title()
    assert math.isclose(float(number(achieved, 4)), analysis.speed_curve().delta, rel_tol=1e-3)
    _assert_standard(ax)


@pytest.mark.slow  # the drive's design and the chosen machine's periodic solution: 5-7 s
def test_a_drive_scene_draws_the_machine_its_drive_chose(drawn):
    """Was: ``flyopt plot problems/press-drive.toml --what speed`` drew the scene's energy model with a
    48,440 kg·m² flywheel and δ = 0.1176, while ``flyopt solve`` answers a 5.5 kW motor at a ratio of 122.4
    with no flywheel and δ = 0.0431. The drawn ω(φ) is now the chosen machine's: its δ is the one the
    drive's CVODES verification found (the committed golden answer), and no flywheel is drawn."""
    import json

    golden = json.loads((Path(__file__).parents[1] / "data" / "golden" / "press-drive.json").read_text())
    checked = golden["drive"]["verification"]
    ax = drawn("press-drive", "speed")
    omega = np.asarray(_gid(ax, "model")[0].get_ydata(), dtype=float)  # rpm
    rpm = 30.0 / math.pi
    # the drawn curve's own extremes against CVODES's: the two periodic solutions agree to their tolerances
    assert math.isclose(omega.max(), checked["omega_max"] * rpm, rel_tol=1e-4)
    assert math.isclose(omega.min(), checked["omega_min"] * rpm, rel_tol=1e-4)
    assert "δ = 0.0431 achieved, 0.1176 allowed" in ax.get_title()
    assert "J_F = 0 kg·m²" in _legend_text(ax) and "energy model" not in _legend_text(ax)


@pytest.mark.slow  # the drive's search over the catalogue: 2-3 s
def test_a_drive_that_finds_no_motor_draws_no_machine(tmp_path, capsys):
    """Was: with no motor size meeting the limits (press-drive with a 1 ms start-up allowed), ``flyopt plot``
    drew the scene's energy model and its flywheel, a machine without the motor the scene asks for, and exited
    0. Now it says why in one line and exits 3, as ``solve`` answers "no drive"."""
    text = (PROBLEMS / "press-drive.toml").read_text(encoding="utf-8")
    assert 'max_startup = "15 s"' in text
    scene = tmp_path / "press-drive.toml"
    scene.write_text(text.replace('max_startup = "15 s"', 'max_startup = "0.001 s"'), encoding="utf-8")
    out = tmp_path / "speed.png"
    assert main(["plot", str(scene), "--what", "speed", "-o", str(out)]) == 3
    err = capsys.readouterr().err
    # the drive's verdict in one sentence: each kind of reason with its count (the table of sizes gives each)
    assert err.count("\n") == 1 and "no drive meets the limits" in err and "start-up: 13 sizes" in err, err
    assert not out.exists()


# --------------------------------------------------------------------------
# energy_mass
# --------------------------------------------------------------------------


@pytest.mark.parametrize("scene", ["shear-press", "conveyor", "punch-press-wheel"])
def test_energy_mass_of_a_constant_inertia_is_refused(tmp_path, capsys, scene):
    """Was: drawn as a vertical line on a ±5e-10 axis (or 'nothing to draw' for the conveyor)."""
    out = tmp_path / "em.png"
    assert main(["plot", str(PROBLEMS / f"{scene}.toml"), "--what", "energy_mass", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "inertia that varies with the angle" in err and "energy_mass" in err
    assert not out.exists()


def test_energy_mass_shows_the_origin_and_its_tangent_points(drawn):
    """Was: the tangents' meeting point off the plot, tangent points and φ unmarked. The tangent points
    are checked on the drawn curve itself: E_0 = min over φ of ½ ω_max² (J_F + J) − ΔE, so the ω_max
    tangent touches where ½ ω_max² J − ΔE is least, the ω_min one where ½ ω_min² J − ΔE is largest
    (docs/flywheel-design.md, section 6)."""
    import flyopt

    ax = drawn("slider-crank-press", "energy_mass")
    analysis = flyopt.analyse(flyopt.load(PROBLEMS / "slider-crank-press.toml"))
    em = analysis.requirement.detail
    overview = next(a for a in ax.figure.axes if a is not ax and any(c.get_gid() == "origin" for c in a.lines))
    (origin,) = [line for line in overview.lines if line.get_gid() == "origin"]
    # each panel's energy axis in the unit its label names, chosen from what it draws (J near the curve, kJ
    # for the whole, whose origin lies 1.74 kJ down)
    joules = {"[J]": 1.0, "[kJ]": 1e3}
    near, whole = (joules[re.search(r"\[.*\]", a.get_ylabel()).group(0)] for a in (ax, overview))
    assert (near, whole) == (1.0, 1e3)
    x0, y0 = origin.get_xdata()[0], origin.get_ydata()[0]
    assert math.isclose(x0, -em.j_required, rel_tol=1e-12) and math.isclose(y0 * whole, -em.e0, rel_tol=1e-12)
    (left, right), (bottom, top) = overview.get_xlim(), overview.get_ylim()
    assert left < x0 < right and bottom < y0 < top
    (curve,) = _gid(ax, "curve")
    pieces = curve.get_segments()  # polylines, each coloured by its span of φ, each starting where the last ended
    assert all(np.array_equal(a[-1], b[0]) for a, b in zip(pieces[:-1], pieces[1:]))
    drawn_points = np.concatenate([pieces[0][:1]] + [piece[1:] for piece in pieces])
    j, de = drawn_points[:, 0], drawn_points[:, 1] * near
    for w, gid, pick in ((em.omega_max, "tangent_max", np.argmin), (em.omega_min, "tangent_min", np.argmax)):
        k = pick(0.5 * w**2 * j - de)
        (point,) = _gid(ax, gid)
        # within the drawn curve's spacing (1441 angles and the knots: a quarter degree)
        assert math.isclose(point.get_xdata()[0], j[k], rel_tol=0, abs_tol=5e-3 * np.ptp(j))
        assert math.isclose(point.get_ydata()[0] * near, de[k], rel_tol=0, abs_tol=5e-3 * np.ptp(de))
    assert curve.get_array() is not None and "crank angle φ [deg]" in {a.get_ylabel() for a in ax.figure.axes}
    _assert_standard(ax)


# --------------------------------------------------------------------------
# sweep and pareto
# --------------------------------------------------------------------------


def _sweep_frame():
    """A sweep of delta × speed × material as flyopt writes it (SI), one infeasible point."""
    import pandas as pd

    rows = []
    for material in ("cast_iron", "cast_steel"):
        for rpm in (600.0, 900.0):
            for delta in (0.02, 0.05, 0.1):
                mass = (2.0 if material == "cast_iron" else 1.0) * 100.0 / (rpm / 60) ** 2 / delta
                rows.append(
                    {
                        "delta": delta,
                        "speed": rpm * 2 * math.pi / 60,
                        "material": material,
                        "status": "designed",
                        "mass": mass,
                        "d_outer": 0.5,
                    }
                )
    rows[0].update(status="infeasible", mass=float("nan"), d_outer=float("nan"))
    return pd.DataFrame(rows)


def test_sweep_lines_never_join_points_of_another_field_and_show_display_units():
    """Was: three varied fields joined into sawtooth lines, legends of raw SI floats
    ('speed = 62.83185307179586'), infeasible points dropped silently."""
    from flyopt.report import plots

    frame = _sweep_frame()
    ax = plots.plot_sweep(frame, "delta", "mass", by="material")
    lines = [line for line in ax.lines if line.get_label().startswith("material")]
    assert len(lines) == 4  # material × speed
    for line in lines:
        x = np.asarray(line.get_xdata(), dtype=float)
        assert np.all(np.diff(x) > 0), line.get_label()  # one point per δ: no sawtooth
    labels = {line.get_label() for line in lines}
    assert "material = cast_steel, speed = 600 rpm" in labels and "material = cast_iron, speed = 900 rpm" in labels
    (miss,) = _gid(ax, "infeasible")
    assert list(miss.get_xdata()) == [0.02]
    ax.figure.canvas.draw()
    assert "infeasible: no material and shaft can give J_F (1 point)" in _legend_text(ax)
    assert ax.get_xlabel() == "allowed δ [-]" and ax.get_ylabel() == "mass [kg]"
    _assert_standard(ax)


def test_sweep_axes_in_the_chosen_units():
    """The unit of a column is flyopt.outputs.results' (m, rad/s), shown in the system's (mm, rpm; in)."""
    from flyopt.report import plots

    frame = _sweep_frame()
    frame = frame[(frame["material"] == "cast_steel") & (frame["delta"] == 0.05)]
    ax = plots.plot_sweep(frame, "speed", "d_outer")
    assert ax.get_xlabel() == "speed [rpm]" and ax.get_ylabel() == "outer diameter D [mm]"
    np.testing.assert_allclose(ax.lines[0].get_xdata(), [600.0, 900.0], rtol=1e-12)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), [500.0, 500.0], rtol=1e-12)
    ax = plots.plot_sweep(frame, "speed", "d_outer", units="imperial")
    assert ax.get_ylabel() == "outer diameter D [in]"
    np.testing.assert_allclose(ax.lines[0].get_ydata(), [0.5 / 0.0254] * 2, rtol=1e-12)


def test_pareto_refuses_points_of_different_delta(tmp_path, capsys):
    """Was: a 'front' built from points of different δ without a word. Refused in one line (exit 2)."""
    frame = _sweep_frame()
    frame = frame[frame["speed"] == frame["speed"].iloc[0]]
    path = tmp_path / "mixed.csv"
    frame.to_csv(path, index=False)
    out = tmp_path / "p.png"
    assert main(["plot", str(path), "--what", "pareto", "--x", "d_outer", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "differ in delta (delta from 0.02 to 0.1)" in err and not out.exists()
    # δ as an objective is a front of its own (flyopt pareto --objectives mass,delta)
    from flyopt.report import plots

    ax = plots.plot_pareto(frame[frame["material"] == "cast_steel"], "delta", "mass")
    assert len(_gid(ax, "front")[0].get_xdata()) == 3


@pytest.mark.parametrize("units, unit", [("engineering", "mm"), ("imperial", "in")])
def test_a_fronts_axes_name_the_wheel_in_words(units, unit):
    """Was: the axis of ``flyopt pareto``'s front read "outer_diameter [mm]", the file's column, where the
    text and the app say "outer diameter D"; a sweep's ``d_outer`` is the same diameter, said the same way."""
    import pandas as pd

    from flyopt.report import plots

    front = pd.DataFrame(
        {"mass": [40.0, 30.0, 25.0], "outer_diameter": [0.5, 0.6, 0.8], "epsilon": [0.5, 0.6, 0.8]}
    ).assign(status="designed", best_material="cast_iron")
    ax = plots.plot_pareto(front, "outer_diameter", "mass", units=units)
    assert ax.get_xlabel() == f"outer diameter D [{unit}]"
    assert ax.get_ylabel() == ("mass [kg]" if units == "engineering" else "mass [lb]")
    # the read-out under the pointer (the app's) names the diameter as the axis does
    from flyopt.report.plots import readout

    (designs,) = [line for line in ax.lines if line.get_label().startswith("designs")]
    rows = getattr(designs, readout.ATTRIBUTE).rows
    assert [row[1].split(" = ")[0] for row in rows] == ["outer diameter D"] * 3


def test_units_option_is_checked_in_one_line(tmp_path, capsys):
    assert (
        main(
            [
                "plot",
                str(PROBLEMS / "shear-press.toml"),
                "--what",
                "energy",
                "--units",
                "metric",
                "-o",
                str(tmp_path / "x.png"),
            ]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert err == "flyopt: error: --units: unknown unit system 'metric' (allowed: engineering, si, imperial)\n"


def test_speed_without_a_flywheel_is_the_machine_as_it_is():
    """A motor stiff enough that no flywheel is needed (press-drive's chosen 132S-4 at its ratio): the dynamic
    requirement's own solution sits at its margin J_F < 0, a vanishing inertia (where, before the cubic's
    overshoot was kept out of the extremes, it reported δ 0.1176 on a curve of 0.0431, and the plot drew that
    labelled J_F = 0). The speed drawn is the machine with no flywheel: J_F = 0, its extremes those of its
    own curve, and its δ the CVODES verification's. A machine with no inertia of its own (motor-press at
    δ 0.7) is drawn at the vanishing inertia it tends to."""
    from flyopt.analysis import EXTRAS, analyse
    from flyopt.drive.codesign import MotorRun, chosen_scene
    from flyopt.io.scene import load
    from flyopt.machine.catalogue import catalogue
    from flyopt.report import plots
    from flyopt.sizing import periodic

    scene = load(PROBLEMS / "press-drive.toml")
    motor = next(m for m in catalogue("iec_4pole").motors if m.name.startswith("132S-4"))
    built = chosen_scene(scene, MotorRun(motor=motor, feasible=True, motor_ratio=122.363))
    analysis = analyse(built, "dynamic", extras=EXTRAS)  # what the text report reads, and ω(φ)
    assert analysis.j_required == 0 and analysis.j_margin < 0
    # δ holds however small the inertia: j_margin is the bound -min J_e, and the report says so
    assert analysis.delta_holds_at_any_inertia
    assert not analysis.machine.variable_inertia
    assert analysis.j_margin == pytest.approx(-analysis.machine.j_mean(), rel=1e-12)
    from flyopt.report.text import analysis_report

    report = analysis_report(analysis)
    assert "however small the inertia" in (report if isinstance(report, str) else "\n".join(report))
    assert not analyse(load(PROBLEMS / "motor-press.toml")).delta_holds_at_any_inertia
    speed = analysis.speed_curve()
    assert speed.j_flywheel == 0
    omega = np.asarray(speed.omega)
    assert speed.omega_max == pytest.approx(omega.max(), rel=1e-6)
    assert speed.omega_min == pytest.approx(omega.min(), rel=1e-6)
    machine = analysis.machine
    checked = periodic.verify(
        machine.net_torque(),
        machine.j_machine,
        machine.cycle_angle,
        built.omega_mean,
        built.delta,
        0.0,
        machine.knots(),
    )
    assert speed.delta == pytest.approx(checked.achieved_delta, rel=1e-6)
    ax = plots.plot_speed(built, analysis)
    line = next(l for l in ax.get_lines() if l.get_gid() == "model")
    assert "J_F = 0" in line.get_label()
    y = np.asarray(line.get_ydata())
    assert np.ptp(y) / (0.5 * (y.max() + y.min())) == pytest.approx(speed.delta, rel=1e-6)
    loose = load(PROBLEMS / "motor-press.toml").replace(delta=0.7)
    bare = analyse(loose, extras=("speed",))
    assert bare.j_margin == 0 and bare.delta_holds_at_any_inertia
    assert bare.speed_curve().delta < 0.7
    plots.plot_speed(loose, bare)
