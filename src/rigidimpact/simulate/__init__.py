"""Simulation after the impact: only the effects a scene asks for."""
