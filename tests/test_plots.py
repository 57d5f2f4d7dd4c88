"""Every diagram renders to a non-empty file (Agg backend); bad requests are one-line errors."""

import pytest

from conftest import PROBLEMS
from flyopt.cli import main
from flyopt.plots import PLOTS

SCENES = ["shear-press", "four-stroke-engine", "compressor", "example1-net-areas"]


@pytest.mark.parametrize("what", sorted(PLOTS))
@pytest.mark.parametrize("scene", SCENES)
def test_every_plot_renders(tmp_path, scene, what, capsys):
    out = tmp_path / f"{scene}-{what}.png"
    status = main(["plot", str(PROBLEMS / f"{scene}.toml"), "--what", what, "-o", str(out)])
    if scene == "example1-net-areas" and what == "speed":
        # a net-area scene has no angles: said in one line, nothing written
        assert status == 2 and not out.exists()
        assert "net-area scene has no angles" in capsys.readouterr().err
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
