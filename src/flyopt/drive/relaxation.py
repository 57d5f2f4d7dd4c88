"""The drive's continuous relaxation: motor rating, ratios and flywheel in one CasADi NLP.

The catalogue's motor sizes are a ladder; the relaxation makes the rating P a
continuous variable whose rated slip, rotor inertia, breakdown ratio, mass and
price follow power laws fitted to the catalogue (least squares in log P). One
NLP (IPOPT) then chooses P, the motor ratio i = ω_motor/ω_crank, the flywheel
J_F at the crank, its shaft ratio r and its outer radius R, with the periodic
steady state of the machine by collocation over the cycle
(docs/flywheel-design.md, sections 7 and 14):

    E_k = ½ (J_e(φ_k) + J_rot(P) i² + J_F) ω_k²,
    E_{k+1} − E_k = h/2 [(i η M(i ω_k) − M_r(φ_k⁺)) + (i η M(i ω_{k+1}) − M_r(φ_{k+1}⁻))],

periodic (ω_N = ω_0), the nodes at every knot of the load table (its steps
taken from the side of each interval), M the Kloss curve of the motor. The
constraints:

- speed: every ω_k within ω_m (1 ± δ/2) (the scene's mean speed and δ);
- thermal: the RMS torque in time, ∫ M² dt / ∫ dt with dt = dφ/ω, at most
  the rated torque squared;
- breakdown: the motor never slows past its breakdown speed;
- start-up: the declutched run-up on the Kloss curve with the cycle-mean
  inertia, in closed form,
  t = J/(i² η) · ω_0/(2 M_b s_b) [(1 − s_e²)/2 + s_b² ln(1/s_e)],
  s_e = 1 − i ω_m/ω_0, at most ``max_startup``;
- the wheel: the designer's whole-wheel NLP (:func:`flyopt.design.wheel_nlp.formulate`,
  every dimension a variable, every row of the structure: inertia, envelope,
  width, H/B, walls, hub, and the rim speed or the stress of every part) on
  the flywheel shaft, whose speed r ω_max is a variable here; its inertia
  there times r² at least J_F. Each part's allowable is the material's
  strongest (its strength table's thinnest row) and the hub and arms carry
  no torque, so for the same J_F and r its wheel is never heavier than the
  designer's (and is the same where the allowable does not depend on the wall).

The objective is the motor's mass (or price) plus the wheel's mass (or cost).
It is a relaxation: it locates the motor size; :func:`flyopt.drive.codesign.design_drive`
then solves the catalogue sizes around it exactly (periodic shooting, the
wheel designer) and ranks them.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.errors import SolverFailed
from flyopt.machine.motor import kloss_torque
from flyopt.sizing._numerics import quiet
from flyopt.sizing.startup import kloss_runup_time

if TYPE_CHECKING:
    from collections.abc import Iterable

    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec
    from flyopt.design.wheel_nlp import WheelProblem, WheelStructure
    from flyopt.io.drive import DriveSpec
    from flyopt.machine.catalogue import CatalogueMotor
    from flyopt.machine.motor import InductionMotor
    from flyopt.machine.reduce import Machine
#: Collocation intervals over the cycle (plus one node at every knot).
NODES = 240

#: IPOPT statuses accepted as a solution.
_ACCEPTED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")


@dataclass(frozen=True)
class CatalogueFit:
    """Power laws of a catalogue's sizes in the rating P [W]: y = exp(a + b ln P) (``breakdown``: a + b ln P)."""

    synchronous_speed: float
    p_min: float
    p_max: float
    slip: tuple[float, float]  # (a, b) of each power law
    rotor_inertia: tuple[float, float]
    breakdown: tuple[float, float]
    mass: tuple[float, float] | None
    price: tuple[float, float] | None

    @classmethod
    def of(cls, motors: Iterable[CatalogueMotor]) -> CatalogueFit | None:
        """Fit a catalogue (at least three sizes of one synchronous speed), or None when it cannot be."""
        motors = list(motors)
        speeds = {round(m.synchronous_speed, 9) for m in motors}
        if len(motors) < 3 or len(speeds) != 1:
            return None
        x = np.log([m.rated_power for m in motors])

        def power_law(values):
            if any(v is None or not v > 0 for v in values):
                return None
            b, a = np.polyfit(x, np.log(values), 1)
            return float(a), float(b)

        slips = [(m.synchronous_speed - m.rated_speed) / m.synchronous_speed for m in motors]
        k = [m.motor().breakdown_ratio for m in motors]  # the motor's own, or the documented default
        b, a = np.polyfit(x, k, 1)
        return cls(
            synchronous_speed=motors[0].synchronous_speed,
            p_min=float(min(m.rated_power for m in motors)),
            p_max=float(max(m.rated_power for m in motors)),
            slip=power_law(slips),
            rotor_inertia=power_law([m.rotor_inertia for m in motors]),
            breakdown=(float(a), float(b)),
            mass=power_law([getattr(m, "mass", None) for m in motors]),
            price=power_law([getattr(m, "price", None) for m in motors]),
        )

    def motor(self, power: float) -> tuple[InductionMotor, float, float | None]:
        """The relaxed motor of rating ``power`` [W]: (InductionMotor, rotor inertia [kg*m^2], mass [kg] or None)."""
        from flyopt.machine.motor import InductionMotor

        lnp = math.log(power)
        slip = float(_law(self.slip, lnp, np))
        k = self.breakdown[0] + self.breakdown[1] * lnp
        motor = InductionMotor(power, self.synchronous_speed * (1 - slip), self.synchronous_speed, k)
        mass = None if self.mass is None else float(_law(self.mass, lnp, np))
        return motor, float(_law(self.rotor_inertia, lnp, np)), mass


@dataclass(frozen=True)
class Relaxation:
    """The relaxed optimum: rating [W], ratios [-], flywheel at the crank [kg*m^2], status, and its wheel
    (``wheel_mass`` [kg], ``d_outer`` [m] and ``wheel``, its material and arm count).

    ``sensitivities``: d(objective)/d(limit) of the relaxed optimum, in the
    objective's unit (kg, or currency) per SI unit of each limit: ``max_startup``
    [s], ``rim_speed`` (the material's safe rim speed) [m/s], ``ratio_max`` and
    ``ratio_min`` (the flywheel shaft's range) [-], ``max_outer_diameter`` [m],
    ``delta`` [-]; zero where the limit does not bind.
    """

    rated_power: float
    motor_ratio: float
    flywheel_ratio: float
    j_flywheel: float
    objective: float
    status: str
    sensitivities: dict[str, float] = field(default_factory=dict)
    wheel_mass: float | None = None
    d_outer: float | None = None
    wheel: str = ""

    #: The SI unit of each limit a sensitivity is taken per.
    LIMIT_UNITS = {
        "delta": "-",
        "max_startup": "s",
        "rim_speed": "m/s",
        "ratio_max": "-",
        "ratio_min": "-",
        "max_outer_diameter": "m",
    }

    def to_dict(self) -> dict[str, Any]:
        """The relaxation for JSON: its sensitivities a list of entries (limit, its unit, d objective / d limit),
        as a design's are (their names are quantities of their own elsewhere in a document)."""
        out = {("j_required" if k == "j_flywheel" else k): v for k, v in self.__dict__.items() if k != "sensitivities"}
        out["sensitivities"] = [
            {"limit": name, "unit": self.LIMIT_UNITS[name], "dobjective_dlimit": value}
            for name, value in self.sensitivities.items()
        ]
        return out


def _law(fit, lnp, ca):
    a, b = fit
    return ca.exp(a + b * lnp)


#: Builds of the relaxation's NLP (a test checks that a second solve on the same machine builds none).
BUILDS = {"count": 0}

#: The smallest dimension of the relaxation's wheel [m]: where the drive needs no flywheel its wheel
#: shrinks toward nothing, and its dimensions (logarithms in the NLP) stop here instead of at -inf.
MIN_DIMENSION = 1e-4


@dataclass(frozen=True)
class RelaxedWheel:
    """The wheel of the relaxation: the whole-wheel NLP's structure and limits for one material.

    ``problem`` is the :class:`flyopt.design.wheel_nlp.WheelProblem` the
    designer would solve (:func:`flyopt.design.wheel_design.wheel_problem`),
    with the material's strongest allowable stress on every part and no
    torque on the hub or arms; its inertia and shaft speed are the drive's
    variables. ``v_max``: the material's safe rim speed [m/s] (used under
    the rim-speed criterion); ``cost_per_kg``: its cost, or None.
    """

    structure: WheelStructure
    problem: WheelProblem
    v_max: float
    cost_per_kg: float | None
    label: str

    @classmethod
    def of(cls, material: Material, spec: DesignSpec, bore: float = 0.0, n_arms: int = 0) -> RelaxedWheel:
        """The relaxed wheel of a material under a design spec, on a seat of diameter ``bore`` [m]."""
        from flyopt.design.designer import rim_speed_limit
        from flyopt.design.wheel_design import strongest_allowables, wheel_problem

        v_max = rim_speed_limit(material, spec)
        structure, problem = wheel_problem(material, spec, bore, 0.0, n_arms, 1.0, 1.0, v_max)
        structure = structure._replace(objective="mass")
        problem = dataclasses.replace(problem, allowable=strongest_allowables(material, spec, structure))
        label = material.name + (f", {n_arms} arms" if n_arms else "")
        return cls(structure, problem, v_max, material.cost, label)


@dataclass(frozen=True)
class _Model:
    """The relaxation's NLP for one machine, catalogue fit and structure; its limits are parameters."""

    solver: object
    values: object  # x, par -> (P, i, r, J_F, objective, wheel mass, wheel outer diameter)
    n: int  # collocation intervals
    rows: tuple[int, ...]  # row sizes, in order
    wheel_rows: tuple[str, ...]  # names of the wheel's rows, in order (they come last)
    wheel_names: tuple[str, ...]  # the wheel's variables
    scale: float  # of the objective
    extra_lo: tuple[float, ...]
    extra_hi: tuple[float, ...]
    extra_x0: tuple[float, ...]
    lbg: np.ndarray  # without the wheel's rows
    ubg: np.ndarray


def _model(machine, omega_mean, efficiency, fit, thermal, startup, objective_name, load_torque, structure):
    """The relaxation's NLP, built once per machine and structure (kept in the machine's cache).

    Parameters of the NLP: ``par`` = (δ, cost per kg, max_startup [s], J scale [kg*m^2], density,
    Poisson's ratio, torque, bore, stress scale, the allowables of the wheel's parts).
    """
    key = (
        "drive_relaxation",
        fit,
        float(omega_mean),
        float(efficiency),
        bool(thermal),
        bool(startup),
        objective_name,
        float(load_torque),
        structure,
    )

    def build() -> _Model:
        BUILDS["count"] += 1
        return _build(machine, omega_mean, efficiency, fit, thermal, startup, objective_name, load_torque, structure)

    return machine.memo(key, build)


#: The wheel's parameters in the relaxation, after (δ, cost per kg, max_startup, J scale).
_WHEEL_PARAMETERS = ("density", "poisson", "torque", "bore", "stress_scale")


def _build(machine, omega_mean, efficiency, fit, thermal, startup, objective_name, load_torque, structure):
    import casadi as ca

    from flyopt.design import wheel_nlp
    from flyopt.design.nlp import QUIET_IPOPT

    cycle = machine.cycle_angle
    resisting = machine.angle_only().resisting
    knots = np.asarray(machine.knots(), dtype=float)
    phi = np.union1d(np.linspace(0.0, cycle, NODES + 1), knots[(knots > 0) & (knots < cycle)])
    left, right = resisting.limits(phi)  # M_r(φ⁻), M_r(φ⁺)
    j_e = machine.j_machine(phi) if machine.variable_inertia else np.full(phi.shape, float(machine.j_machine))
    h = np.diff(phi)
    n = len(phi) - 1  # intervals; node n is node 0 again
    w0 = fit.synchronous_speed

    lnp, i_m, jf, r = (ca.SX.sym(name) for name in ("lnp", "i_m", "jf", "r"))
    wheel_names = wheel_nlp.variables_of(structure)
    x_wheel = ca.SX.sym("wheel", len(wheel_names))
    w = ca.SX.sym("w", n)  # ω_k / ω_m, k = 0..n-1
    n_allow = len(wheel_nlp.stressed_parts(structure))
    par = ca.SX.sym("par", 4 + len(_WHEEL_PARAMETERS) + n_allow)
    delta, cost_per_kg, t_max, j_scale = (par[k] for k in range(4))  # J_F = j_scale * jf
    rows = []  # (expression, lower, upper)

    p = ca.exp(lnp)
    s_n = _law(fit.slip, lnp, ca)
    j_rot = _law(fit.rotor_inertia, lnp, ca)
    k = fit.breakdown[0] + fit.breakdown[1] * lnp
    w_n = w0 * (1 - s_n)
    m_n = p / w_n
    s_b = s_n * (k + ca.sqrt(k * k - 1))

    def motor(speed):  # Kloss torque at the motor shaft
        return kloss_torque(speed, w0, k * m_n, s_b)

    omega = omega_mean * ca.vertcat(w, w[0])
    j_f = j_scale * jf
    energy = 0.5 * (ca.DM(j_e) + j_rot * i_m**2 + j_f) * omega**2
    m_motor = motor(i_m * omega)
    net_a = i_m * efficiency * m_motor[:-1] - ca.DM(right[:-1])
    net_b = i_m * efficiency * m_motor[1:] - ca.DM(left[1:])
    e_scale = 0.5 * j_scale * omega_mean**2 * delta
    rows.append(((energy[1:] - energy[:-1] - ca.DM(h) / 2 * (net_a + net_b)) / e_scale, 0.0, 0.0))
    rows.append((i_m * w - w0 * (1 - s_b) / omega_mean, 0.0, math.inf))  # above breakdown
    extra, extra_lo, extra_hi, extra_x0 = [], [], [], []
    sums = {}  # index in rows -> (terms, a symbol of their sum, its variable, the row): see _jacobian
    if thermal:
        # ∫M² dt and ∫dt as variables of their own: their ratio written directly would couple every node
        # in a dense Hessian
        squares, period = ca.SX.sym("squares"), ca.SX.sym("period")
        inv = 1.0 / omega
        t_scale = cycle / omega_mean
        m_scale = load_torque / (omega_mean * efficiency) * omega_mean / w0  # about the mean motor torque
        # two rows that add a term of every interval: dense rows, whose Jacobian is formed apart (_jacobian)
        for terms, extra_var, finish in (
            (
                ca.DM(h) / 2 * (m_motor[:-1] ** 2 * inv[:-1] + m_motor[1:] ** 2 * inv[1:]),
                squares,
                lambda total: total / (m_scale**2 * t_scale) - squares,
            ),
            (ca.DM(h) / 2 * (inv[:-1] + inv[1:]), period, lambda total: total / t_scale - period),
        ):
            total = ca.SX.sym("total")
            sums[len(rows)] = (terms, total, extra_var, finish(total))
            rows.append((finish(ca.sum1(terms)), 0.0, 0.0))
        rows.append((squares * m_scale**2 - m_n**2 * period, -math.inf, 0.0))
        extra += [squares, period]
        extra_lo += [0.0, 0.0]
        extra_hi += [math.inf, math.inf]
        extra_x0 += [1.0, 1.0]
    s_e = 1 - i_m * omega_mean / w0
    rows.append((s_e, 1e-6, math.inf))
    if startup:
        j_total = float(np.mean(j_e[:-1])) + j_rot * i_m**2 + j_f
        run = kloss_runup_time(j_total, i_m, efficiency, k * m_n, s_b, w0, omega_mean, ca)
        rows.append((run / t_max, -math.inf, 1.0))
    # the wheel: the designer's NLP rows (flyopt.design.wheel_nlp.formulate) on the flywheel shaft, whose speed
    # r ω_max is a variable here; its inertia there, times r², gives J_F at the crank
    shaft_omega = r * omega_mean * (1 + delta / 2)
    wheel_par = {name: par[4 + k] for k, name in enumerate(_WHEEL_PARAMETERS)}
    wheel_par.update(omega=shaft_omega, log_half_omega=ca.log(shaft_omega / 2))
    form = wheel_nlp.formulate(structure, x_wheel, wheel_par, par[4 + len(_WHEEL_PARAMETERS) :])
    wheel_rows = [
        (name, (form.inertia * r**2 - j_f) / j_scale) if name == "inertia" else (name, expr)
        for name, expr in zip(form.row_names, form.rows)
    ]
    if objective_name == "cost":
        objective = _law(fit.price, lnp, ca) + cost_per_kg * form.mass
        scale = float(_law(fit.price, math.log(fit.p_max), np))
    else:
        objective = _law(fit.mass, lnp, ca) + form.mass
        scale = float(_law(fit.mass, math.log(fit.p_max), np))
    x = ca.vertcat(lnp, i_m, jf, r, x_wheel, w, *extra)
    parts = [row[0] for row in rows] + [expr for _, expr in wheel_rows]
    g = ca.vertcat(*parts)
    jac_g = ca.Function("nlp_jac_g", [x, par], [g, _jacobian(parts, sums, x)], ["x", "p"], ["g", "jac_g_x"])
    solver = ca.nlpsol(
        "drive",
        "ipopt",
        {"x": x, "p": par, "f": objective / scale, "g": g},
        {
            **QUIET_IPOPT,
            "ipopt.max_iter": 3000,
            "ipopt.tol": 1e-10,
            "jac_g": jac_g,
        },
    )
    values = ca.Function("values", [x, par], [p, i_m, r, j_f, objective, form.mass, form.dims.d_outer])
    return _Model(
        solver=solver,
        values=values,
        n=n,
        rows=tuple(row[0].shape[0] for row in rows),
        wheel_rows=tuple(name for name, _ in wheel_rows),
        wheel_names=tuple(wheel_names),
        scale=scale,
        extra_lo=tuple(extra_lo),
        extra_hi=tuple(extra_hi),
        extra_x0=tuple(extra_x0),
        lbg=np.concatenate([np.full(row[0].shape[0], row[1]) for row in rows]),
        ubg=np.concatenate([np.full(row[0].shape[0], row[2]) for row in rows]),
    )


def _jacobian(parts, sums, x):
    """The constraints' Jacobian, the same numbers as CasADi's own, formed without its cost of dense rows.

    CasADi colours the Jacobian's columns and differentiates forward, one
    sweep of the whole graph per colour; a row that adds a term of every
    interval (the RMS torque's integrals) shares a column with every other,
    so every column took a colour of its own (a sweep per variable, ~0.3 s).
    Here the other rows are differentiated as CasADi would (forward, their own
    colouring: a few sweeps), and a dense row in two steps of the same forward
    rules: its terms (a few sweeps), then the sum of them with those
    derivatives as seeds (a sweep of the sum per variable, a few operations
    each). Every entry is the same expression as CasADi's own, so the NLP, and
    IPOPT's path, are unchanged (a test compares the two bit for bit).

    Parameters
    ----------
    parts : list of SX
        The constraints' blocks, in order.
    sums : dict
        Index of a dense block -> (its terms, a symbol for their sum, the one variable the block
        holds besides the terms, the block as a function of the two).
    x : SX
        The variables.
    """
    import casadi as ca

    forward = {"allow_reverse": False}
    blocks, plain = [], []
    n = x.shape[0]
    for k, part in enumerate(parts):
        if k not in sums:
            plain.append(part)
            continue
        if plain:
            blocks.append(ca.jacobian(ca.vertcat(*plain), x, forward))
            plain = []
        terms, total, var, row = sums[k]
        finish = ca.Function("finish", [total, var], [row]).forward(n)
        d_total = ca.sum1(ca.jacobian(terms, x, forward))  # the sum's forward derivatives: its terms' in order
        blocks.append(ca.sparsify(finish(ca.sum1(terms), var, part, d_total, ca.jacobian(var, x))))
    if plain:
        blocks.append(ca.jacobian(ca.vertcat(*plain), x, forward))
    return ca.vertcat(*blocks)


def relax(
    machine: Machine,
    omega_mean: float,
    delta: float,
    efficiency: float,
    fit: CatalogueFit,
    spec: DriveSpec,
    wheel: RelaxedWheel,
    load_torque: float,
) -> Relaxation:
    """Solve the relaxation (:class:`Relaxation`).

    The NLP is built once per machine, catalogue fit and structure (thermal,
    start-up, objective, the wheel's structure); δ, the wheel's material and
    limits and ``max_startup`` enter as parameters and bounds, so another
    material or limit solves it again without building it.

    Parameters
    ----------
    machine : flyopt.machine.reduce.Machine
        The scene reduced (its resisting torque and J_e; the driving torque is the motor's).
    omega_mean, delta, efficiency : float
    fit : CatalogueFit
    spec : DriveSpec
    wheel : RelaxedWheel
    load_torque : float
        Mean load torque at the crank [N*m] (scales and the first guess).

    Raises
    ------
    SolverFailed
        IPOPT did not converge.
    """
    from flyopt.design import wheel_nlp

    structure, problem = wheel.structure, wheel.problem
    model = _model(
        machine,
        omega_mean,
        efficiency,
        fit,
        spec.thermal,
        spec.max_startup is not None,
        spec.objective,
        load_torque,
        structure,
    )
    n, w0 = model.n, fit.synchronous_speed
    j_scale = max(load_torque * machine.cycle_angle / (omega_mean**2 * delta), 1e-6)
    omega_top = omega_mean * (1 + delta / 2)
    lo, hi = spec.ratio_bounds()
    # the wheel: its variables' bounds and rows' bounds as the designer's (the inertia row: J r² >= J_F, written
    # as a difference), every dimension at least MIN_DIMENSION
    floor = math.log(MIN_DIMENSION)
    w_lo, w_hi, _ = wheel_nlp.variable_bounds(structure, problem)
    w_lo = [max(v, floor) for v in w_lo]
    g_lo, g_hi = wheel_nlp.row_bounds(structure, model.wheel_rows, dataclasses.replace(problem, j_shaft=1.0))
    inertia = model.wheel_rows.index("inertia")
    g_lo[inertia], g_hi[inertia] = 0.0, math.inf
    start = wheel_nlp.starting_wheel(
        structure, dataclasses.replace(problem, j_shaft=j_scale / hi**2, omega=hi * omega_top), model.wheel_names
    )
    w_x0 = [
        min(max(math.log(max(start[name], MIN_DIMENSION)), a), b) for name, a, b in zip(model.wheel_names, w_lo, w_hi)
    ]
    stress_scale = problem.density * (hi * omega_top * start["d_outer"] / 2) ** 2
    allow = wheel_nlp.allowable_parameters(structure, problem.allowable, stress_scale)
    par = [
        delta,
        wheel.cost_per_kg or 0.0,
        spec.max_startup or 1.0,
        j_scale,
        problem.density,
        problem.poisson,
        problem.torque,
        problem.bore,
        stress_scale,
    ] + allow
    nw = len(model.wheel_names)
    lbx = [math.log(fit.p_min), 1e-9, 0.0, lo] + w_lo + [1 - delta / 2] * n + list(model.extra_lo)
    ubx = [math.log(fit.p_max), math.inf, math.inf, hi] + w_hi + [1 + delta / 2] * n + list(model.extra_hi)
    # first guess: twice the mean power, the ratio of the work balance, a flywheel of the energy method
    p0 = min(max(2 * load_torque * omega_mean / efficiency, fit.p_min), fit.p_max)
    sn0 = float(_law(fit.slip, math.log(p0), np))
    x0 = [math.log(p0), w0 * (1 - 0.5 * sn0) / omega_mean, 1.0, hi] + w_x0 + [1.0] * n + list(model.extra_x0)
    solver = model.solver
    try:
        with quiet():
            found = solver(
                x0=x0,
                p=par,
                lbx=lbx,
                ubx=ubx,
                lbg=np.concatenate([model.lbg, g_lo]),
                ubg=np.concatenate([model.ubg, g_hi]),
            )
    except RuntimeError as err:
        raise SolverFailed(f"the drive's relaxation did not converge: {err}") from None
    status = solver.stats()["return_status"]
    if status not in _ACCEPTED:
        raise SolverFailed(f"the drive's relaxation did not converge: {status}")
    p, i_m, r, j_f, objective, wheel_mass, d_outer = (float(v) for v in model.values(found["x"], par))
    # d(objective)/d(limit) from the multipliers: CasADi's lam_x, lam_g are those of the Lagrangian
    # f + lam' g, so d f*/d ubx = -lam_x where lam_x > 0, d f*/d lbx = -lam_x where lam_x < 0, likewise
    # for a row's bounds, and lam_p = -d f*/d p; times the objective's scale
    lam_x = np.asarray(found["lam_x"]).ravel() * model.scale
    lam_g = np.asarray(found["lam_g"]).ravel() * model.scale
    lam_p = np.asarray(found["lam_p"]).ravel() * model.scale
    wheel_lam = dict(zip(model.wheel_rows, lam_g[sum(model.rows) :]))
    sens = {}
    if spec.max_startup is not None:
        sens["max_startup"] = -lam_p[2]
    if "rim_speed" in wheel_lam:
        sens["rim_speed"] = -wheel_lam["rim_speed"] / wheel.v_max
    if spec.ratios is None:
        sens["ratio_max"] = -max(lam_x[3], 0.0)
        sens["ratio_min"] = -min(lam_x[3], 0.0)
    if "max_outer_diameter" in wheel_lam:
        sens["max_outer_diameter"] = -wheel_lam["max_outer_diameter"] / problem.envelope
    lam_w = lam_x[4 + nw : 4 + nw + n]
    sens["delta"] = -0.5 * float(np.sum(np.abs(lam_w))) - lam_p[0]
    return Relaxation(
        rated_power=p,
        motor_ratio=i_m,
        flywheel_ratio=r,
        j_flywheel=j_f,
        objective=objective,
        status=status,
        sensitivities={k: float(v) for k, v in sens.items()},
        wheel_mass=wheel_mass,
        d_outer=d_outer,
        wheel=wheel.label,
    )
