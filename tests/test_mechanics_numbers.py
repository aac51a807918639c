"""The mechanics bridge at numbers out of the rationals (angles such as pi/6 or 3/10):
solved in 50-digit floating point, chosen before any course or acting set is tried,
against a double pendulum's impact derived by hand here (M and the contact rows of two
point masses on massless links) and Routh's method written apart (tests/oracle.py)."""

from __future__ import annotations

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import oracle
import rigidimpact as ri
from oracle import mp

q1, q2, u1, u2 = me.dynamicsymbols("q1 q2 u1 u2")
m1, m2, l1, l2, g, e, mu = sp.symbols("m1 m2 l1 l2 g e mu", positive=True)


def _kane():
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", [q1, N.z])
    B = N.orientnew("B", "Axis", [q2, N.z])
    A.set_ang_vel(N, u1 * N.z)
    B.set_ang_vel(N, u2 * N.z)
    hinge = me.Point("O")
    hinge.set_vel(N, 0)
    P1 = hinge.locatenew("P1", -l1 * A.y)
    P1.v2pt_theory(hinge, N, A)
    P2 = P1.locatenew("P2", -l2 * B.y)
    P2.v2pt_theory(P1, N, B)
    kane = me.KanesMethod(N, [q1, q2], [u1, u2], [q1.diff() - u1, q2.diff() - u2])
    kane.kanes_equations([me.Particle("p1", P1, m1), me.Particle("p2", P2, m2)],
                         [(P1, -m1 * g * N.y), (P2, -m2 * g * N.y)])
    return kane, N, P1, P2


KANE, N, P1, P2 = _kane()
V = {m1: 1, m2: 1, l1: 1, l2: 1, e: sp.Rational(1, 2), q1: sp.Rational(3, 10),
     q2: -sp.Rational(1, 2), u1: 1, u2: 2}


def _tip(**kw):
    kw.setdefault("restitution", e)
    kw.setdefault("name", "tip")
    return ri.mechanics.impact(KANE, [ri.mechanics.contact(P2, -N.x, **kw)], frame=N)


def _by_hand(a, b):
    """M of two unit masses on unit links at angles a, b, and the tip's rows along -x
    (normal) and -y (tangent): P2' = (cos a u1 + cos b u2, sin a u1 + sin b u2)."""
    M = mp.matrix([[2, mp.cos(a - b)], [mp.cos(a - b), 1]])
    jn = mp.matrix([[-mp.cos(a), -mp.cos(b)]])
    jt = mp.matrix([[-mp.sin(a), -mp.sin(b)]])
    return M, jn, jt


def _newton(a, b, u, e_):
    M, jn, _ = _by_hand(a, b)
    Minv_j = mp.inverse(M) * jn.T
    closing = (jn * u)[0]
    return u - (1 + e_) * closing / (jn * Minv_j)[0] * Minv_j


def test_angles_with_two_roots_are_solved_not_crashed():
    # q = pi/6, pi/4: sqrt(2) and sqrt(6) in M and J (once SymPy's CoercionFailed)
    solution = _tip().at({**V, q1: sp.pi / 6, q2: sp.pi / 4}).solve()
    expected = _newton(mp.pi / 6, mp.pi / 4, mp.matrix([1, 2]), mp.mpf(1) / 2)
    got = [mp.mpf(str(x)) for x in solution.speeds_after]
    assert max(abs(got[i] - expected[i]) for i in range(2)) < mp.mpf(10) ** -40
    assert "50-digit floating point" in solution.notes[0]


def test_dependent_sticking_rows_at_any_angle_exact_and_float():
    # both points stick with e = 0 at q1 = q2: four conditions on two speeds, consistent
    # (both points at rest fixes u+ = 0); the least-norm impulses are shown
    both = ri.mechanics.impact(KANE, [
        ri.mechanics.contact(P1, -N.x, restitution=0, tangential="stick", name="elbow"),
        ri.mechanics.contact(P2, -N.x, restitution=0, tangential="stick", name="tip")],
        frame=N)
    for angle in (sp.Rational(1, 5), sp.Float(0.2), 0):
        values = {**V, q1: angle, q2: angle, u1: 1, u2: 1, e: 0}
        solution = both.at(values).solve()
        assert all(abs(x) < 1e-40 for x in solution.speeds_after), angle
        assert any("least-norm" in n for n in solution.notes)


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_friction_at_numbers_is_quick_and_gives_numbers(law):
    solution = _tip(law=law, tangential="coulomb", friction=mu).at(
        {**V, mu: sp.Rational(1, 2)}).solve()
    before, lost, fraction = solution.energies
    assert all(isinstance(x, sp.Float) for x in (before, lost, fraction))
    # Routh's method written apart, on the 2x2 W of the hand-derived M and rows
    a, b = mp.mpf(3) / 10, -mp.mpf(1) / 2
    M, jn, jt = _by_hand(a, b)
    Minv = mp.inverse(M)
    rows = [jn, jt]
    w = [[(r * Minv * s.T)[0] for s in rows] for r in rows]
    u = mp.matrix([1, 2])
    touch = oracle.Touch("tip", (0, 0), (1, 0), mp.mpf(1) / 2, mp.mpf(1) / 2, law)
    p_n, p_t = oracle.routh_w(w, (jn * u)[0], (jt * u)[0], touch)
    expected = u + Minv * (jn.T * p_n + jt.T * p_t)
    got = [mp.mpf(str(x)) for x in solution.speeds_after]
    assert max(abs(got[i] - expected[i]) for i in range(2)) < mp.mpf(10) ** -30
    if law != "newton":  # Poisson's and the energetic law never create energy
        assert lost > 0


def test_a_mechanics_solution_checks_itself_over_random_states():
    # a seeded sample of the double pendulum striking the wall with its tip, every law,
    # smooth and rough, exact and floating angles: each answer's residuals (taken from
    # M, J and the impulses, apart from the solve) hold, or its warnings say what not
    import random

    rng = random.Random(37)
    seen = 0
    for _ in range(12):
        law = rng.choice(["newton", "poisson", "energetic"])
        friction = rng.choice([None, sp.Rational(rng.randint(1, 8), 8)])
        kw = {"law": law} if friction is None else {
            "law": law, "tangential": "coulomb", "friction": friction}
        values = {**V, q1: sp.Rational(rng.randint(-8, 8), 10),
                  q2: sp.Rational(rng.randint(-8, 8), 10) if rng.random() < 0.5
                  else sp.pi / rng.randint(3, 8),
                  u1: rng.randint(1, 4), u2: rng.randint(1, 4), e: sp.Rational(1, 2)}
        try:
            solution = _tip(**kw).at(values).solve()
        except ri.InputError as error:  # not approaching: one line
            assert "no contact is approaching" in str(error)
            continue
        seen += 1
        checks = solution.checks
        assert checks["momentum"] < 1e-40
        assert checks["tip.pushes"] == 0 and checks["tip.opens"] == 0
        if checks["energy"] > 0:
            assert any("created kinetic energy" in w for w in solution.warnings)
    assert seen >= 6


def test_a_mechanics_answer_breaking_its_checks_is_refused():
    from dataclasses import replace

    from rigidimpact.solve.collision import certified

    solution = _tip().at({**V, q1: sp.pi / 6, q2: sp.pi / 4}).solve()
    assert solution.checks["momentum"] < 1e-40
    broken = replace(solution, given_checks={**solution.given_checks, "momentum": 1})
    with pytest.raises(ri.InputError, match="fails its own check"):
        certified(broken, limits=False)


def test_friction_in_floating_point_says_so():
    solution = _tip(tangential="coulomb", friction=mu).at(
        {**V, mu: sp.Rational(1, 2)}).solve()
    assert solution.notes == ("solved in 50-digit floating point (the numbers are out of "
                              "the rationals)",)


def test_a_pendulum_that_locks_against_the_floor_in_floats():
    # a bob (mass 1/2) on a rod of length 1/2 at q = 3/10, turning at 7/4 up into a
    # floor above it (Coulomb mu = 3/4, e = 1/4): its point can only move across the
    # rod, so the normal velocity and the slip stop together and the restitution impulse
    # along the cone's other edge would drive it in: the contact locks, u+ = 0. By hand,
    # the angular impulse about the hinge, -P_n (sin q + 3/4 cos q) / 2, takes away
    # m l^2 u = 7/32, so P_n = 7 / (16 (sin q + 3/4 cos q)). At 50 digits W's
    # determinant is rounding, not zero: the one-freedom course must still be found,
    # through the bridge's sequential rule (it gave NaN) and the built-in shapes
    # (refused: its check asked restitution's law of a locked contact).
    q, u = me.dynamicsymbols("q u")
    frame = me.ReferenceFrame("N")
    arm = frame.orientnew("A", "Axis", [q, frame.z])
    arm.set_ang_vel(frame, u * frame.z)
    hinge = me.Point("O")
    hinge.set_vel(frame, 0)
    bob = hinge.locatenew("P", -arm.y / 2)
    bob.v2pt_theory(hinge, frame, arm)
    kane = me.KanesMethod(frame, [q], [u], [q.diff() - u])
    kane.kanes_equations([me.Particle("b", bob, sp.Rational(1, 2))], [])
    angle = mp.mpf(3) / 10
    expected = 7 / (16 * (mp.sin(angle) + mp.mpf(3) / 4 * mp.cos(angle)))
    contacts = [ri.mechanics.contact(bob, -frame.y, restitution=sp.Rational(1, 4),
                                     tangential="coulomb", friction=sp.Rational(3, 4),
                                     name=name) for name in ("c0", "c1")]
    bridge = ri.mechanics.impact(kane, contacts, frame=frame).at(
        {q: sp.Rational(3, 10), u: sp.Rational(7, 4)}).solve(ri.Sequential(("c1", "c0")))
    assert abs(bridge.impulses["c0"] + bridge.impulses["c1"] - expected) < 1e-40
    assert abs(bridge.speeds_after[0]) < 1e-40
    at = (sp.sin(sp.Rational(3, 10)) / 2, -sp.cos(sp.Rational(3, 10)) / 2)
    body = ri.Body.rigid(sp.Rational(1, 2), 0, at, (sp.cos(sp.Rational(3, 10)) * 7 / 8,
                                                    sp.sin(sp.Rational(3, 10)) * 7 / 8),
                         sp.Rational(7, 4), name="bob", pivot=(0, 0))
    built = ri.Collision((body, ri.Body.fixed("floor")), (ri.Contact(
        normal=(0, 1), restitution=sp.Rational(1, 4), tangential="coulomb",
        friction=sp.Rational(3, 4), bodies=("bob", "floor"), point=at),)).simultaneous()
    assert built.courses == ("contact: slip-lock",) and built.after[0].spin == 0
    assert abs(built.impulses["contact"] - expected) < 1e-40


def test_two_sticking_points_where_only_the_tip_need_push():
    # elbow and tip both stick (e = 0) at q = (0.3, -0.4), u = (1, 1): the tip sticking
    # alone stops both speeds (u+ = 0: two stick conditions on two speeds) with the
    # elbow released, and its impulse is the one that does so, found here from the
    # hand-derived M and rows: M (0 - u) = jn^T P_n + jt^T P_t
    both = ri.mechanics.impact(KANE, [
        ri.mechanics.contact(P1, -N.x, restitution=0, tangential="stick", name="elbow"),
        ri.mechanics.contact(P2, -N.x, restitution=0, tangential="stick", name="tip")],
        frame=N)
    values = {**V, q1: sp.Rational(3, 10), q2: -sp.Rational(2, 5), u1: 1, u2: 1, e: 0}
    solution = both.at(values).solve()
    assert all(abs(x) < 1e-40 for x in solution.speeds_after)
    M, jn, jt = _by_hand(mp.mpf(3) / 10, -mp.mpf(2) / 5)
    rows = mp.matrix([[jn[0, 0], jt[0, 0]], [jn[0, 1], jt[0, 1]]])
    p = mp.lu_solve(rows, -(M * mp.matrix([1, 1])))
    assert abs(mp.mpf(str(solution.impulses["tip"])) - p[0]) < mp.mpf(10) ** -40
    assert p[0] > 0 and solution.impulses["elbow"] == 0


def test_a_friction_course_with_mu_left_a_symbol_is_refused_in_one_line():
    # at mu = 0.05 the tip's slip reverses, at larger mu it stops and sticks: a course
    # picked with mu left a symbol would hold for some mu only
    with pytest.raises(ri.InputError, match="depends on mu: give it a number"):
        _tip(tangential="coulomb", friction=mu).at(V).solve()
    assert _tip(tangential="coulomb", friction=mu).at(
        {**V, mu: sp.Rational(1, 20)}).solve().regime == "slip-reversal"


def _chain(links: int):
    """A chain of `links` point masses m on massless links of length l hanging from O, its tip
    striking a wall (normal -x) with Newton's e, every quantity a symbol."""
    q = me.dynamicsymbols(f"c1:{links + 1}")
    u = me.dynamicsymbols(f"w1:{links + 1}")
    m, length = sp.symbols("m l", positive=True)
    frame = me.ReferenceFrame("F")
    top = me.Point("T")
    top.set_vel(frame, 0)
    tip, particles = top, []
    for i in range(links):
        link = frame.orientnew(f"L{i}", "Axis", [q[i], frame.z])
        link.set_ang_vel(frame, u[i] * frame.z)
        point = tip.locatenew(f"Q{i}", -length * link.y)
        point.v2pt_theory(tip, frame, link)
        particles.append(me.Particle(f"b{i}", point, m))
        tip = point
    kane = me.KanesMethod(frame, q, u, [q[i].diff() - u[i] for i in range(links)])
    kane.kanes_equations(particles, [(p.point, -m * g * frame.y) for p in particles])
    system = ri.mechanics.impact(kane, [ri.mechanics.contact(tip, -frame.x, restitution=e,
                                                             name="tip")], frame=frame)
    return system, q, u, m, length


def test_a_closed_form_past_its_term_budget_is_refused_and_below_it_agrees():
    # a five-link chain with symbols ran past 200 s: its work (the symbols times the
    # product of its rows' terms, 1.4e7 here) is past the budget, so it is refused in
    # one line; the three-link chain's closed form, put at numbers, equals the answer
    # solved at those numbers (the same physics two ways), and its energy lost is the
    # kinetic energy before less after, computed here from M
    five = _chain(5)[0]
    with pytest.raises(ri.InputError, match="past the budget of 1e\\+07"):
        five.solve()
    three, q, u, m, length = _chain(3)
    closed = three.solve()
    point = {q[0]: sp.Rational(1, 5), q[1]: -sp.Rational(1, 3), q[2]: sp.Rational(1, 2),
             u[0]: 1, u[1]: -2, u[2]: 3, m: 2, length: sp.Rational(3, 2), e: sp.Rational(1, 2),
             g: 10}
    at = three.at(point).solve()
    for x, y in zip(closed.speeds_after, at.speeds_after, strict=True):
        assert abs(sp.N(x.xreplace(point), 50) - sp.N(y, 50)) < 1e-40


    def kinetic(speeds):  # mass i moves at l sum_{j <= i} w_j (cos c_j, sin c_j)
        total, vx, vy = 0, 0, 0
        for angle, w in zip((point[a] for a in q), speeds, strict=True):
            vx += point[length] * w * sp.cos(angle)
            vy += point[length] * w * sp.sin(angle)
            total += point[m] * (vx ** 2 + vy ** 2) / 2
        return total

    lost = kinetic([point[w] for w in u]) - kinetic(list(at.speeds_after))
    assert abs(sp.N(lost - at.energies[1], 50)) < 1e-40
    assert abs(sp.N(lost - closed.energies[1].xreplace(point), 50)) < 1e-40


# ---- the certificate reads the system's own kinematics, not the M and J solved with ---

def test_the_certificate_catches_a_wrong_jacobian():
    # the tip's normal row with one entry doubled: solved with that J and M, the old
    # residual M du - J^T P was zero; the system's own bodies and points say otherwise
    from dataclasses import replace

    hit = _tip().at(V)
    right = hit.solve()
    assert right.checks["momentum"] < 1e-40 and right.checks["tip.restitution"] < 1e-40
    J = sp.Matrix(hit.J)
    J[0, 1] *= 2
    with pytest.raises(ri.InputError, match="fails its own check.*momentum"):
        replace(hit, J=sp.ImmutableMatrix(J)).solve()


def test_the_certificate_reads_each_law_from_the_points_velocities():
    # Newton's e at one contact, from the tip's own velocity before and after:
    # v+ = -e v- (hand derivation in _newton), and the energy from the particles
    solution = _tip().at(V).solve()
    assert set(solution.checks) >= {"momentum", "tip.pushes", "tip.opens",
                                    "tip.restitution", "tip.smooth", "energy"}
    assert max(solution.checks.values()) < 1e-40
    expected = _newton(mp.mpf(3) / 10, -mp.mpf(1) / 2, mp.matrix([1, 2]), mp.mpf(1) / 2)
    got = [mp.mpf(str(x)) for x in solution.speeds_after]
    assert max(abs(got[i] - expected[i]) for i in range(2)) < mp.mpf(10) ** -40


def test_a_float_angle_is_solved_to_the_solves_digits():
    # 1/4 and -1/2 are exact in binary: the float angles are the same numbers as the
    # rationals, so the 50-digit answer must agree with the exact one to its digits
    # (cos(0.25) taken at the input's 15 digits once left 1e-17 between them)
    exact = _tip().at({**V, q1: sp.Rational(1, 4)}).solve()
    rounded = _tip().at({**V, q1: sp.Float(0.25), q2: sp.Float(-0.5)}).solve()
    assert "50-digit floating point" in rounded.notes[0]
    for a, b in zip(exact.speeds_after, rounded.speeds_after, strict=True):
        assert abs(sp.N(a, 60) - b) < 1e-45


def _bob(**laws):
    """A particle of mass m on a massless rod of length l hinged at O, striking a wall
    (normal x) with Newton's e (or the contact's `laws`): the closed form is u+ = -e u-."""
    q, u = me.dynamicsymbols("q_b u_b")
    mass, length = sp.symbols("m l", positive=True)
    frame, arm = me.ReferenceFrame("F"), me.ReferenceFrame("Arm")
    arm.orient_axis(frame, frame.z, q)
    arm.set_ang_vel(frame, u * frame.z)
    hinge = me.Point("H")
    hinge.set_vel(frame, 0)
    bob = hinge.locatenew("bob", -length * arm.y)
    bob.v2pt_theory(hinge, frame, arm)
    kane = me.KanesMethod(frame, [q], [u], [q.diff() - u])
    kane.kanes_equations([me.Particle("P", bob, mass)], [])
    laws.setdefault("restitution", e)
    return ri.mechanics.impact(kane, [ri.mechanics.contact(bob, frame.x, **laws)],
                               frame=frame), u


def test_a_closed_form_is_checked_at_random_points_by_the_systems_own_kinematics():
    from dataclasses import replace

    hit, u = _bob()
    solution = hit.solve()
    assert solution.speeds_after[0] == -e * u
    assert solution.given_checks["_points"] == 3
    assert set(solution.checks) >= {"momentum", "contact.restitution", "energy"}
    assert max(solution.checks.values()) < 1e-40
    # the closed form of a doubled Jacobian row (the same u+, half the impulse) is
    # caught by the bob's own momentum
    with pytest.raises(ri.InputError, match="fails its own check.*momentum"):
        replace(hit, J=sp.ImmutableMatrix(2 * sp.Matrix(hit.J))).solve()


def test_the_certificate_checks_friction_against_the_slip_in_a_mechanics_system():
    # the tip sliding on the wall throughout (mu = 1/20, q2 = -6/5): its answer holds
    # every law;
    # the same impulse with friction turned round, the speeds moved to match it (the
    # momentum balance, the cone and the normal law still hold), drives the slip after
    # instead of opposing it. The contact's laws are the built-in shapes' own statement
    # (certificate.contact_residuals), which now catches it here too.
    from rigidimpact.mechanics.certify import checks

    hit = _tip(tangential="coulomb", friction=sp.Rational(1, 20)).at(
        {**V, q2: -sp.Rational(6, 5)})
    right = hit.solve()
    assert right.regime == "slip"
    P = sp.Matrix([right.impulses["tip"], right.tangential["tip"]])
    assert checks(hit, sp.Matrix(right.speeds_after), P)["tip.against_slip"] < 1e-40
    turned = sp.Matrix([P[0], -P[1]])
    moved = sp.Matrix(hit.u_before) + sp.Matrix(hit.M).inv() * sp.Matrix(hit.J).T * turned
    found = checks(hit, moved, turned)
    assert found["momentum"] < 1e-40 and found["tip.cone"] < 1e-40
    assert found["tip.against_slip"] > 1e-3


def test_a_mechanics_contact_still_closing_after_is_caught_at_any_rule_but_sequential():
    # the plastic tip (e = 0) with its impulse short by a part in 10^14: the momentum
    # balance holds, the tip still closes at 1e-14 of its speed before. The built-in
    # shapes' certificate allows a closing speed only to the sequential rule, within
    # that rule's settling line (1e-40 of the largest speed); the system's certificate
    # allowed 1e-12 of it to every rule, and printed this answer.
    from rigidimpact.mechanics.certify import checks
    from rigidimpact.solve.certificate import assess

    hit = _tip(restitution=0).at(V)
    right = hit.solve()
    assert abs(right.tangential["tip"]) < 1e-45  # smooth
    P = sp.Matrix([right.impulses["tip"], 0])
    assert checks(hit, sp.Matrix(right.speeds_after), P)["tip.opens"] < 1e-45
    short = P * (1 - sp.Rational(1, 10 ** 14))
    moved = sp.Matrix(hit.u_before) + sp.Matrix(hit.M).inv() * sp.Matrix(hit.J).T * short
    found = checks(hit, moved, short)
    assert found["momentum"] < 1e-40
    closing = -(sp.Matrix(hit.J) * moved)[0]
    assert 0 < closing < 1e-13 * found["_scale"]
    assert found["tip.opens"] == pytest.approx(float(closing), rel=1e-9)
    for rule in ("simultaneous", "driven"):
        assert any(f.startswith("tip.opens") for f in assess(found, rule, right.contacts)[1])
    assert not any(f.startswith("tip.opens") for f in assess(
        {**found, "tip.opens": found["_scale"] * sp.Float(1e-41)}, "sequential",
        right.contacts)[1])


# ---- a 3-D contact's rows: sin^2 + cos^2 = 1 by the polynomials' normal form -----------

def test_a_3d_bodys_contact_rows_simplify_as_trigsimp_does():
    # a body turned by three angles (XYZ): its point's partial velocities along the
    # floor's normal are polynomials in the angles' sines and cosines. Their remainder
    # modulo sin^2 + cos^2 - 1 is trigsimp's own answer, term for term, where trigsimp
    # takes seconds each; along an oblique direction an equal form; a row that is not a
    # polynomial in them is left to trigsimp
    from rigidimpact.symbolic.rewrite import pythagorean as _pythagorean

    N = me.ReferenceFrame("N")
    a, b, c = me.dynamicsymbols("a b c")
    B = N.orientnew("B", "Body", [a, b, c], "XYZ")
    w = me.dynamicsymbols("w_x w_y w_z")
    B.set_ang_vel(N, w[0] * N.x + w[1] * N.y + w[2] * N.z)
    centre = me.Point("C")
    centre.set_vel(N, 0)
    r = sp.Symbol("r", positive=True)
    point = centre.locatenew("P", sp.Rational(1, 2) * B.x + r * B.y - sp.Rational(3, 4) * B.z)
    point.v2pt_theory(centre, N, B)
    partials = me.partial_velocity([point.vel(N)], list(w), N)[0]
    x = partials[0].dot(N.z)
    assert _pythagorean(x) == sp.trigsimp(x)
    oblique = partials[2].dot((N.x + N.y) / sp.sqrt(2))
    assert sp.expand(_pythagorean(oblique) - sp.trigsimp(oblique)) == 0
    # a square left after the reduction, or not a polynomial: trigsimp's own answer
    for x in (sp.sin(a) ** 2 + r * sp.cos(a) ** 2, sp.sin(a) / (1 + sp.cos(a) ** 2)):
        assert _pythagorean(x) == sp.trigsimp(x)
    assert _pythagorean(sp.sin(a) ** 2 * sp.sin(b) + sp.cos(a) ** 2 * sp.sin(b)) == sp.sin(b)


def test_the_impact_maps_kernel_agrees_with_the_double_pendulum_by_hand():
    # the compiled map over 50 seeded states in one call, against M and the tip's row
    # derived by hand here (Newton's law, every contact acting)
    import numpy as np

    rng = np.random.default_rng(7)
    q = rng.uniform(-1.2, 1.2, (50, 2))
    u = rng.uniform(-2, 2, (50, 2))
    into = np.cos(q[:, 0]) * u[:, 0] + np.cos(q[:, 1]) * u[:, 1]  # the tip's x speed
    u[into < 0] *= -1
    kernel = _tip().kernel({m1: 1, m2: 1, l1: 1, l2: 1, e: sp.Rational(1, 2)})
    found = kernel(q, u)
    assert kernel.rows == ("tip.n",) and not found.warnings
    for k in range(50):
        expected = _newton(q[k, 0], q[k, 1], mp.matrix(u[k].tolist()), mp.mpf(1) / 2)
        assert found.speeds_after[k].tolist() == pytest.approx(
            [float(x) for x in expected], rel=1e-12, abs=1e-12)
    # the same states moving away from the wall: a contact would pull, no speeds given
    away = kernel(q, -u)
    assert not away.honoured.any() and np.isnan(away.speeds_after).all()
    assert away.warnings[0].startswith("at 50 of 50 states a contact would pull")


def test_the_kernel_with_a_sticking_tip_agrees_with_solve_at_numbers():
    import numpy as np

    values = {m1: 1, m2: 2, l1: 1, l2: sp.Rational(3, 2)}
    hit = _tip(restitution=0, tangential="stick")
    kernel = hit.kernel(values)
    assert kernel.rows == ("tip.n", "tip.t")
    q, u = np.array([[0.3, -0.5]]), np.array([[1.0, 2.0]])
    found = kernel(q, u)
    exact = hit.at({**values, q1: sp.Rational(3, 10), q2: -sp.Rational(1, 2), u1: 1,
                    u2: 2}).solve()
    assert found.speeds_after[0].tolist() == pytest.approx(
        [float(x) for x in exact.speeds_after], rel=1e-12)


def test_the_kernel_refuses_what_it_cannot_map_in_one_line():
    with pytest.raises(ri.InputError, match="smooth or sticking contacts under a "
                       "restitution law at the velocity level"):
        _tip(tangential="coulomb", friction=mu).kernel({mu: sp.Rational(1, 3)})
    with pytest.raises(ri.InputError, match="needs a number for l1, l2, m1, m2"):
        _tip().kernel({e: 0})
    with pytest.raises(ri.InputError, match="restitution"):
        _tip().kernel({m1: 1, m2: 1, l1: 1, l2: 1})


def test_the_kernel_says_where_the_contacts_rows_depend_on_each_other():
    # a sticking tip of a single pendulum: one speed, two rows, W singular everywhere
    import numpy as np

    hit, _ = _bob(restitution=0, tangential="stick")
    m, length = sp.symbols("m l", positive=True)
    found = hit.kernel({m: 1, length: 1})(np.array([[0.2], [0.4]]), np.array([[-1.0], [-2.0]]))
    assert np.isnan(found.speeds_after).all() and not found.honoured.any()
    assert "singular" in found.warnings[0] and found.warnings[0].startswith("at 2 of 2")
