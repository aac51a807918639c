"""The sequential rule: one contact at a time, in a given order, in every order or in a
seeded sample of orders; each step is that contact's own impact under its own laws
(Newton's e, Routh's method for Coulomb friction, Walton's rough law), and passes
repeat until no contact approaches.
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import ClassVar

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.solve.certificate import SETTLED as CERTIFICATE_SETTLED
from rigidimpact.solve.conditions import (
    case_conditions,
    tidied,
)
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.rules.base import Rule, RuleSettings, own_step, whole_number
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.rewrite import tidy

FLOAT_DIGITS = 60  # where exact algebra would nest roots: floating point at this precision
LONG_DIGITS = 200  # a rational this long is carried as a FLOAT_DIGITS Float from there


# a sequential run still going after this many impacts (and as many again per 100
# contacts) is refused: a budget of work, so the same scene is answered or refused alike
# on every machine at any load (three rough contacts ringing under the energetic law
# settle after 825 impacts; two contacts at e = 1 can ring for ever)
MAX_SEQUENTIAL_IMPACTS = 2000


MAX_PASSES = 1000  # sequential passes before the rule is declared endless


# a sequence of one-at-a-time impacts can go on forever while converging (inelastic
# collapse); it is cut where every contact's normal velocity left closing is this small
# next to the largest speed or spin before, the certificate's own line on its own scale
# (certificate.SETTLED: a contact may still close at 1e-40 of the largest speed, spin or
# impulse), so a run the rule ends is never one its check refuses
SETTLED = sp.Rational(repr(CERTIFICATE_SETTLED))


MAX_ORDERS = 720  # every order of up to six contacts


MAX_SAMPLED_ORDERS = 10000


# a sample of orders estimated (from the first order's passes) to make more impacts
# than this is refused before it runs
MAX_SAMPLE_IMPACTS = 200_000


@dataclass(frozen=True)
class Sequential(Rule):
    """One contact at a time in `order`; every order when `order` is None, or a seeded
    sample of `sample` orders.

    Examples
    --------
    >>> from rigidimpact.solve.collision import chain
    >>> from rigidimpact.solve.collision import chain
    >>> [o.label for o in chain(3).solve(Sequential(("c0", "c1")))]
    ['sequential c0, c1']
    """

    order: tuple[str, ...] | None = None
    sample: int | None = None  # with no order: this many orders drawn with `seed`
    seed: int = 0
    name: ClassVar[str] = "sequential"
    in_turn: ClassVar[bool] = True
    said: ClassVar[str] = (
        "every contact smooth; one contact at a time in the order given, each a two-body "
        "impact with Newton's e, repeated until no contact approaches")
    said_with_friction: ClassVar[str] = (
        "one contact at a time in the order given, each that contact's own impact under "
        "its own laws (Routh's method for Coulomb friction, Walton's for a rough "
        "contact); repeated until no contact approaches")
    settles: ClassVar[float] = CERTIFICATE_SETTLED  # passes end below this closing speed
    impulse_words: ClassVar[str] = ("the sum of {name}'s impulses in turn (each its own "
                                    "impact)")

    def __post_init__(self) -> None:
        if self.order is not None:
            if isinstance(self.order, str) or not all(
                    isinstance(x, str) for x in self.order):
                raise InputError("order", "must be a sequence of contact names, e.g. "
                                 f"(\"c0\", \"c1\"), not {self.order!r}")
            object.__setattr__(self, "order", tuple(self.order))
        if self.sample is not None:
            whole_number("sample", self.sample, 1, MAX_SAMPLED_ORDERS,
                          " sampled orders (each a whole sequential run)")
        whole_number("seed", self.seed, 0)

    @classmethod
    def from_settings(cls, settings: RuleSettings) -> Sequential:
        if settings.sample is not None and settings.order is None:
            return cls(None, *settings.sample)
        return cls(settings.order)

    def outcomes(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        if self.order is None and self.sample is not None:
            return sampled_orders(problem, self.sample, self.seed)
        if self.order is None:
            return every_order(problem)
        if problem.symbols:
            return sequential_cases(problem, self.order)
        return (sequential(problem, self.order),)


def _smooth_step(problem: ImpulseRows, k: int, u: list[sp.Expr], closing: sp.Expr) -> sp.Expr:
    """Contact k alone, smooth, with Newton's e: its impulse, with u changed in place
    (only the two bodies' coordinates the contact moves)."""
    impulse = tidy((problem.leaving(k, closing) - closing) / problem.scaled_W[k, k])
    if problem.dense:
        change = problem.M_inverse * problem.scaled_J[k, :].T * impulse
        for j in range(len(u)):
            u[j] = tidy(u[j] + change[j])
        return impulse
    for j, value in problem.sparse_rows[k]:
        u[j] = tidy(u[j] + value * impulse * problem.inverse_inertia[j])
    return impulse


def sequential(problem: ImpulseRows, order: Sequence[str]) -> Solution:
    """One contact at a time in `order`, passes repeated until none approaches.

    With e < 1 the passes can go on forever while the closing speeds shrink
    geometrically (a stack coming to rest): they stop once every closing speed left
    is below 1e-40 of the largest before, so such results are exact to that size.
    """
    problem.numbers_only("sequential")
    index = problem.order_index(order)
    u = list(problem.u_before)
    floating: list[str] = []
    across = [sp.Integer(0)] * len(index)  # in space, each contact's second tangent
    integrated: list[float] = []  # the tolerances of steps followed in floating point

    def step(k: int, closing: sp.Expr) -> tuple[sp.Expr, sp.Expr, str | None]:
        grips = problem.contacts[k].laws[1].grips
        if not floating and ((grips and not all(x.is_Rational for x in u))
                             or any(_long(x) for x in u)):
            # the arithmetic is chosen before the next case analysis: a state out of
            # the rationals (an energetic step's square root) would nest a root in
            # every later step, and contacts passing an impulse back and forth for
            # hundreds of passes (e = 0: inelastic collapse) grow rationals of
            # thousands of digits, so from here on every step starts from the state
            # as FLOAT_DIGITS-digit Floats
            floating.append(problem.contacts[k].name)
        if floating:
            u[:] = [_rounded(x) for x in u]
        if grips:  # its own impact (Routh's for Coulomb; the cone in space)
            P, course, after, tolerance, _ = own_step(problem, k, sp.Matrix(u))
            if floating:
                P, after = P.applyfunc(_rounded), after.applyfunc(_rounded)
            if tolerance is not None:
                integrated.append(tolerance)
            u[:] = list(after)
            if len(P) == 3:
                across[k] += P[2]
            return P[0], P[1], course
        return _smooth_step(problem, k, u, closing), sp.Integer(0), None

    taken_steps = itertools.count(1)

    def checked(k: int, closing: sp.Expr) -> tuple[sp.Expr, sp.Expr, str | None]:
        before = list(u)
        taken = step(k, closing)
        _check_step(problem, k, before, u, taken[0], closing, bool(floating),
                    next(taken_steps), max(integrated, default=None))
        return taken

    def settled() -> sp.Expr:
        # once a step was followed in floating point (the cone in space) the closing
        # speeds are known to its tolerance: the rule ends below 1e-12 of the largest
        # before, not 1e-40
        return sp.Float(1e-12) if integrated else SETTLED

    # the certificate's scale: the largest speed or spin before; a contact's closing
    # speed in the rules' rows is its normal velocity times its row's scale
    speeds = max(abs(v) for v in problem.u_before)
    count, steps = sequential_passes([index[name] for name in order],
                                     lambda k: problem.closing(k, u), checked,
                                     lambda k: speeds * problem.row_scale[k],
                                     settled=settled)
    total, tangential = sp.zeros(len(index), 1), sp.zeros(len(index), 1)
    for k, impulse, along, _ in steps:
        total[k] += impulse
        tangential[k] += along
    courses = tuple(f"{problem.contacts[k].name}: {course}" for k, _, _, course in steps
                    if course is not None)
    notes = (f"from {floating[0]}'s step on, the velocities held square roots that "
             "would nest, or rationals too long to carry, at every further step: each "
             "step from there started from "
             f"them rounded to {FLOAT_DIGITS} digits (the results are good to about "
             "that many digits, not exact)",) if floating else ()
    return problem.outcome("sequential", tuple(order), sp.Matrix(u),
                         problem.named(total.applyfunc(tidy)),
                         tuple(t.name for t, p in zip(problem.contacts, total, strict=True)
                               if p > 0),
                         count, tangential=problem.named(tangential.applyfunc(tidy))
                         if problem.frictional else {}, courses=courses, notes=notes,
                         method=f"rounded to {FLOAT_DIGITS} digits between steps"
                         if floating else "",
                         **({"tangent_impulses": {
                             t.name: (tidy(tangential[i]), tidy(across[i]))
                             for i, t in enumerate(problem.contacts)}}
                            if problem.tangents == 2 else {}))


def _check_step(problem: ImpulseRows, k: int, before: Sequence[sp.Expr],
                after: Sequence[sp.Expr], impulse: sp.Expr, closing: sp.Expr,
                rounded: bool, number: int, tolerance: float | None = None) -> None:
    """Each step of the sequential rule is an impact of its own, checked on its own from
    the velocities before and after it and its impulse: the contact does not pull,
    it does not close after, and (smooth) it leaves as its restitution law asks, with
    the momentum of every coordinate it moves changed by its impulse alone (M du =
    J_k^T P_k, from M itself, not the M^-1 the step moved them with). Exact, or to the
    rounding of FLOAT_DIGITS-digit steps, or to 1000 times the tolerance of a step
    followed in floating point; a failure is refused in one line."""
    size = max(1, *(abs(x) for x in before))
    slack = sp.Integer(0) if not rounded else sp.Float(10) ** (5 - FLOAT_DIGITS) * size
    if tolerance is not None:
        slack = max(slack, sp.Float(1000 * tolerance) * size)
    contact = problem.contacts[k]
    failures = []
    if impulse < -slack:
        failures.append(f"its impulse {sp.N(impulse, 6)} pulls")
    leaving = problem.closing(k, after)
    if leaving < -slack:
        failures.append(f"it still closes after ({sp.N(leaving, 6)})")
    if not contact.laws[1].grips:
        target = problem.leaving(k, closing)
        if abs(leaving - target) > slack:
            failures.append(f"it leaves at {sp.N(leaving, 6)}, not its law's "
                            f"{sp.N(target, 6)}")
        if not problem.dense:
            for j, value in problem.sparse_rows[k]:
                change = (after[j] - before[j]) / problem.inverse_inertia[j]
                if abs(tidy(change - value * impulse)) > slack:
                    failures.append(f"the momentum of coordinate {j} changes by "
                                    f"{sp.N(change, 6)}, not by the impulse's "
                                    f"{sp.N(value * impulse, 6)}")
    if failures:
        raise InputError("impact", f"the sequential rule's step {number} ({contact.name}) "
                         f"fails its own check ({'; '.join(failures[:3])}): it is not "
                         "given; please report the scene")


def sequential_pass(problem: ImpulseRows, order: Sequence[str]) -> Solution:
    """The sequential rule with symbols: one pass in `order`, every contact acting
    once, with the conditions that make it so (each contact closing at its turn) and
    that end the rule there (no contact closing after the pass).

    Examples
    --------
    >>> from rigidimpact.solve.collision import chain
    >>> e = sp.Symbol("e", nonnegative=True)
    >>> out = chain(3, e).sequential_pass(("c0", "c1"))
    >>> [out.results()[f"ball{k}.vx"] for k in range(3)]
    [-(e - 1)/2, (1 - e)*(e + 1)/4, (e + 1)**2/4]

    With e < 1 the first pair still closes after the pass, so one pass ends the rule
    only at e = 1:

    >>> out.conditions
    (e**2 - 2*e <= -1,)
    """
    problem.smooth_only("with symbols")
    index = problem.order_index(order)
    u = list(problem.u_before)
    total = sp.zeros(len(index), 1)
    conditions = []
    for name in order:
        k = index[name]
        closing = problem.closing(k, u)
        conditions.append(sp.Lt(closing, 0))
        total[k] = _smooth_step(problem, k, u, closing)
    conditions += [sp.Ge(x, 0) for x in problem.closings(u)]
    return problem.outcome("sequential", tuple(order), sp.Matrix(u),
                   problem.named(total.applyfunc(tidy)), tuple(order),
                   conditions=case_conditions(conditions))


def sequential_cases(problem: ImpulseRows, order: Sequence[str]) -> tuple[Solution, ...]:
    """The sequential rule with symbols, friction allowed: one pass in `order`, each
    contact's step its own impact under its own laws, as in :func:`sequential_pass`.
    A Coulomb or rough step can take several courses (Routh's and Walton's regimes,
    each with its conditions), so the pass is a tree of cases: one outcome per path
    through it, with every condition along the path (and the pass's own: each
    contact closing at its turn, or not closing and taking no step, none closing
    after). A path whose conditions cannot hold is dropped.

    Examples
    --------
    A particle of mass 1 sliding onto a floor at (1, -1) with Coulomb's mu and
    Poisson's e = 1/2: the normal impulse is 1 in compression and 3/2 in all, so it
    slides throughout while mu 3/2 <= 1, stops sliding in compression once mu >= 1,
    and in restitution between.

    >>> from rigidimpact.laws.contact import Contact
    >>> from rigidimpact.model.bodies import Body
    >>> from rigidimpact.solve.collision import Collision
    >>> mu = sp.Symbol("mu", positive=True)
    >>> floor = Contact((0, -1), sp.Rational(1, 2), "coulomb", "poisson", "f",
    ...                 bodies=("p", "floor"), friction=mu)
    >>> ball = Body.rigid(1, 0, (0, 0), (1, -1), name="p")
    >>> cases = Collision((ball, Body.fixed("floor")), (floor,)).sequential_cases(("f",))
    >>> for c in cases:
    ...     print(c.courses, c.results()["p.vx"], c.conditions)
    ('f: slip',) -(3*mu - 2)/2 (mu <= 2/3,)
    ('f: slip-stick, in compression',) 0 (mu > 1,)
    ('f: slip-stick, in restitution',) 0 (mu <= 1, mu > 2/3)
    """
    if not problem.frictional:
        return (sequential_pass(problem, order),)
    index = problem.order_index(order)
    n = len(index)
    # each path so far: (u, normal impulses, tangential impulses, conditions, courses,
    # the contacts that stepped)
    branches: list[tuple[sp.Matrix, sp.Matrix, sp.Matrix, list, list[str], list[str]]] = [
        (sp.Matrix(problem.u_before), sp.zeros(n, 1), sp.zeros(n, 1), [], [], [])]
    for name in order:
        k = index[name]
        restitution, tangential = problem.contacts[k].laws
        rows = sp.Matrix.vstack(problem.scaled_J[k, :], problem.scaled_J_t[k, :])
        W = (rows * problem.M_inverse * rows.T).applyfunc(tidied)
        grown = []
        for u, total, along, conditions, courses, acted in branches:
            v = (rows * u).applyfunc(tidy)
            # where the contact does not close at its turn it takes no step
            kept = case_conditions([*conditions, sp.Ge(v[0], 0)])
            if kept != (sp.false,):
                grown.append((u, total, along, [c for c in kept if c is not sp.true],
                              [*courses, f"{name}: does not close"], acted))
            here = [*conditions, sp.Lt(v[0], 0)]
            if tangential.solved_by_regimes:  # each course a branch, with its conditions
                _no_nested_roots(name, v, courses, problem.symbols)
                steps = [(r.impulse, r.conditions, r.name)
                         for r in tangential.regimes(W, v, restitution)]
            else:  # the law's one face: its impact alone
                out = tangential.impulse(W, v, restitution)
                steps = [((out.impulse[0], out.impulse[1]), (), out.course)]
            for (normal, t), more, course in steps:
                kept = case_conditions([*here, *more])
                if kept == (sp.false,):
                    continue
                push = sp.Matrix([tidy(normal), tidy(t)])
                after = (u + problem.M_inverse * rows.T * push).applyfunc(tidy)
                grown.append((after, total + _at(n, k, push[0]), along + _at(n, k, push[1]),
                              [c for c in kept if c is not sp.true],
                              [*courses, f"{name}: {course}"], [*acted, name]))
        branches = grown
    cases = []
    for u, total, along, conditions, courses, acted in branches:
        kept = case_conditions([*conditions, *(sp.Ge(x, 0) for x in problem.closings(u))])
        if kept == (sp.false,):
            continue
        cases.append(problem.outcome("sequential", tuple(order), u,
                                   problem.named(total.applyfunc(tidy)), tuple(acted),
                                   tangential=problem.named(along.applyfunc(tidy)),
                                   courses=tuple(courses), conditions=kept))
    if not cases:
        symbols = ", ".join(sorted(map(str, problem.symbols)))
        raise InputError("contacts", f"one pass in the order {', '.join(order)} does not "
                         "end the sequential rule for any value of the symbols (a "
                         "contact closes again after it, or no contact closes): the "
                         "passes that follow need numbers; give [values] (or --set) for "
                         f"{symbols}")
    return tuple(cases)


def _no_nested_roots(name: str, v: sp.Matrix, courses: Sequence[str],
                     symbols: Iterable[sp.Symbol]) -> None:
    """Refuse a course by regimes taken over speeds that hold roots of the symbols (an
    energetic course before it): its own roots would nest in them, and the work grows
    past any bound (one such step of three contacts ran for minutes). A budget by the
    kind of work, counted the same on every machine."""
    roots = [p for x in v for p in sp.sympify(x).atoms(sp.Pow)
             if not p.exp.is_Integer and p.base.free_symbols]
    if roots:
        given = ", ".join(sorted(map(str, symbols)))
        raise InputError("contacts", f"the sequential rule with symbols: after the "
                         f"courses ({'; '.join(courses)}) the speeds hold roots of {given}, "
                         f"and {name}'s courses would nest roots in them, past what a "
                         f"closed form can carry: give [values] (or --set) for {given}")


def every_order(problem: ImpulseRows) -> tuple[Solution, ...]:
    """The sequential rule in every order of the contacts."""
    names = [t.name for t in problem.contacts]
    count = math.factorial(len(names))  # counted before any order is made
    if count > MAX_ORDERS:
        raise InputError("impact.order", f"{len(names)} contacts have {count} orders "
                         f"(at most {MAX_ORDERS} are run): give one, or ask for a "
                         "seeded sample (orders = N, seed = S)")
    orders = list(itertools.permutations(names))
    if problem.symbols:
        return tuple(sequential_pass(problem, order) for order in orders)
    return tuple(sequential(problem, order) for order in orders)


def sampled_orders(problem: ImpulseRows, count: int, seed: int) -> tuple[Solution, ...]:
    """The sequential rule in `count` orders drawn at random (``random.Random(seed)``,
    each a uniform shuffle; repeats possible when the orders are few): a sample of
    the outcomes' spread, not every order."""
    problem.numbers_only("sequential")
    if not 1 <= count <= MAX_SAMPLED_ORDERS:
        raise InputError("impact.orders", f"must lie in [1, {MAX_SAMPLED_ORDERS}], got "
                         f"{count}")
    draw, names = random.Random(seed), [t.name for t in problem.contacts]
    orders = []
    for _ in range(count):
        order = names[:]
        draw.shuffle(order)
        orders.append(tuple(order))
    # a budget of work, not only a count: the first order's passes say what all cost
    found = [sequential(problem, orders[0])]
    estimate = max(found[0].passes, 1) * len(names) * count
    if estimate > MAX_SAMPLE_IMPACTS:
        raise InputError("impact.orders", f"{count} orders would make up to {estimate} "
                         f"impacts (the first took {found[0].passes} passes over "
                         f"{len(names)} contacts), past the budget of "
                         f"{MAX_SAMPLE_IMPACTS}: ask for fewer")
    return tuple(found + [sequential(problem, order) for order in orders[1:]])


def sequential_passes(order: Sequence[int], closing: Callable[[int], sp.Expr],
                      step: Callable[[int, sp.Expr], tuple[sp.Expr, sp.Expr, str | None]],
                      scale: sp.Expr | Callable[[int], sp.Expr],
                      settled: sp.Expr | Callable[[], sp.Expr] = SETTLED
                      ) -> tuple[int, list[tuple[int, sp.Expr, sp.Expr, str | None]]]:
    """The sequential rule's passes, for any model: contact by contact in `order`, each
    contact still closing (``closing(k) < 0``, beyond `settled` times `scale`; `settled`
    may be a function, asked at each contact, and `scale` one of the contact) takes its
    own impact (``step(k, closing)``: its normal and tangential impulse and its course,
    the model's velocities moved by the step), repeated until a pass in which none acts.
    Returns the passes in which some contact acted and every step taken.

    Examples
    --------
    Two unit masses at rest and a third arriving at 1, e = 1, head on:

    >>> u = [1, 0, 0]
    >>> def hit(k, closing):  # equal masses: they swap velocities
    ...     u[k], u[k + 1] = u[k + 1], u[k]
    ...     return -closing, 0, None
    >>> sequential_passes([0, 1], lambda k: u[k + 1] - u[k], hit, 1)
    (1, [(0, 1, 0, None), (1, 1, 0, None)])
    """
    steps: list[tuple[int, sp.Expr, sp.Expr, str | None]] = []
    count, acted = 0, True
    most = MAX_SEQUENTIAL_IMPACTS * (1 + len(order) // 100)

    def endless() -> InputError:
        return InputError("impact.rule", f"the sequential rule did not settle in {count} "
                          f"passes ({len(steps)} impacts; its budget is {MAX_PASSES} "
                          f"passes and {most} impacts): the contacts keep closing again "
                          "after each other's impacts (with e = 1 they can ring for "
                          "ever); try the simultaneous rule")

    while acted:  # a pass in which no contact acted ends the rule
        if count == MAX_PASSES:
            raise endless()
        count, acted = count + 1, False
        for k in order:
            now = closing(k)
            line = (settled() if callable(settled) else settled) * \
                (scale(k) if callable(scale) else scale)
            if now >= 0 or -now <= line:
                continue
            if len(steps) == most:
                raise endless()
            steps.append((k, *step(k, now)))
            acted = True
    return count - 1, steps


def _long(x: sp.Expr) -> bool:
    """A rational of more than LONG_DIGITS digits above or below its line."""
    return bool(x.is_Rational and max(abs(x.p), x.q) > LONG)


LONG = 10**LONG_DIGITS


def carried(x: sp.Expr) -> sp.Expr:
    """A number as the sequential rule carries it to the next step: as it is, or a
    rational longer than LONG_DIGITS digits as a FLOAT_DIGITS-digit Float.

    Examples
    --------
    >>> carried(sp.Rational(1, 3)), carried(sp.Rational(1, 3**500)).is_Float
    (1/3, True)
    """
    return _rounded(x) if _long(x) else x


def _rounded(x: sp.Expr) -> sp.Expr:
    """A number as a Float of FLOAT_DIGITS significant digits (a Float stays as it is):
    SymPy's polynomial arithmetic keeps a Float's precision, and unlike a rational of
    that many digits it puts no large integer under the next square root."""
    x = sp.sympify(x)
    if x.is_Float:
        return x
    return sp.N(x, FLOAT_DIGITS)


def _at(n: int, k: int, value: sp.Expr) -> sp.Matrix:
    """An n-vector holding `value` at k."""
    vector = sp.zeros(n, 1)
    vector[k] = value
    return vector
