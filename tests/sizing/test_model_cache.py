"""The periodic model's CasADi functions are built once per machine and shared (issue 11, item 5)."""

import gc
import math
import weakref

import casadi as ca
import numpy as np
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
    periodic_model._COMPILED.clear()  # and so are the CVODES functions and the cycles they integrated
    periodic_model._CYCLES.clear()
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


def test_machines_reduced_apart_share_the_cvodes_functions_and_their_cycles(write_scene):
    """A machine reduced twice (the drive's verification and its analysis) builds CVODES once and
    integrates a cycle once; a machine of the same structure with other table values, or the same
    inputs at another flywheel, is integrated afresh and gives its own numbers."""
    text = (PROBLEMS / "motor-press.toml").read_text()
    scene = flyopt.load(PROBLEMS / "motor-press.toml")

    def model_of(machine):
        return periodic_model.periodic_model(
            machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.knots()
        )

    first, second = model_of(choose.reduce(scene)), model_of(choose.reduce(scene))
    assert first is not second and first.structure == second.structure
    periodic_model._COMPILED.clear()
    periodic_model._CYCLES.clear()
    periodic.BUILDS.clear()
    omega, j = scene.omega_mean, 50.0
    w_s = shooting.energy_swing(first, omega)
    e = 0.5 * (float(first.inertia(0.0)) + j) * omega**2
    a = first.shoot(j, e, w_s)
    cycle_a = first.trajectory(j, e, w_s)
    builds = dict(periodic.BUILDS)
    b = second.shoot(j, e, w_s)
    cycle_b = second.trajectory(j, e, w_s)
    assert dict(periodic.BUILDS) == builds == {"integrator": 1, "shooting function": 1, "cycle function": 1}
    assert a == b and np.array_equal(cycle_a[0], cycle_b[0]) and cycle_a[1] == cycle_b[1]
    cycle_b[0][:] = np.nan  # a caller's copy: the kept cycle is untouched
    assert np.array_equal(second.trajectory(j, e, w_s)[0], cycle_a[0])
    assert cycle_a[1] == 0.0 and np.ptp(cycle_a[0]) > 0.1  # a running machine, not stalled
    # another flywheel: integrated, not served
    assert first.shoot(1.1 * j, e, w_s) != a
    # the same structure, a heavier load (other table values): its own cycle
    heavier = model_of(
        choose.reduce(flyopt.load(write_scene(text.replace("[165, 9000], [180, 9000]", "[165, 9500], [180, 9500]"))))
    )
    assert heavier.structure == first.structure
    assert heavier.shoot(j, e, w_s) != a
    assert not np.array_equal(heavier.trajectory(j, e, w_s)[0], cycle_a[0])
    assert periodic.BUILDS["integrator"] == 1
