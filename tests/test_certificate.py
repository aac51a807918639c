"""The certificate every Solution carries: a seeded property test over random scenes of
built-in shapes (discs and bars, 2 to 6 contacts, every law and rule) asserts that each
Solution's checks hold, or that its warnings name what they break; and the residuals
are computed apart from the solver (a Solution made wrong on purpose shows it)."""

from __future__ import annotations

import random
from dataclasses import replace

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from helpers import touching
from rigidimpact.errors import InputError
from rigidimpact.solve.collision import certified

LAWS = ("newton", "poisson", "energetic")
TRIPLES = [(3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25)]


def _q(rng: random.Random, low: int, high: int, d: int = 8) -> sp.Rational:
    return sp.Rational(rng.randint(low, high), d)


def random_cluster(rng: random.Random):
    """A striker disc and 1 to 5 discs around it, each touching it (and a floor under
    the striker half the time): 2 to 6 contacts, unit normals from Pythagorean triples."""
    triples = [(3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25), (20, 21, 29), (12, 35, 37)]
    law = rng.choice(LAWS)
    friction = rng.choice([None, None, _q(rng, 1, 8, 4)])
    striker = ri.Body.rigid(_q(rng, 4, 16), _q(rng, 1, 8), (0, 0),
                            (_q(rng, -8, 8), _q(rng, 2, 12)), _q(rng, -8, 8), name="s")
    bodies, contacts = [striker], []
    count = rng.randint(1, 5)
    for k, (a, b, c) in enumerate(rng.sample(triples, count)):
        sx, sy = rng.choice([(1, 1), (-1, 1)])
        n = (sp.Rational(sx * a, c), sp.Rational(sy * b, c))
        bodies.append(ri.Body.rigid(_q(rng, 4, 16), _q(rng, 1, 8), (2 * n[0], 2 * n[1]),
                                    (0, 0), name=f"d{k}"))
        contacts.append(touching(f"c{k}", "s", f"d{k}", n, n, _q(rng, 0, 4, 4), law,
                                 friction))
    if rng.random() < 0.5 or len(contacts) < 2:
        bodies.append(ri.Body.fixed("floor"))
        contacts.append(touching("ground", "s", "floor", (0, -1), (0, -1),
                                 _q(rng, 0, 4, 4), law, friction))
    rule = rng.choice([ri.Simultaneous(), ri.Compliant(), ri.Sequential(tuple(
        rng.sample([t.name for t in contacts], len(contacts))))])
    try:
        return ri.Collision(tuple(bodies), tuple(contacts)), rule
    except InputError:  # no contact approaches: no impact
        return None, rule


def test_every_solution_certifies_itself_or_says_why():
    rng, seen, refused, rules = random.Random(37), 0, 0, set()
    for _ in range(60):
        collision, rule = random_cluster(rng)
        if collision is None:
            refused += 1
            continue
        try:
            [solution] = collision.solve(rule)
        except InputError:  # no approach, or a law the rule has no form for: one line
            refused += 1
            continue
        seen += 1
        checks = solution.checks
        assert checks, "a numeric Solution always carries its checks"
        broken = {k for k, v in checks.items() if v != 0}
        if rule.name == "compliant":  # an integration: trusted to 1e-6 of the scale
            scale = max([abs(x) for x in solution.impulses.values()] +
                        [abs(v) for b in collision.bodies for v in b.velocity])
            broken = {k for k in broken if checks[k] > sp.Float(1e-6) * scale}
        if len(collision.contacts) == 1 or rule.name == "sequential":
            # the sequential rule ends below 1e-40 of the closing speeds
            broken = {k for k in broken if not (k.endswith(".opens") and checks[k] < 1e-35)}
        for key in broken:
            said = " ".join(solution.warnings)
            if key == "energy":
                assert "kinetic energy is created" in said, (key, solution.warnings)
            else:
                assert key.endswith(".opens") and "still approaches" in said, key
        rules.add(rule.name)
    assert seen >= 30 and refused < 30 and rules == {"simultaneous", "sequential",
                                                      "compliant"}


def test_the_residuals_are_computed_apart_from_the_solver():
    rng, solution = random.Random(5), None
    while solution is None:
        collision, rule = random_cluster(rng)
        try:
            [solution] = collision.solve(rule) if collision is not None else [None]
        except InputError:
            continue
    name = next(iter(solution.impulses))
    pushed = replace(solution, impulses={**solution.impulses,
                                         name: solution.impulses[name] + sp.Rational(1, 3)})
    assert any(v != 0 for k, v in pushed.checks.items() if "momentum" in k)
    with pytest.raises(InputError, match="fails its own check"):
        certified(pushed)


def test_poisson_acting_together_that_leaves_a_contact_closing_says_so():
    # Poisson's law scales each compression impulse by its own 1 + e, which need not
    # leave every contact opening: searched over seeded clusters, every such Solution
    # warns, in Python as on the command line
    rng, checked = random.Random(11), 0
    for _ in range(200):
        collision, _ = random_cluster(rng)
        if collision is None or len(collision.contacts) < 2 or \
                collision.contacts[0].law != "poisson" or collision.frictional:
            continue
        try:
            [solution] = collision.solve(ri.Simultaneous())
        except InputError:
            continue
        checked += 1
        closing = [k for k, v in solution.checks.items() if k.endswith(".opens") and v > 0]
        assert all(any(k.split(".")[0] in w and "still approaches" in w
                       for w in solution.warnings) for k in closing)
    assert checked >= 10


def test_a_sticking_contact_that_would_pull_says_so():
    # a bar (mass 1, inertia 1/3) whose end at O touches the floor, centre at (3/5, 4/5)
    # from it, sliding at (10, -1) without spin; sticking with e = 1/2 asks the end to
    # leave at (0, 1/2). By hand, with P = (Px, Py) the floor's impulse on the bar and
    # w+ = 3 (4 Px - 3 Py) / 5: 250 + 73 Px - 36 Py = 0 and 52 Py - 36 Px = 75/2, so
    # Py = -501/200: the floor would have to pull. The law's limit, said, not refused.
    bar = ri.Body.rigid(1, sp.Rational(1, 3), (sp.Rational(3, 5), sp.Rational(4, 5)),
                        (10, -1), 0, name="bar")
    solution = ri.Impact(bar, ri.Body.fixed("floor"), ri.Contact(
        normal=(0, -1), restitution=sp.Rational(1, 2), tangential="stick")).solve()
    assert solution.impulses["contact"] == sp.Rational(-501, 200)
    assert solution.checks["contact.pushes"] == sp.Rational(501, 200)
    assert any("contact would pull" in w for w in solution.warnings)


def test_the_two_body_core_refuses_an_answer_that_fails_its_check():
    # the one-contact core certifies what it returns: a broken answer is refused
    bar = ri.Body.rigid(1, sp.Rational(1, 3), (sp.Rational(3, 5), sp.Rational(4, 5)),
                        (1, -1), 0, name="bar")
    solution = ri.Impact(bar, ri.Body.fixed("floor"), ri.Contact(
        normal=(0, -1), restitution=sp.Rational(1, 2))).solve()
    assert max(solution.checks.values()) == 0
    broken = replace(solution, impulses={"contact": solution.impulses["contact"] * 2})
    with pytest.raises(InputError, match="fails its own check"):
        certified(broken)


def random_chain(rng: random.Random):
    """A chain of 1 to 3 point masses on massless links hinged at the origin (a
    sympy.physics.mechanics system), at angles whose sines are rational or not (atan of
    a Pythagorean ratio, or a plain 3/10), with 2 or 3 contacts at its joints."""
    links = rng.randint(1, 3)
    q = me.dynamicsymbols(f"q1:{links + 1}")
    u = me.dynamicsymbols(f"u1:{links + 1}")
    N = me.ReferenceFrame("N")
    point = me.Point("O")
    point.set_vel(N, 0)
    points, particles, values = [], [], {}
    for k in range(links):
        A = N.orientnew(f"A{k}", "Axis", [q[k], N.z])
        A.set_ang_vel(N, u[k] * N.z)
        P = point.locatenew(f"P{k}", -_q(rng, 2, 6, 4) * A.y)
        P.v2pt_theory(point, N, A)
        particles.append(me.Particle(f"p{k}", P, _q(rng, 2, 8, 4)))
        a, b, _ = rng.choice(TRIPLES)
        values[q[k]] = rng.choice([1, -1]) * rng.choice([sp.atan(sp.Rational(a, b)),
                                                         sp.Rational(3, 10)])
        values[u[k]] = _q(rng, -8, 8, 4)
        points.append(P)
        point = P
    kane = me.KanesMethod(N, q, u, [qi.diff() - ui for qi, ui in zip(q, u, strict=True)])
    kane.kanes_equations(particles, [])
    law = rng.choice(LAWS)
    tangential = rng.choice(["smooth", "stick", "coulomb"] if law == "newton"
                            else ["smooth", "coulomb"])
    contacts = []
    for k in range(rng.randint(2, 3)):
        extra = {"friction": _q(rng, 1, 8)} if tangential == "coulomb" else {}
        contacts.append(ri.mechanics.contact(
            rng.choice(points), rng.choice([N.x, -N.x, N.y, -N.y]),
            restitution=_q(rng, 0, 4, 4), law=law, tangential=tangential, name=f"c{k}",
            **extra))
    rule = rng.choice([ri.Simultaneous(), ri.Sequential(tuple(
        c.name for c in rng.sample(contacts, len(contacts))))])
    return ri.mechanics.impact(kane, contacts, frame=N).at(values), rule


def test_every_mechanics_solution_certifies_itself_or_says_why():
    # the same property for sympy.physics.mechanics systems: each Solution's residuals
    # (in the system's own coordinates) hold, or its warnings name what they break
    rng, seen, rules = random.Random(3), 0, set()
    for _ in range(50):
        system, rule = random_chain(rng)
        try:
            solution = system.solve(rule)
        except InputError:  # no approach, no acting set, a law with no form: one line
            continue
        seen += 1
        rules.add(rule.name)
        checks = solution.checks
        assert checks and "momentum" in checks
        scale = max([abs(x) for x in solution.impulses.values()] + [1])
        said = " ".join(solution.warnings)
        for key, value in checks.items():
            if value <= sp.Float(1e-30) * scale:
                continue
            if key == "energy":
                assert "created kinetic energy" in said, (key, value, solution.warnings)
            else:
                assert key.split(".")[0] in said, (key, value, solution.warnings)
    assert seen >= 15 and rules == {"simultaneous", "sequential"}


# ---- one contact's impulse path: friction piece by piece, each law's own end ---------

def _bar_on_rough_floor(law):
    """A bar (m = 1, I = 1/3) landing at (1/2, -1) without spin, its centre at (3/5, 4/5)
    from the touching point, on a floor with friction 1/2 and e = 1/2: slip stops during
    the impact (slip-stick), so the three restitution laws end it at three impulses."""
    from rigidimpact.laws.contact import Contact
    from rigidimpact.model.bodies import Body
    from rigidimpact.solve.impact import Impact

    R = sp.Rational
    bar = Body(mass=1, inertia=R(1, 3), position=(R(3, 5), R(4, 5)), velocity=(R(1, 2), -1),
               spin=0, name="bar")
    return Impact(Body.fixed("floor"), bar, Contact(
        normal=(0, 1), restitution=R(1, 2), law=law, tangential="coulomb",
        friction=R(1, 2))).solve()


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_each_law_is_checked_at_its_own_end_along_the_path(law):
    solution = _bar_on_rough_floor(law)
    assert solution.regime.startswith("slip-stick") and len(solution.path) == 3
    # exact where the answer is rational; the energetic end has a square root, checked
    # in 50-digit arithmetic
    tolerance = 1e-40 if law == "energetic" else 0
    assert solution.checks["contact.path"] <= tolerance
    assert solution.checks["contact.restitution"] <= tolerance
    # the same answer read under the other two laws breaks their ends (the three differ
    # on a bent path: Newton's P_n = 183/200, Poisson's 33/40, the energetic law's a root)
    for other in {"newton", "poisson", "energetic"} - {law}:
        read = replace(solution, contacts=(replace(solution.contacts[0], law=other),))
        assert read.checks["contact.restitution"] > 0, other


def test_friction_is_checked_piece_by_piece_along_the_path():
    solution = _bar_on_rough_floor("newton")
    start, corner, end = solution.path
    # slip runs until the corner: a straight path to the same end sticks from the start
    # while the bar still slips
    assert replace(solution, path=(start, end)).checks["contact.path"] > 0
    # friction turned along the slip on the first piece
    turned = replace(solution, path=(start, (corner[0], -corner[1]), end))
    assert turned.checks["contact.path"] > 0
    # a path that does not end at the impulse given
    assert replace(solution, path=(start, corner)).checks["contact.path"] > 0


# ---- one certificate, in the plane and in space ----

def _in_space(body):
    """A planar body written in space: z = 0, its spin about z, its central moment
    about every axis (a planar impulse turns it about z alone)."""
    from rigidimpact.model.space import Body3

    if body.support == "fixed":
        return Body3.fixed(body.name)
    return Body3.rigid(body.mass, (body.inertia,) * 3, (*body.position, 0),
                       (*body.velocity, 0), (0, 0, body.spin), name=body.name)


def _both_ways(solution, normal_shift=0):
    """The residuals of a planar one-contact answer, in the plane and written in space,
    with `normal_shift` added to its normal impulse (a wrong answer, the same in both)."""
    from rigidimpact.laws.contact import Contact
    from rigidimpact.solve.certificate import residuals

    c = solution.contact
    p_n = solution.impulses[c.name] + normal_shift
    p_t = solution.tangential.get(c.name, 0)
    plane = residuals(solution.before, solution.after, (c,), {c.name: p_n},
                      {c.name: p_t}, solution.rule, solution.acted)
    # in space the frame is (n, t1, t2) with t1 = (1, 0, 0) and t2 = (0, 0, -1) for the
    # normal (0, 1, 0): the planar tangent (-1, 0) is -t1
    twin = Contact(normal=(*c.normal, 0), restitution=c.restitution, tangential=c.tangential,
                   law=c.law, friction=c.friction, bodies=c.bodies, name=c.name,
                   point=(*c.point, 0))
    space = residuals(tuple(map(_in_space, solution.before)),
                      tuple(map(_in_space, solution.after)), (twin,), {c.name: p_n},
                      {c.name: (-p_t, 0)}, solution.rule, solution.acted)
    return plane, space


@pytest.mark.parametrize("shift", [0, sp.Rational(1, 3)])
@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_one_certificate_checks_the_plane_and_space_alike(law, shift):
    # the bar on a rough floor, right and (shifted) wrong, certified as a planar answer
    # and as the same answer written in space: every condition has one residual, so
    # each planar key has its twin with the same value, and the third dimension's are 0
    from rigidimpact.laws.contact import Contact
    from rigidimpact.model.bodies import Body
    from rigidimpact.solve.impact import Impact

    R = sp.Rational
    bar = Body(mass=1, inertia=R(1, 3), position=(R(3, 5), R(4, 5)),
               velocity=(R(1, 2), -1), spin=0, name="bar")
    solution = Impact(Body.fixed("floor"), bar, Contact(
        normal=(0, 1), restitution=R(1, 2), law=law, tangential="coulomb",
        friction=R(1, 2), name="floor")).solve()
    solution = replace(solution, path=())  # its path is planar: the conditions of the
    # totals, which both dimensions state
    plane, space = _both_ways(solution, shift)
    twin = {"angular_momentum": "angular_momentum_z"}
    compared = 0
    for key, value in plane.items():
        if key.startswith("_"):
            continue
        name, condition = key.rsplit(".", 1) if "." in key else ("", key)
        other = f"{name}.{twin.get(condition, condition)}" if name else key
        if other not in space:  # inside the cone the plane's slip can only stop or
            assert condition == "slides"  # reverse; in space it may turn: not stated
            continue
        assert abs(float(sp.sympify(value) - sp.sympify(space[other]))) < 1e-40, key
        compared += 1
    assert compared >= 7  # momentum (3), no pull, opening, the cone, energy
    for key in ("bar.momentum_z", "bar.angular_momentum_x", "bar.angular_momentum_y"):
        assert space[key] == 0
    # (the energetic law's answer has square roots: its residuals are 50-digit rounding)
    wrong = [k for k, v in plane.items() if not k.startswith("_") and float(v) > 1e-30]
    assert bool(wrong) == bool(shift)  # the shifted answer is caught, in both


def test_poisson_end_of_a_smooth_contact_in_space_is_checked():
    # a box's corner on a smooth floor: one contact's straight impulse path, so Poisson's
    # end (the whole impulse (1 + e) times the compression's) is checked in space as in
    # the plane; an impulse a third larger, with the bodies moved to match it (momentum
    # holds), breaks it. Before one certificate served both, a 3-D contact under
    # Poisson's law had its end checked by nothing.
    from rigidimpact.laws.contact import Contact
    from rigidimpact.model.space import Body3
    from rigidimpact.solve.certificate import residuals
    from rigidimpact.solve.space import SpaceCollision

    R = sp.Rational
    box = Body3.rigid(2, (R(1, 2), R(2, 3), R(5, 6)), (R(1, 2), R(1, 3), 1), (R(1, 4), 0, -1),
                      (1, -R(1, 2), R(1, 3)), name="box")
    floor = Contact(normal=(0, 0, 1), restitution=R(1, 2), law="poisson",
                    bodies=("floor", "box"), point=(0, 0, 0), name="floor")
    collision = SpaceCollision((Body3.fixed("floor"), box), (floor,))
    solution = collision.solve()
    assert solution.given_checks["floor.restitution"] == 0
    P = solution.impulses["floor"] * R(4, 3)
    u = collision.u_before + collision.M_inverse * collision.rows(floor).T * sp.Matrix(
        [P, 0, 0])
    moved = box.moved(u)
    found = residuals(collision.bodies, (collision.bodies[0], moved), (floor,),
                      {"floor": P}, {"floor": (0, 0)}, "simultaneous", ("floor",))
    assert all(found[k] == 0 for k in ("box.momentum_x", "box.angular_momentum_y"))
    assert found["floor.restitution"] > 0


def test_a_closed_form_is_certified_alike_walked_once_or_substituted_by_sympy(monkeypatch):
    # a symbolic answer is checked at seeded rational points of its symbols; its values
    # there are found by walking each expression once (symbolic/evaluate.py). SymPy's
    # own substitution, the way it was done before, is the reference: the same checks,
    # the same arithmetic (exact or 50 digits) and points, and every residual within
    # that arithmetic's tolerance both ways
    from rigidimpact.model.space import Body3
    from rigidimpact.paper import problems
    from rigidimpact.solve import certificate
    from rigidimpact.solve.space import SpaceCollision

    def ball():
        e, m, v = sp.symbols("e m v", positive=True)
        body = Body3.sphere(m, 1, (0, 0, 1), (1, sp.Rational(1, 2), -v), (3, -1, 2),
                            name="ball")
        floor = ri.Contact(normal=(0, 0, 1), restitution=e, tangential="coulomb",
                           bodies=("floor", "ball"), point=(0, 0, 0),
                           friction=sp.Symbol("mu", positive=True))
        return SpaceCollision((Body3.fixed("floor"), body), (floor,)).solve().given_checks

    def every():
        planar = [problems.barbell().solution, problems.two_body().solution,
                  problems.barbell_solution(0, "stick"), problems.discs().solution]
        return [type(s)._certificate.func(s) for s in planar] + [ball()]

    walked = every()

    def refused(*args, **kwargs):
        raise certificate.Unsupported("SymPy's way")

    monkeypatch.setattr(certificate, "value_at", refused)
    substituted = every()
    for ours, theirs in zip(walked, substituted, strict=True):
        assert ours["_symbolic"] and ours["_points"] >= 1
        assert ours.keys() == theirs.keys()
        for flag in ("_exact", "_floats", "_points"):
            assert ours[flag] == theirs[flag], flag
        tolerance = 0 if ours["_exact"] else 1e-35
        for key in ours:
            if not key.startswith("_"):
                assert float(ours[key]) <= tolerance and float(theirs[key]) <= tolerance, key
