"""Input: scene files (TOML, with units) to a Scene, the sweep grammar, a press's and a drive's tables.

A ring on top of the pipeline: it builds the domain objects of the stages
below (curves, mechanisms, motors, the design spec) from checked fields.
"""
