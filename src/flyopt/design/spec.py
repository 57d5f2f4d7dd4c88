"""What a flywheel design must satisfy: the mounting shafts and the design specification.

One representation of every limit inside the package: an absent envelope or
width limit is ``math.inf`` (no limit), never None or NaN; a pinned mean
diameter is a number or None (free). Inputs may say None for "no limit";
:class:`DesignSpec` turns it into ``inf``, and the JSON output writes ``null``.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, sections 8-10.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

from flyopt.design import castability as casting
from flyopt.design import geometry, preferred
from flyopt.names import Criterion, Geometry, Objective
from flyopt.validate import choice, finite, positive

__all__ = ["OBJECTIVES", "CRITERIA", "MountShaft", "DesignSpec", "StressFactor"]

#: The manufacturing step one design of a wheel flyopt designs whole is rounded to when the scene gives none
#: (:func:`flyopt.design.inputs.one_design`): whole millimetres [m].
DEFAULT_ROUND_TO = 1e-3

#: Objectives understood by :func:`design_flywheel`.
OBJECTIVES = {
    Objective.MASS: "minimize the flywheel mass [kg]",
    Objective.OUTER_DIAMETER: "minimize the outer diameter [m]",
    Objective.COST: "minimize mass times the material's cost per kg",
}

#: Strength criteria understood by :func:`design_flywheel`.
CRITERIA = {
    Criterion.RIM_SPEED: "the textbook limit: the outer diameter's peripheral speed at omega_max stays below the "
    "material's safe rim speed (cast iron 36 m/s, cast steel 50 m/s)",
    Criterion.STRESS: "the governing stress of every part at omega_max stays below the allowable stress (von Mises "
    "against yield for ductile materials, largest principal stress against tensile strength for "
    "brittle ones)",
    Criterion.MEAN_RIM_SPEED: "the courses' convention, for a bare rim only: the peripheral speed at the MEAN "
    "diameter and the MEAN speed is the material's safe rim speed (sigma = rho v^2), which sets D_m; less safe "
    "than rim_speed (the report shows the real stress at the outer diameter and omega_max)",
}

#: The geometries the courses' rim convention (criterion mean_rim_speed) sizes: a rim without web or arms.
BOOK_RIM_GEOMETRIES = (Geometry.RIM, Geometry.THIN_RIM)

#: Arm counts a rim_arms wheel considers unless the scene says (the machine-design texts' range).
DEFAULT_ARMS = (4, 6, 8)


def _positive(value, name, unit):
    return positive(value, f"{name} {unit}")


@dataclass(frozen=True)
class MountShaft:
    """A shaft the flywheel may be mounted on.

    Parameters
    ----------
    name : str
        Shaft name for reports, e.g. ``"motor"``.
    speed_ratio : float
        omega_shaft / omega_reference [-], > 0.
    diameter : float or None
        The shaft seat [m]: the wheel's bore, hub and key follow from it
        unless the design gives its own bore.
    torque : float or None
        The peak torque [N*m] the wheel exchanges with this shaft where a model of the shaft's drive train gives
        it (the train's forced response, J_w theta''_w, :func:`flyopt.design.shaft.cycle.key_torque_on`: the
        torque its post-check checks the key at); it replaces the rigid body's torque / speed_ratio for this
        shaft's hub, key and arms. None: the rigid body's (docs/flywheel-design.md, section 26).
    """

    name: str
    speed_ratio: float
    diameter: float | None = None
    torque: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"shaft name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "speed_ratio", _positive(self.speed_ratio, f"shaft {self.name!r}: speed_ratio", "[-]"))
        if self.diameter is not None:
            object.__setattr__(self, "diameter", _positive(self.diameter, f"shaft {self.name!r}: diameter", "[m]"))
        if self.torque is not None:
            object.__setattr__(self, "torque", _positive(self.torque, f"shaft {self.name!r}: torque", "[N*m]"))


class StressFactor(NamedTuple):
    """A factor on the modelled stress of one part of one combination's wheel (the FE check's concentration)."""

    material: str
    shaft: str
    n_arms: int
    part: str
    factor: float


@dataclass(frozen=True)
class DesignSpec:
    """What the design must satisfy and optimize, shared by every combination.

    Parameters
    ----------
    geometry : {"rim", "thin_rim", "disc", "rim_web", "rim_arms"}
        Inertia model (see :data:`flyopt.design.geometry.GEOMETRIES`).
    hb_ratio : (float, float)
        Allowed range of H/B, radial thickness over axial width [-]; equal
        ends fix it. Ignored by ``disc``.
    max_outer_diameter : float
        Envelope on the outer diameter [m]; ``inf`` (or None on input) for none.
    max_width : float
        Limit on the axial width B [m]; ``inf`` (or None on input) for none.
    d_mean : float or None
        Pinned mean diameter D_m [m]; for ``disc`` the pinned diameter D.
    objective : {"mass", "outer_diameter", "cost"}
        What to minimize. ``cost`` needs a cost per kg on every material.
    criterion : {"rim_speed", "stress"}
        What limits the wheel's size (see :data:`CRITERIA`).
    safety_factor : float or None
        Factor on the material's strength for the allowable stress, when the
        material gives no allowable stress; None: the material's own default.
    bore : float or None
        Diameter of the shaft seat [m]; None: the mounting shaft's diameter,
        or no bore when the shaft gives none. 0 means no bore.
    arms : tuple of int
        Arm counts a ``rim_arms`` wheel considers (each >= 3).
    min_wall : float or None
        Thinnest section the process can make [m]; None: the material's
        default. Bounds every section of a whole wheel and of any wheel under
        the stress criterion (the textbook rim-speed design of a bare wheel
        is left as the textbook makes it).
    rim_speed : float or None
        The rim's speed at its mean diameter and the mean speed [m/s] (the
        books' "mean speed of the flywheel is 25 m/s"): pins each shaft's
        D_m = 2 v / omega'_m. A bare rim only; not with ``d_mean``.
    round_to : float or None
        The manufacturing step [m] (0.001: whole millimetres): the winning
        wheel is rounded to it and checked again against every limit
        (:mod:`flyopt.design.rounding`); 0: the continuous optimum, said
        so; None: not given, so the continuous optimum, except that one
        design of a wheel flyopt designs whole (``flyopt solve``, ``report``,
        ``export``: :func:`flyopt.design.inputs.one_design`) is rounded to
        :data:`DEFAULT_ROUND_TO`.
    diameter_series : str or None
        A preferred-number series (ISO 3: "R5", "R10", "R20", "R40";
        :mod:`flyopt.design.preferred`) the rounded wheel's outer and hub
        diameters are taken from; its other dimensions go to ``round_to``'s
        step. None (default): every dimension to the step.
    round_strict : bool
        Whether a winner no wheel near it on the grid can replace makes the
        design infeasible (True: the step the scene asked for) or leaves the
        continuous optimum as the design, with the reason (False: the
        default step :func:`flyopt.design.inputs.one_design` gives).
    rim_share : float
        Share of the required inertia the rim supplies, in (0, 1]: the
        courses often let the rim give 90-95 % and leave the rest to the arms
        and hub, which are then not designed (default 1: the whole of it).
    prune : bool
        Whether a whole-wheel combination whose objective bound
        (:func:`flyopt.design.wheel_design.objective_bound`) already exceeds
        a design found is left undesigned (True, the default: it cannot win,
        and IPOPT is spared); False designs every combination, for a full
        trade-off table.
    fem_check : bool or None
        True: ``flyopt solve`` checks the best design by the axisymmetric
        finite-element model (:func:`flyopt.design.fem.fem_check`) and
        reports it beside the Lamé/arm model; False: no FE check; None (not
        given): the FE check of one design of a wheel flyopt designs whole is
        reported, and nothing else. With True the design is accepted against the larger of the two: where a
        part's FE peak exceeds its allowable, the wheel is designed again with
        that part's allowable divided by the concentration the FE found
        (``stress_factors``), until the FE peaks are within the allowables
        (:func:`flyopt.design.fem.accept`).
    stress_factors : tuple of StressFactor
        A factor >= 1 on the modelled stress of one part of one combination
        (the concentration the FE check found on that combination's wheel):
        the part's allowable is divided by it. Set by the FE acceptance, not
        by a scene (default: none).
    castability : flyopt.design.castability.Overrides
        The scene's castability (docs/flywheel-design.md, section 23):
        ``process``, the process of every material (a name of
        ``flyopt/data/castability.toml``, or ``"none"`` for no rules; None:
        each material's own), and ``min_wall`` rows (size, wall) [m] and
        ``section_ratio`` [-] replacing the process's numbers. The rules
        bound every whole wheel the NLP designs (rim_web, rim_arms and a disc
        designed whole), not the textbook's bare rims and discs.
    disc_hub : bool
        A bored disc stands on a hub of the seat's proportions (the hub's
        diameter and length are NLP variables, the hub at least as long as
        the disc is wide, its key's length within it): the disc an engine
        carries on a keyed crankshaft seat. False (default): an annulus on
        its bore, as the texts size it.

    Raises
    ------
    ValueError
        On an unknown name, a non-positive length, or a bad H/B range; and for
        ``outer_diameter`` with a ``disc`` and no ``max_width`` (an ever
        thinner, wider disc makes the diameter as small as one likes).
    """

    geometry: str = "rim"
    hb_ratio: tuple[float, float] = (1.5, 2.0)
    max_outer_diameter: float = math.inf
    max_width: float = math.inf
    d_mean: float | None = None
    objective: str = "mass"
    criterion: str = "rim_speed"
    safety_factor: float | None = None
    bore: float | None = None
    arms: tuple[int, ...] = DEFAULT_ARMS
    min_wall: float | None = None
    rim_speed: float | None = None
    round_to: float | None = None  # 0: not rounded, said so
    round_strict: bool = True
    diameter_series: str | None = None
    rim_share: float = 1.0
    prune: bool = True
    fem_check: bool | None = None
    stress_factors: tuple[StressFactor, ...] = ()
    castability: casting.Overrides = casting.Overrides()
    disc_hub: bool = False

    def stress_factors_for(self, material: str, shaft: str, n_arms: int = 0) -> dict[str, float]:
        """The :attr:`stress_factors` of one combination (material and shaft names, arm count): part -> factor."""
        return {
            f.part: f.factor
            for f in self.stress_factors
            if (f.material, f.shaft, f.n_arms) == (material, shaft, n_arms)
        }

    def textbook(self, bore: float | None = None) -> bool:
        """Whether this is the textbook design: a bare wheel without a bore sized by the rim speed limit
        (the closed forms and the NLP of :mod:`flyopt.design.nlp`); anything else is a whole wheel
        (:mod:`flyopt.design.wheel`). ``bore`` [m] is the combination's (a disc with a bore is an annulus)."""
        return (
            self.geometry in geometry.BARE
            and self.criterion in (Criterion.RIM_SPEED, Criterion.MEAN_RIM_SPEED)
            and not (self.geometry == Geometry.DISC and bore)
        )

    @property
    def by_mean_rim_speed(self) -> bool:
        """Whether the courses' convention sizes the rim: D_m where the rim reaches v_max at the mean speed."""
        return self.criterion == Criterion.MEAN_RIM_SPEED

    @property
    def pins_d_mean(self) -> bool:
        """Whether every combination's mean diameter is pinned: given (d_mean), or set by the courses' rim
        convention (each combination's own, :attr:`flyopt.design.combination.Combination.d_mean`)."""
        return self.d_mean is not None or self.by_mean_rim_speed or self.rim_speed is not None

    @property
    def has_envelope(self) -> bool:
        """Whether an envelope limits the outer diameter."""
        return self.max_outer_diameter < math.inf

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: limits that are not set are None."""
        return {
            "geometry": self.geometry,
            "hb_ratio": list(self.hb_ratio),
            "max_outer_diameter": _none_if_inf(self.max_outer_diameter),
            "max_width": _none_if_inf(self.max_width),
            "d_mean": self.d_mean,
            "objective": self.objective,
            "criterion": self.criterion,
            "safety_factor": self.safety_factor,
            "bore": self.bore,
            "arms": list(self.arms),
            "min_wall": self.min_wall,
            "rim_speed": self.rim_speed,
            "rim_share": self.rim_share,
            "round_to": self.round_to,
            "diameter_series": self.diameter_series,
            "prune": self.prune,
            "fem_check": self.fem_check,
            "disc_hub": self.disc_hub,
            "process": self.castability.process,
            "castability": {
                "min_wall": [list(row) for row in self.castability.min_wall]
                if self.castability.min_wall is not None
                else None,
                "section_ratio": self.castability.section_ratio,
            },
        }

    def __post_init__(self) -> None:
        choice(self.geometry, geometry.GEOMETRIES, "geometry")
        choice(self.objective, OBJECTIVES, "objective")
        try:
            low, high = self.hb_ratio
        except (TypeError, ValueError) as err:
            raise ValueError(f"hb_ratio must be a pair (min, max) of H/B, got {self.hb_ratio!r}") from err
        low = _positive(low, "hb_ratio min", "[-]")
        high = _positive(high, "hb_ratio max", "[-]")
        if low > high:
            raise ValueError(f"hb_ratio min {low} must not exceed max {high}")
        object.__setattr__(self, "hb_ratio", (low, high))
        for name in ("max_outer_diameter", "max_width"):
            value = getattr(self, name)
            limit = math.inf if value is None or value == math.inf else _positive(value, name, "[m]")
            object.__setattr__(self, name, limit)
        if self.d_mean is not None:
            object.__setattr__(self, "d_mean", _positive(self.d_mean, "d_mean", "[m]"))
        choice(self.criterion, CRITERIA, "criterion")
        if self.safety_factor is not None:
            factor = finite(self.safety_factor, "safety_factor [-]")
            if factor < 1.0:
                raise ValueError(
                    f"safety_factor [-] must be >= 1 (the allowable stress is the "
                    f"strength divided by it), got {self.safety_factor!r}"
                )
            object.__setattr__(self, "safety_factor", factor)
        if self.bore is not None:
            bore = finite(self.bore, "bore [m]")
            if bore < 0.0:
                raise ValueError(f"bore [m] must be >= 0 (0: no bore), got {self.bore!r}")
            if bore >= self.max_outer_diameter:
                raise ValueError(f"bore {bore} m must be smaller than max_outer_diameter {self.max_outer_diameter} m")
            object.__setattr__(self, "bore", bore)
        try:
            arms = tuple(self.arms)
        except TypeError as err:
            raise ValueError(f"arms must be a list of arm counts, got {self.arms!r}") from err
        if not arms or any(isinstance(n, bool) or not isinstance(n, int) or n < 3 for n in arms):
            raise ValueError(f"arms must be a non-empty list of whole arm counts >= 3, got {list(arms)!r}")
        if len(set(arms)) != len(arms):
            raise ValueError(f"arms lists an arm count twice: {list(arms)!r}")
        object.__setattr__(self, "arms", arms)
        if not isinstance(self.prune, bool):
            raise ValueError(f"prune must be true or false, got {self.prune!r}")
        if self.fem_check is not None and not isinstance(self.fem_check, bool):
            raise ValueError(f"fem_check must be true or false, got {self.fem_check!r}")
        if self.diameter_series is not None:
            choice(self.diameter_series, preferred.SERIES, "diameter_series")
        if not isinstance(self.disc_hub, bool):
            raise ValueError(f"disc_hub must be true or false, got {self.disc_hub!r}")
        if self.disc_hub and self.geometry != Geometry.DISC:
            raise ValueError(
                f"disc_hub is a disc's (geometry disc), not {self.geometry}'s: web and arms wheels have a hub"
            )
        factors = tuple(StressFactor(*f) for f in self.stress_factors)
        if any(not finite(f.factor, "a stress factor [-]") >= 1.0 for f in factors):
            raise ValueError(f"stress_factors must be >= 1 (a concentration on the modelled stress), got {factors!r}")
        object.__setattr__(self, "stress_factors", tuple(sorted(factors)))
        object.__setattr__(self, "castability", _castability(self.castability))
        if self.min_wall is not None:
            object.__setattr__(self, "min_wall", _positive(self.min_wall, "min_wall", "[m]"))
        if self.round_to:  # 0: the continuous optimum, asked for
            object.__setattr__(self, "round_to", _positive(self.round_to, "round_to", "[m]"))
        share = finite(self.rim_share, "rim_share [-]")
        if not 0.0 < share <= 1.0:
            raise ValueError(
                f"rim_share [-] must lie in (0, 1] (the share of the inertia the rim gives), got {share!r}"
            )
        object.__setattr__(self, "rim_share", share)
        if self.by_mean_rim_speed and self.geometry not in BOOK_RIM_GEOMETRIES:
            raise ValueError(
                f"criterion 'mean_rim_speed' sizes a bare rim (geometry {' or '.join(map(repr, BOOK_RIM_GEOMETRIES))}), "
                f"not a {self.geometry!r}: use 'rim_speed' or 'stress'"
            )
        if self.rim_speed is not None:
            object.__setattr__(self, "rim_speed", _positive(self.rim_speed, "rim_speed", "[m/s]"))
            if self.geometry not in BOOK_RIM_GEOMETRIES:
                raise ValueError(f"rim_speed is a bare rim's (geometry 'rim' or 'thin_rim'), not a {self.geometry!r}'s")
            if self.criterion == Criterion.STRESS:
                raise ValueError(
                    "rim_speed pins a rim sized by its rim speed; under the stress criterion the wheel is designed "
                    "whole: give d_mean (2 v / omega'_m) instead"
                )
            if self.d_mean is not None or self.by_mean_rim_speed:
                raise ValueError(
                    "rim_speed pins the mean diameter, as "
                    + (
                        "d_mean does: give one of them"
                        if self.d_mean is not None
                        else "criterion 'mean_rim_speed' does"
                    )
                )
        if share < 1.0 and self.geometry not in BOOK_RIM_GEOMETRIES:
            raise ValueError(
                f"rim_share is the share of a bare rim (geometry 'rim' or 'thin_rim'), not of a {self.geometry!r}, "
                "whose own web or arms and hub flyopt designs"
            )
        if self.objective == Objective.OUTER_DIAMETER and self.geometry == Geometry.DISC and self.max_width == math.inf:
            raise ValueError(
                "objective 'outer_diameter' with geometry 'disc' needs "
                "max_width: without it an ever thinner, wider disc makes "
                "the diameter as small as one likes"
            )


def _castability(over: Any) -> casting.Overrides:
    """A spec's castability overrides checked: a known process, walls and a ratio within their ranges."""
    over = casting.Overrides(*over) if not isinstance(over, casting.Overrides) else over
    known = (*casting.processes(), casting.NONE)
    if over.process is not None and over.process not in known:
        raise ValueError(f"castability process must be one of {', '.join(known)}, got {over.process!r}")
    rows = over.min_wall
    if rows is not None:
        try:
            rows = tuple((float(s), float(w)) for s, w in rows)
        except (TypeError, ValueError) as err:
            raise ValueError(f"castability min_wall must be rows (size, wall) [m], got {rows!r}") from err
        low, high = casting.WALL_RANGE
        if (
            not rows
            or any(not (math.isfinite(s) and s >= 0.0 and low <= w <= high) for s, w in rows)
            or any(s1 <= s0 or w1 < w0 for (s0, w0), (s1, w1) in zip(rows, rows[1:]))
        ):
            raise ValueError(
                f"castability min_wall rows must have sizes >= 0 increasing and walls in [{low:g}, {high:g}] m "
                f"not decreasing, got {rows!r}"
            )
    ratio = over.section_ratio
    if ratio is not None:
        low, high = casting.RATIO_RANGE
        if not low <= finite(ratio, "castability section_ratio [-]") <= high:
            raise ValueError(f"castability section_ratio [-] must lie in [{low:g}, {high:g}], got {ratio!r}")
        ratio = float(ratio)
    return casting.Overrides(over.process, rows, ratio)


def _none_if_inf(value):
    return None if value == math.inf else value
