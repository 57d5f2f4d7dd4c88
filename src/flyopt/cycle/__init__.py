"""Cycle analysis: the work balance, the energy indicator diagram and A_max (docs/flywheel-design.md, section 4)."""
