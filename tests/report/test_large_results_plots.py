"""Diagrams of large results tables: only the columns a diagram reads are read, and a set of points too many to
mark one by one is marked once per half a point of the axes (the line and its read-outs keep every point)."""

import io

import matplotlib
import numpy as np
import pandas as pd
import pytest
from conftest import PROBLEMS

from flyopt.cli import studies
from flyopt.cli.main import main
from flyopt.outputs import results
from flyopt.report.plots import readout, standard
from flyopt.report.plots.results import MARK_CELLS, MAX_MARKERS, plot_pareto, plot_sweep, plotted_columns


def _svg(ax):
    """The figure of ``ax`` as SVG bytes, the same for the same drawing (no date, fixed ids)."""
    buffer = io.BytesIO()
    figure = standard.figure_of(ax)
    with matplotlib.rc_context({"svg.hashsalt": "flyopt"}):
        figure.savefig(buffer, format="svg", metadata={"Date": None})
    standard.close(figure)
    return buffer.getvalue()


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    """A sweep over δ and material (Parquet, its sweep recorded), the same table as a CSV without its
    metadata (the varied fields then found by their values), and a Pareto front (CSV with its sidecar)."""
    folder = tmp_path_factory.mktemp("tables")
    sweep = folder / "sweep.parquet"
    assert (
        studies.sweep_main(
            [
                str(PROBLEMS / "punch-press.toml"),
                "--vary",
                "delta=0.02:0.3:log5",
                "--vary",
                "material=cast_iron,cast_steel",
                "-o",
                str(sweep),
                "--no-progress",
            ]
        )
        == 0
    )
    bare = folder / "bare.csv"
    results.read_results(sweep).to_csv(bare, index=False)
    front = folder / "front.csv"
    arguments = [str(PROBLEMS / "shear-press.toml"), "--objectives", "mass,outer_diameter", "--points", "5"]
    assert studies.pareto_main([*arguments, "-o", str(front)]) == 0
    return {"sweep": sweep, "bare": bare, "front": front}


@pytest.mark.parametrize(
    "table, what, x, y, by",
    [
        ("sweep", "sweep", "delta", "mass", None),  # one line per material, which the sweep records it varied
        ("sweep", "sweep", "delta", "objective", "material"),  # the objective's unit is by its name's column
        ("bare", "sweep", "delta", "mass", None),  # no metadata: the varied fields are those that vary
        ("bare", "sweep", "delta", "rim_speed", "material"),
        ("front", "pareto", "outer_diameter", "mass", None),
        ("front", "pareto", "epsilon", "mass", None),  # epsilon's unit is the front's second objective's
    ],
)
def test_a_diagram_of_the_columns_it_reads_is_the_diagram_of_the_whole_table(tables, table, what, x, y, by):
    path = tables[table]
    names, metadata = results.results_columns(path)
    whole = results.read_results(path)
    assert names == list(whole.columns)
    assert metadata == (whole.attrs.get("flyopt") or None)
    wanted = plotted_columns(names, metadata, what, x, y, by)
    assert len(wanted) < len(names) / 2  # the point: most of a table is not read
    part = results.read_results(path, columns=wanted)
    draw = (lambda f: plot_sweep(f, x, y, by)) if what == "sweep" else (lambda f: plot_pareto(f, x, y))
    assert _svg(draw(part)) == _svg(draw(whole))


def test_a_column_the_table_lacks_is_named_with_the_tables_columns(tables):
    names, metadata = results.results_columns(tables["sweep"])
    with pytest.raises(ValueError, match=r"no column 'colour' \(columns: point, delta, ") as refused:
        plotted_columns(names, metadata, "sweep", "delta", "colour")
    with pytest.raises(ValueError) as drawn:
        plot_sweep(results.read_results(tables["sweep"]), "delta", "colour")
    assert str(refused.value) == str(drawn.value)


def test_the_plot_command_reads_only_the_columns_of_its_diagram(tables, tmp_path, monkeypatch):
    read = []
    real = results.read_results

    def spy(path, columns=None):
        read.append(columns)
        return real(path, columns)

    monkeypatch.setattr(results, "read_results", spy)
    out = tmp_path / "s.svg"
    assert main(["plot", str(tables["sweep"]), "--what", "sweep", "--x", "delta", "-o", str(out)]) == 0
    assert read == [["delta", "material", "status", "mass"]]
    assert out.read_bytes().startswith(b"<?xml")
    read.clear()
    assert main(["plot", str(tables["front"]), "--what", "pareto", "-o", str(tmp_path / "f.svg")]) == 0
    (columns,) = read
    assert {"mass", "outer_diameter", "status"} <= set(columns) and "message" not in columns


def test_a_sweep_of_many_points_marks_one_in_each_half_point_and_keeps_every_point_on_its_line():
    n = 20_000
    delta = np.geomspace(0.01, 0.3, n)
    status = np.where(np.arange(n) % 7 == 3, "infeasible", "designed")
    frame = pd.DataFrame({"delta": delta, "mass": np.where(status == "designed", 2.0 / delta, np.nan)})
    frame["status"] = status
    ax = plot_sweep(frame, "delta", "mass")
    (line,) = [a for a in ax.get_lines() if a.get_label() == "mass"]
    ok = status == "designed"
    assert np.array_equal(line.get_xdata(), delta[ok])  # the line and its read-outs: every point
    assert readout.ATTRIBUTE in vars(line)
    marked = np.asarray(line.get_markevery())
    assert 0 < len(marked) <= MAX_MARKERS
    # every point lies within 1/MARK_CELLS of the data's span on both axes (x in its log scale) of a marker: the
    # nearest marker found by brute force, not by the cells the code bins in
    lx, ys = np.log10(line.get_xdata()), np.asarray(line.get_ydata())
    mx, my = lx[marked], ys[marked]
    for part in np.array_split(np.arange(len(lx)), 20):
        dx = np.abs(lx[part, None] - mx[None, :]) / np.ptp(lx)
        dy = np.abs(ys[part, None] - my[None, :]) / np.ptp(ys)
        assert (np.maximum(dx, dy).min(axis=1) <= 1 / MARK_CELLS).all()
    assert len(set(marked.tolist())) == len(marked)  # each marker a point of its own
    (missed,) = [a for a in ax.get_lines() if a.get_gid() == "infeasible"]
    assert len(missed.get_xdata()) == n - ok.sum() and len(missed.get_markevery()) <= MARK_CELLS + 1
    svg = _svg(ax)
    assert svg.count(b"<use ") <= 2 * MAX_MARKERS and b"<image" not in svg  # 20,000 markers drawn were 2.2 MB
    assert len(svg) < 400_000


def test_a_cloud_too_dense_to_mark_one_by_one_is_an_image_in_a_vector_file():
    rng = np.random.default_rng(7)
    n = 20_000
    frame = pd.DataFrame({"mass": rng.uniform(1, 2, n), "outer_diameter": rng.uniform(0.5, 1.0, n), "epsilon": 0.0})
    ax = plot_pareto(frame, "outer_diameter", "mass")
    designs = next(a for a in ax.get_lines() if a.get_label().startswith("designs (20000)"))
    assert designs.get_rasterized() and len(designs.get_xdata()) == n
    svg = _svg(ax)
    assert b"<image" in svg and svg.count(b"<use ") < MAX_MARKERS
    assert len(svg) < 1_000_000


def test_a_few_points_are_each_marked():
    frame = pd.DataFrame({"delta": np.linspace(0.01, 0.3, MAX_MARKERS), "mass": 1.0, "status": "designed"})
    (line,) = plot_sweep(frame, "delta", "mass").get_lines()
    assert line.get_markevery() is None and not line.get_rasterized()


def test_a_sweep_of_more_lines_than_drawn_is_refused_before_a_group_is_made(monkeypatch):
    """Every line's group was made before they were counted: 50,000 values of --by took 43 s and 2 GB to
    refuse, a million ended in a MemoryError."""
    from pandas.core.groupby import DataFrameGroupBy

    n = 20_000
    frame = pd.DataFrame({"delta": np.linspace(0.01, 0.1, n), "mass": 1.0, "status": "designed"})
    frame["material"] = [f"m{i}" for i in range(n)]

    def made(self):
        raise AssertionError("a group was made")

    monkeypatch.setattr(DataFrameGroupBy, "__iter__", made)
    with pytest.raises(ValueError, match=r"the sweep varies material besides delta: 20000 lines would be drawn"):
        plot_sweep(frame, "delta", "mass", by="material")


def test_a_front_without_a_design_of_both_values_is_refused_in_words():
    """A front whose every outer diameter is empty ended in an IndexError (exit 1)."""
    frame = pd.DataFrame({"mass": [1.0, 2.0], "outer_diameter": [np.nan, np.nan], "epsilon": [0.1, 0.2]})
    frame["status"] = "designed"
    with pytest.raises(ValueError, match="no design has both outer_diameter and mass: there is no front to draw"):
        plot_pareto(frame, "outer_diameter", "mass")


def test_a_long_text_in_a_legend_is_clipped():
    """A material named by 100,000 characters took 36 s to lay out (and warned on stderr)."""
    frame = pd.DataFrame({"delta": [0.01, 0.02, 0.01, 0.02], "mass": [1.0, 2.0, 3.0, 4.0], "status": "designed"})
    frame["material"] = ["a" * 100_000] * 2 + ["b" * 100_000] * 2
    ax = plot_sweep(frame, "delta", "mass", by="material")
    labels = [line.get_label() for line in ax.get_lines() if not line.get_label().startswith("_")]
    assert sorted(labels) == [f"material = {c * 119}… (100000 characters)" for c in "ab"]
