"""The digest of what a diagram draws (flyopt.report.plots.digest): exact, and the same digest draws the same SVG.

The app keeps a diagram an edit leaves unchanged on the strength of this digest alone (flyopt.app.diagrams), so
both halves are tested: a digest that told two different data apart too seldom would keep a wrong diagram (the
first tests: one ulp, a shape, a type are told apart; what it cannot digest it refuses), and the split plots
must draw from their data alone (the last test: over scenes of every model, the diagrams drawn at two δ are
compared to the byte with their digests: the same where, and only where, the SVGs are the same).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np
import pytest
from conftest import PROBLEMS

from flyopt.report.plots.digest import digest


@dataclass(frozen=True)
class Pair:
    a: float
    b: object = None


@dataclass(frozen=True)
class Other:
    a: float
    b: object = None


def test_equal_data_have_equal_digests_and_a_digest_is_a_hex_string():
    one = digest("turning_moment", Pair(1.5, (np.arange(4.0), "x", None, True, 3)), "si", 4)
    two = digest("turning_moment", Pair(1.5, (np.arange(4.0), "x", None, True, 3)), "si", 4)
    assert one == two and re.fullmatch(r"[0-9a-f]{40}", one)


@pytest.mark.parametrize(
    ("left", "right"),
    [
        (1.0, float(np.nextafter(1.0, 2.0))),  # one ulp
        (0.0, -0.0),  # equal numbers, different bytes: drawn again rather than risked
        (np.array([1.0, 2.0]), np.array([[1.0], [2.0]])),  # the same bytes, another shape
        (np.array([1.0, 2.0]), np.array([1.0, 2.0], dtype=np.float32)),  # another dtype
        (np.array([1, 2]), (1, 2)),  # an array is not a tuple
        (1, 1.0),  # an int is not a float
        (True, 1),  # a bool is not an int
        (0.1, np.float32(0.1)),  # a float32 is not a float, though it prints the same
        (1.5, np.float64(1.5)),  # nor is a numpy scalar a Python float (the data coerce to one)
        ((1.0, 2.0), [1.0, 2.0]),  # a list is not a tuple
        ("", None),
        (("ab", "c"), ("a", "bc")),  # strings end where they end
        ((1.0, (2.0,)), ((1.0, 2.0),)),  # nesting counts
        (Pair(1.0), Other(1.0)),  # a dataclass by its type as well as its fields
        (Pair(1.0, 2.0), Pair(1.0, 2.5)),
    ],
)
def test_different_data_have_different_digests(left, right):
    assert digest(left) != digest(right)


@pytest.mark.parametrize(
    "value", [{"a": 1.0}, {1.0}, np.array(["a"]), np.array([None]), np.str_("a"), np.datetime64(0, "s"), object(), Pair]
)
def test_what_it_cannot_digest_exactly_is_refused(value):
    with pytest.raises(TypeError, match="digest"):
        digest(Pair(1.0, value))


def _delta_scaled(text, factor):
    return re.sub(
        r"(?m)^(delta\s*=\s*)([0-9.eE+-]+)", lambda m: m.group(1) + repr(float(m.group(2)) * factor), text, count=1
    )


def _split_figures(path):
    """(digest, SVG) of each diagram of ``path`` drawn by a split plot (a Figure block with a digest)."""
    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.html import svg_of

    document = build(collect(path), "engineering", figures={"turning_moment", "energy", "inertia_delta", "speed"})
    try:
        return {
            block.key: (block.digest, svg_of(block.figure, block.key))
            for section in document.sections
            for block in section.blocks
            if getattr(block, "digest", "") and block.figure is not None
        }
    finally:
        document.close()


#: Scenes of every model: the energy model (tables, expressions, net areas), the energy–mass model (a mechanism,
#: an engine) and the dynamic one (a motor): δ leaves the first kind's turning-moment and energy diagrams as
#: they are and changes the others' (their speed extremes or periodic solution move with it).
SCENES = [
    "shear-press",
    "compressor",
    "example1-net-areas",
    "slider-crank-press",
    "four-cylinder-engine",
    "motor-press",
]


def test_the_same_digest_draws_the_same_svg_and_a_different_one_a_different_svg(tmp_path):
    same = differ = 0
    for name in SCENES:
        text = (PROBLEMS / f"{name}.toml").read_text(encoding="utf-8")
        drawn = []
        for factor in (1.0, 0.8):
            path = tmp_path / f"{name}-{factor}.toml"
            path.write_text(_delta_scaled(text, factor), encoding="utf-8")
            drawn.append(_split_figures(path))
        assert {"turning_moment", "energy"} <= drawn[0].keys() == drawn[1].keys(), name
        for key, (first, svg) in drawn[0].items():
            second, other = drawn[1][key]
            assert (first == second) == (svg == other), f"{name}: {key}"
            same += first == second
            differ += first != second
    assert same >= 6 and differ >= 6  # both cases met, or the test would prove nothing


@pytest.mark.parametrize("name", ["plot_turning_moment", "plot_energy", "plot_inertia_delta", "plot_speed"])
def test_a_split_plot_says_a_wrong_unit_system_first_as_before(name):
    """The plot_* functions read their data, then draw: a wrong unit system is still said before anything about
    the data (plot_speed of an energy-model scene without its ω(φ) said that instead after the split)."""
    import flyopt
    from flyopt.io.scene import load
    from flyopt.report import plots

    scene = load(PROBLEMS / "shear-press.toml")
    with pytest.raises(ValueError, match="unit system"):
        getattr(plots, name)(scene, flyopt.analyse(scene), units="bogus")
