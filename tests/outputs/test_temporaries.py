"""flyopt.outputs: every temporary file is new, and a CSV and its sidecar go into place together
(issue 25: nothing written where the user did not point).

A temporary was ``NAME.tmp-PID`` opened with ``open(..., "w")``: a link planted at that name
(the PID is easy to guess) was followed and the file it points at overwritten, and a file
there was truncated. Temporaries are now created with ``O_CREAT | O_EXCL | O_NOFOLLOW``
under a random name, and what is renamed into place must still be the file that was created.
"""

import errno
import os
import stat

import pandas as pd
import pytest

from flyopt.errors import OutputError, SceneError
from flyopt.outputs import files
from flyopt.outputs.files import Temporary, replace_atomically, write_text
from flyopt.outputs.results import ResultWriter, read_results, sidecar_path, write_results

FRAME = pd.DataFrame({"delta": [0.02, 0.05], "a_max": [1.5, 2.5]})
METADATA = {"kind": "sweep", "note": "new"}


def _victim(tmp_path):
    """A file outside the output's folder that a planted link points at."""
    victim = tmp_path / "elsewhere" / "victim.txt"
    victim.parent.mkdir()
    victim.write_text("precious\n")
    return victim


def _plant_links(folder, name, victim):
    """Links at the old, predictable temporary names: ``NAME.tmp-PID`` (and a stale PID)."""
    planted = [folder / f"{name}.tmp-{os.getpid()}", folder / f"{name}.tmp-1"]
    for link in planted:
        link.symlink_to(victim)
    return planted


def _writers():
    def text(out):
        write_text(out, "A_max = 1 J")

    def table(out):
        write_results(FRAME, out, metadata=METADATA)

    def streamed(out):
        with ResultWriter(out, metadata=lambda columns: METADATA) as writer:
            writer.append(FRAME)
            writer.close()

    def by_name(out):
        replace_atomically(out, lambda tmp: tmp.write_bytes(b"drawn by name\n"))

    return {
        "text": (text, "out.txt"),
        "csv": (table, "out.csv"),
        "parquet": (table, "out.parquet"),
        "streamed-csv": (streamed, "out.csv"),
        "streamed-parquet": (streamed, "out.parquet"),
        "by-name": (by_name, "out.svg"),
    }


WRITERS = _writers()


@pytest.mark.parametrize("writer", list(WRITERS))
def test_a_link_planted_at_the_temporary_name_is_not_followed(tmp_path, writer):
    write, name = WRITERS[writer]
    victim = _victim(tmp_path)
    folder = tmp_path / "out"
    folder.mkdir()
    planted = _plant_links(folder, name, victim)
    write(folder / name)
    assert victim.read_text() == "precious\n"
    assert all(link.is_symlink() and link.resolve() == victim for link in planted)
    assert (folder / name).is_file() and not (folder / name).is_symlink()
    extra = [sidecar_path(folder / name).name] if name.endswith(".csv") else []
    assert sorted(p.name for p in folder.iterdir()) == sorted([name, *extra, *(p.name for p in planted)])


@pytest.mark.parametrize("planted", ["link", "file", "dangling-link"])
def test_a_temporary_is_created_anew_under_another_name_when_its_name_is_taken(tmp_path, monkeypatch, planted):
    """Even a planted name that the random part hits is left alone: another name is drawn."""
    victim = _victim(tmp_path)
    tokens = iter(["taken", "taken", "free"])
    monkeypatch.setattr(files.secrets, "token_hex", lambda n=None: next(tokens))
    out = tmp_path / "out.txt"
    taken = tmp_path / f"out.txt.tmp-{os.getpid()}-taken"
    if planted == "link":
        taken.symlink_to(victim)
    elif planted == "dangling-link":
        taken.symlink_to(tmp_path / "nowhere" / "new.txt")
    else:
        taken.write_text("someone else's\n")
    write_text(out, "A_max = 1 J")
    assert out.read_text() == "A_max = 1 J\n"
    assert victim.read_text() == "precious\n" and not (tmp_path / "nowhere").exists()
    assert os.path.lexists(taken)
    if planted == "file":
        assert taken.read_text() == "someone else's\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["elsewhere", "out.txt", taken.name])


def test_a_temporary_swapped_for_a_link_while_written_is_not_moved_into_place(tmp_path):
    """A writer that opens the temporary by its name: if the name no longer holds the file
    that was created (here a link put in its place), the output is refused and left as it was."""
    victim = _victim(tmp_path)
    out = tmp_path / "out.svg"
    out.write_text("earlier\n")

    def swap(tmp):
        tmp.unlink()
        tmp.symlink_to(victim)

    with pytest.raises(OutputError, match="was replaced by another while writing") as caught:
        replace_atomically(out, swap)
    assert caught.value.filename == str(out)
    assert out.read_text() == "earlier\n" and not out.is_symlink()
    assert victim.read_text() == "precious\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["elsewhere", "out.svg"]


def test_a_temporary_is_removed_on_any_failure(tmp_path):
    out = tmp_path / "out.svg"
    for error in (RuntimeError("a writer's bug"), KeyboardInterrupt(), OSError(errno.ENOSPC, "No space left")):

        def fail(tmp, error=error):
            tmp.write_bytes(b"half")
            raise error

        with pytest.raises(type(error) if not isinstance(error, OSError) else OutputError):
            replace_atomically(out, fail)
        assert list(tmp_path.iterdir()) == []


def test_a_temporary_that_cannot_be_created_names_the_output(tmp_path):
    out = tmp_path / "out.csv"
    with pytest.raises(OutputError, match="No such file or directory") as caught:
        Temporary(out, tmp_path / "no-such-folder")
    assert caught.value.filename == str(out)


def test_a_temporary_has_a_new_files_permissions(tmp_path):
    """Created as ``open(..., "w")`` creates a file (0666 less the umask), not private like mkstemp's."""
    old = os.umask(0o022)
    try:
        write_text(tmp_path / "out.txt", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "out.txt").stat().st_mode) == 0o644


def test_an_output_with_the_longest_name_has_a_temporary(tmp_path):
    """``NAME.tmp-PID`` was longer than a file name may be for a 250-character NAME."""
    out = tmp_path / ("x" * 246 + ".txt")
    write_text(out, "A_max = 1 J")
    assert out.read_text() == "A_max = 1 J\n" and list(tmp_path.iterdir()) == [out]


# --------------------------------------------------------------------------
# A CSV and its sidecar: both written, then both moved, or neither
# --------------------------------------------------------------------------


def _earlier_pair(folder):
    out = folder / "study.csv"
    write_results(FRAME.iloc[:1], out, metadata={"kind": "sweep", "note": "earlier"})
    return out, out.read_bytes(), sidecar_path(out).read_bytes()


def test_a_csv_refused_at_the_end_leaves_the_earlier_sidecar(tmp_path):
    """A sweep's output that became a folder while the sweep ran: its sidecar had been written
    over the earlier one, then removed with the refusal, so the earlier table lost its metadata.
    Both names are checked before either file moves; the earlier sidecar stays as it was."""
    out, _, side = _earlier_pair(tmp_path)
    parts = tmp_path / "study.csv.parts"
    parts.mkdir()
    writer = ResultWriter(out, temporary_folder=parts, metadata=lambda columns: METADATA)
    writer.append(FRAME)
    out.unlink()
    out.mkdir()  # put there while the sweep ran
    with pytest.raises(SceneError, match="is a folder"):
        writer.close()
    assert sidecar_path(out).read_bytes() == side
    assert out.is_dir() and list(out.iterdir()) == []
    assert list(parts.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.csv", "study.csv.json", "study.csv.parts"]


@pytest.mark.parametrize("blocked", ["table", "sidecar"])
def test_a_csv_or_sidecar_that_cannot_go_into_place_changes_neither(tmp_path, blocked):
    """A device at either name (made here, never the machine's /dev): refused, the other file untouched."""
    if os.geteuid() != 0:
        pytest.fail("making a device node needs root (this test's machine runs as root)")
    out = tmp_path / "study.csv"
    if blocked == "table":
        sidecar_path(out).write_text("earlier sidecar\n")
    else:
        out.write_text("earlier table\n")
    node = out if blocked == "table" else sidecar_path(out)
    os.mknod(node, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    before = {p.name: (p.read_bytes() if p.is_file() else None) for p in tmp_path.iterdir()}
    with pytest.raises(SceneError, match="is a device"):
        write_results(FRAME, out, metadata=METADATA)
    if blocked == "sidecar":  # streamed: refused at the end, after every row was written
        with pytest.raises(SceneError, match="is a device"):
            with ResultWriter(out, metadata=lambda columns: METADATA) as writer:
                writer.append(FRAME)
                writer.close()
    after = {p.name: (p.read_bytes() if p.is_file() else None) for p in tmp_path.iterdir()}
    assert after == before
    assert stat.S_ISCHR(os.lstat(node).st_mode)


@pytest.mark.parametrize("write", ["write_results", "ResultWriter"])
def test_a_table_that_fails_to_move_after_its_sidecar_leaves_no_sidecar(tmp_path, monkeypatch, write):
    """The last rename failing (an I/O error) after the sidecar's: the new sidecar describes a
    table that is not there and is removed; no temporary is left."""
    out = tmp_path / "study.csv"
    real = os.replace

    def fail_on_table(src, dst, **kwargs):
        if os.fspath(dst) == os.fspath(out):
            raise OSError(errno.EIO, os.strerror(errno.EIO), os.fspath(dst))
        return real(src, dst, **kwargs)

    monkeypatch.setattr(os, "replace", fail_on_table)
    with pytest.raises(OutputError, match="Input/output error") as caught:
        if write == "write_results":
            write_results(FRAME, out, metadata=METADATA)
        else:
            with ResultWriter(out, metadata=lambda columns: METADATA) as writer:
                writer.append(FRAME)
                writer.close()
    assert caught.value.filename == str(out)
    assert list(tmp_path.iterdir()) == []


def test_a_csv_and_its_sidecar_are_written_together(tmp_path):
    out, table, side = _earlier_pair(tmp_path)
    write_results(FRAME, out, metadata=METADATA)
    assert out.read_bytes() != table and sidecar_path(out).read_bytes() != side
    back = read_results(out)
    assert back.attrs["flyopt"]["note"] == "new" and len(back) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.csv", "study.csv.json"]


def test_the_pdf_report_and_a_plot_are_written_into_the_handle_of_their_temporary(tmp_path, monkeypatch):
    """The report's PDF and a saved plot go through write_atomically (the file it made, by its handle):
    replace_atomically, which hands a writer the temporary's name to open again, is not used for them."""
    import flyopt.outputs.files as files

    def refuse(*args, **kwargs):
        raise AssertionError("written by the temporary's name")

    monkeypatch.setattr(files, "replace_atomically", refuse)
    from flyopt.cli.main import main

    pdf = tmp_path / "report.pdf"
    png = tmp_path / "torque.png"
    assert main(["report", "problems/shear-press.toml", "-o", str(pdf), "-q"]) == 0
    assert main(["plot", "problems/shear-press.toml", "--what", "turning_moment", "-o", str(png), "-q"]) == 0
    assert pdf.read_bytes().startswith(b"%PDF") and png.read_bytes().startswith(b"\x89PNG")
