"""Shared test helpers."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"


@pytest.fixture
def main_cli(capsys):
    """flyopt's command line in this process: call(*args) -> (exit status, stdout, stderr)."""
    from flyopt.cli.main import main

    def call(*args):
        status = main([str(a) for a in args])
        out, err = capsys.readouterr()
        return status, out, err

    return call


@pytest.fixture
def write_scene(tmp_path):
    """Write a scene text to a file and return its path."""

    def write(text, name="scene.toml"):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


def assert_published(actual, published):
    """Check a computed value against a figure as printed in a source.

    ``published`` is the printed text, e.g. "0.8223" or "72.65": the value
    must round to it, i.e. lie within half a unit of its last printed digit.
    """
    from decimal import Decimal

    figure = Decimal(published)
    half_unit = Decimal(1).scaleb(figure.as_tuple().exponent) / 2
    assert abs(Decimal(repr(float(actual))) - figure) <= half_unit, (
        f"{actual!r} does not round to the published {published} (±{half_unit})"
    )


def names_field(line, path, field):
    """Whether a refusal's line names the scene file and the field: ``flyopt: error: FILE: field: ...``
    as every command says it, or ``FILE:LINE: field: ...`` as ``flyopt check`` places it on its line."""
    import re

    if line.startswith(f"flyopt: error: {path}: {field}: "):
        return True
    return re.match(rf"{re.escape(str(path))}:\d+: {re.escape(field)}: ", line) is not None
