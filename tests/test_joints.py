"""Joints: bodies pinned together in scene files and in Python, solved by the same rules
as every contact (the joints' impulses eliminated by the projected inverse mass).

Checked against derivations written apart: the double pendulum of
derivations/double-pendulum-wall.toml against the same two rods built in
sympy.physics.mechanics (KanesMethod, its own M and contact rows) under every law, and
the hinged chain of derivations/hinged-chain.toml against Newton-Euler equations of the
two rods written by hand here."""

from __future__ import annotations

import importlib.util
import math
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.model.joints import Joint
from rigidimpact.scenes.scene import load_scene
from rigidimpact.solve.rules import Compliant, Simultaneous

ROOT = Path(__file__).resolve().parents[1]
PENDULUM = (ROOT / "derivations" / "double-pendulum-wall.toml").read_text()
CHAIN = (ROOT / "derivations" / "hinged-chain.toml").read_text()
HALF = sp.Rational(1, 2)


def _rods(g=0):
    """The double pendulum of the scene as a sympy.physics.mechanics system: two uniform
    rods (mass 1, length 1) at angles q1, q2 from the downward vertical, turning at u1
    and u2, under gravity g; returns the KanesMethod, its frame, the lower rod's tip and
    the coordinates and speeds."""
    q1, q2, u1, u2 = me.dynamicsymbols("q1 q2 u1 u2")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", [q1, N.z])
    B = N.orientnew("B", "Axis", [q2, N.z])
    A.set_ang_vel(N, u1 * N.z)
    B.set_ang_vel(N, u2 * N.z)
    hinge = me.Point("O")
    hinge.set_vel(N, 0)
    upper_c = hinge.locatenew("Cu", -A.y / 2)
    knee = hinge.locatenew("K", -A.y)
    lower_c = knee.locatenew("Cl", -B.y / 2)
    tip = knee.locatenew("T", -B.y)
    for point, frame, base in ((upper_c, A, hinge), (knee, A, hinge), (lower_c, B, knee),
                               (tip, B, knee)):
        point.v2pt_theory(base, N, frame)
    rods = [me.RigidBody("upper", upper_c, A, 1, (me.inertia(A, 0, 0, sp.Rational(1, 12)),
                                                  upper_c)),
            me.RigidBody("lower", lower_c, B, 1, (me.inertia(B, 0, 0, sp.Rational(1, 12)),
                                                  lower_c))]
    kane = me.KanesMethod(N, [q1, q2], [u1, u2], [q1.diff() - u1, q2.diff() - u2])
    kane.kanes_equations(rods, [(upper_c, -g * N.y), (lower_c, -g * N.y)])
    return kane, N, tip, (q1, q2), (u1, u2)


def _bridge(law: str, tangential: str, friction=None):
    """The twin at q1 = 30 deg, q2 = 60 deg, turning at 1 and 2, its tip striking a wall
    on its right."""
    kane, N, tip, (q1, q2), (u1, u2) = _rods()
    extra = {"friction": friction} if friction is not None else {}
    contact = ri.mechanics.contact(tip, -N.x, restitution=HALF, law=law,
                                   tangential=tangential, name="tip", **extra)
    return ri.mechanics.impact(kane, [contact], frame=N).at(
        {q1: sp.pi / 6, q2: sp.pi / 3, u1: 1, u2: 2}).solve()


def _pendulum(law: str, tangential: str, friction=None) -> ri.Solution:
    text = PENDULUM.replace('tangential = "smooth"', f'tangential = "{tangential}"\n'
                            f'law = "{law}"' + (f'\nfriction = "{friction}"'
                                                if friction is not None else ""))
    scene = ri.parse_scene(text, "pendulum")
    [solution] = scene.outcomes()
    return solution


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
@pytest.mark.parametrize("tangential,friction", [("smooth", None),
                                                 ("coulomb", sp.Rational(1, 5)),
                                                 ("coulomb", sp.Rational(3, 2))])
def test_the_double_pendulum_scene_is_its_mechanics_twin(law, tangential, friction):
    built = _pendulum(law, tangential, friction)
    twin = _bridge(law, tangential, friction)
    after = {b.name: b for b in built.after}
    for mine, theirs in ((after["upper"].spin, twin.speeds_after[0]),
                         (after["lower"].spin, twin.speeds_after[1]),
                         (built.impulses["tip"], twin.impulses["tip"])):
        assert abs(sp.N(mine - theirs, 40)) < 1e-30, (mine, theirs)
    assert abs(sp.N(built.tangential.get("tip", 0)) ** 2 -
               sp.N(twin.tangential.get("tip", 0)) ** 2) < 1e-30
    assert max(built.checks.values()) < 1e-40  # momentum, the law, the joint holding


def test_the_double_pendulum_by_hand():
    # both rods hanging straight down (q1 = q2 = 0), unit masses and lengths: M about
    # the hinge angles is [[1/3 + 1, 1/2], [1/2, 1/3]] and the tip's x velocity is
    # u1 + u2, so its effective inverse mass is J M^-1 J^T = (4/3 - 1 + 1/3)/(4/9 -
    # 1/4) = 24/7, and with e = 1/2 and a closing speed 1 + 2 the tip takes the impulse
    # (3/2)(3)/(24/7) = 21/16
    text = PENDULUM.replace('theta_1 = "30 deg"', "theta_1 = 0").replace(
        'theta_2 = "60 deg"', "theta_2 = 0")
    [solution] = ri.parse_scene(text, "hanging").outcomes()
    assert solution.impulses["tip"] == sp.Rational(21, 16)
    after = {b.name: b for b in solution.after}
    tip_after = after["upper"].spin + after["lower"].spin  # each length 1
    assert tip_after == -HALF * 3


def _chain_by_hand():
    """The chain of two rods (mass M, length l, along y from O) struck at its lower end
    along x: Newton-Euler for each rod with the hinge impulse J (on the upper rod; the
    lower gets -J), a point at height y of a rod turning at w moving by -w (y - y_c)."""
    M, length, P = sp.symbols("M l P", positive=True)
    J = sp.Symbol("J")
    v1, w1, v2, w2 = sp.symbols("v1 w1 v2 w2")
    inertia = M * length ** 2 / 12
    half = length / 2
    solved = sp.solve([M * v1 - (P - J), inertia * w1 - (P + J) * half,
                       M * v2 - J, inertia * w2 - J * half,
                       (v1 - w1 * half) - (v2 + w2 * half)], [v1, w1, v2, w2, J], dict=True)
    (s,) = solved
    end = (s[v1] + s[w1] * half) / P  # the struck end's speed per unit impulse
    return sp.simplify(1 / end), M


def test_the_hinged_chain_answers_like_its_effective_mass():
    effective, M = _chain_by_hand()
    assert sp.simplify(effective - 2 * M / 7) == 0
    m, e, v = sp.symbols("m e v_ix", positive=True)
    scene = ri.parse_scene(CHAIN, "chain")
    closed = scene.derivation({}).results  # no values: over the symbols
    ball = sp.Symbol("v_ix") * (7 * sp.Symbol("m") - 2 * sp.Symbol("M") * sp.Symbol("e")) / (
        7 * sp.Symbol("m") + 2 * sp.Symbol("M"))
    got = closed["ball.vx"].subs({s: sp.Symbol(s.name) for s in closed["ball.vx"].free_symbols})
    assert sp.simplify(got - ball) == 0
    numbers = scene.derivation().results  # at the scene's [values]: m 1, M 2, e 1/2
    assert numbers["ball.vx"] == sp.Rational(7 - 2, 7 + 4)
    assert numbers["hinge.impulse_y"] == 0
    assert max(scene.outcomes()[0].checks.values()) == 0


@pytest.mark.parametrize("text", [PENDULUM, CHAIN])
def test_the_printed_equations_hold_at_the_solution(text):
    scene = ri.parse_scene(text, "linked")
    collision = scene.collision(scene.values)
    for rule in (ri.Simultaneous(), ri.Sequential((scene.contacts[0].name,))):
        [solution] = collision.solve(rule)
        values = collision.solved_values(solution)
        equations = collision.equations(solution)
        assert any(eq.law == "joint" for eq in equations)
        for eq in equations:
            assert sp.N(eq.residual.xreplace(values), 40) == 0 or \
                abs(sp.N(eq.residual.xreplace(values), 40)) < 1e-35, eq


def test_a_joint_is_checked_where_it_is_stated():
    ball = ri.Body.particle(1, (1, 0), "ball")
    rod = ri.Body.rigid(2, sp.Rational(1, 6), (0, HALF), name="rod")
    lump = ri.Body.rigid(1, 0, (0, 1), name="lump")
    hit = ri.Contact(restitution=HALF, bodies=("ball", "rod"), name="hit")
    with pytest.raises(InputError, match="not on lump: a point mass"):
        ri.Collision((ball, rod, lump), (hit,), (Joint("pin", ("rod", "lump"), (0, 2)),))
    moving = ri.Body.rigid(1, 0, (0, 1), (1, 0), name="lump")
    with pytest.raises(InputError, match="do not move together"):
        ri.Collision((ball, rod, moving), (hit,), (Joint("pin", ("rod", "lump"), (0, 1)),))
    with pytest.raises(InputError, match="no body named"):
        ri.Collision((ball, rod, lump), (hit,), (Joint("pin", ("rod", "lamp"), (0, 1)),))
    with pytest.raises(InputError, match="must differ"):
        ri.Collision((ball, rod, lump), (hit,), (Joint("hit", ("rod", "lump"), (0, 1)),))
    with pytest.raises(InputError, match="not independent"):
        ri.Collision((ball, rod, lump), (hit,), (Joint("a", ("rod", "lump"), (0, 1)),
                                                 Joint("b", ("rod", "lump"), (0, 1))))
    rod_shape = ri.Body.rod(2, 1, sp.pi / 2, HALF, name="rod")  # from O up to (0, 1)
    with pytest.raises(InputError, match="from the centre of a rod"):
        ri.Collision((ball, rod_shape, lump), (hit,), (Joint("pin", ("rod", "lump"),
                                                             (0, 2)),))


def test_a_bad_joint_in_a_scene_file_is_one_line(tmp_path, capsys):
    cases = {
        "far": CHAIN.replace('point = ["0", "l"]', 'point = ["0", "3*l"]'),
        "nameless": CHAIN.replace('name = "hinge"\n', ""),
        "stranger": CHAIN.replace('bodies = ["lower", "upper"]', 'bodies = ["lower", "x"]'),
        "extra": CHAIN.replace('point = ["0", "l"]', 'point = ["0", "l"]\nspring = 1'),
        "apart": CHAIN.replace('position = ["0", "3*l/2"]',
                               'position = ["0", "3*l/2"]\nvelocity = ["1", "0"]'),
    }
    for name, text in cases.items():
        path = tmp_path / f"{name}.toml"
        path.write_text(text)
        assert main(["evaluate", str(path)]) == 2, name
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "Traceback" not in err, (name, err)
    path = tmp_path / "chain.toml"
    path.write_text(CHAIN + '\n[simulate]\nuntil = "restrike"\n')
    assert main(["simulate", str(path)]) == 2
    assert "between two moving bodies" in capsys.readouterr().err


def _compass_gait():
    spec = importlib.util.spec_from_file_location("compass_gait",
                                                  ROOT / "derivations" / "compass_gait.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_compass_gait_heel_strike_scene_is_the_published_walkers_map():
    # derivations/compass_gait.py's floating biped (its own legs(), its heel contact) at
    # the scene's numbers, alpha = asin(7/25): where its old stance foot lifts, the
    # scene releases its toe and the legs' rates after and the foot's velocity are
    # compass_gait.py's exactly (two independent states pin the linear map); where that
    # foot would sink into the slope, the floating model does not hold (compass_gait.py
    # refuses such a state), and the scene's toe acts instead
    cg = _compass_gait()
    kane, frame, swing, _, _ = cg.legs(floating=True)
    strike = ri.mechanics.impact(kane, [ri.mechanics.contact(
        swing, frame.y, restitution=0, tangential="stick", name="heel")], frame=frame)
    x, y, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    alpha = sp.asin(sp.Rational(7, 25))
    numbers = {cg.m: 5, cg.m_H: 10, cg.a: HALF, cg.b: HALF, cg.g: sp.Rational(49, 5),
               cg.gamma: 0}
    scene = ri.load_scene(ROOT / "derivations" / "compass-gait-heel-strike.toml")
    lifted, sunk = [], []
    for before in ((sp.Rational(-11, 10), sp.Rational(-2, 5)), (-1, sp.Rational(-1, 2)),
                   (sp.Rational(-3, 2), sp.Rational(-1, 5)), (sp.Rational(-1, 5), -2)):
        theirs = strike.at({**numbers, x: 0, y: 0, st: -alpha, sw: alpha, ux: 0, uy: 0,
                            w_st: before[0], w_sw: before[1]}).solve()
        lift = sp.nsimplify(theirs.speeds_after[1])
        values = {**scene.values, scene.symbols["omega_st"]: before[0],
                  scene.symbols["omega_sw"]: before[1]}
        [mine] = scene.outcomes(values)
        if lift < 0:
            assert "toe" in mine.acted
            sunk.append(before)
            continue
        assert mine.acted == ("heel",)
        after = {b.name: b for b in mine.after}
        assert after["stance"].spin == sp.nsimplify(theirs.speeds_after[2])
        assert after["swing"].spin == sp.nsimplify(theirs.speeds_after[3])
        stance = after["stance"]
        foot = stance.velocity + stance.spin * sp.Matrix([stance.position[1],
                                                          -stance.position[0]])
        assert list(foot) == [sp.nsimplify(v) for v in theirs.speeds_after[:2]]
        lifted.append(before)
    assert len(lifted) >= 2 and sp.Matrix(lifted).rank() == 2 and sunk


def _twin_flow(g):
    """The twin's equations of motion under gravity, integrated apart from the package's
    linkage simulator."""
    return ri.mechanics.flow_of(_rods(g)[0], {})


def test_the_double_pendulum_flies_on_as_its_mechanics_twin():
    from scipy.integrate import solve_ivp

    from rigidimpact.simulate.linkage import run_linkage

    text = PENDULUM.replace('until = "restrike"', "until = 0.75")
    scene = ri.parse_scene(text, "pendulum")
    out = run_linkage(scene)
    [impact] = scene.outcomes()
    after = {b.name: b for b in impact.after}
    start = [float(sp.pi / 6), float(sp.pi / 3), float(after["upper"].spin),
             float(after["lower"].spin)]
    flown = solve_ivp(_twin_flow(sp.Float(9.81)), (0, 0.75), start, method="DOP853",
                      rtol=1e-12, atol=1e-12)
    q1, q2, u1, u2 = flown.y[:, -1]
    assert out.final["upper.turn"] == pytest.approx(q1 - start[0], abs=1e-8)
    assert out.final["lower.turn"] == pytest.approx(q2 - start[1], abs=1e-8)
    assert out.final["upper.omega"] == pytest.approx(u1, abs=1e-8)
    assert out.final["lower.omega"] == pytest.approx(u2, abs=1e-8)
    assert out.details["joint_drift"] < 1e-8


def test_the_linkage_keeps_its_energy_until_it_strikes_again():
    from rigidimpact.simulate.linkage import run_linkage

    scene = ri.parse_scene(PENDULUM, "pendulum")
    out = run_linkage(scene)
    assert out.events[-1]["kind"] == "restrike" and out.events[-1]["contact"] == "tip"
    [impact] = scene.outcomes()
    after = {b.name: b for b in impact.after}

    def energy(state):  # both rods mass 1, inertia 1/12 about their centres
        return sum(0.5 * (state[f"{n}.vx"] ** 2 + state[f"{n}.vy"] ** 2)
                   + 0.5 / 12 * state[f"{n}.omega"] ** 2 + 9.81 * state[f"{n}.y"]
                   for n in ("upper", "lower"))

    first = {f"{n}.{k}": float(v) for n, b in after.items() if b.support != "fixed"
             for k, v in (("vx", b.velocity[0]), ("vy", b.velocity[1]),
                          ("omega", b.spin), ("y", b.position[1]))}
    assert energy(out.final) == pytest.approx(energy(first), abs=1e-8)
    # at the re-strike the tip is back at the wall's line, x = sin(30) + sin(60) deg
    tip_x = out.final["lower.x"] + 0.5 * math.sin(math.pi / 3 + out.final["lower.turn"])
    assert tip_x == pytest.approx(0.5 + math.sqrt(3) / 2, abs=1e-9)


TRIPLES = [(3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25)]


def _random_linkage(rng):
    """A chain of 2 or 3 uniform rods hinged end to end, the first on a pivot at O half
    the time, at rational-sine angles, turning at random rates (each rod's velocity the
    one its joints allow), its last end striking a wall, a floor or a ball."""
    count = rng.randint(2, 3)
    pinned = rng.random() < 0.5
    start, base_velocity = sp.Matrix([0, 0]), sp.Matrix([0, 0])
    bodies, joints = [], []
    for k in range(count):
        a, b, c = rng.choice(TRIPLES)
        sx, sy = rng.choice([(1, 1), (1, -1), (-1, 1), (-1, -1)])
        d = sp.Matrix([sp.Rational(sx * a, c), sp.Rational(sy * b, c)])  # along the rod
        length = sp.Rational(rng.randint(2, 6), 2)
        w = sp.Rational(rng.randint(-6, 6), 2)
        centre = start + d * length / 2
        velocity = base_velocity + w * sp.Matrix([-d[1], d[0]]) * length / 2
        angle = sp.atan2(d[1], d[0])
        body = ri.Body.rod(sp.Rational(rng.randint(1, 4)), length, angle, 0, tuple(velocity),
                           w, name=f"r{k}")
        pivot = {"pivot": sp.ImmutableMatrix([0, 0])} if k == 0 and pinned else {}
        bodies.append(replace(body, position=sp.ImmutableMatrix(centre), **pivot))
        if k:
            joints.append(Joint(f"j{k}", (f"r{k - 1}", f"r{k}"), tuple(start)))
        start = start + d * length
        base_velocity = base_velocity + w * sp.Matrix([-d[1], d[0]]) * length
    tip, tip_velocity = start, base_velocity
    law = rng.choice(["newton", "poisson", "energetic"])
    tangential = rng.choice(["smooth", "coulomb"] + (["stick"] if law == "newton" else []))
    friction = sp.Rational(rng.randint(1, 8), 4) if tangential == "coulomb" else None
    kind = rng.choice(["wall", "ball"])
    closing = [n for n in ((1, 0), (-1, 0), (0, 1), (0, -1))
               if (tip_velocity.T * sp.Matrix(n))[0] > 0]
    if not closing:
        return None
    normal = rng.choice(closing)
    if kind == "wall":
        other = ri.Body.fixed("wall")
    else:
        other = ri.Body.rigid(1, 0, tuple(tip), (0, 0), name="ball")
    hit = ri.Contact(normal=normal, restitution=sp.Rational(rng.randint(0, 4), 4), law=law,
                     tangential=tangential, friction=friction, name="hit",
                     bodies=(f"r{count - 1}", other.name), point=tuple(tip))
    rules = [ri.Simultaneous(), ri.Sequential(("hit",))]
    return ri.Collision((*bodies, other), (hit,), tuple(joints)), rng.choice(rules)


def test_random_linkages_obey_their_laws():
    # a seeded search: every answer's certificate (momentum with the joints' impulses,
    # the joints holding after, the contact's law, no energy created) holds, or its
    # warnings name what the model cannot honour; a refusal is one line
    import random

    rng, seen = random.Random(32), 0
    for _ in range(40):
        built = _random_linkage(rng)
        if built is None:
            continue
        collision, rule = built
        try:
            [solution] = collision.solve(rule)
        except InputError:
            continue
        seen += 1
        said = " ".join(solution.warnings)
        for key, value in solution.checks.items():
            if value == 0 or abs(value) < 1e-35:
                continue
            assert (key == "energy" and "kinetic energy is created" in said) or \
                (key.endswith(".pushes") and "would pull" in said), (key, value)
        assert all(solution.checks[f"j{k}.holds"] == 0 or
                   abs(solution.checks[f"j{k}.holds"]) < 1e-35
                   for k in range(1, len(collision.joints) + 1))
    assert seen >= 20


@pytest.mark.parametrize("name", ["hinged-chain", "double-pendulum-wall"])
def test_the_compliant_rule_gives_back_the_one_contact_answer_through_joints(name):
    # one contact alone: its spring-dashpot's damping is chosen from e on the contact's
    # effective mass 1/W (here through the joints' projected M^-1), so it gives back
    # Newton's e exactly, and the speeds of the rigid answer, to the integration's error
    scene = load_scene(ROOT / "derivations" / f"{name}.toml")
    collision = scene.collision(dict(scene.values))
    (rigid,) = collision.solve(Simultaneous())
    (spring,) = collision.solve(Compliant())
    exact, integrated = rigid.results(), spring.results()
    assert max(abs(float(exact[k] - integrated[k])) for k in exact) < 1e-8
    assert all(abs(float(v)) < 1e-8 for k, v in spring.checks.items() if "holds" in k)


def chain_scene(links: int) -> str:
    """A ball (m = 1, at 1 along +x) strikes the lowest of `links` uniform rods (M = 2,
    length 1) hinged end to end along the y axis, with e = 1/2."""
    out = ['[[bodies]]', 'name = "ball"', 'shape = "particle"', 'mass = "1"',
           'velocity = ["1", "0"]']
    for i in range(links):
        out += ['[[bodies]]', f'name = "r{i}"', 'shape = "rod"', 'mass = "2"',
                'length = "1"', 'angle = "90 deg"', f'position = ["0", "{2 * i + 1}/2"]']
    for i in range(links - 1):
        out += ['[[joints]]', f'name = "h{i}"', f'bodies = ["r{i}", "r{i + 1}"]',
                f'point = ["0", "{i + 1}"]']
    out += ['[[contacts]]', 'name = "hit"', 'bodies = ["ball", "r0"]',
            'normal = ["1", "0"]', 'restitution = "1/2"']
    return "\n".join(out) + "\n"


def chain_end_mass(links: int) -> Fraction:
    """The mass the ball meets at the chain's free end, by hand: a rod (M, I = M l^2/12)
    struck square at one end A with a point mass mu hinged at its other end B takes the
    joint impulse Q = -2P/(M/mu + 4), so A moves at (4P + 2Q)/M and the rod with its
    load meets the blow as M (M + 4 mu)/(4 M + 12 mu); the last rod starts from mu = 0
    (M/4), and a long chain tends to M/(2 sqrt 3)."""
    M, mu = Fraction(2), Fraction(0)
    for _ in range(links):
        mu = M * (M + 4 * mu) / (4 * M + 12 * mu)
    return mu


@pytest.mark.parametrize("links", [2, 30, pytest.param(200, marks=pytest.mark.slow)])
def test_a_long_free_chain_meets_the_ball_as_the_hand_recursion_says(tmp_path, capsys,
                                                                     links):
    # the joints' matrices are formed and inverted in the numbers' own field, sparse: a
    # chain of 200 rods answers in seconds (it ran past 400 s with SymPy's dense
    # determinant and inverse)
    import json

    path = tmp_path / "chain.toml"
    path.write_text(chain_scene(links))
    assert main(["evaluate", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    mu = chain_end_mass(links)
    expected = (1 - Fraction(1, 2) * mu) / (1 + mu)  # Newton's law with momentum
    assert out["ball.vx"] == pytest.approx(float(expected), rel=1e-14)
    # the struck rod's centre: (P - Q)/M with the ball's impulse P and Q the impulse its
    # upper hinge gives the rest of the chain (the point mass mu of `links - 1` rods)
    P, rest = 1 - expected, chain_end_mass(links - 1)
    Q = -2 * P / (2 / rest + 4) if rest else 0
    assert out["r0.vx"] == pytest.approx(float((P - Q) / 2), rel=1e-14)
    assert max(abs(v) for v in out["checks"].values()) == 0


TRIANGLE = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "1"
position = ["0", "1/2"]
velocity = ["1", "0"]
[[bodies]]
name = "a"
shape = "rod"
mass = "1"
length = "1"
angle = "90 deg"
position = ["0", "1/2"]
[[bodies]]
name = "b"
shape = "rod"
mass = "1"
length = "1"
angle = "0"
position = ["1/2", "1"]
[[bodies]]
name = "c"
shape = "rod"
mass = "1"
length = "sqrt(2)"
angle = "45 deg"
position = ["1/2", "1/2"]
[[joints]]
name = "ab"
bodies = ["a", "b"]
point = ["0", "1"]
[[joints]]
name = "bc"
bodies = ["b", "c"]
point = ["1", "1"]
[[joints]]
name = "ca"
bodies = ["c", "a"]
point = ["0", "0"]
[[contacts]]
name = "hit"
bodies = ["ball", "a"]
point = ["0", "1/2"]
normal = ["1", "0"]
restitution = "1/2"
"""


def test_a_closed_loop_of_joints_is_solved(tmp_path, capsys):
    """A triangle of rods pinned at its corners (a closed loop) is answered, as the docs
    say: momentum is kept along x and y, and the ball rebounds by Newton's law."""
    import json

    from rigidimpact.cli import main

    path = tmp_path / "triangle.toml"
    path.write_text(TRIANGLE, encoding="utf-8")
    assert main(["evaluate", str(path), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert sum(r[f"{b}.vx"] for b in ("ball", "a", "b", "c")) == pytest.approx(1)
    assert sum(r[f"{b}.vy"] for b in ("ball", "a", "b", "c")) == pytest.approx(0, abs=1e-12)
    # the struck point of rod a (its centre) leaves the ball at e = 1/2 of the approach
    assert r["a.vx"] - r["ball.vx"] == pytest.approx(0.5)


def test_the_compliant_rule_solves_a_scene_with_joints(tmp_path, capsys):
    """The hinged chain under the compliant rule: its stiff contact gives the rigid
    answer of the simultaneous rule (the ball leaves at 5/11, docs/scenes.md)."""
    import json

    from rigidimpact.cli import main

    text = (Path(__file__).resolve().parents[1] / "derivations" / "hinged-chain.toml"
            ).read_text(encoding="utf-8")
    path = tmp_path / "chain.toml"
    path.write_text(text.replace("[[contacts]]", '[impact]\nrule = "compliant"\n\n'
                                 "[[contacts]]", 1), encoding="utf-8")
    assert main(["evaluate", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["ball.vx"] == pytest.approx(5 / 11, rel=1e-6)
