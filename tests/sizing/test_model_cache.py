"""The periodic model's CasADi functions are built once per machine and shared (issue 11, item 5)."""

import gc
import math
import weakref

import casadi as ca
from conftest import PROBLEMS

import flyopt
from flyopt.sizing import choose, periodic, periodic_model, shooting


def test_one_solve_verify_of_the_motor_press_builds_each_structure_once():
    """One ``solve --verify`` of problems/motor-press.toml sizes the flywheel with the periodic
    model, compares the energy method's flywheel on it and verifies the design on it: one
    machine, one model. The declutched run-up (the motor's Kloss curve against the constant
    inertia alone) is in closed form and builds nothing. The flywheel
    is found by the one Newton solve: its fixed-step cycle at one step per grid interval and
    the check at two (two structures); CVODES simulates the comparison and the verification."""
    periodic.BUILDS.clear()
    shooting._STRUCTURES.clear()  # from cold: the fixed-step functions are shared by structure
    solution = flyopt.solve(flyopt.load(PROBLEMS / "motor-press.toml"), verify_design=True)
    out = solution.to_dict()  # all that `solve --verify --json` prints: comparison and run-up included
    assert out["verification"] is not None and out["model"] == "dynamic"
    assert out["startup"]["time"] > 0 and len(out["models"]) == 2
    assert dict(periodic.BUILDS) == {
        "periodic model": 1,
        "integrator": 1,
        "shooting function": 1,
        "cycle function": 1,
        "fixed-step function": 2,
    }


def test_machines_of_one_structure_share_the_compiled_one_solve(write_scene):
    """The one-solve's compiled steps depend on the torque law and the inertia, not on the
    machine object nor on a table's values: a second reduction of the scene, the same press
    at another δ and with a heavier load build nothing again; another motor builds its own."""
    text = (PROBLEMS / "motor-press.toml").read_text()
    scene = flyopt.load(PROBLEMS / "motor-press.toml")
    flyopt.solve(scene, extras=())
    periodic.BUILDS.clear()
    flyopt.solve(flyopt.load(PROBLEMS / "motor-press.toml"), extras=())
    flyopt.solve(scene.replace(delta=0.05), extras=())
    flyopt.solve(
        flyopt.load(write_scene(text.replace("[165, 9000], [180, 9000]", "[165, 9500], [180, 9500]"))), extras=()
    )
    assert periodic.BUILDS["fixed-step function"] == 0 and periodic.BUILDS["periodic model"] == 3
    flyopt.solve(flyopt.load(write_scene(text.replace('rated_power = "5.5 kW"', 'rated_power = "7.5 kW"'))), extras=())
    assert periodic.BUILDS["fixed-step function"] >= 1


def test_a_machine_keeps_one_model_for_as_long_as_it_lives():
    """Every run on one machine gets the same model; a second machine of the same scene gets
    its own; a machine that is gone takes its model with it (the cache holds no machine)."""
    scene = flyopt.load(PROBLEMS / "motor-press.toml")
    machine = choose.reduce(scene)
    assert machine.net_torque() is machine.net_torque()

    def model_of(m):
        return periodic_model.periodic_model(m.net_torque(), m.j_machine, m.cycle_angle, m.knots())

    first = model_of(machine)
    assert model_of(machine) is first
    other = choose.reduce(scene)
    assert model_of(other) is not first
    torques = [weakref.ref(machine.net_torque()), weakref.ref(other.net_torque())]
    del machine, first, other
    gc.collect()
    assert [ref() for ref in torques] == [None, None]  # so their entries have left the cache


def test_the_same_torque_callable_is_built_once():
    """A caller that passes the same net torque again (a sweep over flywheels) reuses the model."""

    def net(phi, omega):
        return 10.0 * ca.sin(phi)

    periodic.BUILDS.clear()
    for j_flywheel in (0.5, 1.0, 2.0):
        periodic.periodic_solution(net, 1.0, 2 * math.pi, 50.0, j_flywheel)
    assert periodic.BUILDS["periodic model"] == 1
    assert periodic.BUILDS["cycle function"] == 1
