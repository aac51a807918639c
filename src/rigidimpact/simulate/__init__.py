"""Simulation after the impact: only the effects a scene asks for.

:func:`make_plan` turns a scene's ``[simulate]`` table into the smallest model that
answers it; :func:`run` carries it out.
"""

from rigidimpact.simulate.planner import EFFECTS, Plan, goes_past_impact, make_plan
from rigidimpact.simulate.runner import Outcome, explain, impact_view, run

__all__ = ["EFFECTS", "Plan", "goes_past_impact", "make_plan", "Outcome", "run", "explain",
           "impact_view"]
