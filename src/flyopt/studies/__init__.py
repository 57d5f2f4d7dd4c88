"""Studies over many designs: sweeps, Pareto fronts and material trade-offs."""
