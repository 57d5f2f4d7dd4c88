"""The winner rounded to a manufacturing step (design.round_to, issue 28 item 2): on the grid, every limit held.

References are independent of flyopt's rounding: the grid written out by hand, the rounded wheel's
inertia by the annulus formula J = ρ π t (r_o⁴ − r_i⁴) / 2 summed over its parts, a brute-force
search of a wider grid window for a bare rim, and the periodic simulation (--verify) of the rounded
wheel for δ.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import run_flyopt, unplaced

import flyopt
from flyopt.design.rounding import grid_values
from flyopt.errors import SceneError
from flyopt.io.scene import from_dict

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"
MM = 1e-3


@pytest.mark.parametrize(
    ("value", "reach", "expected"),
    [
        (0.0098, 1, (0.009, 0.010)),
        (0.008 * (1 + 1e-13), 1, (0.008,)),  # on the grid to round-off: not moved
        (0.0098, 2, (0.008, 0.009, 0.010, 0.011)),
        (0.0005, 1, (0.001,)),  # no zero or negative size
    ],
)
def test_the_grid_next_to_a_value(value, reach, expected):
    assert grid_values(value, MM, reach) == pytest.approx(expected, abs=1e-15)


def _scene(path: Path, **design: str) -> flyopt.Scene:
    """The shipped scene with ``design`` keys added to its [design] (no files of its own: none read)."""
    import tomllib

    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data["design"] = {**data.get("design", {}), **design}
    return from_dict(data, source=str(path))


def _on_grid(value: float, step: float) -> bool:
    return abs(value / step - round(value / step)) < 1e-9


@pytest.mark.parametrize("geometry", ["rim_web", "rim_arms"])
def test_the_punch_press_wheel_rounded_to_whole_millimetres_meets_every_limit(geometry):
    """rim_arms needs the re-optimization: its arms must fit the hub (n a / (π D_hub) <= 1) and carry their
    stress, which no corner of the grid cell does (the arms and the hub must both grow)."""
    scene = _scene(PROBLEMS / "punch-press-wheel.toml", round_to="1 mm", geometry=geometry)
    solution = flyopt.solve(scene, verify_design=True)
    design = solution.design
    best, continuous = design.best, design.continuous
    assert design.status == "designed" and best.provenance.solver_status == "rounded"
    for name in ("d_outer", "h", "b", "t_web", "d_hub", "l_hub", "arm_major"):
        value = getattr(best.dims, name)
        assert value is None or _on_grid(value, MM), name
    # the rounded wheel's inertia by the annulus formula, part by part (rim, web, hub), against the required
    rho = solution.scene.material_library()[best.material].density
    if geometry == "rim_web":
        inertia = sum(
            rho * math.pi * p["thickness"] * (p["r_outer"] ** 4 - p["r_inner"] ** 4) / 2.0 for p in best.parts.items
        )
        assert inertia == pytest.approx(best.j_flywheel, rel=1e-12)
    assert best.j_flywheel >= best.limits.j_required_on_shaft * (1 - 1e-12)
    # a restriction of the continuous problem: never lighter than its optimum
    assert best.mass >= continuous.mass * (1 - 1e-9)
    # the stresses of the rounded wheel are its own, within the allowable of each part (the stress criterion)
    for part in best.stresses.stress["parts"]:
        assert part["stress"] <= part["allowable"] * (1 + 1e-9)
    # δ by the periodic simulation of the machine with the rounded wheel
    assert not solution.verification.flagged
    assert solution.verification.achieved_delta <= solution.scene.delta * (1 + 1e-9)


def test_a_bare_rim_rounded_is_the_lightest_wheel_of_a_wider_window_by_brute_force():
    """rim-sizing: a thin rim, D_m = 0.8 m pinned, H/B = 2, cast steel; J = 76 kg·m² at the continuous optimum.

    Brute force over ±5 mm of H and B: the thin rim's J = m D_m²/4 with m = π D_m H B ρ
    (docs/flywheel-design.md, section 9), H/B within [2, 2] and J >= J_F."""
    scene = _scene(PROBLEMS / "rim-sizing.toml", round_to="1 mm")
    design = flyopt.solve(scene).design
    best = design.best
    assert best.geometry == "thin_rim"
    rho = scene.material_library()[best.material].density
    j_required = best.limits.j_required_on_shaft
    d_m = 0.8
    h0, b0 = design.continuous.dims.h, design.continuous.dims.b
    lightest = None
    for i in range(-5, 7):
        for k in range(-5, 7):
            h = (math.floor(h0 / MM) + i) * MM
            b = (math.floor(b0 / MM) + k) * MM
            if abs(h / b - 2.0) > 1e-9:
                continue
            m = math.pi * d_m * h * b * rho
            if m * d_m**2 / 4.0 < j_required * (1 - 1e-12):
                continue
            if lightest is None or m < lightest[0]:
                lightest = (m, h, b)
    assert lightest is not None
    assert best.mass == pytest.approx(lightest[0], rel=1e-12)
    assert (best.dims.h, best.dims.b) == pytest.approx(lightest[1:], abs=1e-12)
    assert best.dims.d_mean == pytest.approx(d_m, rel=1e-12)  # the pinned mean diameter stays


def test_no_wheel_near_the_optimum_is_reported_in_words_and_exit_3(tmp_path):
    """H/B fixed at 1.37 cannot be kept on a 1 mm grid near the optimum: no design, and the reason says so."""
    text = (PROBLEMS / "rim-sizing.toml").read_text(encoding="utf-8")
    assert "hb_ratio" in text
    lines = [line for line in text.splitlines() if not line.startswith("hb_ratio")]
    text = "\n".join(lines).replace("[design]", '[design]\nround_to = "1 mm"\nhb_ratio = 1.37', 1)
    scene = tmp_path / "fixed-ratio.toml"
    scene.write_text(text, encoding="utf-8")
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 3, run.stderr
    assert "no rounded design: no wheel near the optimum on the 1 mm grid meets every limit" in run.stdout
    assert "H/B is fixed at 1.37 (hb_ratio)" in run.stdout


@pytest.mark.parametrize(("value", "words"), [("0 mm", "positive"), ("0.5 m", "no manufacturing step")])
def test_a_bad_step_is_refused_in_one_line(value, words):
    with pytest.raises(SceneError) as err:
        from_dict(
            {
                "machine": {"speed": "120 rpm", "delta": 0.05},
                "torque": {"net": {"areas": ["10 kJ", "-10 kJ"]}},
                "design": {"round_to": value},
            }
        )
    assert err.value.field == "design.round_to" and words in str(err.value)


def test_sweeps_and_fronts_refuse_rounding_in_one_line(tmp_path):
    scene = tmp_path / "rounded.toml"
    text = (
        (PROBLEMS / "rim-sizing.toml").read_text(encoding="utf-8").replace("[design]", '[design]\nround_to = "1 mm"', 1)
    )
    scene.write_text(text, encoding="utf-8")
    for command in (
        ["sweep", str(scene), "--vary", "delta=0.01,0.02", "-o", str(tmp_path / "s.csv")],
        ["pareto", str(scene), "-o", str(tmp_path / "p.csv")],
    ):
        run = run_flyopt(*command)
        assert run.returncode == 2 and len(run.stderr.strip().splitlines()) == 1, run.stderr
        assert f"{scene}: design.round_to: rounds one winning wheel" in unplaced(run.stderr, scene)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rounded.toml"]


def test_solve_and_the_report_show_the_continuous_optimum_beside_the_rounded_wheel(tmp_path):
    scene = tmp_path / "rounded.toml"
    text = (
        (PROBLEMS / "rim-sizing.toml").read_text(encoding="utf-8").replace("[design]", '[design]\nround_to = "1 mm"', 1)
    )
    scene.write_text(text, encoding="utf-8")
    words = "rounded to 1 mm (design.round_to): +8.07 kg (+1.70 %) over the continuous optimum: 475 kg"
    run = run_flyopt("solve", str(scene))
    assert run.returncode == 0 and words in run.stdout, run.stderr
    out = tmp_path / "rounded.html"
    run = run_flyopt("report", str(scene), "-o", str(out))
    assert run.returncode == 0, run.stderr
    assert words in out.read_text(encoding="utf-8")


def test_a_whole_wheel_is_rounded_by_default_and_round_to_false_asks_for_the_continuous_optimum(tmp_path):
    """solve rounds a wheel designed whole to whole millimetres without being asked (issue 28: the rounded
    wheel is the design reported); round_to = false gives the continuous optimum, and the scene schema takes
    it; a textbook rim is not rounded."""
    import json

    import jsonschema

    try:  # Python >= 3.11
        import tomllib
    except ModuleNotFoundError:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    text = (PROBLEMS / "press-arms-wheel.toml").read_text(encoding="utf-8")
    rounded = flyopt.solve(flyopt.load(PROBLEMS / "press-arms-wheel.toml")).design
    assert rounded.spec.round_to == 0.001 and rounded.continuous is not None
    for name in ("d_outer", "h", "b", "d_hub", "l_hub", "arm_major"):
        value = getattr(rounded.best.dims, name) * 1e3
        assert abs(value - round(value)) < 1e-9, (name, value)
    # the result's message describes the rounded wheel, the design, not the continuous optimum beside it
    best, optimum = rounded.best, rounded.continuous
    for wheel, said in ((best, True), (optimum, False)):
        words = f"D_outer {wheel.dims.d_outer:.3g} m, B {wheel.dims.b:.3g} m, mass {wheel.mass:.3g} kg"
        assert (words in rounded.message) is said, (words, rounded.message)
    path = tmp_path / "continuous.toml"
    path.write_text(text.replace("[design]\n", "[design]\nround_to = false\n", 1), encoding="utf-8")
    continuous = flyopt.solve(flyopt.load(path)).design
    assert continuous.continuous is None and continuous.best.mass == pytest.approx(rounded.continuous.mass, rel=1e-9)
    assert continuous.best.mass < rounded.best.mass
    schema = json.loads((Path(flyopt.__file__).parent / "data" / "scene.schema.json").read_text(encoding="utf-8"))
    with open(path, "rb") as handle:
        jsonschema.Draft202012Validator(schema).validate(tomllib.load(handle))
    book = flyopt.solve(flyopt.load(PROBLEMS / "rim-sizing.toml")).design
    assert book.continuous is None and book.spec.round_to is None


# ------------------------------------------------------------------ preferred numbers (design.diameter_series)

#: ISO 3:1973's basic series R20 and R40, rounded values, written out here from the standard's table (DIN 323-1
#: table 1 gives the same), independently of flyopt/data/preferred_numbers.toml.
ISO3_R20 = "1.00 1.12 1.25 1.40 1.60 1.80 2.00 2.24 2.50 2.80 3.15 3.55 4.00 4.50 5.00 5.60 6.30 7.10 8.00 9.00"
ISO3_R40 = (
    "1.00 1.06 1.12 1.18 1.25 1.32 1.40 1.50 1.60 1.70 1.80 1.90 2.00 2.12 2.24 2.36 2.50 2.65 2.80 3.00 "
    "3.15 3.35 3.55 3.75 4.00 4.25 4.50 4.75 5.00 5.30 5.60 6.00 6.30 6.70 7.10 7.50 8.00 8.50 9.00 9.50"
)


def _r40_mm():
    """R40 from 10 mm to 10 m, in whole millimetres (every value there is one)."""
    return {round(float(m) * 10**k) for k in (1, 2, 3) for m in ISO3_R40.split()}


def test_the_series_are_iso_3s():
    """The data file's series are the standard's; each rounded value within 1.3 % of its theoretical 10^(k/n)
    (ISO 3's bound for R40's rounded values), and R20 is every other R40 value."""
    from flyopt.design import preferred

    assert preferred.mantissas("R40") == tuple(float(v) for v in ISO3_R40.split())
    assert preferred.mantissas("R20") == tuple(float(v) for v in ISO3_R20.split())
    assert preferred.mantissas("R20") == preferred.mantissas("R40")[::2]
    assert preferred.mantissas("R10") == preferred.mantissas("R20")[::2]
    assert preferred.mantissas("R5") == preferred.mantissas("R10")[::2]
    for n in (5, 10, 20, 40):
        for k, m in enumerate(preferred.mantissas(f"R{n}")):
            assert abs(m / 10 ** (k / n) - 1.0) <= 0.013, (n, k, m)


@pytest.mark.parametrize(
    ("value", "series", "reach", "expected"),
    [
        (0.657, "R40", 1, (0.63, 0.67)),
        (0.67 * (1 + 1e-13), "R40", 1, (0.67,)),  # in the series to round-off: not moved
        (0.657, "R40", 2, (0.6, 0.63, 0.67, 0.71)),
        (0.0987, "R20", 1, (0.09, 0.1)),
        (1.0, "R10", 2, (0.8, 1.0, 1.25)),  # across a decade
        (0.0091, "R40", 1, (0.009, 0.0095)),
    ],
)
def test_the_series_values_next_to_a_length(value, series, reach, expected):
    from flyopt.design.preferred import series_values

    assert series_values(value, series, reach) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("name", ["punch-press-wheel", "press-arms-wheel"])
def test_diameters_on_r40_the_rest_on_whole_millimetres_every_limit_held(name):
    """The outer and hub diameters from R40, the other dimensions on the 1 mm grid; the rounded wheel's inertia
    by the annulus formula (the web wheel) meets the requirement; never lighter than the continuous optimum."""
    design = flyopt.solve(_scene(PROBLEMS / f"{name}.toml", diameter_series="R40")).design
    best, continuous = design.best, design.continuous
    assert design.status == "designed" and best.provenance.solver_status == "rounded"
    series = _r40_mm()
    for dimension in ("d_outer", "d_hub"):
        assert round(getattr(best.dims, dimension) * 1e3, 6) in series, dimension
    for dimension in ("h", "b", "t_web", "l_hub", "arm_major"):
        value = getattr(best.dims, dimension)
        assert value is None or _on_grid(value, MM), dimension
    if best.geometry == "rim_web":
        rho = flyopt.load(PROBLEMS / f"{name}.toml").material_library()[best.material].density
        inertia = sum(
            rho * math.pi * p["thickness"] * (p["r_outer"] ** 4 - p["r_inner"] ** 4) / 2.0 for p in best.parts.items
        )
        assert inertia == pytest.approx(best.j_flywheel, rel=1e-12)
    assert best.j_flywheel >= best.limits.j_required_on_shaft * (1 - 1e-12)
    for part in best.stresses.stress["parts"]:
        assert part["stress"] <= part["allowable"] * (1 + 1e-9)
    assert best.mass >= continuous.mass * (1 - 1e-9)
    assert "R40" in design.rounding


def test_an_unknown_series_is_refused_in_one_line():
    with pytest.raises(SceneError) as err:
        _scene(PROBLEMS / "punch-press-wheel.toml", diameter_series="R30")
    assert err.value.field == "design.diameter_series" and "R40" in str(err.value)


def test_a_whole_wheel_with_a_pinned_mean_diameter_is_rounded_around_it():
    """Regression: the rounding's warm re-solves took their start from the dimensions it rounds, which leave
    D_outer out where D_m is pinned (D_outer = D_m + H follows H): KeyError 'd_outer'. D_m stays at 0.6 m,
    every other dimension on the 1 mm grid, the inertia by the annulus formula meets the requirement."""
    design = flyopt.solve(_scene(PROBLEMS / "punch-press-wheel.toml", d_mean="0.6 m")).design
    best = design.best
    assert design.status == "designed" and best.provenance.solver_status == "rounded"
    assert best.dims.d_mean == pytest.approx(0.6, rel=1e-12)
    for name in ("h", "b", "t_web", "d_hub", "l_hub"):
        assert _on_grid(getattr(best.dims, name), MM), name
    rho = flyopt.load(PROBLEMS / "punch-press-wheel.toml").material_library()[best.material].density
    inertia = sum(
        rho * math.pi * p["thickness"] * (p["r_outer"] ** 4 - p["r_inner"] ** 4) / 2.0 for p in best.parts.items
    )
    assert inertia == pytest.approx(best.j_flywheel, rel=1e-12)
    assert best.j_flywheel >= best.limits.j_required_on_shaft * (1 - 1e-12)


def test_a_rounded_wheel_its_post_check_refuses_is_not_the_design():
    """design_flywheel(accept=...) (the shaft's check) passed the continuous optimum; rounding moves the wheel,
    and the rounded wheel must pass it too. Here the post-check refuses every wheel on the 1 mm grid: with the
    default step the continuous optimum stays the design, said so; a step asked for makes the result
    infeasible. Before, the rounded wheel was reported without being checked."""
    import dataclasses

    from test_wheel_nlp import ENGINE, _engine_material

    from flyopt.design import DesignSpec, MountShaft, design_flywheel

    steel = _engine_material()  # the engine scenes' cast steel, 60 MPa allowable

    def on_grid(design):
        return all(_on_grid(getattr(design.dims, n), 1e-3) for n in ("d_outer", "b", "t_web"))

    def accept(design):
        return "a wheel on the 1 mm grid (this test's rule)" if on_grid(design) else None

    spec = DesignSpec(geometry="rim_web", criterion="stress", hb_ratio=(0.5, 2.0), round_to=1e-3, round_strict=False)
    args = (ENGINE["j"], ENGINE["omega"], [MountShaft("crankshaft", 1.0, 0.07)], [steel])
    plain = design_flywheel(*args, spec, torque=ENGINE["torque"])
    assert plain.continuous is not None and on_grid(plain.best)  # rounded without the post-check
    loose = design_flywheel(*args, spec, torque=ENGINE["torque"], accept=accept)
    assert loose.status == "designed" and not on_grid(loose.best)
    assert loose.best.mass == plain.continuous.mass and loose.best.dims == plain.continuous.dims
    assert "NOT rounded" in loose.rounding and "this test's rule" in loose.rounding
    strict = design_flywheel(
        *args, dataclasses.replace(spec, round_strict=True), torque=ENGINE["torque"], accept=accept
    )
    assert strict.status == "infeasible" and strict.best is None and "this test's rule" in strict.message


def test_rounding_re_solves_with_the_solver_options_the_design_was_given(monkeypatch):
    """Rounding's re-designs use the caller's solver options: asked for IPOPT alone, every whole-wheel solve
    of punch-press-wheel, rounding's included, is IPOPT's (they ran with the default solver before)."""
    from flyopt.design import rounding, wheel_nlp

    solved, rounded = [], []
    original, round_original = wheel_nlp.solve, rounding.round_design

    def spy(model, problem, label):
        solved.append(model.fast is None)  # no sqpmethod in front: the model IPOPT alone solves
        return original(model, problem, label)

    def round_spy(*args, **kwargs):
        before = len(solved)
        found = round_original(*args, **kwargs)
        rounded.append(len(solved) - before)
        return found

    monkeypatch.setattr(wheel_nlp, "solve", spy)
    monkeypatch.setattr(rounding, "round_design", round_spy)
    design = flyopt.solve(
        flyopt.load(PROBLEMS / "punch-press-wheel.toml"), solver_options={wheel_nlp.SOLVER_OPTION: "ipopt"}
    ).design
    assert design.continuous is not None and rounded and rounded[0] > 0  # rounding re-solved
    assert all(solved), f"{solved.count(False)} of {len(solved)} solves ignored the options"


def test_a_fixed_ratio_rounded_wheel_leaves_the_terminal_silent(tmp_path, capfd):
    """press-arms-wheel at ``hb_ratio = 1.5``: once the rounding has fixed H and B (and the rest), CasADi counted
    the ratio's equality row with the fixed variables and printed "NLP is overconstrained: There are 7 equality
    constraints but only 6 variables" at each of 10 solves above a valid design. The row, a constant there, is
    freed where the fixed H and B meet the ratio; the wheel is the same, H/B 1.5 to round-off."""
    text = (PROBLEMS / "press-arms-wheel.toml").read_text(encoding="utf-8")
    assert "hb_ratio = [0.5, 2.0]" in text
    path = tmp_path / "fixed.toml"
    path.write_text(text.replace("hb_ratio = [0.5, 2.0]", "hb_ratio = 1.5"), encoding="utf-8")
    capfd.readouterr()
    design = flyopt.solve(flyopt.load(path)).design
    assert capfd.readouterr() == ("", "")
    dims = design.best.dims
    assert design.best.feasible and dims.h / dims.b == pytest.approx(1.5, rel=1e-12)
    for name in ("h", "b"):  # rounded to the millimetre, so both were fixed by the rounding
        assert abs(getattr(dims, name) * 1e3 - round(getattr(dims, name) * 1e3)) < 1e-9
