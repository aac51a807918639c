"""Three-dimensional scenes: a scene file whose vectors have three components.

The format is the plane's, one dimension up (docs/scenes.md, "Three dimensions"):
bodies of shape ``sphere`` (``mass``, ``radius``, optional central ``inertia``),
``rigid`` (``mass``, ``inertia`` as three principal moments or a 3 x 3 table,
``orientation = { axis = [..], angle = ".." }``) or ``fixed``, each free one with
``position``, ``velocity`` and ``spin = [wx, wy, wz]``; one ``[contact]`` with its two
``bodies``, its ``point`` and ``normal`` (three components each), ``restitution``,
``law`` and ``tangential`` (smooth, stick, coulomb with ``friction``, or rough with
``tangential_restitution`` and optionally ``friction``). ``[impact]``
may set ``tolerance`` to follow the contact numerically even where a closed form exists.
``[[planes]]`` (read by ``simulate`` past separation) are fixed planes a sphere may
strike later, each written as a contact: its ``point`` on the plane, its ``normal``, its
laws and the two ``bodies`` (a fixed one and a sphere); every sphere of the run may strike
every plane. ``[[pairs]]`` give the laws by which two spheres meet later (a cue ball and
an object ball): a ``name``, the two spheres as ``bodies`` and the laws, with no point
or normal (both are found where they meet).

Text from the file is read by the project's bounded expression parser, never by eval.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.joints import Joint
from rigidimpact.model.space import SPEEDS, Body3
from rigidimpact.scenes.scene import (
    Scene,
    _compliance,
    _contact_tables,
    _impact_table,
    _joints,
    _sample,
    _symbols_table,
    _table,
    _values_table,
    is_spatial,
    orders_extra,
    parse_expression,
    read_contact,
    read_toml,
    scene_from_data,
    vector,
)
from rigidimpact.solve.derivation import Derivation, Evaluation, exact_numbers, read_values
from rigidimpact.solve.registry import conduct
from rigidimpact.solve.rules import DEFAULT_RULE, Rule, RuleSettings, rule_named
from rigidimpact.solve.solution import Solution
from rigidimpact.solve.space import SpaceCollision
from rigidimpact.symbolic.distributions import RandomInputs, random_table
from rigidimpact.symbolic.notation import COMPONENTS, Given, labelled

__all__ = ["SpaceScene", "parse_space_scene", "space_scene_from_data", "load_space_scene",
           "load_any", "is_spatial"]

BODY_FIELDS = {"sphere": ("name", "shape", "mass", "radius", "inertia", "position",
                          "velocity", "spin"),
               "rigid": ("name", "shape", "mass", "inertia", "orientation", "position",
                         "velocity", "spin"),
               "fixed": ("name", "shape")}
CONTACT_FIELDS = ("name", "bodies", "point", "normal", "restitution", "law", "tangential",
                  "friction", "tangential_restitution")


@dataclass(frozen=True)
class SpaceScene:
    """A 3-D scene: its bodies and its contact, with symbols and values."""

    title: str
    symbols: Mapping[str, sp.Symbol]
    values: Mapping[sp.Symbol, sp.Expr]
    bodies: tuple[Body3, ...]
    contacts: tuple[Contact, ...]
    name: str = "scene"
    tolerance: float | None = None
    used: frozenset[sp.Symbol] = field(default=frozenset(), repr=False)
    simulate: Mapping[str, Any] = field(default_factory=dict, repr=False)
    facets: int | None = None
    rule: str = DEFAULT_RULE  # [impact] rule, a name of the one registry
    order: tuple[str, ...] | None = None
    joints: tuple[Joint, ...] = ()  # [[joints]]: ball joints and hinges
    random: RandomInputs | None = None  # [random]: symbols with a distribution
    compliance: tuple[tuple[float, ...], bool] = ((1e6,), False)  # [impact] stiffness
    planes: tuple[Contact, ...] = ()  # [[planes]]: fixed planes struck later (simulate)
    pairs: tuple[Contact, ...] = ()  # [[pairs]]: two spheres' laws when they meet later
    sample: tuple[int, int] | None = None  # [impact] orders = N, seed = S

    @property
    def impact_rule(self) -> Rule:
        """The ``[impact]`` rule as its object (the registry's, as in the plane)."""
        return rule_named(self.rule, RuleSettings(self.order, self.sample, self.compliance,
                                                  self.tolerance))

    @property
    def roles(self) -> tuple:
        """What bounds the data by role: in space each draw is checked by the solve
        itself (see :func:`_check_random` for the support's ends)."""
        return ()

    @property
    def contact(self) -> Contact:
        """The (first) contact."""
        return self.contacts[0]

    @property
    def data_symbols(self) -> dict[str, sp.Symbol]:
        return {str(s): s for s in sorted(self.used, key=str)}

    def collision(self, values: Mapping[sp.Symbol, Any] | None = None) -> SpaceCollision:
        problem = SpaceCollision(self.bodies, self.contacts, self.tolerance, self.facets,
                                 self.impact_rule, joints=self.joints,
                                 compliance=self.compliance)
        return problem.at(values) if values else problem

    def derivation(self, values: Mapping[sp.Symbol, Any] | None = None,
                   printed: bool = True) -> Derivation:
        """The impact in closed form where it has one (every law, Coulomb's cone when the
        slip cannot turn), else at `values` (the scene's ``[values]`` by default): the
        laws printed in vector form, the speeds after and the impulses."""
        start = time.perf_counter()
        notes: tuple[str, ...] = ()
        try:
            solution = self.collision(values).solve()
        except InputError as symbolic:
            if values is not None or "give numbers" not in symbolic.message:
                raise
            if not self.values:
                raise InputError("values", "this contact is followed numerically (its slip "
                                 "direction may turn): give the scene [values]") from None
            values = self.values
            solution = self.collision(values).solve()
            notes = ("solved at the scene's [values]: " + (
                "several 3-D contacts are followed numerically" if len(self.contacts) > 1
                else "the slip direction may turn, so the contact is followed numerically"),)
        collision = self.collision(values)
        setup = tuple(_described(b) for b in self.bodies) + tuple(
            _contact_words(c) for c in self.contacts) + tuple(
            f"joint {j.name}: {j.first} and {j.second} at {list(j.point)}, " + (
                "a ball joint" if j.axis is None else f"a hinge about {list(j.axis)}")
            for j in self.joints)
        setup += tuple(_contact_words(p, "plane", " (struck later, by simulate)")
                       for p in self.planes)
        setup += tuple(Given(f"pair {p.name}: {p.first} and {p.second} when they meet (by "
                             "simulate), ") + _law_words(p) for p in self.pairs)
        setup += tuple(Given("course: ") + _unnamed(c) for c in solution.courses)
        equations = _equations(collision) if printed else ()
        return Derivation(self.name, self.title, setup + notes + solution.notes, equations,
                          tuple(unknowns_at(collision, solution)),
                          solution.results(), solution=solution,
                          seconds=time.perf_counter() - start,
                          warnings=tuple(solution.warnings))

    def evaluate(self, settings: Mapping[str, Any], sources: Mapping[str, str],
                 dps: int | None = None, exact: bool = False) -> Evaluation:
        """Every result in numbers at `settings` (names to values; the scene's
        ``[values]`` are the defaults), with the course and the checks."""
        given = read_values(settings, dict(sources), self.data_symbols, (), self.name)
        missing = sorted(str(s) for s in self.used if s not in given)
        if missing:
            raise InputError("values", f"give a value for {', '.join(missing)}")
        outcomes = self.collision(given).outcomes()
        solution = outcomes[0]
        digits = dps or 17
        numbers = {k: float(sp.N(v, digits)) for k, v in solution.results().items()}
        extra: dict[str, Any] = {"rule": "one contact" if len(self.contacts) == 1 else
                                 conduct(solution.rule).spoken or solution.label,
                                 "acted": list(solution.acted)}
        if solution.checks:
            extra["checks"] = {k: float(v) for k, v in solution.checks.items()}
        if solution.courses:
            extra["courses"] = list(solution.courses)
        if solution.notes:
            extra["notes"] = list(solution.notes)
        extra.update(orders_extra(outcomes, self.impact_rule))
        return Evaluation(numbers, tuple(solution.warnings), solution.regime, extra,
                          exact_numbers(solution.results()) if exact else None)


def _described(b: Body3) -> Given:
    if b.support == "fixed":
        return Given(f"{b.name}: fixed")
    shape = Given("sphere of radius {}", b.radius) if b.radius is not None \
        else Given("rigid body")
    return Given(f"{b.name}: ") + shape + Given(
        ", mass {}, central inertia {}, centre {}, velocity {}, spin {}", b.mass,
        list(b.inertia), list(b.position), list(b.velocity), list(b.spin))


def _unnamed(course: str) -> str:
    """A contact's course without the contact's name before it (``name: course``)."""
    name = course.split(": ", 1)[0] + ": "
    if isinstance(course, Given):
        return Given(course.template[len(name):], *course.values)
    return course[len(name):]


def _law_words(c: Contact) -> Given:
    """A contact's laws in words: restitution, then the tangential law (its own)."""
    return Given(f"{c.laws[0].words()} e = {{}}, ", c.restitution) + \
        c.laws[1].words(spatial=True)


def _contact_words(c: Contact, kind: str = "contact", note: str = "") -> Given:
    """A contact's (or a plane's) line of the givens: where, and its laws."""
    t_1, t_2 = sp.symbols("t_1 t_2")
    return Given(f"{kind} {c.name}{note}: {c.first} and {c.second} at {{}}, normal {{}}, ",
                 list(c.point), list(c.normal)) + _law_words(c) + Given(
        "; tangents {} (the x axis across the normal, or the y axis's) and {} (the normal "
        "across {})", t_1, t_2, t_1)


def _equations(collision: SpaceCollision) -> tuple[Equation, ...]:
    """The laws in vector form, each holding at the solution (tested): every free body's
    momentum and angular momentum about its centre against the contact impulses
    ``P = P_n n + P_t1 t1 + P_t2 t2`` (world frame), and the contact's restitution law
    where it is Newton's (with several contacts: the striking one's)."""
    out = []
    impulses = {c.name: sp.Matrix(c.frame).T * sp.Matrix(_impulse(c))
                for c in collision.contacts}
    held = collision.G.T * sp.Matrix([x for j in collision.joints for x in _held(j)]) \
        if collision.joints else sp.zeros(6 * len(collision.free), 1)
    for k, body in enumerate(collision.free):
        after = sp.Matrix(_after(body))
        force, moment = held[6 * k:6 * k + 3, 0], held[6 * k + 3:6 * k + 6, 0]
        for c in collision.contacts:
            sign = 1 if body.name == c.second else -1 if body.name == c.first else 0
            arm = sp.Matrix(c.point) - sp.Matrix(body.position)
            force += sign * impulses[c.name]
            moment += sign * arm.cross(impulses[c.name])
        out.append(Equation(f"momentum of {body.name}", "",
                            sp.ImmutableMatrix(body.mass * (after[:3, 0]
                                                            - sp.Matrix(body.velocity))),
                            sp.ImmutableMatrix(force), law="momentum"))
        out.append(Equation(f"angular momentum of {body.name} about its centre", "",
                            sp.ImmutableMatrix(sp.Matrix(body.inertia) * (
                                after[3:, 0] - sp.Matrix(body.spin))),
                            sp.ImmutableMatrix(moment), law="momentum"))
    c = collision.contacts[0]
    after = sp.Matrix([x for b in collision.free for x in _after(b)])
    if len(collision.contacts) == 1 and not c.laws[0].splits_on_compression:
        J = collision.rows(c)  # a kinematic law: its normal velocity after, as it asks
        out.append(Equation(f"{c.laws[0].words()} at {c.name}".replace(
            ",", ""), "", (J * after)[0], c.laws[0].leaving((J * collision.u_before)[0]),
            law="restitution"))
    row = 0
    for j in collision.joints:  # the joint holds after: its bilateral rows are zero
        size = 3 if j.axis is None else 5
        out.append(Equation(f"joint {j.name} holds (the two bodies' points move together"
                            + (", and turn together across its axis)" if j.axis is not None
                               else ")"), "",
                            sp.ImmutableMatrix(collision.G[row:row + size, :] * after),
                            sp.ImmutableMatrix(sp.zeros(size, 1)), law="joint"))
        row += size
    return tuple(out)


def _held(j: Joint) -> tuple[sp.Symbol, ...]:
    """A joint's printed impulse on its second body (x, y, z; a hinge's two moments)."""
    return tuple(labelled(*COMPONENTS[k][:2], j.name) for k in (
        "impulse_x", "impulse_y", "impulse_z",
        *(() if j.axis is None else ("moment_1", "moment_2"))))


def _impulse(c: Contact) -> tuple[sp.Symbol, ...]:
    """The printed impulse of contact c along n, t1, t2 (named by the contact, as its
    result keys are)."""
    return tuple(labelled(*COMPONENTS[k][:2], c.name) for k in (
        "normal_impulse", "tangential_impulse_1", "tangential_impulse_2"))


AFTER = ("vx", "vy", "vz", "omega_x", "omega_y", "omega_z")  # result keys, as SPEEDS


def _after(body: Body3) -> list[sp.Symbol]:
    """The printed unknowns: a body's speeds after, named by the body (as its result
    keys are)."""
    return [labelled(*COMPONENTS[k][:2], body.name, after=True) for k in AFTER]


def unknowns_at(collision: SpaceCollision, solution: Solution) -> dict[sp.Symbol, sp.Expr]:
    """The printed equations' unknowns at the solution (for checking them)."""
    r = solution.results()
    values = {x: r[f"{b.name}.{s}"] for b in collision.free
              for x, s in zip(_after(b), SPEEDS, strict=True)}
    for c in collision.contacts:
        found = [r.get(f"{c.name}.{k}", sp.Integer(0)) for k in (
            "normal_impulse", "tangential_impulse_1", "tangential_impulse_2")]
        values |= dict(zip(_impulse(c), found, strict=True))
    for j in collision.joints:
        names = ["impulse_x", "impulse_y", "impulse_z"] + (
            [] if j.axis is None else ["moment_1", "moment_2"])
        values |= dict(zip(_held(j), (r[f"{j.name}.{k}"] for k in names), strict=True))
    return values


def _vector3(value: Any, where: str, symbols: Mapping[str, sp.Symbol]) -> tuple:
    return vector(value, where, symbols, 3)


def _read_body(table: Any, index: int, symbols: Mapping[str, sp.Symbol]) -> Body3:
    place = f"bodies[{index}]"
    if not isinstance(table, dict):
        raise InputError(place, "must be a table")
    shape = table.get("shape")
    if shape not in BODY_FIELDS:
        raise InputError(f"{place}.shape", f"a 3-D scene's shapes are "
                         f"{', '.join(BODY_FIELDS)}, not {shape!r}")
    for key in table:
        if key not in BODY_FIELDS[shape]:
            raise InputError(f"{place}.{key}", f"unknown field for a {shape}; expected "
                             f"{', '.join(BODY_FIELDS[shape])}")
    name = table.get("name", f"body{index}")
    if not isinstance(name, str) or not name.isidentifier():
        raise InputError(f"{place}.name", "must be an identifier")
    if shape == "fixed":
        return Body3.fixed(name)

    def scalar(key: str) -> sp.Expr:
        if key not in table:
            raise InputError(f"{place}.{key}", "required")
        return parse_expression(table[key], f"{place}.{key}", symbols)

    def vector(key: str) -> tuple:
        return _vector3(table.get(key, [0, 0, 0]), f"{place}.{key}", symbols)

    position, velocity, spin = vector("position"), vector("velocity"), vector("spin")
    if shape == "sphere":
        moment = scalar("inertia") if "inertia" in table else None
        return Body3.sphere(scalar("mass"), scalar("radius"), position, velocity, spin,
                            name, inertia=moment)
    raw = table.get("inertia")
    if not isinstance(raw, list) or len(raw) != 3:
        raise InputError(f"{place}.inertia", "three principal moments [I1, I2, I3] or a "
                         "3 x 3 table [[..], [..], [..]]")
    if all(isinstance(row, list) for row in raw):
        inertia: Any = sp.Matrix([list(_vector3(row, f"{place}.inertia[{i}]", symbols))
                                  for i, row in enumerate(raw)])
    else:
        inertia = _vector3(raw, f"{place}.inertia", symbols)
    orientation = None
    if "orientation" in table:
        spec = table["orientation"]
        if not isinstance(spec, dict) or set(spec) != {"axis", "angle"}:
            raise InputError(f"{place}.orientation", "a table { axis = [x, y, z], angle = "
                             "\"30 deg\" }: the turn from the body's axes to the scene's")
        orientation = (_vector3(spec["axis"], f"{place}.orientation.axis", symbols),
                       parse_expression(spec["angle"], f"{place}.orientation.angle",
                                        symbols))
    return Body3.rigid(scalar("mass"), inertia, position, velocity, spin, orientation, name)


def _read_contact(table: Any, symbols: Mapping[str, sp.Symbol], place: str = "contact",
                  named: bool = False) -> Contact:
    """A contact of a 3-D scene: the one contact reader, in space."""
    return read_contact(table, place, symbols, size=3, named=named)


def _read_contacts(data: Mapping[str, Any],
                   symbols: Mapping[str, sp.Symbol]) -> tuple[Contact, ...]:
    """``[contact]``, or the ``[[contacts]]`` entries (each named), as in the plane."""
    tables = _contact_tables(data)
    contacts = tuple(_read_contact(t, symbols, place, named=len(tables) > 1)
                     for t, place in tables)
    seen: set[str] = set()
    for (_, place), c in zip(tables, contacts, strict=True):
        if c.name in seen:
            raise InputError(f"{place}.name", f"two contacts are named {c.name!r}")
        seen.add(c.name)
    return contacts


def _read_planes(data: Mapping[str, Any], symbols: Mapping[str, sp.Symbol],
                 bodies: Sequence[Body3], contacts: Sequence[Contact]) -> tuple[Contact, ...]:
    """``[[planes]]``: fixed planes a sphere may strike after the impact, each read as a
    contact (its laws, its point on the plane, its normal), naming a fixed body and a
    free one; their names are their own and the contacts'."""
    entries = data.get("planes", [])
    if not isinstance(entries, list) or not all(isinstance(t, dict) for t in entries):
        raise InputError("planes", "[[planes]] must be tables, one a plane")
    support = {b.name: b.support for b in bodies}
    seen = {c.name for c in contacts}
    planes = []
    for k, t in enumerate(entries):
        where = f"planes[{k}]"
        if "name" not in t:
            raise InputError(f"{where}.name", "required: a plane's name")
        plane = _read_contact(t, symbols, where, named=True)
        if plane.name in seen:
            raise InputError(f"{where}.name", f"{plane.name!r} names another contact or "
                             "plane")
        seen.add(plane.name)
        kinds = sorted(support.get(b, "missing") == "fixed" for b in plane.bodies or ())
        if any(b not in support for b in plane.bodies or ()):
            raise InputError(f"{where}.bodies", "must name two of the scene's bodies")
        if kinds != [False, True]:
            raise InputError(f"{where}.bodies", "a plane belongs to a fixed body: name it "
                             "and the sphere that may strike it")
        planes.append(plane)
    return tuple(planes)


def _read_pairs(data: Mapping[str, Any], symbols: Mapping[str, sp.Symbol],
                bodies: Sequence[Body3], taken: Sequence[Contact]) -> tuple[Contact, ...]:
    """``[[pairs]]``: the laws of two spheres that meet later, each read as a contact
    whose point and normal are found where the two meet."""
    entries = data.get("pairs", [])
    if not isinstance(entries, list) or not all(isinstance(t, dict) for t in entries):
        raise InputError("pairs", "[[pairs]] must be tables, one a pair of spheres")
    spheres = {b.name for b in bodies if b.radius is not None and b.support != "fixed"}
    seen = {c.name for c in taken}
    met: set[frozenset] = set()
    pairs = []
    for k, t in enumerate(entries):
        where = f"pairs[{k}]"
        if "name" not in t:
            raise InputError(f"{where}.name", "required: a pair's name")
        for key in ("point", "normal"):
            if key in t:
                raise InputError(f"{where}.{key}", "a pair's point and normal are found "
                                 "where its spheres meet: leave it out")
        pair = _read_contact({**t, "normal": ["1", "0", "0"]}, symbols, where, named=True)
        if pair.name in seen:
            raise InputError(f"{where}.name", f"{pair.name!r} names another contact, plane "
                             "or pair")
        seen.add(pair.name)
        if not set(pair.bodies or ()) <= spheres or pair.first == pair.second:
            raise InputError(f"{where}.bodies", "two of the scene's free spheres")
        if frozenset(pair.bodies or ()) in met:
            raise InputError(f"{where}.bodies", f"{pair.first} and {pair.second} have "
                             "laws in another pair")
        met.add(frozenset(pair.bodies or ()))
        pairs.append(pair)
    return tuple(pairs)


def parse_space_scene(text: str, name: str = "scene") -> SpaceScene:
    """Read a 3-D scene from TOML text (see the module's text)."""
    return space_scene_from_data(read_toml(text), name)


def space_scene_from_data(data: dict[str, Any], name: str = "scene") -> SpaceScene:
    """A 3-D scene from its TOML, already read."""
    allowed = {"title", "symbols", "values", "bodies", "contact", "contacts", "impact",
               "simulate", "joints", "random", "planes", "pairs"}
    for key in data:
        if key not in allowed:
            raise InputError(key, f"unknown section in a 3-D scene; expected "
                             f"{', '.join(sorted(allowed))}")
    title = data.get("title", name)
    if not isinstance(title, str):
        raise InputError("title", "must be text")
    symbols = _symbols_table(_table(data, "symbols", "name = { assumption = true }"))
    values = _values_table(_table(data, "values", "name = number"), symbols)
    randoms = random_table(_table(data, "random", "name = { uniform = [a, b] }"), symbols)
    raw = data.get("bodies")
    if not isinstance(raw, list) or len(raw) < 2:
        raise InputError("bodies", "a 3-D scene needs at least two [[bodies]]")
    bodies = tuple(_read_body(t, i, symbols) for i, t in enumerate(raw))
    contacts = _read_contacts(data, symbols)
    joints = _read_joints(data, symbols, [b.name for b in bodies])
    tolerance, facets = None, None
    impact = _table(data, "impact", "settings")
    # the plane's reading of the rule, its order or sample and its springs; space adds
    # the integration's tolerance and the cone's facets
    rule, order = _impact_table(impact, [c.name for c in contacts], ("tolerance", "facets"))
    sample = _sample(impact)
    if "facets" in impact:
        facets = impact["facets"]
        if isinstance(facets, bool) or not isinstance(facets, int):
            raise InputError("impact.facets", f"a whole number, not {facets!r}")
    if "tolerance" in impact:
        value = impact["tolerance"]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                not 1e-14 <= value <= 1e-2:
            raise InputError("impact.tolerance", f"a number in [1e-14, 1e-2], not {value!r}")
        tolerance = float(value)
    planes = _read_planes(data, symbols, bodies, contacts)
    pairs = _read_pairs(data, symbols, bodies, contacts + planes)
    used = frozenset().union(*(x.free_symbols for b in bodies for x in (
        b.mass, *b.inertia, *b.position, *b.velocity, *b.spin)
        if isinstance(x, sp.Basic)), *(sp.sympify(x).free_symbols for c in contacts + planes + pairs
                                       for x in (c.restitution, c.friction or 0,
                                                 c.tangential_restitution or 0,
                                                 *c.point, *c.normal)))
    simulate = _table(data, "simulate", "settings")
    used |= frozenset().union(*(sp.sympify(x).free_symbols for j in joints
                                 for x in (*j.point, *(j.axis if j.axis is not None else ()))))
    compliance = _compliance(impact, len(contacts))
    scene = SpaceScene(title, symbols, values, bodies, contacts, name, tolerance, used,
                       simulate, facets, rule, order, joints, randoms, compliance, planes,
                       pairs, sample)
    scene.collision()  # its bodies, contacts, joints and rule agree
    if randoms is not None:
        _check_random(scene)
    return scene


def _check_random(scene: SpaceScene) -> None:
    """Each random input is a symbol the scene uses, and at each finite end of its
    support (the scene's other [values] held) the bodies still approach and every law
    holds: a draw there is an impact, as in the plane."""
    table = scene.random
    assert table is not None
    for symbol, law in table.inputs.items():
        if symbol not in scene.used:
            raise InputError(f"random.{symbol.name}", "the scene does not use this symbol")
        missing = sorted(str(s) for s in scene.used - set(scene.values) - {symbol})
        if missing:
            continue  # the ends are checked at numbers only
        for end in law.support:
            if not end.is_finite or (law.kind == "lognormal" and end == 0):
                continue  # an open end, never drawn
            try:
                scene.collision({**scene.values, symbol: end}).solve()
            except InputError as exc:
                raise InputError(f"random.{symbol.name}", f"at the end {end} of its "
                                 f"support: {exc.message}") from None


def _read_joints(data: Mapping[str, Any], symbols: Mapping[str, sp.Symbol],
                 names: Sequence[str]) -> tuple[Joint, ...]:
    """The ``[[joints]]`` of a 3-D scene (the plane's reader, with points [x, y, z]):
    each a `name`, the two `bodies` it joins, the `point` and, for a hinge, its `axis`
    (without one, a ball joint). A joint to a fixed body pivots the other."""
    return _joints(data, dict.fromkeys(names), symbols, _vector3, axis=True)


def load_space_scene(path: str | Path) -> SpaceScene:
    """Read a 3-D scene file."""
    return parse_space_scene(_read(path), Path(path).stem)


def load_any(path: str | Path) -> Scene | SpaceScene:
    """A scene file, planar or 3-D (three-component vectors make it 3-D); its TOML is
    read once."""
    data = read_toml(_read(path))
    if is_spatial(data):
        return space_scene_from_data(data, Path(path).stem)
    return scene_from_data(data, Path(path).stem)


def _read(path: str | Path) -> str:
    try:
        return Path(path).read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(str(path), f"cannot read the scene file: "
                         f"{getattr(exc, 'strerror', None) or exc}") from None
