"""The one registry of rules, name to class, and what a rule's answers promise.

The registry is filled in one place, :mod:`rigidimpact.solve.rules` (a new rule is one
line there), and read wherever a rule is met by the name an answer carries: the scene
readers, the certificate, the printed equations, a mechanics system's reading back.
Nothing else tests a rule's name.

What a rule promises is :class:`Conduct`, the base of every rule: its class attributes
say how its answers are checked and printed, so a rule written outside the package
states them once, on its class, and is checked as it promises.

Examples
--------
>>> conduct("a rule nobody registered").whole_impact
False
"""

from __future__ import annotations

from typing import Any, ClassVar

__all__ = ["Conduct", "RULES", "conduct"]


class Conduct:
    """What a rule's answers promise (the defaults: a rule that says nothing more)."""

    # each acting contact's own law holds over the whole impact, at the velocity level
    # (its law's target after, a released contact opening at least as fast): the
    # simultaneous rule; otherwise a contact's total is a sum of steps or a path's
    whole_impact: ClassVar[bool] = False
    # an integrating rule's answers are held to this relative tolerance (1000 times
    # its integrator's), not to their arithmetic's
    stated_tolerance: ClassVar[float | None] = None
    # a closing speed left below this ends the rule (the sequential passes)
    settles: ClassVar[float] = 0.0
    # a contact may still approach after the impact (springs let go on their own
    # time): said as a warning, not a failed check
    may_stay_closing: ClassVar[bool] = False
    # the contacts act one at a time, in an order (or every order, or a sample)
    in_turn: ClassVar[bool] = False
    # how a contact's impulse arises, where it is printed in place of its law
    # ({name}: the contact)
    impulse_words: ClassVar[str] = "{name}'s impulse under the rule"
    # what every answer of the rule says of itself, in space (empty: nothing)
    summary: ClassVar[str] = ""
    # the rule as a 3-D scene's evaluate names it (empty: its label)
    spoken: ClassVar[str] = ""
    # the laws the rule imposes, in words, and with friction where it says more
    said: ClassVar[str] = ""
    said_with_friction: ClassVar[str] = ""
    name: ClassVar[str] = ""

    @classmethod
    def in_words(cls, frictional: bool = False) -> str:
        """What the rule imposes, in words (with friction where any contact has it): its
        own ``said``, or its docstring's first paragraph."""
        if frictional and cls.said_with_friction:
            return cls.said_with_friction
        return cls.said or (cls.__doc__ or f"the {cls.name} rule").strip().split("\n\n")[0]


RULES: dict[str, Any] = {}  # name to Rule class, filled by rigidimpact.solve.rules


def conduct(name: str) -> type[Conduct]:
    """The registered rule of that name (its class), or the defaults of
    :class:`Conduct` for a name not registered."""
    found = RULES.get(name)
    return found if isinstance(found, type) and issubclass(found, Conduct) else Conduct
