"""The analysis pipeline: scene → cycle → required inertia → result.

Reads like the domain page: solve an unknown constant torque from the work
balance, build the energy indicator diagram, take A_max, size the flywheel
by J_F = A_max/(ω_m² δ) − J_c, and move it to every shaft by the
ratio-squared transfer.
"""

from dataclasses import dataclass

from .cycle import energy_indicator, energy_indicator_from_areas, required_inertia
from .errors import NonPeriodicCycle, SceneError
from .transmission import inertia_on_shaft
from .units import gd2_from_inertia

MODEL_ENERGY = "energy"


@dataclass(frozen=True)
class ShaftRequirement:
    """The required flywheel on one shaft."""

    name: str
    speed_ratio: float      # ω_shaft/ω_reference [-]
    omega: float            # mean speed of the shaft [rad/s]
    efficiency: float       # from the motor to this shaft [-]
    j_required: float       # [kg*m^2], 0 when no flywheel is needed
    gd2_required: float     # [N*m^2]

    def to_dict(self):
        return dict(self.__dict__)


@dataclass(frozen=True)
class Analysis:
    """Result of the cycle analysis of a scene (all SI).

    ``j_required`` is the flywheel inertia at the reference shaft, 0 when the
    machine's own inertia suffices (``flywheel_needed`` False; ``j_margin``
    then tells by how much it suffices, as a negative number).
    """

    title: str
    model: str
    omega_mean: float
    delta: float
    cycle_angle: float
    j_constant: float
    a_max: float
    work_per_cycle: float | None
    driving_torque: float | None
    resisting_torque: float | None
    power: float | None
    efficiency: float
    motor_power: float | None
    omega_max: float
    omega_min: float
    angle_omega_max: float | None
    angle_omega_min: float | None
    index_omega_max: int
    index_omega_min: int
    j_margin: float
    j_required: float
    gd2_required: float
    flywheel_needed: bool
    energy_chain: tuple
    shafts: tuple
    indicator: object = None

    def to_dict(self):
        """Plain JSON-ready dictionary, every number in SI."""
        out = {k: v for k, v in self.__dict__.items() if k not in ("indicator", "shafts", "energy_chain")}
        out["energy_chain"] = [dict(e) for e in self.energy_chain]
        out["shafts"] = [s.to_dict() for s in self.shafts]
        return out


def analyse(scene):
    """Analyse a scene's cycle and size the flywheel it needs.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    Analysis

    Raises
    ------
    NonPeriodicCycle
        The cycle's work does not balance.
    """
    try:
        return _analyse(scene)
    except (SceneError, NonPeriodicCycle) as err:
        raise err.with_source(scene.source) from None


def _analyse(scene):
    if scene.net is not None:
        ind = energy_indicator_from_areas(scene.net.energies, scene.cycle_angle)
        work = driving = resisting = power = motor_power = None
        chain = tuple({"index": k, "angle": None, "delta_e": float(e)} for k, e in enumerate(ind.chain_delta_e))
    else:
        ind = energy_indicator(scene.driving, scene.resisting, scene.cycle_angle)
        work, driving, resisting = ind.work_driving, ind.driving_mean, ind.resisting_mean
        power = driving * scene.omega_mean
        motor_power = power / scene.efficiency
        chain = tuple({"index": k, "angle": float(a), "delta_e": float(e)}
                      for k, (a, e) in enumerate(zip(ind.chain_angle, ind.chain_delta_e)))
    j_margin = required_inertia(ind.a_max, scene.omega_mean, scene.delta, scene.j_constant)
    needed = j_margin > 0
    j_req = j_margin if needed else 0.0
    shafts = tuple(ShaftRequirement(
        name=s.name, speed_ratio=s.speed_ratio, omega=s.speed_ratio * scene.omega_mean,
        efficiency=s.efficiency, j_required=inertia_on_shaft(j_req, s.speed_ratio),
        gd2_required=gd2_from_inertia(inertia_on_shaft(j_req, s.speed_ratio))) for s in scene.shafts)
    return Analysis(
        title=scene.title, model=MODEL_ENERGY, omega_mean=scene.omega_mean, delta=scene.delta,
        cycle_angle=scene.cycle_angle, j_constant=scene.j_constant, a_max=ind.a_max,
        work_per_cycle=work, driving_torque=driving, resisting_torque=resisting, power=power,
        efficiency=scene.efficiency, motor_power=motor_power,
        omega_max=scene.omega_mean * (1 + scene.delta / 2), omega_min=scene.omega_mean * (1 - scene.delta / 2),
        angle_omega_max=ind.angle_omega_max, angle_omega_min=ind.angle_omega_min,
        index_omega_max=ind.index_max, index_omega_min=ind.index_min,
        j_margin=j_margin, j_required=j_req, gd2_required=gd2_from_inertia(j_req), flywheel_needed=needed,
        energy_chain=chain, shafts=shafts, indicator=ind)
