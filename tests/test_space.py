"""Impacts in three dimensions against hand derivations and against the planar theory.

- the spinning sphere landing on a floor (the case the mechanics bridge used to refuse),
  by hand: the floor's W is diag(1/m, 1/m + r^2/I, 1/m + r^2/I), the normal impulse
  (1 + e) m |v_n|, and the contact slides throughout or sticks by comparing the slip
  with mu (1 + e) |v_n| (1 + m r^2 / I);
- the same with symbols: the Piecewise of the closed form against that condition;
- a slender body landing on one end with its motion in a vertical plane: its W couples
  the normal and the tangent, so the path is integrated, and it must give Routh's exact
  planar answer (slip, stick or slip reversal) to the integration's tolerance;
- a body whose slip direction turns: the laws' residuals, the cone (the impulse's size
  below mu P_n where the direction turned), Newton's law and no energy created.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.analyses.cone import accuracy_ladder
from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.laws.cone import cone_impact, isotropic, tangents
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import NewtonRestitution, PoissonRestitution
from rigidimpact.model.space import Body3
from rigidimpact.scenes.space import unknowns_at
from rigidimpact.solve.space import SpaceCollision

HALF, FIFTH, QUARTER = sp.Rational(1, 2), sp.Rational(1, 5), sp.Rational(1, 4)


def _floor(e=HALF, mu=FIFTH, law="newton", tangential="coulomb"):
    return Contact(normal=(0, 0, 1), restitution=e, tangential=tangential, law=law,
                   friction=mu if tangential == "coulomb" else None,
                   bodies=("floor", "ball"), point=(0, 0, 0))


def _sphere(velocity, spin, radius=1, mass=1, inertia=None):
    return Body3.sphere(mass, radius, (0, 0, radius), velocity, spin, name="ball",
                        inertia=inertia)


def test_the_spinning_sphere_by_hand():
    # v = (1, 1/2, -2), spin (3, -1, 2): the lowest point slips at v + w x (0, 0, -1)
    # = (2, 7/2); P_n = (1 + e) * 2 = 3; sticking would need |v_t| / (7/2) = sqrt(65)/7
    # = 1.15 > mu P_n = 3/5: it slides throughout, P_t = -(3/5) (2, 7/2) / |(2, 7/2)|
    out = SpaceCollision((Body3.fixed("floor"), _sphere((1, HALF, -2), (3, -1, 2))),
                         (_floor(),)).solve()
    r = out.results()
    slip = sp.Matrix([2, sp.Rational(7, 2)])
    a, b = -sp.Rational(3, 5) * slip / sp.sqrt(slip.dot(slip))
    assert (r["contact.normal_impulse"], out.regime) == (3, "slides throughout")
    assert sp.simplify(r["contact.tangential_impulse_1"] - a) == 0
    assert sp.simplify(r["contact.tangential_impulse_2"] - b) == 0
    assert r["contact.tangential_impulse"] == sp.Rational(3, 5)
    # the centre takes P / m; the spin I^-1 (r x P) with r = (0, 0, -1): (5/2) (b, -a, 0)
    expected = {"ball.vx": 1 + a, "ball.vy": HALF + b, "ball.vz": 1,
                "ball.omega_x": 3 + sp.Rational(5, 2) * b,
                "ball.omega_y": -1 - sp.Rational(5, 2) * a, "ball.omega_z": 2}
    for key, value in expected.items():
        assert sp.simplify(r[key] - value) == 0, key
    assert all(v == 0 for v in out.checks.values())


def test_a_sphere_that_stops_slipping_leaves_rolling():
    # slip (1/2, 0) is less than mu (1 + e) |v_n| (7/2) = 21/10: it sticks before the
    # end, so its touching point leaves with no slip, and P_t = -(1/2) / (7/2) = -1/7
    out = SpaceCollision((Body3.fixed("floor"), _sphere((HALF, 0, -2), (0, 0, 0))),
                         (_floor(),)).solve()
    r = out.results()
    assert out.regime == "slides, then sticks"
    assert (r["contact.tangential_impulse_1"], r["contact.tangential_impulse_2"]) == \
        (-sp.Rational(1, 7), 0)
    # rolling: the lowest point's velocity v + w x (0, 0, -r) has x part v_x - w_y r = 0
    assert r["ball.vx"] - r["ball.omega_y"] * 1 == 0


def test_a_hollow_ball_and_the_laws_that_agree_on_a_sphere():
    # a thin shell (I = 2/3 m r^2): the tangential W is 1 + 3/2 = 5/2; Newton's,
    # Poisson's and the energetic law agree (the normal does not feel friction)
    answers = []
    for law in ("newton", "poisson", "energetic"):
        out = SpaceCollision((Body3.fixed("floor"), _sphere(
            (1, HALF, -2), (3, -1, 2), inertia=sp.Rational(2, 3))), (_floor(law=law),)
        ).solve()
        answers.append(out.results())
    assert answers[0] == answers[1] == answers[2]
    assert answers[0]["ball.vz"] == 1


def test_the_closed_form_with_symbols_is_a_piecewise_on_the_hand_condition():
    m, r, v, mu, e = sp.symbols("m r v mu e", positive=True)
    sx, sy = sp.symbols("s_x s_y", real=True)
    W = sp.diag(1 / m, sp.Rational(7, 2) / m, sp.Rational(7, 2) / m)
    out = cone_impact(W, (-v, sx, sy), NewtonRestitution(e), mu)
    p = (1 + e) * m * v
    assert sp.simplify(out.impulse[0] - p) == 0
    piece = out.impulse[1]
    assert isinstance(piece, sp.Piecewise)
    (slide, condition), (stick, _) = piece.args
    assert sp.simplify(slide + mu * p * sx / sp.sqrt(sx**2 + sy**2)) == 0
    assert sp.simplify(stick + sx * m * 2 / 7) == 0
    # the condition is mu (7/2) (1 + e) v <= |v_t|: true and false at chosen points
    at = {m: 1, v: 2, e: HALF, mu: FIFTH}
    assert bool(condition.subs(at | {sx: 2, sy: sp.Rational(7, 2)}))
    assert not bool(condition.subs(at | {sx: HALF, sy: 0}))


def test_the_tangents_are_the_documented_ones():
    n, t1, t2 = tangents((0, 0, 1))
    assert (list(t1), list(t2)) == ([1, 0, 0], [0, 1, 0])
    n, t1, t2 = tangents((1, 1, 0))
    assert sp.simplify(t1.dot(n)) == 0 and sp.simplify(t2 - n.cross(t1)) == sp.zeros(3, 1)
    assert t1[2] == 0 and t1[0] > 0  # the x axis's part across n


# ---- a slender body in a vertical plane: the 3-D path against Routh's exact answer ----

ROD_AXIS = sp.Matrix([[sp.Rational(4, 5), 0, -sp.Rational(3, 5)], [0, 1, 0],
                      [sp.Rational(3, 5), 0, sp.Rational(4, 5)]])  # body x along (4, 0, 3)/5


def _rod_3d(velocity, omega_y, mu, e, law):
    rod = Body3.rigid(1, (sp.Rational(1, 100), sp.Rational(1, 3), sp.Rational(1, 3)),
                      (sp.Rational(4, 5), 0, sp.Rational(3, 5)),
                      (velocity[0], 0, velocity[1]), (0, omega_y, 0), ROD_AXIS, name="ball")
    return SpaceCollision((Body3.fixed("floor"), rod), (Contact(
        normal=(0, 0, 1), restitution=e, tangential="coulomb", friction=mu, law=law,
        bodies=("floor", "ball"), point=(0, 0, 0)),))


def _rod_2d(velocity, omega_y, mu, e, law):
    # the plane x-z seen as the plane x-y: a turn w_y about y is -w_y about the out-of-plane
    # axis (x cross z = -y); the moment about y is the body's 1/3
    rod = ri.Body.rigid(1, sp.Rational(1, 3), (sp.Rational(4, 5), sp.Rational(3, 5)),
                        velocity, -omega_y, name="rod")
    return ri.Collision((ri.Body.fixed("floor"), rod), (ri.Contact(
        normal=(0, 1), restitution=e, tangential="coulomb", friction=mu, law=law,
        bodies=("floor", "rod"), point=(0, 0)),))


PLANAR = [((1, -1), 0, sp.Rational(3, 10)),          # slides forward
          ((sp.Rational(1, 10), -1), 0, sp.Rational(3, 10)),  # slip stops
          ((-sp.Rational(1, 5), -1), 1, sp.Rational(1, 10)),  # spins: slip may reverse
          ((0, -1), -1, sp.Rational(6, 10)),
          ((2, -sp.Rational(1, 2)), -3, sp.Rational(1, 2))]


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
@pytest.mark.parametrize("velocity,omega_y,mu", PLANAR)
def test_a_body_in_a_vertical_plane_gives_rouths_planar_answer(velocity, omega_y, mu, law):
    e = HALF
    space = _rod_3d(velocity, omega_y, mu, e, law)
    assert not isotropic(space.W(space.contacts[0]))  # no closed form of the cone
    (flat,) = _rod_2d(velocity, omega_y, mu, e, law).solve(ri.Simultaneous())
    planar = flat.results()
    pairs = {"ball.vx": planar["rod.vx"], "ball.vz": planar["rod.vy"],
             "ball.omega_y": -planar["rod.omega"], "ball.vy": 0, "ball.omega_x": 0,
             "ball.omega_z": 0, "contact.normal_impulse": planar["contact.normal_impulse"]}
    # the slip keeps to one line: Coulomb's law with one tangent, the plane's own
    # answer exactly, course and all
    exact = space.solve()
    assert exact.regime == flat.regime
    for key, value in pairs.items():
        assert sp.simplify(exact.results()[key] - value) == 0, (key, value)
    # followed numerically (a tolerance asked for), the cone's integration agrees
    out = replace(space, tolerance=1e-10).solve()
    r = out.results()
    for key, value in pairs.items():
        assert abs(float(r[key]) - float(value)) < 1e-7, (key, r[key], value)
    # the course: a slip reversal where Routh's method finds one, sticking where it does
    assert ("again" in out.regime) == flat.regime.startswith("slip-reversal"), out.regime
    assert ("sticks" in out.regime) == ("stick" in flat.regime), out.regime
    # the planar tangent is the normal turned +90 degrees: -x here, where t1 = +x
    assert abs(float(r["contact.tangential_impulse_1"])
               + float(planar["contact.tangential_impulse"])) < 1e-7


TURNED = sp.Matrix([[2, -1, 2], [2, 2, -1], [-1, 2, 2]]) / 3  # a rotation, rational


def test_a_slip_direction_that_turns_obeys_every_law():
    # a box landing on a corner, slipping obliquely: W's tangential block is neither
    # isotropic nor uncoupled, so the slip turns; the answer keeps each law
    box = Body3.rigid(2, (sp.Rational(1, 2), sp.Rational(1, 3), sp.Rational(2, 3)),
                      (sp.Rational(1, 2), sp.Rational(1, 3), sp.Rational(3, 4)),
                      (1, sp.Rational(1, 2), -2), (1, -2, sp.Rational(1, 2)),
                      TURNED, name="ball")
    for law in ("newton", "poisson", "energetic"):
        out = SpaceCollision((Body3.fixed("floor"), box), (_floor(
            mu=sp.Rational(3, 10), law=law),)).solve()
        r = out.results()
        assert out.notes and "integrated" in out.notes[0], law
        turned = float(out.notes[0].split("turned by ")[1].split(" degrees")[0])
        assert turned > 1, law  # the slip did turn
        checks = out.checks
        scale = max(abs(float(v)) for v in r.values())
        for key, value in checks.items():
            assert float(value) < 1e-7 * max(scale, 1), (law, key, value)
        size = math.hypot(float(r["contact.tangential_impulse_1"]),
                          float(r["contact.tangential_impulse_2"]))
        assert size <= 3 / 10 * float(r["contact.normal_impulse"]) * (1 + 1e-9)
        assert float(r["energy_loss_fraction"]) > 0


def test_the_integration_converges_to_the_exact_sphere_answer():
    W = sp.diag(1, sp.Rational(7, 2), sp.Rational(7, 2))
    exact = cone_impact(W, (-2, HALF, sp.Rational(1, 3)), PoissonRestitution(HALF), FIFTH)
    errors = []
    for tolerance in (1e-4, 1e-8, 1e-12):
        numeric = cone_impact(W, (-2, HALF, sp.Rational(1, 3)), PoissonRestitution(HALF), FIFTH,
                              tolerance=tolerance)
        errors.append(max(abs(float(a - b)) for a, b in zip(exact.impulse, numeric.impulse,
                                                            strict=True)))
    assert errors[0] < 1e-3 and errors[2] < 1e-9


def test_bad_3d_input_is_refused_in_one_line():
    ball = _sphere((1, 0, -1), (0, 0, 0))
    with pytest.raises(InputError, match="not approaching"):
        SpaceCollision((Body3.fixed("floor"), _sphere((1, 0, 1), (0, 0, 0))),
                       (_floor(),)).solve()
    with pytest.raises(InputError, match="Walton's rough law takes Newton's"):
        SpaceCollision((Body3.fixed("floor"), ball), (Contact(
            normal=(0, 0, 1), restitution=HALF, tangential="rough", friction=FIFTH,
            law="poisson", tangential_restitution=HALF, bodies=("floor", "ball")),)).solve()
    with pytest.raises(InputError, match="triangle"):
        Body3.rigid(1, (1, 1, 3))
    with pytest.raises(InputError, match="three components"):
        Body3.sphere(1, 1, (0, 0))


# ---- the same bodies as sympy.physics.mechanics systems: the bridge's tangent plane ----

def _six_speeds():
    """A free rigid body's frame N, coordinates q (centre, then XYZ body angles),
    speeds u (centre velocity, angular velocity in N), body frame B and centre C."""
    N = me.ReferenceFrame("N")
    q = me.dynamicsymbols("x y z a b c")
    u = me.dynamicsymbols("u_x u_y u_z w_x w_y w_z")
    B = N.orientnew("B", "Body", q[3:], "XYZ")
    B.set_ang_vel(N, u[3] * N.x + u[4] * N.y + u[5] * N.z)
    origin = me.Point("O")
    origin.set_vel(N, 0)
    C = origin.locatenew("C", q[0] * N.x + q[1] * N.y + q[2] * N.z)
    C.set_vel(N, u[0] * N.x + u[1] * N.y + u[2] * N.z)
    return N, q, u, B, C


def _free_body(inertia, centre, velocity, spin, point, e, mu, law="newton",
               tangential="coulomb", beta=None):
    """A free rigid body with six speeds (centre velocity, angular velocity in N) built
    with KanesMethod, striking the floor z = 0 at `point` (from its centre)."""
    N, q, u, B, C = _six_speeds()
    P = C.locatenew("P", point[0] * B.x + point[1] * B.y + point[2] * B.z)
    P.v2pt_theory(C, N, B)
    tensor = sp.Matrix(inertia)
    body = me.RigidBody("body", C, B, 1, (me.inertia(
        B, tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[1, 2],
        tensor[0, 2]), C))
    kane = me.KanesMethod(N, q, u, [a.diff() - b for a, b in zip(q, u, strict=True)])
    kane.kanes_equations([body], [])
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        P, N.z, restitution=e, tangential=tangential, friction=mu, law=law, name="floor",
        tangential_restitution=beta)],
        frame=N)
    return hit.at(dict(zip(q, [*centre, 0, 0, 0], strict=True))).at(
        dict(zip(u, [*velocity, *spin], strict=True))).solve()


def test_the_bridge_answers_the_spinning_sphere_it_used_to_refuse():
    # the 3-D issue's case: a free sphere (six speeds) on the floor, velocity (1, 1/2, -2),
    # spin (3, -1, 2), e = 1/2, mu = 1/5: refused before as "can only move straight
    # across"; its touching point slips at (2, 7/2) in the floor's plane
    out = _free_body(sp.eye(3) * sp.Rational(2, 5), (0, 0, 1), (1, HALF, -2), (3, -1, 2),
                     (0, 0, -1), HALF, FIFTH)
    r = out.results()
    slip = sp.Matrix([2, sp.Rational(7, 2)])
    a, b = -sp.Rational(3, 5) * slip / sp.sqrt(slip.dot(slip))
    by_hand = {"u_x": 1 + a, "u_y": HALF + b, "u_z": 1, "w_x": 3 + sp.Rational(5, 2) * b,
               "w_y": -1 - sp.Rational(5, 2) * a, "w_z": 2, "floor.normal_impulse": 3}
    for key, value in by_hand.items():
        assert sp.simplify(r[key] - value) == 0, key
    assert out.regime == "slides throughout"


@pytest.mark.parametrize("mu", [None, FIFTH])
def test_waltons_law_through_the_bridge_is_the_built_in_bodys(mu):
    # the tangential law's one face with two tangents serves the mechanics bridge too:
    # Walton's law (e = 1/2, beta = 1/2) at a spinning sphere's floor contact, limited
    # by friction or not, gives the built-in 3-D sphere's answer exactly
    bridge = _free_body(sp.eye(3) * sp.Rational(2, 5), (0, 0, 1), (1, HALF, -2), (3, -1, 2),
                        (0, 0, -1), HALF, mu, tangential="rough", beta=HALF).results()
    ball = Body3.sphere(1, 1, (0, 0, 1), (1, HALF, -2), (3, -1, 2), name="ball")
    ours = SpaceCollision((Body3.fixed("floor"), ball), (Contact(
        normal=(0, 0, 1), restitution=HALF, tangential="rough", friction=mu,
        tangential_restitution=HALF, bodies=("floor", "ball"), point=(0, 0, 0)),)
                          ).solve().results()
    for theirs, mine in zip(["u_x", "u_y", "u_z", "w_x", "w_y", "w_z"],
                            ["vx", "vy", "vz", "omega_x", "omega_y", "omega_z"], strict=True):
        assert sp.simplify(bridge[theirs] - ours[f"ball.{mine}"]) == 0, theirs


def test_a_turned_box_gives_the_same_answer_from_both_sources():
    # the box whose slip turns: built-in 3-D body and its mechanics twin, one contact
    # solver, the same speeds to the integration's tolerance
    corner = (sp.Rational(1, 2), sp.Rational(1, 3), -sp.Rational(3, 4))  # from the centre
    touching = (0, 0, 0)
    shifted = Body3.rigid(1, (sp.Rational(1, 2), sp.Rational(1, 3), sp.Rational(2, 3)),
                          tuple(-x for x in corner), (1, HALF, -2), (1, -2, HALF), TURNED,
                          name="ball")
    ours = SpaceCollision((Body3.fixed("floor"), shifted), (Contact(
        normal=(0, 0, 1), restitution=HALF, tangential="coulomb", friction=sp.Rational(3, 10),
        bodies=("floor", "ball"), point=touching),)).solve().results()
    theirs = _free_body(shifted.inertia, tuple(-x for x in corner), (1, HALF, -2),
                        (1, -2, HALF), corner, HALF, sp.Rational(3, 10)).results()
    names = dict(zip(["u_x", "u_y", "u_z", "w_x", "w_y", "w_z"],
                     ["vx", "vy", "vz", "omega_x", "omega_y", "omega_z"], strict=True))
    for theirs_key, ours_key in names.items():
        assert abs(float(theirs[theirs_key]) - float(ours[f"ball.{ours_key}"])) < 1e-8
    assert abs(float(theirs["floor.normal_impulse"])
               - float(ours["contact.normal_impulse"])) < 1e-8


# ---- 3-D scene files: derive and evaluate from the command line and from Python ----

DERIVATIONS = Path(__file__).resolve().parents[1] / "derivations"


@pytest.mark.parametrize("name", ["spinning-ball-floor", "box-corner-floor",
                                  "cushion-rebound"])
def test_a_3d_scene_derives_with_equations_that_hold(name):
    scene = ri.load_any(DERIVATIONS / f"{name}.toml")
    assert isinstance(scene, ri.SpaceScene)
    d = scene.derivation()
    values = dict(scene.values) if name != "spinning-ball-floor" else {}
    collision = scene.collision(values or None)
    at = unknowns_at(collision, d.solution)
    assert set(d.unknowns) == set(at)
    for eq in d.equations:
        residual = sp.Matrix([eq.residual]) if not isinstance(eq.residual, sp.MatrixBase) \
            else sp.Matrix(eq.residual)
        residual = residual.xreplace(at)
        if name == "spinning-ball-floor":  # closed forms with symbols, in both courses
            for point in ({"m": 1, "r": 1, "e": HALF, "mu": FIFTH},
                          {"m": 2, "r": HALF, "e": sp.Rational(1, 3), "mu": 1}):
                numbers = {scene.symbols[k]: v for k, v in point.items()}
                assert all(abs(sp.N(x.xreplace(numbers), 30)) < 1e-25 for x in residual), \
                    eq.label
        else:
            assert all(abs(float(x)) < 1e-12 for x in residual), eq.label


def test_the_spinning_ball_scene_gives_the_hand_answer_from_the_command_line(capsys):
    assert main(["evaluate", str(DERIVATIONS / "spinning-ball-floor.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    slip = math.hypot(2, 3.5)
    assert out["ball.vz"] == pytest.approx(1.0, abs=1e-15)
    assert out["contact.tangential_impulse_1"] == pytest.approx(-0.6 * 2 / slip, rel=1e-14)
    assert out["ball.omega_y"] == pytest.approx(-1 + 2.5 * 0.6 * 2 / slip, rel=1e-14)
    assert out["regime"] == "slides throughout"
    # the second course: a small slip sticks before the end
    assert main(["evaluate", str(DERIVATIONS / "spinning-ball-floor.toml"), "--set", "mu=1",
                 "--json"]) == 0
    stuck = json.loads(capsys.readouterr().out)
    assert stuck["regime"] == "slides, then sticks"
    # rolling after: the lowest point's slip (v_x - w_y r, v_y + w_x r) is zero
    assert abs(stuck["ball.vx"] - stuck["ball.omega_y"]) < 1e-14
    assert abs(stuck["ball.vy"] + stuck["ball.omega_x"]) < 1e-14


def test_a_3d_scene_is_refused_in_one_line_where_it_is_not_read(tmp_path, capsys):
    with pytest.raises(InputError, match="3-D scene"):
        ri.load_scene(DERIVATIONS / "spinning-ball-floor.toml")
    bad = (DERIVATIONS / "box-corner-floor.toml").read_text().replace(
        'inertia = ["1/2", "1/3", "2/3"]', 'inertia = ["1/2", "1/3", "3"]')
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    assert main(["evaluate", str(path)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "triangle" in err[0]


def test_the_integration_buys_accuracy_with_steps():
    # the accuracy ladder of docs/three-d.md: tighter tolerances, smaller errors against
    # the exact answers (closed form, Routh) and the tight reference
    rows = accuracy_ladder((1e-4, 1e-10), repeats=1)
    by_case: dict[str, list] = {}
    for row in rows:
        by_case.setdefault(row["case"], []).append(row)
    for case, (loose, tight) in by_case.items():
        assert tight["error"] <= max(loose["error"], 1e-14), case
        assert tight["error"] < 1e-9, case
        assert tight["steps"] >= loose["steps"], case


def test_waltons_rough_law_in_3d_by_hand():
    # the spinning sphere with beta = 1/2, mu = 1/5: reversing the slip (2, 7/2) at half
    # its size needs P_t = -(3/2) (2, 7/2) / (7/2) = (-6/7, -3/2), |P_t| = 1.73 > mu P_n
    # = 3/5: it slides throughout, as under Coulomb's law; with mu = 1 it reverses
    def rough(mu):
        contact = Contact(normal=(0, 0, 1), restitution=HALF, tangential="rough",
                          friction=mu, tangential_restitution=HALF, bodies=("floor", "ball"))
        return SpaceCollision((Body3.fixed("floor"), _sphere((1, HALF, -2), (3, -1, 2))),
                              (contact,)).solve()
    slid = rough(FIFTH)
    assert slid.regime == "slides throughout"
    assert slid.results()["contact.tangential_impulse"] == sp.Rational(3, 5)
    back = rough(1)
    r = back.results()
    assert back.regime == "tangential restitution"
    assert (r["contact.tangential_impulse_1"], r["contact.tangential_impulse_2"]) == \
        (-sp.Rational(6, 7), -sp.Rational(3, 2))
    # the lowest point leaves slipping at -(1/2) of (2, 7/2): v - w_y r, v_y + w_x r
    assert (r["ball.vx"] - r["ball.omega_y"], r["ball.vy"] + r["ball.omega_x"]) == \
        (-1, -sp.Rational(7, 4))
    assert all(v == 0 for v in back.checks.values())


# ---- several 3-D contacts: one strikes, the others rest ----

def _resting_ball(velocity, spin, wall_mu=FIFTH, floor_mu=FIFTH, wall_law="newton"):
    """A unit solid sphere on the floor z = 0 striking the wall x = 1 (normal -x)."""
    ball = _sphere(velocity, spin)
    wall = Contact(normal=(-1, 0, 0), restitution=HALF, tangential="coulomb",
                   friction=wall_mu, law=wall_law, name="wall", bodies=("w", "ball"),
                   point=(1, 0, 1))
    floor = Contact(normal=(0, 0, 1), restitution=0, tangential="coulomb",
                    friction=floor_mu, name="floor", bodies=("floor", "ball"),
                    point=(0, 0, 0))
    return SpaceCollision((Body3.fixed("w"), Body3.fixed("floor"), ball), (wall, floor))


def test_a_wall_at_the_equator_leaves_the_floor_idle_and_acts_as_alone():
    # the wall touches the ball at its equator: its normal is horizontal, and so is its
    # friction (the slip there is horizontal and stays so), so nothing presses the ball
    # into the floor: the floor takes nothing and the wall acts as it would alone, whose
    # answer is the one-contact closed form (the slip stops: 1 < mu (7/2) (3/2))
    out = _resting_ball((1, 1, 0), (0, 0, 0)).solve()
    alone = SpaceCollision((Body3.fixed("w"), _sphere((1, 1, 0), (0, 0, 0))), (Contact(
        normal=(-1, 0, 0), restitution=HALF, tangential="coulomb", friction=FIFTH,
        name="wall", bodies=("w", "ball"), point=(1, 0, 1)),)).solve()
    r, a = out.results(), alone.results()
    for key in ("ball.vx", "ball.vy", "ball.omega_z", "wall.normal_impulse"):
        assert float(r[key]) == pytest.approx(float(a[key]), rel=1e-9)
    assert float(r["floor.normal_impulse"]) == pytest.approx(0.0, abs=1e-12)


def test_several_3d_contacts_are_refused_in_one_line_where_not_solved():
    ball = _sphere((1, 0, -1), (0, 0, 0))
    wall = Contact(normal=(-1, 0, 0), restitution=HALF, name="wall", bodies=("w", "ball"),
                   point=(1, 0, 1))
    floor = Contact(normal=(0, 0, 1), restitution=HALF, name="floor",
                    bodies=("floor", "ball"), point=(0, 0, 0))
    bodies = (Body3.fixed("w"), Body3.fixed("floor"), ball)
    both = SpaceCollision(bodies, (wall, floor)).solve()  # both strike, smooth: exact
    assert "exact" in both.notes[-1]
    r = both.results()  # the normals are orthogonal through the centre: each its own
    assert (r["ball.vx"], r["ball.vz"]) == (-HALF, HALF)
    rough = tuple(replace(c, tangential="coulomb", friction=FIFTH) for c in (wall, floor))
    both = SpaceCollision(bodies, rough).solve()  # with friction: the circular cone
    assert "circular cone" in both.notes[0]
    both = SpaceCollision(bodies, rough, facets=8).solve()  # or a pyramid
    assert "pyramid of 8 edges" in both.notes[0]
    # a smooth contact has no cone: the pyramid changes nothing, and the answer is exact
    smooth = SpaceCollision(bodies, (wall, floor), facets=8).solve()
    assert smooth.results() == SpaceCollision(bodies, (wall, floor)).solve().results()
    assert "exact" in smooth.notes[-1]
    # a sticking floor under the default rule (the simultaneous one, as in the plane):
    # the floor's point leaves at rest along the floor, its normal speed e times 1
    stuck = SpaceCollision(bodies, (wall, replace(floor, tangential="stick"))).solve()
    r = stuck.results()
    assert float(r["ball.vz"]) == pytest.approx(0.5, abs=1e-12)
    slip = float(r["ball.vx"]) - float(r["ball.omega_y"]) * 1  # v + omega x (0, 0, -1)
    assert slip == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(InputError, match="driven rule follows Coulomb"):
        SpaceCollision(bodies, (wall, replace(floor, tangential="stick")), rule="driven")\
            .solve()
    x = sp.Symbol("x", positive=True)
    with pytest.raises(InputError, match="give numbers"):
        SpaceCollision((Body3.fixed("w"), Body3.fixed("floor"), _sphere((x, 0, 0), (0, 0, 0))),
                       (wall, floor)).solve()
    with pytest.raises(InputError, match="share a name"):
        SpaceCollision(bodies, (wall, replace(floor, name="wall")))


def test_a_resting_contact_that_would_pull_lets_go():
    # the wall's nose below the equator pushes the ball up and back: the floor would
    # have to pull to hold it, so it lets go at once and the ball leaves the floor
    ball = _sphere((2, 0, 0), (0, 0, 0))
    c, s = sp.Rational(24, 25), sp.Rational(7, 25)
    wall = Contact(normal=(-c, 0, s), restitution=HALF, tangential="coulomb",
                   friction=FIFTH, name="wall", bodies=("w", "ball"), point=(c, 0, 1 - s))
    floor = Contact(normal=(0, 0, 1), restitution=0, tangential="coulomb", friction=FIFTH,
                    name="floor", bodies=("floor", "ball"), point=(0, 0, 0))
    bodies = (Body3.fixed("w"), Body3.fixed("floor"), ball)
    out = SpaceCollision(bodies, (wall, floor), rule="driven").solve()
    r = out.results()
    assert float(r["floor.normal_impulse"]) == pytest.approx(0.0, abs=1e-12)
    assert float(r["ball.vz"]) > 0
    assert "lets go" in out.regime
    # the default rule (simultaneous) releases the floor too, with the same speeds
    default = SpaceCollision(bodies, (wall, floor)).solve()
    assert "floor: released" in default.regime
    for key, value in default.results().items():
        assert float(value) == pytest.approx(float(r[key]), rel=1e-9, abs=1e-12), key


# ---- several 3-D contacts striking at once: the cone as a pyramid ----

def _cube(velocity, facets=8, e=0, mu=QUARTER, law="newton"):  # facets None: the cone
    """A cube of side 2 (mass 1, I = 2/3) landing flat on its four corners."""
    cube = Body3.rigid(1, (sp.Rational(2, 3),) * 3, (0, 0, 1), velocity, (0, 0, 0),
                       name="box")
    corners = tuple(Contact(normal=(0, 0, 1), restitution=e, tangential="coulomb",
                            friction=mu, law=law, name=f"c{i}", bodies=("floor", "box"),
                            point=(x, y, 0))
                    for i, (x, y) in enumerate(((-1, -1), (1, -1), (1, 1), (-1, 1))))
    return SpaceCollision((Body3.fixed("floor"), cube), corners, facets=facets)


@pytest.mark.parametrize("facets", [4, 8, 16])
@pytest.mark.parametrize("e", [0, HALF])
def test_a_cube_landing_flat_on_four_corners_by_hand(facets, e):
    # the corners push in all (1 + e) m v_z, friction mu times that along -x (the slip is
    # along x, an edge of every pyramid here): v_x = 1/2 - mu (1 + e), no turn
    out = _cube((HALF, 0, -1), facets, e).solve()
    r = {k: float(v) for k, v in out.results().items()}
    assert r["box.vz"] == pytest.approx(float(e), abs=1e-12)
    assert r["box.vx"] == pytest.approx(0.5 - 0.25 * (1 + float(e)), abs=1e-12)
    for k in ("vy", "omega_x", "omega_y", "omega_z"):
        assert r[f"box.{k}"] == pytest.approx(0.0, abs=1e-12)
    assert max(float(x) for x in out.checks.values()) < 1e-12
    total = sum(r[f"c{i}.normal_impulse"] for i in range(4))
    assert total == pytest.approx(1 + float(e), abs=1e-12)
    for i in range(4):
        assert r[f"c{i}.tangential_impulse"] <= 0.25 * r[f"c{i}.normal_impulse"] + 1e-12


def test_the_pyramid_approaches_the_cone_as_its_edges_multiply():
    # sliding at 25.7 degrees, between edges: the circular cone's answer keeps the slip's
    # direction and takes mu m v_z off its speed (by symmetry the cube does not turn);
    # the pyramid's friction points within 180/facets degrees of it and is no larger, so
    # the velocity after is within mu (1 + e) v_z pi/facets of the cone's
    a = math.pi / 7
    cone = (0.25 * math.cos(a), 0.25 * math.sin(a))
    for facets in (8, 16, 32, 64, 128):
        out = _cube((sp.cos(sp.pi / 7) / 2, sp.sin(sp.pi / 7) / 2, -1), facets).solve()
        r = out.results()
        gap = math.hypot(float(r["box.vx"]) - cone[0], float(r["box.vy"]) - cone[1])
        assert gap <= 0.25 * math.pi / facets, facets
        assert max(float(x) for x in out.checks.values()) < 1e-12


@pytest.mark.parametrize("angle", [0, sp.pi / 7, sp.pi / 3])
@pytest.mark.parametrize("e", [0, HALF])
def test_the_circular_cone_gives_the_hand_answer_at_every_angle(angle, e):
    # with no facets the cone itself: every corner slides straight against the slip,
    # which keeps its direction (by symmetry the cube does not turn), and the speed
    # across loses mu (1 + e) v_z whatever the direction
    velocity = (sp.cos(angle) / 2, sp.sin(angle) / 2, -1)
    out = _cube(velocity, facets=None, e=e).solve()
    r = {k: float(v) for k, v in out.results().items()}
    left = 0.5 - 0.25 * (1 + float(e))
    assert r["box.vx"] == pytest.approx(left * math.cos(float(angle)), abs=1e-12)
    assert r["box.vy"] == pytest.approx(left * math.sin(float(angle)), abs=1e-12)
    assert r["box.vz"] == pytest.approx(float(e), abs=1e-12)
    for k in ("omega_x", "omega_y", "omega_z"):
        assert r[f"box.{k}"] == pytest.approx(0.0, abs=1e-12)
    assert "circular cone" in out.notes[0]
    assert max(float(x) for x in out.checks.values()) < 1e-12
    assert {c.split(": ")[1] for c in out.courses} == {"slides"}


def test_the_circular_cone_holds_a_corner_that_sticks():
    # slower across than the cone can stop (mu (1 + e) v_z = 1/4 > 1/5): every corner
    # sticks and the cube stops across, inside its cone
    out = _cube((sp.Rational(1, 5), 0, -1), facets=None).solve()
    r = {k: float(v) for k, v in out.results().items()}
    assert max(abs(r[f"box.{k}"]) for k in ("vx", "vy", "vz")) < 1e-12
    for i in range(4):
        assert r[f"c{i}.tangential_impulse"] < 0.25 * r[f"c{i}.normal_impulse"]
    assert {c.split(": ")[1] for c in out.courses} == {"sticks"}


def test_several_striking_contacts_are_refused_where_not_solved():
    with pytest.raises(InputError, match="takes Newton's law at every contact"):
        _cube((HALF, 0, -1), law="poisson").solve()
    with pytest.raises(InputError, match="even whole number"):
        _cube((HALF, 0, -1), facets=7)


def test_the_compliant_rule_in_space_is_the_planar_one():
    # three balls in a row along x (a cradle), every contact a spring-dashpot of the same
    # stiffness, e = 1: the 3-D rule runs the planar rule's one implementation, so the
    # cradle written in space gives the planar chain's speeds to the integration's digits
    from rigidimpact.solve.collision import chain

    balls = tuple(Body3.sphere(1, HALF, (k, 0, 0), (1 if k == 0 else 0, 0, 0),
                               name=f"ball{k}") for k in range(3))
    contacts = tuple(Contact(normal=(1, 0, 0), restitution=1, name=f"c{k}",
                             bodies=(f"ball{k}", f"ball{k + 1}"), point=(k + HALF, 0, 0))
                     for k in range(2))
    space = SpaceCollision(balls, contacts, rule="compliant").solve()
    flat = chain(3).compliant().results()
    r = space.results()
    assert space.rule == "compliant" and not space.warnings
    for k in range(3):
        assert abs(float(r[f"ball{k}.vx"]) - float(flat[f"ball{k}.vx"])) < 1e-9
    # momentum to the integration's digits, and the energy kept (e = 1)
    assert abs(sum(float(r[f"ball{k}.vx"]) for k in range(3)) - 1) < 1e-9
    assert abs(float(space.energy_lost)) < 1e-6
    stiffer = SpaceCollision(balls, contacts, rule="compliant",
                             compliance=((1e6, 1e8), False)).solve().results()
    assert stiffer["ball2.vx"] != r["ball2.vx"]  # the stiffnesses' ratio decides


def _ball_in_a_corner(rule, order=(), velocity=(1, HALF, -2)):
    """A solid ball (m = 1, r = 1, I = 2/5) with six speeds built with KanesMethod, its
    centre at (0, 0, 1), moving at (1, 1/2, -2) and spinning at (3, -1, 2) into a
    corner: the floor z = 0 (e = 1/2, mu = 1/5) and the wall x = 1 (e = 1/2, mu =
    3/10). The mechanics bridge and the built-in 3-D ball, solved by `rule`."""
    N, q, u, B, C = _six_speeds()
    low = C.locatenew("low", -N.z)
    low.v2pt_theory(C, N, B)
    side = C.locatenew("side", N.x)
    side.v2pt_theory(C, N, B)
    fifth = sp.Rational(2, 5)
    body = me.RigidBody("ball", C, B, 1, (me.inertia(B, fifth, fifth, fifth), C))
    kane = me.KanesMethod(N, q, u, [a.diff() - b for a, b in zip(q, u, strict=True)])
    kane.kanes_equations([body], [])
    spin = (3, -1, 2)
    hit = ri.mechanics.impact(kane, [
        ri.mechanics.contact(low, N.z, restitution=HALF, tangential="coulomb",
                             friction=FIFTH, name="floor"),
        ri.mechanics.contact(side, -N.x, restitution=HALF, tangential="coulomb",
                             friction=sp.Rational(3, 10), name="wall")], frame=N)
    bridge = hit.at(dict(zip(q, [0, 0, 1, 0, 0, 0], strict=True))).at(
        dict(zip(u, [*velocity, *spin], strict=True))).solve(rule)
    ball = Body3.sphere(1, 1, (0, 0, 1), velocity, spin, name="ball")
    contacts = (Contact(normal=(0, 0, 1), restitution=HALF, tangential="coulomb",
                        friction=FIFTH, name="floor", bodies=("ground", "ball"),
                        point=(0, 0, 0)),
                Contact(normal=(-1, 0, 0), restitution=HALF, tangential="coulomb",
                        friction=sp.Rational(3, 10), name="wall", bodies=("ground", "ball"),
                        point=(1, 0, 1)))
    built_in = SpaceCollision((Body3.fixed("ground"), ball), contacts, rule=rule.name,
                              order=tuple(order) or None).solve()
    return bridge, built_in


@pytest.mark.parametrize("rule", ["simultaneous", "sequential"])
def test_a_mechanics_system_with_two_tangent_planes_is_the_built_in_balls(rule):
    # several contacts sliding across tangent planes were refused by the bridge ("solved
    # alone so far"); now the rules run on its rows (n, t1, t2 a contact), and the same
    # ball written as a KanesMethod system and as the built-in 3-D body gets one answer
    chosen = ri.Simultaneous() if rule == "simultaneous" else ri.Sequential(("floor", "wall"))
    bridge, built_in = _ball_in_a_corner(chosen, () if rule == "simultaneous"
                                         else ("floor", "wall"))
    theirs, ours = bridge.results(), built_in.results()
    for mine, other in zip(["u_x", "u_y", "u_z", "w_x", "w_y", "w_z"],
                           ["vx", "vy", "vz", "omega_x", "omega_y", "omega_z"], strict=True):
        assert abs(float(theirs[mine]) - float(ours[f"ball.{other}"])) < 1e-9, mine
    for name in ("floor", "wall"):
        assert abs(float(theirs[f"{name}.normal_impulse"])
                   - float(ours[f"{name}.normal_impulse"])) < 1e-9
    assert bridge.rule == built_in.rule == rule
    assert max(float(x) for k, x in bridge.checks.items()) < 1e-8


def test_a_mechanics_ball_resting_on_a_floor_into_a_wall_by_the_driven_rule():
    # the driven rule on the same rows: the ball rolls on the floor (no normal speed)
    # into the wall, the floor resting and pushing while the wall strikes
    bridge, built_in = _ball_in_a_corner(ri.Driven(), velocity=(1, HALF, 0))
    theirs, ours = bridge.results(), built_in.results()
    for mine, other in zip(["u_x", "u_y", "u_z", "w_x", "w_y", "w_z"],
                           ["vx", "vy", "vz", "omega_x", "omega_y", "omega_z"], strict=True):
        assert abs(float(theirs[mine]) - float(ours[f"ball.{other}"])) < 1e-8, mine
    assert float(theirs["floor.normal_impulse"]) > 0  # the floor pushed while resting
    assert bridge.rule == built_in.rule == "driven"


# ---- a 3-D closed form with symbols is certified too ----

def _symbolic_ball(tangential, **coefficients):
    e, m, v = sp.symbols("e m v", positive=True)
    ball = Body3.sphere(m, 1, (0, 0, 1), (1, HALF, -v), (3, -1, 2), name="ball")
    floor = Contact(normal=(0, 0, 1), restitution=e, tangential=tangential,
                    bodies=("floor", "ball"), point=(0, 0, 0), **coefficients)
    return SpaceCollision((Body3.fixed("floor"), ball), (floor,))


@pytest.mark.parametrize("tangential, coefficients", [
    ("smooth", {}), ("stick", {}), ("coulomb", {"friction": sp.Symbol("mu", positive=True)}),
    ("rough", {"tangential_restitution": HALF})])
def test_a_3d_closed_form_is_checked_at_random_points_of_its_symbols(tangential,
                                                                     coefficients):
    # it used to carry no check at all ("checked in the tests"); now each law's residuals
    # are computed at three seeded rational points of m, v, e (and mu) where the ball
    # approaches, as the plane checks its closed forms
    out = _symbolic_ball(tangential, **coefficients).solve()
    assert out.impulses["contact"].free_symbols  # a closed form, not numbers
    checks = out.given_checks
    assert checks["_symbolic"] and checks["_points"] == 3
    own = {"smooth": "smooth", "stick": "sticks", "coulomb": "cone", "rough": "rough"}
    assert f"contact.{own[tangential]}" in checks and "contact.restitution" in checks
    assert max(float(v) for k, v in checks.items() if not k.startswith("_")) < 1e-30


def test_a_wrong_3d_closed_form_is_refused_not_printed(monkeypatch):
    # a smooth law whose impulse is twice its own: its symbolic answer breaks Newton's
    # law at every point, so it is refused in one line instead of printed
    from rigidimpact.laws.law import ContactImpulse, Smooth

    own = Smooth.impulse

    def doubled(self, W, v, restitution, tolerance=None):
        out = own(self, W, v, restitution, tolerance)
        return ContactImpulse(out.impulse * 2, out.course)

    monkeypatch.setattr(Smooth, "impulse", doubled)
    with pytest.raises(InputError, match="contact.restitution off by"):
        _symbolic_ball("smooth").solve()
