"""The drive: motor size, transmission ratio and flywheel designed together.

A stage above the design: for each motor of a catalogue it calls the stages
below (reduce, the periodic models of sizing, the analysis, the wheel design)
and never copies them. :mod:`~flyopt.drive.codesign` decides each motor size
exactly and chooses the drive; :mod:`~flyopt.drive.relaxation` is the continuous
relaxation over the catalogue that orders the sizes and gives the sensitivities.
"""
