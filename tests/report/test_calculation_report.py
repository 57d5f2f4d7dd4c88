"""``flyopt report`` of a scene that is one calculation ([operation], [position] in both forms, [electric_drive],
[power_chain]): a report of its own, the given data, the method with the numbers substituted and the answers.

Every calculation scene of problems/textbook/ is rendered through the command line and read back with the
standard library's HTML parser (the reader of tests/report/test_document.py), then checked against what does
not come from the report's code:

- structure: the page parses with every element closed, its sections are the answer, the given data, the
  method and the provenance, the title block names the scene file, the date, flyopt's version, the units
  and the calculation, and there is no diagram (it has no cycle) and no warning;
- the numbers: every quantity of the answer carries a value of the same name in the calculation's own
  result, as ``flyopt solve --json`` writes it (one path: nothing recomputed);
- the worked steps: every equation's substituted numbers, evaluated here by Python's arithmetic, give
  the result it shows, to the digits shown.
"""

import json
import math
import re

import pytest
from conftest import ROOT, run_flyopt
from test_document import Page

TEXTBOOK = ROOT / "problems" / "textbook"
SCENES = sorted(
    p.stem
    for p in TEXTBOOK.glob("*.toml")
    if re.search(r"^\[(operation|position|electric_drive|power_chain)\]", p.read_text(encoding="utf-8"), re.M)
)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("calculation-reports")


_RENDERED = {}


def render(scene, folder, suffix="html", units="engineering"):
    """``flyopt report`` in this process: (status, path, stderr)."""
    key = (scene, suffix, units)
    if key not in _RENDERED:
        import contextlib
        import io

        from flyopt.cli.main import main

        out = folder / f"{scene}-{units}.{suffix}"
        err = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            status = main(["report", str(TEXTBOOK / f"{scene}.toml"), "-o", str(out), "--units", units])
        _RENDERED[key] = (status, out, err.getvalue())
    return _RENDERED[key]


def test_the_calculation_scenes_are_found():
    assert len(SCENES) >= 9, SCENES


@pytest.mark.parametrize("scene", SCENES)
def test_a_calculation_is_reported_whole(scene, folder):
    import flyopt

    status, out, err = render(scene, folder)
    assert status == 0 and err == "", err
    page = Page(out.read_text(encoding="utf-8"))
    assert page.errors == []
    # the method's sections of the notes follow as Appendix A (tests/report/test_method.py)
    assert page.sections[:5] == ["summary", "scene", "steps", "provenance", "appendix"]
    assert all(key.startswith("notes-") for key in page.sections[5:]) and page.sections[5:]
    assert page.figures == {}
    block = page.title_block
    assert block["scene file"].endswith(f"{scene}.toml")
    assert block["flyopt version"] == flyopt.__version__
    assert block["units"].startswith("engineering")
    assert block["calculation"].startswith("[")
    assert block["status"] == "calculated"
    assert page.equations, "the method shows its formulas"
    assert all(re.fullmatch(r"Appendix A\.\d+", e["ref"]) for e in page.equations)
    assert {f"notes-{e['ref'].rsplit('.', 1)[1]}" for e in page.equations} <= set(page.sections)


def _json_values(scene):
    """name -> every value of that name anywhere in ``flyopt solve --json`` of the scene."""
    run = run_flyopt("solve", "--json", TEXTBOOK / f"{scene}.toml")
    assert run.returncode == 0, run.stderr
    found = {}

    def walk(value, name=None):
        if isinstance(value, dict):
            for key, item in value.items():
                walk(item, key)
        elif isinstance(value, list):
            for item in value:
                walk(item, name)
        elif isinstance(value, (int, float)) and not isinstance(value, bool) and name is not None:
            found.setdefault(name, []).append(float(value))

    walk(json.loads(run.stdout))
    return found


@pytest.mark.parametrize("scene", SCENES)
def test_the_answers_are_the_calculations_own(scene, folder):
    _, out, _ = render(scene, folder)
    page = Page(out.read_text(encoding="utf-8"))
    values = _json_values(scene)
    named = [q for q in page.quantities if q["section"] == "summary" and q["name"] and q["si"] is not None]
    assert named, "the answer names its quantities"
    for q in named:
        shown = float(q["si"])
        assert any(math.isclose(shown, v, rel_tol=1e-12, abs_tol=1e-300) for v in values.get(q["name"], [])), (
            q,
            values.get(q["name"]),
        )


#: Units as the equations write them, longest first (removed before the arithmetic).
_UNITS = sorted(
    ["rad/s²", "rad/s", "kg·m²", "N·m²", "N·m", "m/s²", "m/s", "m/rad", "kg", "Pa", "W", "J", "N", "s", "m"],
    key=len,
    reverse=True,
)


def _arithmetic(text):
    """A substituted line of the report as a Python expression: ×, −, ², √, π, °, sin/cos/tan/asin."""
    text = re.sub(r"(?<=\d),(?=\d{3})", "", text)  # thousands, not an argument's comma
    text = re.sub(r"\[[^\]\d]*\]", "", text)  # "[N·m²]": the unit of a whole line
    text = text.replace("[", "(").replace("]", ")")
    for unit in _UNITS:
        text = re.sub(rf"(?<=[\d)\s]){re.escape(unit)}(?![\w²])", " ", text)
    text = text.replace("^{3/2}", "**1.5").replace("^{", "**(").replace("}", ")")
    # a function applied without brackets to one angle: "sin² 60°", "cos 2×60°", "tan 12.5°"
    text = re.sub(
        r"(sin|cos|tan)([²⁴]?) ((?:2×)?[\d.]+°)",
        lambda m: f"{m[1]}({m[3]}){'**2' if m[2] == '²' else '**4' if m[2] == '⁴' else ''}",
        text,
    )
    text = re.sub(r"(?<=\d)π", "*π", text)
    text = text.replace("°", "*pi/180").replace("×", "*").replace("−", "-").replace("π", "pi")
    text = text.replace("√", "sqrt").replace("²", "**2").replace("⁴", "**4").replace("³", "**3")
    return re.sub(
        r"(?<=[\d)])\s+(?=sqrt|sin|cos|tan|asin|\()", " * ", text
    )  # "2 √(...)": a product written as a book writes it


def _value(text):
    return float(re.search(r"-?[\d,]*\.?\d+(?:e[+-]?\d+)?", text)[0].replace(",", ""))


def _check_steps(page):
    """Every equation's substituted numbers, evaluated by Python, give the result it shows (to its digits)."""
    scope = {name: getattr(math, name) for name in ("sin", "cos", "tan", "asin", "sqrt", "pi")} | {"max": max}
    for equation in page.equations:
        numbers = " ".join(equation["num"]).strip().removeprefix("=").strip()
        result = equation["res"].strip().removeprefix("=").strip()
        expression = _arithmetic(numbers)
        value = eval(expression, {"__builtins__": {}}, scope)  # noqa: S307 -- our own report's arithmetic
        if result.split()[0].endswith("°"):  # an angle the step gives in degrees
            value = math.degrees(value)
        shown = _value(result)
        assert math.isclose(value, shown, rel_tol=5e-5, abs_tol=1e-9), (equation["key"], expression, value, result)


@pytest.mark.parametrize("scene", SCENES)
def test_every_worked_step_gives_the_result_it_shows(scene, folder):
    _, out, _ = render(scene, folder)
    _check_steps(Page(out.read_text(encoding="utf-8")))


#: Scenes beside the book's: each branch of a report the textbook scenes do not reach.
VARIANTS = {
    # the motor alone covers the operation (ΔE = max(0, E − P τ) = 0); a wheel on a faster shaft; J_c; machine.delta
    "operation": (
        "khurmi-16-21",
        [
            ('speed = "300 rpm"', 'speed = "300 rpm"\ndelta = 0.2\ninertia = "5 kg*m^2"'),
            ('energy = "10 kJ"', 'energy = "1 kJ"'),
            (
                '[flywheel]\nmass = "150 kg"\nradius_of_gyration = "0.6 m"',
                '[flywheel]\ninertia = "10 kg*m^2"\nshaft = "fast"',
            ),
            ("[operation]", '[[shaft]]\nname = "fast"\nspeed_ratio = 2\n\n[operation]'),
        ],
    ),
    # a vertical engine (m_R g in F_P), its gas force given directly, past the outer half of the stroke
    "crank": (
        "khurmi-15-crank-forces",
        [
            ('angle = "60 deg"', 'angle = "120 deg"\norientation = "vertical"\ngas_force = "10 kN"'),
            ('bore = "0.5 m"', ""),
            ('pressure = "0.35 N/mm^2"', ""),
        ],
    ),
    # reduced to a member that only translates there (an equivalent mass and force at its centre)
    "translating": (
        "seed000-calc7-gear-sine-mechanism-position",
        [('input_angle = "60 deg"', 'input_angle = "60 deg"\nreduce_to = "bar 4"')],
    ),
    # reduced to a member that turns, with no point given
    "turning": (
        "seed000-calc6-guide-bar-position",
        [('reduce_to = "guide-bar 3"', 'reduce_to = "block 2"'), ('force_at = "550 mm"', "")],
    ),
}


@pytest.mark.parametrize(
    # two branches in the default run (4 s each), every branch in the slow run
    "variant",
    [v if v in ("operation", "crank") else pytest.param(v, marks=pytest.mark.slow) for v in sorted(VARIANTS)],
)
def test_every_branch_of_a_report_is_written_and_its_steps_hold(variant, tmp_path):
    base, edits = VARIANTS[variant]
    text = (TEXTBOOK / f"{base}.toml").read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    scene = tmp_path / f"{variant}.toml"
    scene.write_text(text, encoding="utf-8")
    for suffix in ("html", "pdf"):
        run = run_flyopt("report", str(scene), "-o", str(tmp_path / f"out.{suffix}"))
        assert run.returncode == 0 and run.stderr == "", run.stderr
    page = Page((tmp_path / "out.html").read_text(encoding="utf-8"))
    assert page.errors == []
    _check_steps(page)
    keys = {e["key"] for e in page.equations}
    expected = {
        "operation": {"j_at_reference", "inertia", "energy_from_flywheel"},
        "crank": {"piston_effort", "turning_moment"},
        "translating": {"reduced_mass", "reduced_force"},
        "turning": {"reduced_inertia", "reduced_moment"},
    }[variant]
    assert expected <= keys, keys
    if variant == "operation":
        assert "max(0, " in " ".join(e["sym"] for e in page.equations)
    if variant == "crank":
        assert "gas_force" not in keys and any("m_{R} g" in e["sym"] or "mR g" in e["sym"] for e in page.equations)


@pytest.mark.parametrize("units", ["si", "imperial"])
def test_every_unit_system_writes_it(units, folder):
    for scene in ("khurmi-16-21", "seed-004-lathe-drive"):
        status, out, err = render(scene, folder, units=units)
        assert status == 0 and err == ""
        assert Page(out.read_text(encoding="utf-8")).title_block["units"].startswith(units)


def test_an_operation_beyond_the_allowed_delta_is_reported_and_exits_4(tmp_path):
    """As ``flyopt solve``: the report is written, says the speed falls too far, and exits 4."""
    text = (TEXTBOOK / "khurmi-16-21.toml").read_text(encoding="utf-8")
    scene = tmp_path / "tight.toml"
    scene.write_text(text.replace('speed = "300 rpm"', 'speed = "300 rpm"\ndelta = 0.05'), encoding="utf-8")
    out = tmp_path / "tight.html"
    run = run_flyopt("report", str(scene), "-o", str(out))
    assert run.returncode == 4, run.stderr
    page = Page(out.read_text(encoding="utf-8"))
    assert "FLAGGED" in page.title_block["status"]
    assert "does NOT hold" in "".join(page.text)


def test_hostile_names_reach_both_formats_escaped(tmp_path):
    """Branch names with markup, HTML and braces: the report is written in both formats, the names escaped
    (no element of theirs in the page) and the subscripts of the formulas whole."""
    scene = tmp_path / "hostile.toml"
    scene.write_text(
        "\n".join(
            [
                'title = "<script>x</script> & _{a}"',
                "[power_chain]",
                "stages = [0.9]",
                "[[power_chain.branch]]",
                'name = "A}_{<b>"',
                "stages = [0.8]",
                'power = "1 kW"',
                "[[power_chain.branch]]",
                'name = "B&^{x"',
                "stages = [0.5]",
                'power = "2 kW"',
            ]
        ),
        encoding="utf-8",
    )
    for suffix in ("html", "pdf"):
        out = tmp_path / f"hostile.{suffix}"
        run = run_flyopt("report", str(scene), "-o", str(out))
        assert run.returncode == 0 and run.stderr == "", run.stderr
    html = (tmp_path / "hostile.html").read_text(encoding="utf-8")
    page = Page(html)
    assert page.errors == []
    assert "<script>" not in html and "<b>" not in html
    assert "<script>x</script>" in "".join(page.text)
    symbols = [e["sym"] for e in page.equations]
    assert "ηA<b> = η1 × η2" in symbols and "ηB&x = η1 × η2" in symbols, symbols
