"""Tests of flyopt.studies.parts: a resume checks each part on disk and computes a damaged one again.

Temporary files a kill left in the parts folder are removed; a part that
cannot be read, holds another chunk or lacks rows is said on stderr in one
line and computed again, and the file equals an uninterrupted run's.
"""

import subprocess
import sys

import pandas as pd
import pytest
from test_runner import PUNCH, VARY

from flyopt.outputs.results import read_results
from flyopt.studies.sweep import sweep


def test_resume_removes_temporary_files_a_kill_left_in_the_parts(tmp_path):
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=2)
    parts = tmp_path / "study.parquet.parts"
    (parts / "study.parquet.tmp-99999").write_bytes(b"PAR1 half a file")
    (parts / "chunk-00002.parquet.tmp-99999").write_bytes(b"PAR1")
    sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.parquet"]


def truncate(path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def other_chunk(path):
    path.write_bytes(path.with_name("chunk-00000.parquet").read_bytes())


def empty(path):
    path.write_bytes(b"")


def _edited(column, value, where=None):
    """A damage: the part's ``column`` set to ``value`` (in the rows ``where`` selects), written back with its
    metadata as flyopt writes a part."""

    def edit(path):
        from flyopt.outputs.results import write_results

        frame = read_results(path)
        rows = where(frame) if where is not None else slice(None)
        frame.loc[rows, column] = value
        write_results(frame, path, metadata=frame.attrs.get("flyopt"))

    edit.__name__ = f"{column}={value}"
    return edit


def _designed(frame):
    return frame["status"] == "designed"


@pytest.mark.parametrize(
    "damage, words",
    [
        (truncate, "cannot be read"),
        (empty, "cannot be read"),
        (other_chunk, "holds other points than its chunk"),
        # a part edited by hand was copied into the output as it was, exit 0
        (_edited("delta", 99.0), "holds other values of 'delta' than its chunk's points"),
        (_edited("mass", -5.0, _designed), "holds a designed point without a finite, positive mass"),
        (_edited("mass", float("nan"), _designed), "holds a designed point without a finite, positive mass"),
    ],
)
def test_resume_recomputes_a_damaged_part(tmp_path, capsys, damage, words):
    """Regression (issue 11): a truncated part file crashed --resume (pyarrow's error).
    Each part is read back and checked against its chunk; a damaged one is said in one
    line on stderr and computed again, never used."""
    out = tmp_path / "study.parquet"
    whole = sweep(PUNCH, VARY, chunk_size=4)
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=3)
    damage(tmp_path / "study.parquet.parts" / "chunk-00001.parquet")
    capsys.readouterr()
    done = sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "chunk-00001.parquet: " in err and words in err
    assert "computing chunk 1 again" in err
    assert done.attrs["sweep"]["chunks_reused"] == [0, 2]
    assert done.attrs["sweep"]["chunks_run"] == [1, 3, 4]
    pd.testing.assert_frame_equal(read_results(out), whole)


def test_part_with_missing_rows_is_recomputed(tmp_path, capsys):
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=2)
    part = tmp_path / "study.parquet.parts" / "chunk-00001.parquet"
    read_results(part).iloc[:3].to_parquet(part, index=False)
    sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert "holds 3 rows, not the chunk's 4" in capsys.readouterr().err
    pd.testing.assert_frame_equal(read_results(out), sweep(PUNCH, VARY, chunk_size=4))


def test_a_second_sweep_of_a_running_sweeps_output_is_refused_naming_its_process(tmp_path):
    """Issue 25, item 10: two sweeps to one output were not locked out; the second was told to
    --resume a sweep still running, and if it did it failed on a bare chunk path. The parts folder
    is held by the running sweep (flock): a second sweep, resumed or not, is refused and told whose
    it is; once the first has stopped, --resume takes it."""
    import os

    from flyopt.studies.parts import Parts

    out = tmp_path / "study.parquet"
    first = Parts(out)
    record = {"fingerprint": "f"}
    assert first.open(record, [], resume=False) == []
    script = (
        "import sys\n"
        "from flyopt.errors import SceneError\n"
        "from flyopt.studies.parts import Parts\n"
        "try:\n"
        f"    Parts({str(out)!r}).open({{'fingerprint': 'f'}}, [], resume=sys.argv[1] == 'resume')\n"
        "except SceneError as err:\n"
        "    print(err)\n"
        "else:\n"
        "    print('taken')\n"
    )
    for mode in ("new", "resume"):
        run = subprocess.run([sys.executable, "-c", script, mode], capture_output=True, text=True, timeout=60)
        assert f"is being written by the sweep of process {os.getpid()}, still running" in run.stdout, run
    first.release()
    run = subprocess.run([sys.executable, "-c", script, "resume"], capture_output=True, text=True, timeout=60)
    assert run.stdout.strip() == "taken", run


def test_a_sweep_to_an_output_that_is_not_a_regular_file_makes_nothing(tmp_path):
    """A FIFO at a sweep's output was refused only after the parts folder was made (and the layout
    analysed): the folder stayed, and the next run was told to resume it. The output is checked first."""
    import os

    from flyopt.errors import SceneError

    out = tmp_path / "study.csv"
    os.mkfifo(out)
    with pytest.raises(SceneError, match="is a FIFO"):
        sweep(PUNCH, VARY, output=out, chunk_size=4)
    assert [p.name for p in tmp_path.iterdir()] == ["study.csv"]


def test_a_link_planted_at_the_lock_is_never_followed(tmp_path):
    # the lock was opened with O_CREAT and truncated: a link at its name emptied the file it points at
    from flyopt.errors import SceneError
    from flyopt.studies.parts import Parts

    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    parts = Parts(tmp_path / "study.parquet")
    parts.folder.mkdir()
    (parts.folder / Parts.LOCK).symlink_to(victim)
    with pytest.raises(SceneError, match="lock"):
        parts.lock()
    assert victim.read_text() == "keep me"


def test_a_parts_folder_that_is_a_link_is_refused_and_nothing_outside_is_touched(tmp_path):
    """OUTPUT.parts as a symbolic link: the sweep wrote its lock where it led (emptying a file there) and, on a
    resume, removed what it took for its temporaries there. Refused now, in one line, before anything is written."""
    from flyopt.errors import SceneError

    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "lock").write_text("a file of the user's")
    (outside / "thesis.tmp-final").write_text("keep me")
    (tmp_path / "study.parquet.parts").symlink_to(outside)
    for resume in (False, True):
        with pytest.raises(SceneError, match="is a symbolic link: the sweep keeps its finished chunks"):
            sweep(PUNCH, VARY, chunk_size=4, output=tmp_path / "study.parquet", resume=resume)
    assert (outside / "lock").read_text() == "a file of the user's"
    assert sorted(p.name for p in outside.iterdir()) == ["lock", "thesis.tmp-final"]
    assert not (tmp_path / "study.parquet").exists()


def test_a_resume_removes_its_own_temporaries_alone_and_no_link_at_a_part(tmp_path, capsys):
    """In a real parts folder: a file merely named like a temporary is kept; a link planted at a chunk's name is
    removed (not followed: the chunk is written in the folder), and the file equals an uninterrupted run's."""
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=1)
    parts = tmp_path / "study.parquet.parts"
    (parts / "notes.tmp-final").write_text("the user's")
    target = tmp_path / "elsewhere.parquet"
    (parts / "chunk-00002.parquet").symlink_to(target)
    sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True, keep_parts=True)
    assert not target.exists()
    assert (parts / "notes.tmp-final").read_text() == "the user's"
    assert "chunk-00002.parquet: a symbolic link, not a part" in capsys.readouterr().err
    pd.testing.assert_frame_equal(read_results(out), sweep(PUNCH, VARY, chunk_size=4))


def test_a_manifest_that_is_no_file_is_refused_not_read(tmp_path):
    """--resume reads the manifest as any input: a FIFO at its name is refused at once (it blocked forever)."""
    import os

    from flyopt.errors import SceneError

    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=1)
    manifest = tmp_path / "study.parquet.parts" / "sweep.json"
    manifest.unlink()
    os.mkfifo(manifest)
    with pytest.raises(SceneError, match="manifest .* not a regular file but a FIFO"):
        sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)


@pytest.mark.parametrize(
    "key, value, words",
    [
        ("seed", "x", "its seed must be a whole number from 0 to 9223372036854775807, got 'x'"),
        ("seed", -5, "its seed must be a whole number from 0 to 9223372036854775807, got -5"),
        ("seed", 2**63, "its seed must be a whole number from 0 to 9223372036854775807, got 9223372036854775808"),
        ("chunk_size", 0, "its chunk_size must be a whole number >= 1, got 0"),
        ("chunk_size", [1], "its chunk_size must be a whole number >= 1, got [1]"),
    ],
)
def test_a_damaged_manifest_is_refused_naming_it_not_read_as_the_users_options(tmp_path, key, value, words):
    """The manifest's seed and chunk size are used to lay the sweep out before its fingerprint is compared: a
    seed of "x" was refused as the user's own `--seed` (which they never gave), a chunk size of 0 ended in
    "range() arg 3 must not be zero". Both are held to what the options allow, the manifest named."""
    import json

    from flyopt.errors import SceneError

    out = tmp_path / "study.parquet"
    sweep(PUNCH, {"delta": "0.02:0.2"}, samples=4, seed=3, chunk_size=2, output=out, max_chunks=1)
    manifest = tmp_path / "study.parquet.parts" / "sweep.json"
    record = json.loads(manifest.read_text(encoding="utf-8"))
    record[key] = value
    manifest.write_text(json.dumps(record), encoding="utf-8")
    with pytest.raises(SceneError) as refusal:
        sweep(PUNCH, {"delta": "0.02:0.2"}, samples=4, output=out, resume=True)
    assert refusal.value.field == "--resume" and "manifest" in refusal.value.message, refusal.value
    assert words in refusal.value.message and "delete the folder" in refusal.value.message


def test_parts_another_flyopt_version_computed_are_not_reused(tmp_path, monkeypatch):
    """A resume after an upgrade would have put the old version's designs beside the new one's in one table."""
    import flyopt
    from flyopt.errors import SceneError

    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=1)
    monkeypatch.setattr(flyopt, "__version__", flyopt.__version__ + ".post1", raising=False)
    with pytest.raises(SceneError, match="come from a different sweep"):
        sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    monkeypatch.undo()
    done = sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)  # the same version: resumed
    assert len(done) == len(sweep(PUNCH, VARY))


@pytest.mark.parametrize(
    "text",
    ["[" * 200_000 + "]" * 200_000, '{"a":' * 200_000 + "1" + "}" * 200_000, "not json", "[1, 2]", ""],
    ids=["arrays-deep", "objects-deep", "not-json", "an-array", "empty"],
)
def test_a_manifest_that_is_no_json_object_is_refused_naming_it(tmp_path, text):
    """A manifest nested 200,000 deep ended `--resume` in a RecursionError traceback; one that was not JSON
    was called another sweep's. Each is refused as damaged, the manifest and the folder named."""
    from flyopt.errors import SceneError

    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=1)
    manifest = tmp_path / "study.parquet.parts" / "sweep.json"
    manifest.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError) as refusal:
        sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert refusal.value.field == "--resume", refusal.value
    assert refusal.value.message == (
        f"the sweep's manifest {str(manifest)!r} is damaged: not a JSON object as flyopt writes it; "
        f"delete the folder {str(manifest.parent)!r} to start over"
    )


def test_a_folder_where_a_part_belongs_is_refused_in_one_line_and_kept(tmp_path, capsys):
    """It was said to be computed again, then every resume failed on it ("Is a directory")."""
    from flyopt.errors import SceneError

    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=2)
    part = tmp_path / "study.parquet.parts" / "chunk-00001.parquet"
    part.unlink()
    part.mkdir()
    (part / "mine.txt").write_text("the user's", encoding="utf-8")
    capsys.readouterr()
    with pytest.raises(SceneError, match=r"is a folder where chunk 1's part belongs: move it away, then resume"):
        sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert capsys.readouterr().err == ""  # nothing said about computing it again
    assert (part / "mine.txt").read_text(encoding="utf-8") == "the user's" and not out.exists()
