"""Lateral critical speeds of the shaft with its wheel (issue 30, item 3).

Closed forms for the simple cases, after Shigley's *Mechanical Engineering
Design*, 9th ed., section 7-6:

- Jeffcott's rotor: one mass m on a massless shaft of stiffness k at the mass,
  omega = sqrt(k/m), k = 1/delta_ii from :mod:`~flyopt.design.shaft.beam`;
- Rayleigh's energy method, Eq. (7-23): omega_1^2 = g sum(m_i y_i) / sum(m_i y_i^2),
  y_i the static deflections along gravity under all the weights (an upper
  bound of the first critical speed);
- Dunkerley's sum, Eq. (7-32): 1/omega_1^2 ~ sum 1/omega_ii^2, omega_ii^2 = 1/(m_i delta_ii)
  (a lower bound).

A beam finite-element model for stepped shafts and overhung wheels: Euler-
Bernoulli elements (cubic Hermite, two nodes, deflection and slope at each;
consistent mass, the shaft's own rotary inertia and gyroscopics neglected),
the bearings as rigid supports or radial springs, the wheel as a rigid disc
of mass m, diametral inertia I_d and polar inertia I_p at a node. The rotor is
axisymmetric with isotropic bearings, so the two planes join into one complex
coordinate w = u + i v (and its slope); a whirl w = W e^{i omega t} is forward
for omega > 0 (the sense of rotation) and backward for omega < 0, and at shaft
speed Omega

    (K - omega^2 M + omega Omega G) W = 0,    G = I_p at each disc's slope,

(M. I. Friswell et al., *Dynamics of Rotating Machines*, Cambridge University
Press, 2010, sections 3.5 and 5.3, in complex coordinates). It is solved as
the standard eigenproblem [[0, I], [M^-1 K, Omega M^-1 G]] z = omega z, after
the degrees of freedom without inertia (a massless shaft's) are condensed out
exactly. The
critical speed where forward whirl meets the 1x excitation (omega = Omega)
solves K W = Omega^2 (M - G) W, the backward one K W = Omega^2 (M + G) W.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from flyopt.design.shaft.beam import SteppedShaft, elastic_line, influence_coefficient
from flyopt.validate import number

__all__ = [
    "GRAVITY",
    "Disc",
    "RotorModel",
    "Whirl",
    "rotor_model",
    "jeffcott_speed",
    "rayleigh_speed",
    "dunkerley_speed",
    "natural_frequencies",
    "whirl_frequencies",
    "critical_speeds",
    "running_margin",
]

#: Standard gravity [m/s^2] (the static deflections of Rayleigh's method).
GRAVITY = 9.80665


@dataclass(frozen=True)
class Disc:
    """A rigid wheel on the shaft: its centre at ``position`` [m], ``mass`` [kg],
    ``diametral_inertia`` I_d and ``polar_inertia`` I_p [kg*m^2] about its centre."""

    position: float
    mass: float
    diametral_inertia: float = 0.0
    polar_inertia: float = 0.0

    def __post_init__(self) -> None:
        units = {"position": "m", "mass": "kg", "diametral_inertia": "kg*m^2", "polar_inertia": "kg*m^2"}
        for name, unit in units.items():
            value = number(getattr(self, name), f"disc {name} [{unit}]", minimum=0.0, strict=name == "mass")
            object.__setattr__(self, name, value)
        if self.polar_inertia > 2.0 * self.diametral_inertia * (1.0 + 1e-12):
            raise ValueError(
                f"disc polar_inertia {self.polar_inertia:g} must not exceed twice its diametral_inertia "
                f"{self.diametral_inertia:g} (I_x + I_y >= I_z for any body)"
            )


@dataclass(frozen=True)
class RotorModel:
    """The assembled finite-element model: node positions [m], the free degrees of freedom
    (deflection and slope of each node, less the rigid bearings' deflections), and K, M, G on them."""

    nodes: np.ndarray
    free: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray
    gyroscopic: np.ndarray


def _mesh(
    shaft: SteppedShaft,
    discs: Sequence[Disc],
    elements: int | None,
    max_element: float | None,
    extra: Sequence[float],
) -> np.ndarray:
    points = np.unique(np.concatenate(([0.0], shaft.steps, shaft.bearings, [d.position for d in discs], extra)))
    if elements is not None:
        if elements < 1:
            raise ValueError(f"elements must be >= 1, got {elements}")
        counts = np.full(points.size - 1, int(elements))
    else:
        step = shaft.length / 20.0 if max_element is None else float(max_element)
        if not step > 0.0:
            raise ValueError(f"max_element [m] must be > 0, got {max_element!r}")
        counts = np.maximum(1, np.ceil(np.diff(points) / step - 1e-9).astype(int))
    pieces = [np.linspace(a, b, n + 1)[:-1] for a, b, n in zip(points[:-1], points[1:], counts)]
    return np.concatenate(pieces + [points[-1:]])


def rotor_model(
    shaft: SteppedShaft,
    discs: Sequence[Disc] = (),
    *,
    elements: int | None = None,
    max_element: float | None = None,
    shaft_mass: bool = True,
    extra_nodes: Sequence[float] = (),
) -> RotorModel:
    """Assemble the beam finite-element model of the shaft, its bearings and its discs.

    Parameters
    ----------
    shaft : SteppedShaft
        Steps, E, density and the bearings (rigid, or springs of ``bearing_stiffness`` [N/m]).
    discs : sequence of Disc
        The wheel (and any other rigid disc) on the shaft.
    elements : int, optional
        Elements between each pair of neighbouring breakpoints (ends, steps, bearings, discs).
    max_element : float, optional
        Otherwise the longest element [m] (default L/20).
    shaft_mass : bool
        False for a massless shaft (Jeffcott's and the closed forms' model).
    extra_nodes : sequence of float
        More breakpoints [m] (where a load acts, or a result is wanted).

    Notes
    -----
    Element stiffness (EI/l^3) [[12, 6l, -12, 6l], [6l, 4l^2, -6l, 2l^2], ...] and
    consistent mass (rho A l/420) [[156, 22l, 54, -13l], ...] (Friswell et al. 2010, Eq. (5.57),
    the Euler-Bernoulli limit of their Timoshenko element).
    """
    for where in [d.position for d in discs] + [float(x) for x in extra_nodes]:
        if not 0.0 <= where <= shaft.length:
            raise ValueError(f"disc and node positions [m] must lie on the shaft, 0 to {shaft.length:g}, got {where:g}")
    nodes = _mesh(shaft, discs, elements, max_element, extra_nodes)
    size = 2 * nodes.size
    k = np.zeros((size, size))
    m = np.zeros((size, size))
    g = np.zeros((size, size))
    ll = np.diff(nodes)
    middles = 0.5 * (nodes[:-1] + nodes[1:])
    ei = shaft.flexural_rigidity(middles)
    # every element's 4 x 4 matrices at once (the elements' dofs overlap by two: the sums below add each
    # element's share in element order, as a loop over the elements would)
    one, l1, l2 = np.ones_like(ll), ll, ll**2
    ke = (ei / ll**3)[:, None, None] * np.stack(
        [
            np.stack([12.0 * one, 6 * l1, -12.0 * one, 6 * l1], axis=-1),
            np.stack([6 * l1, 4 * l2, -6 * l1, 2 * l2], axis=-1),
            np.stack([-12.0 * one, -6 * l1, 12.0 * one, -6 * l1], axis=-1),
            np.stack([6 * l1, 2 * l2, -6 * l1, 4 * l2], axis=-1),
        ],
        axis=1,
    )
    dofs = 2 * np.arange(ll.size)[:, None] + np.arange(4)[None, :]
    rows, cols = np.broadcast_arrays(dofs[:, :, None], dofs[:, None, :])
    np.add.at(k, (rows, cols), ke)
    if shaft_mass:
        area = math.pi * shaft.diameter_at(middles) ** 2 / 4.0
        me = (shaft.density * area * ll / 420.0)[:, None, None] * np.stack(
            [
                np.stack([156.0 * one, 22 * l1, 54.0 * one, -13 * l1], axis=-1),
                np.stack([22 * l1, 4 * l2, 13 * l1, -3 * l2], axis=-1),
                np.stack([54.0 * one, 13 * l1, 156.0 * one, -22 * l1], axis=-1),
                np.stack([-13 * l1, -3 * l2, -22 * l1, 4 * l2], axis=-1),
            ],
            axis=1,
        )
        np.add.at(m, (rows, cols), me)
    for disc in discs:
        node = int(np.argmin(np.abs(nodes - disc.position)))
        m[2 * node, 2 * node] += disc.mass
        m[2 * node + 1, 2 * node + 1] += disc.diametral_inertia
        g[2 * node + 1, 2 * node + 1] += disc.polar_inertia
    fixed = []
    for position, stiffness in zip(shaft.bearings, shaft.bearing_stiffness):
        node = int(np.argmin(np.abs(nodes - position)))
        if stiffness is None:
            fixed.append(2 * node)
        else:
            k[2 * node, 2 * node] += stiffness
    free = np.setdiff1d(np.arange(size), fixed)
    sub = np.ix_(free, free)
    return RotorModel(nodes, free, k[sub], m[sub], g[sub])


def jeffcott_speed(shaft: SteppedShaft, position: float, mass: float) -> float:
    """Jeffcott's critical speed omega = sqrt(k/m) [rad/s] of a mass on the massless shaft, k = 1/delta_ii."""
    return math.sqrt(1.0 / (number(mass, "mass [kg]", minimum=0.0) * influence_coefficient(shaft, position)))


def _masses(
    positions: Sequence[float] | np.ndarray, masses: Sequence[float] | np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    x = np.atleast_1d(np.asarray(positions, dtype=float))
    m = np.atleast_1d(np.asarray(masses, dtype=float))
    if x.shape != m.shape or x.size == 0 or not np.all(m > 0.0) or not np.all(np.isfinite(m)):
        raise ValueError("positions [m] and masses [kg] must be as many, not empty, and the masses finite and > 0")
    return x, m


def rayleigh_speed(
    shaft: SteppedShaft, positions: Sequence[float] | np.ndarray, masses: Sequence[float] | np.ndarray
) -> float:
    """Rayleigh's first critical speed [rad/s], Shigley 9th ed. Eq. (7-23), on the massless shaft.

    omega_1^2 = g sum(m_i y_i) / sum(m_i y_i^2), y_i the static deflections (along gravity)
    under all the weights m_i g together; an upper bound of the first critical speed.
    """
    x, m = _masses(positions, masses)
    y = -elastic_line(shaft, x, -m * GRAVITY, at=x).deflection
    return math.sqrt(GRAVITY * float(np.sum(m * y)) / float(np.sum(m * y * y)))


def dunkerley_speed(
    shaft: SteppedShaft, positions: Sequence[float] | np.ndarray, masses: Sequence[float] | np.ndarray
) -> float:
    """Dunkerley's first critical speed [rad/s], Shigley 9th ed. Eq. (7-32), on the massless shaft.

    1/omega_1^2 = sum 1/omega_ii^2 = sum m_i delta_ii, each mass alone on the shaft; a lower bound.
    """
    x, m = _masses(positions, masses)
    total = sum(float(mi) * influence_coefficient(shaft, float(xi)) for xi, mi in zip(x, m))
    return 1.0 / math.sqrt(total)


def _condensed(model: RotorModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K, M, G on the degrees of freedom that carry inertia; the others condensed out exactly.

    A massless degree of freedom (a massless shaft's, a disc's slope without I_d) has no inertia
    nor gyroscopic term, so K_red = K_mm - K_ms K_ss^-1 K_sm is exact, not Guyan's approximation;
    it keeps M positive definite for the eigensolvers.
    """
    inertial = np.diag(model.mass) > 0.0
    if np.all(inertial):
        return model.stiffness, model.mass, model.gyroscopic
    if not np.any(inertial):
        raise ValueError("the rotor has no mass: give the shaft a density or a disc")
    keep, drop = np.flatnonzero(inertial), np.flatnonzero(~inertial)
    k = model.stiffness
    k_mm, k_ms, k_ss = k[np.ix_(keep, keep)], k[np.ix_(keep, drop)], k[np.ix_(drop, drop)]
    reduced = k_mm - k_ms @ np.linalg.solve(k_ss, k_ms.T)
    return 0.5 * (reduced + reduced.T), model.mass[np.ix_(keep, keep)], model.gyroscopic[np.ix_(keep, keep)]


def _real(values: np.ndarray) -> np.ndarray:
    scale = max(1.0, float(np.max(np.abs(values)))) if values.size else 1.0
    if values.size and np.max(np.abs(np.imag(values))) > 1e-8 * scale:
        raise ValueError("the rotor's eigenvalues are not real: check the model (negative stiffness or mass?)")
    return np.sort(np.real(values))


def natural_frequencies(model: RotorModel) -> np.ndarray:
    """Whirl frequencies at rest [rad/s], ascending: K W = omega^2 M W (on the inertial DOFs)."""
    import scipy.linalg

    k, m, _ = _condensed(model)
    return np.sqrt(np.clip(scipy.linalg.eigh(k, m, eigvals_only=True), 0.0, None))


@dataclass(frozen=True)
class Whirl:
    """Forward and backward whirl frequencies [rad/s] at each shaft speed [rad/s]: arrays (speeds, modes)."""

    speeds: np.ndarray
    forward: np.ndarray
    backward: np.ndarray


def whirl_frequencies(model: RotorModel, speeds: Sequence[float] | np.ndarray, modes: int = 3) -> Whirl:
    """Forward and backward whirl frequencies against shaft speed: the Campbell diagram's lines.

    Parameters
    ----------
    model : RotorModel
    speeds : sequence of float
        Shaft speeds Omega [rad/s].
    modes : int
        How many of the lowest modes to return (NaN where the model has fewer).

    Returns
    -------
    Whirl
        ``forward[i, j]`` the j-th forward whirl frequency (omega > 0, ascending) at
        ``speeds[i]``; ``backward[i, j]`` the j-th backward one, as a positive number.

    Notes
    -----
    With M^-1 from a Cholesky factor, the pencil becomes the standard eigenproblem
    [[0, I], [M^-1 K, Omega M^-1 G]] z = omega z, whose 2n eigenvalues are real.
    """
    import scipy.linalg

    k, m, g = _condensed(model)
    factor = scipy.linalg.cho_factor(m)
    mk, mg = scipy.linalg.cho_solve(factor, k), scipy.linalg.cho_solve(factor, g)
    n = k.shape[0]
    top = np.hstack((np.zeros((n, n)), np.eye(n)))
    speeds_ = np.atleast_1d(np.asarray(speeds, dtype=float))
    forward = np.full((speeds_.size, modes), np.nan)
    backward = np.full((speeds_.size, modes), np.nan)
    for i, omega in enumerate(speeds_):
        values = _real(np.linalg.eigvals(np.vstack((top, np.hstack((mk, omega * mg))))))
        positive = values[values > 0.0][:modes]
        negative = -values[values < 0.0][::-1][:modes]
        forward[i, : positive.size] = positive
        backward[i, : negative.size] = negative
    return Whirl(speeds_, forward, backward)


def critical_speeds(model: RotorModel, *, whirl: str = "forward", modes: int = 3) -> np.ndarray:
    """Shaft speeds [rad/s] at which a whirl frequency equals the speed (the 1x line), ascending.

    forward: K W = Omega^2 (M - G) W; backward: K W = Omega^2 (M + G) W, solved as
    K^-1 (M -+ G) W = (1/Omega^2) W. A disc whose I_p outweighs I_d (a thin disc,
    I_p = 2 I_d) has no forward critical speed of its tilting mode (1/Omega^2 <= 0): left out.
    """
    if whirl not in ("forward", "backward"):
        raise ValueError(f"whirl must be 'forward' or 'backward', got {whirl!r}")
    k, m, g = _condensed(model)
    sign = -1.0 if whirl == "forward" else 1.0
    inverse_squares = _real(np.linalg.eigvals(np.linalg.solve(k, m + sign * g)))
    positive = inverse_squares[inverse_squares > 0.0]
    return np.sort(1.0 / np.sqrt(positive))[:modes]


def running_margin(critical_speed: float, speed_range_rpm: tuple[float, float]) -> float:
    """Relative separation of a critical speed [rad/s] from the running range [n_min, n_max] [rpm].

    (n_c - n_max)/n_max above the range, (n_min - n_c)/n_min below it, 0 inside it: the
    rule of :func:`flyopt.machine.torsion.critical_speeds` (the one place it is decided),
    with the lateral critical speed as a mode met by the first order.
    """
    from flyopt.machine.torsion import critical_speeds as torsional_critical_speeds

    speed = number(critical_speed, "critical_speed [rad/s]", minimum=0.0)
    return torsional_critical_speeds([speed / (2.0 * math.pi)], [1.0], speed_range_rpm)[0].margin
