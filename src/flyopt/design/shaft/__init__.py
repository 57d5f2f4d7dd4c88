"""The mounting shaft: strength, deflection and lateral critical speed (issue 30, items 2 and 3).

:mod:`~flyopt.design.shaft.strength` (Shigley's fatigue method: Marin factors,
notch sensitivity, the DE shaft equations and the first-cycle yield check),
:mod:`~flyopt.design.shaft.beam` (a stepped shaft on two bearings: deflection
and slope by integration of M/EI) and :mod:`~flyopt.design.shaft.lateral`
(Jeffcott, Rayleigh, Dunkerley and a beam finite-element model with the
wheel's gyroscopic effect). Library modules: no scene describes a shaft yet
and nothing in the design calls them (docs/flywheel-design.md, section 24).

The package is on the design floor because the strength check takes its
strengths from :class:`flyopt.design.materials.Material` (the one place a
material's strength at a section is decided).
"""
