"""The simultaneous rule: every contact acts at once, none pulls.

With numbers, a linear complementarity problem: Lemke's exact method for rational
data, block pivoting with an exact confirmation at scale, the acting sets tried
where numbers are irrational; with Coulomb friction at the velocity level every
combination of contact states for a few contacts, past them one complementarity
problem (:func:`_frictional_lcp`); with symbols, one outcome per case that can hold,
each with its conditions. One implementation for every source of the problem.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any, ClassVar

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.solve.conditions import (
    case_conditions,
    exact_solve,
    tidied,
)
from rigidimpact.solve.coulomb import coulomb_newton
from rigidimpact.solve.lcp import (
    NoSolution,
    confirm,
    confirm_by_rows,
    confirm_support,
    least_norm,
    lemke,
    lemke_float,
    pivoting,
    proximal,
    residual,
    rounded_solve,
)
from rigidimpact.solve.problem import MAX_ENUMERATED, ImpulseRows
from rigidimpact.solve.rules.base import Rule
from rigidimpact.solve.rules.floating import (
    STATE,
    float_problem,
    frictional_newton,
    frictional_pyramid,
    one_acting,
)
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.rewrite import tidy

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

# the simultaneous rule with symbols: a case (signs before x acting contacts) that can
# hold took 0.3 to 2.5 s here (64 cases of three contacts with symbolic speeds 40 s, 256
# past 5 minutes), one that cannot next to nothing (128 cases of a cradle in 1.6 s); so
# the cases are counted first, and the work done is counted as it goes
MAX_SYMBOLIC_CASES = 4096


# the enumerations' budget of work, counted, never timed, so that the same problem is
# answered or refused alike on every machine at any load: each linear system solved
# costs its size cubed, ten times that and as much again for each symbol where symbols
# are left (their expressions grow with them). Three contacts between four discs with
# symbolic speeds, m and e need 26,460 units (56 s here) and are refused; seven
# contacts at irrational numbers need at most 7,840, eight 22,528
MAX_ENUMERATION_WORK = 20_000


class _Work:
    """Work counted against MAX_ENUMERATION_WORK; past it, one line (`refusal`)."""

    def __init__(self, problem: ImpulseRows, refusal: str) -> None:
        symbols = len(problem.symbols)
        self.done, self.refusal = 0, refusal
        self.weight = 10 * (1 + symbols) if symbols else 1

    def spend(self, size: int) -> None:
        self.done += self.weight * max(size, 1) ** 3
        if self.done > MAX_ENUMERATION_WORK:
            raise InputError("contacts", self.refusal)


# the simultaneous rule: Lemke's exact dense tableau up to this many contacts; past it
# (or past MAX_ENUMERATED with irrational numbers) floating point with an exact check
MAX_LEMKE = 64
# with roots in W (sqrt(3)), more contacts than this are solved as at scale: the acting
# set found in floating point and confirmed exactly in the numbers' field (a fan of 12
# contacts took more than ten minutes of symbolic determinants when enumerated)
MAX_ALGEBRAIC_ENUMERATED = 4


# the simultaneous rule with friction: every combination of contact states is tried
# (each answer found, so non-unique ones are said) up to this many combinations; past it
# one linear complementarity problem (Stewart and Trinkle; Anitescu and Potra) by
# Lemke's method, exact, which finds one answer
MAX_FRICTION_STATES = 729
# the combinations of states are tried within this budget of work, whatever
# MAX_FRICTION_STATES says: each costs (2 n)^3 for n contacts (its 2n unknowns), so every
# combination of up to four contacts fits (256 x 512) and the bench's lifted count ends
# alike on every machine
MAX_STATES_WORK = 200_000
# where every combination would pass that budget, the one linear solve of every closing
# contact sticking is tried, then one complementarity problem (the bench turns this off
# to time the enumeration until its budget refuses)
STATES_DIRECT = True
# the frictional problem (four unknowns a contact): Lemke's method in floating point with
# an exact confirmation up to MAX_FRICTION_LEMKE contacts (a dense tableau), and where
# the confirmation fails, Lemke's exact tableau up to MAX_FRICTION_EXACT_LEMKE
MAX_FRICTION_LEMKE = 400
MAX_FRICTION_EXACT_LEMKE = 40



@dataclass(frozen=True)
class Simultaneous(Rule):
    """All contacts at once, none pulling (a complementarity problem); with symbols, one
    outcome per case, each with its conditions.

    Examples
    --------
    >>> from rigidimpact.solve.collision import chain
    >>> from rigidimpact.solve.collision import chain
    >>> [o.label for o in chain(3).solve(Simultaneous())]
    ['simultaneous']
    """

    name: ClassVar[str] = "simultaneous"
    whole_impact: ClassVar[bool] = True
    said: ClassVar[str] = (
        "every contact smooth; the impulses P >= 0 act together, with the restitution law "
        "at each contact that acts and no contact pulling (v+ = v- + W P, a "
        "complementarity problem)")
    said_with_friction: ClassVar[str] = (
        "Coulomb friction at the velocity level: the impulses act together; each contact "
        "is released, sticks (Newton's e across, no slip after, |P_t| <= mu P_n) or "
        "slides (|P_t| = mu P_n against its slip after); every combination solved exactly")

    def outcomes(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        if problem.symbols:
            return simultaneous_cases(problem)
        return (simultaneous(problem),)


def simultaneous(problem: ImpulseRows) -> Solution:
    """All contacts at once, no contact pulling (a complementarity problem).

    Newton's law: every acting contact leaves at ``-e`` times its closing velocity
    before, every released one at least that fast. Poisson's law: the compression
    impulses solve the same problem with target zero, and each is scaled by 1 + e.
    How the problem is solved depends on its size and numbers (see :func:`_lcp`):
    Lemke's method in exact arithmetic, trying the acting sets from the largest down,
    or past those sizes floating point with an exact check (``rigidimpact bench``
    times both); the outcome's `method` and notes say which when it is not the first.
    """
    problem.numbers_only("simultaneous")
    if problem.frictional:
        return _frictional_simultaneous(problem)
    v = problem.scaled_velocity_before
    poisson = problem.acts_by_impulse()
    target = sp.zeros(len(v), 1) if poisson else \
        sp.Matrix([problem.leaving(i, min(v[i], 0)) for i in range(len(v))])
    impulses, how, method = _lcp(problem, v, target)
    if poisson:  # each law makes its whole impulse from its compression impulse
        impulses = sp.Matrix([problem.contacts[i].laws[0].from_compression(impulses[i])
                              for i in range(len(v))])
    u = problem.kick(problem.u_before, impulses)
    return problem.outcome("simultaneous", (), u, problem.named(impulses),
                   tuple(t.name for t, p in zip(problem.contacts, impulses, strict=True)
                         if p > 0), notes=how + (_still_closing(problem, u) if poisson else ()),
                         method=method)


def _still_closing(problem: ImpulseRows, u: sp.Matrix) -> tuple[str, ...]:
    """A warning for every contact that still approaches after the impact (the bodies
    would pass into each other): Poisson's law scales each compression impulse by
    its own 1 + e, which need not leave every contact opening."""
    after = problem.closings(u)
    scale = max(abs(x) for x in problem.scaled_velocity_before)
    closing = [(t.name, after[i] / problem.row_scale[i]) for i, t in enumerate(problem.contacts)
               if after[i] < -sp.Rational(1, 10**12) * scale]
    return tuple(f"{name} still approaches after the impact (normal velocity "
                 f"{float(speed):.6g}): the bodies would pass into each other; the "
                 f"simultaneous rule with Poisson's law cannot honour the physics here "
                 f"(the sequential rule can)" for name, speed in closing)


def _frictional_simultaneous(problem: ImpulseRows) -> Solution:
    """All contacts at once with Coulomb friction, at the velocity level.

    Each contact is released (no impulse, separating at least as fast as Newton's
    law asks), sticking (it leaves with Newton's normal velocity and no slip, its
    tangential impulse inside the cone |P_t| <= mu P_n) or sliding (on the cone's
    edge, opposite to the slip it leaves with). This is the model of time-stepping
    codes (Stewart and Trinkle, Anitescu and Potra), not Routh's integration over
    the impact: friction acts on the velocities after, so it agrees with Routh's
    method when the slip does not change during the impact. Up to MAX_FRICTION_STATES
    combinations every combination of states is solved exactly; with friction the
    problem can have several solutions, or none (Painleve's paradox), and the outcome
    says so. Past that, one complementarity problem finds one answer
    (:func:`_frictional_lcp`).
    """
    if len(problem.contacts) == 1:  # one contact: its own exact answer, under any law
        return one_acting(problem, 0, [sp.Integer(0)])
    restitution, tangential = zip(*(t.laws for t in problem.contacts), strict=True)
    n = len(problem.contacts)
    v_n = problem.scaled_velocity_before
    late = [t.name for t, r in zip(problem.contacts, restitution, strict=True)
            if r.together != "velocity"]
    formless = [(t.name, law.name) for t, law in zip(problem.contacts, tangential,
                                                      strict=True)
                if not law.velocity_states]
    closing = [i for i in range(n) if v_n[i] < 0]
    if (late or formless) and len(closing) == 1:
        # one contact closes: its own exact impact, under its own laws, if that leaves
        # every other contact opening (the answer every rule gives for one acting
        # contact); otherwise one line saying so
        return one_acting(problem, closing[0], [sp.Integer(0)] * n)
    if late:
        raise InputError(f"{late[0]}.law", "with friction the simultaneous rule takes "
                         "Newton's law at every contact (the sequential rule takes "
                         "each law)")
    if formless:
        raise InputError(f"{formless[0][0]}.tangential", f"the {formless[0][1]} law "
                         "has no form for contacts acting together: use the "
                         "sequential rule (each contact's own impact)")
    mu = [law.cone() for law in tangential]
    target = [problem.leaving(i, min(v_n[i], 0)) for i in range(n)]
    if problem.tangents == 2:  # in space: Coulomb's circular cone, in floating point
        across = sp.SparseMatrix([list(problem.contact_rows(i)[j, :]) for i in range(n)
                                  for j in (1, 2)])
        solve = frictional_newton if problem.facets is None else frictional_pyramid
        return solve(problem, sp.SparseMatrix.vstack(sp.SparseMatrix(problem.scaled_J),
                                                     across),
                     v_n, _sparse_times(across, problem.u_before), mu, target, tangential)
    v_t = _sparse_times(problem.scaled_J_t, problem.u_before)
    if problem.facets is not None:  # one tangent's pyramid, + and -: Coulomb's law
        return frictional_pyramid(problem, sp.SparseMatrix.vstack(
            sp.SparseMatrix(problem.scaled_J), sp.SparseMatrix(problem.scaled_J_t)),
            v_n, v_t, mu, target, tangential)
    states = [("off",) + law.velocity_states for law in tangential]
    count = math.prod(len(s) for s in states)
    rows = sp.Matrix.vstack(problem.scaled_J, problem.scaled_J_t)
    if count > MAX_FRICTION_STATES:  # past a few contacts: one complementarity problem
        return _frictional_lcp(problem, v_n, v_t, mu, target, tangential)
    W = (rows * problem.M_inverse * rows.T).applyfunc(tidied)
    if STATES_DIRECT and (count - 1) * (2 * n) ** 3 > MAX_STATES_WORK:
        # more combinations than the enumeration may try: first the one linear solve of
        # every closing contact sticking, then one complementarity problem
        gripping = tuple(s[1] if v_n[i] <= 0 else "off" for i, s in enumerate(states))
        fits = _friction_pattern(problem, gripping, W, v_n, v_t, target, mu)
        if fits is None:
            return _frictional_lcp(problem, v_n, v_t, mu, target, tangential)
        return _friction_outcome(problem, rows, [(fits[0], gripping)], not fits[1],
                                 tried_all=False)
    found: list[tuple[sp.Matrix, tuple[str, ...]]] = []
    not_unique = False
    for tried, pattern in enumerate(itertools.product(*states)):
        if all(state == "off" for state in pattern):
            continue
        if tried * (2 * n) ** 3 > MAX_STATES_WORK:  # counted, never timed (the bench
            # lifts MAX_FRICTION_STATES and lets this end the enumeration)
            raise InputError("contacts", f"{n} frictional contacts have {count} "
                             "combinations of states (released, sticking, sliding either "
                             f"way), more than the budget of work ({MAX_STATES_WORK} "
                             "units) lets the rule try: try the sequential rule with an "
                             "order")
        fits = _friction_pattern(problem, pattern, W, v_n, v_t, target, mu)
        if fits is None:
            continue
        solved, unique = fits
        not_unique = not_unique or not unique
        if all(solved != f for f, _ in found):
            found.append((solved, pattern))
    if not found:
        raise InputError("impact.rule", "no impulses satisfy the simultaneous rule with "
                         "friction here (a Painleve-type inconsistency); try the "
                         "sequential rule")
    acting = {tuple(i for i in range(n) if f[i] > 0) for f, _ in found}
    if len(acting) == 1 and len(next(iter(acting))) == 1:
        (k,), = acting
        if tangential[k].solved_by_regimes:  # one contact acts: its own exact answer
            return one_acting(problem, k, target)
    return _friction_outcome(problem, rows, found, not_unique)


def _friction_outcome(problem: ImpulseRows, rows: sp.Matrix,
                      found: Sequence[tuple[sp.Matrix, tuple[str, ...]]],
                      not_unique: bool, tried_all: bool = True) -> Solution:
    """The outcome of the combinations of states that fit the rule (`found`, each with
    its impulses, normal then tangential), saying where the impulses or the motion are
    not unique, and where the combinations were not all tried."""
    n = len(problem.contacts)
    impulses, pattern = found[0]
    motions = [(problem.u_before + problem.M_inverse * rows.T * f).applyfunc(tidy)
               for f, _ in found]
    u = motions[0]
    notes: tuple[str, ...] = ()
    if not_unique:
        notes = ("more contact conditions than freedoms: the motion after is unique but "
                 "the impulses are not; shown: the least-norm impulses of each state, or "
                 "where those would pull, a sharing that pushes",)
    if len(found) > 1 and all(m == u for m in motions):
        # with the velocities after fixed, the conditions on the impulses are convex:
        # every mixture of the solutions found is one too; the mean is shown
        impulses = (sum((f for f, _ in found), sp.zeros(2 * n, 1)) / len(found)
                    ).applyfunc(tidy)
        pattern = tuple(pattern[i] if all(p[i] == pattern[i] for _, p in found)
                        else "mixed" for i in range(n))
        notes += (f"the motion after is unique but the impulses are not: {len(found)} "
                 "ways to share them between the contacts fit the rule, and every "
                 "mixture of them; shown: their mean",)
    elif len(found) > 1:
        notes += (f"the simultaneous rule with friction has {len(found)} solutions here, "
                 "with different motions after; shown: " + ", ".join(
                     STATE[s] for s in pattern) + "; others: " + "; ".join(
                     ", ".join(STATE[s] for s in p) for _, p in found[1:]),)
    if not tried_all:
        notes += ("every closing contact sticking fits the rule; the other combinations "
                  "of states (released, sticking, sliding) were not tried, being more "
                  "than the budget of work allows: the rule may have other solutions",)
    normal = impulses[:n, 0]
    return problem.outcome("simultaneous", (), u,
                   problem.named(normal), tuple(t.name for t, p in
                                              zip(problem.contacts, normal, strict=True)
                                              if p > 0),
                   tangential=problem.named(impulses[n:, 0]),
                   courses=tuple(f"{t.name}: {STATE[s]}" for t, s in
                                 zip(problem.contacts, pattern, strict=True)),
                   notes=notes)


def _sparse_times(rows: sp.Matrix, u: sp.Matrix) -> sp.Matrix:
    """``rows * u`` over the nonzero entries of `rows` only (a contact's row touches two
    bodies), tidied."""
    out: list[Any] = [sp.Integer(0)] * rows.rows
    for i, j, x in rows.row_list():
        out[i] += x * u[j]
    return sp.Matrix([tidy(x) for x in out])


def _fraction(x: Any) -> Fraction:
    """A rational of QQ (or a Fraction, or 0) as a Fraction."""
    return Fraction(int(x.numerator), int(x.denominator)) if x else Fraction(0)


def _rational(x: Any) -> sp.Rational:
    """A rational of QQ (or a Fraction) as SymPy's."""
    return sp.Rational(int(x.numerator), int(x.denominator))


def _frictional_lcp(problem: ImpulseRows, v_n: sp.Matrix, v_t: sp.Matrix,
                    mu: Sequence[Any], target: Sequence[sp.Expr],
                    tangential: Sequence[Any]) -> Solution:
    """Coulomb friction at many contacts acting together as one linear complementarity
    problem (Stewart and Trinkle 1996; Anitescu and Potra 1997). In the plane the cone
    has two edges, so the problem is exact, not a faceted approximation. Each contact has
    four unknowns: its normal impulse p, its friction split into the two edges' parts
    a, b >= 0 (P_t = a - b), and a slack s, the size of its slip after:

        w_p = v_n+ - target >= 0  with p      (Newton's law, or released and opening)
        w_a = s + v_t+ >= 0       with a      (friction against a slip one way)
        w_b = s - v_t+ >= 0       with b      (or the other)
        w_s = mu p - a - b >= 0   with s      (the cone: sliding on its edge)

    A sticking contact (``tangential = "stick"``) has no cone and no slack: ``w_a = v_t+``
    and ``w_b = -v_t+``, so its slip after is zero; a smooth one has mu = 0. Lemke's
    method in floating point finds which unknowns are positive, and the rationals confirm
    it (then the answer is exact); where they do not, Lemke's exact tableau solves it, up
    to a size. It finds one answer: with friction there may be others (the outcome says
    so), which the enumeration of states finds for few contacts.
    """
    n = len(problem.contacts)
    rows = sp.Matrix.vstack(problem.scaled_J, problem.scaled_J_t)
    data = [*v_n, *v_t, *target, *(m for m in mu if m is not None)]
    if n > MAX_FRICTION_LEMKE or rows.free_symbols or problem.M_inverse.free_symbols or not all(
            sp.sympify(x).is_Rational for x in data):
        return frictional_newton(problem, rows, v_n, v_t, mu, target, tangential)
    try:
        # sparse, all of them: a product of a sparse and a dense DomainMatrix makes both
        # dense (J of a chain of 400 is 800 by 1,203 with four entries a row)
        J = rows.to_DM().convert_to(QQ).to_sparse()
        Minv = problem.M_inverse.to_DM().convert_to(QQ).to_sparse()
    except Exception:  # noqa: BLE001 - an irrational entry: not in the rationals
        return frictional_newton(problem, rows, v_n, v_t, mu, target, tangential)
    W = (J * Minv * J.transpose()).to_sdm()  # sparse: {row: {column: value}}

    M, q, sticks, cone = _friction_tableau(W, v_n, v_t, mu, target, tangential)
    size = 4 * n
    def confirmed(guess: np.ndarray) -> list[Any] | None:
        """The exact solution on the support of a floating-point `guess`, if it is one."""
        cut = 1e-9 * max(1.0, float(np.abs(guess).max()))
        support = {int(i) for i in np.nonzero(guess > cut)[0]}
        for i in range(n):  # a friction with both edges' parts: only their difference
            if n + i in support and 2 * n + i in support:  # counts (the two columns are
                support.discard(n + i if guess[n + i] < guess[2 * n + i] else 2 * n + i)
        # a released contact's slack is any value at least its slip after: raised to it
        released = [3 * n + i for i in range(n) if i not in support and not sticks[i]]
        support -= set(released)
        return confirm_support(M, q, sorted(int(i) for i in support), released, times)

    Jt = J.transpose()

    def times(z: list[Any]) -> list[Any]:
        """M z through J's sparse rows (W = J M^-1 J^T is dense when one body touches
        every contact; J is not): the rows of M as built above."""
        x = DomainMatrix({k: {0: v} for k, v in enumerate(
            [*z[:n], *(z[n + i] - z[2 * n + i] for i in range(n))]) if v}, (2 * n, 1), QQ)
        y = (J * (Minv * (Jt * x))).to_sdm()
        Wx = [y[k][0] if k in y else QQ(0) for k in range(2 * n)]
        out = [*Wx[:n], *Wx[n:], *(-v for v in Wx[n:]), *([QQ(0)] * n)]
        for i in range(n):
            if sticks[i]:
                out[3 * n + i] = z[3 * n + i]
            else:
                out[n + i] += z[3 * n + i]
                out[2 * n + i] += z[3 * n + i]
                out[3 * n + i] = cone[i] * z[i] - z[n + i] - z[2 * n + i]
        return out

    z, how = None, ("found in floating point by a semismooth Newton method and confirmed "
                    "in exact arithmetic")
    try:  # the sparse Newton method's answer, in the problem's four unknowns a contact
        J_f, Minv_f, W_f, b_f, cone_f, u0_f = float_problem(problem, rows, v_n, v_t, mu,
                                                             target, tangential)
        lam = coulomb_newton(W_f, b_f, cone_f)[0]
        slip_f = (J_f @ (u0_f + Minv_f @ (J_f.T @ lam)))[n:]
        z = confirmed(np.concatenate([lam[:n], np.maximum(lam[n:], 0.0),
                                      np.maximum(-lam[n:], 0.0),
                                      np.where(sticks, 0.0, np.abs(slip_f))]))
    except NoSolution:
        z = None
    if z is None:  # Lemke's method in floating point on the dense tableau
        dense = np.zeros((size, size))
        for i, row in enumerate(M):
            for j, x in row.items():
                dense[i, j] = float(x)
        guess = lemke_float(dense, np.array([float(x) for x in q]))
        z = None if guess is None else confirmed(guess)
        how = "found in floating point by Lemke's method and confirmed in exact arithmetic"
    if z is None:
        if n > MAX_FRICTION_EXACT_LEMKE:  # too large for the exact tableau
            return frictional_newton(problem, rows, v_n, v_t, mu, target, tangential)
        try:
            z = lemke([[_fraction(row.get(j, 0)) for j in range(size)] for row in M],
                      [_fraction(x) for x in q])
        except NoSolution as exc:
            raise InputError("impact.rule", "no impulses satisfy the simultaneous rule "
                             f"with friction here ({exc}: a Painleve-type inconsistency); "
                             "try the sequential rule") from None
        how = "solved by Lemke's exact tableau"
    P = [z[i] for i in range(n)] + [z[n + i] - z[2 * n + i] for i in range(n)]
    impulses = DomainMatrix({k: {0: QQ(int(x.numerator), int(x.denominator))}
                             for k, x in enumerate(P) if x}, (2 * n, 1), QQ)
    u0 = problem.u_before.to_DM().convert_to(QQ).to_sparse()
    u_dm = u0 + Minv * (J.transpose() * impulses)
    slip_dm = J * u_dm
    u = sp.Matrix([QQ.to_sympy(u_dm[k, 0].element) for k in range(u_dm.shape[0])])
    normal = sp.Matrix([_rational(P[i]) for i in range(n)])
    along = sp.Matrix([_rational(P[n + i]) for i in range(n)])
    acting = [i for i in range(n) if P[i] > 0]
    if len(acting) == 1 and tangential[acting[0]].solved_by_regimes:
        return one_acting(problem, acting[0], list(target))
    slip = [slip_dm[n + i, 0].element for i in range(n)]
    states = ["off" if P[i] == 0 else "on" if not tangential[i].grips else
              "stick" if slip[i] == 0 else "slide+" if slip[i] > 0 else "slide-"
              for i in range(n)]
    note = (f"{n} frictional contacts: solved as one linear complementarity problem "
            f"({size} unknowns), {how}; it gives one answer, and with friction others "
            "may exist")
    return problem.outcome("simultaneous", (), u, problem.named(normal),
                            tuple(problem.contacts[i].name for i in acting),
                            tangential=problem.named(along),
                            courses=tuple(f"{t.name}: {STATE[s]}" for t, s in
                                          zip(problem.contacts, states, strict=True)),
                            notes=(note,), method="lemke")


def _friction_tableau(W: Any, v_n: sp.Matrix, v_t: sp.Matrix, mu: Sequence[Any],
                      target: Sequence[sp.Expr], tangential: Sequence[Any]
                      ) -> tuple[list[dict[int, Any]], list[Any], list[bool], list[Any]]:
    """The frictional complementarity problem's sparse rows M and q over the rationals
    (see :func:`_frictional_lcp`), which contacts stick and each contact's cone."""
    n = len(v_n)
    # every entry an element of QQ (python-flint's fmpq where installed, as W's own
    # entries are): the confirmation below adds and compares them without converting
    def g(x: Any) -> Any:
        x = sp.Rational(x)
        return QQ(int(x.p), int(x.q))

    sticks = [m is None and law.grips for m, law in zip(mu, tangential, strict=True)]
    cone = [QQ(0) if (m is None or not law.grips) else g(m)
            for m, law in zip(mu, tangential, strict=True)]
    size = 4 * n
    M: list[dict[int, Any]] = [{} for _ in range(size)]  # sparse rows
    q = [QQ(0)] * size
    for i in range(n):
        q[i] = g(v_n[i]) - g(target[i])
        q[n + i], q[2 * n + i] = g(v_t[i]), -g(v_t[i])
    for i, row in W.items():
        for j, value in row.items():
            x = value
            if i < n and j < n:
                M[i][j] = x
            elif i < n:  # W_nt: the tangential impulses' effect on the normal velocity
                M[i][j] = x
                M[i][n + j] = -x
            elif j < n:  # W_tn
                M[i][j] = x
                M[n + i][j] = -x
            else:  # W_tt
                M[i][j], M[i][n + j] = x, -x
                M[n + i][j], M[n + i][n + j] = -x, x
    for i in range(n):
        if sticks[i]:
            M[3 * n + i][3 * n + i] = QQ(1)  # no slack: the slip after is zero
        else:
            M[n + i][3 * n + i] = M[2 * n + i][3 * n + i] = QQ(1)
            if cone[i]:
                M[3 * n + i][i] = cone[i]
            M[3 * n + i][n + i] = M[3 * n + i][2 * n + i] = QQ(-1)
    return M, q, sticks, cone


def _friction_pattern(problem: ImpulseRows, pattern, W, v_n, v_t, target,
                      mu) -> tuple[sp.Matrix, bool] | None:
    """The impulses (normal then tangential) for one choice of contact states, if
    that choice is consistent, and whether they are the only ones."""
    n = len(pattern)
    P = sp.symbols(f"p0:{2 * n}")
    after = sp.Matrix(list(v_n) + list(v_t)) + W * sp.Matrix(P)
    equations = []
    for i, state in enumerate(pattern):
        if state == "off":
            equations += [P[i], P[n + i]]
            continue
        equations.append(after[i] - target[i])
        if state in ("on",):
            equations.append(P[n + i])
        elif state == "stick":
            equations.append(after[n + i])
        else:
            equations.append(P[n + i] + (1 if state == "slide+" else -1) * mu[i] * P[i])
    matrix, rhs = sp.linear_eq_to_matrix(equations, P)
    rounded = matrix.has(sp.Float) or rhs.has(sp.Float)
    if rounded:  # rounded numbers: the rank from their digits
        impulses, unique = rounded_solve(matrix, rhs)
        if impulses is None:
            return None
    else:
        impulses, unique = exact_solve(matrix, rhs), True
    if impulses is None:  # the states do not fix the impulses: if they are consistent
        impulses, unique = least_norm(matrix, rhs), False  # the motion is fixed (W's
        if impulses is None:  # null vectors are J^T's); the least-norm ones are shown
            return None
    # rounded numbers are compared within their own rounding (a contact left exactly
    # touching comes out 1e-50 one way or the other)
    slack = _rounding(matrix, rhs, impulses) if rounded else 0
    if not _pattern_holds(pattern, impulses, W, v_n, v_t, target, mu, slack):
        if unique:
            return None
        # the impulses are not fixed: the least-norm ones break a sign, but another
        # sharing of the same motion may keep them all (a tip in a corner stopped by a
        # wall alone)
        impulses = _fitting_share(matrix, rhs, pattern, mu, rounded)
        if impulses is None or not _pattern_holds(pattern, impulses, W, v_n, v_t, target,
                                                  mu, slack):
            return None
    if rounded:  # an impulse of rounding's size is none
        impulses = impulses.applyfunc(lambda x: 0 if abs(x) <= slack else x)
    return impulses, unique


def _rounding(matrix: sp.Matrix, rhs: sp.Matrix, impulses: sp.Matrix) -> Any:
    """What rounded numbers' comparisons allow: 1e-(0.6 digits) of the largest entry."""
    digits = max([getattr(x, "_prec", 53) for x in (*matrix, *rhs) if x.is_Float]
                 + [53]) * 3 // 10
    scale = max([abs(x) for x in (*matrix, *rhs, *impulses)] + [sp.Integer(1)])
    return scale * sp.Float(10, digits) ** -(digits * 6 // 10)


def _pattern_holds(pattern: Sequence[str], impulses: sp.Matrix, W: sp.Matrix,
                   v_n: Sequence[Any], v_t: Sequence[Any], target: Sequence[Any],
                   mu: Sequence[Any], slack: Any) -> bool:
    """Whether `impulses` keep the signs of their states: no pulling, a released
    contact not approaching, a sticking one inside its cone, a sliding one slipping
    its way (within `slack`, for rounded numbers)."""
    n = len(pattern)
    after = (sp.Matrix(list(v_n) + list(v_t)) + W * impulses).applyfunc(tidy)
    for i, state in enumerate(pattern):
        p_n, p_t, slip = impulses[i], impulses[n + i], after[n + i]
        if state == "off":
            if after[i] < target[i] - slack:
                return False
            continue
        if p_n < -slack:
            return False
        if state == "stick" and mu[i] is not None and abs(p_t) > mu[i] * p_n + slack:
            return False
        if state == "slide+" and slip < -slack or state == "slide-" and slip > slack:
            return False
    return True


def _fitting_share(matrix: sp.Matrix, rhs: sp.Matrix, pattern: Sequence[str],
                   mu: Sequence[Any], rounded: bool) -> sp.Matrix | None:
    """Impulses that meet the states' equations with every acting contact pushing and
    every sticking one inside its cone, where the equations do not fix them: a linear
    programme over their solutions (in floating point, SciPy's HiGHS) that asks the
    least friction (the sum of |P_t|), whose vertex is then solved again from its own
    equations (the states', the bounds it meets and the frictions it leaves at zero),
    exactly or in the rounded numbers' digits. None where no such impulses exist."""
    from scipy.optimize import linprog

    n = len(pattern)
    A = np.array(matrix.evalf(20).tolist(), dtype=float)
    b = np.array(rhs.evalf(20).tolist(), dtype=float).ravel()
    bounds: list[list[float]] = []  # each row r: r . P <= 0
    for i, state in enumerate(pattern):
        if state == "off":
            continue
        bounds.append([-1.0 if k == i else 0.0 for k in range(2 * n)])
        if state == "stick" and mu[i] is not None:
            cone = float(mu[i])
            for sign in (1.0, -1.0):
                bounds.append([-cone if k == i else sign if k == n + i else 0.0
                               for k in range(2 * n)])
    if not bounds:
        return None
    # the unknowns P and, for each tangential impulse, a bound s_i >= |P_t,i|
    rows = [[*r, *([0.0] * n)] for r in bounds]
    for i in range(n):
        for sign in (1.0, -1.0):
            rows.append([sign if k == n + i else 0.0 for k in range(2 * n)]
                        + [-1.0 if k == i else 0.0 for k in range(n)])
    found = linprog(np.r_[np.zeros(2 * n), np.ones(n)], A_ub=np.array(rows),
                    b_ub=np.zeros(len(rows)), A_eq=np.c_[A, np.zeros((len(b), n))],
                    b_eq=b, bounds=[(None, None)] * (3 * n), method="highs")
    if found.status != 0:
        return None
    x = found.x[:2 * n]
    size = max(1.0, float(np.abs(x).max()))
    tight = [r for r in bounds if abs(np.dot(r, x)) <= 1e-9 * size] + [
        [1.0 if k == n + i else 0.0 for k in range(2 * n)] for i in range(n)
        if pattern[i] != "off" and abs(x[n + i]) <= 1e-9 * size]
    extra = sp.Matrix([[sp.nsimplify(x) for x in r] for r in tight]) if tight else \
        sp.zeros(0, 2 * n)
    if rounded:
        extra = extra.applyfunc(lambda x: sp.Float(x, 50))
    system, values = sp.Matrix.vstack(matrix, extra), sp.Matrix.vstack(
        rhs, sp.zeros(len(tight), 1))
    return rounded_solve(system, values)[0] if rounded else least_norm(system, values)


def _active_sets(problem: ImpulseRows, v: sp.Matrix, target: sp.Matrix):
    """Each set of acting contacts whose block of W is invertible, largest first:
    ``(active, P, v + W P)`` with P solving ``(v + W P)_i = target_i`` where it acts
    and zero elsewhere (the conditions that pick a set are the caller's)."""
    n = len(v)
    work = _Work(problem, f"{n} contacts: {2 ** n} sets of acting contacts, more than "
                 f"the enumeration's budget of work ({MAX_ENUMERATION_WORK} units) lets "
                 "it try (give numbers for the symbols, and rational normals: the rule "
                 "then needs no such search)")
    for size in range(n, 0, -1):
        for active in itertools.combinations(range(n), size):
            work.spend(size)  # counted for singular blocks too
            block = problem.scaled_W.extract(list(active), list(active))
            det = tidy(block.det())
            if det == 0 or (block.has(sp.Float) and det.is_number and abs(det) <= 1e-35
                            * abs(sp.prod(block[i, i] for i in range(size)))):
                continue  # singular (at 50 digits: to within their rounding)
            solved = block.LUsolve(sp.Matrix([target[i] - v[i] for i in active]))
            impulses = sp.zeros(n, 1)
            for k, i in enumerate(active):
                impulses[i] = tidy(solved[k])
            yield active, impulses, v + problem.scaled_W * impulses


def _lcp(problem: ImpulseRows, v: sp.Matrix,
         target: sp.Matrix) -> tuple[sp.Matrix, tuple[str, ...], str]:
    """The complementarity problem: exactly by Lemke's method (:mod:`rigidimpact.solve.lcp`)
    when its numbers are rational, W invertible (then exactly one answer fits, the one
    enumeration finds) and the contacts at most :data:`MAX_LEMKE`; at more contacts,
    or with irrational numbers past :data:`MAX_ENUMERATED`, in floating point with an
    exact check (:func:`_lcp_at_scale`); otherwise by enumerating the acting sets.
    Returns the impulses, the notes a reader must see (an answer in floating point,
    with its residual) and how the problem was solved (at scale)."""
    rational = problem.rational_W and all(isinstance(x, sp.Rational)
                                        for x in list(v) + list(target))
    if len(v) > MAX_LEMKE or (not rational and len(v) > MAX_ENUMERATED) or (
            not rational and len(v) > MAX_ALGEBRAIC_ENUMERATED
            and _algebraic(problem.scaled_W, v, target)):
        return _lcp_at_scale(problem, v, target, rational)
    if rational:
        W = problem.scaled_W.to_DM()
        if W.rank() == W.shape[0]:
            q = [Fraction(int(x.p), int(x.q)) for x in v - target]
            M = [[Fraction(int(x.p), int(x.q)) for x in problem.scaled_W.row(i)]
                 for i in range(len(v))]
            try:
                z = lemke(M, q)
            except NoSolution:  # cannot happen for a positive definite W; be safe
                return _complementarity(problem, v, target), (), ""
            return sp.Matrix([sp.Rational(x.numerator, x.denominator) for x in z]), (), \
                ""
        if len(v) > MAX_ENUMERATED:  # singular W: many impulses, one motion after
            return _lcp_at_scale(problem, v, target, rational)
    return _complementarity(problem, v, target), (), ""


def _lcp_at_scale(problem: ImpulseRows, v: sp.Matrix, target: sp.Matrix,
                  rational: bool) -> tuple[sp.Matrix, tuple[str, ...], str]:
    """Many contacts: the acting set by block principal pivoting in floating point
    (sparse W), then, with rational numbers, that set solved and checked exactly.
    The notes say which it is, with the floating-point answer's certified residual
    when the exact check could not be made; a singular W (more contacts than a
    body's freedoms) has many impulses with the same motion after, and the one
    reported is then said to be chosen close to the least-norm one."""
    import numpy as np
    from scipy.sparse.linalg import splu

    n = len(v)
    W = problem.float_W()
    q = np.array([float(v[i] - target[i]) for i in range(n)])
    try:
        pivots = np.abs(splu(W, permc_spec="MMD_AT_PLUS_A").U.diagonal())
        singular = bool(pivots.min() < 1e-11 * pivots.max())
    except RuntimeError:  # exactly singular
        singular = True
    if singular:
        z, steps = proximal(W, q, 1e-2 * float(W.diagonal().max()))
        method = f"the proximal point method, {steps} rounds of block principal pivoting"
    else:
        z, steps, _ = pivoting(W, q)
        method = f"block principal pivoting, {steps} steps"
        acting = [i for i in range(n) if z[i] > 0]
        if rational and problem.rational_rows:  # in SymPy's QQ (python-flint's fmpq
            def field(x: sp.Rational) -> Any:  # where it is installed), W unformed
                return QQ(int(x.p), int(x.q))

            exact = confirm_by_rows(
                [[(j, field(x)) for j, x in row] for row in problem.sparse_rows],
                [field(x) for x in problem.inverse_inertia],
                [field(x) for x in v - target], acting)
        elif not rational and _algebraic(problem.scaled_W, v, target):  # sqrt(3) in W
            exact = _confirm_in_field(problem.scaled_W, v, target, acting)
        elif rational:  # W rational, J not (sqrt(3) in a hexagonal cluster)
            rows: dict[int, dict[int, Fraction]] = {i: {} for i in range(n)}
            for i, j, x in problem.W_entries:
                rows[i][j] = Fraction(int(x.p), int(x.q))
            exact = confirm(rows, [Fraction(int(x.p), int(x.q)) for x in v - target],
                            acting)
        else:
            exact = None
        if exact is not None:
            if isinstance(exact, sp.Matrix):  # already SymPy's (a field with roots)
                return exact, (), (f"{n} contacts: the acting set found in floating "
                                   f"point ({method}) and confirmed in exact arithmetic")
            return sp.Matrix([sp.sympify(QQ.to_sympy(x) if not isinstance(x, Fraction)
                                         else sp.Rational(x.numerator, x.denominator))
                              for x in exact]), (), (
                    f"{n} contacts: the acting set found in floating point ({method}) "
                    "and confirmed in exact arithmetic")
    error = residual(W, q, z)
    how = ("W is singular (more contacts than the bodies' freedoms): the motion after "
           "is unique, the impulses are not (those reported stay close to the "
           "least-norm ones); " if singular else "")
    note = (f"{n} contacts solved in floating point ({method}): {how}complementarity "
            f"residual {error:.1e} of the largest closing speed"
            + ("" if error < 1e-9 else " (LARGE: do not trust these numbers)"))
    return sp.Matrix([sp.Float(float(x), 17) for x in z]), (note,), note


def _algebraic(W: sp.Matrix, v: sp.Matrix, target: sp.Matrix) -> bool:
    """Whether W and the speeds are numbers built from roots of rationals (sqrt(3) in a
    fan of contacts at multiples of 30 degrees): exact in a field of numbers."""
    data = sp.Tuple(*W, *v, *target)
    return not data.free_symbols and not data.atoms(sp.Float, sp.sin, sp.cos, sp.tan)


def _confirm_in_field(W: sp.Matrix, v: sp.Matrix, target: sp.Matrix,
                      acting: Sequence[int]) -> sp.Matrix | None:
    """The impulses of the acting set `acting` solved exactly in the numbers' own field
    (the rationals with sqrt(3) adjoined, say), and kept only if they are the answer:
    each acting impulse positive and each other contact's speed at least its target.
    Signs of numbers in the field are decided at 50 digits after an exact zero test.
    None where the set is not confirmed."""
    n = len(v)
    if not acting:
        return sp.zeros(n, 1) if all(sp.N(v[i] - target[i], 50) >= 0 for i in range(n)) \
            else None
    A = list(acting)
    # W and the speeds taken into one field at once: two fields made apart and unified
    # cost a search for an isomorphism between them (PSLQ), minutes for four roots
    whole = sp.Matrix.hstack(W, v - target).to_DM(extension=True).to_field()
    K, rows = whole.domain, whole.to_list()
    block = DomainMatrix([[rows[i][j] for j in A] for i in A], (len(A), len(A)), K)
    rhs = DomainMatrix([[-rows[i][n]] for i in A], (len(A), 1), K)
    try:
        solved = block.lu_solve(rhs).to_list()
    except (ZeroDivisionError, ValueError, sp.polys.matrices.exceptions.DMError):
        return None  # a singular block
    P = [K.zero] * n
    for k, i in enumerate(A):
        P[i] = solved[k][0]

    def positive(x: Any, strict: bool) -> bool:
        if x == K.zero:
            return not strict
        return bool(sp.N(K.to_sympy(x), 50) > 0)

    if not all(positive(P[i], True) for i in A):
        return None
    if not all(positive(sum((rows[i][j] * P[j] for j in A), rows[i][n]), False)
               for i in range(n) if i not in A):
        return None
    return sp.Matrix([sp.radsimp(K.to_sympy(x)) for x in P])


def _complementarity(problem: ImpulseRows, v: sp.Matrix, target: sp.Matrix) -> sp.Matrix:
    """P >= 0 with ``v + W P >= target`` and equality wherever P > 0, by trying the
    acting sets (largest first) within MAX_ENUMERATION_WORK: past that, one line says
    how large the problem is instead of a run of minutes."""
    for active, impulses, after in _active_sets(problem, v, target):
        if all(impulses[i] >= 0 for i in active) and all(
                after[i] - target[i] >= 0 for i in range(len(v)) if i not in active):
            return impulses
    return sp.zeros(len(v), 1)


def simultaneous_cases(problem: ImpulseRows) -> tuple[Solution, ...]:
    """The simultaneous rule with symbols: one outcome per set of acting contacts,
    each with the conditions under which it is the one (its impulses >= 0, every
    released contact separating at least as fast as its law asks, every contact
    closing or at rest before). Where W is positive definite exactly one case holds
    at any numbers. Under Newton's law each contact's sign before decides its target
    (-e v- if it closes, 0 if it opens), so the cases are also split by those signs.

    Examples
    --------
    >>> from rigidimpact.laws.contact import Contact
    >>> from rigidimpact.model.bodies import Body
    >>> from rigidimpact.solve.collision import Collision
    >>> m = sp.Symbol("m", positive=True)
    >>> balls = [Body.rigid(1, 1, (0, 0), (1, 0), name="a"),
    ...          Body.rigid(m, 1, (2, 0), (0, 0), name="b"),
    ...          Body.rigid(1, 1, (4, 0), (0, 0), name="c")]
    >>> touches = [Contact(restitution=1, name="ab", bodies=("a", "b"), point=(1, 0)),
    ...            Contact(restitution=1, name="bc", bodies=("b", "c"), point=(3, 0))]
    >>> both = Collision(tuple(balls), tuple(touches)).simultaneous_cases()[0]
    >>> both.results()["c.vx"], both.conditions
    (2/(m + 2), (True,))
    """
    regimes = [t.name for t in problem.contacts if t.laws[1].solved_by_regimes]
    if regimes:  # Coulomb's and Walton's courses: no closed form acting together
        problem.smooth_only("with symbols")
    stick = [i for i, t in enumerate(problem.contacts) if t.laws[1].grips]
    v = problem.scaled_velocity_before
    poisson = problem.acts_by_impulse()
    n = len(v)
    if stick and poisson:
        raise InputError(f"{problem.contacts[stick[0]].name}.law", "a sticking contact "
                         "acting together with others takes Newton's law")
    # Newton's target -e min(v, 0) depends on each contact's sign before: one
    # pattern of signs at a time (a contact at rest, or under Poisson's law: one)
    options = []
    for i in range(n):
        if poisson or tidy(v[i]).is_zero:
            options.append([(sp.true, sp.Integer(0), v[i].is_negative is True)])
            continue
        options.append([(sp.Le(v[i], 0), problem.leaving(i, v[i]), True),
                        (sp.Ge(v[i], 0), sp.Integer(0), False)])
    count = math.prod(len(o) for o in options) * 2**n  # sign patterns x acting sets
    if count > MAX_SYMBOLIC_CASES:
        raise InputError("contacts", _too_many_cases(n, count))
    work = _Work(problem, _too_many_cases(n, count))
    cases = []
    for pattern in itertools.product(*options):
        if not poisson and not any(closing for _, _, closing in pattern):
            continue  # nothing approaches: no impact
        signs = case_conditions([c for c, _, _ in pattern])
        if signs == (sp.false,):
            continue
        target = sp.Matrix([t for _, t, _ in pattern])
        found = (_active_sets(problem, v, target) if not stick
                 else _sticking_sets(problem, v, target, stick))
        for active, compression, after, *extra in found:
            work.spend(len(active))
            held = case_conditions(list(signs) + [sp.Ge(compression[i], 0) for i in active]
                               + [sp.Ge(tidy(after[i] - target[i]), 0)
                                  for i in range(n) if i not in active])
            if held == (sp.false,):
                continue
            impulses = sp.Matrix([problem.contacts[i].laws[0].from_compression(
                compression[i]) if poisson else compression[i]
                for i in range(n)]).applyfunc(tidy)
            if extra:  # sticking contacts: their tangential impulses move u too
                tangential, free = extra
                u = (problem.u_before + problem.M_inverse * (problem.scaled_J.T * impulses
                                                       + problem.scaled_J_t.T * tangential)
                     ).applyfunc(tidy)
                more: dict[str, Any] = {"tangential": problem.named(tangential),
                        "courses": tuple(f"{t.name}: " + (STATE["stick"] if i in active
                                                          else STATE["off"])
                                         for i, t in enumerate(problem.contacts))}
                if free:
                    more["notes"] = (f"the motion after is unique but the impulses are "
                                     f"not: {', '.join(map(str, free))} may take any "
                                     "value that meets the conditions",)
            else:
                u, more = problem.kick(problem.u_before, impulses), {}
            more["conditions"] = held
            cases.append(problem.outcome("simultaneous", (), u, problem.named(impulses),
                                       tuple(problem.contacts[i].name for i in active),
                                       **more))
    return tuple(cases)


def _sticking_sets(problem: ImpulseRows, v: sp.Matrix, target: sp.Matrix, stick: Sequence[int]):
    """As :func:`_active_sets`, with the contacts in `stick` leaving without slip
    where they act (their tangential impulse an unknown of its own, no cone):
    ``(active, P_n, v_n + (W P)_n, P_t)`` for each set whose block is invertible."""
    n = len(v)
    rows = sp.Matrix.vstack(problem.scaled_J, problem.scaled_J_t)
    W = (rows * problem.M_inverse * rows.T).applyfunc(tidied)
    slip = (problem.scaled_J_t * problem.u_before).applyfunc(tidy)
    work = _Work(problem, _too_many_cases(n, 2**n))
    for size in range(n, 0, -1):
        for active in itertools.combinations(range(n), size):
            work.spend(size + len([i for i in active if i in stick]))
            unknowns = list(active) + [n + i for i in active if i in stick]
            block = W.extract(unknowns, unknowns)
            rhs = sp.Matrix([target[i] - v[i] for i in active]
                            + [-slip[i] for i in active if i in stick])
            if tidy(block.det()) != 0:
                solved, free = block.LUsolve(rhs), ()
            else:  # more conditions than freedoms: consistent, or no such case
                try:
                    solved, params = block.gauss_jordan_solve(rhs)
                except ValueError:
                    continue
                # the impulses are not unique (the motion after is: a null vector
                # of W's block is one of J^T's); each free part keeps a name
                free = tuple(sp.Symbol(f"tau_{k + 1}", real=True)
                             for k in range(len(params)))
                solved = solved.xreplace(dict(zip(params, free, strict=True)))
            P = sp.zeros(2 * n, 1)
            for k, j in enumerate(unknowns):
                P[j] = tidy(solved[k])
            yield active, P[:n, 0], v + (W * P)[:n, 0], P[n:, 0], free


def _too_many_cases(n: int, count: int) -> str:
    return (f"{n} contacts with symbols make {count} cases (signs before x contacts "
            f"acting), more than the budget of work ({MAX_ENUMERATION_WORK} units) "
            "lets the rule solve: give "
            "numbers for the symbols (--set or [values]) and it is solved exactly at them")



