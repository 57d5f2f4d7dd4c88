"""flyopt.outputs.results: the result tables and their Parquet and CSV files (issue 15, part 3).

Missing values are nulls in Parquet, CSV and JSON, read from the files by pyarrow, the csv
module and json, not through flyopt's reader. Parquet metadata and the CSV sidecar carry the
units and the provenance, compared with a SHA-256 of the scene file and SI values computed here.
"""

import csv
import hashlib
import importlib.metadata
import json
import math

import numpy as np
import pandas as pd
import pyarrow.compute as pc
import pyarrow.parquet as pq
import pytest
from conftest import PROBLEMS
from output_cases import (
    delete_at,
    schema_errors,
    set_at,
    variant,
)

import flyopt
from flyopt.cli.main import main
from flyopt.outputs import results
from flyopt.outputs.documents import table_metadata
from flyopt.outputs.results import read_results
from flyopt.studies.payload import digest

# --------------------------------------------------------------------------
# Tables: missing values, metadata, provenance
# --------------------------------------------------------------------------

#: Points that are designed by the closed form and by IPOPT, and infeasible (a 0.3 m envelope).
VARY = {
    "delta": "0.01,0.1",
    "design.max_outer_diameter": "0.3,1.2",
    "objective": "mass,outer_diameter",
    "speed": "60,120rpm",
}


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    folder = tmp_path_factory.mktemp("study")
    scene = flyopt.load(PROBLEMS / "punch-press.toml")
    frame = flyopt.sweep(scene, VARY, workers=1)
    for suffix in ("parquet", "csv"):
        flyopt.sweep(scene, VARY, output=folder / f"study.{suffix}", workers=1)
    return scene, frame, folder


def test_a_sweep_has_points_of_every_kind(study):
    _, frame, _ = study
    assert set(frame["status"]) == {"designed", "infeasible"}
    assert set(frame["method"]) == {"closed_form", "ipopt"}


def test_parquet_holds_nulls_not_empty_text_or_minus_one(study):
    """Read by pyarrow itself: where a point has no value the cell is null, never "" or -1 or NaN."""
    _, frame, folder = study
    table = pq.read_table(folder / "study.parquet")
    designed = np.array(table.column("status").to_pylist()) == "designed"
    ipopt = np.array(table.column("method").to_pylist()) == "ipopt"
    for name in ("best_material", "best_shaft", "binding"):
        column = table.column(name)
        assert (np.array(column.is_null().to_pylist()) == ~designed).all(), name
        assert "" not in column.to_pylist()
    iterations = table.column("iterations")
    assert str(iterations.type) == "int64"
    assert (np.array(iterations.is_null().to_pylist()) == ~(designed & ipopt)).all()
    assert -1 not in iterations.to_pylist()
    for name in ("mass", "d_outer", "cost", "design.d_mean"):
        column = table.column(name)
        assert not pc.any(pc.is_nan(column)).as_py(), name  # NaN is a value; no value is null
    assert table.column("mass").null_count == int((~designed).sum())
    assert table.column("design.d_mean").null_count == len(frame)  # no pinned mean diameter
    assert table.column("message").null_count > 0 and "" not in table.column("message").to_pylist()


def test_csv_holds_empty_cells_and_its_sidecar_says_so(study):
    _, frame, folder = study
    with open(folder / "study.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == len(frame)
    for row in rows:
        if row["status"] != "designed":
            assert row["best_material"] == row["mass"] == row["binding"] == ""
        if row["method"] != "ipopt" or row["status"] != "designed":
            assert row["iterations"] == ""
        assert "-1" not in (row["iterations"], row["n_feasible"]) and "nan" not in row.values()
    plain = pd.read_csv(folder / "study.csv")  # pandas without flyopt reads an empty cell as NaN
    assert plain["best_material"].isna().sum() == int((frame["status"] != "designed").sum())
    sidecar = json.loads((folder / "study.csv.json").read_text())
    assert schema_errors(sidecar) == []
    assert sidecar["csv"] == {"delimiter": ",", "header": True, "null": ""}
    assert [c["name"] for c in sidecar["columns"]] == list(plain.columns)
    types = {c["name"]: c["type"] for c in sidecar["columns"]}
    assert types["iterations"] == "integer" and types["best_material"] == "string" and types["mass"] == "number"


def test_the_frame_in_memory_has_the_same_nulls(study):
    _, frame, folder = study
    assert frame["best_material"].isna().equals(frame["status"] != "designed")
    assert str(frame["iterations"].dtype) == "Int64"
    assert frame["iterations"].isna().equals((frame["method"] != "ipopt") | (frame["status"] != "designed"))
    text = [c for c in frame.columns if results.column_kind(c, frame[c]) == "str"]
    assert len(text) >= 9 and not any(frame[c].dropna().eq("").any() for c in text)
    for suffix in ("parquet", "csv"):
        pd.testing.assert_frame_equal(read_results(folder / f"study.{suffix}"), frame)


def test_sweep_files_carry_units_and_provenance(study):
    """The metadata against values computed here: the scene file's SHA-256, flyopt's digest of the
    scene, the swept speeds in rad/s (60 rpm = 2 pi rad/s), the installed version."""
    scene, frame, folder = study
    stored = json.loads(pq.read_schema(folder / "study.parquet").metadata[b"flyopt"])
    sidecar = json.loads((folder / "study.csv.json").read_text())
    assert {k: v for k, v in sidecar.items() if k != "csv"} == stored
    assert schema_errors(stored) == []
    assert stored["kind"] == "sweep" and stored["flyopt_version"] == importlib.metadata.version("flyopt")
    assert stored["scene"] == str(PROBLEMS / "punch-press.toml")
    assert stored["scene_file_sha256"] == hashlib.sha256((PROBLEMS / "punch-press.toml").read_bytes()).hexdigest()
    assert stored["scene_digest"] == digest(flyopt.load(PROBLEMS / "punch-press.toml"))
    vary = stored["sweep"]["vary"]
    # 60 and 120 rpm in rad/s, to round-off (flyopt multiplies by pint's factor 2 pi/60 in one step)
    np.testing.assert_allclose(
        vary["speed"]["values"], [60 * 2 * math.pi / 60, 120 * 2 * math.pi / 60], rtol=1e-15, atol=0
    )
    assert vary["design.objective"]["values"] == ["mass", "outer_diameter"]
    assert stored["sweep"]["method"] == "auto" and stored["sweep"]["points"] == len(frame)
    units = stored["units"]
    assert units["speed"] == "rad/s" and units["mass"] == "kg" and units["design.max_outer_diameter"] == "m"
    assert units["a_max"] == "J" and units["delta"] == "1" and "status" not in units and "point" not in units
    assert units["objective"] is None  # the sweep varies the objective: kg or m by row
    assert [c["name"] for c in stored["columns"]] == list(frame.columns)
    assert read_results(folder / "study.parquet").attrs["flyopt"] == stored
    assert frame.attrs["flyopt"] == stored


def test_a_sweep_of_one_objective_gives_its_unit(tmp_path):
    out = tmp_path / "one.parquet"
    flyopt.sweep(flyopt.load(PROBLEMS / "shear-press.toml"), {"delta": "0.02,0.05"}, output=out)
    assert read_results(out).attrs["flyopt"]["units"]["objective"] == "kg"


def test_pareto_files_record_their_objectives_and_plot_needs_no_x(tmp_path, capsys, monkeypatch):
    """The objectives are read from the file's metadata, not guessed from its columns: a front
    whose columns were put in another order still plots its second objective along x."""
    from flyopt.report import plots

    drawn = []
    original = plots.plot_pareto
    monkeypatch.setattr(
        plots, "plot_pareto", lambda frame, x, y, ax=None, **kw: drawn.append(x) or original(frame, x, y, **kw)
    )
    for suffix in ("parquet", "csv", "json"):
        out = tmp_path / f"front.{suffix}"
        assert (
            main(
                [
                    "pareto",
                    str(PROBLEMS / "punch-press.toml"),
                    "--objectives",
                    "mass,delta",
                    "--points",
                    "4",
                    "-o",
                    str(out),
                    "-q",
                ]
            )
            == 0
        )
        assert capsys.readouterr().out == ""
        if suffix == "json":
            document = json.loads(out.read_text())
        else:
            document = read_results(out).attrs["flyopt"]
            frame = read_results(out)
            assert list(frame.columns[:2]) == ["mass", "delta"]
            shuffled = tmp_path / f"shuffled.{suffix}"
            columns = [c for c in frame.columns if c not in ("mass", "delta")] + ["delta", "mass"]
            assert plots.pareto_objectives(frame[columns]) is None  # the columns alone tell nothing
            results.write_results(
                frame[columns],
                shuffled,
                metadata=table_metadata("pareto", columns, objectives=document["objectives"]),
            )
            assert main(["plot", str(shuffled), "--what", "pareto", "-o", str(tmp_path / f"{suffix}.png")]) == 0
            assert drawn[-1] == "delta" and capsys.readouterr().out.startswith("wrote ")
        assert schema_errors(document) == [] and document["objectives"] == ["mass", "delta"]
        assert document["kind"] == "pareto" and document["units"]["epsilon"] == "1"
    assert "rows" in document and len(document["rows"]) == 4


def test_pareto_and_tradeoff_json_are_documents_with_nulls(tmp_path, capsys):
    scene = variant(
        tmp_path, "s", (PROBLEMS / "shear-press.toml").read_text().replace("delta = 0.05", "delta = 0.004")
    )  # cast iron cannot give J_F (tests/studies/test_pareto_tradeoff.py)
    assert main(["tradeoff", str(scene), "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert schema_errors(document) == [] and document["kind"] == "tradeoff"
    rows = {r["material"]: r for r in document["rows"]}
    assert rows["cast_iron"]["status"] == "infeasible"
    assert rows["cast_iron"]["mass"] is None and rows["cast_iron"]["shaft"] is None
    assert rows["cast_iron"]["binding"] is None and rows["cast_steel"]["reason"] is None
    assert "" not in [v for r in document["rows"] for v in r.values()]
    assert document["units"]["mass"] == "kg" and document["units"]["rim_speed"] == "m/s"
    assert document["scene_file_sha256"] == hashlib.sha256(scene.read_bytes()).hexdigest()


def test_a_tradeoff_writes_parquet(tmp_path):
    """Regression: the trade-off's text columns (shaft, limit) were taken for numbers and
    ``flyopt tradeoff -o table.parquet`` failed with exit 1."""
    out = tmp_path / "table.parquet"
    assert main(["tradeoff", str(PROBLEMS / "punch-press.toml"), "-o", str(out), "-q"]) == 0
    table = read_results(out)
    assert list(table["material"]) == ["cast_steel", "ductile_iron", "cast_iron"]
    assert set(table["limit"]) == {"rim_speed,hb_min"}
    assert table.attrs["flyopt"]["kind"] == "tradeoff" and schema_errors(table.attrs["flyopt"]) == []


def test_a_mutated_table_document_fails(study):
    _, _, folder = study
    stored = json.loads(pq.read_schema(folder / "study.parquet").metadata[b"flyopt"])
    for mutate in (
        delete_at(["units"]),
        delete_at(["sweep"]),
        set_at(["kind"], "pareto"),
        set_at(["scene_file_sha256"], "abc"),
        set_at(["columns", 0, "type"], "float"),
        set_at(["sweep", "seed"], "none"),
    ):
        changed = json.loads(json.dumps(stored))
        mutate(changed)
        assert schema_errors(changed)
