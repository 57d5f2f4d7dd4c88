"""The mounting shaft: strength, deflection, lateral critical speed and the torsional check (issue 30, items 2-4).

:mod:`~flyopt.design.shaft.strength` (Shigley's fatigue method: Marin factors,
notch sensitivity, the DE shaft equations and the first-cycle yield check),
:mod:`~flyopt.design.shaft.beam` (a stepped shaft on two bearings: deflection
and slope by integration of M/EI), :mod:`~flyopt.design.shaft.lateral`
(Jeffcott, Rayleigh, Dunkerley and a beam finite-element model with the
wheel's gyroscopic effect) and :mod:`~flyopt.design.shaft.torsional` (the
drive train's torsional model, :mod:`flyopt.machine.torsion`, driven by the
orders of the cycle's net torque: critical speeds and margins against the
running range, Campbell data, forced response over speed).
:mod:`~flyopt.design.shaft.check` joins them for a shaft a scene describes as a
part, with the wheel designed for it and the cycle that sized it, and
:mod:`~flyopt.design.shaft.cycle` makes that check the designer's post-check
(docs/flywheel-design.md, sections 24 to 26).

The package is on the design floor because the strength check takes its
strengths from :class:`flyopt.design.materials.Material` (the one place a
material's strength at a section is decided).
"""
