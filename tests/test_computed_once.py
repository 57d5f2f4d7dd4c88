"""Computed once, read many times (issue 24): ``flyopt report``, ``flyopt solve`` and every ``flyopt plot``
solve the scene once, in :func:`flyopt.pipeline.solve`, and then only read the solution.

Every model and design entry point is wrapped: it runs as usual while the one solve is under way, and
raises AssertionError outside it (before or after), so a reader that computes anything (a second
analysis, the comparison of models, the start-up, ω(φ), the textbook flywheel, J_F at other δ, a design,
a stress profile, a simulation) fails the command. ``solve`` itself must be called exactly once.
"""

import contextlib

import pytest
from conftest import PROBLEMS

from flyopt.cli.main import main

#: Each kind of machine in the default run; the others, which the default ones cover kind for kind
#: (an energy-mass press, an engine without moving masses, a constant-inertia press), in the slow run.
SCENES = [
    "motor-press",  # the dynamic model: the start-up and ω(φ) of a motor
    "punch-press-wheel",  # a whole wheel: its stresses
    "engine-members",  # an [engine] with moving masses: the textbook flywheel, the energy-mass diagram
    "example1-net-areas",  # no curves: the diagrams that do not apply say so
    pytest.param("slider-crank-press", marks=pytest.mark.slow),
    pytest.param("four-stroke-engine", marks=pytest.mark.slow),
    pytest.param("shear-press", marks=pytest.mark.slow),
]
DIAGRAMS = ["turning_moment", "energy", "inertia_delta", "cross_section", "stress", "speed", "energy_mass"]


def _entry_points():
    """(module, name) of every function that runs a model, designs or samples the cycle, which a reader must not call."""
    import flyopt.analysis
    import flyopt.delta_curve
    import flyopt.design
    import flyopt.design.designer
    import flyopt.design.strength
    import flyopt.pipeline
    import flyopt.sizing.choose
    import flyopt.sizing.energy_mass
    import flyopt.sizing.periodic
    import flyopt.sizing.startup
    import flyopt.sizing.textbook

    return [
        (flyopt.analysis, "_analyse"),
        (flyopt.analysis, "complete"),
        (flyopt.analysis, "startup_run"),
        (flyopt.analysis, "_speed_curve"),
        # the flywheel's peak torque samples the torque curves: the design stage asks for it (the arms, the key,
        # the stress profile), a reader never does
        (flyopt.analysis, "flywheel_torque"),
        (flyopt.sizing.choose, "requirement"),
        (flyopt.sizing.choose, "compare"),
        (flyopt.sizing.periodic, "periodic_solution"),
        (flyopt.sizing.periodic, "verify"),
        (flyopt.sizing.energy_mass, "achieved_speed"),
        (flyopt.sizing.startup, "startup_time"),
        (flyopt.sizing.textbook, "textbook_requirement"),
        (flyopt.design, "design_flywheel"),
        (flyopt.design.designer, "design_flywheel"),
        (flyopt.design.strength, "profile"),
        (flyopt.pipeline, "design_scene"),
        (flyopt.pipeline, "verify"),
        (flyopt.pipeline, "stress_profile"),
        (flyopt.pipeline, "with_extras"),
        (flyopt.delta_curve, "inertia_curve"),
    ]


@pytest.fixture
def solved_once(monkeypatch):
    """Wrap the entry points; returns the count of solves and the calls made outside the solve."""
    import flyopt.pipeline

    state = {"solves": 0, "solving": False, "late": []}

    def guarded(module, name, function):
        def call(*args, **kwargs):
            if not state["solving"]:
                state["late"].append(f"{module.__name__}.{name}")
                raise AssertionError(f"{module.__name__}.{name} called outside the solve: a reader computes")
            return function(*args, **kwargs)

        return call

    for module, name in _entry_points():
        monkeypatch.setattr(module, name, guarded(module, name, getattr(module, name)))
    solve = flyopt.pipeline.solve

    def counted(*args, **kwargs):
        state["solves"] += 1
        state["solving"] = True
        try:
            return solve(*args, **kwargs)
        finally:
            state["solving"] = False

    monkeypatch.setattr(flyopt.pipeline, "solve", counted)
    return state


def _run(state, capsys, *argv):
    with contextlib.suppress(SystemExit):
        status = main(list(argv))
    out = capsys.readouterr()
    assert not state["late"], f"{argv}: computed outside the solve: {state['late']}\n{out.err}"
    assert state["solves"] == 1, f"{argv}: {state['solves']} solves"
    assert "AssertionError" not in out.err and "Traceback" not in out.err, out.err
    return status, out


@pytest.mark.parametrize("scene", SCENES)
def test_the_report_solves_once(scene, solved_once, tmp_path, capsys):
    status, out = _run(solved_once, capsys, "report", str(PROBLEMS / f"{scene}.toml"), "-o", str(tmp_path / "r.html"))
    assert status in (0, 3, 4) and (tmp_path / "r.html").stat().st_size > 0


@pytest.mark.parametrize("scene", SCENES)
def test_every_diagram_from_one_solve(scene, solved_once, tmp_path, capsys):
    """``--what all -o DIR/``: every diagram that applies written, each other said in one line, one solve."""
    status, out = _run(
        solved_once, capsys, "plot", str(PROBLEMS / f"{scene}.toml"), "--what", "all", "--verify", "-o", str(tmp_path)
    )
    assert status in (0, 3)
    for what in DIAGRAMS:
        written = (tmp_path / f"{what}.png").exists()
        assert written == (f"wrote {tmp_path / what}.png" in out.out), what
        assert written or f": {what}: " in out.out + out.err, f"{what} neither written nor said"
    assert (tmp_path / "turning_moment.png").exists() or scene == "example1-net-areas"
    assert (tmp_path / "energy.png").exists()


#: The scenes each diagram is drawn of alone: the models and kinds of input a diagram may need.
ALONE = ["shear-press", "slider-crank-press", "motor-press", "engine-members", "example1-net-areas"]
#: (scene, diagram): why it is refused, in one line.
NOT_DRAWABLE = {
    ("example1-net-areas", "speed"): "net-area scene has no angles",
    ("example1-net-areas", "energy_mass"): "needs torques of the angle only given as curves",
    ("motor-press", "energy_mass"): "needs torques of the angle only given as curves",
    # a constant inertia: the energy–mass diagram would be a vertical line (it was drawn, on a ±5e-10 axis)
    ("shear-press", "energy_mass"): "drawn for an inertia that varies with the angle",
}


def test_the_diagrams_are_every_diagram():
    from flyopt.report.plots import PLOTS

    assert sorted(DIAGRAMS) == sorted(PLOTS)


# in the slow set (the default run's five minutes): engine-members (energy_mass, as slider-crank-press, from its
# members) and shear-press (the energy model, as punch-press-wheel in test_every_diagram_from_one_solve; a
# diagram that does not apply is refused in one line as example1-net-areas's and motor-press's are)
@pytest.mark.parametrize(
    "scene",
    [pytest.param(s, marks=pytest.mark.slow) if s in ("engine-members", "shear-press") else s for s in ALONE],
)
@pytest.mark.parametrize("what", DIAGRAMS)
def test_each_diagram_solves_once_and_renders(scene, what, solved_once, tmp_path, capsys):
    """One diagram alone: one solve that computes what it draws (``flyopt.cli.plot.needs``), a real PNG
    written; a diagram that does not apply is refused in one line and nothing written."""
    extra = ["--verify"] if what == "speed" else []
    out = tmp_path / "d.png"
    status, said = _run(
        solved_once, capsys, "plot", str(PROBLEMS / f"{scene}.toml"), "--what", what, *extra, "-o", str(out)
    )
    if (scene, what) in NOT_DRAWABLE:
        assert status == 2 and not out.exists()
        assert NOT_DRAWABLE[scene, what] in said.err and said.err.count("\n") == 1
        return
    assert status == 0, said.err
    assert out.stat().st_size > 10_000  # a real image, not an empty canvas
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("scene", ["slider-crank-press", "engine-members", "example1-net-areas"])
@pytest.mark.parametrize("json", [False, True])
def test_the_solve_report_reads_what_it_shows(scene, json, solved_once, capsys):
    """``flyopt solve`` (text and JSON): the comparison of models, the start-up and the textbook flywheel
    come with the solve (its default extras), not from the report."""
    status, out = _run(solved_once, capsys, "solve", str(PROBLEMS / f"{scene}.toml"), *(["--json"] if json else []))
    assert status == 0 and out.out


def test_a_reader_cannot_compute():
    """An analysis that was not asked for an extra says so when it is read; it never solves it."""
    from flyopt.analysis import NotComputed, analyse
    from flyopt.io.scene import load
    from flyopt.pipeline import solve

    analysis = analyse(load(PROBLEMS / "motor-press.toml"))
    for read in (lambda: analysis.models, lambda: analysis.startup, analysis.speed_curve, lambda: analysis.textbook):
        with pytest.raises(NotComputed, match="was not computed"):
            read()
    solution = solve(load(PROBLEMS / "shear-press.toml"), design_flywheel=False, extras=())
    with pytest.raises(NotComputed, match="Solution.inertia_curve"):
        _ = solution.inertia_curve
    with pytest.raises(ValueError, match="unknown extras"):
        solve(load(PROBLEMS / "shear-press.toml"), extras=("speeds",))
