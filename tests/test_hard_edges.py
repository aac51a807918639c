"""Hard edges met by hostile inputs: each case a scene or call that once crashed, was
refused though valid, or ran past any reasonable time; each is answered rightly now, or
refused in one line naming what is wrong."""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import refused, scene_file

_TURNED_BOX = """
[symbols]
a = {}
[[bodies]]
name = "floor"
shape = "fixed"
[[bodies]]
name = "box"
shape = "rigid"
mass = "1"
inertia = ["1", "2", "2"]
orientation = { axis = ["a", "a", "a"], angle = "30 deg" }
position = ["0.3", "0.2", "1"]
velocity = ["0", "0", "-1"]
[contact]
bodies = ["floor", "box"]
point = ["0", "0", "0"]
normal = ["0", "0", "1"]
restitution = "1/2"
"""


def test_an_orientation_axis_that_the_values_make_zero_is_refused(tmp_path, capsys):
    path = scene_file(tmp_path, _TURNED_BOX)
    refused(capsys, ["evaluate", path, "--set", "a=0"], "box.orientation.axis")
    with_values = _TURNED_BOX.replace("a = {}\n", "a = {}\n[values]\na = 0\n")
    for command in ("evaluate", "simulate"):
        refused(capsys, [command, scene_file(tmp_path, with_values, "v.toml")],
                "box.orientation.axis: is the zero vector")


def _rough_rod(angle_deg, vx, vy, restitution="e", friction="mu", beta="beta"):
    return f"""
[symbols]
e = {{ nonnegative = true }}
mu = {{ nonnegative = true }}
beta = {{}}
[[bodies]]
name = "rod"
shape = "rod"
mass = "1"
length = "2"
angle = "{angle_deg} deg"
struck_at = "1"
velocity = ["{vx}", "{vy}"]
[[bodies]]
name = "floor"
shape = "fixed"
[contact]
bodies = ["rod", "floor"]
normal = ["0", "-1"]
restitution = "{restitution}"
tangential = "rough"
friction = "{friction}"
tangential_restitution = "{beta}"
"""


def _walton_broken(angle_deg, u, e, mu, beta, got):
    """How far an answer is from Walton's law, solved apart: the rod's lower end at
    O, its centre r = (cos a, sin a) from it, the floor's normal -y; the end leaves
    with -e times its normal velocity and -beta times its slip where friction mu
    allows, and otherwise slides with mu P_n straight against the slip before."""
    import math

    a = math.radians(angle_deg)
    rx, ry = -math.cos(a), -math.sin(a)  # from the centre to the end
    inertia = 1 / 3

    def end(vx, vy, w):
        return vx - w * ry, vy + w * rx

    vx, vy, w = got["rod.vx"], got["rod.vy"], got["rod.omega"]
    p_t, p_n = vx - u[0], vy - u[1]  # the floor pushes the rod up (+y) and along x
    moment = rx * p_n - ry * p_t
    slip0, up0 = end(u[0], u[1], 0.0)
    slip1, up1 = end(vx, vy, w)
    gaps = [abs(moment / inertia - w), abs(up1 + e * up0)]
    if abs(p_t) < mu * p_n * (1 - 1e-9):
        gaps.append(abs(slip1 + beta * slip0))
    else:
        gaps += [abs(abs(p_t) - mu * p_n), max(0.0, p_t * slip0)]
    return max(gaps)


def test_walton_on_the_cones_edge_is_checked_by_its_own_promise(tmp_path, capsys):
    """Walton's law slides with its friction against the slip before; where the normal
    couples to the slip, the slip after may pass -beta times the slip before, which the
    certificate once took for a broken law and refused every such derivation."""
    from helpers import evaluated
    from rigidimpact.cli import main

    path = scene_file(tmp_path, _rough_rod(45, "0.6", "-1"))
    assert main(["derive", path]) == 0
    capsys.readouterr()
    # mu = 0 or beta = 1 leaves no tangential impulse: P = (0, 0.8), by hand
    for setting in (["mu=0", "beta=1/2"], ["mu=2/5", "beta=1"]):
        got = evaluated(capsys, ["evaluate", path, "--set", "e=1",
                                 *(x for s in setting for x in ("--set", s))])
        assert abs(got["rod.vx"] - 0.6) < 1e-12 and abs(got["rod.vy"] + 0.2) < 1e-12
        assert abs(got["rod.omega"] + 1.2 * 2**0.5) < 1e-12


@pytest.mark.parametrize("count", [2, pytest.param(6, marks=pytest.mark.slow)])
def test_a_seeded_family_of_rough_rods_is_answered_by_walton(tmp_path, capsys, count):
    from helpers import evaluated
    from rigidimpact.cli import main

    rng = random.Random(70)
    for k in range(count):
        angle = rng.randint(10, 80)
        u = (round(rng.uniform(-2, 2), 2), round(rng.uniform(-2, -0.1), 2))
        path = scene_file(tmp_path, _rough_rod(angle, *u), f"rod{k}.toml")
        assert main(["derive", path]) == 0, (angle, u)
        capsys.readouterr()
        e, mu, beta = rng.choice([0, 0.5, 1]), rng.uniform(0, 1), rng.uniform(-1, 1)
        got = evaluated(capsys, ["evaluate", path, "--set", f"e={e}", "--set",
                                 f"mu={mu!r}", "--set", f"beta={beta!r}"])
        assert _walton_broken(angle, u, e, mu, beta, got) < 1e-9, (angle, u, e, mu, beta)


def _bar_on_floor(xs, spin, tangential='"stick"', vx="0"):
    text = ('[[bodies]]\nname = "bar"\nshape = "rod"\nmass = "1"\nlength = "2"\n'
            f'angle = "0 deg"\nposition = ["0", "0"]\nvelocity = ["{vx}", "-1"]\n'
            f'spin = "{spin}"\n[[bodies]]\nname = "floor"\nshape = "fixed"\n')
    for i, x in enumerate(xs):
        text += (f'[[contacts]]\nname = "c{i}"\nbodies = ["bar", "floor"]\n'
                 f'point = ["{x}", "0"]\nnormal = ["0", "-1"]\nrestitution = "1/2"\n'
                 f'tangential = {tangential}\n')
    return text


def test_eight_sticking_contacts_are_one_linear_solve(tmp_path, capsys):
    """Every combination of eight contacts' states passes the enumeration's budget; all
    of them sticking is one linear solve, and it fits: Newton's law at every point of
    the bar (e = 1/2) with no slip is the bar's speeds reversed and halved."""
    import json

    from rigidimpact.cli import main

    xs = ["-1", "-5/7", "-3/7", "-1/7", "1/7", "3/7", "5/7", "1"]
    path = scene_file(tmp_path, _bar_on_floor(xs, "1/2"))
    assert main(["evaluate", path, "--json"]) == 0
    out, err = capsys.readouterr()
    got = json.loads(out)
    assert got["bar.vx"] == 0 and got["bar.vy"] == 0.5 and got["bar.omega"] == -0.25
    assert all(got[f"c{i}.normal_impulse"] >= 0 for i in range(8))
    assert abs(sum(got[f"c{i}.normal_impulse"] for i in range(8)) - 1.5) < 1e-12
    assert main_warns(err, "impulses are not") and main_warns(err, "were not tried")


def main_warns(err: str, words: str) -> bool:
    return any(line.startswith("rigidimpact: warning:") and words in line
               for line in err.splitlines())


def test_a_seeded_family_of_bars_past_the_enumeration_is_answered(tmp_path, capsys):
    """Bars on a floor at 7 to 9 contacts, sticking or with Coulomb's mu = 1/5 and a
    slide along the floor: each answer obeys the rule at every contact (Newton's law
    where it pushes, no pulling, no approach, the cone, friction against the slip)."""
    import random
    from fractions import Fraction

    from helpers import evaluated

    rng = random.Random(7070)
    for k in range(6):
        count = rng.randint(7, 9)
        xs = sorted({Fraction(rng.randint(-20, 20), 20) for _ in range(count)})
        spin = Fraction(rng.randint(-9, 9), 10)
        coulomb = k % 2 == 1
        text = _bar_on_floor([str(x) for x in xs], str(spin),
                             '"coulomb"\nfriction = "1/5"' if coulomb else '"stick"',
                             vx="1/2" if coulomb else "0")
        got = evaluated(capsys, ["evaluate", scene_file(tmp_path, text, f"b{k}.toml")])
        vx0 = 0.5 if coulomb else 0.0
        vx, vy, w = got["bar.vx"], got["bar.vy"], got["bar.omega"]
        p_n = [got[f"c{i}.normal_impulse"] for i in range(len(xs))]
        # the floor receives P_t along n turned by +90 degrees, (1, 0): the bar -P_t
        p_t = [-got[f"c{i}.tangential_impulse"] for i in range(len(xs))]
        assert abs(vy + 1 - sum(p_n)) < 1e-9 and abs(vx - vx0 - sum(p_t)) < 1e-9
        moment = sum(float(x) * p for x, p in zip(xs, p_n, strict=True))
        assert abs(w - float(spin) - 3 * moment) < 1e-9
        for x, pn, pt in zip(xs, p_n, p_t, strict=True):
            before, after = -1 + float(spin * x), vy + w * float(x)
            assert pn >= -1e-12 and after >= -0.5 * before - 1e-9
            if pn > 1e-12:
                assert abs(after + 0.5 * before) < 1e-9
                if coulomb:
                    assert abs(pt) <= 0.2 * pn + 1e-9
                    assert abs(pt) < 0.2 * pn - 1e-9 and abs(vx) < 1e-9 or pt * vx <= 1e-12
                else:
                    assert abs(vx) < 1e-9


def test_a_double_pendulums_tip_stopped_in_a_corner_by_two_sticking_contacts():
    """The tip of a double pendulum (two uniform rods of mass 1 and length 1) meets a
    floor and a wall at once, e = 0, both sticking: the tip stops, so the system stops
    (its tip Jacobian is invertible), and the impulse on the tip is fixed while its
    sharing between the contacts is not. It was refused as a Painleve-type
    inconsistency: the least-norm sharing pulls at the floor, and rounded comparisons
    took a touch of 1e-50 for an approach. Held, at float and at exact data, against
    the impulse found by hand, F = Jt^-T M (0 - u), and the laws."""
    import sys
    from pathlib import Path

    import numpy as np
    import sympy as sp

    import rigidimpact as ri

    sys.path.insert(0, str(Path(__file__).parents[1] / "derivations"))
    from double_pendulum_floor import VALUES, pendulum

    kane, N, tip = pendulum()
    (q1, q2), (u1, u2) = kane.q, kane.u
    q, u = np.array([0.6, 0.8]), np.array([-1.0, -2.5])
    M = np.array([[4 / 3, np.cos(q[0] - q[1]) / 2], [np.cos(q[0] - q[1]) / 2, 1 / 3]])
    jt = np.array([[np.cos(q[0]), np.cos(q[1])], [np.sin(q[0]), np.sin(q[1])]])
    force = np.linalg.solve(jt.T, M @ -u)
    assert force[0] > 0 > force[1]  # the wall pushes; the floor alone would pull
    for state, speeds in (({q1: 0.6, q2: 0.8}, {u1: -1.0, u2: -2.5}),
                          ({q1: sp.Rational(3, 5), q2: sp.Rational(4, 5)},
                           {u1: -1, u2: sp.Rational(-5, 2)})):
        hit = ri.mechanics.impact(kane, [
            ri.mechanics.contact(tip, N.y, restitution=0, tangential="stick", name="floor"),
            ri.mechanics.contact(tip, N.x, restitution=0, tangential="stick", name="wall")],
            frame=N)
        solution = hit.at({**state, **VALUES}).at(speeds).solve()
        assert max(abs(float(x)) for x in solution.speeds_after) < 1e-40
        normal, along = solution.impulses, solution.tangential
        assert float(normal["floor"]) >= 0 and float(normal["wall"]) >= 0
        # the floor's tangent is -x, the wall's +y: the impulse on the tip
        on_tip = (float(normal["wall"]) - float(along["floor"]),
                  float(normal["floor"]) + float(along["wall"]))
        assert np.allclose(on_tip, force, rtol=1e-12)
        assert any("impulses are not" in note for note in solution.notes)
        assert not solution.warnings


def _fan_of_radicals() -> str:
    """A striker (mass 1, inertia 1) meeting twelve bodies at once along the normals
    (sqrt(k), +-1), k = 1..6: W's entries hold sqrt(2), sqrt(3), sqrt(5), sqrt(6) and
    sqrt(7), a field of degree 16."""
    text = ('[[bodies]]\nname = "s"\nshape = "rigid"\nmass = "1"\ninertia = "1"\n'
            'position = ["0", "0"]\nvelocity = ["1", "1/3"]\n')
    i = 0
    for sign in ("1", "-1"):
        for k in range(1, 7):
            x, y = f"sqrt({k})/sqrt({k + 1})", f"{sign}/sqrt({k + 1})"
            text += (f'[[bodies]]\nname = "b{i}"\nshape = "rigid"\nmass = "1"\n'
                     f'inertia = "1"\nposition = ["2*{x}", "2*{y}"]\n'
                     f'[[contacts]]\nname = "c{i}"\nbodies = ["s", "b{i}"]\n'
                     f'point = ["{x}", "{y}"]\nnormal = ["sqrt({k})", "{sign}"]\n'
                     'restitution = "1/2"\n')
            i += 1
    return text


def test_a_fan_of_radical_normals_is_confirmed_in_one_field(tmp_path, capsys, monkeypatch):
    """The acting set found in floating point is confirmed exactly in the field of the
    data's roots, made once: two fields made apart and unified searched for an
    isomorphism between them (PSLQ) for minutes at some hash seeds. Held against the
    laws solved apart: momentum, and Newton's law (e = 1/2) at every contact, all
    acting."""
    import numpy as np
    from sympy.polys.numberfields import subfield

    from helpers import evaluated

    def refuse(*_args, **_kwargs):
        raise AssertionError("an isomorphism of number fields was searched for")

    monkeypatch.setattr(subfield, "field_isomorphism", refuse)
    got = evaluated(capsys, ["evaluate", scene_file(tmp_path, _fan_of_radicals())])
    normals = [np.array([k**0.5, s]) / (k + 1) ** 0.5 for s in (1, -1) for k in range(1, 7)]
    striker = np.array([got["s.vx"], got["s.vy"]])
    pushes = [got[f"c{i}.normal_impulse"] for i in range(12)]
    assert np.allclose(striker, [1, 1 / 3] - sum(p * n for p, n in zip(pushes, normals,
                                                                        strict=True)))
    for i, n in enumerate(normals):
        other = np.array([got[f"b{i}.vx"], got[f"b{i}.vy"]])
        assert np.allclose(other, pushes[i] * n) and pushes[i] > 0
        closing = n @ np.array([1, 1 / 3])
        assert abs((other - striker) @ n - closing / 2) < 1e-12


def _hinged_chain(n: int) -> str:
    text = '[[bodies]]\nname = "ball"\nshape = "particle"\nmass = "1"\nvelocity = ["1", "0"]\n'
    for i in range(n):
        text += (f'[[bodies]]\nname = "r{i}"\nshape = "rod"\nmass = "2"\nlength = "1"\n'
                 f'angle = "90 deg"\nposition = ["0", "{i}+1/2"]\n')
    for i in range(n - 1):
        text += (f'[[joints]]\nname = "h{i}"\nbodies = ["r{i}", "r{i + 1}"]\n'
                 f'point = ["0", "{i + 1}"]\n')
    return text + ('[[contacts]]\nname = "hit"\nbodies = ["ball", "r0"]\nnormal = ["1", "0"]\n'
                   'restitution = "1/2"\n')


@pytest.mark.slow  # 10 s: the slow tier (CI runs it)
def test_a_chain_of_200_hinged_rods_against_its_constrained_equations(tmp_path, capsys):
    """A ball (mass 1, at 1) strikes the foot of a chain of 200 hinged rods (mass 2,
    length 1, standing on end); e = 1/2. Its answer is held against the impact's own
    equations solved apart in NumPy: M du = G^T lam + J^T P with every hinge held
    (G u+ = 0) and Newton's law at the foot (J u+ = 1/2). The joints' S is solved,
    never inverted, and M^-1 never formed densely (it took 17 s)."""
    import numpy as np

    from helpers import evaluated

    n = 200
    got = evaluated(capsys, ["evaluate", scene_file(tmp_path, _hinged_chain(n))])
    size = 2 + 3 * n  # the ball's (vx, vy), then each rod's (vx, vy, omega)
    mass = np.diag([1.0, 1.0] + [2.0, 2.0, 1 / 6] * n)

    def point_row(rod, at_y):  # the velocity (x, y) of rod's point (0, at_y)
        rows = np.zeros((2, size))
        k = 2 + 3 * rod
        arm = at_y - (rod + 0.5)
        rows[0, k], rows[0, k + 2] = 1.0, -arm
        rows[1, k + 1] = 1.0
        return rows

    G = np.vstack([point_row(i + 1, i + 1) - point_row(i, i + 1) for i in range(n - 1)])
    J = point_row(0, 0)[:1] - np.eye(size)[:1]  # the foot's x less the ball's
    C = np.vstack([G, J])
    kkt = np.block([[mass, -C.T], [C, np.zeros((len(C), len(C)))]])
    u0 = np.zeros(size)
    u0[0] = 1.0
    rhs = np.concatenate([mass @ u0, np.zeros(len(G)), [0.5]])
    u = np.linalg.solve(kkt, rhs)[:size]
    assert abs(got["ball.vx"] - u[0]) < 1e-12
    for i in range(n):
        for k, key in enumerate(("vx", "vy", "omega")):
            assert abs(got[f"r{i}.{key}"] - u[2 + 3 * i + k]) < 1e-9, (i, key)


_TILTED_DROP = """
[values]
e = 0.5
theta = "30 deg"
[random]
theta = { LAW }
outputs = ["ball.vy"]
samples = 20000
seed = 1
[[bodies]]
name = "ball"
shape = "particle"
mass = "1"
velocity = ["cos(theta)", "-sin(theta)"]
[[bodies]]
name = "floor"
shape = "fixed"
[contact]
bodies = ["ball", "floor"]
normal = ["0", "-1"]
restitution = "e"
"""


def test_an_end_of_a_continuous_support_where_the_ball_grazes_is_drawn(tmp_path, capsys):
    """theta uniform on [0, pi/2], approach speed sin(theta): at the end 0 the ball only
    grazes, a draw of probability zero. By hand, vy = e sin(theta) has the density
    2 / (pi e sqrt(1 - y^2/e^2)) on (0, e) and the mean 2 e / pi. A discrete input with
    a grazing value, and a continuous one whose draws move apart, are still refused."""
    import sympy as sp

    from helpers import evaluated

    path = scene_file(tmp_path, _TILTED_DROP.replace("LAW", 'uniform = ["0", "pi/2"]'))
    got = evaluated(capsys, ["derive", path])["distributions"]["ball.vy"]
    e, y = sp.symbols("e y")
    assert sp.simplify(sp.sympify(got["mean"]) - 2 * e / sp.pi) == 0
    density = sp.sympify(got["density"]).subs(e, sp.Rational(1, 2))
    want = 2 / (sp.pi * sp.Rational(1, 2) * sp.sqrt(1 - 4 * y**2))
    assert sp.simplify(density - want) == 0
    for law, where in (('discrete = ["0", "pi/4"]', "at theta = 0"),
                       ('uniform = ["-1/10", "pi/2"]', "at theta = -0.1")):
        path = scene_file(tmp_path, _TILTED_DROP.replace("LAW", law), "refused.toml")
        refused(capsys, ["derive", path], where)


def _three_rough(law: str) -> str:
    """Three Coulomb contacts of a bar on a floor, one pass in order, mu a symbol."""
    text = (Path(__file__).parent / "rough_scenes" / "b-three-energetic-sequential.toml"
            ).read_text(encoding="utf-8")
    text = text.replace('friction = "3/4"', 'friction = "mu"').replace(
        'law = "energetic"', f'law = "{law}"')
    return text + "\n[symbols]\nmu = { nonnegative = true }\n"


@pytest.mark.parametrize("law", [pytest.param(law, marks=pytest.mark.slow)
                                 for law in ("newton", "poisson")])
def test_three_rough_contacts_in_turn_over_a_symbolic_mu(tmp_path, capsys, law):
    """A pass over three rough contacts with mu a symbol: its cases' conditions are
    sets of mu found exactly (a blanket simplification ran past a minute), they cover
    every mu >= 0 once, and each case is the numeric rule's answer inside it; a
    contact that does not close at its turn takes no step (each case had it act, so
    no case held)."""
    import sympy as sp

    from rigidimpact.scenes.scene import parse_scene

    scene = parse_scene(_three_rough(law))
    mu = scene.symbols["mu"]
    cases = scene.derivation().outcomes
    assert cases and all("c2: does not close" in c.courses for c in cases)
    rng = random.Random(68)
    for value in [sp.Rational(rng.randint(0, 300), 100) for _ in range(6)]:
        holding = [c for c in cases if all(bool(x.subs(mu, value)) for x in c.conditions)]
        assert len(holding) == 1, value
        (numeric,) = scene.derivation({mu: value}, printed=False).outcomes
        for key, got in holding[0].results().items():
            want = numeric.results()[key]
            assert abs(sp.N(got.subs(mu, value) - want, 30)) < 1e-25, (value, key)


def test_nested_roots_of_a_symbol_are_refused_in_one_line(tmp_path, capsys):
    path = scene_file(tmp_path, _three_rough("energetic"))
    refused(capsys, ["derive", path], "give [values] (or --set) for mu")
