"""Several contacts at scale: the simultaneous rule past Lemke's dense tableau and the
compliant rule on long chains, checked against exact answers, enumeration and laws."""

import numpy as np
import pytest
import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.collision import Collision, chain, cluster, fan
from rigidimpact.solve.rules import simultaneous as rule

HALF = sp.Rational(1, 2)


def _targets(problem: Collision) -> tuple[sp.Matrix, sp.Matrix]:
    v = problem.velocity_before
    e = [c.restitution for c in problem.contacts]
    return v, sp.Matrix([-e[i] * min(v[i], 0) for i in range(len(v))])


@pytest.mark.parametrize("problem", [fan(6), fan(16), chain(12, HALF), chain(40),
                                     chain(30, sp.Rational(1, 3), 2)],
                         ids=["fan6", "fan16", "cradle12", "cradle40", "cradle30"])
def test_the_path_at_scale_gives_lemkes_exact_answer(problem):
    # below MAX_LEMKE the rule uses Lemke's exact method; the path used past it (floating
    # point, then the acting set solved and checked exactly) must give the same numbers
    v, target = _targets(problem)
    lemke, notes, _ = rule._lcp(problem, v, target)
    assert notes == ()
    scaled, notes, method = rule._lcp_at_scale(problem, v, target, True)
    assert scaled == lemke  # exact rationals, equal entry by entry
    assert notes == () and "confirmed in exact arithmetic" in method


def test_the_path_at_scale_gives_enumerations_exact_answer_where_it_still_runs():
    for problem in (fan(4), fan(8), chain(9, HALF)):
        v, target = _targets(problem)
        assert rule._lcp_at_scale(problem, v, target, True)[0] == \
            rule._complementarity(problem, v, target)


@pytest.mark.parametrize("e", [1, HALF])
def test_a_cradle_of_a_thousand_balls_is_exact(e):
    # all contacts act (independent derivation): the striker leaves the next ball at e
    # times its speed, the other 1000 balls move together at V; momentum 1 = v0 + 1000 V
    # and V - v0 = e give V = (1 + e) / 1001, v0 = V - e
    n = 1001
    outcome = chain(n, e).simultaneous()
    r = outcome.results()
    V = sp.Rational(1 + e, n) if e == 1 else (1 + e) / n
    assert r["ball0.vx"] == V - e
    assert all(r[f"ball{k}.vx"] == V for k in (1, 500, n - 1))
    assert "confirmed in exact arithmetic" in outcome.method and not outcome.notes
    assert len(outcome.acted) == n - 1


def _wedged(e):
    """A striker drives a disc into three walls (normals at 0 and +-60 degrees): the disc
    has two freedoms and three wall contacts, so W is singular."""
    r3 = sp.sqrt(3)
    bodies = (Body.rigid(1, sp.Rational(1, 8), (-1, 0), (1, 0), name="striker"),
              Body.rigid(2, sp.Rational(1, 4), (0, 0), (0, 0), name="disc"),
              Body.fixed("wall"))
    contacts = [Contact((1, 0), e, name="hit", bodies=("striker", "disc"), point=(-HALF, 0))]
    for name, (x, y) in (("east", (1, 0)), ("north", (HALF, r3 / 2)),
                         ("south", (HALF, -r3 / 2))):
        contacts.append(Contact((x, y), e, name=name, bodies=("disc", "wall"),
                                point=(x / 2, y / 2)))
    return Collision(bodies, tuple(contacts))


@pytest.mark.parametrize("problem", [_wedged(HALF), _wedged(1), cluster(2, 2, HALF),
                                     cluster(2, 3, 1)],
                         ids=["wedged", "wedged-elastic", "cluster2x2", "cluster2x3"])
def test_the_path_at_scale_moves_bodies_as_enumeration_says(problem):
    # where W is singular many impulses fit and one motion after; the floating-point
    # path (the proximal point method there) must find enumeration's motion
    v, target = _targets(problem)
    exact = problem.kick(problem.u_before, rule._complementarity(problem, v, target))
    impulses, notes, _ = rule._lcp_at_scale(problem, v, target, True)
    scaled = problem.kick(problem.u_before, impulses)
    W = problem.W.to_DM()
    if W.rank() < W.shape[0]:
        assert "W is singular" in notes[0]
    assert max(abs(float(a - b)) for a, b in zip(exact, scaled, strict=True)) < 1e-12


@pytest.mark.parametrize("e", [1, HALF])
def test_a_large_cluster_obeys_the_laws_of_the_rule(e):
    # 8 x 8 discs, 162 contacts: no impulse pulls, no contact closes after, every acting
    # contact meets Newton's law, momentum is kept and no energy is created
    problem = cluster(8, 8, restitution=e)
    outcome = problem.simultaneous()
    P = np.array([float(outcome.impulses[t.name]) for t in problem.contacts])
    u = np.array([float(x) for x in problem._u_of(outcome)])
    J = np.array(problem.J.evalf(), dtype=float)
    v = np.array([float(x) for x in problem.velocity_before])
    target = -float(e) * np.minimum(v, 0)
    after = J @ u
    assert P.min() > -1e-12 and (after - target).min() > -1e-12
    assert np.abs(P * (after - target)).max() < 1e-12
    vx = u[0::3]  # each disc's coordinates are (vx, vy, omega)
    assert vx.sum() == pytest.approx(1, abs=1e-12)
    assert u[1::3].sum() == pytest.approx(0, abs=1e-12)
    lost = float(outcome.energy_loss_fraction)
    assert lost > -1e-12 and (lost > 0.01 if e != 1 else abs(lost) < 1e-12)


def _wave(n, speed):
    out = chain(n, 1, speed).compliant(1.0, hertz=True, tolerance=1e-10, record=True)
    t, u = out.history
    return out, t, u[0::3]


def test_nesterenkos_wave_speed_and_width_over_a_factor_ten():
    # Nesterenko (Dynamics of Heterogeneous Materials, 2001, ch. 1): an unloaded Hertzian
    # chain carries a solitary wave of fixed width whose speed grows as the 1/5 power of
    # its amplitude (so of the striker's speed): 10 times faster, 10^(1/5) = 1.585 times
    # quicker. His long-wave profile is cos^4(sqrt(10) x / 5), x in diameters, whose
    # standard deviation is sqrt(pi^2 / 12 - 5 / 8) * 5 / sqrt(10) = 0.703 diameters; the
    # discrete wave is a little narrower. Its width must not depend on the speed.
    theta = np.linspace(-np.pi / 2, np.pi / 2, 200001)
    shape = np.cos(theta) ** 4
    continuum = np.sqrt((theta**2 * shape).sum() / shape.sum()) * 5 / np.sqrt(10)
    assert continuum == pytest.approx(np.sqrt(np.pi**2 / 12 - 5 / 8) * 5 / np.sqrt(10))
    speeds, widths = [], []
    for striker in (1, 10):
        _, t, vx = _wave(100, striker)
        passes = [t[np.argmax(vx[b])] for b in (30, 70)]
        speeds.append(40 / (passes[1] - passes[0]))
        profile = np.maximum(vx[:, np.argmax(vx[50])], 0)
        x = np.arange(len(profile))
        mean = (profile * x).sum() / profile.sum()
        widths.append(np.sqrt((profile * (x - mean) ** 2).sum() / profile.sum()))
    assert speeds[1] / speeds[0] == pytest.approx(10**0.2, rel=1e-3)
    assert widths[1] == pytest.approx(widths[0], rel=1e-4)
    assert widths[0] == pytest.approx(continuum, rel=0.1)


@pytest.mark.parametrize("n", [201, pytest.param(1001, marks=pytest.mark.slow)])
def test_a_long_hertz_chain_keeps_momentum_energy_and_its_wave(n):
    # the wave that reaches the last ball (of 200, and of 1000 in the slow tier) is the
    # one that reached ball 40: a solitary wave does not change on the way (the end
    # balls of both chains leave alike)
    out = chain(n, 1, 1).compliant(1.0, hertz=True)
    short = chain(41, 1, 1).compliant(1.0, hertz=True)
    results, ends = out.results(), short.results()
    vx = np.array([float(results[f"ball{k}.vx"]) for k in range(n)])
    ends = np.array([float(ends[f"ball{k}.vx"]) for k in range(38, 41)])
    assert vx.sum() == pytest.approx(1, abs=1e-12)
    assert abs(float(out.energy_loss_fraction)) < out.energy_tolerance
    assert vx[-3:] == pytest.approx(ends, abs=1e-6)
    assert not out.notes
