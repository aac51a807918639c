"""One contact, every law, every path: the two-body impact and every rule of the
several-contact collision give the same exact answer, because each law gives its own
one-contact impulse in contact space (``ContactLaw.impulse``) and every rule defers to it
when only one contact acts."""

from __future__ import annotations

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.errors import InputError
from rigidimpact.laws import law as law_module
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import NewtonRestitution
from rigidimpact.model.bodies import Body
from rigidimpact.solve.collision import Collision, Sequential, Simultaneous
from rigidimpact.solve.impact import Impact

HALF, TENTH = sp.Rational(1, 2), sp.Rational(1, 10)
LAWS = [("smooth", law, {}) for law in ("newton", "poisson", "energetic")] + [
    ("stick", "newton", {})] + [
    ("coulomb", law, {"friction": TENTH}) for law in ("newton", "poisson", "energetic")] + [
    ("rough", "newton", {"friction": HALF, "tangential_restitution": HALF})]


def _rod(tilt):
    # a rod (mass 1, inertia 1/3: half-length 1) whose end strikes a wall at O, its
    # centre at -(cos, sin) of a rational direction, moving in and down
    a, b = tilt
    length = sp.sqrt(a**2 + b**2)
    return Body.rigid(1, sp.Rational(1, 3), (-a / length, -b / length), (1, -HALF), 0, "rod")


@pytest.mark.parametrize(("tangential", "law", "coefficients"), LAWS)
@pytest.mark.parametrize("tilt", [(4, 3), (3, 4)])
def test_one_contact_gives_the_same_exact_answer_by_every_rule_and_law(tangential, law,
                                                                       coefficients, tilt):
    rod, wall = _rod(tilt), Body.fixed("wall")
    contact = Contact(restitution=HALF, tangential=tangential, law=law, **coefficients)
    alone = Impact(rod, wall, contact).solve().results()
    collision = Collision((rod, wall), (Contact(restitution=HALF, tangential=tangential,
                                                law=law, bodies=("rod", "wall"),
                                                **coefficients),))
    # solve() hands one contact to the two-body core; each rule's own solver, reached
    # directly, must agree with it (they are separate code: the rules' one-acting paths)
    solved = [collision.solve(rule)[0] for rule in (Simultaneous(), Sequential(("contact",)),
                                                      Sequential())]
    own = [collision.simultaneous(), collision.sequential(("contact",))]
    for outcome in solved + own:
        got = outcome.results()
        for key in ("rod.vx", "rod.vy", "rod.omega", "contact.normal_impulse",
                    "contact.tangential_impulse", "energy_loss_fraction"):
            assert sp.simplify(got[key] - alone[key]) == 0, (outcome, key, got[key],
                                                             alone[key])


@pytest.mark.parametrize("law", ["poisson", "energetic"])
def test_walton_takes_newtons_law_only(law):
    # Walton's law sets the velocities after with Newton's e: under another law it was
    # once read as Newton's without a word; now one line says so
    with pytest.raises(InputError, match="Walton's rough law takes Newton's restitution"):
        Contact(restitution=HALF, tangential="rough", law=law, friction=HALF,
                tangential_restitution=HALF)


def test_one_law_owns_its_one_contact_impulse():
    # a particle of mass 1/2 on a fixed floor (W = 2 I) at 45 degrees, e = 1: each law's
    # own impulse in contact space, worked by hand
    from rigidimpact.laws.law import Coulomb, NewtonRestitution, Rough, Smooth, Stick

    W, v = sp.Matrix([[2, 0], [0, 2]]), sp.Matrix([-1, 1])
    newton = NewtonRestitution(1)
    def own(law):
        out = law.impulse(W, v, newton)
        return (*out.impulse, out.course)

    assert own(Smooth()) == (1, 0, "smooth")
    assert own(Stick()) == (1, -HALF, "stick")  # P_t = -v_t / 2
    assert own(Coulomb(sp.Rational(1, 4))) == (1, -sp.Rational(1, 4), "slip")
    # Walton with beta = 1: the tangential velocity reverses, needing P_t = -1 (|P_t| <=
    # mu P_n holds with mu = 1)
    assert own(Rough(1, 1))[:2] == (1, -1)


def test_stick_and_rough_act_at_several_contacts_in_sequence():
    # two particles side by side drop onto a floor, one contact sticking and one rough:
    # in sequence each is its own one-contact impact (no coupling: W is diagonal)
    a = Body.rigid(1, 0, (0, 0), (1, -1), name="a")
    b = Body.rigid(1, 0, (5, 0), (2, -1), name="b")
    floor = Body.fixed("floor")
    contacts = (Contact((0, -1), HALF, "stick", name="left", bodies=("a", "floor")),
                Contact((0, -1), HALF, "rough", name="right", bodies=("b", "floor"),
                        point=(5, 0), friction=1, tangential_restitution=HALF))
    (outcome,) = Collision((a, b, floor), contacts).solve(Sequential(("left", "right")))
    r = outcome.results()
    # P_n = (1 + e) 1 = 3/2 at both. Stick: vx -> 0. Rough (beta = 1/2): reversing the
    # slip to -beta vx = -1 needs a tangential impulse of 3 > mu P_n = 3/2, so it is
    # capped there: vx = 2 - 3/2 = 1/2
    assert (r["a.vx"], r["a.vy"]) == (0, HALF)
    assert (r["b.vx"], r["b.vy"]) == (HALF, HALF)
    # the simultaneous rule: stick has a velocity-level form, Walton's law has none
    with pytest.raises(InputError, match="right.tangential: the rough law has no form"):
        Collision((a, b, floor), contacts).solve(Simultaneous())
    (both,) = Collision((a, b, floor), contacts[:1] + (Contact(
        (0, -1), HALF, "coulomb", name="right", bodies=("b", "floor"), point=(5, 0),
        friction=HALF),)).solve(Simultaneous())
    # Coulomb mu = 1/2 slides throughout: vx = 2 - mu P_n = 5/4
    assert (both.results()["a.vx"], both.results()["b.vx"]) == (0, sp.Rational(5, 4))


# ---- what is printed is what is solved, at several contacts --------------------------

def _residuals(collision, outcome):
    values = collision.solved_values(outcome)
    return [sp.nsimplify(eq.residual.xreplace(values)) if outcome.rule != "compliant"
            else float(eq.residual.xreplace(values)) for eq in collision.equations(outcome)]


@pytest.mark.parametrize(("name", "rule"), [
    (name, rule) for name in ("newtons-cradle", "rod-lands-flat", "rod-slides-flat",
                              "two-ball-drop")
    for rule in ("simultaneous", "sequential", "compliant")
    if (name, rule) != ("rod-slides-flat", "compliant")])  # compliant springs are smooth
def test_every_printed_equation_holds_at_the_outcome(name, rule):
    from dataclasses import replace
    from pathlib import Path

    from rigidimpact.scenes.scene import load_scene

    root = Path(__file__).parents[1]
    scene = load_scene(root / "derivations" / f"{name}.toml")
    values = {s: v for s, v in scene.values.items()}
    for symbol in scene.data_symbols.values():
        values.setdefault(symbol, sp.Rational(1, 2))  # e, mu left symbolic: a number
    order = tuple(c.name for c in scene.contacts)
    scene = replace(scene, rule=rule, order=order if rule == "sequential" else None)
    collision = scene.collision(values)
    for outcome in collision.solve(scene.impact_rule):
        equations = collision.equations(outcome)
        # one momentum balance per generalized velocity, and one law per contact (two
        # with friction) from the rule
        per_contact = 2 if collision.frictional else 1
        assert len(equations) == len(collision.coordinates) + per_contact * len(order)
        for residual in _residuals(collision, outcome):
            if rule == "compliant":
                assert residual == pytest.approx(0, abs=1e-9)
            else:
                assert residual == 0


@pytest.mark.parametrize("law", ["newton", "poisson"])
def test_the_simultaneous_rule_prints_each_contacts_own_law(law):
    # a striker between two touching balls (the cluster of the 30-degree test): under
    # Newton's law each acting contact's restitution, under Poisson's its compression
    # condition; substituting the outcome zeroes both
    r3, half = sp.sqrt(3), HALF
    bodies = (Body.rigid(1, 1, (0, 0), (1, 0), name="s"),
              Body.rigid(2, 1, (r3, 1), (0, 0), name="up"),
              Body.rigid(3, 1, (r3, -1), (0, 0), name="lo"))
    contacts = (Contact((r3, 1), half, law=law, name="a", bodies=("s", "up"),
                        point=(r3 / 2, half)),
                Contact((r3, -1), half, law=law, name="b", bodies=("s", "lo"),
                        point=(r3 / 2, -half)))
    collision = Collision(bodies, contacts)
    outcome = collision.simultaneous()
    labels = [eq.label for eq in collision.equations(outcome) if eq.law == "restitution"]
    assert len(labels) == 2
    assert all(("Newton" in label) == (law == "newton") for label in labels)
    assert all(residual == 0 for residual in _residuals(collision, outcome))


def test_a_pivoted_rod_struck_at_two_contacts_prints_its_equations(tmp_path, capsys):
    import json

    from helpers import hinged_rod_struck_twice, scene_file
    from rigidimpact.cli import main

    text = hinged_rod_struck_twice("poisson")
    assert main(["derive", scene_file(tmp_path, text), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    labels = [eq["label"] for eq in out["equations"]]
    assert "angular momentum of rod about its pivot: its change is the contacts' impulse" \
        in labels
    assert sum("Poisson's law" in label for label in labels) == 2
    assert {"rod.pivot_impulse_x", "rod.pivot_impulse_y"} <= set(out["results"])
    assert "omega_z^+_rod" in out["unknowns"] and "P_n^b" in out["unknowns"]
    assert main(["derive", scene_file(tmp_path, text)]) == 0
    printed = capsys.readouterr().out
    assert "poisson restitution 4/5, smooth" in printed
    assert "Equations solved:" in printed


# ---- a new restitution law is one class -----------------------------------------------

THRESHOLD = sp.Rational(1, 2)


class Threshold(NewtonRestitution):
    """Newton's e above a closing speed of 1/2, plastic below it: a threshold that
    granular codes use to stop slow contacts chattering. One class with one method: what
    it asks of a closing contact (`leaving`); every path and dimension asks that."""

    name = "threshold"

    def leaving(self, closing):
        return -(self.e if -closing > THRESHOLD else 0) * closing


def _balls(speeds, law):
    bodies = tuple(Body.rigid(1, sp.Rational(1, 10), (k, 0), (v, 0), name=f"b{k}")
                   for k, v in enumerate(speeds))
    contacts = tuple(Contact(restitution=HALF, law=law, name=f"c{k}",
                             bodies=(f"b{k}", f"b{k + 1}"), point=(k + HALF, 0))
                     for k in range(len(speeds) - 1))
    return Collision(bodies, contacts)


def test_a_new_restitution_law_is_one_class(monkeypatch):
    monkeypatch.setitem(law_module.RESTITUTION_LAWS, "threshold", Threshold)
    # one contact, every path: fast (closing 1): e = 1/2 acts, the balls leave at 1/4
    # and 3/4; slow (closing 1/4): plastic, both leave at 1/8 (hand derivation)
    for speed, expected in ((1, (sp.Rational(1, 4), sp.Rational(3, 4))),
                            (sp.Rational(1, 4), (sp.Rational(1, 8), sp.Rational(1, 8)))):
        pair = _balls((speed, 0), "threshold")
        single = Impact(pair.bodies[0], pair.bodies[1],
                        Contact(restitution=HALF, law="threshold")).solve().results()
        assert (single["b0.vx"], single["b1.vx"]) == expected
        for rule in (Simultaneous(), Sequential(("c0",))):
            (outcome,) = pair.solve(rule)
            assert (outcome.results()["b0.vx"], outcome.results()["b1.vx"]) == expected
    # three balls one at a time: c0 (closing 1) leaves 1/4, 3/4; c1 (closing 3/4) leaves
    # 3/16, 9/16; c0 again closes at 1/16, below the threshold, so it ends plastic at
    # 7/32 each; Newton's law alone would bounce it again
    (outcome,) = _balls((1, 0, 0), "threshold").solve(Sequential(("c0", "c1")))
    r = outcome.results()
    assert [r[f"b{k}.vx"] for k in range(3)] == [sp.Rational(7, 32), sp.Rational(7, 32),
                                                 sp.Rational(9, 16)]
    (newton,) = _balls((1, 0, 0), "newton").solve(Sequential(("c0", "c1")))
    assert newton.results()["b0.vx"] != r["b0.vx"]
    # the printed equation is the law's own
    (fast,) = _balls((1, 0), "threshold").solve(Simultaneous())
    printed = [eq for eq in _balls((1, 0), "threshold").equations(fast)
               if eq.law == "restitution"]
    assert [eq.rhs for eq in printed] == [sp.Rational(1, 2)]
    # the compliant rule has no form for it, and says so
    with pytest.raises(InputError, match="threshold law has no spring-dashpot form"):
        _balls((1, 0), "threshold").compliant()


def test_a_new_law_gives_the_same_answer_in_the_plane_and_in_space(monkeypatch):
    # a solid ball (m = 1, radius 1) lands slipping at (1, 0) on a floor with friction
    # 1/5, at a closing speed of 1 (above the threshold: e = 1/2) or 1/4 (plastic). By
    # hand: P_n = (1 + e) v; the ball (W_tt = 7/2) sticks if mu (7/2) P_n >= 1:
    # fast: P_n = 3/2, 21/20 >= 1, so it rolls off at 5/7; slow: P_n = 1/4, it slides
    # throughout, P_t = -P_n/5, and leaves at 19/20
    from dataclasses import replace

    from rigidimpact.model.space import Body3
    from rigidimpact.solve.space import SpaceCollision

    monkeypatch.setitem(law_module.RESTITUTION_LAWS, "threshold", Threshold)
    fifth = sp.Rational(1, 5)
    for speed, up, along in ((1, HALF, sp.Rational(5, 7)),
                             (sp.Rational(1, 4), 0, sp.Rational(19, 20))):
        ball = Body3.sphere(1, 1, (0, 0, 1), (1, 0, -speed), (0, 0, 0), name="ball")
        floor = Contact(normal=(0, 0, 1), restitution=HALF, law="threshold",
                        tangential="coulomb", friction=fifth, bodies=("floor", "ball"),
                        point=(0, 0, 0))
        bodies = (Body3.fixed("floor"), ball)
        exact = SpaceCollision(bodies, (floor,)).solve().results()  # closed form
        assert (exact["ball.vz"], exact["ball.vx"]) == (up, along)
        followed = SpaceCollision(bodies, (floor,), tolerance=1e-10).solve().results()
        assert abs(followed["ball.vz"] - up) < 1e-8 and abs(followed["ball.vx"] - along) < 1e-8
        smooth = SpaceCollision(bodies, (replace(floor, tangential="smooth",
                                                 friction=None),)).solve().results()
        assert (smooth["ball.vz"], smooth["ball.vx"]) == (up, 1)
        # the plane: a disc of the same mass and moment 2/5, one contact
        disc = Body.rigid(1, sp.Rational(2, 5), (0, 1), (1, -speed), name="ball")
        planar = Impact(Body.fixed("floor"), disc, Contact(
            normal=(0, 1), restitution=HALF, law="threshold", tangential="coulomb",
            friction=fifth)).solve().results()
        assert (planar["ball.vy"], planar["ball.vx"]) == (up, along)


def test_a_mechanics_system_prints_the_restitution_its_law_solved(monkeypatch):
    # a bob (mass 1, rod 1) hanging straight down and swinging at 1/4 into a wall: the
    # threshold law is plastic below a closing speed of 1/2, so u+ = 0; the printed
    # restitution must say so (it used to print Newton's -e v = 1/8 beside u+ = 0)
    monkeypatch.setitem(law_module.RESTITUTION_LAWS, "threshold", Threshold)
    q, u = me.dynamicsymbols("q u")
    frame = me.ReferenceFrame("N")
    arm = frame.orientnew("A", "Axis", [q, frame.z])
    arm.set_ang_vel(frame, u * frame.z)
    hinge = me.Point("O")
    hinge.set_vel(frame, 0)
    bob = hinge.locatenew("P", -arm.y)
    bob.v2pt_theory(hinge, frame, arm)
    kane = me.KanesMethod(frame, [q], [u], [q.diff() - u])
    kane.kanes_equations([me.Particle("b", bob, 1)], [])
    # the normal (-x) velocity after is -u+: plastic 0 at 1/4, e = 1/2 of 1 at 1
    for speed, after, leaving in ((sp.Rational(1, 4), 0, 0), (1, -HALF, HALF)):
        solution = ri.mechanics.impact(kane, [ri.mechanics.contact(
            bob, -frame.x, restitution=HALF, law="threshold", name="wall")],
            frame=frame).at({q: 0, u: speed}).solve()
        assert solution.speeds_after[0] == after
        [printed] = [eq for eq in solution.equations if eq.law == "restitution"]
        assert printed.rhs == leaving
        speeds = dict(zip(solution.unknowns, solution.speeds_after, strict=False))
        assert printed.lhs.subs(speeds) == leaving


def test_one_contact_reports_the_rule_it_was_asked_for():
    # one contact's answer is its own under every rule, but it is reported under the
    # rule asked for (it used to say "simultaneous" whatever the rule)
    pair = _balls((1, 0), "newton")
    (together,) = pair.solve(Simultaneous())
    (in_turn,) = pair.solve(Sequential(("c0",)))
    assert (together.rule, in_turn.rule, in_turn.order) == ("simultaneous", "sequential",
                                                            ("c0",))
    assert together.results() == in_turn.results()
