"""What every rule shares: the base class, the laws each rule imposes in words, and the
check of a whole-number argument.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, ClassVar, NamedTuple

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.solve.conditions import tidied
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.registry import Conduct, conduct
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.given import shown
from rigidimpact.symbolic.notation import Given
from rigidimpact.symbolic.rewrite import tidy


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

    def answer(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        """The one door every answer goes through, whatever its source: one contact
        is the contact's own impact under its own laws, whatever the rule (the source's
        own closed form where it has one, :meth:`ImpulseRows.own_answer`, else the
        rules' one-contact step, :meth:`one_contact`), reported under this rule; two
        or more are :meth:`outcomes`, checked (:meth:`checked_outcomes`)."""
        if len(problem.contacts) == 1:
            own = problem.own_answer(self)
            if own is None:
                return (self.one_contact(problem),)
            if own.rule == self.name:
                return (own,)
            return (replace(own, rule=self.name, order=(
                (problem.contacts[0].name,) if self.in_turn else ())),)
        return self.checked_outcomes(problem)

    def one_contact(self, problem: ImpulseRows) -> Solution:
        """A problem of one contact: its own impact (:func:`own_step`), read back by the
        source (``problem.outcome``) under this rule's name, certified there."""
        step = own_step(problem, 0, problem.u_before)
        (contact,) = problem.contacts
        return alone_outcome(problem, 0, self.name, step.impulse, step.course, step.after,
                             order=(contact.name,) if self.in_turn else (),
                             notes=step.notes)

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


class Step(NamedTuple):
    """One contact's own impact: its impulse (n, t1[, t2]), course, the generalized
    velocities after, the tolerance where it was followed in floating point (None:
    exact), and the law's notes."""

    impulse: sp.Matrix
    course: str
    after: sp.Matrix
    tolerance: float | None
    notes: tuple[str, ...]


def own_step(problem: ImpulseRows, k: int, u: sp.Matrix) -> Step:
    """Contact k's impact alone under its own laws, from speeds u, in its frame with
    one tangent or two: the rules' one-contact step, written once (the tangential law's
    one face, :meth:`~rigidimpact.laws.law.ContactLaw.impulse`: Routh's method or the
    cone for Coulomb, Walton's for rough). Returns the impulse, its course, the
    generalized velocities after, the tolerance where it was followed in floating
    point, and the law's notes (a source's stated tolerance, a 3-D collision's, is the
    face's)."""
    restitution, tangential = problem.contacts[k].laws
    rows = problem.contact_rows(k)
    W = (rows * problem.M_inverse * rows.T).applyfunc(tidied)
    if W.det() == 0 and tangential.grips and not tangential.solved_by_regimes:
        raise InputError(f"{problem.contacts[k].name}.tangential",
                         f"{tangential.name}: the touching points have one degree of "
                         "freedom here (their 2x2 W is singular), so they cannot both "
                         "stop slipping and leave by the restitution law; tangential = "
                         "\"coulomb\" follows them (Routh's method), or make it smooth")
    out = tangential.impulse(W, (rows * u).applyfunc(tidy), restitution, problem.tolerance)
    P = out.impulse.applyfunc(tidy)
    u_after = (u + problem.M_inverse * (rows.T * P)).applyfunc(tidy)
    return Step(P, out.course, u_after, None if out.exact else out.tolerance,
                tuple(out.notes))


def alone_outcome(problem: ImpulseRows, k: int, rule: str, P: sp.Matrix, course: str,
                  u: sp.Matrix, courses: tuple[str, ...] | None = None,
                  **more: Any) -> Solution:
    """The outcome in which contact k alone carried the impulse P (n, t1[, t2]) on its
    course, every other contact nothing, read back by the source under `rule`;
    `courses` (default: k's course, the others released) and the rest as
    ``problem.outcome`` takes them."""
    n = len(problem.contacts)
    normal, along, across = sp.zeros(n, 1), sp.zeros(n, 1), sp.zeros(n, 1)
    normal[k], along[k] = P[0], P[1]
    if len(P) == 3:
        across[k] = P[2]
    name = problem.contacts[k].name
    if problem.tangents == 2:  # in space: its second tangent too
        more["tangent_impulses"] = {c.name: (along[i], across[i])
                                    for i, c in enumerate(problem.contacts)}
    if problem.frictional:
        more["tangential"] = problem.named(along)
    order = more.pop("order", ())
    return problem.outcome(rule, order, u, problem.named(normal),
                           (name,) if P[0] != 0 else (), courses=courses or tuple(
                               Given(f"{c.name}: ") + course if i == k else
                               f"{c.name}: released" for i, c in enumerate(problem.contacts)),
                           **more)
