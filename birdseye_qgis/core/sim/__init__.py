"""Simulation: a deterministic synthetic campaign (field, flight, rendered frames, terrain)."""
