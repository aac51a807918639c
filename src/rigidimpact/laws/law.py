"""The laws of an impulsive contact, as labelled equations with the paper's numbers.

Each function takes bodies in the contact frame (x along the normal) before and after
the impact and returns an :class:`Equation` ``lhs = rhs`` that keeps what it says and
which law it is, so a derivation can be shown step by step. The laws are generic: the
equation numbers of Mungan (Eur. J. Phys. 28, 2007) are attached by the paper's own
problems (:data:`rigidimpact.paper.problems.PAPER_NUMBERS`), not here.

Examples
--------
>>> from rigidimpact.model.bodies import Body
>>> ball = Body.particle(2, velocity=(3, 0))
>>> after = ball.with_motion((1, 0), 0)
>>> tangential_momentum(ball, after)  # doctest: +NORMALIZE_WHITESPACE
Equation(label='tangential momentum of ball is unchanged', paper='', lhs=0, rhs=0,
         law='tangential momentum')
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws import cone, ends, routh
from rigidimpact.laws.walton import walton
from rigidimpact.model.bodies import Body
from rigidimpact.symbolic.geometry import cross
from rigidimpact.symbolic.notation import Given, escape_text, to_latex

__all__ = [
    "ContactImpulse",
    "Equation",
    "normal_momentum",
    "tangential_momentum",
    "pair_tangential_momentum",
    "angular_momentum",
    "angular_momentum_about_pivot",
    "restitution",
    "no_slip",
    "impulse_momentum",
    "ContactLaw",
    "NewtonRestitution",
    "Smooth",
    "Stick",
    "PoissonRestitution",
    "EnergeticRestitution",
    "Coulomb",
    "Rough",
    "RESTITUTION_LAWS",
    "TANGENTIAL_LAWS",
]


@dataclass(frozen=True)
class Equation:
    """``lhs = rhs``, with what it states, the paper's equation number(s) where a
    paper's problem gives them, and which law it is.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> eq = Equation("demo", "(1)", 2 * x, 4)
    >>> eq.residual, eq.as_sympy()
    (2*x - 4, Eq(2*x, 4))
    """

    label: str
    paper: str
    lhs: sp.Expr
    rhs: sp.Expr
    law: str = ""  # which law this is, so a problem from a paper can number it

    def __post_init__(self) -> None:
        object.__setattr__(self, "lhs", sp.sympify(self.lhs, strict=True))
        object.__setattr__(self, "rhs", sp.sympify(self.rhs, strict=True))

    @property
    def residual(self) -> sp.Expr:
        """``lhs - rhs``, zero when the equation holds."""
        return self.lhs - self.rhs

    def _repr_latex_(self) -> str:
        r"""Typeset in Jupyter, in the paper's notation, with what the law says.

        Examples
        --------
        >>> from rigidimpact.symbolic.notation import symbol
        >>> print(Equation("restitution", "(4)", symbol("V_x"), 0)._repr_latex_())
        $\displaystyle V_{x} = 0 \qquad \text{restitution (4)}$
        """

        note = escape_text(self.label + (f" {self.paper}" if self.paper else ""),
                           angles=False)
        return (rf"$\displaystyle {to_latex(self.lhs)} = {to_latex(self.rhs)} \qquad "
                rf"\text{{{note}}}$")

    def as_sympy(self) -> sp.Equality:
        """The equation as an unevaluated SymPy ``Eq``."""
        return sp.Eq(self.lhs, self.rhs, evaluate=False)

    def subs(self, *args, **kwargs) -> Equation:
        """The same law with a substitution made on both sides.

        Examples
        --------
        >>> x = sp.Symbol("x")
        >>> Equation("demo", "", x, 1).subs(x, 2).lhs
        2
        """
        return replace(self, lhs=self.lhs.subs(*args, **kwargs),
                       rhs=self.rhs.subs(*args, **kwargs))

    def xreplace(self, rule: dict) -> Equation:
        """The same law with `rule` replacing subexpressions exactly on both sides.

        Examples
        --------
        >>> x = sp.Symbol("x")
        >>> Equation("demo", "", x, 1).xreplace({x: 2}).lhs
        2
        """
        return replace(self, lhs=self.lhs.xreplace(rule), rhs=self.rhs.xreplace(rule))


def normal_momentum(first: Body, first_after: Body, second: Body,
                    second_after: Body) -> Equation:
    """Linear momentum of the pair along the normal is conserved: eqs. (1) and (12).

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(3, (0, 0), "b")
    >>> normal_momentum(a, a.with_motion((0, 0), 0), b, b.with_motion((1, 0), 0)).residual
    -1
    """
    return Equation(
        "linear momentum along the normal",
        "",
        first.momentum[0] + second.momentum[0],
        first_after.momentum[0] + second_after.momentum[0],
        "normal momentum",
    )


def tangential_momentum(before: Body, after: Body) -> Equation:
    """A smooth contact gives no tangential impulse: each body keeps V_y, eq. (13)."""
    return Equation(f"tangential momentum of {before.name} is unchanged", "",
                    before.velocity[1], after.velocity[1], "tangential momentum")


def pair_tangential_momentum(first: Body, first_after: Body, second: Body,
                             second_after: Body) -> Equation:
    """With sticking the tangential impulses cancel in pairs: the pair keeps its P_y.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 0), "b")
    >>> pair_tangential_momentum(a, a, b, b).residual
    0
    """
    return Equation(
        "tangential momentum of the pair",
        "",
        first.momentum[1] + second.momentum[1],
        first_after.momentum[1] + second_after.momentum[1],
        "pair tangential momentum",
    )


def angular_momentum(before: Body, after: Body) -> Equation:
    """The impulse acts at O, so each body's angular momentum about O is kept: (2), (14).

    Spin part ``I omega`` plus orbital part ``m R x V``, before and after.

    Examples
    --------
    >>> b = Body.rigid(1, 1, (0, 1), velocity=(1, 0))
    >>> angular_momentum(b, b.with_motion((0, 0), sp.Symbol("w"))).as_sympy()
    Eq(-1, w)
    """
    return Equation(f"angular momentum of {before.name} about O", "",
                    before.angular_momentum, after.angular_momentum, "angular momentum")


def angular_momentum_about_pivot(before: tuple[Body, Body], after: tuple[Body, Body],
                                 hinged: Body) -> Equation:
    """With one body on a fixed hinge, the pair's angular momentum about the hinge is kept.

    The hinge's reaction impulse acts at the hinge, so it has no moment about it; the
    contact impulses are internal to the pair. Each body counts ``I omega`` plus
    ``m (R - q) x V`` about the hinge q. (The pair's linear momentum is *not* kept: the
    reaction changes it.)

    Examples
    --------
    >>> ball = Body.particle(1, (1, 0), "ball")
    >>> rod = Body.rod(3, 2, sp.pi / 2, 0, pivot=(0, -1), name="rod")
    >>> w, u = sp.symbols("w u")
    >>> angular_momentum_about_pivot((ball, rod), (ball.with_motion((u, 0), 0),
    ...                              rod.with_motion((-w, 0), w)), rod).as_sympy()
    Eq(-1, -u + 4*w)
    """
    q = hinged.pivot

    def about_pivot(body: Body) -> sp.Expr:
        if body.support == "fixed":
            return sp.Integer(0)
        return body.inertia * body.spin + body.mass * cross(body.position - q, body.velocity)

    return Equation(f"angular momentum of the pair about {hinged.name}'s pivot", "",
                    sum((about_pivot(b) for b in before), sp.Integer(0)),
                    sum((about_pivot(b) for b in after), sp.Integer(0)),
                    "angular momentum about the pivot")


def restitution(first: Body, first_after: Body, second: Body, second_after: Body,
                e: sp.Expr) -> Equation:
    """Newton's kinematic restitution at O along the normal: eqs. (3) and (4).

    ``v_2fx - v_1fx = -e (v_2ix - v_1ix)`` with the contact velocities of eq. (11).

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(1, (0, 0), "b")
    >>> restitution(a, a, b, b, 1).as_sympy()
    Eq(-2, 2)
    """
    return Equation(
        "restitution along the normal",
        "",
        second_after.contact_velocity[0] - first_after.contact_velocity[0],
        -e * (second.contact_velocity[0] - first.contact_velocity[0]),
        "restitution",
    )


def no_slip(first_after: Body, second_after: Body) -> Equation:
    """Sticking: the contact points leave O with the same tangential velocity.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 3), "b")
    >>> no_slip(a, b).residual
    2
    """
    return Equation(
        "sticking: no tangential slip at O afterwards",
        "",
        second_after.contact_velocity[1] - first_after.contact_velocity[1],
        sp.Integer(0),
        "no slip",
    )


def impulse_momentum(before: Body, after: Body, impulse: sp.MatrixBase) -> Equation:
    """A supported body's turn changes by the moment of the impulse it receives at O.

    About a pivot q the reaction has no moment, so ``I_q (omega_f - omega_i) = (O - q) x
    P``; this is the law printed when no conservation law holds (both bodies supported),
    with the contact impulse P among the unknowns.

    Examples
    --------
    >>> rod = Body.rod(3, 2, sp.pi / 2, -1, pivot=(0, -2), name="rod")
    >>> w, P = sp.symbols("w P")
    >>> impulse_momentum(rod, rod.with_motion((-w, 0), w), sp.Matrix([P, 0])).as_sympy()
    Eq(4*w, -2*P)
    """
    return Equation(f"angular impulse on {before.name} about its pivot", "",
                    before.inertia_about_pivot * (after.spin - before.spin),
                    cross(-before.pivot, impulse), "angular impulse about the pivot")


# ---- contact laws: each gives the equations a derivation prints and the conditions the
# solver imposes on the impulse P = (P_n, P_t), built from those same equations

@dataclass(frozen=True)
class ContactImpulse:
    """One contact's impact on its own, in its frame (normal, then one tangent in the
    plane or two in space): what every tangential law gives every path.

    impulse : the impulse on the second body, contact frame (a Piecewise over the
        courses where symbols leave several possible).
    course : its name (the law's, or the courses' with their conditions).
    notes : what an integrated answer says of itself (its tolerance, its steps).
    exact : whether it is a closed form (else integrated, to `tolerance`).
    """

    impulse: sp.Matrix
    course: str
    notes: tuple[str, ...] = ()
    exact: bool = True
    tolerance: float | None = None

    @classmethod
    def of_regimes(cls, regimes: Sequence[Any]) -> ContactImpulse:
        """The course taken; with symbols, a Piecewise over the courses, each under its
        conditions (the last where none of the others holds)."""
        if len(regimes) == 1:
            (r,) = regimes
            return cls(sp.Matrix([sp.sympify(x) for x in r.impulse]), r.name)
        size = len(regimes[0].impulse)
        impulse = sp.Matrix([sp.Piecewise(*((sp.sympify(r.impulse[i]), sp.And(*r.conditions))
                                            for r in regimes[:-1]),
                                          (sp.sympify(regimes[-1].impulse[i]), True))
                             for i in range(size)])
        course = Given("")
        for r in regimes[:-1]:
            course += Given(f"{r.name} where {{}}; otherwise ", sp.And(*r.conditions))
        return cls(impulse, course + regimes[-1].name)


class ContactLaw:
    """A law acting at the contact: one face, in contact space, that every path solves
    with (the two-body derivation, the rules, space, a mechanics system), and its
    printed form.

    A tangential law states its impulse in the contact's frame, with one tangent (the
    plane) or two (space): as conditions linear in the velocities after and the
    impulse (:meth:`linear_conditions`), or as the courses of a bent impulse path
    (:meth:`regimes`, Routh's method). :meth:`impulse` is what every path asks of it.
    ``equations(before, after)`` print the law over the unknown motion after; by
    default they are read from :meth:`linear_conditions` itself. A new law is one
    subclass here and its entry in :data:`RESTITUTION_LAWS` or :data:`TANGENTIAL_LAWS`.
    A restitution law has one face in contact space too: the normal velocity it asks
    after a straight impulse path (:meth:`NewtonRestitution.leaving`, from which its
    printed equation is built), the end of a bent path in closed form
    (``end_of_bent_path``, Routh's method) and in floating point (``end_event``, the
    3-D integrators, one implementation a law in :mod:`rigidimpact.laws.ends`), and
    the check of that end from the path alone (``end_residual``). A kinematic law
    (Newton's kind) overrides :meth:`~NewtonRestitution.leaving` alone.
    """

    name = ""
    solved_by_regimes = False  # True: the impulse comes from `regimes`, not linear conditions
    # the states the law allows a contact at the velocity level, where several contacts
    # act together (the simultaneous rule): "on" (pushing, no tangential impulse),
    # "stick" (no slip after), "slide+"/"slide-" (on the friction cone's edge); empty:
    # the law has no velocity-level form and acts only as one contact's own impact
    velocity_states: ClassVar[tuple[str, ...]] = ()
    grips: ClassVar[bool] = True  # False: the law never gives a tangential impulse
    # True: the law's printed condition is on the velocities after (no slip), so where
    # no momentum law holds its tangential impulse is an unknown of its own
    unknown_tangential: ClassVar[bool] = False
    # the contact's coefficients the law takes, each with whether it must be given
    coefficients: ClassVar[dict[str, bool]] = {}
    # why the law takes Newton's restitution only (empty: it takes every law)
    newtons_only: ClassVar[str] = ""
    # the law as a word in messages ("Newton's restitution with a sticking contact");
    # empty: its name. Not inherited: a new law is not called by its parent's word
    called: ClassVar[str] = ""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "called" not in cls.__dict__:
            cls.called = ""

    def energy_warning(self, restitution: NewtonRestitution) -> str | None:
        """What this law, with `restitution`, cannot honour in general (kinetic energy
        created for some data), said before any numbers; None when nothing.

        Examples
        --------
        >>> Coulomb(1).energy_warning(NewtonRestitution(1))[:40]
        "Newton's restitution with Coulomb fricti"
        >>> Coulomb(1).energy_warning(PoissonRestitution(1)) is None
        True
        """
        return None

    def cone(self) -> Any:
        """The friction coefficient bounding a sticking contact (None: no bound)."""
        return None

    def words(self, spatial: bool = False) -> Given:
        """The law in words with its coefficients, as a scene's givens print it (in
        space, with its cone named); a law added to the registry is named by its name."""
        return Given(self.name)

    def walton(self) -> tuple[Any, Any] | None:
        """The law as Walton's: (beta, mu), the slip after being -beta times the slip
        before unless that needs more than the cone mu allows (mu None: no cone); None
        where the law is not of that form (a ball's bounces on a flat sum them)."""
        return None

    def coulomb(self) -> Any:
        """Coulomb's coefficient where the law is Coulomb's friction alone (a ball
        sliding on a plane, the tangentially compliant bounce), else None."""
        return None

    @classmethod
    def from_contact(cls, contact: Any) -> ContactLaw:
        """The law with the coefficients it takes from a contact (none by default)."""
        return cls()

    def equations(self, before: tuple[Body, Body],
                  after: tuple[Body, Body]) -> tuple[Equation, ...]:
        """The law printed over the motion after: each of its tangential conditions
        (:meth:`linear_conditions`, after the restitution law's row) that the touching
        points' velocities state alone, at O in the contact's frame. A law whose
        conditions hold the impulse itself (smooth: no tangential impulse) prints its
        own form.

        Examples
        --------
        >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 3), "b")
        >>> [eq.residual for eq in ContactLaw.equations(Stick(), (a, b), (a, b))]
        [2]
        """
        def relative(pair: tuple[Body, Body]) -> sp.Matrix:
            return sp.Matrix(pair[1].contact_velocity) - sp.Matrix(pair[0].contact_velocity)

        impulse = sp.Matrix([sp.Dummy("P_n"), sp.Dummy("P_t")])
        v_after = relative(after)
        rows = self.linear_conditions(relative(before), v_after, impulse, v_after[0])[1:]
        return tuple(Equation(f"{self.name}: tangential law at O", "", row, sp.Integer(0),
                              self.name) for row in rows if not row.has(*impulse))

    def regimes(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution) -> tuple:
        """The courses of the impact, for a law that is not a linear condition."""
        raise NotImplementedError(f"{type(self).__name__} is imposed as linear conditions")

    def impulse(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution, tolerance: float | None = None
                ) -> ContactImpulse:
        """This contact's impact on its own, in its frame with one tangent (the plane)
        or two (space): the one face of a tangential law that every path asks, in 2-D
        and 3-D alike. With regimes and symbols, a Piecewise over the courses.

        Examples
        --------
        A particle of mass 1 sliding onto a smooth floor at (-1, 2, 3): the tangents
        keep their velocities and the normal one reverses (e = 1).

        >>> Smooth().impulse(sp.eye(3), sp.Matrix([-1, 2, 3]), NewtonRestitution(1)).impulse.T
        Matrix([[2, 0, 0]])
        """
        if self.solved_by_regimes:
            return ContactImpulse.of_regimes(self.regimes(W, v_before, restitution))
        return ContactImpulse(self._linear(W, v_before, restitution), self.name)

    def linear_conditions(self, v_before: sp.MatrixBase, v_after: sp.MatrixBase,
                          impulse: sp.MatrixBase, leaving: sp.Expr) -> list[sp.Expr]:
        """The residuals, linear in the velocities after and the impulse (contact
        space, one tangent or two), that a law imposed as linear conditions asks to
        vanish: the normal velocity after the restitution law asks (`leaving`, its
        :meth:`NewtonRestitution.leaving` of ``v_before[0]``) and the tangential
        conditions. Any solver of W P = v+ - v- may impose them. A law that states
        neither these nor :meth:`regimes` has no face to solve with: it is refused in
        one line on every path, never taken for another law."""
        raise InputError(f"{self.name or type(self).__name__}.tangential",
                         "this law states no contact-space face (linear_conditions, or "
                         "regimes), which every path solves with; printed equations "
                         "alone do not fix an impulse")

    def _linear(self, W, v_before, restitution) -> sp.Matrix:
        P = sp.Matrix(sp.symbols(f"p0:{len(v_before)}"))
        after = sp.Matrix(v_before) + sp.Matrix(W) * P
        matrix, rhs = sp.linear_eq_to_matrix(
            self.linear_conditions(v_before, after, P, restitution.leaving(v_before[0])),
            list(P))
        if routh.singular(matrix):
            raise InputError("tangential", "the touching points have one degree of "
                             "freedom here (a body that can only turn, against a fixed "
                             "one), so they cannot both stop slipping and leave by the "
                             "restitution law; tangential = \"coulomb\" follows them "
                             "(Routh's method)" if self.grips else "the contact laws do "
                             "not fix the impulse here")
        return matrix.LUsolve(rhs)

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


@dataclass(frozen=True, repr=False)
class NewtonRestitution(ContactLaw):
    """Newton's kinematic law: the normal closing speed reverses, scaled by e.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(1, (0, 0), "b")
    >>> NewtonRestitution(1).equations((a, b), (a, b))[0].as_sympy()
    Eq(-2, 2)
    """

    e: sp.Expr
    name = "newton"
    called = "Newton's"
    splits_on_compression = False  # on a bent impulse path: the end is set by velocity
    # on a bent impulse path (friction): never creates kinetic energy (Poisson's and the
    # energetic law); Newton's kinematic law can (Kane and Levinson's paradox)
    dissipative_on_bent_path: ClassVar[bool] = False
    # contacts acting together (the simultaneous rule): "velocity" (each acting contact
    # leaves at -e times its closing velocity), "impulse" (the compression impulses
    # solved with target zero, each scaled by 1 + e), None (no such form)
    together: ClassVar[str | None] = "velocity"

    def newtons_e(self) -> Any:
        """Newton's kinematic coefficient, where this is Newton's law (a simulator whose
        model is built on it asks), else None: a law that asks another target
        (:meth:`leaving`) is not Newton's, whatever its class."""
        return self.e if type(self).leaving is NewtonRestitution.leaving else None

    def words(self, spatial: bool = False) -> Given:
        # from the law's own word (not inherited: a new law is named by its name)
        return Given(f"{self.called} restitution" if self.called
                     else f"the {self.name} restitution law,")

    def equations(self, before, after):
        """The printed restitution equation of one contact, from :meth:`leaving` (the
        law's one face): the normal velocity after equals what the law asks of the
        closing velocity before."""
        (equation,) = (restitution(before[0], after[0], before[1], after[1], self.e),)
        closing = before[1].contact_velocity[0] - before[0].contact_velocity[0]
        return (replace(equation, rhs=self.leaving(closing)),)

    def leaving(self, closing: sp.Expr) -> sp.Expr:
        """The normal velocity after (second minus first) this law asks of a contact
        closing at `closing` (negative) on a straight impulse path: ``-e closing``.
        Every path asks this, in the plane and in space: the one-contact core's printed
        equation (:meth:`equations`), the rules for several contacts, the linear solves,
        and (as the end of a bent path, :meth:`end_event`) the path integrators; a new
        kinematic law overrides it alone."""
        return -self.e * closing

    def end_event(self, closing: float) -> ends.End:
        """The end of an impact followed along its path in floating point (the 3-D
        cone, contacts driven together): a function of ``(p, v_n, p_c, work_c, work)``
        (the normal impulse, the normal velocity, the impulse and the normal work at the
        end of compression, None before it, and the normal work so far) that crosses
        zero upward where the impact ends. Newton's: the normal velocity reaches
        :meth:`leaving`'s.

        Examples
        --------
        >>> end = NewtonRestitution(sp.Rational(1, 2)).end_event(-2.0)
        >>> end(1.0, 0.5, 1.0, -1.0, -0.5), end(1.5, 1.0, 1.0, -1.0, -0.25)
        (-0.5, 0.0)
        """
        return ends.kinematic(float(self.leaving(sp.Float(closing, 30))))

    def from_compression(self, compression: sp.Expr) -> sp.Expr:
        """The whole normal impulse from the impulse of compression, for a law whose
        contacts act together by impulse (``together = "impulse"``)."""
        raise NotImplementedError(f"{type(self).__name__} acts together by velocity")

    def compression(self, total: sp.Expr) -> sp.Expr:
        """The impulse of compression within a whole normal impulse (the inverse of
        :meth:`from_compression`)."""
        raise NotImplementedError(f"{type(self).__name__} acts together by velocity")

    def end_of_bent_path(self, first, second, v_n: sp.Expr,
                         stop_in_restitution: bool) -> sp.Expr:
        """The normal impulse at the end of an impact whose slip stopped at
        ``second.start`` (Routh's method, :mod:`rigidimpact.laws.routh`)."""
        return routh.newton_end(first, second, v_n, self.leaving(v_n))

    def end_residual(self, path: Sequence[tuple[Any, Any]], num: Callable[[Any], Any],
                     back: Callable[[Any], sp.Expr]) -> Any:
        """How far an impact's end is from this law's, from its path alone (the
        certificate's check, :mod:`rigidimpact.solve.certificate`).

        `path` gives the normal impulse and the normal velocity at each corner of the
        impulse path, ``((0, v-), ..., (P_n, v+))``, straight between corners, in the
        caller's arithmetic; `num` puts a SymPy number into it and `back` takes one out.
        Newton's kinematic law: the velocity after against :meth:`leaving`'s, whatever
        the path (so a law that overrides only :meth:`leaving` is checked by it).

        Examples
        --------
        >>> law = NewtonRestitution(sp.Rational(1, 2))
        >>> law.end_residual(((0, -2), (3, 1)), sp.sympify, sp.sympify)
        0
        """
        closing = min(path[0][1], num(0))
        return abs(path[-1][1] - num(self.leaving(back(closing))))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.e})"


def compression_end(path: Sequence[tuple[Any, Any]]) -> Any:
    """The normal impulse at which the normal velocity reaches zero along a path of
    corners ``(p_n, v_n)``, straight between them (the whole impulse if it never does).

    Examples
    --------
    >>> compression_end(sp.sympify(((0, -2), (1, -1), (3, 1))))
    2
    """
    for (p0, v0), (p1, v1) in zip(path, path[1:], strict=False):
        if v1 >= 0 > v0:
            return p0 + (p1 - p0) * (-v0) / (v1 - v0)
        if v0 >= 0:
            return p0
    return path[-1][0]


def works(path: Sequence[tuple[Any, Any]]) -> tuple[Any, Any]:
    """The normal impulse's work in compression (negative) and in restitution along a
    path of corners ``(p_n, v_n)``, straight between them: the areas under v_n on either
    side of :func:`compression_end`.

    Examples
    --------
    >>> works(sp.sympify(((0, -2), (2, 0), (3, 2))))
    (-2, 1)
    """
    p_c = compression_end(path)
    compression = restitution = path[0][0] * 0
    for (p0, v0), (p1, v1) in zip(path, path[1:], strict=False):
        if p1 == p0:
            continue
        for a, b, into in ((p0, min(p1, p_c), "c"), (max(p0, p_c), p1, "r")):
            if b <= a:
                continue
            slope = (v1 - v0) / (p1 - p0)
            area = (v0 + slope * (a - p0) + v0 + slope * (b - p0)) * (b - a) / 2
            if into == "c":
                compression += area
            else:
                restitution += area
    return compression, restitution


class Smooth(ContactLaw):
    """No tangential impulse; printed as each free body keeping its tangential momentum
    (the paper's eq. 13), imposed as ``P_t = 0``.

    Examples
    --------
    >>> a = Body.particle(1, (2, 1), "a")
    >>> Smooth().equations((a, Body.fixed()), (a, Body.fixed()))[0].residual
    0
    """

    name = "smooth"
    velocity_states = ("on",)
    grips = False

    def words(self, spatial: bool = False) -> Given:
        return Given("smooth")

    def walton(self) -> tuple[Any, Any] | None:
        return sp.Integer(-1), None  # the slip is kept

    def equations(self, before, after):
        return tuple(tangential_momentum(b, a) for b, a in zip(before, after, strict=True)
                     if b.support == "free")

    def linear_conditions(self, v_before, v_after, impulse, leaving) -> list[sp.Expr]:
        return [v_after[0] - leaving, *impulse[1:]]  # the restitution law; no friction


class Stick(ContactLaw):
    """The touching points leave with the same tangential velocity.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 3), "b")
    >>> Stick().equations((a, b), (a, b))[0].residual
    2
    """

    name = "stick"
    velocity_states = ("stick",)
    unknown_tangential = True
    newtons_only = "a sticking contact is an algebraic law with Newton's e"
    called = "sticking"

    def words(self, spatial: bool = False) -> Given:
        return Given("sticking (no slip after)" if spatial else "sticking")

    def walton(self) -> tuple[Any, Any] | None:
        return sp.Integer(0), None  # no slip after, whatever it takes

    def energy_warning(self, restitution: NewtonRestitution) -> str | None:
        if sp.sympify(restitution.e).is_zero:
            return None
        return ("Newton's restitution with a sticking contact is not energy-consistent: for "
                "e > 0 it creates kinetic energy for some data (check that "
                "energy_loss_fraction >= 0 at your values; evaluate warns when it is not)")

    def equations(self, before, after):
        return (no_slip(after[0], after[1]),)

    def linear_conditions(self, v_before, v_after, impulse, leaving) -> list[sp.Expr]:
        return [v_after[0] - leaving, *v_after[1:]]  # the restitution law across, no slip


@dataclass(frozen=True, repr=False)
class PoissonRestitution(NewtonRestitution):
    """Poisson's kinetic law: the normal impulse of restitution is e times that of
    compression. On a straight impulse path (a smooth contact) it reads as Newton's law,
    and that is what is printed and imposed there; with friction the path bends and the
    law is applied by Routh's method (:mod:`rigidimpact.laws.routh`).

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(1, (0, 0), "b")
    >>> PoissonRestitution(1).equations((a, b), (a, b))[0].label
    "restitution along the normal (Poisson's law on a straight impulse path)"
    """

    name = "poisson"
    called = "Poisson's"
    splits_on_compression = True
    dissipative_on_bent_path = True
    together = "impulse"

    def newtons_e(self) -> Any:
        return None  # a kinetic or energetic law, Newton's only on a straight path

    def end_of_bent_path(self, first, second, v_n: sp.Expr,
                         stop_in_restitution: bool) -> sp.Expr:
        return routh.poisson_end(first, second, v_n, self.e, stop_in_restitution)

    def end_event(self, closing: float) -> ends.End:
        """The normal impulse reaches ``(1 + e)`` times its compression impulse (see
        :meth:`NewtonRestitution.end_event`)."""
        return ends.poisson(float(self.e))

    def end_residual(self, path: Sequence[tuple[Any, Any]], num: Callable[[Any], Any],
                     back: Callable[[Any], sp.Expr]) -> Any:
        """The whole normal impulse against ``(1 + e)`` times the impulse at which the
        normal velocity reached zero along the path (see
        :meth:`NewtonRestitution.end_residual`).

        Examples
        --------
        >>> law = PoissonRestitution(sp.Rational(1, 2))
        >>> law.end_residual(((0, -2), (2, 0), (3, 2)), sp.sympify, sp.sympify)
        0
        """
        return abs(path[-1][0] - (1 + num(self.e)) * compression_end(path))

    def from_compression(self, compression: sp.Expr) -> sp.Expr:
        """The whole normal impulse from the impulse of compression: ``(1 + e) P_c``.
        Contacts acting together under this law (``together = "impulse"``) solve for
        their compression impulses, then each takes this.

        Examples
        --------
        >>> PoissonRestitution(sp.Rational(1, 2)).from_compression(2)
        3
        """
        return (1 + self.e) * compression

    def compression(self, total: sp.Expr) -> sp.Expr:
        """The impulse of compression within a whole normal impulse (the inverse of
        :meth:`from_compression`).

        Examples
        --------
        >>> PoissonRestitution(sp.Rational(1, 2)).compression(3)
        2
        """
        return total / (1 + self.e)

    def equations(self, before, after):
        (equation,) = super().equations(before, after)
        return (replace(equation, label=f"{equation.label} (Poisson's law on a straight "
                                        "impulse path)"),)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.e})"


@dataclass(frozen=True, repr=False)
class EnergeticRestitution(NewtonRestitution):
    """Stronge's energetic law: the work of the normal impulse in restitution is e^2
    times minus its work in compression; on a straight impulse path it reads as Newton's.

    Examples
    --------
    >>> EnergeticRestitution(1)
    EnergeticRestitution(1)
    """

    name = "energetic"
    called = "the energetic"
    splits_on_compression = True
    dissipative_on_bent_path = True
    together = None  # the work split of one contact: no form for contacts acting together

    def newtons_e(self) -> Any:
        return None  # a kinetic or energetic law, Newton's only on a straight path

    def words(self, spatial: bool = False) -> Given:
        return Given("the energetic restitution law,")

    def end_of_bent_path(self, first, second, v_n: sp.Expr,
                         stop_in_restitution: bool) -> sp.Expr:
        return routh.energetic_end(first, second, v_n, self.e, stop_in_restitution)

    def end_event(self, closing: float) -> ends.End:
        """The normal work in restitution reaches ``-e^2`` times the work in
        compression (see :meth:`NewtonRestitution.end_event`)."""
        return ends.energetic(float(self.e))

    def end_residual(self, path: Sequence[tuple[Any, Any]], num: Callable[[Any], Any],
                     back: Callable[[Any], sp.Expr]) -> Any:
        """The normal impulse's work in restitution against ``-e^2`` times its work in
        compression along the path (the area under the normal velocity on either side
        of its zero), over the closing speed so that it reads as an impulse (see
        :meth:`NewtonRestitution.end_residual`).

        Examples
        --------
        >>> law = EnergeticRestitution(sp.Rational(1, 2))
        >>> law.end_residual(((0, -2), (2, 0), (3, 1)), sp.sympify, sp.sympify)
        0
        """
        compression, restitution = works(path)
        e = num(self.e)
        return abs(restitution + e * e * compression) / abs(min(path[0][1], num(0)))

    def equations(self, before, after):
        (equation,) = super().equations(before, after)
        return (replace(equation, label=f"{equation.label} (the energetic law on a straight "
                                        "impulse path)"),)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.e})"


@dataclass(frozen=True, repr=False)
class Coulomb(ContactLaw):
    """Coulomb friction, |P_t| <= mu P_n, opposing slip: not a linear condition, so the
    impulse comes from Routh's method (:meth:`regimes`) and each course of the impact is
    printed as a regime with its conditions (:mod:`rigidimpact.laws.routh`).

    Examples
    --------
    >>> Coulomb(sp.Rational(1, 4)).equations((), ())
    ()
    >>> W = sp.Matrix([[2, 0], [0, 2]])   # a particle of mass 1/2 on a fixed floor
    >>> [r.name for r in Coulomb(sp.Rational(1, 4)).regimes(W, sp.Matrix([-1, 1]),
    ...                                                     NewtonRestitution(1))]
    ['slip']
    """

    mu: Any = None
    name = "coulomb"
    coefficients: ClassVar[dict[str, bool]] = {"friction": True}
    called = "Coulomb-friction"

    def energy_warning(self, restitution: NewtonRestitution) -> str | None:
        if restitution.dissipative_on_bent_path or sp.sympify(restitution.e).is_zero:
            return None
        return ("Newton's restitution with Coulomb friction is not energy-consistent: when "
                "slip stops or reverses during the impact it can create kinetic energy (the "
                "Kane-Levinson paradox; Poisson's and the energetic law do not); evaluate "
                "warns where it does")
    solved_by_regimes = True
    velocity_states: ClassVar[tuple[str, ...]] = ("stick", "slide+", "slide-")

    def cone(self) -> Any:
        return self.mu

    def words(self, spatial: bool = False) -> Given:
        return Given("Coulomb friction, circular cone, mu = {}" if spatial
                     else "Coulomb friction {}", self.mu)

    def walton(self) -> tuple[Any, Any] | None:
        return sp.Integer(0), self.mu  # sticks where the cone holds it

    def coulomb(self) -> Any:
        return self.mu

    @classmethod
    def from_contact(cls, contact: Any) -> Coulomb:
        return cls(contact.friction)

    def equations(self, before, after):
        return ()

    def regimes(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution) -> tuple:
        """Every course the impact can take under this friction and `restitution`
        (Routh's method), each with its conditions; with numbers, the one taken."""
        return routh.regimes(W, v_before, self.mu, restitution)

    def impulse(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution, tolerance: float | None = None
                ) -> ContactImpulse:
        """One tangent: Routh's courses. Two: where the slip keeps to one line through
        the impact, Routh's courses on that line (the same law); else the circular cone
        followed in the normal impulse (:func:`rigidimpact.laws.cone.cone_impact`: a
        closed form where the slip cannot turn, integrated where it can)."""
        if len(v_before) == 2:
            return super().impulse(W, v_before, restitution)
        W, v = sp.Matrix(W), sp.Matrix(list(v_before))
        if tolerance is None and (line := cone.one_line(W, v)) is not None:
            W_line = sp.Matrix([[W[0, 0], line.dot(W[1:, 0])],
                                [line.dot(W[1:, 0]), line.dot(W[1:, 1:] * line)]])
            flat = super().impulse(W_line, sp.Matrix([v[0], line.dot(v[1:, 0])]),
                                   restitution)
            p_n, p_t = flat.impulse
            return ContactImpulse(sp.Matrix([p_n, p_t * line[0], p_t * line[1]]),
                                  flat.course)
        out = cone.cone_impact(W, v, restitution, self.mu, tolerance)
        notes = () if out.exact else (
            f"the contact's path is integrated in the normal impulse to a relative "
            f"tolerance of {out.tolerance:g} ({out.steps} steps; the slip direction "
            f"turned by {out.turned * 180 / 3.141592653589793:.4g} degrees); course: "
            f"{out.course}",)
        return ContactImpulse(out.impulse, out.course, notes, out.exact, out.tolerance)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.mu})"


@dataclass(frozen=True, repr=False)
class Rough(Coulomb):
    """Walton's law: the tangential velocity of the touching points reverses, scaled by
    beta, unless that needs more than Coulomb's friction (mu, or none) allows.

    Examples
    --------
    >>> W = sp.Matrix([[1, 0], [0, sp.Rational(7, 2)]])  # a solid sphere of mass 1
    >>> [r.impulse for r in Rough(None, 1).regimes(W, sp.Matrix([-1, 1]),
    ...                                            NewtonRestitution(1))]
    [(2, -4/7)]
    """

    beta: Any = None
    name = "rough"
    coefficients: ClassVar[dict[str, bool]] = {"friction": False,
                                                "tangential_restitution": True}
    # Walton's law sets the velocities after with Newton's e; under another law its e
    # would be read as Newton's without a word (the plane did so once)
    newtons_only = "Walton's rough law takes Newton's restitution"
    called = "rough"
    # Walton's tangential restitution has no velocity-level form
    velocity_states: ClassVar[tuple[str, ...]] = ()

    @classmethod
    def from_contact(cls, contact: Any) -> Rough:
        return cls(contact.friction, contact.tangential_restitution)

    def words(self, spatial: bool = False) -> Given:
        if spatial:
            return Given("Walton's rough law, beta = {}", self.beta) + (
                Given(", without a friction limit") if self.mu is None
                else Given(", mu = {}", self.mu))
        friction = Given("without a friction limit") if self.mu is None \
            else Given("friction {}", self.mu)
        return Given("rough (Walton), ") + friction + Given(
            ", tangential restitution {}", self.beta)

    def walton(self) -> tuple[Any, Any] | None:
        return None if self.beta is None else (sp.sympify(self.beta), self.mu)

    def coulomb(self) -> Any:
        return None  # Walton's law, not Coulomb's alone

    def energy_warning(self, restitution: NewtonRestitution) -> str | None:
        return None  # Walton's law sets the velocities after: said at numbers, if at all

    def regimes(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution) -> tuple:
        return walton(W, v_before, self.beta, self.mu, restitution.leaving(v_before[0]))

    def impulse(self, W: sp.MatrixBase, v_before: sp.MatrixBase,
                restitution: NewtonRestitution, tolerance: float | None = None
                ) -> ContactImpulse:
        """Walton's courses (:mod:`rigidimpact.laws.walton`), one tangent or two; a 3-D
        answer names slipping throughout as the cone does ("slides throughout")."""
        regimes = self.regimes(W, v_before, restitution)
        if len(v_before) == 3:
            regimes = tuple(replace(r, name="slides throughout") if r.name == routh.SLIP
                            else r for r in regimes)
        return ContactImpulse.of_regimes(regimes)

    def __repr__(self) -> str:
        return f"Rough({self.mu}, {self.beta})"


RESTITUTION_LAWS: dict[str, type[NewtonRestitution]] = {
    "newton": NewtonRestitution, "poisson": PoissonRestitution,
    "energetic": EnergeticRestitution}
TANGENTIAL_LAWS: dict[str, type[ContactLaw]] = {
    "smooth": Smooth, "stick": Stick, "coulomb": Coulomb, "rough": Rough}
