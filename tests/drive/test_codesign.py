"""The drive designed with the flywheel (flyopt.drive.codesign, flyopt.drive.relaxation).

References are independent of the code under test: a brute-force enumeration
of every motor size over a fine grid of flywheel ratios; quadrature (scipy
quad) of the RMS torque; the root of the work balance
checked by substitution; the collocation of the relaxation against flyopt's
CVODES periodic solution of the same relaxed motor; and the smaller motor shown
to break a limit in the simulation.
"""

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import integrate

from flyopt.drive import codesign as drive
from flyopt.drive.relaxation import CatalogueFit
from flyopt.io.drive import DriveSpec
from flyopt.io.scene import load
from flyopt.machine.catalogue import Catalogue, CatalogueMotor

RPM = math.pi / 30

# A user's own motor options for the tests (a plausible 4-pole ladder: 1500 rpm, slip 3-4 %,
# rotor inertia and mass growing with the rating). The optimizer is under test, not the data.
OPTIONS = Catalogue(
    "motor_option",
    tuple(
        CatalogueMotor(
            name=f"{p:g} kW",
            rated_power=p * 1e3,
            rated_speed=n * RPM,
            synchronous_speed=1500 * RPM,
            rotor_inertia=j,
            breakdown_ratio=k,
            mass=m,
        )
        for p, n, j, k, m in [
            (3.0, 1435, 0.0095, 2.9, 22.0),
            (4.0, 1440, 0.012, 2.8, 30.0),
            (5.5, 1450, 0.022, 2.7, 40.0),
            (7.5, 1455, 0.030, 2.7, 50.0),
            (11.0, 1460, 0.060, 2.6, 75.0),
            (15.0, 1465, 0.075, 2.6, 95.0),
        ]
    ),
)


def _scene(**changes):
    spec = DriveSpec(motors=OPTIONS, ratio_range=(2.0, 8.0), objective="mass", max_startup=30.0, thermal=True)
    spec = DriveSpec(**{**spec.__dict__, **changes})
    return load("problems/punch-press.toml").replace(drive=spec)


@pytest.fixture(scope="module")
def designed():
    scene = _scene()
    return scene, drive.design_drive(scene)


def test_work_balance_ratio_is_the_root():
    """The motor ratio estimate puts the angle-mean motor torque on the load: i η M_lin(i ω) = M̄."""
    motor = OPTIONS.motors[3]
    load, omega, eta = 700.0, 2 * math.pi, 0.92
    i = drive.motor_ratio_estimate(motor, load, omega, eta)
    torque = motor.motor().torque(i * omega, "linear")
    assert i * eta * torque == pytest.approx(load, rel=1e-12)
    assert i * omega > motor.motor().linear_limit_speed  # the stable, low-slip root
    assert drive.motor_ratio_estimate(motor, 1e6, omega, eta) is None  # no ratio reaches a huge load


def test_rms_torque_against_quadrature():
    """RMS of the motor torque in time on ω(φ) = ω̄ (1 + a sin φ), against scipy quad of the exact integrals."""
    motor = OPTIONS.motors[2].motor()
    w_bar, a, ratio = 6.0, 0.04, 24.0
    phi = np.linspace(0.0, 2 * math.pi, 20001)
    solution = SimpleNamespace(phi=phi, omega=w_bar * (1 + a * np.sin(phi)))
    rms, mean = drive.rms_torque(solution, motor, ratio)

    def w(p):
        return w_bar * (1 + a * math.sin(p))

    def m(p):
        return float(motor.torque(ratio * w(p), "kloss"))

    period = integrate.quad(lambda p: 1 / w(p), 0, 2 * math.pi, epsabs=0, epsrel=1e-13)[0]
    squares = integrate.quad(lambda p: m(p) ** 2 / w(p), 0, 2 * math.pi, epsabs=0, epsrel=1e-13)[0]
    means = integrate.quad(lambda p: m(p) / w(p), 0, 2 * math.pi, epsabs=0, epsrel=1e-13)[0]
    assert rms == pytest.approx(math.sqrt(squares / period), rel=1e-7)
    assert mean == pytest.approx(means / period, rel=1e-7)


@pytest.mark.slow  # every size of the ladder solved exactly: about a minute
def test_codesign_matches_brute_force(designed):
    """Every motor size over a fine grid of flywheel ratios: the same motor and the best mass to 1e-6."""
    scene, result = designed
    assert result.status == "designed"
    load_torque = drive_load(scene)
    grid = ("fixed", *np.linspace(2.0, 8.0, 241))
    from flyopt.design import design_inputs

    inputs = design_inputs(scene)
    brute = [
        drive.evaluate_motor(scene, m, load_torque, scene.drive, grid, inputs.materials, inputs.spec) for m in OPTIONS
    ]
    feasible = [r for r in brute if r.feasible]
    best = min(feasible, key=lambda r: r.objective)
    assert result.best.motor.name == best.motor.name
    assert result.best.objective <= best.objective * (1 + 1e-6)
    assert result.best.objective == pytest.approx(best.objective, rel=1e-6)
    # the relaxation solved fewer sizes than the catalogue holds, and the winner among them
    assert len(result.runs) < len(OPTIONS)
    assert result.relaxation is not None


def test_the_relaxations_wheel_is_named_for_people():
    """The text names the relaxed wheel's material as everywhere else ("cast steel"), not by its key."""
    import flyopt
    from flyopt.report.drive import relaxation_summary

    result = flyopt.solve(load("problems/press-drive.toml")).drive
    key = result.relaxation.wheel.partition(", ")[0]
    summary, _ = relaxation_summary(result, "engineering")
    assert key == "cast_steel" and key not in summary
    assert "wheel cast steel " in summary  # the name flyopt materials lists for it


def drive_load(scene):
    from flyopt.analysis import analyse

    return analyse(scene).driving_torque


@pytest.mark.slow  # every size of the ladder solved exactly: about a minute
def test_one_size_smaller_breaks_a_limit_in_the_simulation(designed):
    """The next smaller motor with the chosen wheel: the simulation shows δ or the thermal limit exceeded."""
    scene, result = designed
    best = result.best
    smaller = [m for m in OPTIONS if m.rated_power < best.motor.rated_power][-1]
    from flyopt.design import design_inputs

    inputs = design_inputs(scene)
    run = drive.evaluate_motor(
        scene, smaller, drive_load(scene), scene.drive, ("fixed", best.flywheel_ratio), inputs.materials, inputs.spec
    )
    ratio = run.motor_ratio or drive.motor_ratio_estimate(
        smaller, drive_load(scene), scene.omega_mean, scene.efficiency
    )
    trial = drive.MotorRun(motor=smaller, feasible=True, motor_ratio=ratio)
    check = drive.verify_drive(scene, trial, j_flywheel=best.wheel.j_at_reference)
    assert check.flagged
    assert any("delta" in n or "thermal" in n for n in check.notes)
    from flyopt.report.drive import check_verdict

    verdict = check_verdict(check, "imperial", 4)  # its notes in the reader's units (the RMS torque in lbf·ft)
    assert verdict.startswith("FLAGGED: ") and "N·m" not in verdict and "rad/s" not in verdict, verdict
    # and the chosen drive, simulated with its wheel as built, keeps every limit
    ok = drive.verify_drive(scene, best)
    assert not ok.flagged, ok.notes
    assert ok.verification.achieved_delta <= scene.delta * (1 + 1e-6)
    assert ok.rms_torque <= best.motor.rated_torque * (1 + 1e-6)


@pytest.mark.slow  # every size of the ladder solved exactly: about a minute
def test_relaxation_collocation_against_the_periodic_solution(designed):
    """The relaxed motor and flywheel, simulated by CVODES shooting: δ and the mean speed within the collocation error."""
    from flyopt.analysis import analyse
    from flyopt.cycle.torque import MotorTorque
    from flyopt.machine.reduce import reduce
    from flyopt.machine.transmission import inertia_at_reference
    from flyopt.sizing.periodic import periodic_solution

    scene, result = designed
    relaxed = result.relaxation
    fit = CatalogueFit.of(OPTIONS)
    motor, j_rot, _ = fit.motor(relaxed.rated_power)
    built = scene.replace(
        driving=MotorTorque(motor, relaxed.motor_ratio, scene.efficiency, "kloss", "test"),
        j_constant=scene.j_constant + inertia_at_reference(j_rot, relaxed.motor_ratio),
    )
    machine = reduce(built)
    sol = periodic_solution(
        machine.net_torque(),
        machine.j_machine,
        machine.cycle_angle,
        scene.omega_mean,
        relaxed.j_flywheel,
        machine.knots(),
    )
    # the NLP kept every node within ω_m (1 ± δ/2); trapezoidal collocation on ~250 intervals: O(h²)
    assert sol.omega_max <= scene.omega_mean * (1 + scene.delta / 2) * (1 + 2e-4)
    assert sol.omega_min >= scene.omega_mean * (1 - scene.delta / 2) * (1 - 2e-4)
    assert analyse(scene).driving_torque > 0


@pytest.mark.slow  # two motor sizes solved exactly, no relaxation to prune: about 12 s
def test_every_size_without_a_relaxation_when_too_few():
    """Two sizes are no ladder to fit: every size is solved, and the note says so."""
    few = Catalogue("motor_option", OPTIONS.motors[3:5])
    scene = _scene(motors=few)
    result = drive.design_drive(scene)
    assert result.relaxation is None and "every catalogue size" in result.note
    assert len(result.runs) == 2


@pytest.mark.slow  # every size of the ladder solved exactly: about a minute
def test_motor_power_front_is_the_nondominated_set():
    """Every size solved; the front keeps exactly the runs no other run beats in both power and wheel mass."""
    result = drive.design_drive(_scene(), every_size=True)
    assert len(result.runs) == len(OPTIONS)
    front = drive.motor_power_front(result)
    feasible = [r for r in result.runs if r.feasible]
    for run in feasible:
        dominated = any(
            o.motor.rated_power <= run.motor.rated_power
            and o.wheel_mass <= run.wheel_mass
            and (o.motor.rated_power, o.wheel_mass) != (run.motor.rated_power, run.wheel_mass)
            for o in feasible
        )
        assert (run in front) == (not dominated), run.motor.name
    # a bigger motor needs no heavier wheel along the front
    assert all(a.wheel_mass > b.wheel_mass for a, b in zip(front, front[1:]))


def test_motor_power_front_needs_a_drive(tmp_path):
    """A front of flywheel mass against motor power on a scene without [drive]: one line, exit 2."""
    from conftest import ROOT, run_flyopt

    result = run_flyopt("pareto", ROOT / "problems" / "punch-press.toml", "--objectives", "mass,motor_power")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "objectives" in lines[0] and "[drive]" in lines[0]


def test_the_motor_power_fronts_inertias_mean_what_a_sweeps_and_solves_do():
    """press-drive's front of wheel mass against motor power: ``j_flywheel`` is the wheel's inertia on its own
    shaft, as ``solve --json``'s design and a sweep's column (it was the inertia at the crank, 45,930 kg·m² for a
    248 kg wheel of 1.2 m, whose inertia on its shaft is below m (D/2)² = 89 kg·m²). Moved to the crank by the
    flywheel ratio squared it is ``j_at_reference``, the same kinetic energy, and that is what the motor size
    needs there, ``j_required``."""
    from conftest import PROBLEMS

    from flyopt.studies.pareto import pareto

    front = pareto(load(PROBLEMS / "press-drive.toml"), "mass,motor_power")
    designed = front[front["status"] == "designed"]
    assert len(designed) >= 1
    for row in designed.to_dict("records"):
        radius = row["d_outer"] / 2
        assert 0 < row["j_flywheel"] < row["mass"] * radius**2  # the wheel's own, about its own axis
        assert row["j_at_reference"] == pytest.approx(row["j_flywheel"] * row["flywheel_ratio"] ** 2, rel=1e-12)
        assert row["j_flywheel"] * row["flywheel_ratio"] ** 2 == pytest.approx(row["j_required"], rel=1e-6)
    idle = front[front["status"] == "not_needed"]
    assert (idle["j_required"] == 0).all() and idle["j_flywheel"].isna().all()
    # the file's metadata types each column as the front holds it (it typed the motor's name a number)
    from flyopt.outputs.documents import table_metadata

    types = {c["name"]: c["type"] for c in table_metadata("pareto", list(front.columns))["columns"]}
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    for name in front.columns:
        column = front[name]
        if is_bool_dtype(column.dtype):
            expected = "boolean"
        elif is_numeric_dtype(column.dtype):
            expected = "number"
        else:  # text, or objects that are all text
            assert all(isinstance(v, str) for v in column.dropna()), name
            expected = "string"
        assert types[name] == expected, (name, types[name], column.dtype)


@pytest.mark.slow  # every size of the ladder solved exactly: about half a minute
def test_flyopt_pareto_motor_power_writes_the_front(tmp_path):
    """flyopt pareto --objectives mass,motor_power: the non-dominated (motor power, wheel mass) of every size,
    its objectives recorded for flyopt plot."""
    import json
    import subprocess
    import sys

    import pandas as pd

    out = tmp_path / "front.csv"
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "flyopt",
            "pareto",
            "problems/press-drive.toml",
            "--objectives",
            "mass,motor_power",
            "-o",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    front = pd.read_csv(out)
    scene = load("problems/press-drive.toml")
    every = drive.design_drive(scene, every_size=True)
    expected = drive.motor_power_front(every)
    assert list(front["motor"]) == [r.motor.name for r in expected]
    assert front["mass"].to_numpy() == pytest.approx([r.wheel_mass for r in expected], rel=1e-9)
    assert json.loads(out.with_name("front.csv.json").read_text())["objectives"] == ["mass", "motor_power"]


def test_relaxation_sensitivities_against_central_differences():
    """d(objective)/d(limit) from IPOPT's multipliers against the relaxation re-solved at limit ± h."""

    from flyopt.analysis import analyse
    from flyopt.design import design_inputs
    from flyopt.drive.relaxation import RelaxedWheel, relax

    scene = _scene(max_startup=2.5)  # the run-up binds too (3.2 s unbound)
    analysis = analyse(scene)
    fit = CatalogueFit.of(OPTIONS)
    v_max, envelope = 50.0, 1.2
    load_torque = analysis.driving_torque
    inputs = design_inputs(scene)
    steel = next(m for m in inputs.materials if m.name == "cast_steel")

    def solve(delta=scene.delta, spec=scene.drive, v=v_max, d=envelope):
        wheel = RelaxedWheel.of(
            dataclasses.replace(steel, max_rim_speed=v), dataclasses.replace(inputs.spec, max_outer_diameter=d)
        )
        return relax(analysis.machine, scene.omega_mean, delta, scene.efficiency, fit, spec, wheel, load_torque)

    base = solve()
    sens = base.sensitivities
    moves = {
        "delta": lambda h: solve(delta=scene.delta + h),
        "max_startup": lambda h: solve(spec=dataclasses.replace(scene.drive, max_startup=2.5 + h)),
        "rim_speed": lambda h: solve(v=v_max + h),
        "ratio_max": lambda h: solve(spec=dataclasses.replace(scene.drive, ratio_range=(2.0, 8.0 + h))),
        "max_outer_diameter": lambda h: solve(d=envelope + h),
    }
    steps = {"delta": 1e-5, "max_startup": 1e-4, "rim_speed": 1e-3, "ratio_max": 1e-5, "max_outer_diameter": 1e-6}
    binding = 0
    for limit, move in moves.items():
        h = steps[limit]
        fd = (move(h).objective - move(-h).objective) / (2 * h)
        assert sens[limit] == pytest.approx(fd, rel=2e-5, abs=1e-8 * base.objective), limit
        binding += abs(fd) > 1e-6 * base.objective
    assert binding == 4  # delta, run-up, ratio and envelope bind; the rim speed does not


def test_the_relaxation_is_built_once_per_machine():
    """Another material or limit solves the relaxation again without building its NLP (limits are parameters)."""
    from flyopt.analysis import analyse
    from flyopt.design import design_inputs
    from flyopt.drive import relaxation as drive_nlp

    scene = _scene()
    analysis = analyse(scene)
    fit = CatalogueFit.of(OPTIONS)
    inputs = design_inputs(scene)
    iron, steel = (next(m for m in inputs.materials if m.name == name) for name in ("cast_iron", "cast_steel"))
    before = drive_nlp.BUILDS["count"]
    first = drive_nlp.relax(
        analysis.machine,
        scene.omega_mean,
        scene.delta,
        scene.efficiency,
        fit,
        scene.drive,
        drive_nlp.RelaxedWheel.of(steel, inputs.spec),
        analysis.driving_torque,
    )
    second = drive_nlp.relax(
        analysis.machine,
        scene.omega_mean,
        scene.delta,
        scene.efficiency,
        fit,
        scene.drive,
        drive_nlp.RelaxedWheel.of(iron, inputs.spec),
        analysis.driving_torque,
    )
    assert drive_nlp.BUILDS["count"] == before + 1
    assert first.status == second.status == "Solve_Succeeded"


@pytest.mark.parametrize(
    "geometry, criterion, material, arms",
    [
        ("rim", "rim_speed", "cast_steel", 0),
        ("disc", "rim_speed", "cast_iron", 0),
        ("rim_web", "stress", "cast_steel", 0),
        ("rim_arms", "stress", "cast_steel", 6),
        ("rim_arms", "stress", "cast_iron", 6),
    ],
)
def test_relaxation_wheel_is_the_designers_wheel(geometry, criterion, material, arms):
    """The relaxation's wheel at its optimum (J_F, r) against flyopt's designer given that inertia on that shaft
    (the closed form for the bare wheels; the whole-wheel NLP with its exact stress checks for the others):
    never heavier, and the same wheel where the allowable stress does not depend on the wall (cast steel).
    Cast iron's allowable falls with the wall (EN 1561); the relaxation takes its strongest row."""

    from flyopt.analysis import analyse
    from flyopt.design import design_inputs
    from flyopt.design.designer import design_flywheel
    from flyopt.design.spec import MountShaft
    from flyopt.drive.relaxation import RelaxedWheel, relax

    scene = _scene()
    analysis = analyse(scene)
    inputs = design_inputs(scene)
    bore = 0.05 if geometry in ("rim_web", "rim_arms") else None
    spec = dataclasses.replace(inputs.spec, geometry=geometry, criterion=criterion, bore=bore)
    chosen = next(m for m in inputs.materials if m.name == material)
    wheel = RelaxedWheel.of(chosen, spec, bore or 0.0, arms)
    relaxed = relax(
        analysis.machine,
        scene.omega_mean,
        scene.delta,
        scene.efficiency,
        CatalogueFit.of(OPTIONS),
        scene.drive,
        wheel,
        analysis.driving_torque,
    )
    assert relaxed.status == "Solve_Succeeded" and relaxed.j_flywheel > 0
    omega_top = scene.omega_mean * (1 + scene.delta / 2)
    designed = design_flywheel(
        relaxed.j_flywheel,
        omega_top,
        [MountShaft("flywheel", relaxed.flywheel_ratio)],
        [chosen],
        dataclasses.replace(spec, arms=(arms,) if arms else spec.arms),
    )
    assert designed.status == "designed"
    assert relaxed.wheel_mass <= designed.best.mass * (1 + 1e-7)
    if material == "cast_steel" or criterion == "rim_speed":
        assert relaxed.wheel_mass == pytest.approx(designed.best.mass, rel=1e-6)
        assert relaxed.d_outer == pytest.approx(designed.best.dims.d_outer, rel=1e-4)
    else:
        assert relaxed.wheel_mass < designed.best.mass * (1 - 1e-6)


# The same ladder with a price per size, and the wheel's materials with a cost per kg: illustrative test
# data (no source prices these motors), for the co-design by cost.
PRICED = Catalogue(
    "motor_option",
    tuple(
        dataclasses.replace(m, price=price)
        for m, price in zip(OPTIONS.motors, (310.0, 365.0, 455.0, 570.0, 810.0, 1060.0))
    ),
)


@pytest.mark.slow  # every size of the ladder over 241 ratios: about a minute
def test_codesign_by_cost_matches_brute_force():
    """Objective cost (motor price + wheel cost): the same motor and the best cost to 1e-6 as every size over a
    241-point grid of flywheel ratios, each wheel the designer's cheapest material."""
    from flyopt.design import design_inputs

    scene = _scene(motors=PRICED, objective="cost")
    library = scene.material_library()
    priced = tuple(
        dataclasses.replace(library[name], cost=cost) for name, cost in (("cast_iron", 2.2), ("cast_steel", 4.0))
    )
    scene = scene.replace(materials=priced, design_materials=("cast_iron", "cast_steel"))
    result = drive.design_drive(scene)
    assert result.status == "designed" and result.objective == "cost"
    assert result.relaxation is not None
    inputs = design_inputs(scene)
    grid = ("fixed", *np.linspace(2.0, 8.0, 241))
    brute = [
        drive.evaluate_motor(scene, m, drive_load(scene), scene.drive, grid, inputs.materials, inputs.spec)
        for m in PRICED
    ]
    best = min((r for r in brute if r.feasible), key=lambda r: r.objective)
    assert result.best.motor.name == best.motor.name
    assert result.best.objective <= best.objective * (1 + 1e-6)
    assert result.best.objective == pytest.approx(best.objective, rel=1e-6)
    # the reported cost is its own motor's price and its own wheel's cost (the brute force's best is another design,
    # on a grid of ratios: the co-design's continuous optimum is 1.5e-8 cheaper, within the 1e-6 above)
    assert result.best.cost == pytest.approx(result.best.motor.price + result.best.wheel.cost, rel=1e-12)


def test_a_shaft_described_as_a_part_beside_a_drive_is_its_flywheel_shaft(main_cli, tmp_path):
    """The drive puts its wheel on its own flywheel shaft, the [[shaft]] named "flywheel", at the ratio it
    designs: described as a part (no speed_ratio), the scene once refused solves, its wheels checked with it
    (tests/drive/test_drive_shaft.py); a described shaft of another name would carry no wheel, and is still
    refused in one line (exit 2) rather than silently left unchecked."""
    from conftest import PROBLEMS

    text = (PROBLEMS / "press-drive.toml").read_text(encoding="utf-8")
    part = (
        'material = "42crmo4_qt"\n'
        'segments = [{ to = "700 mm", diameter = "70 mm" }]\nbearings = ["60 mm", "620 mm"]\n'
        'wheel_at = "300 mm"\ntorque_at = "660 mm"\n'
    )
    path = tmp_path / "drive.toml"
    path.write_text(text + '\n[[shaft]]\nname = "intermediate"\nspeed_ratio = 6.0\n' + part, encoding="utf-8")
    status, out, err = main_cli("solve", path)
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and "shaft[0]" in err and "[drive]" in err and '"flywheel"' in err
    assert "Traceback" not in err
    path.write_text(text + '\n[[shaft]]\nname = "flywheel"\n' + part, encoding="utf-8")
    status, out, err = main_cli("solve", path)
    assert status == 0, err
    assert "Drive designed with the flywheel" in out


def test_the_walk_leaves_a_size_unsolved_only_where_it_cannot_win():
    # every run's objective is its motor's mass plus a wheel's (>= 0): a size whose motor alone is no lighter
    # than the best is left unsolved, and the walk chooses what it chose solving every size it reached
    # (and, where the objective falls then rises along the ladder, the brute-force best of every size)
    rng = np.random.default_rng(26)
    masses = [m.mass for m in OPTIONS.motors]
    pruned_any = False
    for trial in range(300):
        wheels = rng.uniform(0.0, 80.0, len(masses)) * (rng.uniform(size=len(masses)) < 0.8)
        if trial % 2:  # a valley: the wheel shrinks as the motor grows
            wheels = np.sort(wheels)[::-1]
        objectives = [m + w for m, w in zip(masses, wheels)]
        power = float(rng.uniform(3.0e3, 15.0e3))

        def walk(least):
            done = {}

            def evaluate(k):
                done[k] = SimpleNamespace(feasible=True, objective=objectives[k])

            skipped = drive._neighbours(OPTIONS, power, evaluate, done, least)
            best = min(done, key=lambda k: (objectives[k], k))
            return best, set(done), skipped

        best, solved, skipped = walk(lambda k: masses[k])
        every_best, every_solved, _ = walk(lambda k: None)
        assert best == every_best and solved <= every_solved
        assert all(k not in solved and masses[k] >= objectives[best] for k in skipped)
        assert set(skipped) == every_solved - solved
        pruned_any |= bool(skipped)
        if trial % 2 and all(np.diff(objectives[: best + 1]) <= 0) and all(np.diff(objectives[best:]) >= 0):
            assert best == int(np.argmin(objectives))
    assert pruned_any
