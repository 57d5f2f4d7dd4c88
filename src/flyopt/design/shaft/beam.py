"""A stepped shaft on two bearings: bending moment, slope and deflection (issue 30, item 2).

The shaft is a line 0 <= x <= L of solid round steps (diameter d_j on
[x_j, x_{j+1}], EI_j = E pi d_j^4 / 64), carried by two bearings at x_A < x_B
(rigid, or radial springs k_A, k_B [N/m]) and loaded by transverse point
forces F_i [N] at x_i, in one plane (forces in two planes: call once per
plane and add the results as vectors). A force beyond a bearing is
overhung (a wheel outboard of its bearings).

The reactions come from statics; the moment is piecewise linear,
M(x) = sum over forces left of x of F (x - x_F) (reactions included), and the
elastic line is EI y'' = M integrated twice (Shigley 9th ed., section 4-5,
and section 7-5 for shafts: "integrate M/EI"). Between two consecutive
breakpoints (a load, a bearing, a step) M/EI is linear, so the integration is
exact there:

    theta_1 = theta_0 + h (m_0 + m_1) / (2 EI),    y_1 = y_0 + theta_0 h + h^2 (2 m_0 + m_1) / (6 EI).

The two constants of integration put the shaft on its bearings: y(x_A) = -R_A/k_A,
y(x_B) = -R_B/k_B (0 for a rigid bearing). A positive force acts along +y and
the deflection y [m] and slope theta [rad] are along the same axis.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from flyopt.validate import positive

__all__ = ["SteppedShaft", "ElasticLine", "elastic_line", "elastic_lines", "reactions", "influence_coefficient"]


@dataclass(frozen=True)
class SteppedShaft:
    """A solid round shaft of steps on two bearings.

    Parameters
    ----------
    steps : sequence of float
        The step ends x_1 < x_2 < ... < x_n = L [m]; the shaft starts at x = 0.
    diameters : sequence of float
        d_j [m] of the step that ends at ``steps[j]``.
    elastic_modulus : float
        E [Pa].
    bearings : (float, float)
        x_A < x_B [m], within the shaft.
    bearing_stiffness : (float or None, float or None)
        Radial stiffness [N/m] of each bearing; None (the default) is rigid.
    density : float
        rho [kg/m^3] of the shaft (its own mass, for the lateral model); default 7850.
    """

    steps: tuple[float, ...]
    diameters: tuple[float, ...]
    elastic_modulus: float
    bearings: tuple[float, float]
    bearing_stiffness: tuple[float | None, float | None] = (None, None)
    density: float = 7850.0
    _edges: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        steps = tuple(positive(x, "steps [m]") for x in self.steps)
        diameters = tuple(positive(d, "diameters [m]") for d in self.diameters)
        if not steps or len(steps) != len(diameters):
            raise ValueError(
                f"steps and diameters must be as many and not empty, got {len(steps)} and {len(diameters)}"
            )
        if any(b <= a for a, b in zip(steps, steps[1:])):
            raise ValueError(f"steps [m] must increase, got {self.steps!r}")
        a, b = (float(x) for x in self.bearings)
        if not (0.0 <= a < b <= steps[-1]):
            raise ValueError(f"bearings [m] must be 0 <= x_A < x_B <= L = {steps[-1]:g}, got {self.bearings!r}")
        stiffness = tuple(None if k is None else positive(k, "bearing_stiffness [N/m]") for k in self.bearing_stiffness)
        if len(stiffness) != 2:
            raise ValueError(f"bearing_stiffness must be two values, got {self.bearing_stiffness!r}")
        object.__setattr__(self, "steps", steps)
        object.__setattr__(self, "diameters", diameters)
        object.__setattr__(self, "elastic_modulus", positive(self.elastic_modulus, "elastic_modulus [Pa]"))
        object.__setattr__(self, "density", positive(self.density, "density [kg/m^3]"))
        object.__setattr__(self, "bearings", (a, b))
        object.__setattr__(self, "bearing_stiffness", stiffness)
        object.__setattr__(self, "_edges", np.concatenate(([0.0], steps)))

    @property
    def length(self) -> float:
        """L [m]."""
        return self.steps[-1]

    def diameter_at(self, x: np.ndarray | float) -> np.ndarray:
        """d [m] at x (at a step, the step to its right; at L, the last step)."""
        index = np.clip(
            np.searchsorted(self._edges, np.asarray(x, dtype=float), side="right") - 1, 0, len(self.steps) - 1
        )
        return np.asarray(self.diameters)[index]

    def flexural_rigidity(self, x: np.ndarray | float) -> np.ndarray:
        """EI [N*m^2] at x: E pi d^4 / 64."""
        return self.elastic_modulus * math.pi * self.diameter_at(x) ** 4 / 64.0


def _loads(shaft: SteppedShaft, positions: Sequence[float] | np.ndarray, forces: Sequence[float] | np.ndarray):
    x = np.atleast_1d(np.asarray(positions, dtype=float))
    f = np.atleast_1d(np.asarray(forces, dtype=float))
    if x.shape != f.shape:
        raise ValueError(f"positions and forces must be as many, got {x.size} and {f.size}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(f))):
        raise ValueError("positions [m] and forces [N] must be finite")
    if np.any(x < 0.0) or np.any(x > shaft.length):
        raise ValueError(f"positions [m] must lie on the shaft, 0 to {shaft.length:g}, got {x.tolist()!r}")
    return x, f


def reactions(
    shaft: SteppedShaft, positions: Sequence[float] | np.ndarray, forces: Sequence[float] | np.ndarray
) -> tuple[float, float]:
    """The bearing reactions (R_A, R_B) [N] by statics: sum of forces and moments about A vanish."""
    x, f = _loads(shaft, positions, forces)
    a, b = shaft.bearings
    r_b = -float(np.sum(f * (x - a))) / (b - a)
    r_a = -float(np.sum(f)) - r_b
    return r_a, r_b


@dataclass(frozen=True)
class ElasticLine:
    """The shaft's bending moment M [N*m], slope theta [rad] and deflection y [m] at the points x [m]."""

    x: np.ndarray
    moment: np.ndarray
    slope: np.ndarray
    deflection: np.ndarray
    reactions: tuple[float, float]


def elastic_line(
    shaft: SteppedShaft,
    positions: Sequence[float] | np.ndarray,
    forces: Sequence[float] | np.ndarray,
    at: Sequence[float] | np.ndarray | None = None,
) -> ElasticLine:
    """Moment, slope and deflection of a stepped shaft under point forces, by exact integration of M/EI.

    Parameters
    ----------
    shaft : SteppedShaft
    positions, forces : sequence of float
        x_i [m] and F_i [N] (along +y) of the point forces.
    at : sequence of float, optional
        Where to report [m]; default: every breakpoint (the ends, steps, bearings and loads).

    Returns
    -------
    ElasticLine
        At ``at`` (sorted as given). At a load or a step the moment is continuous;
        the slope and deflection are continuous everywhere.
    """
    x_load, f_load = _loads(shaft, positions, forces)
    return elastic_lines(shaft, x_load, f_load[None, :], at)[0]


def elastic_lines(
    shaft: SteppedShaft,
    positions: Sequence[float] | np.ndarray,
    forces: np.ndarray,
    at: Sequence[float] | np.ndarray | None = None,
) -> tuple[ElasticLine, ...]:
    """:func:`elastic_line` of several load cases on the same points at once: ``forces[c]`` [N] at ``positions``
    [m] is case c (a zero force where a case has none). One pass over one grid for every case, so a check that
    needs the shaft's lines in two planes and under the unbalance pays for one."""
    x_load = np.atleast_1d(np.asarray(positions, dtype=float))
    cases = np.atleast_2d(np.asarray(forces, dtype=float))
    for row in cases:
        _loads(shaft, x_load, row)
    a, b = shaft.bearings
    # the reactions by statics: the sums of forces and of moments about A vanish (:func:`reactions`)
    r_b = -np.sum(cases * (x_load - a)[None, :], axis=1) / (b - a)
    r_a = -np.sum(cases, axis=1) - r_b
    query = None if at is None else np.atleast_1d(np.asarray(at, dtype=float))
    if query is not None and (np.any(query < 0.0) or np.any(query > shaft.length) or not np.all(np.isfinite(query))):
        raise ValueError(f"at [m] must lie on the shaft, 0 to {shaft.length:g}")
    extra = np.empty(0) if query is None else query
    grid = np.unique(np.concatenate(([0.0], shaft.steps, [a, b], x_load, extra)))
    # all forces, reactions included
    fx = np.concatenate((x_load, [a, b]))
    ff = np.concatenate((cases, r_a[:, None], r_b[:, None]), axis=1)
    # M(x) = sum_{x_F < x} F (x - x_F): continuous, so evaluating at the breakpoints is unambiguous
    arm = np.clip(grid[:, None] - fx[None, :], 0.0, None)
    moment = np.sum(ff[:, None, :] * arm[None, :, :], axis=2)
    h = np.diff(grid)
    ei = shaft.flexural_rigidity(0.5 * (grid[:-1] + grid[1:]))
    m0, m1 = moment[:, :-1], moment[:, 1:]
    dtheta = h * (m0 + m1) / (2.0 * ei)
    # theta_p and y_p: particular solution with theta(0) = y(0) = 0
    zero = np.zeros((cases.shape[0], 1))
    theta_p = np.concatenate((zero, np.cumsum(dtheta, axis=1)), axis=1)
    dy_from_curvature = h**2 * (2.0 * m0 + m1) / (6.0 * ei)
    y_p = np.concatenate((zero, np.cumsum(theta_p[:, :-1] * h + dy_from_curvature, axis=1)), axis=1)
    # y = y_p + c0 + c1 x with the bearings' displacements (a and b are nodes of the grid)
    k_a, k_b = shaft.bearing_stiffness
    y_a = np.zeros_like(r_a) if k_a is None else -r_a / k_a
    y_b = np.zeros_like(r_b) if k_b is None else -r_b / k_b
    ya_p, yb_p = y_p[:, np.searchsorted(grid, a)], y_p[:, np.searchsorted(grid, b)]
    c1 = ((y_b - yb_p) - (y_a - ya_p)) / (b - a)
    c0 = (y_a - ya_p) - c1 * a
    slope = theta_p + c1[:, None]
    deflection = y_p + c0[:, None] + c1[:, None] * grid[None, :]
    index = slice(None) if query is None else np.searchsorted(grid, query)
    x_out = grid if query is None else query
    return tuple(
        ElasticLine(x_out, moment[c, index], slope[c, index], deflection[c, index], (float(r_a[c]), float(r_b[c])))
        for c in range(cases.shape[0])
    )


def influence_coefficient(shaft: SteppedShaft, at: float, load: float | None = None) -> float:
    """delta_ij [m/N]: the deflection at ``at`` under a unit force at ``load`` (default: at ``at``).

    1 / delta_ii is the shaft's stiffness at a point, the k of Jeffcott's rotor.
    """
    where = at if load is None else load
    return float(-elastic_line(shaft, [where], [-1.0], at=[at]).deflection[0])
