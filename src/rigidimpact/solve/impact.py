"""An impact of two bodies: its unknowns, its equations, and their solution.

The equations are built from the laws in :mod:`rigidimpact.laws.law` in the contact frame
(x along the normal), solved as the linear system they are, and tidied by ``cancel``
and ``factor`` only: no blanket ``simplify``.

Examples
--------
>>> from rigidimpact.model.bodies import Body
>>> from rigidimpact.laws.contact import Contact
>>> a = Body.particle(1, velocity=(2, 0), name="a")
>>> b = Body.particle(1, name="b")
>>> sol = Impact(a, b, Contact(restitution=1)).solve()
>>> sol.results()["a.vx"], sol.results()["b.vx"]
(0, 2)
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws import law as laws
from rigidimpact.laws import routh
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.model.impulse import TouchingPair
from rigidimpact.solve.solution import Solution, certified
from rigidimpact.symbolic.geometry import spin_cross
from rigidimpact.symbolic.notation import labelled, make_symbol
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Impact"]

# digits kept when an all-number scene has transcendental data (see Impact.numeric)
NUMERIC_DIGITS = 50
DEFAULT_UNKNOWNS = (("V_1fx", "V_1fy", "omega_1fz"), ("V_2fx", "V_2fy", "omega_2fz"))


def _rotated(body: Body, frame: sp.MatrixBase, digits: int | None) -> Body:
    """The body described in the contact frame (as 50-digit numbers in numeric mode)."""
    pivot = body.pivot
    if frame != sp.eye(2):
        pivot = None if pivot is None else sp.ImmutableMatrix(frame * pivot)
        body = replace(body, position=frame * body.position, velocity=frame * body.velocity,
                       pivot=pivot)
    if digits:
        body = replace(body, mass=body.mass.evalf(digits), inertia=body.inertia.evalf(digits),
                       position=body.position.evalf(digits),
                       velocity=body.velocity.evalf(digits), spin=body.spin.evalf(digits),
                       pivot=None if pivot is None else pivot.evalf(digits))
    return body


@dataclass(frozen=True)
class Impact:
    """Two bodies meeting at O under a contact law.

    Parameters
    ----------
    first, second : Body
        The first is on the -x side of O (the side the normal points away from).
    contact : Contact
        Line of impact, restitution and tangential behaviour.
    unknown_names : pair of (vx, vy, omega) names, optional
        Names for the final velocity components in the contact frame; the default is
        the paper's section 3 notation ``V_1fx, V_1fy, omega_1fz, ...``.
    numbers : tuple of (law, number) pairs, optional
        Equation numbers of a published source, by law (see
        :data:`rigidimpact.paper.problems.PAPER_NUMBERS`); generic impacts have none.

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> imp = Impact(Body.particle(1, (1, 0), "p"), Body.disc(1, 1, name="d"), Contact())
    >>> [str(u) for u in imp.unknowns]
    ['V_1fx', 'V_1fy', 'V_2fx', 'V_2fy', 'omega_2fz']
    """

    first: Body
    second: Body
    contact: Contact
    unknown_names: tuple[tuple[str, str, str], tuple[str, str, str]] = DEFAULT_UNKNOWNS
    numbers: tuple[tuple[str, str], ...] = ()

    def __post_init__(self) -> None:
        for where, body in (("first", self.first), ("second", self.second)):
            if not isinstance(body, Body):
                raise InputError(where, f"must be a Body (Body.particle, Body.rod, ...), got "
                                 f"{type(body).__name__} {body!r}")
        if not isinstance(self.contact, Contact):
            raise InputError("contact", f"must be a Contact, got "
                             f"{type(self.contact).__name__} {self.contact!r}")
        if self.first.name == self.second.name:
            raise InputError("bodies", f"the two bodies share the name {self.first.name!r}")
        for body in (self.first, self.second):
            if body.inertia.is_zero and body.support != "fixed" and \
                    not all(c.is_zero for c in body.position):
                raise InputError(f"{body.name}.position", "a point mass must sit at the "
                                 "contact point O, or it cannot be touched there")
        if self.first.support == "fixed" and self.second.support == "fixed":
            raise InputError("bodies", "two fixed bodies cannot collide: at least one must "
                             "move")
        approach = self.approach_speed
        if approach.is_nonpositive:
            raise InputError("bodies", f"the bodies are not approaching at O (normal approach "
                             f"speed {approach}); there is no impact")

    @cached_property
    def numeric(self) -> bool:
        """True when the impact is all numbers and some are transcendental (a sine of
        0.37 rad, say): such an impact is solved with 50-digit floats, because exact
        arithmetic over many unrelated trig values swells without making anything clearer.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> rod = Body.rod(1, 2, sp.Rational(37, 100), sp.Rational(1, 2), name="r")
        >>> Impact(Body.particle(1, (1, 0), "p"), rod, Contact()).numeric
        True

        An angle such as 201 degrees is exact in SymPy as nested radicals (a square root
        of an expression with square roots); exact algebra over them swells the same way,
        so they count as transcendental here.
        """
        data = [self.contact.restitution, *self.contact.normal]
        for b in (self.first, self.second):
            data += [b.mass, b.inertia, *b.position, *b.velocity, b.spin]
            data += [] if b.pivot is None else list(b.pivot)
        exact = sp.Tuple(*data)
        return not exact.free_symbols and (bool(exact.atoms(sp.sin, sp.cos, sp.tan))
                                           or _nested_radicals(exact))

    @cached_property
    def frame(self) -> sp.ImmutableMatrix:
        """Rotation from scene to contact coordinates."""
        frame = self.contact.frame
        return frame.evalf(NUMERIC_DIGITS) if self.numeric else frame

    @cached_property
    def _local(self) -> tuple[tuple[Body, Body], dict[sp.Dummy, sp.Expr]]:
        """The bodies in the contact frame, and what stands for what.

        With a symbolic tilt of the normal, each rotated component that still holds the
        angle (``R_1x cos(phi) + R_1y sin(phi)``) is replaced by a stand-in symbol: the
        algebra is then that of the untilted problem, and the rotation is put back once,
        at the end, untidied. Tidying through the angle multiplies out products of
        sines and cosines with every other symbol and costs minutes.
        """
        digits = NUMERIC_DIGITS if self.numeric else None
        bodies = [_rotated(b, self.contact.frame, digits) for b in (self.first, self.second)]
        # a symbolic angle, or a numeric one inside sin and cos (cos(0.3)), tilts the frame
        tilt = self.contact.frame.free_symbols | self.contact.frame.atoms(sp.sin, sp.cos)
        if digits or not tilt:
            return (bodies[0], bodies[1]), {}
        stand_ins: dict[sp.Dummy, sp.Expr] = {}

        def local(x: sp.Expr, name: str) -> sp.Expr:
            x = tidy(x)
            if not x.has(*tilt):
                return x
            stand_in = sp.Dummy(name, real=True)
            stand_ins[stand_in] = x
            return stand_in

        for k, body in enumerate(bodies):
            def vector(v, name, k=k):
                return None if v is None else sp.ImmutableMatrix(
                    [local(c, f"{name}{k + 1}{axis}") for c, axis in zip(v, "nt", strict=True)])
            position = vector(body.position, "R")
            if body.pivot is None:
                pivot, velocity = None, vector(body.velocity, "V")
            else:  # the pivot through its offset from the centre (zero stays zero), and
                # the velocity as the turn about it, in the same stand-ins
                pivot = sp.ImmutableMatrix(position - vector(body.position - body.pivot, "D"))
                velocity = spin_cross(body.spin, position - pivot)
            bodies[k] = replace(body, position=position, velocity=velocity, pivot=pivot)
        return (bodies[0], bodies[1]), stand_ins

    @property
    def stand_ins(self) -> dict[sp.Dummy, sp.Expr]:
        """What each stand-in symbol of a tilted frame stands for (empty without a tilt)."""
        return self._local[1]

    @property
    def before(self) -> tuple[Body, Body]:
        """Both bodies before the impact, in the contact frame (see ``_local``)."""
        return self._local[0]

    @property
    def approach_speed(self) -> sp.Expr:
        """How fast the contact points close along the normal: ``v_1ix - v_2ix``.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> Impact(Body.particle(1, (3, 0), "a"), Body.particle(1, (1, 0), "b"),
        ...        Contact()).approach_speed
        2
        """
        first, second = self.before
        closing = sp.cancel(first.contact_velocity[0] - second.contact_velocity[0])
        return closing.xreplace(self._local[1])

    @cached_property
    def after(self) -> tuple[Body, Body]:
        """Both bodies after the impact, with unknown symbols for their motion."""
        states = []
        for body, names in zip(self.before, self.unknown_names, strict=True):
            vx, vy, omega = (make_symbol(n, real=True) for n in names)
            if body.support == "fixed":
                states.append(body)
            elif body.support == "pivot":  # one unknown: the turn about the pivot
                states.append(body.with_motion(_turning(omega, body), omega))
            else:
                spin = 0 if body.inertia.is_zero else omega
                states.append(body.with_motion((vx, vy), spin))
        return states[0], states[1]

    @cached_property
    def _impulse_unknowns(self) -> tuple[sp.Symbol, ...]:
        """The contact impulse's components, unknowns of their own when both bodies are
        supported (no conservation law then holds without them)."""
        if self.first.support == "free" or self.second.support == "free":
            return ()
        names = ("n", "t") if self.contact.laws[1].unknown_tangential else ("n",)
        return tuple(labelled("P", n, self.contact.name, real=True) for n in names)

    @property
    def unknowns(self) -> tuple[sp.Symbol, ...]:
        """The final velocity components and spins to solve for (and the contact
        impulse when both bodies are supported)."""
        found: list[sp.Symbol] = []
        for body in self.after:
            if body.support == "free":
                found += [body.velocity[0], body.velocity[1]]
            if body.support != "fixed" and isinstance(body.spin, sp.Symbol):
                found.append(body.spin)
        return tuple(found) + self._impulse_unknowns

    def equations(self) -> tuple[laws.Equation, ...]:
        """The laws that fix the unknowns, in the order the paper gives them (with a
        symbolic tilt, in the rotated components themselves).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> imp = Impact(Body.particle(1, (1, 0), "p"), Body.rod(1, 2, 1, 1, name="r"),
        ...              Contact())
        >>> [eq.law for eq in imp.equations()]  # doctest: +NORMALIZE_WHITESPACE
        ['normal momentum', 'tangential momentum', 'tangential momentum',
         'angular momentum', 'restitution']
        """
        stand_ins = self._local[1]
        local = self._local_equations()
        numbers = dict(self.numbers)
        if numbers:
            local = tuple(replace(eq, paper=numbers.get(eq.law, eq.paper)) for eq in local)
        return tuple(eq.xreplace(stand_ins) for eq in local) if stand_ins else local

    def _contact_laws(self) -> tuple[laws.NewtonRestitution, laws.ContactLaw]:
        """The contact's restitution and tangential laws (e as 50-digit numbers in
        numeric mode)."""
        restitution, tangential = self.contact.laws
        if self.numeric:
            restitution = replace(restitution,
                                  e=self.contact.restitution.evalf(NUMERIC_DIGITS))
        return restitution, tangential

    def _local_equations(self) -> tuple[laws.Equation, ...]:
        """The laws in the contact frame, stand-ins and all: the momentum laws that hold
        for these supports, then the contact's own laws (printed as they are imposed)."""
        before, after = self.before, self.after
        restitution, tangential = self._contact_laws()
        linear, angular = self._momentum_laws()
        smooth = not tangential.grips
        # with friction the path in impulse space bends: Poisson's and the energetic law
        # are then not Newton's relation, and Routh's method (printed course by course)
        # is what imposes them
        bent = self.contact.by_regimes and restitution.splits_on_compression
        return (*linear, *(tangential.equations(before, after) if smooth else ()), *angular,
                *(() if bent else restitution.equations(before, after)),
                *(() if smooth else tangential.equations(before, after)))

    def _momentum_laws(self) -> tuple[list[laws.Equation], list[laws.Equation]]:
        """Which momenta the impact keeps, by the bodies' supports (linear, angular).

        Two free bodies keep the pair's linear momentum and each its angular momentum
        about O. With one body pivoted or fixed the support's reaction is unknown, so
        the pair's linear momentum is not kept: with a pivot, the pair's angular
        momentum about the pivot is (the reaction has no moment there), and the free
        body keeps its own angular momentum about O. With both supported nothing is
        kept: each pivoted body turns by the moment of the contact impulse about its
        pivot, with the impulse among the unknowns.
        """
        (first, second), (first_after, second_after) = self.before, self.after
        pair = ((first, first_after), (second, second_after))
        if self._impulse_unknowns:
            impulse = sp.Matrix([*self._impulse_unknowns, 0][:2])
            return [laws.impulse_momentum(b, a, sign * impulse)
                    for (b, a), sign in zip(pair, (-1, 1), strict=True)
                    if b.support == "pivot"], []
        free = [(b, a) for b, a in pair if b.support == "free"]
        angular = [laws.angular_momentum(b, a) for b, a in free if not b.inertia.is_zero]
        supported = [b for b, _ in pair if b.support != "free"]
        if supported:
            pivot = ([laws.angular_momentum_about_pivot((first, second),
                                                        (first_after, second_after),
                                                        supported[0])]
                     if supported[0].support == "pivot" else [])
            return pivot, angular
        linear = [laws.normal_momentum(first, first_after, second, second_after)]
        if self.contact.laws[1].grips:
            linear.append(
                laws.pair_tangential_momentum(first, first_after, second, second_after))
        return linear, angular

    def diagram(self, values: dict) -> Any:
        """Routh's diagram of this frictional impact at `values` (exact numbers for its
        symbols): the course taken and the impulse at each of its events, for
        :func:`rigidimpact.outputs.plots.routh_diagram`.

        Examples
        --------
        >>> ball = Body.particle(1, (1, 1), "ball")
        >>> found = Impact(ball, Body.fixed("floor"), Contact(
        ...     restitution=1, tangential="coulomb", friction=sp.Rational(1, 4))).diagram({})
        >>> found.regime.name, found.regime.path[-1]
        ('slip', (2, 1/2))
        """
        return routh.diagram(self, values)

    def solve(self) -> Solution:
        """Solve for the impulse at O in the generalized-impulse core, then the motion;
        at numbers the answer is certified (see :func:`~rigidimpact.solve.solution.certified`):
        its physical limits are among its warnings, and one that fails its own laws'
        check is refused in one line, never returned.

        The core (:class:`~rigidimpact.model.impulse.TouchingPair`) gives each body's motion
        after an impulse P at O: ``u+ = u- + M^-1 J^T P``. The contact's laws, imposed
        on those motions exactly as they are printed, are linear in P (one equation for
        the normal impulse, one for the tangential); solving them and substituting back
        satisfies every printed law at once, with results far more compact than
        eliminating all six velocities together.

        Returns
        -------
        Solution

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> sol = Impact(Body.particle(1, (2, 0), "a"), Body.particle(3, name="b"),
        ...              Contact(restitution=0)).solve()
        >>> sol.results()["b.vx"]
        1/2
        """
        return certified(self._solve())

    def _solve(self) -> Solution:
        core = TouchingPair(self.before)
        if self.contact.by_regimes:
            return self._solve_frictional(core)
        # the tangential law's one face, in contact space, as every path asks it (the
        # rules, space, a mechanics system); its printed equations show it, in the
        # paper's unknowns, and are not solved apart
        restitution, tangential = self._contact_laws()
        found = tangential.impulse(core.W, core.velocity_before, restitution)
        normal, along = (tidy(x) for x in found.impulse)
        return self._solved_by(core, (normal, along))

    def in_terms_of(self, normal: sp.Symbol) -> dict[sp.Symbol, sp.Expr]:
        """Each unknown motion after a smooth impact written with its normal impulse
        left as the symbol `normal` (u+ = u- + M^-1 J^T P, no elimination needed).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> J = sp.Symbol("J")
        >>> found = Impact(Body.particle(2, (1, 0), "a"), Body.particle(3, name="b"),
        ...                Contact()).in_terms_of(J)
        >>> found
        {V_1fx: 1 - J/2, V_1fy: 0, V_2fx: J/3, V_2fy: 0}
        """
        core = TouchingPair(self.before)
        kicked = core.bodies_after(sp.ImmutableMatrix([normal, 0]))
        values = {}
        for state, moved in zip(self.after, kicked, strict=True):
            if state.support == "free":
                values[state.velocity[0]] = sp.expand(moved.velocity[0])
                values[state.velocity[1]] = sp.expand(moved.velocity[1])
            if state.support != "fixed" and isinstance(state.spin, sp.Symbol):
                values[state.spin] = sp.expand(sp.sympify(moved.spin))
        return values

    def _solved_by(self, core: TouchingPair, impulse: tuple[sp.Expr, sp.Expr],
                   **extra) -> Solution:
        """The solution that a known impulse at O gives."""
        local_impulse = sp.ImmutableMatrix(impulse)
        kicked = core.bodies_after(local_impulse)
        values = {}
        for state, moved in zip(self.after, kicked, strict=True):
            if state.support == "free":
                values[state.velocity[0]] = tidy(moved.velocity[0])
                values[state.velocity[1]] = tidy(moved.velocity[1])
            if state.support != "fixed" and isinstance(state.spin, sp.Symbol):
                values[state.spin] = tidy(sp.sympify(moved.spin))
        for unknown, component in zip(self._impulse_unknowns, impulse, strict=False):
            values[unknown] = component
        lost = tidy(-core.work(local_impulse, core.velocity_before,
                               core.velocity_after(local_impulse)))
        return self._solution(values, local_impulse, lost, **extra)

    def _solve_frictional(self, core: TouchingPair) -> Solution:
        """Friction: the impulse by Routh's method (Coulomb) or Walton's law (rough), one
        solution per course the impact can take; with symbols, their ``Piecewise``."""
        restitution, tangential = self.contact.laws  # the tangential law owns its regimes
        if self.numeric:  # in the 50-digit numbers the bodies are in
            restitution, tangential = (_in_digits(law) for law in (restitution, tangential))
        found = tangential.regimes(core.W, core.velocity_before, restitution)
        solutions = [self._solved_by(core, r.impulse, regime=r.name, path=r.path)
                     for r in found]
        if len(solutions) == 1:
            return solutions[0]
        return _piecewise(solutions, tuple(r.conditions for r in found))

    def _solution(self, values: dict, local_impulse: sp.ImmutableMatrix,
                  lost: sp.Expr, **extra) -> Solution:
        """The self-contained solution: final motion rotated back to the scene frame once,
        energies from the work of the impulse in the contact frame, stand-ins put back."""
        stand_ins = self._local[1]
        (first, second), after = self.before, self.after
        moved = [a.with_motion(a.velocity.xreplace(values),
                               sp.sympify(a.spin).xreplace(values))
                 if a.support != "fixed" else a for a in after]
        back = self.frame.T  # contact frame -> scene frame
        finals = []
        for k, (original, local) in enumerate(zip((self.first, self.second), moved,
                                                  strict=True)):
            if original.support == "fixed":
                finals.append(original)
                continue
            velocity = local.velocity if back == sp.eye(2) else \
                (back * local.velocity).applyfunc(tidy)
            spin = sp.sympify(local.spin).xreplace(stand_ins)
            if self.numeric:  # keep the body's data in the same 50-digit numbers
                numbers = self.before[k]
                pivot = None if numbers.pivot is None else back * numbers.pivot
                original = replace(original, mass=numbers.mass, inertia=numbers.inertia,
                                   position=back * numbers.position, pivot=pivot)
            if original.support == "pivot":  # the turn about the pivot, by construction
                finals.append(original.with_motion(_turning(spin, original), spin))
                continue
            finals.append(original.with_motion(velocity.xreplace(stand_ins), spin))
        # a rotation keeps kinetic energy: with a tilt, take it in the scene frame
        given = (self.first, self.second) if stand_ins else (first, second)
        energy_before = tidy(given[0].kinetic_energy + given[1].kinetic_energy)
        lost = lost.xreplace(stand_ins)
        # with a tilt the two are large and share little: their quotient is left as it is
        fraction = lost / energy_before if stand_ins else tidy(lost / energy_before)
        normal, along = (x.xreplace(stand_ins) for x in local_impulse)
        name = self.contact.name
        # the impulse acts at O, the origin of the bodies' positions, whatever point the
        # contact names (a collision's core is handed its bodies shifted to that point)
        at_o = self.contact if all(x == 0 for x in self.contact.point) else \
            replace(self.contact, point=(0, 0))
        return Solution(
            before=(self.first, self.second), after=(finals[0], finals[1]),
            impulses={name: normal}, tangential={name: along}, contacts=(at_o,),
            acted=(name,), frame=self.frame, equations=self.equations(),
            unknowns=self.unknowns,
            values={u: x.xreplace(stand_ins) for u, x in values.items()},
            energies=(energy_before, lost, fraction), approach_speed=self.approach_speed,
            **extra)


def _piecewise(solutions: list[Solution], conditions: tuple[tuple, ...]) -> Solution:
    """One solution whose every result is a ``Piecewise`` over the courses of the impact,
    keeping each course's own solution and conditions."""
    cases = [sp.And(*c) if c else sp.true for c in conditions]

    def pw(pick) -> sp.Expr:
        parts = [pick(s) for s in solutions]
        if all(p == parts[0] for p in parts):
            return parts[0]
        return sp.Piecewise(*zip(parts, cases, strict=True))

    first = solutions[0]
    after = []
    for k, body in enumerate(first.after):
        if body.support == "fixed":
            after.append(body)
            continue
        velocity = [pw(lambda s, k=k, i=i: s.after[k].velocity[i]) for i in (0, 1)]
        after.append(replace(body, velocity=velocity, spin=pw(lambda s, k=k: s.after[k].spin)))
    name = first.contact.name
    return replace(
        first, after=(after[0], after[1]),
        values={u: pw(lambda s, u=u: s.values[u]) for u in first.values},
        impulses={name: pw(lambda s: s.contact_impulse[0])},
        tangential={name: pw(lambda s: s.contact_impulse[1])},
        energies=(first.kinetic_energy_before, pw(lambda s: s.energy_lost),
                  pw(lambda s: s.energy_loss_fraction)),
        regime=None, path=(),
        regimes=tuple((s.regime, c, s) for s, c in zip(solutions, conditions, strict=True)))


def _nested_radicals(exact: sp.Basic) -> bool:
    """True when a root is taken of something that is not a rational number.

    Examples
    --------
    >>> _nested_radicals(sp.Tuple(sp.sqrt(2), sp.Rational(1, 3)))
    False
    >>> _nested_radicals(sp.Tuple(sp.cos(67 * sp.pi / 60)))
    True
    """
    return any(not p.exp.is_Integer and not p.base.is_Rational
               for p in exact.atoms(sp.Pow))


def _in_digits(law: Any) -> Any:
    """A law with its coefficients as 50-digit numbers (numeric mode)."""
    return replace(law, **{f.name: None if getattr(law, f.name) is None else
                           sp.sympify(getattr(law, f.name)).evalf(NUMERIC_DIGITS)
                           for f in fields(law)})


def _turning(spin: sp.Expr, body: Body) -> sp.ImmutableMatrix:
    """The centre's velocity of a body turning at `spin` about its pivot."""
    return spin_cross(spin, body.position - body.pivot)
