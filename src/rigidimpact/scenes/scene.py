"""Scene files: a collision stated once in TOML, read safely.

Expressions in a scene are read by the bounded parser of :mod:`rigidimpact.symbolic.expr`
(numbers, declared symbols, ``+ - * / **`` and ``^``, parentheses, ``sin cos tan sqrt``
and ``pi``, an optional trailing ``deg``): text from a file never reaches ``eval``,
``sympify`` or ``parse_expr``. Every problem is reported as an
:class:`~rigidimpact.errors.InputError` naming the field.

Examples
--------
>>> parse_expression("2*M + m*(1 + sin(theta)^2)", "demo")
2*M + m*(sin(theta)**2 + 1)
>>> parse_expression("30 deg", "demo")
pi/6
>>> parse_expression("__import__(1)", "demo")
Traceback (most recent call last):
...
rigidimpact.errors.InputError: demo: unknown function '__import__'; use sin, cos, tan or sqrt
"""

from __future__ import annotations

import keyword
import re
import time
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.model.joints import Joint
from rigidimpact.model.roles import Role, check_assumptions, check_roles, roles_of
from rigidimpact.model.shapes import SHAPES, Fields
from rigidimpact.solve.collision import MAX_BUILT_CONTACTS, Collision
from rigidimpact.solve.derivation import (
    Derivation,
    Evaluation,
    exact_numbers,
    model_warnings,
    physics_warnings,
    read_values,
)
from rigidimpact.solve.impact import Impact
from rigidimpact.solve.rules import (
    DEFAULT_RULE,
    RULE_CLASSES,
    Rule,
    RuleSettings,
    rule_named,
)
from rigidimpact.solve.rules.sequential import MAX_SAMPLED_ORDERS
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic import expr as expressions
from rigidimpact.symbolic.distributions import RandomInputs, random_table
from rigidimpact.symbolic.geometry import spin_cross
from rigidimpact.symbolic.notation import SYMBOLS, Given, make_symbol, speed_names
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Scene", "load_scene", "parse_scene", "parse_expression", "is_spatial",
           "read_toml", "scene_from_data"]

ASSUMPTIONS = ("positive", "nonnegative", "negative", "nonpositive", "real", "nonzero")


def is_spatial(data: Mapping[str, Any]) -> bool:
    """Whether a scene's tables give any vector three components (a 3-D scene, read by
    :mod:`rigidimpact.scenes.space`)."""
    tables = [t for t in data.get("bodies", []) if isinstance(t, dict)]
    if isinstance(data.get("contact"), dict):
        tables.append(data["contact"])
    tables += [t for t in data.get("contacts", []) if isinstance(t, dict)]
    return any(isinstance(t.get(k), list) and len(t[k]) == 3
               for t in tables for k in ("position", "velocity", "spin", "point", "normal"))


def parse_expression(value: Any, where: str,
                     symbols: Mapping[str, sp.Symbol] = SYMBOLS) -> sp.Expr:
    """An exact SymPy expression from a scene value, over the project's symbols by default.

    The bounded parser itself is :func:`rigidimpact.symbolic.expr.parse_expression`.

    Examples
    --------
    >>> parse_expression(0.25, "x")
    1/4
    >>> parse_expression("2*m", "x")
    2*m
    """
    return expressions.parse_expression(value, where, symbols)


def vector(value: Any, where: str, symbols: Mapping[str, sp.Symbol],
           size: int = 2) -> tuple:
    """A list of `size` components (2: [x, y], 3: [x, y, z]), each read as an
    expression in the scene's symbols."""
    if not isinstance(value, list) or len(value) != size:
        raise InputError(where, f"expected a list of {'two' if size == 2 else 'three'} "
                         f"components [{', '.join('xyz'[:size])}]")
    return tuple(parse_expression(c, f"{where}[{i}]", symbols) for i, c in enumerate(value))


def _vector(value: Any, where: str, symbols: Mapping[str, sp.Symbol]) -> tuple:
    return vector(value, where, symbols)


@dataclass(frozen=True)
class Scene:
    """A collision read from a scene file.

    Parameters
    ----------
    title : str
    symbols : mapping of name to Symbol
        Every name the scene may use.
    values : mapping of Symbol to number
        Numbers for evaluate and simulate.
    bodies : tuple of Body
        In the order of the file, placed from the scene's origin O (see
        :func:`_placed`: one frame rule for one contact and for several).
    contact : Contact
        The first contact (the only one of a one-contact scene).
    simulate : mapping
        The ``[simulate]`` table as read (checked by the simulation planner).
    name : str
        The file's stem.
    """

    title: str
    symbols: Mapping[str, sp.Symbol]
    values: Mapping[sp.Symbol, sp.Expr]
    bodies: tuple[Body, ...]
    contact: Contact
    simulate: Mapping[str, Any] = field(default_factory=dict)
    name: str = "scene"
    contacts: tuple[Contact, ...] = ()
    rule: str = DEFAULT_RULE
    order: tuple[str, ...] | None = None
    compliance: tuple[tuple[float, ...], bool] = ((1e6,), False)
    sample: tuple[int, int] | None = None  # [impact] orders = N, seed = S
    joints: tuple[Joint, ...] = ()  # [[joints]]: bodies pinned together
    random: RandomInputs | None = None  # [random]: symbols with a distribution

    @cached_property
    def roles(self) -> tuple[Role, ...]:
        """What bounds the scene's data by role (see :mod:`rigidimpact.model.roles`);
        found once (a scene is read once and asked for its roles at every check)."""
        return roles_of(self.bodies, self.contacts, self.contacts)

    @property
    def pair(self) -> tuple[Body, Body]:
        """The first contact's two bodies, first then second, seen from its point (the
        frame of the two-body core and of the one-contact simulators).

        Examples
        --------
        >>> scene = parse_scene('''
        ... [[bodies]]
        ... name = "a"
        ... shape = "particle"
        ... mass = "1"
        ... velocity = ["1", "0"]
        ... [[bodies]]
        ... name = "b"
        ... shape = "disc"
        ... mass = "1"
        ... radius = "1"
        ... [contact]
        ... restitution = "1"
        ... point = ["5", "0"]
        ... ''')
        >>> [tuple(b.position) for b in scene.bodies], [tuple(b.position) for b in scene.pair]
        ([(5, 0), (6, 0)], [(0, 0), (1, 0)])
        """
        c = self.contact
        by_name = {b.name: b for b in self.bodies}
        point = -sp.ImmutableMatrix(c.point)
        return by_name[c.first].shifted(point), by_name[c.second].shifted(point)

    def impact(self) -> Impact:
        """The scene's impact (one contact)."""
        if self.joints:
            raise InputError("joints", "this scene has joints: derive and evaluate solve "
                             "it; this command follows one contact of two bodies")
        if len(self.contacts) > 1:
            raise InputError("contacts", "this scene has several contacts: derive and "
                             "evaluate solve it; this command follows one contact")
        first, second = self.pair
        return Impact(first, second, self.contact, unknown_names=(
            speed_names(first.name), speed_names(second.name)))

    @property
    def data_symbols(self) -> dict[str, sp.Symbol]:
        """The symbols the scene's bodies and contacts use, by name.

        Examples
        --------
        >>> import rigidimpact
        >>> root = Path(rigidimpact.__file__).parents[2]
        >>> sorted(load_scene(root / "derivations" / "two-ball-drop.toml").data_symbols)
        ['e']
        """
        found: set[sp.Symbol] = set()
        for b in self.bodies:
            pivot = () if b.pivot is None else tuple(b.pivot)
            found |= sp.Tuple(b.mass, b.inertia, *b.position, *b.velocity, b.spin,
                              *pivot).free_symbols
        for c in self.contacts or (self.contact,):
            found |= sp.Tuple(c.restitution, *c.normal, *c.point, c.friction or 0,
                              c.tangential_restitution or 0).free_symbols
        for j in self.joints:
            found |= sp.Tuple(*j.point).free_symbols
        return {s.name: s for s in sorted(found, key=lambda s: s.name)}

    def with_values(self, settings: Mapping[str, Any], sources: Mapping[str, str]) -> Scene:
        """The scene with other numbers for its symbols (``--set``), checked through the
        same door as ``[values]``: assumptions, roles, geometry, and (one contact) that
        the bodies still approach.

        Examples
        --------
        >>> scene = parse_scene('''
        ... [values]
        ... v = 1
        ... [[bodies]]
        ... name = "a"
        ... shape = "particle"
        ... mass = "1"
        ... velocity = ["v", "0"]
        ... [[bodies]]
        ... name = "b"
        ... shape = "particle"
        ... mass = "1"
        ... [contact]
        ... restitution = "1"
        ... ''')
        >>> scene.with_values({"v": "2"}, {"v": "--set v"}).values
        {v: 2}
        """
        values: dict[str, Any] = {s.name: v for s, v in self.values.items()}
        values.update(settings)
        every = {s.name: f"values.{s.name}" for s in self.values}
        every.update(sources)
        exact = read_values(values, every, self.data_symbols, self.roles, self.name)
        scene = replace(self, values=exact)
        _check_scene(scene)
        return scene

    def collision(self, values: Mapping[sp.Symbol, Any] | None = None) -> Collision:
        """The scene's bodies and contacts (with numbers for its symbols when given)."""
        if not values:  # none to put in: the bodies as they are (at scale, seconds)
            return Collision(self.bodies, self.contacts, self.joints)
        return Collision.from_values(self.bodies, self.contacts, dict(values), self.joints)

    def outcomes(self, values: Mapping[sp.Symbol, Any] | None = None) -> tuple[Solution, ...]:
        """What the scene's rule makes of its contacts at `values` (the scene's
        ``[values]`` by default; every order when a sequential rule has none)."""
        return self.collision(dict(self.values if values is None else values)).solve(
            self.impact_rule)

    @property
    def impact_rule(self) -> Rule:
        """The ``[impact]`` rule as its object (the registry's, as in space)."""
        return rule_named(self.rule, RuleSettings(self.order, self.sample, self.compliance))

    def derivation(self, values: Mapping[sp.Symbol, Any] | None = None,
                   printed: bool = True) -> Derivation:
        """Solve the scene's impact: symbolically, or at `values` when given (several
        contacts at the scene's ``[values]`` unless other values are given; with none
        they are solved over their symbols where the rule has closed forms).

        One path for one contact and for several: the scene's collision and its rule
        give :class:`~rigidimpact.solve.solution.Solution` values (one contact: its own
        exact answer by the two-body core, whatever the rule), and the equations printed
        are the ones solved (with `printed` False they are not written out: numbers
        need none, and at a thousand contacts they cost more than the solve).

        Examples
        --------
        >>> scene = parse_scene('''
        ... [[bodies]]
        ... name = "a"
        ... shape = "particle"
        ... mass = "m"
        ... velocity = ["v_ix", "0"]
        ... [[bodies]]
        ... name = "b"
        ... shape = "particle"
        ... mass = "m"
        ... [contact]
        ... bodies = ["a", "b"]
        ... restitution = "e"
        ... ''')
        >>> scene.derivation().results["b.vx"]
        v_ix*(e + 1)/2
        """
        start = time.perf_counter()
        several = len(self.contacts) > 1 or bool(self.joints)
        if values is None and several:  # several contacts, joints: at the [values]
            values = self.values
        collision = self.collision(values)
        outcomes = collision.solve(self.impact_rule)
        first = outcomes[0]
        # the momentum balance holds under every rule; a contact's own law only where
        # one outcome is reported (each case or order imposes its own)
        # the labelled equations are for reading (derive, LaTeX); numbers need none
        equations = first.equations or (collision.equations(first) if printed else ())
        if len(outcomes) > 1:
            equations = tuple(eq for eq in equations if eq.law == "momentum")
        setup: tuple[str, ...] = tuple(_described(b) for b in self.bodies)
        setup += tuple(_contact_line(c) for c in self.contacts)
        setup += tuple(Given(f"joint {j.name}: {j.first} and {j.second} pinned at {{}}, "
                             "a frictionless hinge", (j.point[0], j.point[1]))
                       for j in self.joints)
        if several:
            setup += (f"rule: {self.rule}" + ("" if self.order is None
                                              else f", order {', '.join(self.order)}"),)
        results = first.results()
        if len(outcomes) > 1 and all(o.conditions for o in outcomes):  # one case at a time
            cases = [sp.And(*o.conditions) for o in outcomes]
            results = {key: _cases([o.results()[key] for o in outcomes], cases)
                       for key in results}
        warnings = tuple(dict.fromkeys(w for c in self.contacts for w in model_warnings(c)))
        return Derivation(self.name, self.title, setup, equations,
                          first.unknowns or collision.unknowns(), results,
                          solution=None if several else first,
                          seconds=time.perf_counter() - start, warnings=warnings,
                          outcomes=outcomes if several else ())

    def evaluate(self, settings: Mapping[str, Any], sources: Mapping[str, str],
                 dps: int | None = None, exact: bool = False) -> Evaluation:
        """Every result in numbers at `settings` (names to values, each checked through
        the same door as ``[values]``; `sources` says where each came from).

        One contact: its closed forms, evaluated by the fused kernel (or with `dps`
        digits). Several contacts: solved at the numbers by the scene's rule, and the
        extra keys say which rule, which contacts acted, and (for every order or a
        sample of orders) each order's results and the spread.

        Examples
        --------
        >>> import rigidimpact
        >>> root = Path(rigidimpact.__file__).parents[2]
        >>> scene = load_scene(root / "derivations" / "newtons-cradle.toml")
        >>> out = scene.evaluate({}, {})
        >>> out.numbers["last.vx"], out.extra["rule"]
        (1.0, 'sequential left, right')
        """
        if len(self.contacts) == 1 and not self.joints:
            return self.derivation().evaluate(settings, dps, sources, exact)
        given = read_values(settings, dict(sources), self.data_symbols, self.roles, self.name)
        derivation = self.derivation(given, printed=False)
        numbers = derivation.evaluate({}, dps).numbers
        outcomes = derivation.outcomes
        extra: dict[str, Any] = {"rule": outcomes[0].label, "acted": list(outcomes[0].acted)}
        if outcomes[0].checks:  # each law's residual, from the bodies and impulses alone
            extra["checks"] = {k: float(v) for k, v in outcomes[0].checks.items()}
        if outcomes[0].courses:
            extra["courses"] = list(outcomes[0].courses)
        extra.update(orders_extra(outcomes, self.impact_rule))
        warnings = physics_warnings(numbers, dps, f"the {self.rule} rule",
                                    outcomes[0].energy_tolerance)
        warnings = (*warnings, *outcomes[0].notes)
        if outcomes[0].method:
            extra["method"] = outcomes[0].method
        return Evaluation(numbers, warnings, None, extra,
                          exact_numbers(outcomes[0].results()) if exact else None)


def orders_extra(outcomes: Sequence[Solution], rule: Rule) -> dict[str, Any]:
    """What ``evaluate`` adds where a rule gives several outcomes (every order, or a
    sample of orders): each order's results, and for a sample its size and the spread
    of each result; the same in the plane and in space."""
    extra: dict[str, Any] = {}
    if len(outcomes) > 1:
        extra["orders"] = [{"order": list(o.order), "acted": list(o.acted),
                            "results": {k: float(v) for k, v in o.results().items()}}
                           for o in outcomes]
    sample = getattr(rule, "sample", None)
    if sample is not None and getattr(rule, "order", None) is None:
        rows = [row["results"] for row in extra["orders"]] if len(outcomes) > 1 else [
            {k: float(v) for k, v in outcomes[0].results().items()}]
        extra["sample"] = {"orders": sample, "seed": getattr(rule, "seed", 0),
                           "distinct": len({tuple(o.order) for o in outcomes})}
        extra["spread"] = {k: [min(r[k] for r in rows), max(r[k] for r in rows)]
                           for k in rows[0]}
    return extra


def _cases(parts: list[sp.Expr], conditions: list[sp.Basic]) -> sp.Expr:
    """One expression over exclusive cases (a ``Piecewise`` unless all agree)."""
    if all(p == parts[0] for p in parts):
        return parts[0]
    return sp.Piecewise(*zip(parts, conditions, strict=True))


def _contact_line(c: Contact) -> Given:
    """One line of the givens for a contact: where, between which bodies, its laws."""
    label = "contact" if c.name == "contact" else f"contact {c.name}"
    return Given(f"{label}: {c.first} -> {c.second} at {{}}, normal {{}}, {c.law} "
                 "restitution {}, ", (c.point[0], c.point[1]), (c.normal[0], c.normal[1]),
                 c.restitution) + _tangential_words(c)


def _tangential_words(c: Contact) -> Given:
    """The contact's tangential law in words, with its coefficients (the law's own)."""
    return c.laws[1].words()


def _described(b: Body) -> Given:
    """One line of the givens for a body."""
    if b.support == "fixed":
        return Given(f"{b.name}: fixed (immovable)")
    line = Given(f"{b.name}: {b.shape}, mass {{}}, centre {{}} from O, velocity {{}}, spin {{}}",
                 b.mass, (b.position[0], b.position[1]), (b.velocity[0], b.velocity[1]),
                 b.spin)
    return line if b.pivot is None else line + Given(", on a pivot at {}",
                                                     (b.pivot[0], b.pivot[1]))


def _table(data: Mapping[str, Any], key: str, form: str) -> dict[str, Any]:
    """An optional top-level table of the scene (empty when absent)."""
    table = data.get(key, {})
    if not isinstance(table, dict):
        raise InputError(key, f"must be a table of {form}")
    return table


def _symbols_table(table: Mapping[str, Any]) -> dict[str, sp.Symbol]:
    symbols = dict(SYMBOLS)
    for name, spec in table.items():
        where = f"symbols.{name}"
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)?", name):
            raise InputError(where, "a symbol name is letters and digits, with at most one _")
        if (name in expressions.FUNCTIONS or name in expressions.CONSTANTS or name == "deg"
                or keyword.iskeyword(name) or name in ("True", "False", "None")):
            raise InputError(where, f"{name!r} is reserved")
        if not isinstance(spec, dict):
            raise InputError(where, "expected a table such as { positive = true }")
        for key, flag in spec.items():
            if key not in ASSUMPTIONS:
                raise InputError(f"{where}.{key}", f"unknown assumption; use one of "
                                 f"{', '.join(ASSUMPTIONS)}")
            if not isinstance(flag, bool):
                raise InputError(f"{where}.{key}", "must be true or false")
        try:
            symbols[name] = make_symbol(name, **spec)
        except ValueError as exc:
            raise InputError(where, str(exc)) from None
    return symbols


# the settings of a run, read under [simulate] only (the planner checks their values)
SIMULATE_SETTINGS = frozenset({
    "until", "effects", "rod_stiffness", "contact_stiffness", "tolerance", "g", "integrator",
    "stiffness_ratio", "impacts", "rolling_resistance", "pivot_friction"})


def _values_table(table: Mapping[str, Any],
                  symbols: Mapping[str, sp.Symbol]) -> dict[sp.Symbol, sp.Expr]:
    values: dict[sp.Symbol, sp.Expr] = {}
    for name, raw in table.items():
        where = f"values.{name}"
        if name not in symbols and name in SIMULATE_SETTINGS:
            shown = f'"{raw}"' if isinstance(raw, str) else raw
            raise InputError(where, f"{name} is a setting of the run, not a symbol: write "
                             f"it under [simulate] ({name} = {shown})")
        if name not in symbols:
            raise InputError(where, "unknown symbol; declare it under [symbols]")
        value = parse_expression(raw, where, {})  # numbers only: a value names no symbol
        values[symbols[name]] = check_assumptions(symbols[name], value, where)
    return values


def _body(table: Any, index: int, side: int, normal: sp.MatrixBase,
          symbols: Mapping[str, sp.Symbol], origin: tuple = (0, 0),
          contact: str = "contact") -> Body:
    """One body from its table, seen from the contact point at `origin`: positions and
    the pivot, given from the scene's origin, are moved there."""
    where = f"bodies[{index}]"
    if not isinstance(table, dict):
        raise InputError(where, "each [[bodies]] entry must be a table")
    name = table.get("name")
    if not isinstance(name, str) or not name.isidentifier():
        raise InputError(f"{where}.name", "required: an identifier such as \"ball\"")
    shape = table.get("shape")
    if not isinstance(shape, str) or shape not in SHAPES:
        raise InputError(f"{where}.shape", f"unknown shape {shape!r}; expected one of "
                         f"{', '.join(SHAPES)}")
    kind = SHAPES[shape]
    allowed = set(kind.fields) | {"name", "shape"}
    if kind.moves:
        allowed |= {"velocity", "pivot"}
    if kind.spins or (kind.moves and "pivot" in table):  # a bob's spin: its swing rate
        allowed |= {"spin"}
    for key in table:
        if key not in allowed:
            raise InputError(f"{where}.{key}", f"not a field of a {shape}; allowed: "
                             f"{', '.join(sorted(allowed))}")
    for key in kind.required:
        if key not in table:
            raise InputError(f"{where}.{key}", f"required for a {shape}")

    velocity = _vector(table.get("velocity", [0, 0]), f"{where}.velocity", symbols)
    spin = parse_expression(table["spin"], f"{where}.spin", symbols) if "spin" in table else 0
    given = Fields(table, lambda key: parse_expression(table[key], f"{where}.{key}", symbols),
                   lambda key: _from_contact(table, key, where, symbols, origin), name,
                   velocity, spin, side * normal, contact)
    try:
        body = kind.build(given)
        if "pivot" in table:
            pivot = _from_contact(table, "pivot", where, symbols, origin)
            if "velocity" in table:  # given: it must be the turn about the pivot
                body = replace(body, pivot=pivot)
                stated = sp.sympify(spin)
                if "spin" in table and not tidy(body.spin - stated).is_zero:
                    raise InputError(f"{where}.spin", f"a pivoted body moves only by "
                                     f"turning about its pivot: its velocity makes the "
                                     f"spin {body.spin}, not {stated}; give one of the two")
            else:  # the velocity follows from the spin
                turn = spin_cross(spin, body.position - sp.ImmutableMatrix(pivot))
                body = replace(body, pivot=pivot, velocity=turn, spin=spin)
        return body
    except InputError as exc:
        # name the entry in the file, not only the body
        field_name = exc.field.split(".", 1)[-1] if "." in exc.field else exc.field
        raise InputError(f"{where}.{field_name}", exc.message) from None


def _from_contact(table: Mapping[str, Any], key: str, where: str,
                  symbols: Mapping[str, sp.Symbol], origin: tuple) -> tuple:
    """A point of the scene (a centre, a pivot) as seen from the contact point."""
    x, y = _vector(table[key], f"{where}.{key}", symbols)
    return (x - origin[0], y - origin[1])


CONTACT_FIELDS = ("name", "bodies", "point", "normal", "restitution", "law", "tangential",
                  "friction", "tangential_restitution")


def _body_tables(data: Mapping[str, Any]) -> dict[str, tuple[int, dict]]:
    """The ``[[bodies]]`` tables by name, with their index in the file."""
    tables = data.get("bodies")
    if not isinstance(tables, list) or len(tables) < 2:
        raise InputError("bodies", "at least two [[bodies]] entries are required")
    by_name: dict[str, tuple[int, dict]] = {}
    for index, table in enumerate(tables):
        if not isinstance(table, dict):
            raise InputError(f"bodies[{index}]", "each [[bodies]] entry must be a table")
        body_name = table.get("name")
        if not isinstance(body_name, str) or not body_name.isidentifier():
            raise InputError(f"bodies[{index}].name", "required: an identifier such as "
                             "\"ball\"")
        if body_name in by_name:
            raise InputError(f"bodies[{index}].name", f"two bodies are named {body_name!r}")
        by_name[body_name] = (index, table)
    return by_name


def _pair(table: Mapping[str, Any], place: str, default: list[str]) -> list[str]:
    """The two body names a contact joins, first on the -x side of its normal."""
    order = table.get("bodies", default)
    if (not isinstance(order, list) or len(order) != 2
            or not all(isinstance(x, str) for x in order) or order[0] == order[1]):
        raise InputError(f"{place}.bodies", "must name the two bodies, e.g. "
                         "[\"ball\", \"bar\"]")
    return order


def read_contact(table: Any, place: str, symbols: Mapping[str, sp.Symbol],
                 bodies: tuple[str, str] | None = None, size: int = 2,
                 named: bool = False) -> Contact:
    """One contact's table, in the plane (`size` 2) or in space (3): its two bodies
    (`bodies`, or the table's own: required in space), its laws, its normal and its
    point (from O; in the plane the normal defaults to x and the point to O), its name
    (required where `named`). A field the contact refuses is named at its place in
    the file."""
    if not isinstance(table, dict):
        raise InputError(place, "must be a table")
    for key in table:
        if key not in CONTACT_FIELDS:
            raise InputError(f"{place}.{key}", f"unknown field; expected "
                             f"{', '.join(CONTACT_FIELDS)}")
    needed = ("restitution", *(("bodies", "normal") if size == 3 else ()),
              *(("name",) if named else ()))
    for key in needed:
        if key not in table:
            raise InputError(f"{place}.{key}", "required" + (
                ": the coefficient e in [0, 1]" if key == "restitution" else
                " with several contacts" if key == "name" else " in a 3-D scene"))
    if bodies is None:
        first, second = _pair(table, place, [])
        bodies = (first, second)
    contact_name = table.get("name", "contact")
    if not isinstance(contact_name, str) or not contact_name.isidentifier():
        raise InputError(f"{place}.name", "must be an identifier such as \"left\"")
    coefficients = {key: parse_expression(table[key], f"{place}.{key}", symbols)
                    for key in ("friction", "tangential_restitution") if key in table}
    try:
        return Contact(vector(table.get("normal", [1, 0]), f"{place}.normal", symbols, size),
                       parse_expression(table["restitution"], f"{place}.restitution",
                                        symbols),
                       table.get("tangential", "smooth"), table.get("law", "newton"),
                       contact_name, bodies=bodies, point=vector(
                           table.get("point", [0] * size), f"{place}.point", symbols, size),
                       **coefficients)
    except InputError as exc:  # the contact's own field, at its place in the file
        if place == "contact":
            raise
        raise InputError(f"{place}.{exc.field.split('.')[-1]}", exc.message) from None


def _compliance(table: Mapping[str, Any], count: int) -> tuple[tuple[float, ...], bool]:
    """``[impact]`` stiffness (one number, or one per contact in their order) and model."""
    raw = table.get("stiffness", 1e6)
    values = raw if isinstance(raw, list) else [raw] * count
    if len(values) != count or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and 1e-3 <= v <= 1e16
            for v in values):
        raise InputError("impact.stiffness", f"one number in [1e-3, 1e16] (N/m), or a list "
                         f"of {count}, one per contact")
    model = table.get("model", "linear")
    if model not in ("linear", "hertz"):
        raise InputError("impact.model", f"must be linear or hertz, got {model!r}")
    return tuple(float(v) for v in values), model == "hertz"


def _contact_tables(data: Mapping[str, Any]) -> list[tuple[dict[str, Any], str]]:
    """The contacts, from ``[contact]`` or the ``[[contacts]]`` entries, each with the
    place to name in messages."""
    if "contact" in data and "contacts" in data:
        raise InputError("contacts", "give either [contact] or [[contacts]], not both")
    if "contacts" in data:
        entries = data["contacts"]
        if not isinstance(entries, list) or not entries:
            raise InputError("contacts", "[[contacts]] must hold at least one table")
        for k, entry in enumerate(entries):
            if not isinstance(entry, dict):
                raise InputError(f"contacts[{k}]", "each [[contacts]] entry must be a table")
        return [(entry, f"contacts[{k}]") for k, entry in enumerate(entries)]
    table = data.get("contact")
    if not isinstance(table, dict):
        raise InputError("contact", "a [contact] table (or [[contacts]] entries) is required")
    return [(table, "contact")]


def _contacts(tables: list[tuple[dict[str, Any], str]], by_name: Mapping[str, Any],
              symbols: Mapping[str, sp.Symbol], joined: bool = False) -> tuple[Contact, ...]:
    """Every contact with its two bodies named and its point (from the origin O). One
    contact without joints is between exactly two bodies; with joints (`joined`) it
    names its two among the linkage's."""
    several = len(tables) > 1 or joined
    if not several and len(by_name) != 2:
        raise InputError("bodies", "exactly two [[bodies]] entries are required with one "
                         "contact (or [[joints]] that pin more bodies together)")
    contacts: list[Contact] = []
    names: set[str] = set()
    for table, place in tables:
        if several and "name" not in table:
            raise InputError(f"{place}.name", "required with several contacts")
        first, second = _pair(table, place, [] if several else list(by_name))
        for body_name in (first, second):
            if body_name not in by_name:
                raise InputError(f"{place}.bodies", f"no body named {body_name!r}")
        contact = read_contact(table, place, symbols, (first, second))
        if contact.name in names:
            raise InputError(f"{place}.name", f"two contacts are named {contact.name!r}")
        names.add(contact.name)
        contacts.append(contact)
    return tuple(contacts)


def _placed(table: dict[str, Any], index: int, touching: Contact | None,
            symbols: Mapping[str, sp.Symbol]) -> Body:
    """A body from its table, in the scene frame (from O). The one frame rule: every
    position, pivot and point is given from O; a shape that places itself (a particle or
    a round body without `position`, a barbell's struck end, a rod's `struck_at`) is
    placed from the point of the first contact that names it, on its own side of that
    contact's normal (`touching`: the first contact that names it, or None)."""
    name = table["name"]
    if touching is None:
        origin, side, unit = sp.ImmutableMatrix([0, 0]), 1, sp.ImmutableMatrix([1, 0])
        contact = "O"
    else:
        origin = sp.ImmutableMatrix(touching.point)
        side = -1 if touching.first == name else 1
        unit, contact = touching.frame.row(0).T, touching.name
    body = _body(table, index, side, unit, symbols, tuple(origin), contact)
    return body.shifted(origin)


def _impact_table(table: Mapping[str, Any], names: list[str],
                  more: tuple[str, ...] = ()) -> tuple[str, tuple[str, ...] | None]:
    """Check ``[impact]`` and return its rule and order (None: every order): the one
    reading for both dimensions (`more`: the fields a 3-D scene also takes).

    With one contact every rule gives the same answer."""
    known = ("rule", "order", "orders", "seed", "stiffness", "model", *more)
    for key in table:
        if key not in known:
            raise InputError(f"impact.{key}", f"unknown field; expected {', '.join(known)}")
    rule = table.get("rule", DEFAULT_RULE)
    if not isinstance(rule, str) or rule not in RULE_CLASSES:  # the one registry
        raise InputError("impact.rule", f"must be one of {', '.join(RULE_CLASSES)}, got "
                         f"{rule!r}")
    if "orders" in table or "seed" in table:
        if not RULE_CLASSES[rule].in_turn or "order" in table:
            raise InputError("impact.orders", "a sample of orders (orders, seed) goes with "
                             "rule = \"sequential\" and no order")
    if "order" not in table:
        return rule, None
    order = table["order"]
    if not isinstance(order, list) or sorted(map(str, order)) != sorted(names) or \
            len(order) != len(names):
        listed = ", ".join(f'"{n}"' for n in names)
        raise InputError("impact.order", f"must list the scene's contacts by name, each "
                         f"once: [{listed}]")
    return rule, tuple(order)


def parse_scene(text: str, name: str = "scene") -> Scene:
    """Read a scene from TOML text.

    Raises
    ------
    InputError
        For malformed TOML or any bad field, naming the field.
    """
    return scene_from_data(read_toml(text), name)


def read_toml(text: str) -> dict[str, Any]:
    """A scene's TOML, after refusing at once a scene far past the budget (100,000
    tables take seconds to read; the exact count is checked again once it is read)."""
    headers = max(text.count("[[contacts]]"), text.count("[[bodies]]"))
    if headers > 2 * MAX_BUILT_CONTACTS:
        raise InputError("contacts", f"about {headers} [[bodies]] or [[contacts]] tables: "
                         f"past the budget of {MAX_BUILT_CONTACTS} (each body and contact is "
                         "a SymPy object, a few milliseconds each); split the scene or use "
                         "fewer contacts")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError("scene", f"malformed TOML: {exc}") from None


def scene_from_data(data: dict[str, Any], name: str = "scene") -> Scene:
    """A planar scene from its TOML, already read (see :func:`parse_scene`)."""
    if is_spatial(data):
        raise InputError("scene", "a 3-D scene (vectors with three components): read it "
                         "with rigidimpact.load_space_scene; derive and evaluate read both")
    allowed = {"title", "symbols", "values", "bodies", "contact", "contacts", "impact",
               "simulate", "joints", "random"}
    for key in data:
        if key not in allowed:
            raise InputError(key, f"unknown section; expected {', '.join(sorted(allowed))}")
    title = data.get("title", name)
    if not isinstance(title, str):
        raise InputError("title", "must be text")
    symbols = _symbols_table(_table(data, "symbols", "name = { assumption = true }"))
    values = _values_table(_table(data, "values", "name = number"), symbols)
    randoms = random_table(_table(data, "random", "name = { uniform = [a, b] }"), symbols)

    by_name = _body_tables(data)
    simulate = _table(data, "simulate", "settings")
    tables = _contact_tables(data)
    _names_first(tables, by_name)
    contacts = _contacts(tables, by_name, symbols, joined=bool(data.get("joints")))
    impact_table = _table(data, "impact", "settings")
    rule, order = _impact_table(impact_table, [c.name for c in contacts])
    sample = _sample(impact_table)
    compliance = _compliance(impact_table, len(contacts))
    joints = _joints(data, by_name, symbols)
    first_touch: dict[str, Contact] = {}
    for c in contacts:
        first_touch.setdefault(c.first, c)
        first_touch.setdefault(c.second, c)
    bodies = tuple(_placed(table, index, first_touch.get(name), symbols)
                   for name, (index, table) in by_name.items())
    scene = Scene(title, symbols, values, bodies, contacts[0], simulate, name,
                  contacts=contacts, rule=rule, order=order, sample=sample,
                  compliance=compliance, joints=joints, random=randoms)
    _check_scene(scene)
    return scene


def _names_first(tables: list[tuple[dict[str, Any], str]],
                 by_name: Mapping[str, Any]) -> None:
    """The scene's size against its budget, and every contact's bodies by name, before
    any number is read or any body built (each costs milliseconds: a misspelt name in
    the last of ten thousand contacts is said at once, not after them all)."""
    size = max(len(tables), len(by_name))
    if size > MAX_BUILT_CONTACTS:
        raise InputError("contacts" if len(tables) >= len(by_name) else "bodies",
                         f"{len(tables)} contacts and {len(by_name)} bodies: past the budget "
                         f"of {MAX_BUILT_CONTACTS} (each body and contact is a SymPy "
                         "object, a few milliseconds each, and the rules' work grows "
                         "with them); split the scene or use fewer contacts")
    for table, place in tables:
        pair = table.get("bodies")
        if isinstance(pair, list):
            for side in pair:
                if isinstance(side, str) and side not in by_name:
                    raise InputError(f"{place}.bodies", f"no body named {side!r}")


def _joints(data: Mapping[str, Any], by_name: Mapping[str, Any],
            symbols: Mapping[str, sp.Symbol], vector: Any = None,
            axis: bool = False) -> tuple[Joint, ...]:
    """The ``[[joints]]`` entries: each a `name`, the two `bodies` it pins together and
    the `point` (from O) where it pins them, read by `vector` (the plane's [x, y] by
    default); in space (`axis`) a hinge's optional ``axis`` too."""
    read = _vector if vector is None else vector
    fields = ("name", "bodies", "point") + (("axis",) if axis else ())
    entries = data.get("joints", [])
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise InputError("joints", "must be [[joints]] tables, each with name, bodies and "
                         "point" + (" (and axis for a hinge)" if axis else ""))
    found: list[Joint] = []
    for k, entry in enumerate(entries):
        place = f"joints[{k}]"
        for key in entry:
            if key not in fields:
                raise InputError(f"{place}.{key}", "not a field of a joint; allowed: "
                                 f"{', '.join(sorted(fields))}")
        for key in ("name", "bodies", "point"):
            if key not in entry:
                raise InputError(f"{place}.{key}", "required for a joint")
        name, pair = entry["name"], entry["bodies"]
        if not isinstance(name, str) or not name.isidentifier():
            raise InputError(f"{place}.name", f"must be an identifier, not {name!r}")
        if any(j.name == name for j in found):
            raise InputError(f"{place}.name", f"two joints are named {name!r}")
        if not (isinstance(pair, list) and len(pair) == 2 and
                all(isinstance(b, str) for b in pair)):
            raise InputError(f"{place}.bodies", "must name two bodies, such as "
                             "[\"upper\", \"lower\"]")
        for side in pair:
            if side not in by_name:
                raise InputError(f"{place}.bodies", f"no body named {side!r}")
        point = read(entry["point"], f"{place}.point", symbols)
        turn = None if entry.get("axis") is None else \
            read(entry["axis"], f"{place}.axis", symbols)
        try:
            found.append(Joint(name, tuple(pair), point, turn))
        except InputError as exc:
            raise InputError(f"{place}.{exc.field.split('.')[-1]}", exc.message) from None
    return tuple(found)


def _check_scene(scene: Scene) -> None:
    """Checks that need the whole scene: roles and approach with the given values, and
    each random symbol's support inside what its role allows."""
    # geometry first (a normal pointing the wrong way also makes the bodies recede)
    check_roles(scene.roles, scene.values, {s: f"values.{s.name}" for s in scene.values})
    for symbol, law in (scene.random.inputs.items() if scene.random else ()):
        for end in law.support:  # an unbounded end: a value far out
            value = end if end.is_finite else sp.sign(end) * sp.Integer(10) ** 9
            if law.kind == "lognormal" and end == 0:  # an open end, never drawn
                value = sp.Rational(1, 10**9)
            check_roles(scene.roles, {symbol: value}, {symbol: f"random.{symbol.name}"})
    if scene.joints:  # each joint on its bodies, holding them together before
        scene.collision()
        if scene.values:
            scene.collision(scene.values)
        return
    if len(scene.contacts) > 1:  # the collision refuses contacts none of which approach
        return
    impact = scene.impact()  # refuses bodies known not to approach
    if scene.values:
        approach = impact.approach_speed.xreplace(dict(scene.values))
        if approach.is_number and approach <= 0:
            raise InputError("bodies", f"the bodies are not approaching at O with [values] "
                             f"(normal approach speed {sp.N(approach, 6)})")
        for symbol, law in (scene.random.inputs.items() if scene.random else ()):
            _approaches_throughout(impact.approach_speed, dict(scene.values), symbol, law)


def _approaches_throughout(approach: sp.Expr, values: dict, symbol: sp.Symbol,
                           law: Any) -> None:
    """Refuse a random input whose draws include impacts that do not happen (the bodies
    not approaching: a pulling impulse), judged at its support's ends and at points
    between (a normal or log-normal input: within six spreads of its centre). A value
    of a discrete input is drawn with its own probability, so no approach there is
    refused; a single value of a continuous one is drawn with probability zero, so only
    bodies moving apart there are (by continuity, so do the draws around it), not a
    speed of exactly zero (theta uniform on [0, pi/2] with an approach speed sin(theta))."""
    if law.kind == "discrete":
        points = list(law.parameters)
    else:
        low, high = law.support
        if law.kind == "normal":
            mean, spread = law.parameters
            low, high = mean - 6 * spread, mean + 6 * spread
        elif law.kind == "lognormal":
            mean, spread = law.parameters
            low, high = sp.exp(mean - 6 * spread), sp.exp(mean + 6 * spread)
        points = [low + (high - low) * sp.Rational(k, 8) for k in range(9)]
    for x in points:
        speed = approach.xreplace({**values, symbol: x})
        if not speed.is_number:
            continue
        size = sp.N(speed, 30)
        if size < 0 or size == 0 and law.kind == "discrete":
            raise InputError(f"random.{symbol.name}", f"at {symbol.name} = {sp.N(x, 6)} "
                             f"the bodies are not approaching (normal approach speed "
                             f"{sp.N(speed, 6)}): such draws are no impact; give a "
                             "distribution on which they approach")


def load_scene(path: str | Path) -> Scene:
    """Read a scene file.

    Raises
    ------
    InputError
        If the file cannot be read or any field is bad.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")  # a byte-order mark is accepted
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(str(path), f"cannot read the scene file: "
                         f"{getattr(exc, 'strerror', None) or exc}") from None
    return parse_scene(text, path.stem)


def _sample(table: Mapping[str, Any]) -> tuple[int, int] | None:
    """``[impact] orders = N, seed = S``: a seeded sample of N orders (None: not asked)."""
    if "orders" not in table:
        if "seed" in table:
            raise InputError("impact.seed", "goes with orders = N (a sample of orders)")
        return None
    count, seed = table["orders"], table.get("seed", 0)
    for key, value in (("orders", count), ("seed", seed)):
        if not isinstance(value, int) or isinstance(value, bool) or value < 0:
            raise InputError(f"impact.{key}", f"must be a whole number >= 0, got {value!r}")
    if not 1 <= count <= MAX_SAMPLED_ORDERS:
        raise InputError("impact.orders", f"must lie in [1, {MAX_SAMPLED_ORDERS}], got {count}")
    return count, seed
