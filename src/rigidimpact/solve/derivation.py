"""A solved problem, ready to print, export, evaluate or verify: :class:`Derivation`.

Every way of stating an impact (the paper's problems, a scene file, several contacts)
ends in one :class:`Derivation`: the givens in words, the labelled equations solved, the
unknowns, the exact results, and, for numbers, :meth:`Derivation.evaluate` (float64 or
mpmath) with the warnings a law's physics calls for.

Examples
--------
>>> from rigidimpact.paper.problems import derive
>>> derive("sticking").results["h"]
L*m/(2*M + m)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.roles import Role, check_assumptions, check_roles, roles_of
from rigidimpact.solve.collision import Collision
from rigidimpact.solve.impact import NUMERIC_DIGITS, Impact
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.expr import parse_expression
from rigidimpact.symbolic.notation import aligned, result_lhs, to_latex
from rigidimpact.symbolic.numeric import evaluate

__all__ = [
    "Derivation",
    "Evaluation",
    "physics_warnings",
    "model_warnings",
    "read_values",
    "model_name",
]


# a frictional impact is solved at its numbers; with transcendental data that is done
# with 50-digit floats (see Impact.numeric), enough for --dps up to this many digits
_FRICTION_DIGITS = NUMERIC_DIGITS - 5


@dataclass(frozen=True)
class Derivation:
    """A solved problem, ready to print, export or verify.

    Parameters
    ----------
    problem : str
        Built-in name or scene file name.
    title : str
        One line saying what collides.
    setup : tuple of str
        The givens in words (a :class:`~rigidimpact.symbolic.notation.Given` line holds
        its values, to be typeset).
    equations : tuple of Equation
        The laws, in order, with the paper's numbers.
    unknowns : tuple of Symbol
        What the equations were solved for.
    results : mapping of str to Expr
        Result key -> exact expression over the problem's symbols.
    named : mapping of str to Expr
        Results rewritten with a named group (the paper's ``f``), where one exists.
    definitions : mapping of str to Expr
        The named groups themselves.
    solution : Solution or None
        The underlying solved impact.
    seconds : float
        Wall time the derivation took.
    warnings : tuple of str
        What the model cannot honour in general (see :func:`model_warnings`).
    outcomes : tuple of Solution
        With several contacts: each rule's (or order's) outcome; `results` are the
        first's.
    """

    problem: str
    title: str
    setup: tuple[str, ...]
    equations: tuple[Equation, ...]
    unknowns: tuple[sp.Symbol, ...]
    results: Mapping[str, sp.Expr]
    named: Mapping[str, sp.Expr] = field(default_factory=dict)
    definitions: Mapping[str, sp.Expr] = field(default_factory=dict)
    solution: Solution | None = field(default=None, repr=False)
    seconds: float = field(default=0.0, repr=False, compare=False)  # a timing: not shown
    warnings: tuple[str, ...] = ()
    outcomes: tuple = ()  # several contacts: what each rule (or order) made of them

    def _repr_latex_(self) -> str:
        r"""The laws and the results, typeset in the paper's notation (Jupyter).

        Examples
        --------
        >>> from rigidimpact.paper.problems import derive
        >>> print(derive("discs")._repr_latex_()[:42])
        $$\begin{aligned} V_{1ix} m + V_{2ix} m &=
        """

        rows = [(to_latex(eq.lhs), to_latex(eq.rhs),
                 eq.label + (f" {eq.paper}" if eq.paper else "")) for eq in self.equations]
        rows += [(result_lhs(key), to_latex(value), "") for key, value in self.results.items()]
        return aligned(rows)

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        """The symbols the results use, by name."""
        found = set().union(*(x.free_symbols for x in self.results.values()))
        return {s.name: s for s in sorted(found, key=lambda s: s.name)}

    @property
    def data_symbols(self) -> dict[str, sp.Symbol]:
        """Every symbol of the problem's data (some may not reach any result)."""
        found = set(self.symbols.values())
        for role in self.roles:
            found |= sp.sympify(role.expr).free_symbols
        if self.solution is not None:
            for body in self.solution.before:
                found |= sp.Tuple(*body.position, *body.velocity, body.spin).free_symbols
                found |= sp.Tuple(*(body.pivot if body.pivot is not None else ())).free_symbols
        return {s.name: s for s in sorted(found, key=lambda s: s.name)}

    @property
    def roles(self) -> tuple[Role, ...]:
        """What bounds the data by role (restitution in [0, 1], masses positive, ...)."""
        if self.solution is None:
            return ()
        contacts = self.solution.contacts
        # a contact that names its bodies and point places them; the paper's problems'
        # contact is at O between the two bodies as given
        return roles_of(self.solution.before, contacts,
                        contacts if self.solution.contact.bodies else None)

    def checked(self, values: Mapping[str, Any],
                sources: Mapping[str, str] | None = None) -> dict[str, sp.Expr]:
        """Exact numbers for every symbol of the results, checked by assumption and role.

        This is the one door every number passes (a scene's ``[values]``, ``--set``,
        the Python API): each value is read exactly (``0.1`` is 1/10), must be a number
        the tool supports, must fit its symbol's assumptions, and every role it fills
        must allow it.

        Parameters
        ----------
        values : mapping of name to number (int, float, str or SymPy number)
        sources : mapping of name to str, optional
            Where each value came from, for messages (default ``values.NAME``).

        Raises
        ------
        InputError
            For an unknown or missing name or a value its symbol or role refuses.

        Examples
        --------
        >>> from rigidimpact.paper.problems import derive
        >>> derive("discs").checked({"V_1ix": 1, "V_2ix": 0, "V_1iy": 0, "V_2iy": 0,
        ...                          "e": 1.5})
        Traceback (most recent call last):
        ...
        rigidimpact.errors.InputError: values.e: the restitution coefficient (contact.restitution = e) must lie in [0, 1], got 3/2
        """  # noqa: E501
        sources = dict(sources or {})
        exact = read_values(values, sources, self.data_symbols, self.roles, self.problem)
        missing = sorted(set(self.symbols) - {s.name for s in exact})
        if missing:
            raise InputError("--set", f"{self.problem} needs values for: {', '.join(missing)}")
        if self.solution is not None and self.solution.approach_speed is not None:
            approach = self.solution.approach_speed.xreplace(exact)
            if approach.is_number and approach <= 0:
                raise InputError(", ".join(sources[n] for n in sorted(sources)) or "values",
                                 "with these values the bodies are not approaching at O")
        return {s.name: v for s, v in exact.items() if s.name in self.symbols}

    def evaluate(self, values: Mapping[str, Any], dps: int | None = None,
                 sources: Mapping[str, str] | None = None,
                 exact: bool = False) -> Evaluation:
        """Every result at `values`, checked first (see :meth:`checked`); with `exact`,
        each also as an exact number (:attr:`Evaluation.exact`).

        Returns an :class:`Evaluation`: the numbers, and warnings where the model cannot
        honour the physics at these values (kinetic energy created, a contact that
        would have to pull).

        Examples
        --------
        >>> from rigidimpact.paper.problems import derive
        >>> out = derive("discs").evaluate({"V_1ix": 1, "V_2ix": 0, "V_1iy": 0,
        ...                                 "V_2iy": 0, "e": 1})
        >>> out.numbers["V_2fx"], out.warnings
        (1.0, ())
        """

        given = self.checked(values, sources)
        extra: dict[str, Any] = {}
        at = {self.symbols[k]: v for k, v in given.items()}
        if self.solution is None:
            numbers = evaluate(self.results, given, dps)
            return Evaluation(numbers, physics_warnings(numbers, dps, "the model"),
                              exact=exact_numbers(self.results, at) if exact else None)
        contact = self.solution.contact
        exactly = None
        if contact.by_regimes and (dps is None or dps <= _FRICTION_DIGITS):
            # numbers first, then the case analysis: one course, exact (or 50-digit)
            # arithmetic, and no formula over every course evaluated where most of its
            # branches are undefined (a friction coefficient of 0, say)
            if contact.bodies:  # a scene's: placed from the scene's origin
                solved = Collision.from_values(self.solution.before, (contact,), at).alone()
            else:
                first, second = (b.at(at) for b in self.solution.before)
                solved = Impact(first, second, contact.at(at)).solve()
            numbers = evaluate(solved.results(), {}, dps)
            exactly = exact_numbers(solved.results()) if exact else None
            regime = solved.regime
            if solved.checks:  # each law's residual at these numbers
                extra["checks"] = {k: float(v) for k, v in solved.checks.items()}
        else:
            numbers = evaluate(self.results, given, dps)
            exactly = exact_numbers(self.results, at) if exact else None
            regime = self.solution.regime_at(at)
        model = model_name(contact)
        if regime is not None:
            model += f" (regime {regime}"
            if not contact.laws[0].dissipative_on_bent_path and (
                    "reversal" in regime or "stick" in regime):
                model += ": slip stopped or reversed during the impact, where Newton's " \
                         "kinematic law can create energy (the Kane-Levinson paradox); " \
                         "Poisson's or the energetic law would not"
            model += ")"
        return Evaluation(numbers, physics_warnings(numbers, dps, model), regime, extra,
                          exactly)


@dataclass(frozen=True)
class Evaluation:
    """Numbers for a derivation's results, with what the model could not honour."""

    numbers: Mapping[str, Any]
    warnings: tuple[str, ...] = ()
    regime: str | None = None  # with friction: the course the impact took
    extra: Mapping[str, Any] = field(default_factory=dict)  # several contacts: acted, orders
    exact: Mapping[str, Any] | None = None  # asked for: each result as an exact number


def exact_numbers(results: Mapping[str, Any], at: Mapping[Any, Any] | None = None
                  ) -> dict[str, sp.Expr]:
    """Each result with the exact numbers `at` put in, its roots tidied (a result solved
    in floating point stays the float it is)."""
    out = {}
    for key, value in results.items():
        x = sp.sympify(value)
        x = x.xreplace(dict(at)) if at else x
        out[key] = x if x.has(sp.Float) else sp.radsimp(sp.together(x))
    return out


def read_values(values: Mapping[str, Any], sources: dict[str, str],
                by_name: Mapping[str, sp.Symbol], roles: tuple[Role, ...],
                problem: str) -> dict[sp.Symbol, sp.Expr]:
    """Exact numbers for named symbols, each checked by its assumptions and every role it
    fills; `sources` says where each came from (filled with ``values.NAME`` if absent).

    Examples
    --------
    >>> from rigidimpact.symbolic.notation import symbol
    >>> e = symbol("e")
    >>> read_values({"e": "0.5"}, {}, {"e": e}, (), "demo")
    {e: 1/2}
    >>> read_values({sp.Symbol("e"): 1}, {}, {"e": e}, (), "demo")  # a symbol: its name
    {e: 1}
    >>> read_values({"k": 1}, {}, {"e": e}, (), "demo")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: values.k: not a symbol of demo; it uses e
    """

    exact = {}
    for key, raw in values.items():
        name = key.name if isinstance(key, sp.Symbol) else key  # a scene's values, as read
        where = sources.setdefault(name, f"values.{name}")
        if name not in by_name:
            raise InputError(where, f"not a symbol of {problem}; it uses "
                             f"{', '.join(by_name) or 'none'}")
        value = raw if isinstance(raw, sp.Basic) else parse_expression(raw, where)
        if not value.is_number or value.free_symbols:
            raise InputError(where, f"must be a number, got {value}")
        exact[by_name[name]] = check_assumptions(by_name[name], sp.sympify(value), where)
    check_roles(roles, exact, {by_name[n]: w for n, w in sources.items() if n in by_name})
    return exact


def model_name(contact: Contact) -> str:
    """The contact's laws in words, for messages.

    Examples
    --------
    >>> model_name(Contact(tangential="stick"))
    "Newton's restitution with a sticking contact"
    """
    restitution, tangential = contact.laws  # each law's own word (a new law: its name)
    return (f"{restitution.called or 'the ' + restitution.name} restitution with a "
            f"{tangential.called or tangential.name} contact")


def model_warnings(contact: Contact) -> tuple[str, ...]:
    """What a contact's laws cannot honour for some data, said once at derivation time.

    Newton's kinematic restitution fixes the normal velocity after; with a sticking
    contact the tangential impulse that enforces no slip also changes the normal one, and
    for e > 0 the pair can leave with more kinetic energy than it had (when the contact
    point also slides before, and the bodies couple the two directions).

    Examples
    --------
    >>> model_warnings(Contact(restitution=sp.Rational(1, 2), tangential="stick"))[0][:52]
    "Newton's restitution with a sticking contact is not "
    >>> model_warnings(Contact(restitution=0, tangential="stick"))
    ()
    """
    restitution, tangential = contact.laws
    warning = tangential.energy_warning(restitution)
    return () if warning is None else (warning,)


def physics_warnings(numbers: Mapping[str, Any], dps: int | None = None,
                     model: str = "the model",
                     energy_tolerance: float | None = None) -> tuple[str, ...]:
    """Where numbers break what an impact must obey, in words (empty when nothing does).

    An impact may not create kinetic energy, and a contact can only push: a negative
    energy loss or a negative normal impulse beyond rounding means the model (Newton's
    restitution with a sticking contact, for instance) cannot honour the physics here.

    Examples
    --------
    >>> physics_warnings({"energy_loss_fraction": -0.25, "impulse": 1.0})
    ('kinetic energy is created: the energy lost is -0.25 of the energy before; the model cannot honour the physics at these values',)
    """  # noqa: E501
    tolerance = 1e-12 if dps is None else 10.0 ** (3 - dps)
    found = []
    loss = numbers.get("energy_loss_fraction")
    beyond = "" if energy_tolerance is None else \
        f" (beyond the integration's tolerance, {energy_tolerance:.0e})"
    if loss is not None and loss < -max(tolerance, energy_tolerance or 0.0):
        found.append(f"kinetic energy is created{beyond}: the energy lost is "
                     f"{float(loss):.6g} of the energy before; {model} cannot honour the "
                     "physics at these values")
    # a scene's results carry the normal impulse twice (impulse, contact.normal_impulse)
    keys = [k for k in numbers if k.endswith("normal_impulse")] or \
        [k for k in numbers if k == "impulse"]
    for key in keys:
        if numbers[key] < -tolerance:
            found.append(f"{key} is {float(numbers[key]):.6g} < 0: the contact would have "
                         f"to pull; {model} cannot honour the physics at these values")
    return tuple(found)
