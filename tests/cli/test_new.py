"""flyopt new KIND: commented template scenes that load, solve and validate against the scene schema."""

import os
import subprocess
import sys

import pytest
from conftest import ROOT

from flyopt.cli.new import TEMPLATES, template
from flyopt.cli.scene_schema import schema, structural_errors

KINDS = sorted(TEMPLATES)


def test_every_template_file_is_a_kind_and_every_kind_has_its_file():
    files = sorted(p.stem for p in (ROOT / "src" / "flyopt" / "data" / "templates").glob("*.toml"))
    assert files == KINDS == ["engine", "motor", "press", "wheel"]


@pytest.mark.parametrize("kind", KINDS)
def test_a_template_is_written_and_solves(main_cli, tmp_path, kind):
    path = tmp_path / f"{kind}.toml"
    status, out, err = main_cli("new", kind, "-o", path)
    assert (status, out, err) == (0, f"wrote {path}\n", "")
    assert path.read_text(encoding="utf-8") == template(kind)
    assert template(kind).lstrip().startswith("#")  # commented for who edits it
    status, out, err = main_cli("solve", path)
    assert status == 0, err
    assert "Flywheel design" in out  # a design, not only an analysis
    status, out, err = main_cli("check", path)
    assert status == 0 and "ok" in out, err


@pytest.mark.parametrize("kind", KINDS)
def test_a_template_validates_against_the_schema(kind):
    jsonschema = pytest.importorskip("jsonschema")
    from flyopt._toml import tomllib

    document = tomllib.loads(template(kind))
    assert list(jsonschema.Draft202012Validator(schema()).iter_errors(document)) == []
    assert structural_errors(document) == []


def test_without_o_the_template_goes_to_stdout(main_cli):
    status, out, err = main_cli("new", "press")
    assert (status, err) == (0, "") and out == template("press")


def test_an_existing_file_is_kept_unless_force(main_cli, tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text("mine", encoding="utf-8")
    status, out, err = main_cli("new", "wheel", "-o", path)
    assert status == 2 and out == "" and path.read_text(encoding="utf-8") == "mine"
    assert (
        err == f"flyopt: error: -o/--output: {str(path)!r} exists: pass --force to replace it, or name another file\n"
    )
    status, out, err = main_cli("new", "wheel", "-o", path, "--force", "--quiet")
    assert (status, out, err) == (0, "", "") and path.read_text(encoding="utf-8") == template("wheel")


def test_a_missing_folder_is_refused_before_anything_is_written(main_cli, tmp_path):
    path = tmp_path / "no" / "scene.toml"
    status, out, err = main_cli("new", "engine", "-o", path)
    assert status == 2 and "does not exist" in err and not path.parent.exists()


def test_a_folder_in_the_way_is_refused(main_cli, tmp_path):
    status, out, err = main_cli("new", "engine", "-o", tmp_path, "--force")
    assert status == 2 and "-o/--output" in err and tmp_path.is_dir()


def test_an_unknown_kind_is_refused_in_one_line():
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "new", "pres"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
        timeout=60,
    )
    assert run.returncode == 2 and run.stdout == "" and len(run.stderr.splitlines()) == 1
    assert "invalid choice: 'pres'" in run.stderr
