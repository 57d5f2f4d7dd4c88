"""Speed against error: every way of getting an answer, timed and checked.

``flyopt bench`` (and ``benchmarks/bench_speed_error.py``) runs, in one
process and on the same inputs, each method of getting a flywheel answer and
reports for each its time per solve (median and spread over repeats) and its
error against a reference of known accuracy. A leaf of the package: nothing
in flyopt imports it but the command line's dispatch to :func:`main`.

One module per concern:

:mod:`~flyopt.bench.timing`
    The run's configuration, the timer, the :class:`~flyopt.bench.timing.Row`
    it records, the CPU pinning and the machine header.
:mod:`~flyopt.bench.references`
    The bench's own exact answers, written without flyopt: A_max of tables
    in rational arithmetic, the annulus integral, the rim model of one
    material on one shaft and its lightest rim by a 1-D root search.
:mod:`~flyopt.bench.peers`
    What other codes do: sampled quadrature rules, SLSQP and brute-force grids.
:mod:`~flyopt.bench.cycle`, :mod:`~flyopt.bench.design`, :mod:`~flyopt.bench.geometry`, :mod:`~flyopt.bench.inertia`
    The sections of the speed-against-error run (A_max; the design ranking;
    the geometry models; the required-inertia models), registered in
    :data:`~flyopt.bench.sections.SECTIONS`.
:mod:`~flyopt.bench.hard`
    The generated hard set (``--hard``).
:mod:`~flyopt.bench.output`
    CSV, plot and Markdown, with the targets they judge.
:mod:`~flyopt.bench.cli`
    The options and :func:`main`. A full run writes into
    ``benchmarks/results``; a ``--quick`` run writes only into an
    ``--output-dir`` it is given.
"""

from flyopt.bench.cli import main

__all__ = ["main"]
