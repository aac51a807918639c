"""An independent oracle for a rigid bar striking a fixed floor through rough contacts.

Written apart from the package, from the textbook statements, in mpmath at 50 digits:
the bar's generalized velocities u = (vx, vy, omega), M = diag(m, m, I), each contact's
unit normal n (from the bar into the floor) and unit tangent t (n turned by +90
degrees), its rows J_n = -(n, r x n) and J_t = -(t, r x t) (r from the centre to the
point: the floor is the second body), and u+ = u- + M^-1 (J_n^T P_n + J_t^T P_t).

- :func:`routh` integrates one contact's impact over its normal impulse (Routh's method):
  the velocities are linear in the impulse on each stretch of constant slip (sliding
  either way or sticking), so each stretch is solved in closed form, and the impact ends
  by Newton's (kinematic), Poisson's (kinetic) or Stronge's (energetic) law.
- :func:`sequential` runs the sequential rule with it: contact by contact in the order,
  passes repeated until no contact approaches.
- :func:`violations` lists what a simultaneous answer at the velocity level breaks: the
  momentum balance, no pulling, Newton's law where a contact acts, no approach where it
  does not, the friction cone, and friction against the slip after.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import mpmath

# a context of its own at 50 digits: mpmath's global precision is left as it is
mp = mpmath.MPContext()
mp.dps = 50
TINY = mp.mpf(10) ** -35


def number(text) -> mp.mpf:
    return mp.mpf(Fraction(str(text)).numerator) / Fraction(str(text)).denominator


@dataclass
class Touch:
    name: str
    point: tuple
    normal: tuple
    e: mp.mpf
    mu: mp.mpf
    law: str

    def rows(self):
        nx, ny = self.normal
        length = mp.sqrt(nx * nx + ny * ny)
        n = (nx / length, ny / length)
        t = (-n[1], n[0])
        rx, ry = self.point
        return ([-n[0], -n[1], -(rx * n[1] - ry * n[0])],
                [-t[0], -t[1], -(rx * t[1] - ry * t[0])])


@dataclass
class Bar:
    m: mp.mpf
    inertia: mp.mpf
    u: list  # vx, vy, omega

    @property
    def inverse(self):
        return [1 / self.m, 1 / self.m, 1 / self.inertia]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b, strict=True))


def kick(bar: Bar, u, touch: Touch, p_n, p_t):
    jn, jt = touch.rows()
    return [u[i] + bar.inverse[i] * (jn[i] * p_n + jt[i] * p_t) for i in range(3)]


def routh(bar: Bar, u, touch: Touch):
    """One contact's own impact from velocities u: (P_n, P_t) by Routh's method."""
    jn, jt = touch.rows()
    w = [[sum(a[i] * bar.inverse[i] * b[i] for i in range(3)) for b in (jn, jt)]
         for a in (jn, jt)]
    return routh_w(w, dot(jn, u), dot(jt, u), touch)


def routh_w(w, vn, vt, touch):
    """Routh's method from the contact's 2x2 W (normal, tangent) and its velocities
    before; `touch` gives mu, e and the law."""
    start = vn
    if vn >= 0:
        return mp.mpf(0), mp.mpf(0)
    p_n = p_t = mp.mpf(0)
    compression_work, restitution_work, p_c = None, mp.mpf(0), None
    for _ in range(20):
        stuck = abs(vt) <= TINY * (abs(start) + 1)
        if not stuck:
            k = -mp.sign(vt) * touch.mu
        elif touch.mu * w[1][1] >= abs(w[1][0]):
            k = -w[1][0] / w[1][1]  # sticks: the friction that keeps vt zero
        else:
            k = -mp.sign(w[1][0]) * touch.mu  # the slip starts again, in W's direction
        a_n, a_t = w[0][0] + w[0][1] * k, w[1][0] + w[1][1] * k
        if a_t == 0 or stuck and abs(a_t) < TINY:
            a_t = mp.mpf(0)
        steps = []
        if not stuck and a_t * vt < 0:
            steps.append(("slip ends", -vt / a_t))
        if p_c is None:
            if a_n > 0:
                steps.append(("compression ends", -vn / a_n))
            assert steps, "the normal velocity does not grow while slipping (it jams)"
        else:
            if touch.law == "newton":
                remaining = (-touch.e * start - vn) / a_n
            elif touch.law == "poisson":
                remaining = (1 + touch.e) * p_c - p_n
            else:  # the restitution work reaches e^2 times the compression work
                left = touch.e ** 2 * -compression_work - restitution_work
                remaining = (-vn + mp.sqrt(vn * vn + 2 * a_n * left)) / a_n if a_n else \
                    left / vn
            steps.append(("end", max(remaining, mp.mpf(0))))
        what, dp = min(steps, key=lambda s: s[1])
        work = vn * dp + a_n * dp * dp / 2
        if p_c is None:
            compression_work = (compression_work or 0) + work
        else:
            restitution_work += work
        p_n, p_t = p_n + dp, p_t + k * dp
        vn, vt = vn + a_n * dp, vt + a_t * dp
        if what == "slip ends":
            vt = mp.mpf(0)
        elif what == "compression ends":
            vn, p_c = mp.mpf(0), p_n
        elif what == "end":
            return p_n, p_t
    raise AssertionError("more than 20 stretches")


def sequential(bar: Bar, touches: list[Touch], order: list[str]):
    """The sequential rule: (u after, {name: (P_n, P_t)})."""
    u, total = list(bar.u), {t.name: [mp.mpf(0), mp.mpf(0)] for t in touches}
    by_name = {t.name: t for t in touches}
    scale = max(abs(dot(t.rows()[0], u)) for t in touches)
    for _ in range(1000):  # the rule's own budget of passes (MAX_PASSES)
        moved = False
        for name in order:
            touch = by_name[name]
            if dot(touch.rows()[0], u) < -mp.mpf(10) ** -40 * scale:  # as the rule ends
                p_n, p_t = routh(bar, u, touch)
                u = kick(bar, u, touch, p_n, p_t)
                total[name][0] += p_n
                total[name][1] += p_t
                moved = True
        if not moved:
            return u, total
    raise AssertionError("the sequential rule did not settle")


def violations(bar: Bar, touches: list[Touch], u_after, impulses, tolerance=1e-30):
    """What a simultaneous answer at the velocity level breaks (empty: nothing)."""
    found = []
    scale = max(abs(x) for x in bar.u) + 1
    expected = list(bar.u)
    for t in touches:
        expected = kick(bar, expected, t, *impulses[t.name])
    if max(abs(a - b) for a, b in zip(expected, u_after, strict=True)) > tolerance * scale:
        found.append("momentum")
    for t in touches:
        jn, jt = t.rows()
        p_n, p_t = impulses[t.name]
        before, after, slip = dot(jn, bar.u), dot(jn, u_after), dot(jt, u_after)
        target = -t.e * min(before, 0)
        if p_n < -tolerance * scale:
            found.append(f"{t.name} pulls")
        if p_n > tolerance * scale and abs(after - target) > tolerance * scale:
            found.append(f"{t.name} acts but leaves at {after}, not {target}")
        if after < target - tolerance * scale:
            found.append(f"{t.name} leaves too slowly: {after} < {target}")
        if abs(p_t) > t.mu * p_n + tolerance * scale:
            found.append(f"{t.name} outside the friction cone")
        if abs(p_t) < t.mu * p_n - tolerance * scale and abs(slip) > tolerance * scale:
            found.append(f"{t.name} inside the cone but slipping after")
        if p_t * slip > tolerance * scale:
            found.append(f"{t.name} friction along the slip")
    return found


def from_scene(data: dict) -> tuple[Bar, list[Touch]]:
    """The oracle's bar and contacts from a scene's dictionary (as read from TOML)."""
    body = next(b for b in data["bodies"] if b["shape"] == "rigid")
    assert all(number(x) == 0 for x in body["position"])
    bar = Bar(number(body["mass"]), number(body["inertia"]),
              [number(body["velocity"][0]), number(body["velocity"][1]),
               number(body.get("spin", "0"))])
    touches = []
    for c in data["contacts"]:
        assert c["bodies"][0] == body["name"]
        touches.append(Touch(c["name"], tuple(number(x) for x in c["point"]),
                             tuple(number(x) for x in c["normal"]), number(c["restitution"]),
                             number(c.get("friction", "0")), c.get("law", "newton")))
    return bar, touches
