"""A textbook catalogue of supported impacts, built on the public API and checked.

Each entry states a classic problem with bodies, a pivot or a fixed body, and a contact,
solves it with :class:`~rigidimpact.solve.impact.Impact`, and compares the result with an
answer derived independently (by hand, from angular momentum about the right point, the
parallel-axis theorem and the restitution law; each derivation is in the docstring).
The checks join ``rigidimpact verify`` as ``catalogue.*``.

Examples
--------
>>> hinged_rod().results()["rod.omega"]
45/14
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.impact import Impact
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.compare import Verdict, agree
from rigidimpact.symbolic.notation import symbol
from rigidimpact.symbolic.rewrite import polynomial_roots, tidy

__all__ = ["hinged_rod", "nailed_stick", "free_stick", "bar_on_wall", "centre_of_percussion",
           "sweet_spot", "ballistic_pendulum", "rocking_block", "rod_on_rough_floor",
           "superball", "CHECKS"]

m, M, l, v, e = (symbol(n) for n in ("m", "M", "l", "v", "e"))  # noqa: E741
d, alpha = sp.Symbol("d", positive=True), sp.Symbol("alpha", positive=True)
HALF_PI = sp.pi / 2
TWO_FIFTHS, THREE_FIFTHS = sp.Rational(2, 5), sp.Rational(3, 5)


def hinged_rod() -> Solution:
    """A 2 kg ball at 5 m/s strikes the free end of an 8 kg, 1.2 m rod hinged at its top,
    e = 0.8 (a standard exercise).

    By hand: about the hinge, 2*5*1.2 = 2*u*1.2 + (8*1.2**2/3)*w, and the rod's end leaves
    at 1.2*w = u + 0.8*5; so w = 45/14 rad/s and u = -1/7 m/s.
    """
    ball = Body.particle(2, (5, 0), "ball")
    rod = Body.rod(8, sp.Rational(6, 5), HALF_PI, sp.Rational(3, 5), name="rod",
                   pivot=(0, sp.Rational(6, 5)))
    return Impact(ball, rod, Contact(restitution=sp.Rational(4, 5))).solve()


def nailed_stick() -> Solution:
    """Clay (a point mass m at speed v) sticks to the end of a stick (mass M, length l)
    nailed at its centre to a smooth table.

    By hand, about the nail: m v l/2 = (m l^2/4 + M l^2/12) w, so w = 6 m v / ((3m + M) l).
    """
    clay = Body.particle(m, (v, 0), "clay")
    stick = Body.rod(M, l, HALF_PI, l / 2, name="stick", pivot=(0, l / 2))
    return Impact(clay, stick, Contact(restitution=0, tangential="stick")).solve()


def free_stick() -> Solution:
    """The same clay sticks to the end of the same stick lying free on the table.

    By hand, about the pair's centre of mass (l/2 M/(m + M) from the clay):
    w = 6 m v / ((4m + M) l).
    """
    clay = Body.particle(m, (v, 0), "clay")
    stick = Body.rod(M, l, HALF_PI, l / 2, name="stick")
    return Impact(clay, stick, Contact(restitution=0, tangential="stick")).solve()


def bar_on_wall() -> Solution:
    """A uniform bar (mass m, length l) moving at v straight at a smooth wall, tilted by
    alpha from the wall's normal, strikes it with one end (restitution e).

    By hand: the centre is a = (l/2) sin(alpha) off the line of impact, so the impulse
    J = (1 + e) v / (1/m + a^2/I) = (1 + e) m v / (1 + 3 sin^2 alpha), the spin
    w = J a / I = 6 (1 + e) v sin(alpha) / (l (1 + 3 sin^2 alpha)) (here the centre is
    below the struck end, so the wall's push turns the bar counter-clockwise, positive),
    and the centre leaves at v - J/m.
    """
    bar = Body.rod(m, l, sp.pi + alpha, l / 2, velocity=(v, 0), name="bar")
    return Impact(bar, Body.fixed("wall"), Contact(restitution=e)).solve()


def centre_of_percussion() -> Solution:
    """A ball (mass m, speed v) strikes a uniform rod (mass M, length l) hanging from a
    hinge at its top, a distance d below the hinge.

    By hand: the rod's centre moves at (l/2) w; the hinge must supply
    M (l/2) w - J, which vanishes when w l M/2 = J with J d = (M l^2/3) w: d = 2l/3,
    whatever the ball and e.
    """
    ball = Body.particle(m, (v, 0), "ball")
    rod = Body.rod(M, l, HALF_PI, d - l / 2, name="rod", pivot=(0, d))  # hinge on top
    return Impact(ball, rod, Contact(restitution=e)).solve()


def sweet_spot() -> Solution:
    """A bat (mass M, central inertia I, centre a from the hands) swung about a pivot at
    the hands is struck a distance d from them.

    By hand, as for the rod: the hands feel no impulse when d = (I + M a^2) / (M a).
    """
    inertia, a = symbol("I"), sp.Symbol("a", positive=True)
    ball = Body.particle(m, (v, 0), "ball")
    bat = Body.rigid(M, inertia, (0, d - a), name="bat", pivot=(0, d))
    return Impact(ball, bat, Contact(restitution=e)).solve()


def ballistic_pendulum() -> Solution:
    """A bullet (mass m, speed v) lodges in a bob (mass M) hung on a light cord of length
    l from a pivot.

    By hand: the bob can only move across the cord, so v m l = (m + M) u l, u = m v/(m + M).
    """
    bullet = Body.particle(m, (v, 0), "bullet")
    bob = Body.particle(M, name="bob")
    bob = Body(bob.name, bob.mass, 0, (0, 0), pivot=(0, l), shape="particle")
    return Impact(bullet, bob, Contact(restitution=0, tangential="stick")).solve()


def rocking_block() -> Solution:
    """A uniform block (half-width b, half-height h) rocking on its corner A lands on its
    other bottom corner B, which sticks (e = 0).

    By hand, about B: the angular momentum before is
    w- (I_C + M (C - B).(C - A)) = w- M (4h^2 - 2b^2)/3 and after I_B w+ = w+ 4M(b^2+h^2)/3,
    so w+/w- = 1 - (3/2) sin^2(alpha), with tan(alpha) = b/h (the diagonal from vertical).
    """
    b, h, w = (sp.Symbol(n, positive=True) for n in ("b", "h", "w"))
    inertia = M * (b**2 + h**2) / 3
    # B is at O, A at (-2b, 0), the centre at (-b, h); turning about A at spin -w, the
    # centre moves at -w z x (b, h) = (w h, -w b); the floor is below: normal (0, -1)
    block = Body.rigid(M, inertia, (-b, h), velocity=(w * h, -w * b), spin=-w, name="block")
    return Impact(block, Body.fixed("floor"),
                  Contact(normal=(0, -1), restitution=0, tangential="stick")).solve()


def rod_on_rough_floor(law: str, friction: sp.Expr = TWO_FIFTHS,
                       tangential: sp.Expr = THREE_FIFTHS) -> Solution:
    """A slender rod (mass 1, half-length 1) at 45 degrees strikes a rough floor with its
    lower end moving at (tangential, normal) = (0.6, -1), no spin; mu = 0.4, e = 1.

    Its slip stops and reverses during compression, so the three restitution laws part:
    the ratio of kinetic energy after to before is 1.033371 under Newton's law (energy
    created: the Kane-Levinson paradox), 0.868652 under Poisson's and 0.912313 under the
    energetic law (the figures of the friction issue; ``tests/test_routh.py`` checks them
    again by integrating the impulse equations with a smoothed Coulomb law).
    """
    rod = Body.rod(1, 2, sp.pi / 4, -1, velocity=(tangential, -1), name="rod")
    return Impact(rod, Body.fixed("floor"), Contact((0, -1), 1, "coulomb", law,
                                                      friction=friction)).solve()


def superball() -> Solution:
    """A solid sphere with tangential restitution beta = 1 (Garwin's superball) bounces
    without spin: W_tt = 1/m + r^2/I = 7/(2m), so the centre keeps 1 - 2(1 + beta)/7 =
    3/7 of its tangential velocity and the contact point's tangential velocity reverses,
    u + r w = -u, so it spins at w = -10 u/(7 r) (R. Garwin, Am. J. Phys. 37 (1969) 88).
    """
    ball = Body.sphere(m, symbol("r"), side=-1, velocity=(v, symbol("u")), name="ball")
    return Impact(ball, Body.fixed("floor"), Contact(restitution=1, tangential="rough",
                                                     tangential_restitution=1)).solve()


def _check(result: sp.Expr, expected: sp.Expr) -> Verdict:
    return agree(tidy(result), expected)


def _check_hinged() -> Verdict:
    r = hinged_rod().results()
    both = [agree(r["rod.omega"], sp.Rational(45, 14)), agree(r["ball.vx"], -sp.Rational(1, 7))]
    return Verdict(all(x.passed for x in both), "; ".join(x.detail for x in both))


def _check_sticks() -> Verdict:
    # the clay pushes the stick's lower end along +x: a counter-clockwise (positive) turn
    nailed = _check(nailed_stick().results()["stick.omega"], 6 * m * v / ((3 * m + M) * l))
    free = _check(free_stick().results()["stick.omega"], 6 * m * v / ((4 * m + M) * l))
    return Verdict(nailed.passed and free.passed, f"nailed: {nailed.detail}; free: "
                   f"{free.detail}")


def _check_wall() -> Verdict:
    s = sp.sin(alpha)
    r = bar_on_wall().results()
    spin = _check(r["bar.omega"], 6 * (1 + e) * v * s / (l * (1 + 3 * s**2)))
    speed = _check(r["bar.vx"], v - (1 + e) * v / (1 + 3 * s**2))
    return Verdict(spin.passed and speed.passed, f"spin: {spin.detail}; centre: "
                   f"{speed.detail}")


def _check_percussion() -> Verdict:
    reaction = centre_of_percussion().results()["rod.pivot_impulse_x"]
    roots = polynomial_roots(reaction, d)
    return Verdict(roots == [2 * l / 3], f"pivot impulse zero at d = {roots}")


def _check_sweet_spot() -> Verdict:
    inertia, a = symbol("I"), sp.Symbol("a", positive=True)
    reaction = sweet_spot().results()["bat.pivot_impulse_x"]
    roots = polynomial_roots(reaction, d)
    expected = (inertia + M * a**2) / (M * a)
    passed = len(roots) == 1 and tidy(roots[0] - expected) == 0
    return Verdict(passed, f"pivot impulse zero at d = {roots}")


def _check_ballistic() -> Verdict:
    return _check(ballistic_pendulum().results()["bob.vx"], m * v / (m + M))


def _check_rocking() -> Verdict:
    b, h, w = (sp.Symbol(n, positive=True) for n in ("b", "h", "w"))
    ratio = rocking_block().results()["block.omega"] / -w
    sin_squared = b**2 / (b**2 + h**2)
    return _check(ratio, 1 - sp.Rational(3, 2) * sin_squared)


def _check_rod_on_floor() -> Verdict:
    published = {"newton": 1.033371, "poisson": 0.868652, "energetic": 0.912313}
    rows = []
    for law, ratio in published.items():
        solution = rod_on_rough_floor(law)
        after = 1 - solution.energy_loss_fraction
        rows.append((law, sp.N(after, 12), abs(sp.N(after, 12) - ratio) <= 5e-7,
                     solution.regime))
    return Verdict(all(ok for *_, ok, _ in rows),
                   "; ".join(f"{law}: K+/K- = {r:.7f} ({regime})" for law, r, _, regime in rows))


def _check_superball() -> Verdict:
    after = superball().first_after
    kept = agree(after.velocity[1], sp.Rational(3, 7) * symbol("u"))
    spin = agree(after.spin, -sp.Rational(10, 7) * symbol("u") / symbol("r"))
    return Verdict(kept.passed and spin.passed, f"V_t: {kept.detail}; spin: {spin.detail}")


CHECKS: tuple[tuple[str, str, Callable[[], Verdict]], ...] = (
    ("catalogue.hinged_rod", "ball on a hinged rod: w = 45/14, ball -1/7", _check_hinged),
    ("catalogue.sticks", "clay on a nailed and on a free stick", _check_sticks),
    ("catalogue.wall", "a bar strikes a smooth wall with one end", _check_wall),
    ("catalogue.percussion", "no hinge impulse at 2l/3 on a uniform rod", _check_percussion),
    ("catalogue.sweet_spot", "no impulse at the hands at (I + M a^2)/(M a)",
     _check_sweet_spot),
    ("catalogue.ballistic", "ballistic pendulum: u = m v/(m + M)", _check_ballistic),
    ("catalogue.rocking", "rocking block: w+/w- = 1 - (3/2) sin^2(alpha)", _check_rocking),
    ("friction.rod", "rod on a rough floor: K+/K- = 1.033371 (Newton), 0.868652 (Poisson), "
     "0.912313 (energetic)", _check_rod_on_floor),
    ("friction.superball", "superball (beta = 1): keeps 3/7 of V_t, spin -10/7 V_t/r",
     _check_superball),
)
