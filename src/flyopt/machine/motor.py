"""Motor characteristics: torque as a function of speed.

Two families, SI throughout (speed [rad/s] of the motor shaft, torque [N*m]):

- :class:`InductionMotor`: the straight line through the synchronous speed
  and the rated point, M = M_n (ω_0 − ω)/(ω_0 − ω_n) (docs/flywheel-design.md, section 7),
  which is what the periodic steady state near rated speed needs; and, for
  runs far from rated speed (a start from rest), the Kloss formula with a
  breakdown-torque ratio.
- :class:`DCMotor`: a separately excited (or shunt) DC motor's straight
  torque–speed line, M = M_stall (1 − ω/ω_0).
- :class:`TableMotor`: a measured or catalogue torque–speed curve, piecewise
  linear through its rows, from rest to beyond its no-load speed.

Every torque method accepts numpy arrays or CasADi symbols.

A motor turns at ``speed_ratio`` times the reference shaft through a
transmission of efficiency η; :meth:`InductionMotor.reference_torque` gives
its torque reduced to the reference shaft, M' = M(i ω) i η (docs/flywheel-design.md,
section 3).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from flyopt.units import rad_s_to_rpm
from flyopt.validate import positive

DEFAULT_BREAKDOWN_RATIO = 2.5
"""Default breakdown (pull-out) torque over rated torque, M_b/M_n [-].

The middle of the 175–300 % range of NEMA design B motors (NEMA MG 10,
Table 2-1, as tabulated in the EASA Engineering Handbook, "General
speed-torque characteristics, three-phase induction motors"; higher values
for smaller motors). Give the catalogue value when it is known.
"""


def plate_rpm(omega: float) -> str:
    """A motor's speed [rad/s] as its rating plate gives it, in rpm to six figures ("1450 rpm"), for the
    refusals of a rating (here and in :mod:`flyopt.machine.catalogue`)."""
    return f"{rad_s_to_rpm(omega):.6g} rpm"


def _positive(value: object, what: str) -> float:
    return positive(value, what)


def kloss_torque(omega: Any, synchronous_speed: Any, breakdown_torque: Any, breakdown_slip: Any) -> Any:
    """The Kloss curve M = 2 M_b s s_b / (s² + s_b²), s = (ω_0 − ω)/ω_0 [N*m] (numpy or CasADi, any argument).

    The one formula of an induction motor's whole curve: :meth:`InductionMotor.torque` evaluates it at
    a motor's figures, a drive search at symbols for them.
    """
    s = (synchronous_speed - omega) / synchronous_speed
    return 2 * breakdown_torque * s * breakdown_slip / (s * s + breakdown_slip * breakdown_slip)


class _Motor:
    # M(ω_motor) [N*m], numpy or CasADi; each kind of motor defines it (an induction motor also takes ``model``)
    torque: Callable[..., Any]

    def reference_torque(
        self, omega: Any, speed_ratio: float = 1.0, efficiency: float = 1.0, model: str | None = None
    ) -> Any:
        """Motor torque reduced to the reference shaft [N*m].

        M' = M(i ω) · i · η, i = ω_motor/ω the speed ratio, η the efficiency
        of the transmission between them (docs/flywheel-design.md, section 3).

        Parameters
        ----------
        omega : array or casadi symbol
            Speed of the reference shaft [rad/s].
        speed_ratio : float
            i = ω_motor/ω_reference [-].
        efficiency : float
            η of the transmission, in (0, 1] [-].
        model : str, optional
            Passed to :meth:`torque` (induction motors only).
        """
        i = _positive(speed_ratio, "speed_ratio")
        eta = _positive(efficiency, "efficiency")
        if eta > 1:
            raise ValueError(f"efficiency must lie in (0, 1], got {efficiency!r}")
        torque = self.torque(omega * i) if model is None else self.torque(omega * i, model=model)
        return torque * (i * eta)


#: The largest rated slip s_n = 1 - n_n/n_s an induction motor is taken with: general-purpose motors run at a
#: few per cent, high-slip designs (NEMA design D) at up to about 13 %; beyond a half the "motor" would
#: be mostly slip (and a typo of a unit, or a speed of 1e300, is refused rather than searched for).
MAX_RATED_SLIP = 0.5


class InductionMotor(_Motor):
    """Three-phase induction motor given by its nameplate.

    Parameters
    ----------
    rated_power : float
        P_n, mechanical output at the rated point [W].
    rated_speed : float
        ω_n [rad/s].
    synchronous_speed : float
        ω_0 [rad/s], above ω_n.
    breakdown_ratio : float, optional
        M_b/M_n > 1 for the Kloss curve [-]; default
        :data:`DEFAULT_BREAKDOWN_RATIO`.

    Attributes
    ----------
    rated_torque : float
        M_n = P_n/ω_n [N*m].
    rated_slip : float
        s_n = (ω_0 − ω_n)/ω_0 [-].
    breakdown_slip : float
        s_b of the Kloss curve through the rated point [-].

    Notes
    -----
    Linear model (near the rated point, docs/flywheel-design.md, section 7):

        M = M_n (ω_0 − ω)/(ω_0 − ω_n).

    Kloss model (the simplified Kloss formula, stator resistance neglected):

        M = 2 M_b / (s/s_b + s_b/s) = 2 M_b s s_b / (s² + s_b²),  s = (ω_0 − ω)/ω_0,

    with s_b = s_n (k + sqrt(k² − 1)), k = M_b/M_n, so that it passes through
    the rated point on its stable branch. Both models agree at ω_0 and at the
    rated point. The linear line is unrealistic far from rated speed (at rest
    it gives M_n/s_n, 25 M_n at 4 % slip); the Kloss curve is the one for a
    start from rest. The simplified Kloss formula underestimates the
    locked-rotor torque of deep-bar and double-cage rotors, so start-up
    times from it err long (on the safe side for sizing the motor).

    References
    ----------
    .. [1] Kloss, M., the torque–slip formula of the induction machine, as in
       Fischer, R., *Elektrische Maschinen*, Hanser, chapter on the
       asynchronous machine.
    .. [2] NEMA MG 10, Table 2-1 (via the EASA Engineering Handbook):
       breakdown torque 175–300 % of rated for design B.
    """

    MODELS = ("linear", "kloss")

    def __init__(
        self, rated_power: float, rated_speed: float, synchronous_speed: float, breakdown_ratio: float | None = None
    ) -> None:
        self.rated_power = _positive(rated_power, "rated_power [W]")
        self.rated_speed = _positive(rated_speed, "rated_speed [rad/s]")
        self.synchronous_speed = _positive(synchronous_speed, "synchronous_speed [rad/s]")
        rated, synchronous = (
            plate_rpm(self.rated_speed),
            plate_rpm(self.synchronous_speed),
        )  # as a motor's plate says them
        if not self.rated_speed < self.synchronous_speed:
            raise ValueError(
                f"an induction motor's rated speed ({rated}) must be below its synchronous speed ({synchronous}): "
                "it runs below it by its slip"
            )
        if not self.rated_speed > (1.0 - MAX_RATED_SLIP) * self.synchronous_speed:
            raise ValueError(
                f"an induction motor's rated speed ({rated}) must be above "
                f"{1.0 - MAX_RATED_SLIP:g} of its synchronous speed ({synchronous}): a rated slip of "
                f"{(self.synchronous_speed - self.rated_speed) / self.synchronous_speed:.3g} is no induction motor's "
                f"(they run at a few per cent of slip, high-slip designs up to about 0.15)"
            )
        k = DEFAULT_BREAKDOWN_RATIO if breakdown_ratio is None else _positive(breakdown_ratio, "breakdown_ratio")
        if k <= 1:
            raise ValueError(f"breakdown_ratio M_b/M_n must exceed 1, got {breakdown_ratio!r}")
        self.breakdown_ratio = k
        self.rated_torque = self.rated_power / self.rated_speed
        self.rated_slip = (self.synchronous_speed - self.rated_speed) / self.synchronous_speed
        self.breakdown_slip = self.rated_slip * (k + math.sqrt(k * k - 1))
        self.breakdown_torque = k * self.rated_torque

    def __repr__(self) -> str:
        return (
            f"InductionMotor(rated_power={self.rated_power!r}, rated_speed={self.rated_speed!r}, "
            f"synchronous_speed={self.synchronous_speed!r}, breakdown_ratio={self.breakdown_ratio!r})"
        )

    @property
    def slope(self) -> float:
        """dM/dω of the linear model [N*m*s/rad] (negative)."""
        return -self.rated_torque / (self.synchronous_speed - self.rated_speed)

    def torque(self, omega: Any, model: str = "linear") -> Any:
        """Motor torque at the motor speed ``omega`` [N*m].

        Parameters
        ----------
        omega : array or casadi symbol
            Motor shaft speed [rad/s].
        model : {"linear", "kloss"}
        """
        if model == "linear":
            return self.rated_torque * (self.synchronous_speed - omega) / (self.synchronous_speed - self.rated_speed)
        if model == "kloss":
            return kloss_torque(omega, self.synchronous_speed, self.breakdown_torque, self.breakdown_slip)
        raise ValueError(f"induction motor model {model!r} is not known (allowed: {', '.join(self.MODELS)})")

    @property
    def linear_limit_speed(self) -> float:
        """Speed where the linear line reaches the breakdown torque, ω_0 − k (ω_0 − ω_n) [rad/s].

        Below it the linear model promises more torque than the motor has: a
        periodic solution whose ω_min falls below this speed should be
        recomputed with ``model="kloss"``.
        """
        return self.synchronous_speed - self.breakdown_ratio * (self.synchronous_speed - self.rated_speed)

    @property
    def breakdown_speed(self) -> float:
        """Speed of the breakdown torque on the Kloss curve, ω_0 (1 − s_b) [rad/s]."""
        return self.synchronous_speed * (1 - self.breakdown_slip)

    def starting_torque(self, model: str = "kloss") -> float:
        """Torque at rest [N*m]."""
        return float(self.torque(0.0, model))


class DCMotor(_Motor):
    """DC motor with a straight torque–speed line.

    Parameters
    ----------
    no_load_speed : float
        ω_0 where the torque vanishes [rad/s].
    stall_torque : float
        M_stall at rest [N*m].

    Notes
    -----
    M = M_stall (1 − ω/ω_0), the line of a separately excited DC motor at
    constant armature voltage and field (armature reaction neglected).
    """

    def __init__(self, no_load_speed: float, stall_torque: float) -> None:
        self.no_load_speed = _positive(no_load_speed, "no_load_speed [rad/s]")
        self.stall_torque = _positive(stall_torque, "stall_torque [N*m]")

    @classmethod
    def from_rated(cls, rated_power: float, rated_speed: float, no_load_speed: float) -> DCMotor:
        """The line through the rated point (P_n/ω_n at ω_n) and the no-load speed.

        Parameters
        ----------
        rated_power : float [W]
        rated_speed : float [rad/s]
        no_load_speed : float [rad/s], above ``rated_speed``
        """
        p = _positive(rated_power, "rated_power [W]")
        wn = _positive(rated_speed, "rated_speed [rad/s]")
        w0 = _positive(no_load_speed, "no_load_speed [rad/s]")
        if not wn < w0:
            raise ValueError(
                f"rated speed ({plate_rpm(rated_speed)}) must be below the no-load speed ({plate_rpm(no_load_speed)})"
            )
        return cls(w0, p / wn * w0 / (w0 - wn))

    def __repr__(self) -> str:
        return f"DCMotor(no_load_speed={self.no_load_speed!r}, stall_torque={self.stall_torque!r})"

    @property
    def slope(self) -> float:
        """dM/dω [N*m*s/rad] (negative)."""
        return -self.stall_torque / self.no_load_speed

    def torque(self, omega: Any) -> Any:
        """Motor torque at the motor speed ``omega`` [N*m] (numpy or CasADi)."""
        return self.stall_torque * (1 - omega / self.no_load_speed)


class TableMotor(_Motor):
    """A motor given by its torque–speed curve: piecewise linear through rows (ω_k, M_k).

    Parameters
    ----------
    speeds : sequence of float
        Motor shaft speeds ω_k [rad/s], increasing, the first 0 (at rest).
    torques : sequence of float
        Torque M_k at each speed [N*m]; the last one at or below zero (the
        curve reaches its no-load speed), the last segment not rising.

    Notes
    -----
    Written as a sum of ramps, M(ω) = M_0 + s_0 ω + Σ_k (s_k − s_{k−1}) max(ω − ω_k, 0)
    with s_k the slope of segment k, so that numpy and CasADi (SX or MX)
    evaluate the same expression; beyond the last row the last segment is
    extended (the generator side past no-load speed), below rest the first.
    A table of n rows costs n − 2 ramps per evaluation.
    """

    def __init__(self, speeds: Sequence[float], torques: Sequence[float]) -> None:
        w = [float(x) for x in speeds]
        m = [float(x) for x in torques]
        if len(w) != len(m) or len(w) < 2:
            raise ValueError("a motor table needs at least two rows [speed, torque]")
        if not all(math.isfinite(x) for x in w + m):
            raise ValueError("a motor table's speeds and torques must be finite")
        if w[0] != 0.0:
            raise ValueError(
                f"a motor table starts at rest (speed 0), not at {w[0]:.6g} rad/s: "
                "its torque there is the starting torque"
            )
        for k in range(1, len(w)):
            if not w[k] > w[k - 1]:
                raise ValueError(
                    f"a motor table's speeds must increase: row {k} ({w[k]:.6g} rad/s) comes after {w[k - 1]:.6g} rad/s"
                )
        if m[-1] > 0.0:
            raise ValueError(
                f"a motor table must reach its no-load speed: the torque at its last row "
                f"({w[-1]:.6g} rad/s) is {m[-1]:.6g} N*m, above zero"
            )
        if m[-1] > m[-2]:
            raise ValueError(
                "a motor table's torque must not rise over its last segment (it is extended beyond the last row)"
            )
        self.speeds, self.torques = tuple(w), tuple(m)
        self._slopes = tuple((m[k + 1] - m[k]) / (w[k + 1] - w[k]) for k in range(len(w) - 1))
        self.stall_torque = m[0]
        self.largest_torque = max(m)
        k = next(k for k in range(len(m)) if m[k] <= 0.0)
        self.no_load_speed = (
            w[k] if k == 0 or m[k] == 0.0 else w[k - 1] + m[k - 1] * (w[k] - w[k - 1]) / (m[k - 1] - m[k])
        )

    def __repr__(self) -> str:
        return f"TableMotor(speeds={list(self.speeds)!r}, torques={list(self.torques)!r})"

    def torque(self, omega: Any) -> Any:
        """Motor torque at the motor speed ``omega`` [N*m] (numpy arrays, floats or CasADi symbols)."""
        ramp = _ramp(omega)
        s = self._slopes
        total = self.torques[0] + s[0] * omega
        for k in range(1, len(s)):
            total = total + (s[k] - s[k - 1]) * ramp(omega - self.speeds[k])
        return total


def _ramp(omega: Any) -> Callable[[Any], Any]:
    """max(x, 0) for the type of ``omega``: CasADi's fmax for its symbols, numpy's maximum otherwise."""
    if type(omega).__module__.startswith("casadi"):
        import casadi as ca

        return lambda x: ca.fmax(x, 0)
    import numpy as np

    return lambda x: np.maximum(x, 0.0)
