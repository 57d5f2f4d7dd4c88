"""A scene's drive train as a torsional chain: its elements in order, from the motor to the crank (issue 30, item 4).

Plain data in SI, read from a described ``[[shaft]]``'s ``train`` (:mod:`flyopt.io.shaft_section`)
and built into a :class:`flyopt.machine.torsion.TorsionalModel` with the wheel designed for that shaft
by :func:`flyopt.design.shaft.train.train_model` (docs/flywheel-design.md, section 26).

The list alternates lumped inertias and the elastic elements between them. Inertias with no
elastic element between them turn together: a gear mesh (the two wheels on shafts of different
speed ratios), or a pulley keyed beside a rotor. The cycle's net torque enters at the last
inertia (the crank end); the first is the motor end.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["TrainInertia", "TrainSpring", "SPRING_KINDS"]

#: The elastic elements of a train: a given torsional stiffness, a round shaft piece, a belt, and a
#: span of the described shaft's own steps.
SPRING_KINDS = ("stiffness", "piece", "belt", "span")


@dataclass(frozen=True)
class TrainInertia:
    """A lumped inertia of the train.

    Attributes
    ----------
    name : str
        What it is ("motor rotor", "crank").
    shaft : str
        The [[shaft]] it turns with.
    ratio : float
        That shaft's speed ratio omega / omega_reference.
    inertia : float or None
        J [kg*m^2] about its axis; None for the flywheel being designed (its J comes with each design).
    """

    name: str
    shaft: str
    ratio: float
    inertia: float | None

    @property
    def is_wheel(self) -> bool:
        """Whether this is the designed flywheel's place."""
        return self.inertia is None


@dataclass(frozen=True)
class TrainSpring:
    """An elastic element between two inertias of the train, on the shaft ``shaft`` (speed ratio ``ratio``).

    ``kind`` is one of :data:`SPRING_KINDS`:

    - ``stiffness``: ``stiffness`` [N*m/rad] given (a coupling);
    - ``piece``: a solid round shaft piece of ``length`` and ``diameter`` [m] in ``material``,
      k = G pi d^4 / (32 l);
    - ``belt``: two spans of stretch stiffness ``stiffness`` [N/m] each on a pulley of ``radius`` [m] of
      ``shaft`` (the inertia before it), k = 2 k_b r^2 on that shaft;
    - ``span``: the described shaft's own steps from ``start`` to ``end`` [m], k = 1 / sum l_i / (G pi d_i^4 / 32).
    """

    name: str
    kind: str
    shaft: str
    ratio: float
    stiffness: float = 0.0
    length: float = 0.0
    diameter: float = 0.0
    material: str = ""
    radius: float = 0.0
    start: float = 0.0
    end: float = 0.0
