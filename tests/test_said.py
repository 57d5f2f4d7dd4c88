"""flyopt.said: a sentence of the design layer that is the string it always was and keeps its quantities, so
that a report fills it in the reader's units (issue 29: units that drift within one output).

References: the conversion factors are the definitions (1 in = 0.0254 m exactly; 1 lb·ft² = 0.45359237 kg ×
0.3048² m²), written here, not read from flyopt.report.display.
"""

import copy
import json
import pickle

import pytest
from conftest import PROBLEMS

from flyopt.report.display import said_text
from flyopt.said import Said, join, said

INCH = 0.0254
LB_FT2 = 0.45359237 * 0.3048**2


def _envelope():
    return said(
        "caps the outer diameter at {d}, where the smallest rim that gives {j} still needs {need}",
        d=(1.2, "length", "1.2 m"),
        j=(863.2, "inertia", "863 kg·m²"),
        need=(1.6, "length", "1.6 m"),
    )


def test_the_string_is_the_sentence_as_written():
    text = _envelope()
    assert text == "caps the outer diameter at 1.2 m, where the smallest rim that gives 863 kg·m² still needs 1.6 m"
    assert isinstance(text, str) and json.dumps({"r": text}) == json.dumps({"r": str(text)})


def test_the_reader_sees_each_quantity_in_his_units():
    shown = said_text(_envelope(), "imperial", 4)
    assert shown == (
        f"caps the outer diameter at {1.2 / INCH:.2f} in, where the smallest rim that gives "
        f"{float(f'{863.2 / LB_FT2:.4g}'):,.0f} lb·ft² still needs {1.6 / INCH:.2f} in"
    )
    assert said_text(_envelope(), "si", 4) == (
        "caps the outer diameter at 1.2 m, where the smallest rim that gives 863.2 kg·m² still needs 1.6 m"
    )
    assert said_text(_envelope(), "engineering", 4) == (
        "caps the outer diameter at 1,200 mm, where the smallest rim that gives 863.2 kg·m² still needs 1,600 mm"
    )
    assert said_text("a plain reason, 3 mm", "imperial", 4) == "a plain reason, 3 mm"


def test_joining_keeps_every_quantity_and_renames_a_clash():
    seat = said("at {d}: ", d=(0.06, "length", "60 mm"))
    whole = "EN-GJL-250 on the crankshaft {braces}: " + seat + _envelope()
    assert isinstance(whole, Said)
    assert str(whole) == "EN-GJL-250 on the crankshaft {braces}: at 60 mm: " + str(_envelope())
    shown = said_text(whole, "imperial", 4)
    assert shown.startswith(f"EN-GJL-250 on the crankshaft {{braces}}: at {0.06 / INCH:.4g} in: caps the outer")
    assert shown.endswith(f"still needs {1.6 / INCH:.2f} in")  # the second "d" renamed, its own value kept
    assert f"{1.2 / INCH:.2f} in" in shown
    joined = join("; ", ["plain", seat, seat])
    assert isinstance(joined, Said) and joined == "plain; at 60 mm: ; at 60 mm: "
    assert said_text(joined, "imperial", 4).count(f"{0.06 / INCH:.4g} in") == 2
    assert type(join("; ", ["a", "b"])) is str


@pytest.mark.parametrize("copied", [lambda s: pickle.loads(pickle.dumps(s)), copy.deepcopy, copy.copy])
def test_a_copy_keeps_its_quantities(copied):
    """A sweep's worker sends its results back pickled; the report reads them."""
    text = copied("Rim: " + _envelope())
    assert isinstance(text, Said) and text == "Rim: " + str(_envelope())
    assert said_text(text, "imperial", 4) == (
        f"Rim: caps the outer diameter at {1.2 / INCH:.2f} in, where the smallest rim that gives "
        f"{float(f'{863.2 / LB_FT2:.4g}'):,.0f} lb·ft² still needs {1.6 / INCH:.2f} in"
    )


def test_an_fstring_gives_the_plain_sentence():
    assert type(f"{_envelope()}") is str


@pytest.mark.parametrize(
    ("words", "given"),
    [
        ("at {d}", {}),
        ("at {d}", {"d": (1.0, "length", "1 m"), "e": (1.0, "length", "1 m")}),
        ("at {d:.3g}", {"d": (1.0, "length", "1 m")}),
        ("at {0}", {}),
    ],
)
def test_a_placeholder_without_its_quantity_is_refused(words, given):
    with pytest.raises(ValueError, match="said"):
        said(words, **given)


def test_a_label_taken_off_keeps_the_quantities():
    """The seat walk quotes a refused combination's reason without its label ("gjs keyed on the shaft: ...")."""
    from flyopt.said import removeprefix

    text = removeprefix("gjs {keyed}: " + _envelope(), "gjs {keyed}: ")
    assert isinstance(text, Said) and text == str(_envelope())
    assert said_text(text, "imperial", 4).startswith(f"caps the outer diameter at {1.2 / INCH:.2f} in")
    assert removeprefix("plain: words", "plain: ") == "words"


def test_a_start_up_that_cannot_begin_says_its_torque_in_the_readers_units():
    """The run-up's refusal (shown as the start-up's note by the text, the report and a drive's refused motor)
    was "the net torque at rest there is -10 N·m" whatever the units; its torque is now read in the system's
    (10 N·m is 7.376 lbf·ft: 10 / (0.3048 × 4.4482216152605), the international foot and pound-force)."""
    import math

    import pytest

    from flyopt.errors import SolverFailed
    from flyopt.report.display import said_text
    from flyopt.said import said_by
    from flyopt.sizing.startup import startup_time

    with pytest.raises(SolverFailed) as caught:
        startup_time(lambda phi, omega: -10.0 + 0 * phi, 2.0, 2 * math.pi, 150.0, 0.0)
    note = said_by(caught.value)
    assert str(note) == str(caught.value)  # the string as written: what the JSON carries
    assert "-10 N·m" in note
    assert "-7.376 lbf·ft" in said_text(note, "imperial")
    assert f"{-10 / (0.3048 * 4.4482216152605):.4g}" == "-7.376"


def test_an_infeasible_drive_lists_whole_reasons_with_their_quantities():
    """The message of a drive no motor size carries lists the refused sizes' reasons up to 2000 characters:
    it was cut there mid-word (and, cut, lost its quantities); now whole reasons, then how many more."""
    from flyopt.drive import codesign
    from flyopt.drive.codesign import MotorRun
    from flyopt.machine.catalogue import CatalogueMotor
    from flyopt.report.display import said_text
    from flyopt.said import said

    runs = []
    for k in range(40):
        motor = CatalogueMotor(
            name=f"M{k}", rated_power=1000.0 + k, rated_speed=150.0, synchronous_speed=157.0, rotor_inertia=0.01,
            breakdown_ratio=2.5, mass=20.0,
        )  # fmt: skip
        reason = said("thermal: its mean torque {t} exceeds its rated torque", t=(28.2, "torque", "28.2 N·m"))
        runs.append(MotorRun(motor=motor, feasible=False, reason=reason, refusal="thermal"))
    text = codesign._refusals(runs, 2000)
    listed = text.split("; and ")[0].split("; ")
    assert len(text) <= 2000 + len("; and 99 more (the table of sizes gives each)")
    assert all(part.startswith(f"M{k}: thermal") and part.endswith("rated torque") for k, part in enumerate(listed))
    assert text.endswith(f"; and {40 - len(listed)} more (the table of sizes gives each)")
    assert said_text(text, "imperial").count("20.8 lbf·ft") == len(listed)
    assert codesign._refusals(runs[:3], 2000) == "; ".join(f"M{k}: " + runs[k].reason for k in range(3))


def test_the_analysis_keeps_a_run_ups_refusal_as_a_sentence(monkeypatch):
    """`flyopt.analysis.startup_run` kept a refused run-up's message by ``str(err)``, which drops its
    quantities: its note is now the sentence itself (the same string), shown in the reader's units."""
    import flyopt
    from flyopt import analysis
    from flyopt.errors import SolverFailed
    from flyopt.machine.reduce import reduce
    from flyopt.report.display import said_text
    from flyopt.said import said
    from flyopt.sizing import startup

    refusal = said("the net torque at rest there is {torque}", torque=(-10.0, "torque", "-10 N·m"))

    def refuse(*args, **kwargs):
        raise SolverFailed(refusal)

    monkeypatch.setattr(startup, "startup_time", refuse)
    monkeypatch.setattr(analysis, "_kloss_runup", lambda *args: None)  # the integration, not the closed form
    machine = reduce(flyopt.load(PROBLEMS / "motor-press.toml"))
    run = analysis.startup_run(machine, 6.0, 1.0)  # a flywheel to run up: the machine is given no inertia
    assert run is not None and run.time is None
    assert run.note == "the net torque at rest there is -10 N·m"
    assert said_text(run.note, "imperial") == "the net torque at rest there is -7.376 lbf·ft"


def test_a_material_name_takes_the_article_it_is_read_with():
    """The report's summary said "A EN-GJS-400-18 wheel …"."""
    from flyopt.said import indefinite

    assert indefinite("EN-GJS-400-18 rim", capital=True) == "An EN-GJS-400-18 rim"
    assert indefinite("cast iron rim", capital=True) == "A cast iron rim"
    assert indefinite("ordinary steel") == "an ordinary steel" and indefinite("unit") == "a unit"
