"""A motor press whose flywheel is set by a stall: the search is bounded, and its answer checked independently.

The scene (from an audit of 36 Kloss-motor presses): a 5 kW induction motor on its Kloss curve drives a crank
24 times slower against a load pulse of 4300 N*m that its breakdown torque (1273 N*m at the crank) cannot
carry; the flywheel must carry the pulse. Below about 217.5 kg*m^2 no periodic steady state exists (the motor
breaks down and the machine stalls), and there δ is about 0.50, below the allowed 0.6: the flywheel is set by
the stall. Before: the solve took 2,225 s. CVODES's sensitivities of a cycle that grazes zero energy (the
speed falling to nothing at the cycle's end) shrank their steps to the limit, 10 s a shot, on the many shots
that locate the edge of the stall; each flywheel the search tried computed sensitivities it never read; each
trial started from the orbit's mean speed, not its speed where the energy is asked for, and missed the narrow
band where it gains; the search bisected toward the stall limit; and the δ sensitivity solved it all twice
more, to difference the stall limit's own tolerance into a slope.
"""

import math
import types
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import flyopt
from flyopt.delta_curve import inertia_curve
from flyopt.machine.reduce import reduce
from flyopt.report.card import solution_card
from flyopt.report.plots.inertia_delta import plot_inertia_delta
from flyopt.report.text import answer_report
from flyopt.sizing import periodic
from flyopt.sizing.periodic import FOLD_AIM, STALL_RTOL, _toward_fold
from flyopt.sizing.periodic_model import periodic_model
from flyopt.sizing.shooting import NotSettled

DATA = Path(__file__).resolve().parents[1] / "data" / "stall"
SCENE = DATA / "press-pulse-expression.toml"
WEAK = DATA / "weak-dc-motor.toml"

RATIO, J_MACHINE = 24.0, 5.0


def crank_torque(omega, phi):
    """M_d − M_r at the crank [N*m], written here from the textbook laws (not flyopt's): the Kloss curve
    M = 2 M_b / (s/s_b + s_b/s), M_b = 1.6 P/ω_n, s_b = s_n (k + √(k² − 1)), times the ratio."""
    w_s, w_n = 1500 * math.pi / 30, 1440 * math.pi / 30
    s_n, k = 1 - w_n / w_s, 1.6
    m_b, s_b = k * 5000.0 / w_n, s_n * (k + math.sqrt(k * k - 1))
    s = 1 - RATIO * omega / w_s
    motor = 2 * m_b / (s / s_b + s_b / s) if s != 0 else 0.0
    return RATIO * motor - (300 + 4000 * max(0.0, math.sin(phi)) ** 6)


def test_a_shot_that_grazes_zero_energy_returns_at_once():
    # The flywheel the energy method asks for (114 kg*m^2) stalls from every speed; the search for a
    # steady state shoots ever closer to the energy below which the cycle ends at zero speed. Just below it
    # the energy dips under zero by a few joules at the cycle's end: CVODES gave up there with
    # CV_TOO_MUCH_WORK after 200,000 steps (10 s a shot). Now the torques are read at no less than 1e-6 of
    # the cycle's starting speed, and the shot returns its stall.
    machine = reduce(flyopt.load(SCENE))
    model = periodic_model(machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.knots())
    j_f, w_s = 114.05316741246244, model.work_scale(2 * math.pi)

    def stalls(e):
        return model.trajectory(j_f, e, w_s)[1] > 0

    low, high = 5000.0, 5014.04  # a stall, and a cycle that ends above zero energy
    assert stalls(low) and not stalls(high)
    for _ in range(60):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if stalls(middle) else (low, middle)
    for below in (0.4, 0.1, 0.02, 0.005):  # the energies CVODES gave up on: 0.4-0.01 J below the edge
        y_end, stall, slope = model.shoot(j_f, low - below, w_s)
        assert stall > 0
        assert math.isfinite(slope)
        # it lost all its energy: it ends at zero speed, within the tens of joules it dipped below it (27 J here)
        assert abs(low - below + w_s * y_end) < 50.0


def _sqrt_law(fold, a, b):
    return lambda u: a * math.sqrt(u - fold) + b * (u - fold)


@pytest.mark.parametrize("a, b", [(2.0, 0.0), (1.5, -3.0), (0.8, 4.0)])
def test_the_fold_is_estimated_from_three_flywheels_that_run(a, b):
    # Near a fold the stable orbit's 1 − m goes like a √(u − u*) + b (u − u*): three points of that law give u*
    # exactly, whatever a and b (the closed form is the test), to the root-finder's tolerance (1e-3 STALL_RTOL).
    tol = 1e-3 * STALL_RTOL
    fold = 5.4321
    law = _sqrt_law(fold, a, b)
    stable = [(u, law(u)) for u in (fold + 0.08, fold + 0.03, fold + 0.01)]
    lo, hi = fold - 0.05, stable[-1][0]
    aim, estimate = _toward_fold(lo, hi, stable, 0, None)
    assert estimate == pytest.approx(fold, abs=tol)
    # hi far above the fold: the trial aims above it (expected to run), at most halfway to hi
    assert estimate < aim <= 0.5 * (estimate + hi)
    # the estimate's change from the last one sets how far above: twice it, no closer than 2 FOLD_AIM
    aim, _ = _toward_fold(lo, hi, stable, 0, fold + 1e-3)
    assert aim == pytest.approx(fold + 2e-3, abs=3 * tol)
    # hi within 2 FOLD_AIM of STALL_RTOL above the fold: the trial aims FOLD_AIM below it (expected to stall)
    near = [*stable, (fold + 0.5 * FOLD_AIM * STALL_RTOL, law(fold + 0.5 * FOLD_AIM * STALL_RTOL))]
    aim, estimate = _toward_fold(lo, near[-1][0], near, 0, None)
    assert aim == pytest.approx(fold - FOLD_AIM * STALL_RTOL, abs=tol)
    # fewer than three points, or too many guided trials in a row: bisect
    assert _toward_fold(lo, hi, stable[:2], 0, None)[0] is None
    assert _toward_fold(lo, hi, stable, periodic.MAX_GUIDED, None)[0] is None


def test_a_fold_that_is_not_one_is_bisected():
    # A multiplier that does not tend to 1 (a torque that steps): no fold lies between lo and hi, and the
    # estimate leaves it to bisection
    stable = [(3.0, 0.5), (2.0, 0.5), (1.0, 0.5)]
    assert _toward_fold(0.5, 1.0, stable, 0, None)[0] is None


@pytest.mark.slow
def test_the_stall_limited_press_is_solved_once_and_checked_by_simulation(monkeypatch):
    """(~20 s) The whole solve: one search for the flywheel (the δ sensitivity is zero without solving it
    again), far fewer flywheels tried than bisection needs, and the limit checked by scipy's integration of
    the textbook laws: at 0.999 of the reported total inertia the speed collapses from the periodic state, at
    the reported one it stays on an orbit whose δ is flyopt's."""
    calls = []
    search = periodic.dynamic_requirement

    def counted(*args, **kwargs):
        calls.append(1)
        return search(*args, **kwargs)

    monkeypatch.setattr(periodic, "dynamic_requirement", counted)
    result = flyopt.solve(flyopt.load(SCENE))
    need = result.analysis.requirement.detail
    assert need.limit == "stall" and len(calls) == 1
    assert need.iterations <= 14  # bisection toward the limit took 17 flywheels
    assert need.solution.delta < 0.6
    (entry,) = [s for s in result.design.best.limits.sensitivities if s["limit"] == "delta"]
    assert entry["dmass_dlimit"] == 0.0 and "stall limit" in entry["sentence"]
    answer = "\n".join(answer_report(result))
    assert f"δ       allowed 0.6; δ {need.solution.delta:.4g} at the stall limit" in answer
    # the report's answer, the app's and a notebook's card: the flywheel is set by the stall
    verdict = solution_card(result).verdict
    assert "its inertia is the least with which the machine runs steadily (with less the drive stalls)" in verdict
    assert f"at δ = {need.solution.delta:.4g}" in verdict

    # the J_F–δ curve: at δ at or above the stall's the flywheel is the stall limit, without a search; below
    # it a search, which starts above the flywheels the first one found stalling (none of its trials stalls)
    scene, analysis = result.scene, result.analysis
    stalled = []
    periodic_solution = periodic._periodic

    def watched(model, j_f, guess):
        try:
            return periodic_solution(model, j_f, guess)
        except periodic.SolverFailed:
            stalled.append(j_f)
            raise

    monkeypatch.setattr(periodic, "_periodic", watched)
    calls.clear()
    deltas, j = inertia_curve(scene, analysis, [0.45, need.solution.delta, 0.55, 0.9])
    assert len(calls) == 1 and not stalled
    assert list(j[1:]) == [analysis.j_margin] * 3
    assert analysis.j_margin < j[0] < 1.2 * analysis.j_margin  # δ 0.45 asks for more, from just above the stall
    ax = plot_inertia_delta(scene, analysis, curve=(deltas, j))
    (line,) = [a for a in ax.lines if a.get_gid() == "delta_stall"]
    assert line.get_xdata()[0] == analysis.delta_reached
    assert "stall limit" in line.get_label()

    j_total = need.j_required + J_MACHINE
    omega0 = float(need.solution.omega[0])

    def rhs(_, state, j):
        phi, omega = state
        return [omega, crank_torque(omega, phi) / j]

    def run(j, omega, cycles):
        """(ω at each cycle's start, δ of the last cycle or None where the speed fell to 1 % of the orbit's),
        from φ = 0 at speed ``omega``; δ from the dense output at 20,001 instants of the last cycle."""
        starts, speeds = [omega], None
        state = [0.0, omega]

        def through(t, s, j):
            return s[0] - 2 * math.pi

        through.terminal, through.direction = True, 1

        def stopped(t, s, j):
            return s[1] - 0.01 * omega0

        stopped.terminal = True
        for _ in range(cycles):
            sol = solve_ivp(
                rhs,
                (0, 60),
                state,
                args=(j,),
                events=(through, stopped),
                rtol=1e-11,
                atol=1e-12,
                method="DOP853",
                dense_output=True,
            )
            if sol.t_events[1].size:
                return starts, None
            state = [0.0, float(sol.y_events[0][0][1])]
            starts.append(state[1])
            speeds = sol.sol(np.linspace(0.0, float(sol.t_events[0][0]), 20001))[1]
        return starts, (speeds.max() - speeds.min()) / (0.5 * (speeds.max() + speeds.min()))

    starts, delta = run(j_total, omega0, 3)
    assert delta is not None and abs(starts[-1] / omega0 - 1) < 1e-6
    assert delta == pytest.approx(need.solution.delta, rel=1e-4)
    collapsed, delta = run(0.999 * j_total, omega0, 400)
    assert delta is None, f"at 0.999 J the speed did not collapse in 400 cycles: {collapsed[-3:]}"


def _searched(monkeypatch, law, fold_at):
    """(requirement, trials) of the search on a stand-in for the periodic solution: no steady state below the
    total inertia ``fold_at`` [kg*m^2], above it ``law(x)`` = (δ, 1 − m) at x = u − u* (u the log of the total
    inertia). The press's machine gives the search its start; the one solve and the balance are withheld."""
    machine = reduce(flyopt.load(SCENE))
    j_low = float(machine.j_machine)
    trials = []

    def stand_in(model, j_f, guess):
        u = math.log(j_f + j_low)
        trials.append(u)
        if u < math.log(fold_at):
            raise periodic.SolverFailed("stalls")
        delta, gap = law(u - math.log(fold_at))
        return types.SimpleNamespace(delta=delta, multiplier=1 - gap, omega=np.array([6.0]), omega_mean=6.0)

    def refuse(*args, **kwargs):
        raise NotSettled("withheld")

    monkeypatch.setattr(periodic, "_one_solve", refuse)
    monkeypatch.setattr(periodic, "_held_by_balance", lambda *args, **kwargs: None)
    monkeypatch.setattr(periodic, "_periodic", stand_in)
    monkeypatch.setattr(periodic, "_as_fitted", lambda model, found, j_low: found)
    args = (machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.omega_mean, 0.6, machine.knots())
    return periodic.dynamic_requirement(*args), trials


@pytest.mark.parametrize("fold_at", [60.0, 222.5, 2000.0])
def test_the_search_closes_on_a_fold_in_fewer_trials_than_bisection(monkeypatch, fold_at):
    # a fold: 1 − m = 1.5 √x − 0.5 x, δ 0.5 − 0.1 √x below the allowed 0.6 everywhere: the limit is the stall
    def law(x):
        return 0.5 - 0.1 * math.sqrt(x), 1.5 * math.sqrt(x) - 0.5 * x

    found, trials = _searched(monkeypatch, law, fold_at)
    assert found.limit == "stall"
    assert 0 <= math.log(found.j_required + J_MACHINE) - math.log(fold_at) <= STALL_RTOL
    monkeypatch.setattr(periodic, "MAX_GUIDED", 0)  # bisection alone, as before
    bisected, by_halves = _searched(monkeypatch, law, fold_at)
    assert bisected.limit == "stall"
    assert len(trials) <= len(by_halves) - 4, (len(trials), len(by_halves))


@pytest.mark.parametrize(
    "law, above",
    [
        # a multiplier that stays below 1 at the limit (no fold), δ = 0.601 − 0.1 x: δ reaches 0.6 at x = 0.01
        (lambda x: (0.601 - 0.1 * x, 0.3 + 0.5 * x), 0.01),
        # a fold, δ = 0.62 − 0.1 √x: δ reaches 0.6 at x = 0.04
        (lambda x: (0.62 - 0.1 * math.sqrt(x), 1.5 * math.sqrt(x) - 0.5 * x), 0.04),
    ],
)
def test_a_delta_reached_just_above_a_stall_is_found_by_the_secant(monkeypatch, law, above):
    # δ reaches the allowed 0.6 a little above the stall: the secant on δ, not the fold's aim, finds it, in no
    # more trials than without the aim (the aim overrode the secant's step inside the bracket: 12 trials for 7)
    found, trials = _searched(monkeypatch, law, 222.5)
    assert found.limit == "delta"
    # the search holds log δ to 1e-10 (its rtol), so x to 1e-10 over |d log δ/dx| >= 0.17 here
    assert math.log(found.j_required + J_MACHINE) - math.log(222.5) == pytest.approx(above, abs=1e-9)
    monkeypatch.setattr(periodic, "MAX_GUIDED", 0)
    _, unguided = _searched(monkeypatch, law, 222.5)
    assert len(trials) <= len(unguided), (len(trials), len(unguided))


def _weak_best_work():
    """The closed form: at the crank M_d = 1920 (1 − ω/ω_0), ω_0 = 1600 rpm / 24; M_d − 1500 e^(−ω/3) is largest
    at ω* = 3 ln(500 ω_0/1920), where its slope is zero; the pulse's ∫ sin⁴ over its half turn is 3π/8.
    W = 2π (M_d(ω*) − 1500 e^(−ω*/3) − 300) − 2000 · 3π/8."""
    w0 = 1600 * math.pi / 30 / 24
    best = 3 * math.log(500 * w0 / 1920)  # d/dω (1920 (1 − ω/ω_0) − 1500 e^(−ω/3)) = 0
    top = 1920 * (1 - best / w0) - 1500 * math.exp(-best / 3)
    return 2 * math.pi * (top - 300) - 2000 * 3 * math.pi / 8


def test_the_drives_best_work_over_the_cycle_bounds_its_closed_form(monkeypatch):
    # No periodic state can exist where even each angle's most favourable torque does not balance the cycle:
    # W = ∮ max_ω M dφ < 0 (−460 J here). flyopt's grid of speeds (step Δω) with its slope margin bounds the
    # closed form from above (a bound must not miss the best speed), by no more than the margin, half a step
    # times a slope within two steps of the best speed: 2π Δω² max|M''| over the turn (M'' = 1500/9 e^(−ω/3)).
    machine = reduce(flyopt.load(WEAK))
    model = periodic_model(machine.net_torque(), machine.j_machine, machine.cycle_angle, machine.knots())
    work, (low, top) = periodic._best_work(model, 2 * math.pi)
    exact = _weak_best_work()
    assert exact < -450 and (low, top) == (0.0, 8 * math.pi)
    step = top / (periodic.RUN_SPEEDS - 1)
    assert exact <= work <= exact + 2 * math.pi * step**2 * 1500 / 9, (work, exact)
    # read a few pieces at a time (a long table's grid), the same work
    monkeypatch.setattr(periodic, "BEST_WORK_VALUES", 3 * model.inner_angles.shape[1] * periodic.RUN_SPEEDS)
    assert periodic._best_work(model, 2 * math.pi)[0] == pytest.approx(work, rel=1e-14)


@pytest.mark.slow
def test_a_drive_too_weak_at_any_speed_is_refused_at_once():
    """(~4 s) It took 80 flywheels up to 1e36 kg*m^2 (1,620 s) and said only that none was found."""
    with pytest.raises(periodic.SolverFailed, match=r"no flywheel gives a periodic steady state: .* J short"):
        flyopt.analyse(flyopt.load(WEAK))
