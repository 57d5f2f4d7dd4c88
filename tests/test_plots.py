"""Every diagram renders to a non-empty file (Agg backend); bad requests are one-line errors."""

import pytest

from conftest import PROBLEMS
from flyopt.cli.main import main
from flyopt.report.plots import PLOTS

SCENES = ["shear-press", "slider-crank-press", "motor-press", "example1-net-areas"]
NOT_DRAWABLE = {  # (scene, diagram): why it is refused, in one line
    ("example1-net-areas", "speed"): "net-area scene has no angles",
    ("example1-net-areas", "energy_mass"): "needs torques of the angle only given as curves",
    ("motor-press", "energy_mass"): "needs torques of the angle only given as curves",
}


@pytest.mark.parametrize("what", sorted(PLOTS))
@pytest.mark.parametrize("scene", SCENES)
def test_every_plot_renders(tmp_path, scene, what, capsys):
    out = tmp_path / f"{scene}-{what}.png"
    status = main(["plot", str(PROBLEMS / f"{scene}.toml"), "--what", what, "-o", str(out)])
    if (scene, what) in NOT_DRAWABLE:
        # said in one line, nothing written
        assert status == 2 and not out.exists()
        assert NOT_DRAWABLE[scene, what] in capsys.readouterr().err
        return
    assert status == 0
    assert out.stat().st_size > 10_000          # a real image, not an empty canvas
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("suffix, magic", [("svg", b"<?xml"), ("pdf", b"%PDF")])
def test_vector_formats(tmp_path, suffix, magic):
    out = tmp_path / f"t.{suffix}"
    assert main(["plot", str(PROBLEMS / "shear-press.toml"), "--what", "turning_moment", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(magic)


@pytest.mark.parametrize("args, words", [
    (["--what", "turning_momnet", "-o", "x.png"], "did you mean 'turning_moment'"),
    (["--what", "energy", "-o", "x.jpg"], "must end in .png, .svg or .pdf"),
])
def test_bad_plot_requests(tmp_path, capsys, args, words):
    args = [a if a != "x.png" and a != "x.jpg" else str(tmp_path / a) for a in args]
    assert main(["plot", str(PROBLEMS / "shear-press.toml"), *args]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []       # nothing half-written


def test_sweep_and_pareto_plots_from_result_files(tmp_path):
    from flyopt.studies import fronts as studies

    sweep_file = tmp_path / "sweep.parquet"
    assert studies.sweep_main([str(PROBLEMS / "punch-press.toml"), "--vary", "delta=0.05:0.2:log4",
                               "--vary", "material=cast_iron,cast_steel", "-o", str(sweep_file),
                               "--no-progress"]) == 0
    out = tmp_path / "sweep.png"
    assert main(["plot", str(sweep_file), "--what", "sweep", "--x", "delta", "--by", "material", "-o", str(out)]) == 0
    assert out.stat().st_size > 10_000
    front = tmp_path / "front.csv"
    assert studies.pareto_main([str(PROBLEMS / "shear-press.toml"), "--objectives", "mass,outer_diameter",
                                "--points", "5", "-o", str(front)]) == 0
    out = tmp_path / "front.svg"
    assert main(["plot", str(front), "--what", "pareto", "--x", "outer_diameter", "--y", "mass", "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"<?xml")


@pytest.mark.parametrize("args, words", [
    (["--what", "energy", "--x", "delta"], "is not a diagram of results"),
    (["--what", "sweep"], "--x: the results diagram 'sweep' needs"),
    (["--what", "sweep", "--x", "colour"], "no column 'colour'"),
])
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
    from flyopt.report import plots

    scene = flyopt.load(PROBLEMS / "slider-crank-press.toml")
    analysis = flyopt.analyse(scene)
    ax = plots.plot_speed(scene, analysis, simulate=True)
    model, simulated = ax.lines[0].get_ydata(), ax.lines[1].get_ydata()
    # the closed form and the simulation reach the same extremes (to the simulation's tolerance)
    assert abs(model.max() / simulated.max() - 1) < 1e-6 and abs(model.min() / simulated.min() - 1) < 1e-6
    out = plots.save(ax, tmp_path / "speed.png")
    assert out.stat().st_size > 10_000
    assert main(["plot", str(PROBLEMS / "shear-press.toml"), "--what", "speed", "--verify",
                 "-o", str(tmp_path / "s.png")]) == 0
