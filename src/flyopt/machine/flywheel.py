"""A flywheel that exists: the wheel a scene's [flywheel] gives, to analyse rather than design."""

from __future__ import annotations

from dataclasses import dataclass

from flyopt.machine.transmission import inertia_at_reference


@dataclass(frozen=True)
class ExistingFlywheel:
    """A flywheel already on the machine (docs/flywheel-design.md, "A flywheel that exists").

    Attributes
    ----------
    inertia : float
        About its own axis [kg*m^2]: the ``inertia`` given, or m k² from ``mass``
        and ``radius_of_gyration``.
    shaft : str
        The [[shaft]] it turns with.
    speed_ratio : float
        ω_shaft / ω_reference of that shaft [-].
    mass, radius_of_gyration : float or None
        [kg], [m], when the wheel was given by them.
    angles : tuple of float
        Angles of the reference shaft [rad] at which the check reports the
        angular acceleration (the book's "when the crank has turned 45°").
    """

    inertia: float
    shaft: str
    speed_ratio: float
    mass: float | None = None
    radius_of_gyration: float | None = None
    angles: tuple[float, ...] = ()

    @property
    def j_at_reference(self) -> float:
        """Its inertia moved to the reference shaft, J (ω_shaft/ω)² [kg*m^2]."""
        return inertia_at_reference(self.inertia, self.speed_ratio)

    def to_dict(self) -> dict[str, float | str | list[float] | None]:
        """The given wheel, SI."""
        return {
            "inertia": self.inertia,
            "shaft": self.shaft,
            "speed_ratio": self.speed_ratio,
            "mass": self.mass,
            "radius_of_gyration": self.radius_of_gyration,
            "j_at_reference": self.j_at_reference,
            "angles": list(self.angles),
        }
