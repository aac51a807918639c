"""Laws as objects: printed and imposed alike; a new law is one class."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from rigidimpact.laws import law as laws
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.impact import Impact


def test_contact_names_its_law_objects():
    restitution, tangential = Contact(restitution=sp.Rational(1, 2), tangential="stick").laws
    assert isinstance(restitution, laws.NewtonRestitution)
    assert restitution.e == sp.Rational(1, 2)
    assert isinstance(tangential, laws.Stick)


@dataclass(frozen=True, repr=False)
class TangentialRestitution(laws.ContactLaw):
    """The tangential velocity of the touching points reverses, scaled by k: one class,
    its one face in contact space (one tangent or two), nothing registered but its name."""

    k: sp.Expr = sp.Integer(1)
    name = "reverse"

    def linear_conditions(self, v_before, v_after, impulse, leaving):
        return [v_after[0] - leaving,
                *(v_after[i] + self.k * v_before[i] for i in range(1, len(v_before)))]


def test_a_new_law_is_one_class(monkeypatch):
    # Garwin's superball (k = 1, no spin before): W_tt = 1/m + r^2/I = 7/(2m), so the
    # centre keeps 1 - 2 (1 + k)/7 = 3/7 of its tangential velocity, the contact
    # point's tangential velocity reverses, and it leaves spinning at -(10/7) v_t / r.
    # The same class, with nothing written for any path, gives that answer through the
    # two-body derivation, every rule of the several-contact core, a mechanics system
    # and in space
    from rigidimpact.model.space import Body3
    from rigidimpact.solve.collision import Collision
    from rigidimpact.solve.rules import Driven, Sequential, Simultaneous
    from rigidimpact.solve.space import SpaceCollision

    monkeypatch.setitem(laws.TANGENTIAL_LAWS, "reverse", TangentialRestitution)
    ball = Body.sphere(1, 1, side=-1, velocity=(1, 1), name="ball")
    impact = Impact(ball, Body.fixed("floor"), Contact(restitution=1, tangential="reverse"))
    solution = impact.solve()
    after = solution.first_after
    assert after.velocity[1] == sp.Rational(3, 7)
    assert after.contact_velocity[1] == -ball.contact_velocity[1]
    assert after.velocity[0] == -1
    # printed from its one face: its row is the touching points' tangential velocity
    # after plus k times before, zero at the answer
    (printed,) = [eq for eq in impact.equations() if eq.law == "reverse"]
    assert printed.residual.free_symbols
    assert printed.residual.subs(solution.values) == 0
    assert solution.checks["contact.tangential_law"] == 0

    # the same ball in the several-contact core, under every rule
    rolled = Body.rigid(1, sp.Rational(2, 5), (0, 0), (1, -1), name="ball")
    floor = Contact((0, 1), 1, "reverse", name="floor", bodies=("floor", "ball"),
                    point=(0, -1))
    for rule in (Simultaneous(), Sequential(), Driven()):
        (out,) = Collision((rolled, Body.fixed("floor")), (floor,)).solve(rule)
        r = out.results()
        assert (r["ball.vx"], r["ball.vy"], r["ball.omega"]) == \
            (sp.Rational(3, 7), 1, -sp.Rational(10, 7)), rule
        assert out.checks["floor.tangential_law"] == 0

    # and as a sympy.physics.mechanics system (its contact rows from its own kinematics)
    import sympy.physics.mechanics as me

    import rigidimpact as ri

    x, y, th = me.dynamicsymbols("x y theta")
    ux, uy, w = me.dynamicsymbols("u_x u_y w")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", [th, N.z])
    A.set_ang_vel(N, w * N.z)
    C = me.Point("C")
    C.set_vel(N, ux * N.x + uy * N.y)
    below = C.locatenew("P", -N.y)
    below.v2pt_theory(C, N, A)
    kane = me.KanesMethod(N, [x, y, th], [ux, uy, w],
                          [x.diff() - ux, y.diff() - uy, th.diff() - w])
    kane.kanes_equations([me.RigidBody("ball", C, A, 1, (
        me.inertia(A, 0, 0, sp.Rational(2, 5)), C))], [])
    system = ri.mechanics.impact(kane, [ri.mechanics.contact(
        below, N.y, restitution=1, tangential="reverse", name="floor")], frame=N)
    out = system.at({x: 0, y: 0, th: 0, ux: 1, uy: -1, w: 0}).solve()
    assert list(out.speeds_after) == [sp.Rational(3, 7), 1, -sp.Rational(10, 7)]

    # and in space, sliding along both tangents: each keeps 3/7 of its velocity
    sphere = Body3.sphere(1, 1, (0, 0, 1), (1, 2, -1), name="ball")
    out = SpaceCollision((Body3.fixed("floor"), sphere), (Contact(
        normal=(0, 0, 1), restitution=1, tangential="reverse", bodies=("floor", "ball"),
        point=(0, 0, 0)),)).solve()
    r = out.results()
    assert (r["ball.vx"], r["ball.vy"], r["ball.vz"]) == \
        (sp.Rational(3, 7), sp.Rational(6, 7), 1)
    # the spin (5/2) r x P with r = (0, 0, -1), P_t = -(4/7)(1, 2): the touching point
    # leaves at v + w x r = -(1, 2), its slip reversed
    assert (r["ball.omega_x"], r["ball.omega_y"]) == (-sp.Rational(20, 7), sp.Rational(10, 7))
    assert out.checks["contact.tangential_law"] == 0


def test_an_answer_that_breaks_a_new_laws_own_conditions_is_refused(monkeypatch):
    # the same law whose impulse is computed wrongly (k taken as 1/2 in the impulse,
    # stated as 1 in its conditions): the certificate asks the law's own face and
    # refuses the answer rather than print it
    import pytest

    from rigidimpact.errors import InputError

    @dataclass(frozen=True, repr=False)
    class Careless(TangentialRestitution):
        def impulse(self, W, v_before, restitution, tolerance=None):
            return laws.ContactImpulse(TangentialRestitution(sp.Rational(1, 2))._linear(
                W, v_before, restitution), self.name)

    monkeypatch.setitem(laws.TANGENTIAL_LAWS, "reverse", Careless)
    ball = Body.sphere(1, 1, side=-1, velocity=(1, 1), name="ball")
    with pytest.raises(InputError, match="tangential_law"):
        Impact(ball, Body.fixed("floor"), Contact(restitution=1, tangential="reverse")).solve()


def test_a_new_restitution_law_is_one_class():
    # a perfectly inelastic law written as one class, with nothing registered elsewhere:
    # the impulse path ends where the normal velocity reaches zero. Routh's method takes
    # it through the object and must give Newton's law at e = 0.
    from rigidimpact.laws import routh
    from rigidimpact.laws.law import Coulomb, NewtonRestitution

    @dataclass(frozen=True, repr=False)
    class Inelastic(NewtonRestitution):
        e: sp.Expr = sp.Integer(0)
        name = "inelastic"

        def end_of_bent_path(self, first, second, v_n, stop_in_restitution):
            at_stop = v_n + first.rate[0] * second.start
            return second.start - at_stop / second.rate[0]

    W = sp.Matrix([[2, 1], [1, 2]])
    bent = 0
    for v in (sp.Matrix([-1, 1]), sp.Matrix([-1, sp.Rational(1, 5)])):
        for mu in (sp.Rational(1, 10), sp.Rational(1, 2), 2):
            ours = Coulomb(mu).regimes(W, v, Inelastic())
            newton = routh.regimes(W, v, mu, NewtonRestitution(0))
            assert [(r.name, r.impulse) for r in ours] == \
                [(r.name, r.impulse) for r in newton]
            bent += sum(len(r.path) == 3 for r in ours)  # slip stopped: the class's end
    assert bent >= 2


def test_a_law_written_only_as_printed_equations_is_refused_on_every_path(monkeypatch):
    # a law with printed equations and no contact-space face has nothing to solve with:
    # it is refused in one line by the two-body derivation and by every rule alike,
    # never taken for a smooth or a sticking contact
    import pytest

    from rigidimpact.errors import InputError
    from rigidimpact.solve.collision import Collision
    from rigidimpact.solve.rules import Sequential, Simultaneous

    @dataclass(frozen=True, repr=False)
    class Printed(laws.ContactLaw):
        name = "printed"

        def equations(self, before, after):
            v = after[1].contact_velocity[1] - after[0].contact_velocity[1]
            return (laws.Equation("no slip", "-", v, 0),)

    monkeypatch.setitem(laws.TANGENTIAL_LAWS, "printed", Printed)
    ball = Body.sphere(1, 1, side=-1, velocity=(1, 1), name="ball")
    with pytest.raises(InputError, match="no contact-space face"):
        Impact(ball, Body.fixed("floor"), Contact(restitution=1, tangential="printed")).solve()
    rolled = Body.rigid(1, sp.Rational(2, 5), (0, 0), (1, -1), name="ball")
    floor = Contact((0, 1), 1, "printed", name="floor", bodies=("floor", "ball"),
                    point=(0, -1))
    wall = Contact((-1, 0), 1, "smooth", name="wall", bodies=("ball", "floor"), point=(1, 0))
    for contacts in ((floor,), (floor, wall)):
        for rule in (Simultaneous(), Sequential()):
            with pytest.raises(InputError, match="no contact-space face"):
                Collision((rolled, Body.fixed("floor")), contacts).solve(rule)
