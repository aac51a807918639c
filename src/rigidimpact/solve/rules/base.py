"""What every rule shares: the base class, the laws each rule imposes in words, and the
check of a whole-number argument.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from rigidimpact.errors import InputError
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.registry import Conduct, conduct
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.given import shown


def rule_laws(rule: str, frictional: bool = False) -> str:
    """The laws a rule imposes, in words (with friction when any contact has it), by the
    name an answer carries: the registered rule's own words; a rule not registered is
    named, never a KeyError."""
    found = conduct(rule)
    if found is Conduct:
        return f"the {rule} rule (not built in: see its class)"
    return found.in_words(frictional)


def whole_number(name: str, value: Any, least: int, most: int | None = None,
                 why: str = "") -> int:
    """`value` as an int in [least, most], or InputError naming `name` (a bool, a float
    or a string is refused, not rounded or parsed).

    Examples
    --------
    >>> whole_number("n", 3, 2)
    3
    >>> whole_number("n", 2.5, 2)
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: n: must be a whole number, not float 2.5
    """
    if isinstance(value, bool) or not hasattr(value, "__index__"):
        raise InputError(name, f"must be a whole number, not {type(value).__name__} "
                         f"{value!r}")
    value = int(value.__index__())
    if value < least:
        raise InputError(name, f"must be at least {least}, got {value}")
    if most is not None and value > most:
        raise InputError(name, f"{value} is past the budget of {most}{why}")
    return value


@dataclass(frozen=True)
class RuleSettings:
    """What a scene's ``[impact]`` table says besides the rule's name, the same in the
    plane and in space: the sequential rule's order (None: every order) or a seeded
    sample of orders, the compliant rule's stiffness per contact and spring law, and
    the relative tolerance of a rule that integrates."""

    order: tuple[str, ...] | None = None
    sample: tuple[int, int] | None = None  # (orders, seed)
    compliance: tuple[tuple[float, ...], bool] = ((1e6,), False)
    tolerance: float | None = None


class Rule(Conduct):
    """How several contacts that close at the same instant act together.

    A rule is one small class in its own module: :meth:`outcomes` says what it makes of
    an impulse problem (:class:`~rigidimpact.solve.problem.ImpulseRows`: one outcome,
    or one per case or order), so every rule returns the same
    :class:`~rigidimpact.solve.solution.Solution` whatever the source of the problem (the
    built-in shapes, joints, a sympy.physics.mechanics system).
    :data:`~rigidimpact.solve.rules.RULE_CLASSES` is the registry, name to class, the
    scene readers read; a new rule needs no entry there to be used from Python.

    The protocol: what a rule may read of the problem, all public on
    :class:`~rigidimpact.solve.problem.ImpulseRows`, the one problem without bodies that
    every source assembles (the planar shapes, a 3-D collision, a mechanics system):

    - the data: ``contacts`` (each with its ``laws``: restitution, tangential),
      ``coordinates``, ``u_before``, ``M_inverse``, ``J``, ``symbols``, ``frictional``,
      ``dense``, ``joints`` (rows a source keeps itself), ``facets`` (a pyramid asked
      for), ``tangents`` (0, 1 or 2 a contact) and each contact's block of rows,
      ``contact_rows(k)`` exact and ``frame_rows(k)`` in floating point;
    - the rows the rules solve with, each contact's scaled by its :attr:`row_scale`
      (rational where the data are): ``scaled_J``, ``scaled_J_t``, ``scaled_W``,
      ``scaled_velocity_before``, ``sparse_rows``, ``inverse_inertia``, and at scale
      ``W_entries``, ``float_W()``, ``rational_rows``, ``rational_W``;
    - the steps: ``closing(k, u)`` and ``closings(u)`` (normal velocities at u),
      ``kick(u, impulses)`` (u after impulses on the scaled rows), ``leaving(k, v)``
      (contact k's restitution law's target), ``acts_by_impulse()`` (Poisson's law
      together), ``order_index(order)``;
    - the refusals: ``numbers_only(rule)``, ``smooth_only(where)``.

    What it returns: ``problem.outcome(rule, order, u_after, problem.named(impulses),
    acted, ...)``, one :class:`Solution` each, certified on the way out (an answer that
    breaks a law is never returned). Its description in words is :meth:`laws`: a new
    rule overrides it or is named by its docstring's first line.
    """

    name: ClassVar[str] = ""

    @classmethod
    def from_settings(cls, settings: RuleSettings) -> Rule:
        """The rule built from a scene's ``[impact]`` settings (each rule takes the ones
        it has: an order, a sample of orders, springs, a tolerance); a rule with no
        settings is built bare."""
        return cls()

    def outcomes(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        raise NotImplementedError

    def checked_outcomes(self, problem: Any) -> tuple[Solution, ...]:
        """:meth:`outcomes`, with what it returned checked: a non-empty tuple (or list)
        of :class:`Solution`, or InputError naming the rule (a rule written outside the
        package that returns anything else is told what a rule must return)."""
        method = f"{type(self).__name__}.outcomes(problem)"
        if type(self).outcomes is Rule.outcomes:
            raise InputError("rule", f"{method} is not written: a rule defines it, "
                             "returning a tuple of Solution (one per outcome)")
        found = self.outcomes(problem)
        if not isinstance(found, (tuple, list)):
            raise InputError("rule", f"{method} must return a tuple of Solution (one per "
                             f"outcome), not {type(found).__name__} {shown(found)}")
        if not found:
            raise InputError("rule", f"{method} must return a tuple of Solution with at "
                             "least one outcome, not an empty one")
        for k, outcome in enumerate(found):
            if not isinstance(outcome, Solution):
                raise InputError("rule", f"{method} must return a tuple of Solution (one "
                                 f"per outcome); item {k} is {type(outcome).__name__} "
                                 f"{shown(outcome)}")
        return tuple(found)

    def laws(self, frictional: bool = False) -> str:
        """What the rule imposes, in words."""
        return self.in_words(frictional)
