"""Sizing models: which model sizes the flywheel, and the energy, energy–mass and periodic models."""
