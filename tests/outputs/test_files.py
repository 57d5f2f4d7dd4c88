"""flyopt.outputs.files: ``-o FILE`` is written whole or not at all, a bad one is one line;
``--quiet`` leaves the result and nothing else (issue 15, part 5).
"""

import os

import pytest
from conftest import PROBLEMS

from flyopt.cli.main import main
from flyopt.outputs.files import write_text
from flyopt.outputs.results import read_results

# --------------------------------------------------------------------------
# -o FILE and --quiet
# --------------------------------------------------------------------------


@pytest.mark.parametrize("options", [[], ["--json"]])
def test_solve_to_a_file_writes_what_it_prints(tmp_path, capsys, options):
    scene = str(PROBLEMS / "shear-press.toml")
    assert main(["solve", scene, *options]) == 0
    printed = capsys.readouterr().out
    out = tmp_path / "result.txt"
    assert main(["solve", scene, *options, "-o", str(out)]) == 0
    said = capsys.readouterr()
    assert said.out == f"wrote {out}\n" and said.err == ""
    assert out.read_text() == printed
    assert main(["solve", scene, *options, "-o", str(out), "--quiet"]) == 0
    assert capsys.readouterr() == ("", "") and out.read_text() == printed
    assert [p.name for p in tmp_path.iterdir()] == ["result.txt"]  # no temporary file left


def test_solve_to_a_file_is_all_or_nothing(tmp_path, capsys, monkeypatch):
    """A failure after part of the result was printed, or Ctrl-C, leaves the old file as it was
    and no temporary file."""
    import flyopt.cli.scene

    out = tmp_path / "result.json"
    out.write_text("earlier result\n")

    def half_then(error):
        def handler(args):
            print('{"a_max": 1,')
            raise error

        return handler

    for error, status in ((flyopt.SolverFailed("did not converge"), 1), (KeyboardInterrupt(), 130)):
        monkeypatch.setattr(flyopt.cli.scene, "run_solve", half_then(error))
        assert main(["solve", str(PROBLEMS / "shear-press.toml"), "-o", str(out)]) == status
        assert out.read_text() == "earlier result\n"
        assert [p.name for p in tmp_path.iterdir()] == ["result.json"]
        assert capsys.readouterr().out == ""


def test_a_text_file_is_written_whole_or_not_at_all(tmp_path):
    out = tmp_path / "result.txt"
    out.write_text("earlier\n")
    with pytest.raises(UnicodeEncodeError):
        write_text(out, "A_max = 1 J\n" * 1000 + "\ud800")  # fails half-way through
    assert out.read_text() == "earlier\n" and [p.name for p in tmp_path.iterdir()] == ["result.txt"]
    write_text(out, "A_max = 1 J")
    assert out.read_text() == "A_max = 1 J\n"


@pytest.mark.parametrize(
    "args, match",
    [
        (
            ["solve", str(PROBLEMS / "shear-press.toml"), "-o", "no/such/folder/x.json"],
            "-o/--output: the folder 'no/such/folder' of 'no/such/folder/x.json' does not exist",
        ),
        (
            ["solve", str(PROBLEMS / "shear-press.toml"), "-o", str(PROBLEMS / "shear-press.toml")],
            "is the scene file itself",
        ),
        (
            ["pareto", str(PROBLEMS / "shear-press.toml"), "-o", "front.txt"],
            "-o/--output: 'front.txt' must end in .csv, .parquet or .json",
        ),
        (
            ["tradeoff", str(PROBLEMS / "shear-press.toml"), "-o", "no/such/folder/t.json", "-q"],
            "-o/--output: the folder 'no/such/folder'",
        ),
        (["solve", str(PROBLEMS / "missing.toml"), "-q"], "missing.toml"),
    ],
)
def test_a_bad_output_is_one_line_and_status_2_even_when_quiet(args, match, capsys):
    assert main(args) == 2
    said = capsys.readouterr()
    assert said.out == "" and said.err.count("\n") == 1 and match in said.err
    assert "Traceback" not in said.err


def test_quiet_leaves_the_result_and_nothing_else(tmp_path, capsys):
    scene = str(PROBLEMS / "shear-press.toml")
    assert main(["check", scene, "--quiet"]) == 0
    assert capsys.readouterr() == ("", "")
    assert main(["plot", scene, "--what", "energy", "-o", str(tmp_path / "e.png"), "-q"]) == 0
    assert capsys.readouterr() == ("", "") and (tmp_path / "e.png").stat().st_size > 0
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-o", str(tmp_path / "s.csv"), "-q"]) == 0
    assert capsys.readouterr() == ("", "") and len(read_results(tmp_path / "s.csv")) == 2
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-q"]) == 0  # the result is stdout
    said = capsys.readouterr()
    assert said.err == "" and said.out.splitlines()[0].startswith("point,delta,")
    assert main(["solve", scene, "-q"]) == 0 and "A_max" in capsys.readouterr().out
    assert main(["sweep", scene, "--vary", "delta=0.02,0.05", "-o", str(tmp_path / "t.csv")]) == 0
    assert "flyopt sweep: wrote" in capsys.readouterr().err  # and without --quiet, the summary


# --------------------------------------------------------------------------
# Issue 25, item 1: -o replaces only a regular file; a link is followed
# --------------------------------------------------------------------------

SHEAR = PROBLEMS / "shear-press.toml"
COMMANDS = {
    "solve": ["solve", str(SHEAR), "--json", "-o"],
    "report": ["report", str(SHEAR), "-o"],
    "plot": ["plot", str(SHEAR), "--what", "turning_moment", "-o"],
    "tradeoff": ["tradeoff", str(SHEAR), "-o"],
}
SUFFIX = {"solve": ".json", "report": ".html", "plot": ".svg", "tradeoff": ".csv"}


def _device(path):
    """A character device with /dev/null's numbers, made in the test's folder (never the machine's own)."""
    import os
    import stat

    os.mknod(path, 0o666 | stat.S_IFCHR, os.makedev(1, 3))


@pytest.mark.parametrize("command", list(COMMANDS))
@pytest.mark.parametrize("kind", ["device", "folder", "fifo"])
def test_an_output_that_is_not_a_regular_file_is_refused(tmp_path, capsys, command, kind):
    """`flyopt solve ... --json -o /dev/full` run as root turned /dev/full into a JSON file; a folder or
    a FIFO at -o was renamed over or hung. Each is refused in one line, exit 2, and left as it was."""
    import os
    import stat

    out = tmp_path / f"out{SUFFIX[command]}"
    if kind == "device":
        if os.geteuid() != 0:
            pytest.fail("making a device node needs root (this test's machine runs as root)")
        _device(out)
    elif kind == "folder":
        out.mkdir()
    else:
        os.mkfifo(out)
    mode = os.lstat(out).st_mode
    assert main([*COMMANDS[command], str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and f"is a {kind if kind != 'fifo' else 'FIFO'}" in err, err
    assert os.lstat(out).st_mode == mode and stat.S_IFMT(mode) != stat.S_IFREG
    assert sorted(p.name for p in tmp_path.iterdir()) == [out.name]  # no temporary left beside it


@pytest.mark.parametrize("command", list(COMMANDS))
def test_an_output_that_is_a_link_writes_its_target(tmp_path, capsys, command):
    """A symlink at -o was replaced by a file; it is followed, its target written, the link kept."""
    target = tmp_path / "real" / f"target{SUFFIX[command]}"
    target.parent.mkdir()
    target.write_text("old")
    link = tmp_path / f"out{SUFFIX[command]}"
    link.symlink_to(target)
    assert main([*COMMANDS[command], str(link)]) == 0
    capsys.readouterr()
    assert link.is_symlink() and link.resolve() == target
    assert target.stat().st_size > 3 and target.read_bytes()[:3] != b"old"
    assert sorted(p.name for p in target.parent.iterdir()) == [target.name]


def test_a_disk_that_fills_up_is_its_own_exit_status_naming_the_file(tmp_path, capsys, monkeypatch):
    """A full disk was reported as bad input (exit 2) naming the scene; it is status 5, the line
    names the file that could not be written, and nothing is left under its name."""
    import errno
    import os

    real_replace = os.replace

    def full(src, dst):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(dst))

    monkeypatch.setattr(os, "replace", full)
    out = tmp_path / "out.json"
    assert main(["solve", str(SHEAR), "--json", "-o", str(out)]) == 5
    err = capsys.readouterr().err
    assert err.splitlines() == [f"flyopt: error: {out}: cannot be written: No space left on device"]
    monkeypatch.setattr(os, "replace", real_replace)
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------
# No command writes its output over the scene it reads (a scene file may have any name)
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "command", "what"),
    [
        ("scene.json", ["solve", "{scene}", "--json", "-o", "{scene}"], "the result"),
        ("scene.html", ["report", "{scene}", "-o", "{scene}"], "the report"),
        ("scene.csv", ["pareto", "{scene}", "-o", "{scene}"], "the front"),
        ("scene.csv", ["tradeoff", "{scene}", "-o", "{scene}"], "the table"),
        ("scene.csv", ["sweep", "{scene}", "--vary", "delta=0.02,0.05", "-o", "{scene}"], "the sweep's table"),
        ("scene.png", ["plot", "{scene}", "--what", "energy", "-o", "{scene}"], "the diagram"),
        ("energy.png", ["plot", "{scene}", "--what", "all", "-o", "{folder}"], "the diagram"),
    ],
    ids=["solve", "report", "pareto", "tradeoff", "sweep", "plot", "plot-all"],
)
def test_no_output_replaces_the_scene_it_was_made_from(tmp_path, capsys, name, command, what):
    scene = tmp_path / name
    text = SHEAR.read_text(encoding="utf-8")
    scene.write_text(text, encoding="utf-8")
    args = [a.format(scene=scene, folder=tmp_path) for a in command]
    assert main(args) == 2
    said = capsys.readouterr()
    assert said.err.count("\n") == 1 and "Traceback" not in said.err, said.err
    assert "is the scene file itself" in said.err and f"name another file for {what}" in said.err, said.err
    assert [p.name for p in tmp_path.iterdir()] == [name] and scene.read_text(encoding="utf-8") == text


# --------------------------------------------------------------------------
# Nor over a data file the scene reads (its points_file): the loader records each file it reads
# --------------------------------------------------------------------------

_SHEAR_FROM_CSV = """title = "Shear press, its resisting torque from a CSV file"

[machine]
speed = "1500 rpm"
delta = 0.05

[torque.resisting]
angle_unit = "deg"
unit = "N*m"
points_file = "{table}"

[torque.driving]
constant = "unknown"

[design]
geometry = "rim"
max_outer_diameter = "0.6 m"
"""

_SHEAR_TABLE = "angle,torque\n0,1600\n45,1600\n90,200\n360,200\n"


@pytest.mark.parametrize(
    ("table", "command", "what"),
    [
        ("torque.csv", ["solve", "{scene}", "-o", "{table}"], "the result"),
        ("torque.csv", ["solve", "{scene}", "--json", "-o", "{spelled}"], "the result"),
        ("torque.html", ["report", "{scene}", "-o", "{table}"], "the report"),
        ("torque.csv", ["pareto", "{scene}", "-o", "{table}"], "the front"),
        ("torque.csv", ["tradeoff", "{scene}", "-o", "{table}"], "the table"),
        ("torque.csv", ["sweep", "{scene}", "--vary", "delta=0.02,0.05", "-o", "{link}"], "the sweep's table"),
        ("torque.png", ["plot", "{scene}", "--what", "energy", "-o", "{table}"], "the diagram"),
        ("energy.png", ["plot", "{scene}", "--what", "all", "-o", "{folder}"], "the diagram"),
        ("torque.svg", ["export", "{scene}", "-o", "{table}"], "the drawing"),
    ],
    ids=["solve", "solve-spelled", "report", "pareto", "tradeoff", "sweep-link", "plot", "plot-all", "export"],
)
def test_no_output_replaces_a_data_file_the_scene_reads(tmp_path, capsys, table, command, what):
    """``flyopt solve scene.toml -o torque.csv`` replaced the scene's own points_file with the result; any
    spelling of that file (another path to it, a symbolic link to it) is refused alike, and nothing is written."""
    scene = tmp_path / "scene.toml"
    scene.write_text(_SHEAR_FROM_CSV.format(table=table), encoding="utf-8")
    data = tmp_path / table
    data.write_text(_SHEAR_TABLE, encoding="utf-8")
    (tmp_path / "sub").mkdir()
    (tmp_path / "link.csv").symlink_to(data)
    before = sorted(p.name for p in tmp_path.iterdir())
    places = {
        "scene": scene,
        "table": data,
        "spelled": tmp_path / "sub" / ".." / table,
        "link": tmp_path / "link.csv",
        "folder": tmp_path,
    }
    assert main(["solve", str(scene), "-q"]) == 0  # the scene itself is sound
    args = [a.format(**places) for a in command]
    assert main(args) == 2
    said = capsys.readouterr()
    assert said.err.count("\n") == 1 and "Traceback" not in said.err, said.err
    label = "--output" if command[0] == "sweep" else "-o/--output"
    assert said.err.startswith(f"flyopt: error: {label}: "), said.err
    assert "the scene's torque.resisting.points_file names, an input" in said.err, said.err
    assert f"name another file for {what}" in said.err, said.err
    assert data.read_text(encoding="utf-8") == _SHEAR_TABLE
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_the_scene_records_the_files_it_read(tmp_path):
    """Scene.inputs: each data file read, by its field; a copy of the scene keeps them; an inline table none."""
    from flyopt.io.scene import load

    (tmp_path / "torque.csv").write_text(_SHEAR_TABLE, encoding="utf-8")
    scene = load(tmp_path / "scene.toml", tomllib_loads(_SHEAR_FROM_CSV.format(table="torque.csv")))
    assert scene.inputs == (("torque.resisting.points_file", str(tmp_path / "torque.csv")),)
    assert scene.replace(delta=0.02).inputs == scene.inputs
    assert load(SHEAR).inputs == ()
    engine = load(PROBLEMS / "four-stroke-engine-csv.toml")
    assert engine.inputs == (("torque.driving.points_file", str(PROBLEMS / "four-stroke-engine-torque.csv")),)


def test_a_report_lists_the_data_files_the_scene_read(tmp_path):
    """The report's provenance names each file read, by its field, from the scene file's folder."""
    from flyopt.cli.report import provenance
    from flyopt.io.scene import load

    (tmp_path / "tables").mkdir()
    (tmp_path / "tables" / "torque.csv").write_text(_SHEAR_TABLE, encoding="utf-8")
    scene = load(tmp_path / "scene.toml", tomllib_loads(_SHEAR_FROM_CSV.format(table="tables/./torque.csv")))
    rows = dict(provenance(scene))
    assert rows["data files the scene reads"] == (
        "torque.resisting.points_file = tables/torque.csv (not in the hash above)"
    )
    assert "data files the scene reads" not in dict(provenance(load(SHEAR)))


def tomllib_loads(text):
    import tomllib

    return tomllib.loads(text)


def test_a_data_file_is_refused_by_a_hard_link_too(tmp_path, capsys):
    """The same file by another name: a hard link to the points_file (the file system's own identity)."""
    scene = tmp_path / "scene.toml"
    scene.write_text(_SHEAR_FROM_CSV.format(table="torque.csv"), encoding="utf-8")
    (tmp_path / "torque.csv").write_text(_SHEAR_TABLE, encoding="utf-8")
    os.link(tmp_path / "torque.csv", tmp_path / "hard.csv")
    assert main(["solve", str(scene), "-o", str(tmp_path / "hard.csv")]) == 2
    assert "the scene's torque.resisting.points_file names, an input" in capsys.readouterr().err
    assert (tmp_path / "torque.csv").read_text(encoding="utf-8") == _SHEAR_TABLE


@pytest.mark.parametrize("command", ["pareto", "tradeoff", "sweep"])
def test_no_table_replaces_a_data_file_by_its_sidecar(tmp_path, capsys, command):
    """A CSV table is written with its sidecar FILE.csv.json: that file may not be one the scene reads either."""
    scene = tmp_path / "scene.toml"
    scene.write_text(_SHEAR_FROM_CSV.format(table="res.csv.json"), encoding="utf-8")
    data = tmp_path / "res.csv.json"
    data.write_text(_SHEAR_TABLE, encoding="utf-8")
    extra = ["--vary", "delta=0.02,0.05"] if command == "sweep" else []
    assert main([command, str(scene), *extra, "-o", str(tmp_path / "res.csv")]) == 2
    said = capsys.readouterr()
    assert said.err.count("\n") == 1 and "res.csv.json' is the file the scene's torque.resisting.points_file" in (
        said.err
    ), said.err
    assert data.read_text(encoding="utf-8") == _SHEAR_TABLE
    assert sorted(p.name for p in tmp_path.iterdir()) == ["res.csv.json", "scene.toml"]


def test_a_sweep_table_in_the_scene_may_not_name_its_data_file(tmp_path, capsys):
    """[sweep] output naming the scene's own points_file: refused by flyopt check and flyopt sweep alike,
    the field named as written, with the file."""
    scene = tmp_path / "scene.toml"
    text = (
        _SHEAR_FROM_CSV.format(table="torque.csv")
        + '\n[sweep]\noutput = "torque.csv"\n[sweep.vary]\ndelta = "0.02,0.05"\n'
    )
    scene.write_text(text, encoding="utf-8")
    (tmp_path / "torque.csv").write_text(_SHEAR_TABLE, encoding="utf-8")
    for command in ("check", "sweep"):
        assert main([command, str(scene)]) == 2
        err = capsys.readouterr().err
        assert f"{scene}" in err and "sweep.output: " in err and "torque.resisting.points_file" in err, err
        assert (tmp_path / "torque.csv").read_text(encoding="utf-8") == _SHEAR_TABLE


def test_the_inputs_name_their_files_after_the_working_folder_changes(tmp_path, monkeypatch):
    """A scene loaded by a relative path keeps absolute paths of its data files: after os.chdir (a notebook)
    flyopt.sweep still refuses to write over them."""
    import flyopt

    folder = tmp_path / "study"
    folder.mkdir()
    (folder / "scene.toml").write_text(_SHEAR_FROM_CSV.format(table="torque.csv"), encoding="utf-8")
    (folder / "torque.csv").write_text(_SHEAR_TABLE, encoding="utf-8")
    monkeypatch.chdir(folder)
    scene = flyopt.load("scene.toml")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(flyopt.SceneError, match="torque.resisting.points_file names, an input"):
        flyopt.sweep(scene, {"delta": [0.02, 0.05]}, output="study/torque.csv")
    assert (folder / "torque.csv").read_text(encoding="utf-8") == _SHEAR_TABLE


def test_where_the_data_files_were_read_from_changes_no_digest(tmp_path, monkeypatch):
    """The scene's digest (a sweep's parts, a table's metadata) is the same whatever folder it was loaded
    from: a sweep started in one folder is resumed from another."""
    from flyopt.io.scene import load
    from flyopt.studies.payload import digest

    absolute = load(PROBLEMS / "four-stroke-engine-csv.toml")
    monkeypatch.chdir(PROBLEMS)
    here = load("four-stroke-engine-csv.toml")
    monkeypatch.chdir(PROBLEMS.parent)
    above = load(f"{PROBLEMS.name}/four-stroke-engine-csv.toml")
    assert absolute.inputs == here.inputs == above.inputs  # absolute paths, alike
    assert digest(absolute) == digest(here) == digest(above)
    changed = load(tomllib_loads_file(PROBLEMS / "four-stroke-engine-csv.toml", tmp_path))
    assert digest(changed) != digest(absolute)  # the digest still sees the table's numbers


def tomllib_loads_file(path, folder):
    """A copy of the scene ``path`` and its CSV in ``folder``, one torque of the CSV changed: the copy's path."""
    import shutil

    shutil.copy(path, folder / path.name)
    table = (path.parent / "four-stroke-engine-torque.csv").read_text(encoding="utf-8").splitlines()
    last = table[-2].split(",")
    table[-2] = f"{last[0]},{float(last[1]) + 1.0}"
    (folder / "four-stroke-engine-torque.csv").write_text("\n".join(table) + "\n", encoding="utf-8")
    return folder / path.name


# --------------------------------------------------------------------------
# A table of results is read as any input (flyopt plot RESULTS, a resume's parts)
# --------------------------------------------------------------------------


def test_a_results_table_that_is_no_file_is_refused_not_read(tmp_path, capsys):
    """`flyopt plot fifo.csv` blocked forever, and a link to /dev/zero filled memory: one line now, exit 2."""
    fifo = tmp_path / "fifo.csv"
    os.mkfifo(fifo)
    (tmp_path / "zero.csv").symlink_to("/dev/zero")
    for table in (fifo, tmp_path / "zero.csv"):
        assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "not a regular file" in err and str(table) in err, err
    assert not (tmp_path / "p.png").exists()


def test_a_results_table_over_the_row_limit_is_refused_before_it_is_read(tmp_path, capsys, monkeypatch):
    """A Parquet file's rows are counted from its footer first: a small file may hold a billion rows."""
    table = tmp_path / "s.parquet"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02:0.1:12", "-o", str(table), "-q"]) == 0
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "10")
    assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 2
    err = capsys.readouterr().err
    assert "has over 10 rows" in err and "FLYOPT_MAX_TABLE_ROWS raises it" in err, err
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "12")
    assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 0


def test_a_sidecar_that_is_no_metadata_is_one_line(tmp_path, capsys):
    """A CSV's sidecar holding a JSON list (or no JSON) ended in a traceback of the plot."""
    table = tmp_path / "s.csv"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05", "-o", str(table), "-q"]) == 0
    for text, words in (("[1, 2]", "not flyopt's metadata"), ("{oops", "not JSON")):
        (tmp_path / "s.csv.json").write_text(text, encoding="utf-8")
        assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and words in err and "Traceback" not in err, err


def _with_columns(frame, count):
    """``frame`` widened to ``count`` columns by numbered copies of its ``mass``."""
    import pandas as pd

    extra = pd.DataFrame({f"extra_{k}": frame["mass"] for k in range(count - len(frame.columns))})
    return pd.concat([frame, extra], axis=1)


@pytest.mark.parametrize("suffix", ["csv", "parquet"])
def test_a_results_table_over_the_column_limit_is_refused_before_its_rows(tmp_path, capsys, suffix):
    """A CSV of 20,000 columns took 22 s to be refused for want of its `mass`; a Parquet file's columns are
    counted from its footer. 1,000 columns are read; 1,001 are one line, exit 2."""
    from flyopt.io.input_files import MAX_TABLE_COLUMNS
    from flyopt.outputs.results import read_results

    table = tmp_path / "s.csv"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05", "-o", str(table), "-q"]) == 0
    frame = read_results(table)
    for count in (MAX_TABLE_COLUMNS, MAX_TABLE_COLUMNS + 1):
        wide = tmp_path / f"w{count}.{suffix}"
        widened = _with_columns(frame, count)
        widened.to_csv(wide, index=False) if suffix == "csv" else widened.to_parquet(wide, index=False)
        status = main(["plot", str(wide), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / f"p{count}.png")])
        err = capsys.readouterr().err
        if count == MAX_TABLE_COLUMNS:
            assert (status, err) == (0, "") and len(read_results(wide).columns) == count
        else:
            assert status == 2 and err == (
                f"flyopt: error: {wide}: cannot read the results: {wide} has {count} columns (allowed: at most "
                f"{MAX_TABLE_COLUMNS})\n"
            )
            assert not (tmp_path / f"p{count}.png").exists()


def test_a_sidecar_naming_more_columns_than_a_table_may_have_is_refused_before_it_is_walked(tmp_path, capsys):
    """A sidecar listing a million columns took 108 s and 1.4 GB to draw the plot (walked, then copied with
    the frame's attrs at each pandas step): refused at once."""
    import json

    from flyopt.io.input_files import MAX_TABLE_COLUMNS

    table = tmp_path / "s.csv"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05", "-o", str(table), "-q"]) == 0
    sidecar = tmp_path / "s.csv.json"
    record = json.loads(sidecar.read_text(encoding="utf-8"))
    count = MAX_TABLE_COLUMNS + 1
    record["columns"] += [{"name": f"x{k}", "type": "number"} for k in range(count - len(record["columns"]))]
    sidecar.write_text(json.dumps(record), encoding="utf-8")
    assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 2
    err = capsys.readouterr().err
    assert err == (
        f"flyopt: error: {table}: cannot read the results: cannot read {sidecar}: columns has {count} entries "
        f"(allowed: at most {MAX_TABLE_COLUMNS})\n"
    )


@pytest.mark.parametrize("what", ["sweep", "pareto"])
@pytest.mark.parametrize("value", ["1e308", "-inf"])
def test_a_number_no_diagram_can_draw_is_refused_in_one_line(tmp_path, capsys, what, value):
    """A mass of 1e308 edited into a sweep's CSV ended the plot in "arange: cannot compute length" after
    matplotlib's overflow warnings; 1e150, at the limit, is drawn."""
    import csv

    from flyopt.report.plots.results import MAX_DRAWN

    table = tmp_path / "s.csv"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05,0.08", "-o", str(table), "-q"]) == 0
    with table.open(encoding="utf-8", newline="") as handle:
        rows = list(csv.reader(handle))
    mass = rows[0].index("mass")
    args = ["--x", "delta"] if what == "sweep" else ["--x", "delta", "--y", "mass"]
    for size, status in ((value, 2), (f"{MAX_DRAWN:g}", 0)):
        rows[2][mass] = size
        with table.open("w", encoding="utf-8", newline="") as handle:
            csv.writer(handle).writerows(rows)
        out = tmp_path / f"p{status}.png"
        assert main(["plot", str(table), "--what", what, *args, "-o", str(out)]) == status
        err = capsys.readouterr().err
        if status:
            shown = f"{float(value):g}"
            assert (
                err
                == (
                    f"flyopt: error: {table}: the column 'mass' holds {shown} (allowed: numbers of size at most "
                    f"{MAX_DRAWN:g}, or none): it cannot be drawn\n"
                )
                and not out.exists()
            )
        else:
            assert err == "" and out.stat().st_size > 0


@pytest.mark.parametrize(
    "where, unit, words",
    [
        ("units", "furlong", "units.mass 'furlong' does not measure mass"),
        ("units", "no_such_unit", "units.mass 'no_such_unit' does not measure mass"),
        ("vary", "furlong", "sweep.vary.delta.unit 'furlong' does not measure a plain number"),
    ],
)
def test_a_sidecar_unit_that_does_not_measure_its_column_is_refused(tmp_path, capsys, where, unit, words):
    """A sidecar saying the mass is in furlongs was read without a word; a varied δ "in furlong" failed only
    when read back in the input's units (`read_results(path, units="input")`), naming no file."""
    import json
    import re

    import flyopt
    from flyopt.errors import SceneError

    table = tmp_path / "s.csv"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05", "-o", str(table), "-q"]) == 0
    sidecar = tmp_path / "s.csv.json"
    record = json.loads(sidecar.read_text(encoding="utf-8"))
    assert record["units"]["mass"] == "kg" and record["sweep"]["vary"]["delta"]["unit"] is None
    flyopt.read_results(table, units="input")  # as written: read
    if where == "units":
        record["units"]["mass"] = unit
    else:
        record["sweep"]["vary"]["delta"]["unit"] = unit
    sidecar.write_text(json.dumps(record), encoding="utf-8")
    assert main(["plot", str(table), "--what", "sweep", "--x", "delta", "-o", str(tmp_path / "p.png")]) == 2
    assert (
        capsys.readouterr().err == f"flyopt: error: {table}: cannot read the results: cannot read {sidecar}: {words}\n"
    )
    with pytest.raises(SceneError, match=re.escape(f"cannot read {sidecar}: {words}")):
        flyopt.read_results(table, units="input")


def test_every_quantity_flyopt_writes_is_read_back_with_its_unit(tmp_path):
    """The metadata's unit check reads what flyopt writes: a column of each quantity flyopt knows (those of
    dimensions only results have, an unbalance in kg*m or a rate in 1/s, included: they ended the read in
    "KeyError: 'unbalance'"), each with the unit its metadata gives it."""
    import pandas as pd

    from flyopt.outputs.documents import table_metadata
    from flyopt.outputs.quantities import INPUTS, OUTPUT_DIMENSIONS, QUANTITIES, dimension_of
    from flyopt.outputs.results import write_results

    names = [n for n in {**QUANTITIES, **INPUTS} if dimension_of(n) is not None]
    assert {dimension_of(n) for n in names} >= set(OUTPUT_DIMENSIONS)
    frame = pd.DataFrame({n: [1.0] for n in names})
    for suffix in ("csv", "parquet"):
        path = tmp_path / f"all.{suffix}"
        write_results(frame, path, metadata=table_metadata("sweep", list(frame.columns)))
        back = read_results(path)
        assert list(back.columns) == names
        assert all(back.attrs["flyopt"]["units"][n] for n in names if dimension_of(n) != "dimensionless")


@pytest.mark.parametrize("command", ["plot-all", "sweep", "pareto", "tradeoff"])
def test_a_link_at_a_name_flyopt_makes_beside_the_output_is_refused_and_not_followed(tmp_path, main_cli, command):
    """A diagram of --what all was written through a link planted in the folder given, a CSV's sidecar through a
    link beside the table: both out of where the user pointed, exit 0."""
    outside = tmp_path / "victim"
    outside.write_text("kept", encoding="utf-8")
    folder = tmp_path / "out"
    folder.mkdir()
    shear = PROBLEMS / "shear-press.toml"
    if command == "plot-all":
        (folder / "energy.png").symlink_to(outside)
        args = ["plot", shear, "--what", "all", "-o", f"{folder}/"]
    else:
        (folder / "t.csv.json").symlink_to(outside)
        extra = ["--vary", "delta=0.01:0.02:2"] if command == "sweep" else []
        args = [command, shear, *extra, "-o", folder / "t.csv"]
    status, _, err = main_cli(*args)
    assert status == 2 and err.count("\n") == 1 and "is a symbolic link: flyopt writes the files it names" in err, err
    assert outside.read_text(encoding="utf-8") == "kept"
    assert [p.name for p in folder.iterdir()] == ["energy.png" if command == "plot-all" else "t.csv.json"]


def test_a_link_planted_at_a_diagrams_name_while_it_is_drawn_is_never_followed(tmp_path, main_cli, monkeypatch):
    """The check before the solve left a window: a link put at out/stress.png while the diagrams were drawn had
    the diagram written where it led (exit 0). The move into place checks again and never follows a link."""
    from matplotlib.figure import Figure

    from flyopt.report.plots import PLOTS

    outside = tmp_path / "victim"
    outside.write_text("kept", encoding="utf-8")
    folder = tmp_path / "out"
    folder.mkdir()
    real = Figure.savefig

    def planting(self, *args, **kwargs):  # the first diagram drawn: a link at every name, after the checks
        for name in PLOTS:
            link = folder / f"{name}.png"
            if not os.path.lexists(link):
                link.symlink_to(outside)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", planting)
    status, _, err = main_cli("plot", PROBLEMS / "shear-press.toml", "--what", "all", "-o", f"{folder}/")
    assert status == 2 and err.count("\n") == 1 and "is a symbolic link" in err, err
    assert outside.read_text(encoding="utf-8") == "kept"
    assert all(p.is_symlink() for p in folder.iterdir())  # no temporary left, nothing written through a link
