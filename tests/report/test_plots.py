"""Every diagram renders to a non-empty file (Agg backend); bad requests are one-line errors."""

import math
from pathlib import Path

import numpy as np
import pytest
from conftest import PROBLEMS, run_flyopt

from flyopt.cli.main import main


@pytest.mark.parametrize("suffix, magic", [("svg", b"<?xml"), ("pdf", b"%PDF")])
def test_vector_formats(tmp_path, suffix, magic):
    out = tmp_path / f"t.{suffix}"
    assert main(["plot", str(PROBLEMS / "shear-press.toml"), "--what", "turning_moment", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(magic)


@pytest.mark.parametrize(
    "args, words",
    [
        (["--what", "turning_momnet", "-o", "x.png"], "did you mean 'turning_moment'"),
        (["--what", "energy", "-o", "x.jpg"], "must end in .png, .svg or .pdf"),
    ],
)
def test_bad_plot_requests(tmp_path, capsys, args, words):
    args = [a if a != "x.png" and a != "x.jpg" else str(tmp_path / a) for a in args]
    assert main(["plot", str(PROBLEMS / "shear-press.toml"), *args]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []  # nothing half-written


def test_sweep_and_pareto_plots_from_result_files(tmp_path):
    from flyopt.cli import studies

    sweep_file = tmp_path / "sweep.parquet"
    assert (
        studies.sweep_main(
            [
                str(PROBLEMS / "punch-press.toml"),
                "--vary",
                "delta=0.05:0.2:log4",
                "--vary",
                "material=cast_iron,cast_steel",
                "-o",
                str(sweep_file),
                "--no-progress",
            ]
        )
        == 0
    )
    out = tmp_path / "sweep.png"
    assert main(["plot", str(sweep_file), "--what", "sweep", "--x", "delta", "--by", "material", "-o", str(out)]) == 0
    assert out.stat().st_size > 10_000
    front = tmp_path / "front.csv"
    assert (
        studies.pareto_main(
            [
                str(PROBLEMS / "shear-press.toml"),
                "--objectives",
                "mass,outer_diameter",
                "--points",
                "5",
                "-o",
                str(front),
            ]
        )
        == 0
    )
    out = tmp_path / "front.svg"
    assert main(["plot", str(front), "--what", "pareto", "--x", "outer_diameter", "--y", "mass", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"<?xml")


@pytest.mark.parametrize(
    "args, words",
    [
        (["--what", "energy", "--x", "delta"], "is not a diagram of results"),
        (["--what", "sweep"], "--x: the results diagram 'sweep' needs"),
        (["--what", "sweep", "--x", "colour"], "no column 'colour'"),
        # a text column on an axis was a TypeError traceback (numpy cannot read pandas' text dtype)
        (["--what", "sweep", "--x", "status"], "column 'status' holds text, and an axis draws numbers (one line"),
        (["--what", "sweep", "--x", "delta", "--y", "status"], "column 'status' holds text, and an axis draws numbers"),
        (["--what", "pareto", "--x", "status"], "column 'status' holds text, and an axis draws numbers"),
    ],
)
def test_bad_result_plot_requests(tmp_path, capsys, args, words):
    import pandas as pd

    results = tmp_path / "r.csv"
    pd.DataFrame({"delta": [0.1, 0.2], "mass": [2.0, 1.0], "status": ["designed"] * 2}).to_csv(results, index=False)
    assert main(["plot", str(results), *args, "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert not (tmp_path / "x.png").exists()


def test_speed_plot_with_the_simulation_overlaid(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import flyopt
    from flyopt.pipeline import verify
    from flyopt.report import plots

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    analysis = flyopt.analyse(scene, extras=("speed",))
    ax = plots.plot_speed(scene, analysis, analysis.speed_curve(), verify(scene, analysis).solution)
    model, simulated = (
        next(line for line in ax.lines if line.get_gid() == gid).get_ydata() for gid in ("model", "simulation")
    )
    # the closed form and the simulation reach the same extremes (to the simulation's tolerance)
    assert abs(model.max() / simulated.max() - 1) < 1e-6 and abs(model.min() / simulated.min() - 1) < 1e-6
    # the legend writes them as the text does, to four figures (it wrote six: 11.7414 rpm, δ 0.043101)
    labels = {line.get_gid(): line.get_label() for line in ax.lines}
    rpm = analysis.omega_max * 30 / math.pi
    assert f"ω_max = {float(f'{rpm:.4g}'):g} rpm" in labels["omega_max"].replace(",", ""), labels["omega_max"]
    delta = verify(scene, analysis).solution.delta
    assert f"(δ = {float(f'{delta:.4g}'):g})" in labels["simulation"], labels["simulation"]
    out = plots.save(ax, tmp_path / "speed.png")
    assert out.stat().st_size > 10_000
    assert (
        main(["plot", str(PROBLEMS / "shear-press.toml"), "--what", "speed", "--verify", "-o", str(tmp_path / "s.png")])
        == 0
    )


# --------------------------------------------------------------------------
# The output file is checked before anything is computed
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "target, words",
    [
        ("missing/dir/x.png", "-o/--output: the folder"),
        ("x.jpg", "-o/--output: "),
        ("x", "must end in .png, .svg or .pdf"),
    ],
)
@pytest.mark.parametrize("source", ["scene", "results"])
def test_bad_output_is_one_line_exit_2_nothing_written(tmp_path, target, words, source):
    import pandas as pd

    if source == "scene":
        given = PROBLEMS / "shear-press.toml"
        what = ["--what", "energy"]
    else:
        given = tmp_path / "r.csv"
        pd.DataFrame({"delta": [0.1, 0.2], "mass": [2.0, 1.0], "status": ["designed"] * 2}).to_csv(given, index=False)
        what = ["--what", "sweep", "--x", "delta"]
    before = set(tmp_path.rglob("*"))
    out = run_flyopt("plot", str(given), *what, "-o", str(tmp_path / target))
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("flyopt: error: ") and words in lines[0]
    if "folder" in words:
        assert str(tmp_path / "missing" / "dir") in lines[0]
    assert set(tmp_path.rglob("*")) == before  # nothing written, no folder made


# --------------------------------------------------------------------------
# A machine that needs no flywheel: nothing to draw is said, not a failure
# --------------------------------------------------------------------------


@pytest.mark.parametrize("what", ["cross_section", "stress", "inertia_delta", "speed"])
def test_nothing_to_draw_when_no_flywheel_is_needed(tmp_path, capsys, what):
    # conveyor: steady torques, A_max = 0, J_F(δ) = 0 for every δ
    out = tmp_path / "x.png"
    assert main(["plot", str(PROBLEMS / "conveyor.toml"), "--what", what, "-o", str(out)]) == 0
    captured = capsys.readouterr()
    assert "nothing to draw" in captured.out and captured.out.count("\n") == 1
    assert "no flywheel is needed" in captured.out and captured.err == ""
    assert not out.exists()


@pytest.mark.parametrize("what", ["turning_moment", "energy"])
def test_steady_machine_still_draws_its_torques(tmp_path, what):
    out = tmp_path / "x.png"
    assert main(["plot", str(PROBLEMS / "conveyor.toml"), "--what", what, "-o", str(out)]) == 0
    assert out.stat().st_size > 10_000


def test_inertia_delta_when_the_machine_inertia_suffices(tmp_path):
    """J_c far above the need: J_F(δ) > 0 only below δ* = A_max/(ω_m² J_c), far left of the scene's δ."""
    import flyopt
    from flyopt.report import plots

    text = (PROBLEMS / "shear-press.toml").read_text().replace("delta = 0.05", 'delta = 0.05\ninertia = "100 kg*m^2"')
    path = tmp_path / "heavy.toml"
    path.write_text(text)
    assert main(["plot", str(path), "--what", "inertia_delta", "-o", str(tmp_path / "j.png")]) == 0
    scene = flyopt.load(path)
    analysis = flyopt.analyse(scene)
    assert not analysis.flywheel_needed
    ax = plots.plot_inertia_delta(scene, analysis)
    delta, j = ax.lines[0].get_data()
    # shear press by hand: M_d = 925π/2π = 462.5 N·m; the deficit from 0 to the crossing at
    # φ = 1.8125 π/4 is 1137.5 (1 + 0.8125/2) π/4 = 1599.609375 π/4 J (1256.33 J, as published)
    a_max, omega_mean = 1599.609375 * math.pi / 4, 1500 * 2 * math.pi / 60
    delta_free = a_max / (omega_mean**2 * 100.0)
    free = next(line for line in ax.lines if line.get_gid() == "delta_free")
    assert math.isclose(free.get_xdata()[0], delta_free, rel_tol=1e-12)
    drawn = np.isfinite(j)
    assert drawn.sum() > 20 and delta[drawn].max() < delta_free
    # every point on the hyperbola J_F = A_max/(ω_m² δ) − J_c (to the round-off of the difference)
    np.testing.assert_allclose(j[drawn], a_max / (omega_mean**2 * delta[drawn]) - 100.0, rtol=1e-9, atol=1e-9 * 100)


# --------------------------------------------------------------------------
# Plots draw computed results and never run a model
# --------------------------------------------------------------------------


def _forbid_models(patch):
    """Make every function of the sizing modules, the analysis and the pipeline raise."""
    import importlib
    import inspect
    import pkgutil

    import flyopt.analysis
    import flyopt.pipeline
    import flyopt.sizing

    def forbidden(*args, **kwargs):
        raise AssertionError("a plot ran a model")

    modules = [importlib.import_module(f"flyopt.sizing.{m.name}") for m in pkgutil.iter_modules(flyopt.sizing.__path__)]
    for module in modules + [flyopt.analysis, flyopt.pipeline]:
        for name, value in list(vars(module).items()):
            if inspect.isfunction(value) and value.__module__.startswith("flyopt."):
                patch.setattr(module, name, forbidden)


@pytest.mark.parametrize(
    "scene, what, options",
    [
        ("slider-crank-press", "energy_mass", []),
        ("slider-crank-press", "inertia_delta", []),  # J_F(δ) of the exact model is computed before, and passed in
        ("motor-press", "turning_moment", []),  # the motor along the periodic solution the analysis carries
        ("shear-press", "speed", ["--verify"]),  # the model's ω(φ) and the simulation are passed in
        ("slider-crank-press", "speed", ["--verify"]),
        ("motor-press", "speed", []),  # the dynamic model's own periodic solution
        ("shear-press", "inertia_delta", []),
        ("shear-press", "energy", []),
        ("shear-press", "turning_moment", []),
        ("shear-press", "cross_section", []),
        ("shear-press", "stress", []),
    ],
)
def test_plots_never_run_a_model(monkeypatch, tmp_path, scene, what, options):
    from flyopt.report import plots

    real, drawn = getattr(plots, f"plot_{what}"), []

    def guarded(*args, **kwargs):  # inside the plot, every model run fails the test
        with pytest.MonkeyPatch.context() as patch:
            _forbid_models(patch)
            drawn.append(real(*args, **kwargs))
        return drawn[-1]

    monkeypatch.setattr(plots, f"plot_{what}", guarded)
    out = tmp_path / "x.png"
    assert main(["plot", str(PROBLEMS / f"{scene}.toml"), "--what", what, *options, "-o", str(out)]) == 0
    assert len(drawn) == 1 and out.stat().st_size > 10_000
    if options:  # model and simulation both drawn
        assert "simulation" in drawn[0].lines[1].get_label()


def test_speed_of_a_dynamic_analysis_that_does_not_fluctuate_is_nothing_to_draw(monkeypatch):
    """Analysis.speed_curve() is None when the speed does not fluctuate (its documented answer): the
    plot says there is nothing to draw, as the CLI does, instead of failing on None's ``omega``."""
    import flyopt
    from flyopt.analysis import Analysis
    from flyopt.report import plots

    scene = flyopt.load(PROBLEMS / "motor-press.toml")
    analysis = flyopt.analyse(scene)
    assert analysis.model == "dynamic"
    monkeypatch.setattr(Analysis, "speed_curve", lambda self: None)
    with pytest.raises(plots.NothingToDraw, match="does not fluctuate"):
        plots.plot_speed(scene, analysis)


def test_energy_mass_refuses_an_analysis_by_another_model():
    import flyopt
    from flyopt.report import plots

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    with pytest.raises(ValueError, match="analyse with model='energy_mass'"):
        plots.plot_energy_mass(scene, flyopt.analyse(scene, model="energy"))


# --------------------------------------------------------------------------
# The README's plot recipes, as written
# --------------------------------------------------------------------------


def _flyopt(*args, cwd):
    return run_flyopt(*map(str, args), cwd=cwd)


def _readme_command(start):
    """The arguments after ``flyopt`` of the README's command that begins with ``start``."""
    import re
    import shlex

    from conftest import ROOT

    commands = re.findall(r"^\| `(flyopt [^`]+)`", (ROOT / "README.md").read_text(encoding="utf-8"), re.M)
    found = [c for c in commands if c.startswith(start)]
    assert len(found) == 1, f"the README has no single command starting {start!r}"
    return shlex.split(found[0])[1:]


def test_readme_sweep_plot_by_material(tmp_path):
    # on a sweep that varies delta only, --by material means the winner's material
    sweep = _flyopt(
        "sweep",
        PROBLEMS / "punch-press.toml",
        "--vary",
        "delta=0.01:0.1:log5",
        "-o",
        "RESULTS.parquet",
        "--no-progress",
        cwd=tmp_path,
    )
    assert sweep.returncode == 0, sweep.stderr
    command = _readme_command("flyopt plot RESULTS.parquet --what sweep")
    out = _flyopt(*command, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / command[command.index("-o") + 1]).stat().st_size > 10_000


def test_readme_pareto_plot_without_x(tmp_path):
    front = _flyopt(
        "pareto",
        PROBLEMS / "shear-press.toml",
        "--objectives",
        "mass,outer_diameter",
        "--points",
        "5",
        "-o",
        "FRONT.csv",
        cwd=tmp_path,
    )
    assert front.returncode == 0, front.stderr
    command = _readme_command("flyopt plot FRONT.csv --what pareto")
    assert "--x" not in command
    out = _flyopt(*command, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / command[command.index("-o") + 1]).stat().st_size > 10_000


def test_pareto_plot_takes_the_second_objective_for_x(tmp_path, monkeypatch):
    import argparse

    import pandas as pd

    from flyopt.cli.plot import add_plot_arguments, run_plot
    from flyopt.report import plots

    front = pd.DataFrame(
        {
            "mass": [3.0, 2.0, 1.0],
            "delta": [0.01, 0.02, 0.04],
            "outer_diameter": [1.0, 2.0, 3.0],
            "epsilon": [0.01, 0.02, 0.04],
        }
    )
    assert plots.pareto_objectives(front) == ("mass", "delta")
    path = tmp_path / "f.csv"
    front.to_csv(path, index=False)
    seen = {}
    real = plots.plot_pareto

    def spy(frame, x, y, ax=None, units="engineering", digits=4):
        seen.update(x=x, y=y)
        return real(frame, x, y, ax, units, digits)

    monkeypatch.setattr(plots, "plot_pareto", spy)
    parser = argparse.ArgumentParser()
    add_plot_arguments(parser)  # the command's own options and defaults
    args = parser.parse_args([str(path), "--what", "pareto", "-o", str(tmp_path / "f.png")])
    assert run_plot(args) == 0
    assert seen == {"x": "delta", "y": "mass"}


# --------------------------------------------------------------------------
# Whole wheels: the dimensioned section and the stresses over the radius
# --------------------------------------------------------------------------

WHEELS = Path(__file__).parents[1] / "data" / "wheels"
WHEEL_GEOMETRIES = ["rim", "disc", "rim_web", "rim_arms"]
#: The ductile iron of the wheel scenes (tests/data/wheels): density [kg/m^3] and Poisson's ratio.
RHO, NU = 7100.0, 0.275


def _designed(path):
    import flyopt
    from flyopt.pipeline import design_scene

    scene = flyopt.load(path)
    analysis = flyopt.analyse(scene)
    design = design_scene(scene, analysis)
    assert design.best is not None and design.best.geometry == path.stem.split("-", 1)[1]
    return scene, analysis, design


@pytest.mark.parametrize("what", ["cross_section", "stress"])
@pytest.mark.parametrize("geometry", WHEEL_GEOMETRIES)
def test_wheel_plots_render_for_every_geometry(tmp_path, geometry, what):
    # pytest turns every warning into an error: a plot that warns (a tight layout that cannot fit,
    # a label that cannot be placed) fails here
    out = tmp_path / f"{geometry}-{what}.png"
    assert main(["plot", str(WHEELS / f"engine-{geometry}.toml"), "--what", what, "-o", str(out)]) == 0
    assert out.stat().st_size > 10_000
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _blocks(ax):
    """The hatched blocks of a drawn section by gid: (x0, x1, y0, y1) in the drawing's unit (mm by default)."""
    from matplotlib.patches import Rectangle

    out = {}
    for patch in ax.patches:
        if isinstance(patch, Rectangle) and patch.get_gid():
            x, y = patch.get_xy()
            out[patch.get_gid()] = (x, x + patch.get_width(), y, y + patch.get_height())
    return out


@pytest.mark.parametrize("geometry", WHEEL_GEOMETRIES)
def test_cross_section_draws_the_candidates_dimensions(geometry):
    from flyopt.report import plots

    _scene, _analysis, design = _designed(WHEELS / f"engine-{geometry}.toml")
    c = design.best
    ax = plots.plot_cross_section(c)
    # the drawing is in mm (the engineering units, the default): its coordinates too, not metres
    blocks = {gid: tuple(v / 1e3 for v in box) for gid, box in _blocks(ax).items()}
    r_o, b = c.dims.d_outer / 2, c.dims.b
    expected = {}
    if geometry == "disc":
        expected["disc"] = (-b / 2, b / 2, c.bore / 2, r_o)
    else:
        expected["rim"] = (-b / 2, b / 2, r_o - c.dims.h, r_o)
    if geometry in ("rim_web", "rim_arms"):
        expected["hub"] = (-c.dims.l_hub / 2, c.dims.l_hub / 2, c.bore / 2, c.dims.d_hub / 2)
        # the upper half is cut through the keyway (section A-A of the drawing): its hub starts t2 over the bore
        t2 = c.parts.key["t2"]
        hub = _blocks(ax)["hub+"]
        np.testing.assert_allclose(
            tuple(v / 1e3 for v in hub),
            (-c.dims.l_hub / 2, c.dims.l_hub / 2, c.bore / 2 + t2, c.dims.d_hub / 2),
            rtol=0,
            atol=1e-12,
        )
    if geometry == "rim_web":
        expected["web"] = (-c.dims.t_web / 2, c.dims.t_web / 2, c.dims.d_hub / 2, r_o - c.dims.h)
    if geometry == "rim_arms":
        expected["arms"] = (-c.dims.arm_minor / 2, c.dims.arm_minor / 2, c.dims.d_hub / 2, r_o - c.dims.h)
    for name, (x0, x1, y0, y1) in expected.items():
        if name != "hub":  # checked above, with its keyway
            np.testing.assert_allclose(blocks[f"{name}+"], (x0, x1, y0, y1), rtol=0, atol=1e-12)
        np.testing.assert_allclose(blocks[f"{name}-"], (x0, x1, -y1, -y0), rtol=0, atol=1e-12)  # mirrored
    assert c.dims.d_outer * 1e3 / 2 < ax.get_ylim()[1] < c.dims.d_outer * 1e3  # the axes hold millimetres
    assert {g[:-1] for g in blocks} == set(expected)
    # every dimension the brief names is written, in mm
    texts = {t.get_text() for t in ax.texts}
    wanted = {f"Ø{c.dims.d_outer * 1e3:.1f}".rstrip("0").rstrip("."), f"B {c.dims.b * 1e3:.1f}".rstrip("0").rstrip(".")}
    if geometry != "disc":
        wanted |= {
            f"Ø{c.dims.d_inner * 1e3:.1f}".rstrip("0").rstrip("."),
            f"H {c.dims.h * 1e3:.1f}".rstrip("0").rstrip("."),
        }
    if geometry in ("rim_web", "rim_arms"):
        wanted |= {
            f"Ø{c.dims.d_hub * 1e3:.1f}".rstrip("0").rstrip("."),
            "Ø70",
            f"hub length {c.dims.l_hub * 1e3:.1f}".rstrip("0").rstrip("."),
        }
    if geometry == "disc":
        wanted.add("Ø70")
    if geometry == "rim_web":
        wanted.add(f"web {c.dims.t_web * 1e3:.1f}".rstrip("0").rstrip("."))
    assert wanted <= texts, wanted - texts
    if geometry == "rim_arms":
        from matplotlib.patches import Ellipse, Polygon

        section = [p for p in ax.patches if isinstance(p, Ellipse) and p.get_gid() == "arm_section"]
        assert len(section) == 1
        np.testing.assert_allclose(
            (section[0].width, section[0].height), (c.dims.arm_minor * 1e3, c.dims.arm_major * 1e3), rtol=1e-12
        )
        front = [a for a in ax.figure.axes if a is not ax]
        assert len(front) == 1
        arms = [p for p in front[0].patches if isinstance(p, Polygon) and p.get_gid() == "arm"]
        assert len(arms) == c.n_arms == 6
        # each arm is a strip of width a (the major axis lies in the plane of rotation)
        for arm in arms:
            xy = arm.get_xy()[:4]
            np.testing.assert_allclose(np.hypot(*(xy[0] - xy[3])), c.dims.arm_major * 1e3, rtol=1e-9)
    ax.figure.clf()


def _stress_axes(geometry):
    from flyopt.pipeline import stress_profile
    from flyopt.report import plots

    scene, analysis, design = _designed(WHEELS / f"engine-{geometry}.toml")
    profile, beams, omega, material = stress_profile(scene, analysis, design)
    ax = plots.plot_stress(design.best, profile, beams, omega, ductile=material.ductile)
    return ax, design, analysis


def _line(ax, label):
    found = [line for line in ax.lines if line.get_label() == label]
    assert len(found) == 1, [line.get_label() for line in ax.lines]
    return found[0]


@pytest.mark.parametrize("geometry", ["disc", "rim"])
def test_stress_plot_at_the_bore_is_the_annulus_closed_form(geometry):
    """A free rotating annulus a < r < b (Timoshenko & Goodier, Theory of Elasticity, section 32):
    at r = a, sigma_r = 0 and sigma_t = (3 + nu)/4 rho w^2 [b^2 + (1 - nu)/(3 + nu) a^2].
    The disc on its 70 mm bore and the bare rim are both such annuli."""
    ax, design, analysis = _stress_axes(geometry)
    c = design.best
    omega = analysis.omega_max  # the speed ratio of the crankshaft is 1
    a = (c.bore if geometry == "disc" else c.dims.d_inner) / 2
    b = c.dims.d_outer / 2
    hoop = (3 + NU) / 4 * RHO * omega**2 * (b**2 + (1 - NU) / (3 + NU) * a**2)
    r, st = _line(ax, "σ_t").get_data()
    r_sr, sr = _line(ax, "σ_r").get_data()
    assert math.isclose(r[0], a * 1e3, rel_tol=1e-12) and math.isclose(r_sr[0], a * 1e3, rel_tol=1e-12)
    assert math.isclose(st[0], hoop / 1e6, rel_tol=1e-9)
    assert abs(sr[0]) < 1e-9 * hoop / 1e6
    # at r = b: sigma_r = 0 again, sigma_t = (3 + nu)/4 rho w^2 [a^2 + (1 - nu)/(3 + nu) b^2]
    outer = (3 + NU) / 4 * RHO * omega**2 * (a**2 + (1 - NU) / (3 + NU) * b**2)
    assert math.isclose(r[-1], b * 1e3, rel_tol=1e-12) and math.isclose(st[-1], outer / 1e6, rel_tol=1e-9)
    # the governing point marked is the hoop stress at the bore (the largest, and von Mises = sigma_t there)
    governing = [line for line in ax.lines if line.get_label().startswith("governing")]
    assert len(governing) == 1
    x, y = governing[0].get_data()
    assert math.isclose(x[0], a * 1e3, rel_tol=1e-9) and math.isclose(y[0], hoop / 1e6, rel_tol=1e-6)
    # its share of the allowable, hoop / allowable from the closed form, to one decimal as the card writes it
    stress = c.stresses.stress
    allowable = next(p["allowable"] for p in stress["parts"] if p["part"] == stress["where"]["part"])
    assert f"({100 * hoop / allowable:.1f} % of its allowable)" in governing[0].get_label()
    ax.figure.clf()


def test_stress_plot_of_an_arms_wheel_marks_rim_and_arm_root():
    ax, design, analysis = _stress_axes("rim_arms")
    c = design.best
    omega = analysis.omega_max
    r_mean = c.dims.d_mean / 2
    # Khurmi ch. 22: 3/4 rho v^2 + 1/4 of the bending of a rim fixed at its arms, 2 pi^2 rho w^2 R^3/(n^2 H)
    rim = 0.75 * RHO * (omega * r_mean) ** 2 + 0.25 * 2 * math.pi**2 * RHO * omega**2 * r_mean**3 / (
        c.n_arms**2 * c.dims.h
    )
    rim_point = [line for line in ax.lines if line.get_label().startswith("rim (hoop + bending)")]
    arm_point = [line for line in ax.lines if line.get_label().startswith("arm root")]
    assert len(rim_point) == 1 and len(arm_point) == 1
    x, y = rim_point[0].get_data()
    assert math.isclose(x[0], r_mean * 1e3, rel_tol=1e-12) and math.isclose(y[0], rim / 1e6, rel_tol=1e-9)
    assert math.isclose(arm_point[0].get_xdata()[0], c.dims.d_hub / 2 * 1e3, rel_tol=1e-12)
    # both labelled on the plot, not only in the legend
    labels = " ".join(t.get_text() for t in ax.texts)
    assert "arm root" in labels and "rim (hoop + bending)" in labels
    # the allowable of each part spans that part
    spans = {p["name"]: (p["r_inner"] * 1e3, p["r_outer"] * 1e3) for p in c.parts.items}
    segments = [seg for coll in ax.collections if "allowable" in coll.get_label() for seg in coll.get_segments()]
    assert sorted((s[0][0], s[1][0]) for s in segments) == sorted(spans.values())
    ax.figure.clf()


# --------------------------------------------------------------------------
# Text a figure can draw (issue 25, item 8)
# --------------------------------------------------------------------------


def test_drawable_text_is_what_the_font_has_and_never_mathtext():
    from flyopt.report.plots import standard

    assert standard.drawable("a\x00b\u202e\U0001f525\t☃ ΔE $\\frac$") == "a\\x00b\\u202e\ufffd ☃ ΔE \\$\\frac\\$"
    assert standard.drawable("plain, φ = 90 deg\nsecond line") == "plain, φ = 90 deg\nsecond line"
    once = standard.drawable("a\x00 $x$ \U0001f525")
    assert standard.drawable(once) == once  # a second pass changes nothing


@pytest.mark.parametrize("what", ["turning_moment", "speed", "energy"])
def test_a_hostile_title_is_drawn_without_a_warning(tmp_path, what, capsys, write_scene):
    # emoji and control characters made matplotlib warn once per glyph and drawing (30 lines on stderr for
    # a report), and "$\frac$" in a title stopped the drawing with a mathtext error (exit 1); the tests'
    # filter turns any warning into an error
    scene = write_scene(
        'title = "a\\u200bb\\u2066c\\ue000d\\u202eevil \\U0001F525 $\\\\frac$"\n'
        '[machine]\nspeed = "1500 rpm"\ndelta = 0.05\n'
        '[torque.resisting]\npoints = [["0 deg", "1600 N*m"], ["90 deg", "200 N*m"], ["360 deg", "200 N*m"]]\n'
        '[torque.driving]\nconstant = "unknown"\n'
    )
    out = tmp_path / f"{what}.svg"
    assert main(["plot", str(scene), "--what", what, "-o", str(out), "-q"]) == 0
    assert capsys.readouterr().err == ""
    svg = out.read_text(encoding="utf-8")
    assert "\u200b" not in svg and "\u202e" not in svg


@pytest.mark.slow  # 9 s; a hostile title's quiet report is in the default run (tests/cli/test_commands.py, html)
def test_a_report_of_a_scene_with_an_undrawable_title_writes_nothing_on_stderr(tmp_path):

    text = (PROBLEMS / "slider-crank-press.toml").read_text()
    title = next(line for line in text.splitlines() if line.startswith("title"))
    scene = tmp_path / "scene.toml"
    scene.write_text(text.replace(title, 'title = "a\\u200bb\\u2066c\\ue000d\\u202eevil \\U0001f525 press"'))
    for args in (
        ["report", str(scene), "-o", str(tmp_path / "r.html")],
        ["plot", str(scene), "--what", "all", "-o", f"{tmp_path}/"],
    ):
        run = run_flyopt(*args, "-q")
        assert run.returncode == 0 and run.stderr == "", run.stderr[:500]


def test_a_small_deltas_three_speeds_are_written_apart_and_no_further():
    """ω_max, ω_m, ω_min of 1000.4, 1000.2 and 1000 rpm read alike to four figures (1,000 rpm): the legend takes
    five, the fewest that tell them apart (by hand: 1,000.4, 1,000.2, 1,000); 1,500 and 1,450 rpm keep four."""
    from flyopt.report import display
    from flyopt.report.plots import standard

    rad = [v * math.pi / 30 for v in (1000.4, 1000.2, 1000.0)]
    assert standard.digits_apart(rad, "angular_speed", "engineering", 4) == 5
    assert standard.digits_apart([v * math.pi / 30 for v in (1500, 1450)], "angular_speed", "engineering", 4) == 4
    same = [1000 * math.pi / 30] * 3  # equal speeds (no fluctuation): nothing to tell apart
    assert standard.digits_apart(same, "angular_speed", "engineering", 4) == 4
    assert standard.digits_apart(rad, "angular_speed", "engineering", 14) <= display.MAX_DIGITS


def test_a_figure_as_svg_draws_its_texts_as_paths_unless_asked_for_text():
    """A report's SVG needs no font (its texts are glyph paths); the app's sets them as <text>, the same words."""
    import re

    from flyopt.report.html import svg_of
    from flyopt.report.plots import standard

    figure = standard.new_figure(figsize=(3, 2))
    figure.add_subplot().set_xlabel("crank angle φ [deg]")
    as_paths, as_text = svg_of(figure, "p"), svg_of(figure, "t", text_as_text=True)
    standard.close(figure)
    assert "<text" not in as_paths and "DejaVuSans-" in as_paths
    assert "crank angle φ [deg]" in re.findall(r"<text[^>]*>([^<]*)</text>", as_text)
    assert "DejaVuSans-" not in as_text
