"""A figure's ticks found once per place of its axes, and its texts laid out once per font and size, while it is
drawn (flyopt.report.plots.standard.settled_ticks and settled_texts).

The reference is matplotlib's own path, which finds every axis' ticks and lays out every text each time
anything asks for them: the figures of the shipped scenes are drawn both ways and must be the same to the byte
(SVG and PDF), and the searches and layouts must be fewer, or the test would pass with the memory never used.
"""

import contextlib
import io

import pytest
from conftest import PROBLEMS

from flyopt.report.plots import standard

#: Scenes whose diagrams between them take every kind of axes the report draws: two y axes on one x
#: (turning moment), a shared axis (J_F–δ, speed), stresses, the wheel's section and drawing, a shaft's moments
#: and a Campbell diagram, an engine's indicator diagram, a mechanism's.
SCENES = ["shear-press", "punch-press-wheel", "punch-press-shaft", "four-cylinder-engine", "slider-crank-press"]


def matplotlibs_own(patch):
    """Draw as matplotlib draws: every tick found and every text laid out each time it is asked for."""
    patch.setattr(standard, "settled_ticks", lambda figure: contextlib.nullcontext())
    patch.setattr(standard, "settled_texts", contextlib.nullcontext)


def _figures(scene):
    """The report's figures of ``scene`` (open matplotlib Figures, by key)."""
    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Figure

    document = build(collect(scene), "engineering", figures=True)
    return document, {
        b.key: b.figure
        for section in document.sections
        for b in section.blocks
        if isinstance(b, Figure) and b.figure is not None
    }


def _drawn(scene, settled, kind="svg"):
    """Each figure of ``scene``'s report as SVG (the app's and the HTML report's path) or PDF bytes, with or
    without the ticks settled (the figures made and laid out the same way)."""
    from flyopt.report.html import svg_of

    patch = pytest.MonkeyPatch()
    if not settled:
        matplotlibs_own(patch)
    try:
        document, figures = _figures(scene)
        out = {}
        for key, figure in figures.items():
            if kind == "svg":
                out[key] = svg_of(figure, key)
            else:
                buffer = io.BytesIO()
                figure.savefig(buffer, format="pdf", metadata={"CreationDate": None, "ModDate": None})
                out[key] = buffer.getvalue()
        document.close()
        return out
    finally:
        patch.undo()


@pytest.mark.parametrize("scene", SCENES)
def test_every_svg_the_same_to_the_byte(scene):
    settled = _drawn(PROBLEMS / f"{scene}.toml", True)
    reference = _drawn(PROBLEMS / f"{scene}.toml", False)
    assert settled.keys() == reference.keys() and len(settled) >= 2
    for key in reference:
        assert settled[key] == reference[key], f"{scene}: {key} differs"


def test_pdf_the_same_to_the_byte():
    """savefig (the PDF report's path: a layout draw, then the PDF's own draw) as well."""
    scene = PROBLEMS / "punch-press-shaft.toml"
    assert _drawn(scene, True, "pdf") == _drawn(scene, False, "pdf")


@pytest.mark.slow
@pytest.mark.parametrize(
    "scene",
    sorted(p.relative_to(PROBLEMS).as_posix() for p in [*PROBLEMS.glob("*.toml"), *PROBLEMS.glob("textbook/*.toml")]),
)
def test_every_shipped_scene_the_same(scene):
    assert _drawn(PROBLEMS / scene, True) == _drawn(PROBLEMS / scene, False)


def _asks(monkeypatch, owner, name, text_as_text=False):
    """How many times ``owner.name`` (a method of matplotlib's) runs while shear-press's diagrams are drawn,
    settled (True) and as matplotlib draws them (False)."""
    from flyopt.report.html import svg_of

    ran = [0]
    original = getattr(owner, name)

    def counted(*args):
        ran[0] += 1
        return original(*args)

    monkeypatch.setattr(owner, name, counted)
    counts = {}
    for settled in (True, False):
        with monkeypatch.context() as patch:
            if not settled:
                matplotlibs_own(patch)
            document, figures = _figures(PROBLEMS / "shear-press.toml")
            ran[0] = 0
            for key, figure in figures.items():
                svg_of(figure, key, text_as_text=text_as_text)
            counts[settled] = ran[0]
            document.close()
    assert getattr(owner, name) is counted  # put back as it was found
    return counts


def test_ticks_are_found_far_fewer_times(monkeypatch):
    """The memory is used: a draw of shear-press's diagrams finds ticks under half as often as matplotlib's."""
    from matplotlib.axis import Axis

    counts = _asks(monkeypatch, Axis, "_update_ticks")
    assert 0 < counts[True] < counts[False] / 2, counts


def test_a_shared_locator_keeps_matplotlibs_path():
    """Axes sharing an axis share its locator and formatter: those axes are left to matplotlib, and the
    figure draws as matplotlib draws it."""
    from flyopt.report.html import svg_of

    def make():
        figure = standard.new_figure(figsize=(4, 3), layout="constrained")
        top = figure.add_subplot(211)
        bottom = figure.add_subplot(212, sharex=top)
        top.plot([0, 1, 2], [3, 1, 2])
        bottom.plot([0, 1, 2], [1e5, 2e5, 1.5e5])
        return figure, top, bottom

    figure, top, bottom = make()
    seen = {}

    original = standard._remembering

    def spy(axis):
        seen[id(axis)] = True
        return original(axis)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(standard, "_remembering", spy)
        settled = svg_of(figure, "f")
    assert id(top.xaxis) not in seen and id(bottom.xaxis) not in seen  # shared: matplotlib's own
    assert id(top.yaxis) in seen and id(bottom.yaxis) in seen
    standard.close(figure)
    figure, *_ = make()
    with pytest.MonkeyPatch.context() as patch:
        matplotlibs_own(patch)
        reference = svg_of(figure, "f")
    standard.close(figure)
    assert settled == reference
    assert not any("_update_ticks" in vars(axis) for axis in (top.xaxis, top.yaxis, bottom.xaxis, bottom.yaxis))


def test_texts_are_laid_out_far_fewer_times(monkeypatch):
    """The memory is used: a draw of shear-press's diagrams lays its texts out under half as often as matplotlib."""
    from matplotlib.text import Text

    counts = _asks(monkeypatch, Text, "_get_layout", text_as_text=True)
    assert 0 < counts[True] < counts[False] / 2, counts


def test_a_text_changed_between_two_asks_is_laid_out_again():
    """The box follows the text: a label whose words, size or rotation change within the block is measured anew."""
    from flyopt.report.html import svg_of

    figure = standard.new_figure(figsize=(3, 2))
    label = figure.add_subplot().set_xlabel("short")
    renderer = figure.canvas.get_renderer()
    with standard.settled_texts():
        first = label.get_window_extent(renderer).width
        label.set_text("a much longer label")
        longer = label.get_window_extent(renderer).width
        label.set_fontsize(20)
        larger = label.get_window_extent(renderer).width
        label.set_rotation(90)
        turned = label.get_window_extent(renderer)
    assert first < longer < larger and turned.height > turned.width
    svg_of(figure, "f")
    standard.close(figure)


def test_subfigures_axes_are_settled_once_each():
    """A root figure's axes include its subfigures' (matplotlib 3.4+): each is settled once, and draws as
    matplotlib draws it (listed twice, every locator looked shared and none was settled)."""
    from flyopt.report.html import svg_of

    def make():
        figure = standard.new_figure(figsize=(5, 3), layout="constrained")
        for sub, scale in zip(figure.subfigures(1, 2), (1.0, 1e4)):
            sub.add_subplot().plot([0, 1, 2], [scale, 3 * scale, 2 * scale])
        return figure

    figure = make()
    seen = []
    original = standard._remembering

    def spy(axis):
        seen.append(axis)
        return original(axis)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(standard, "_remembering", spy)
        settled = svg_of(figure, "f")
    assert len(seen) == 4 and len(set(map(id, seen))) == 4  # two axes of each of the two subfigures' Axes
    standard.close(figure)
    figure = make()
    with pytest.MonkeyPatch.context() as patch:
        matplotlibs_own(patch)
        reference = svg_of(figure, "f")
    standard.close(figure)
    assert settled == reference
