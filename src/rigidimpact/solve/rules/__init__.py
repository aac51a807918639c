"""How contacts that close at the same instant act together: one rule a module, each
working on the one impulse problem (:class:`~rigidimpact.solve.problem.ImpulseRows`)
and returning the same :class:`~rigidimpact.solve.solution.Solution`.

A new rule is one class (subclass :class:`Rule`, give it ``name`` and ``outcomes``, and
``from_settings`` if it reads ``[impact]`` settings) and one line in :data:`RULE_TYPES`.

The default rule, in the plane and in space alike, is :data:`DEFAULT_RULE`: the
simultaneous rule, the one that answers every scene's contacts, with symbols or numbers,
exactly where the data are exact. The driven rule (one contact strikes, the others
rest, followed through the impulse) is asked for by name.
"""

from __future__ import annotations

from rigidimpact.errors import InputError
from rigidimpact.solve.registry import RULES as REGISTRY
from rigidimpact.solve.rules.base import (
    Rule,
    RuleSettings,
    rule_laws,
    whole_number,
)
from rigidimpact.solve.rules.compliant import Compliant
from rigidimpact.solve.rules.driven import Driven
from rigidimpact.solve.rules.sequential import MAX_PASSES, Sequential, sequential_passes
from rigidimpact.solve.rules.simultaneous import Simultaneous

__all__ = ["Rule", "RuleSettings", "DEFAULT_RULE", "rule_named", "RULE_CLASSES",
           "Simultaneous", "Sequential", "Compliant", "Driven", "RULE_TYPES", "RULES",
           "RULE_LAWS", "rule_laws", "whole_number", "sequential_passes", "MAX_PASSES"]

# the one registry of rules, name to class: a new rule is one line here (the scene
# readers of both dimensions, the 3-D collision and rule_named read it)
RULE_CLASSES: dict[str, type[Rule]] = REGISTRY
RULE_CLASSES.update({
    Simultaneous.name: Simultaneous,
    Sequential.name: Sequential,
    Compliant.name: Compliant,
    Driven.name: Driven,
})
RULE_TYPES: tuple[type[Rule], ...] = tuple(RULE_CLASSES.values())  # the built-in ones
RULES = tuple(RULE_CLASSES)  # their names
RULE_LAWS = {name: rule.said for name, rule in RULE_CLASSES.items()}  # in words
DEFAULT_RULE = Simultaneous.name


def rule_named(name: str | None, settings: RuleSettings | None = None) -> Rule:
    """The rule a scene names (None: :data:`DEFAULT_RULE`), built from its settings: the
    one place, for both dimensions, where a rule's name becomes its object.

    Examples
    --------
    >>> rule_named(None)
    Simultaneous()
    >>> rule_named("sequential", RuleSettings(order=("a", "b")))
    Sequential(order=('a', 'b'), sample=None, seed=0)
    """
    if name is None:
        name = DEFAULT_RULE
    if not isinstance(name, str) or name not in RULE_CLASSES:
        raise InputError("impact.rule", f"must be one of {', '.join(RULE_CLASSES)}, got "
                         f"{name!r}")
    return RULE_CLASSES[name].from_settings(settings or RuleSettings())
