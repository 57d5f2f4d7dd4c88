"""Presses and shears from their process data: the cycle a flywheel regulates.

A press is specified by its process (strokes per minute, the energy of one
stroke, how long the working stroke takes, how far the flywheel may slow
down), not by a torque curve. This module turns that data into the
quantities of a scene (docs/flywheel-design.md, sections 2, 8 and 11), in SI
floats; :mod:`flyopt.io.press` reads and checks the [press] table and calls it.

The textbook's model of a press (Khurmi & Gupta, the flywheel examples of
punching presses; docs/flywheel-design.md, section 11):

- the crank turns once per stroke: the cycle is one turn (2π) of the crank,
  the reference shaft, and its mean speed is the strokes per minute;
- the working stroke takes the crank angle θ_w = 2π t_w / T of a working time
  t_w in a stroke period T (the crank turning at constant speed);
- the process takes its energy E over θ_w: as the constant torque E/θ_w (the
  textbook's assumption), or, given the force over the working stroke, as
  the torque that does the same work at each angle; the motor supplies E at a
  constant rate over the whole stroke, so the flywheel gives up
  E (1 − θ_w/2π) = E (1 − t_w/T);
- the flywheel slows from its top speed ω_top at the start of the working
  stroke to ω_bottom at its end: the slowdown s = (ω_top − ω_bottom)/ω_top.

Angles are measured from the start of the working stroke (φ = 0), so the
speed is highest at φ = 0 and lowest at φ = θ_w.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from flyopt.cycle.indicator import speed_extremes
from flyopt.units import rpm_to_rad_s

TURN = 2.0 * math.pi
"""The cycle of a press: one turn of the crank per stroke [rad]."""


def crank_speed(strokes_per_minute: float) -> float:
    """Mean speed of the crank [rad/s] of a press making ``strokes_per_minute`` strokes a minute.

    One stroke per crank turn: ω_m = 2π n/60 with n the strokes per minute
    (docs/flywheel-design.md, section 2).
    """
    return rpm_to_rad_s(strokes_per_minute)


def crank_speed_of_period(period: float) -> float:
    """Mean speed of the crank ω_m = 2π/T [rad/s] of a press making one stroke in ``period`` [s]."""
    return TURN / period


def stroke_period(omega_crank: float) -> float:
    """Duration of one stroke T = 2π/ω_m [s] at a mean crank speed ``omega_crank`` [rad/s]."""
    return TURN / omega_crank


def working_angle(working_time: float, period: float) -> float:
    """Crank angle of the working stroke, θ_w = 2π t_w/T [rad].

    The textbook's assumption: the crank turns at its mean speed while the
    working stroke lasts (the speed changes by the slowdown s only, a few
    per cent to a fifth).

    Parameters
    ----------
    working_time : float
        Duration t_w of the working stroke [s].
    period : float
        Duration T of one stroke [s], T > t_w.
    """
    return TURN * working_time / period


def delta_from_slowdown(slowdown: float) -> float:
    """flyopt's δ of a slowdown s = (ω_top − ω_bottom)/ω_top over the working stroke.

    With ω_top = ω_m (1 + δ/2) and ω_bottom = ω_m (1 − δ/2) (docs/flywheel-design.md,
    section 2), s = δ/(1 + δ/2) = 2δ/(2 + δ), so

        δ = 2 s / (2 − s).

    s in (0, 1) gives δ in (0, 2): the flywheel keeps turning (ω_bottom > 0).
    Khurmi's press slows from 225 to 200 rpm: s = 1/9, δ = 2/17 = 0.1176, the
    mean speed 212.5 rpm.
    """
    return 2.0 * slowdown / (2.0 - slowdown)


def slowdown_from_delta(delta: float) -> float:
    """The slowdown s = 2δ/(2 + δ) of a coefficient of fluctuation δ (the inverse of :func:`delta_from_slowdown`)."""
    return 2.0 * delta / (2.0 + delta)


def mean_from_top_speed(omega_top: float, delta: float) -> float:
    """Mean speed ω_m [rad/s] of a shaft whose top speed is ``omega_top`` [rad/s] at fluctuation δ.

    ω_top = ω_m (1 + δ/2) (:func:`flyopt.cycle.indicator.speed_extremes`), so
    ω_m = ω_top / (1 + δ/2) = ω_top (1 − s/2) with s the slowdown.
    """
    return omega_top / speed_extremes(1.0, delta)[0]


def flywheel_speed_ratio(omega_top: float, delta: float, omega_crank: float) -> float:
    """Speed ratio i = ω_flywheel/ω_crank of the flywheel shaft whose top speed is ``omega_top``.

    The ratio of the mean speeds (docs/flywheel-design.md, section 8): the
    flywheel shaft's mean speed is ω_top/(1 + δ/2), the crank's ``omega_crank``.
    Its J' = J_F/i² then holds the kinetic energy of J_F on the crank:
    J' ω'_m² δ = A_max, i.e. A_max = ½ J' (ω_top² − ω_bottom²).

    Parameters
    ----------
    omega_top : float
        Top speed of the flywheel shaft, at the start of the working stroke [rad/s].
    delta : float
        Coefficient of speed fluctuation [-].
    omega_crank : float
        Mean speed of the crank [rad/s].
    """
    return mean_from_top_speed(omega_top, delta) / omega_crank


def working_torque(energy: float, angle: float) -> float:
    """The constant torque E/θ_w [N*m] that does the work ``energy`` [J] over the working angle [rad].

    The textbook's load of a press: the energy of a stroke taken at a
    constant rate over the working stroke.
    """
    return energy / angle


def punching_angle(thickness: float, stroke: float) -> float:
    """The crank angle of punching from the plate's thickness t and the punch's stroke s [rad]: θ_w = π t / s.

    The courses' assumption (Khurmi & Gupta, "Flywheel in punching press"): the punch travels 2 s in a
    crank turn at a uniform speed, so punching through t takes t / (2 s) of the turn.
    """
    return math.pi * thickness / stroke


def punching_force(shear_strength: float, cut_length: float, thickness: float) -> float:
    """Largest force of punching or shearing, F_max = τ L t [N].

    The sheared area L t (cut length times plate thickness; a round hole:
    L = π d) times the ultimate shear strength τ of the plate [Pa].
    """
    return shear_strength * cut_length * thickness


def punching_energy(max_force: float, thickness: float) -> float:
    """Energy of one punch or cut, E = ½ F_max t [J].

    The force falls from F_max when the punch enters the plate to zero when
    it is through: the work of shearing is half the maximum force times the
    thickness (Khurmi & Gupta, Theory of Machines, "Flywheel in punching
    press": energy per hole = ½ × maximum shearing force × plate thickness).
    """
    return 0.5 * max_force * thickness


def sheared_area_energy(energy_per_area: float, cut_length: float, thickness: float) -> float:
    """Energy of one punch or cut from the energy per unit of sheared area, E = w L t [J].

    The courses' other form of the same datum (Khurmi & Gupta, example 16.22: "6 N·m of
    energy per mm² of sheared area"): the sheared area L t times the energy w it takes per unit
    area [J/m²].
    """
    return energy_per_area * cut_length * thickness


def force_energy(positions: Sequence[float], forces: Sequence[float]) -> float:
    """Work ∫F dx [J] of a force table, piecewise linear in the position (exact: the trapezoids).

    Parameters
    ----------
    positions : sequence of float
        Ram positions over the working stroke [m], non-decreasing.
    forces : sequence of float
        Force at each position [N].
    """
    return math.fsum(
        0.5 * (forces[k] + forces[k + 1]) * (positions[k + 1] - positions[k]) for k in range(len(positions) - 1)
    )


def force_torque(positions: Sequence[float], forces: Sequence[float], angle: float) -> tuple[list[float], list[float]]:
    """A force table over the working stroke as a torque table over the working angle.

    The ram's position is taken uniform in the crank angle over the working
    stroke (the textbook's constant-speed working stroke): position x_k is
    reached at φ_k = θ_w (x_k − x_0)/(x_n − x_0), where the torque doing the
    same work is M_k = F_k dx/dφ = F_k (x_n − x_0)/θ_w. The table stays
    piecewise linear, and ∫M dφ = ∫F dx at every angle.

    Parameters
    ----------
    positions : sequence of float
        Ram positions over the working stroke [m], non-decreasing, x_n > x_0.
    forces : sequence of float
        Force at each position [N].
    angle : float
        Working angle θ_w [rad].

    Returns
    -------
    angles, torques : list of float
        [rad] from 0 to θ_w, and [N*m].
    """
    x0, stroke = positions[0], positions[-1] - positions[0]
    lever = stroke / angle  # dx/dφ [m/rad]
    angles = [angle * (x - x0) / stroke for x in positions]
    angles[-1] = angle
    return angles, [f * lever for f in forces]


def resisting_table(angles: Sequence[float], torques: Sequence[float], angle: float) -> list[list[float]]:
    """The process load over one crank turn: the working-stroke table, then zero to 2π.

    Parameters
    ----------
    angles, torques : sequence of float
        The load over the working stroke, from φ = 0 to the working angle [rad], [N*m].
    angle : float
        The working angle θ_w < 2π [rad].

    Returns
    -------
    list of [angle, torque]
        A table over [0, 2π] with a step down to zero at θ_w (where the
        working stroke's own table does not end at zero already).
    """
    rows = [[float(a), float(m)] for a, m in zip(angles, torques)]
    if rows[-1][1] != 0.0:
        if len(rows) >= 2 and rows[-2][0] == rows[-1][0]:  # already a step at θ_w: step to zero instead
            rows[-1][1] = 0.0
        else:
            rows.append([angle, 0.0])
    rows.append([TURN, 0.0])
    return rows
