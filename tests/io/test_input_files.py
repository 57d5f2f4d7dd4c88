"""The files a scene reads (issue 25, items 3 and 4): inside the scene's folder, regular, within the caps.

A file a scene names (every ``*_file`` field, ``[sweep] output``) is
relative to the scene's folder and may not leave it, even by a symbolic
link; an input is a regular file (no FIFO, device or folder) under a cap of
bytes and rows, checked before reading; a refusal quotes at most 40
characters of a data file. Every refusal is one line, exit status 2, from
``check`` as from ``solve``.
"""

import os
import resource
import subprocess
import sys

import pytest
from conftest import PROBLEMS, ROOT, names_field

import flyopt
from flyopt.errors import SceneError

CANARY = "CANARY-secret-line-of-a-file-outside,0"

SCENE = """
title = "t"
[machine]
speed = "1500 rpm"
delta = 0.05
[torque.resisting]
angle_unit = "deg"
unit = "kN*m"
points_file = {name}
[torque.driving]
constant = "unknown"
"""

GOOD = "angle,torque\n0,1.6\n90,0.2\n360,1.6\n"


def at_most_4_gb():
    """A runaway read (the old reading of /dev/zero) fails at 4 GB instead of filling the machine's memory."""
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))


def cli(*args, env=None, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "flyopt", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=timeout,
        env={**os.environ, **(env or {})},
        preexec_fn=at_most_4_gb,
    )


def scene_naming(tmp_path, name):
    """A scene in ``tmp_path/scene/`` whose resisting torque is read from ``name``; a canary file beside the folder."""
    folder = tmp_path / "scene"
    folder.mkdir(exist_ok=True)
    (tmp_path / "secret.csv").write_text(f"{CANARY}\n", encoding="utf-8")
    (folder / "torque.csv").write_text(GOOD, encoding="utf-8")
    path = folder / "scene.toml"
    path.write_text(SCENE.format(name=f'"{name}"'), encoding="utf-8")
    return path


def refused(path, field, match, env=None, commands=("check", "solve"), timeout=60):
    """Both commands refuse the scene in one line naming it and ``field``, and never quote the canary."""
    for command in commands:
        run = cli(command, path, env=env, timeout=timeout)
        assert run.returncode == 2, (command, run.returncode, run.stderr)
        lines = run.stderr.splitlines()
        assert len(lines) == 1, run.stderr
        assert names_field(lines[0], path, field), lines[0]
        assert match in lines[0], lines[0]
        assert "CANARY" not in run.stderr + run.stdout


@pytest.mark.parametrize(
    "name, match",
    [
        ("{outside}", "is not relative to the scene file's folder"),
        ("../secret.csv", "leads outside the scene file's folder"),
        ("./../scene/../secret.csv", "leads outside the scene file's folder"),
        ("~/secret.csv", "is not relative to the scene file's folder"),
    ],
)
def test_a_points_file_outside_the_scene_folder_is_refused(tmp_path, name, match):
    path = scene_naming(tmp_path, name.format(outside=tmp_path / "secret.csv"))
    refused(path, "torque.resisting.points_file", match)


def test_a_symbolic_link_out_of_the_folder_is_refused_and_one_inside_is_followed(tmp_path):
    path = scene_naming(tmp_path, "link.csv")
    (path.parent / "link.csv").symlink_to(tmp_path / "secret.csv")
    refused(path, "torque.resisting.points_file", "'link.csv' leads outside the scene file's folder")
    (path.parent / "link.csv").unlink()
    (path.parent / "link.csv").symlink_to(path.parent / "torque.csv")
    assert flyopt.load(path).resisting is not None
    (path.parent / "sub").mkdir()
    assert flyopt.load(scene_naming(tmp_path, "./sub/../torque.csv")).resisting is not None


def test_a_refusal_quotes_at_most_40_characters_of_a_data_file(tmp_path):
    path = scene_naming(tmp_path, "torque.csv")
    (path.parent / "torque.csv").write_text(f"angle,torque\n0,1\n{'7' * 30}{CANARY},2\n360,1\n", encoding="utf-8")
    with pytest.raises(SceneError) as error:
        flyopt.load(path)
    assert "CANARY-secret" not in str(error.value)
    quoted = str(error.value).split("'")[1]
    assert quoted.startswith("7" * 30) and len(quoted) <= 40, quoted
    (path.parent / "torque.csv").write_text(f"angle,torque\n0,1\n90,{'8' * 30}{CANARY}\n360,1\n", encoding="utf-8")
    with pytest.raises(SceneError) as error:
        flyopt.load(path)
    assert "CANARY-secret" not in str(error.value), str(error.value)


@pytest.mark.parametrize("name", ["/etc/passwd", "../p.csv", "/dev/zero"])
def test_an_engine_pressure_file_outside_the_folder_is_refused(tmp_path, name):
    text = (PROBLEMS / "four-cylinder-engine.toml").read_text(encoding="utf-8")
    start = text.index("pressure = [")
    end = text.index("]\n", text.index("[720,")) + 2
    (tmp_path / "p.csv").write_text(f"{CANARY}\n", encoding="utf-8")
    (tmp_path / "scene").mkdir()
    path = tmp_path / "scene" / "scene.toml"
    path.write_text(text[:start] + f'pressure_file = "{name}"\n' + text[end:], encoding="utf-8")
    refused(path, "engine.pressure_file", "the scene file's folder", commands=("check",))


@pytest.mark.parametrize(
    "member",
    [
        'velocity_ratio_file = "/etc/passwd"',
        'angular_ratio_file = "../x.csv"',
        'force_file = "/dev/null"',
        'torque_file = "../../x.csv"',
    ],
)
def test_a_member_file_outside_the_folder_is_refused(tmp_path, member):
    field = member.split(" ")[0]
    path = tmp_path / "scene.toml"
    path.write_text(
        '[machine]\nspeed = "100 rpm"\ndelta = 0.05\n[torque.driving]\nconstant = "unknown"\n'
        '[torque.resisting]\nconstant = "10 N*m"\n'
        f'[[member]]\nname = "m"\nmass = 1\nvelocity_ratio = 0.1\n{member}\n'.replace(
            "velocity_ratio = 0.1\nvelocity_ratio_file", "velocity_ratio_file"
        ),
        encoding="utf-8",
    )
    with pytest.raises(SceneError, match=r"(not relative to|leads outside) the scene file's folder") as error:
        flyopt.load(path)
    assert error.value.field == f"member[0].{field}", str(error.value)


def test_a_motor_table_file_outside_the_folder_is_refused(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(
        '[machine]\nspeed = "100 rpm"\ndelta = 0.05\n[[shaft]]\nname = "motor"\nspeed_ratio = 1\n'
        '[torque.driving]\nmotor = { kind = "table", shaft = "motor", points_file = "/etc/passwd" }\n'
        '[torque.resisting]\nconstant = "10 N*m"\n',
        encoding="utf-8",
    )
    with pytest.raises(SceneError, match="is not relative to the scene file's folder") as error:
        flyopt.load(path)
    assert error.value.field.endswith("points_file"), error.value.field


@pytest.mark.parametrize(  # the parent folder by default; an absolute path and a climbing one in the slow run
    "output",
    [
        "../study.csv",
        pytest.param("{tmp_path}/study.csv", marks=pytest.mark.slow),
        pytest.param("sub/../../study.csv", marks=pytest.mark.slow),
    ],
)
def test_a_sweep_output_outside_the_scene_folder_is_refused_by_check_and_sweep(tmp_path, output):
    folder = tmp_path / "scene"
    folder.mkdir()
    path = folder / "scene.toml"
    text = (PROBLEMS / "example1-net-areas.toml").read_text(encoding="utf-8")
    output = output.format(tmp_path=tmp_path)
    path.write_text(f'{text}\n[sweep]\noutput = "{output}"\n[sweep.vary]\n"machine.delta" = "0.01:0.1:2"\n')
    refused(path, "sweep.output", "the scene file's folder", commands=("check", "sweep"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene"]


@pytest.mark.parametrize("output, said", [("study.csv/", "names a folder"), ("sub/study.parquet/", "names a folder")])
def test_a_sweep_output_that_names_no_file_is_refused_as_on_the_command_line(tmp_path, output, said):
    """An outside audit: [sweep] output = "x.csv/" wrote x.csv and check said ok, where -o x.csv/ is refused."""
    path = tmp_path / "scene.toml"
    text = (PROBLEMS / "example1-net-areas.toml").read_text(encoding="utf-8")
    path.write_text(f'{text}\n[sweep]\noutput = "{output}"\n[sweep.vary]\n"machine.delta" = "0.01:0.1:2"\n')
    refused(path, "sweep.output", said, commands=("check", "sweep"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.toml"]


def test_a_sweep_output_inside_the_folder_is_accepted(tmp_path):
    path = tmp_path / "scene.toml"
    text = (PROBLEMS / "example1-net-areas.toml").read_text(encoding="utf-8")
    path.write_text(f'{text}\n[sweep]\noutput = "out/../study.csv"\n[sweep.vary]\n"machine.delta" = "0.01:0.1:2"\n')
    (tmp_path / "out").mkdir()
    run = cli("check", path)
    assert run.returncode == 0, run.stderr


@pytest.mark.parametrize("kind", ["fifo", "folder", "device"])
def test_a_points_file_that_is_not_a_regular_file_is_refused_at_once(tmp_path, kind):
    path = scene_naming(tmp_path, "special.csv")
    special = path.parent / "special.csv"
    if kind == "fifo":
        os.mkfifo(special)
    elif kind == "folder":
        special.mkdir()
    else:
        special.symlink_to("/dev/zero")  # a link to a device is followed only when inside: refused as outside
        refused(path, "torque.resisting.points_file", "'special.csv' leads outside", commands=("check",), timeout=30)
        return
    refused(path, "torque.resisting.points_file", "(allowed: a regular file)", commands=("check",), timeout=30)


def test_the_scene_file_itself_must_be_a_regular_file(tmp_path):
    for special in ("/dev/zero", "/dev/urandom"):
        run = cli("check", special, timeout=30)
        assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
        assert "not a regular file but a device" in run.stderr
    fifo = tmp_path / "scene.toml"
    os.mkfifo(fifo)
    run = cli("check", fifo, timeout=30)
    assert run.returncode == 2 and "not a regular file but a FIFO" in run.stderr, run.stderr


def test_a_command_line_scene_may_be_anywhere_and_name_files_beside_it(tmp_path):
    path = scene_naming(tmp_path, "torque.csv")
    run = cli("check", os.path.relpath(path, ROOT))
    assert run.returncode == 0, run.stderr


def test_the_size_caps_are_checked_before_reading_and_raised_by_the_environment(tmp_path, monkeypatch):
    path = scene_naming(tmp_path, "torque.csv")
    (path.parent / "torque.csv").write_text(GOOD + "# " + "x" * 500 + "\n", encoding="utf-8")
    monkeypatch.setenv("FLYOPT_MAX_FILE_BYTES", "400")
    with pytest.raises(
        SceneError, match=r"cannot read .*torque\.csv: \d+ bytes, over the limit of 400 .*FLYOPT_MAX_FILE"
    ):
        flyopt.load(path)
    monkeypatch.setenv("FLYOPT_MAX_FILE_BYTES", "100")  # the scene file itself
    with pytest.raises(SceneError, match=r"cannot read the file: \d+ bytes, over the limit of 100 ") as error:
        flyopt.load(path)
    assert error.value.source == str(path)
    monkeypatch.setenv("FLYOPT_MAX_FILE_BYTES", "1000")
    assert flyopt.load(path).resisting is not None
    monkeypatch.delenv("FLYOPT_MAX_FILE_BYTES")
    from flyopt.io import input_files

    assert input_files.max_file_bytes() == input_files.MAX_FILE_BYTES == 100_000_000
    assert input_files.max_table_rows() == input_files.MAX_TABLE_ROWS == 2_000_000


def test_the_row_cap_holds_for_csv_and_inline_tables(tmp_path, monkeypatch):
    path = scene_naming(tmp_path, "torque.csv")
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "2")  # GOOD: a header and 3 rows
    with pytest.raises(SceneError, match=r"has over 2 rows \(allowed: at most 2; .*FLYOPT_MAX_TABLE_ROWS"):
        flyopt.load(path)
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "3")  # the header is no row (its line was counted as one)
    assert len(flyopt.load(path).resisting.values) == 3
    inline = tmp_path / "inline.toml"
    rows = ", ".join(f"[{a}, 1]" for a in range(0, 361, 1))
    inline.write_text(SCENE.replace("points_file = {name}", f"points = [{rows}]"), encoding="utf-8")
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "360")
    with pytest.raises(SceneError, match="has over 360 rows") as error:
        flyopt.load(inline)
    assert error.value.field == "torque.resisting.points"
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "361")
    assert flyopt.load(inline).resisting is not None


def test_a_bad_limit_in_the_environment_is_one_line(tmp_path):
    path = scene_naming(tmp_path, "torque.csv")
    run = cli("check", path, env={"FLYOPT_MAX_FILE_BYTES": "lots"})
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert "FLYOPT_MAX_FILE_BYTES must be a whole number of at least 1, got 'lots'" in run.stderr


def test_a_cap_beyond_any_file_reads_every_file(tmp_path, monkeypatch):
    """FLYOPT_MAX_FILE_BYTES=1e29 written out (or any cap past sys.maxsize) overflowed the read: "cannot fit 'int'
    into an index-sized integer", exit 1 blaming the scene. A cap is at most sys.maxsize - 1, and the read takes
    the file's own size, not the cap's (a read of the cap reserved it: 100 MB by default, for every file)."""
    import sys

    from flyopt.io import input_files

    path = scene_naming(tmp_path, "torque.csv")
    for variable in ("FLYOPT_MAX_FILE_BYTES", "FLYOPT_MAX_TABLE_ROWS"):
        monkeypatch.setenv(variable, "1" + "0" * 29)
    assert input_files.max_file_bytes() == input_files.max_table_rows() == sys.maxsize - 1
    assert flyopt.load(path).resisting is not None
    assert input_files.read_input(path, "", "the scene") == path.read_text(encoding="utf-8")
