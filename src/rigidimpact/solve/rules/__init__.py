"""How contacts that close at the same instant act together: one rule a module, each
working on the one impulse problem (:class:`~rigidimpact.solve.problem.ImpactProblem`)
and returning the same :class:`~rigidimpact.solve.solution.Solution`.

A new rule is one class: subclass :class:`Rule` and give it ``name`` and ``outcomes``.
"""

from __future__ import annotations

from rigidimpact.solve.rules.base import RULE_LAWS, RULES, Rule, rule_laws, whole_number
from rigidimpact.solve.rules.compliant import Compliant
from rigidimpact.solve.rules.driven import Driven
from rigidimpact.solve.rules.sequential import MAX_PASSES, Sequential, sequential_passes
from rigidimpact.solve.rules.simultaneous import Simultaneous

__all__ = ["Rule", "Simultaneous", "Sequential", "Compliant", "Driven", "RULE_TYPES", "RULES",
           "RULE_LAWS", "rule_laws", "whole_number", "sequential_passes", "MAX_PASSES"]

# the one registry of the built-in rules: the scene reader takes its names from here
RULE_TYPES: tuple[type[Rule], ...] = (Simultaneous, Sequential, Compliant, Driven)
