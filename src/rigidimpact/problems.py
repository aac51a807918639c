"""The paper's problems built from primitives and solved: each gives a :class:`Derivation`.

Built-in names: ``barbell`` (section 1), ``sticking`` (the clay ball of
figure 2), ``discs`` (equal smooth discs, eq. 16) and ``two-body`` (the general smooth
planar impact of section 3). Nothing here is typed in from the paper's results: every
result is solved from the laws; :mod:`rigidimpact.paper` holds what it is checked against.

Examples
--------
>>> d = derive("barbell")
>>> d.results["V_x"]
m*v_ix*(e + 1)/(2*M + m*sin(theta)**2 + m)
>>> d.named["v_fx"]
v_ix*(-2*M*f + m)/m
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from rigidimpact import laws
from rigidimpact.bodies import Body, join
from rigidimpact.contact import Contact
from rigidimpact.errors import InputError
from rigidimpact.expr import parse_expression
from rigidimpact.impact import NUMERIC_DIGITS, Impact
from rigidimpact.laws import Equation
from rigidimpact.notation import aligned, result_lhs, symbol, to_latex
from rigidimpact.numeric import evaluate
from rigidimpact.rewrite import recognise, solve_linear, tidy
from rigidimpact.roles import Role, check_assumptions, check_roles, roles_of
from rigidimpact.solution import Solution

__all__ = [
    "Derivation",
    "Evaluation",
    "physics_warnings",
    "model_warnings",
    "read_values",
    "model_name",
    "PROBLEMS",
    "derive",
    "barbell_impact",
    "barbell",
    "sticking",
    "sticking_routes",
    "sphere_a_velocity",
    "discs",
    "two_body",
]

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
BALL_BARBELL_UNKNOWNS = (("v_fx", "v_fy", "omega"), ("V_x", "V_y", "omega_z"))
# Mungan's equation numbers for the generic laws, attached to the paper's own problems only
PAPER_NUMBERS = (
    ("normal momentum", "(1), (12)"),
    ("tangential momentum", "(13)"),
    ("pair tangential momentum", "(13), summed"),
    ("angular momentum", "(2), (14)"),
    ("restitution", "(3), (4)"),
    ("no slip", "(8)-(9), fig. 2"),
)


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
        The givens in words.
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
    outcomes : tuple of collision.Outcome
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
        return roles_of(self.solution.before, (self.solution.contact,))

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
        if self.solution is not None:
            approach = self.solution.approach_speed.xreplace(exact)
            if approach.is_number and approach <= 0:
                raise InputError(", ".join(sources[n] for n in sorted(sources)) or "values",
                                 "with these values the bodies are not approaching at O")
        return {s.name: v for s, v in exact.items() if s.name in self.symbols}

    def evaluate(self, values: Mapping[str, Any], dps: int | None = None,
                 sources: Mapping[str, str] | None = None) -> Evaluation:
        """Every result at `values`, checked first (see :meth:`checked`).

        Returns an :class:`Evaluation`: the numbers, and warnings where the model cannot
        honour the physics at these values (kinetic energy created, a contact that
        would have to pull).

        Examples
        --------
        >>> out = derive("discs").evaluate({"V_1ix": 1, "V_2ix": 0, "V_1iy": 0,
        ...                                 "V_2iy": 0, "e": 1})
        >>> out.numbers["V_2fx"], out.warnings
        (1.0, ())
        """

        exact = self.checked(values, sources)
        if self.solution is None:
            numbers = evaluate(self.results, exact, dps)
            return Evaluation(numbers, physics_warnings(numbers, dps, "the model"))
        contact = self.solution.contact
        at = {self.symbols[k]: v for k, v in exact.items()}
        if contact.frictional and (dps is None or dps <= _FRICTION_DIGITS):
            # numbers first, then the case analysis: one course, exact (or 50-digit)
            # arithmetic, and no formula over every course evaluated where most of its
            # branches are undefined (a friction coefficient of 0, say)
            first, second = (b.at(at) for b in self.solution.before)
            solved = Impact(first, second, contact.at(at)).solve()
            numbers = evaluate(solved.results(), {}, dps)
            regime = solved.regime
        else:
            numbers = evaluate(self.results, exact, dps)
            regime = self.solution.regime_at(at)
        model = model_name(contact)
        if regime is not None:
            model += f" (regime {regime}"
            if contact.law == "newton" and ("reversal" in regime or "stick" in regime):
                model += ": slip stopped or reversed during the impact, where Newton's " \
                         "kinematic law can create energy (the Kane-Levinson paradox); " \
                         "Poisson's or the energetic law would not"
            model += ")"
        return Evaluation(numbers, physics_warnings(numbers, dps, model), regime)


@dataclass(frozen=True)
class Evaluation:
    """Numbers for a derivation's results, with what the model could not honour."""

    numbers: Mapping[str, Any]
    warnings: tuple[str, ...] = ()
    regime: str | None = None  # with friction: the course the impact took
    extra: Mapping[str, Any] = field(default_factory=dict)  # several contacts: acted, orders


def read_values(values: Mapping[str, Any], sources: dict[str, str],
                by_name: Mapping[str, sp.Symbol], roles: tuple[Role, ...],
                problem: str) -> dict[sp.Symbol, sp.Expr]:
    """Exact numbers for named symbols, each checked by its assumptions and every role it
    fills; `sources` says where each came from (filled with ``values.NAME`` if absent).

    Examples
    --------
    >>> e = symbol("e")
    >>> read_values({"e": "0.5"}, {}, {"e": e}, (), "demo")
    {e: 1/2}
    >>> read_values({"k": 1}, {}, {"e": e}, (), "demo")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: values.k: not a symbol of demo; it uses e
    """

    exact = {}
    for name, raw in values.items():
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
    tangential = {"stick": "sticking", "coulomb": "Coulomb-friction"}.get(
        contact.tangential, contact.tangential)
    law = {"newton": "Newton's", "poisson": "Poisson's", "energetic": "the energetic"}
    return f"{law[contact.law]} restitution with a {tangential} contact"


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
    if contact.tangential == "stick" and not contact.restitution.is_zero:
        return ("Newton's restitution with a sticking contact is not energy-consistent: for "
                "e > 0 it creates kinetic energy for some data (check that "
                "energy_loss_fraction >= 0 at your values; evaluate warns when it is not)",)
    if contact.tangential == "coulomb" and contact.law == "newton" \
            and not contact.restitution.is_zero:
        return ("Newton's restitution with Coulomb friction is not energy-consistent: when "
                "slip stops or reverses during the impact it can create kinetic energy (the "
                "Kane-Levinson paradox; Poisson's and the energetic law do not); evaluate "
                "warns where it does",)
    return ()


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


def barbell_impact(restitution: sp.Expr = e, tangential: str = "smooth") -> Impact:
    """Section 1: a ball (point mass m, speed v_ix along x) strikes sphere A of a barbell
    at rest (two masses M, rod 2L at angle theta to x).

    Examples
    --------
    >>> [str(u) for u in barbell_impact().unknowns]
    ['v_fx', 'v_fy', 'V_x', 'V_y', 'omega_z']
    """
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    return Impact(ball, bar, Contact(restitution=restitution, tangential=tangential),
                  BALL_BARBELL_UNKNOWNS, PAPER_NUMBERS)


@functools.cache
def barbell_solution(restitution: sp.Expr = e, tangential: str = "smooth") -> Solution:
    """The solved :func:`barbell_impact`, solved once per process (several derivations
    and checks start from the same impact).

    Examples
    --------
    >>> barbell_solution(0, "stick") is barbell_solution(0, "stick")
    True
    """
    return barbell_impact(restitution, tangential).solve()


def _timed(build: Callable[[], Derivation]) -> Callable[[], Derivation]:
    """Time a problem's derivation once; later calls return the same (immutable) result."""

    @functools.cache
    def run() -> Derivation:
        start = time.perf_counter()
        derivation = build()
        return replace(derivation, seconds=time.perf_counter() - start)

    functools.update_wrapper(run, build)
    return run


@_timed
def barbell() -> Derivation:
    """The ball and the barbell of section 1: eqs. (1), (2), (4) solved, (5) and (7).

    Examples
    --------
    >>> barbell().results["omega_z"]
    m*v_ix*(e + 1)*sin(theta)/(L*(2*M + m*sin(theta)**2 + m))
    """
    impact = barbell_impact()
    solution = barbell_solution()
    values = solution.values
    f = symbol("f")
    f_definition = tidy(values[symbol("V_x")] / v_ix)
    results = {
        "v_fx": values[symbol("v_fx")],
        "V_x": values[symbol("V_x")],
        "omega_z": values[symbol("omega_z")],
        "f": f_definition,
        "energy_loss_fraction": solution.energy_loss_fraction,
    }
    named = {key: recognise(results[key], f, f_definition, e)
             for key in ("v_fx", "V_x", "omega_z")}
    return Derivation(
        "barbell",
        "A ball strikes one end of a barbell at an angle (section 1)",
        ("ball: point mass m moving along x with speed v_ix",
         "barbell: masses M at both ends of a massless rod of length 2L, at rest, "
         "rod at angle theta to x; sphere A is struck at O",
         "contact: smooth, Newton restitution e along x"),
        impact.equations(),
        impact.unknowns,
        results,
        named,
        {"f": f_definition},
        solution,
    )


def sphere_a_velocity() -> sp.ImmutableMatrix:
    """Velocity of the struck sphere A just after the impact (section 2).

    Its y component is negative for 0 < theta < 90 degrees although the impulse is
    along +x: the rod's rotation carries A sideways.

    Examples
    --------
    >>> sphere_a_velocity()[1]
    -m*v_ix*(e + 1)*sin(theta)*cos(theta)/(2*M + m*sin(theta)**2 + m)
    """
    bar = barbell_solution().second_after
    sphere_a = next(p for p in bar.parts if p.label == "A")
    return bar.point_velocity(sphere_a.position).applyfunc(tidy)


@functools.cache
def _composite_route() -> tuple[tuple[Equation, ...], dict[str, sp.Expr]]:
    """Eqs. (8)-(9): ball and barbell move as one body (u, omega) about S after."""
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    centre = join(ball, bar).position
    u_x, u_y, omega = symbol("u_x"), symbol("u_y"), symbol("omega_z")
    u = sp.Matrix([u_x, u_y])

    def carried(body: Body) -> Body:
        arm = body.position - centre  # velocity of a point rigidly carried about S
        return body.with_motion(u + sp.Matrix([-omega * arm[1], omega * arm[0]]), omega
                                if not body.inertia.is_zero else 0)

    ball_after, bar_after = carried(ball), carried(bar)
    equations = (
        laws.normal_momentum(ball, ball_after, bar, bar_after),
        laws.pair_tangential_momentum(ball, ball_after, bar, bar_after),
        laws.angular_momentum(bar, bar_after),
    )
    solved = solve_linear([eq.residual for eq in equations], [u_x, u_y, omega])
    numbered = tuple(Equation(eq.label, p, tidy(eq.lhs), tidy(eq.rhs)) for eq, p in
                     zip(equations, ("(8)", "(8), y", "(9)"), strict=True))
    return numbered, {"u_x": tidy(solved[u_x]), "omega_z": tidy(solved[omega])}


def sticking_routes() -> dict[str, dict[str, sp.Expr]]:
    """The clay ball's u_x and omega_z by four independent routes.

    ``composite``: eqs. (8)-(9), the pair moving as one body about S.
    ``alternative``: eqs. (1) and (4) with e = 0 and eq. (2) with V_y = omega h cos(theta).
    ``parallel-axis``: the textbook route, :func:`~rigidimpact.bodies.join`, inertia about S.
    ``impact``: the general solver with a sticking contact and e = 0.

    Examples
    --------
    >>> sorted(sticking_routes())
    ['alternative', 'composite', 'impact', 'parallel-axis']
    """
    routes = {"composite": _composite_route()[1]}

    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    h = _sticking_h()
    smooth = barbell_impact(restitution=0)
    v_fx, V_x, V_y, omega = (symbol(n) for n in ("v_fx", "V_x", "V_y", "omega_z"))
    by_number = {eq.paper: eq for eq in smooth.equations()}
    modified = [by_number["(1), (12)"], by_number["(3), (4)"],
                by_number["(2), (14)"].subs(V_y, omega * h * sp.cos(theta))]
    solved = solve_linear([eq.residual for eq in modified], [v_fx, V_x, omega])
    routes["alternative"] = {
        "u_x": tidy((m * solved[v_fx] + 2 * M * solved[V_x]) / (2 * M + m)),
        "omega_z": tidy(solved[omega]),
    }

    composite = join(ball, bar)
    routes["parallel-axis"] = {"u_x": composite.velocity[0], "omega_z": composite.spin}

    stuck = barbell_solution(0, "stick")
    routes["impact"] = {
        "u_x": tidy((stuck.first_after.momentum[0] + stuck.second_after.momentum[0])
                    / (2 * M + m)),
        "omega_z": stuck.second_after.spin,
    }
    return routes


@functools.cache
def _sticking_h() -> sp.Expr:
    """Distance from the barbell's centre C to the pair's centre S, along the rod."""
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    offset = bar.position - join(ball, bar).position
    along_rod = offset[0] * sp.cos(theta) + offset[1] * sp.sin(theta)
    return tidy(along_rod)


@_timed
def sticking() -> Derivation:
    """The clay ball of figure 2: it sticks to sphere A; eqs. (8)-(10).

    Examples
    --------
    >>> sticking().results["omega_z"]
    m*v_ix*sin(theta)/(2*L*(M + m))
    """
    equations, values = _composite_route()
    h = _sticking_h()
    results = {"u_x": values["u_x"], "omega_z": values["omega_z"], "h": h}
    return Derivation(
        "sticking",
        "A clay ball sticks to one end of a barbell (figure 2)",
        ("ball: point mass m moving along x with speed v_ix; it sticks to sphere A",
         "barbell: masses M at both ends of a massless rod of length 2L, at rest, "
         "rod at angle theta to x",
         "after: ball and barbell move as one rigid body with centre S, velocity u and "
         "spin omega_z"),
        equations,
        (symbol("u_x"), symbol("u_y"), symbol("omega_z")),
        results,
    )


@_timed
def discs() -> Derivation:
    """Equal smooth discs, neither spinning: the impact is central; eq. (16).

    Examples
    --------
    >>> discs().results["V_1fx"]
    V_1ix*(1 - e)/2 + V_2ix*(e + 1)/2
    """
    mass, radius = symbol("m"), symbol("r")
    names = ("V_1ix", "V_1iy", "V_2ix", "V_2iy")
    v1x, v1y, v2x, v2y = (symbol(n) for n in names)
    first = Body.disc(mass, radius, side=-1, velocity=(v1x, v1y), name="disc1")
    second = Body.disc(mass, radius, side=1, velocity=(v2x, v2y), name="disc2")
    impact = Impact(first, second, Contact(restitution=e), numbers=PAPER_NUMBERS)
    solution = impact.solve()
    res = solution.results()

    def by_velocity(expr: sp.Expr) -> sp.Expr:
        # the paper writes (16) as a weighted sum of the two initial velocities
        numerator, denominator = sp.fraction(expr)
        return sp.collect(sp.expand(numerator), [v1x, v2x]) / denominator

    results = {"V_1fx": by_velocity(res["disc1.vx"]), "V_2fx": by_velocity(res["disc2.vx"]),
               "V_1fy": res["disc1.vy"], "V_2fy": res["disc2.vy"],
               "omega_1fz": res["disc1.omega"], "omega_2fz": res["disc2.omega"]}
    return Derivation(
        "discs",
        "Two equal smooth discs collide (eq. 16)",
        ("discs: equal masses m and radii r, not spinning, centres on the normal",
         "velocities (V_1ix, V_1iy) and (V_2ix, V_2iy); smooth contact, restitution e"),
        impact.equations(),
        impact.unknowns,
        results,
        solution=solution,
    )


def two_body_impact(restitution: sp.Expr = e) -> Impact:
    """Section 3: two general rigid bodies, smooth contact, in the paper's notation."""
    bodies = []
    for k in (1, 2):
        s = {n: symbol(n.format(k=k)) for n in ("m_{k}", "I_{k}", "R_{k}x", "R_{k}y",
                                                "V_{k}ix", "V_{k}iy", "omega_{k}iz")}
        bodies.append(Body.rigid(s["m_{k}"], s["I_{k}"], (s["R_{k}x"], s["R_{k}y"]),
                                 velocity=(s["V_{k}ix"], s["V_{k}iy"]),
                                 spin=s["omega_{k}iz"], name=f"body{k}"))
    return Impact(bodies[0], bodies[1], Contact(restitution=restitution),
                  numbers=PAPER_NUMBERS)


@_timed
def two_body() -> Derivation:
    """The general smooth planar impact of section 3: eqs. (11)-(14) solved.

    Examples
    --------
    >>> two_body().results["V_1fy"]
    V_1iy
    """
    impact = two_body_impact()
    solution = impact.solve()
    results = {str(u): solution.values[u] for u in impact.unknowns}
    # the normal impulse J collects the long common factor of every result: written
    # straight from the core (u+ = u- + M^-1 J^T J), not by eliminating e again
    J = symbol("J")
    by_impulse = impact.in_terms_of(J)
    named = {str(u): by_impulse[u] for u in impact.unknowns if results[str(u)].has(e)}
    return Derivation(
        "two-body",
        "Two rigid bodies, smooth contact (section 3)",
        ("body k: mass m_k, central inertia I_k, centre R_k = (R_kx, R_ky) from O, "
         "velocity (V_kix, V_kiy), spin omega_kiz",
         "contact: smooth, normal along x, Newton restitution e"),
        impact.equations(),
        impact.unknowns,
        results,
        named,
        {"J": solution.normal_impulse},
        solution,
    )


PROBLEMS: Mapping[str, Callable[[], Derivation]] = {
    "barbell": barbell,
    "sticking": sticking,
    "discs": discs,
    "two-body": two_body,
}


def derive(name: str) -> Derivation:
    """Derive a built-in problem by name.

    Examples
    --------
    >>> derive("discs").problem
    'discs'
    """
    try:
        build = PROBLEMS[name]
    except KeyError:
        raise InputError("problem", f"unknown problem {name!r}; built-in problems are "
                         f"{', '.join(PROBLEMS)}") from None
    return build()
