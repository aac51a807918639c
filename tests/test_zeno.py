"""The pile-up of a sphere's bounces on a floor (e < 1), summed: against the closed form
t_inf = 2 e v0 / (g (1 - e)), the rolling speed that the angular momentum about the
touching point gives, and a bounce-by-bounce sum written here apart from the package."""

from __future__ import annotations

import math
import random
from fractions import Fraction as F

import pytest
import sympy as sp

from helpers import evaluated, scene_file
from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import Body3
from rigidimpact.simulate.bounces import bounces

R = sp.Rational


def _scene(e: str, mu: str, velocity: list[str], spin: str, until: str, planar: bool,
           tangential: str = "coulomb") -> str:
    """A ball of radius 1/10 touching a floor, in space or in the plane (y up there)."""
    if planar:
        place, normal, point = '["0", "1/10"]', '["0", "1"]', '["0", "0"]'
        speed = f'["{velocity[0]}", "{velocity[2]}"]'
        turn = f'"{spin}"'  # counter-clockwise about z
    else:
        place, normal, point = '["0", "0", "1/10"]', '["0", "0", "1"]', '["0", "0", "0"]'
        speed = "[" + ", ".join(f'"{x}"' for x in velocity) + "]"
        turn = f'["0", "{spin}", "0"]'  # about y: -spin is the plane's counter-clockwise
    friction = f'friction = "{mu}"\n' if tangential == "coulomb" else ""
    return f"""
[[bodies]]
name = "floor_body"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = "1"
radius = "1/10"
position = {place}
velocity = {speed}
spin = {turn}
[contact]
name = "floor"
bodies = ["floor_body", "ball"]
point = {point}
normal = {normal}
restitution = "{e}"
tangential = "{tangential}"
{friction}[simulate]
effects = ["gravity"]
g = 10
until = {until}
"""


def _by_hand(e: F, mu: F, u: F, slip: F, v0: F, g: F, k: F = F(2, 5),
             rtol: float = 1e-17) -> tuple[float, float, float, float]:
    """Bounce by bounce, apart from the package: a ball landing at v0 with velocity u
    and slip along x (one line: the slip keeps its line on a floor), Coulomb's
    friction needing k |s| / (1 + k) to stop the slip and giving at most
    mu (1 + e) times the landing speed; flights 2 e l / g. Summed until the rises are
    below rtol of the first: (time, distance, u, slip) where the bounces pile up."""
    t = x = 0.0
    landing = float(v0)
    u, slip = float(u), float(slip)
    c = float(k / (1 + k))
    while landing > rtol * float(v0):
        stop = -c * slip
        cap = float(mu * (1 + e)) * landing
        du = stop if abs(stop) <= cap else -math.copysign(cap, slip)
        u += du
        slip += du / c
        flight = 2 * float(e) * landing / float(g)
        t += flight
        x += u * flight
        landing *= float(e)
    return t, x, u, slip


def test_a_ball_dropped_with_e_99_100_lies_down_after_99_s_in_space_and_in_the_plane(
        tmp_path, capsys):
    # v0 = 5, e = 99/100, g = 10: t_inf = 2 (99/100) 5 / (10 / 100) = 99. Spin -20 about
    # y (counter-clockwise 20 in the plane): slip 1 + (1/10) 20 = 3, which the first
    # bounce stops (k |s| / (1 + k) = 6/7 <= mu (1 + e) v0 = 199/100): it rolls from t = 0
    # at (v + k R w x n) / (1 + k) = (1 - (2/5) 2) / (7/5) = 1/7, lies down at 99/7
    outs = []
    for planar in (False, True):
        text = _scene("99/100", "1/5", ["1", "0", "-5"], "-20" if not planar else "20",
                      "200", planar)
        out = evaluated(capsys, ["simulate", scene_file(tmp_path, text)])
        settles = [e for e in out["events"] if e["kind"] == "settles"]
        assert len(settles) == 1 and settles[0]["t"] == 99.0
        assert "infinitely many bounces summed" in settles[0]["course"]
        assert any("infinitely many bounces summed" in n for n in out["notes"])
        assert out["exact"] is True and out["settles"] == 99.0
        final = out["final"]
        assert final["ball.vx"] == pytest.approx(1 / 7, rel=1e-15)
        assert final["ball.x"] == pytest.approx(200 / 7, rel=1e-15)
        outs.append(final)
    space, plane = outs
    assert plane["ball.y"] == space["ball.z"] == pytest.approx(0.1)
    assert plane["ball.omega"] == pytest.approx(space["ball.omega_y"] * -1, rel=1e-15)


def test_a_smooth_drop_lies_down_where_the_closed_form_says():
    # smooth: nothing across the floor changes; it lies down at x = 1 * 99 at t = 99
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, -5), name="ball")
    floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="floor", restitution=R(99, 100))
    run = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=100)
    kinds = [e.kind for e in run.events]
    assert kinds.count("settles") == 1 and run.exact
    settle = run.events[kinds.index("settles")]
    assert settle.t == 99 and settle.position.T == sp.Matrix([[99, 0, R(1, 10)]])
    assert run.position.T == sp.Matrix([[100, 0, R(1, 10)]])


def test_a_ball_that_slides_through_every_bounce_lies_down_sliding(tmp_path, capsys):
    # mu = 1/100, e = 1/2: the bounces take c v0 / (1 - e) = 0.0525 * 10 = 0.525 off the
    # slip of 3, so it slides through all of them and lies down with slip 2.475; it then
    # slides (the slip falls at mu g (1 + 1/k) = 0.35) for 2.475 / 0.35 s and rolls at 1/7
    e, mu, g = F(1, 2), F(1, 100), F(10)
    t_inf, x_inf, u_inf, slip = _by_hand(e, mu, F(1), F(3), F(5), g)
    assert t_inf == pytest.approx(2 * 0.5 * 5 / (10 * 0.5), rel=1e-15)
    assert slip == pytest.approx(3 - 0.525, rel=1e-14)
    sliding = slip / 0.35
    end = 30
    x_end = x_inf + u_inf * sliding - 0.1 * sliding ** 2 / 2 + (end - t_inf - sliding) / 7
    for planar in (False, True):
        text = _scene("1/2", "1/100", ["1", "0", "-5"], "20" if planar else "-20",
                      str(end), planar)
        out = evaluated(capsys, ["simulate", scene_file(tmp_path, text)])
        events = {e["kind"]: e for e in out["events"]}
        assert events["settles"]["t"] == pytest.approx(t_inf, rel=1e-15)
        assert "slides at every bounce" in events["settles"]["course"]
        assert events["rolls"]["t"] == pytest.approx(t_inf + sliding, rel=1e-14)
        assert out["final"]["ball.vx"] == pytest.approx(1 / 7, rel=1e-14)
        assert out["final"]["ball.x"] == pytest.approx(x_end, rel=1e-13)


def test_a_seeded_family_lies_down_and_rolls_as_the_kept_angular_momentum_says():
    rng = random.Random(20261207)
    for _ in range(6):
        e = F(rng.randint(1, 99), 100)
        mu = F(rng.randint(1, 60), 100)
        u, w, v0 = F(rng.randint(-20, 20), 10), F(rng.randint(-300, 300), 10), \
            F(rng.randint(1, 60), 10)
        ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (R(u), 0, -R(v0)), (0, R(w), 0),
                            name="ball")
        floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                        name="floor", restitution=R(e), tangential="coulomb",
                        friction=R(mu))
        t_inf = 2 * e * v0 / (10 * (1 - e))
        run = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=R(t_inf) + 40)
        settles = [x for x in run.events if x.kind == "settles"]
        assert len(settles) == 1 and settles[0].t == R(t_inf), (e, mu, u, w, v0)
        # slip u - R w x n along x: u - (1/10) w (w about y: w x z = (w, 0, 0))
        t, x, speed, _ = _by_hand(e, mu, u, u - w / 10, v0, F(10))
        assert float(settles[0].t) == pytest.approx(t, rel=1e-12)
        assert float(settles[0].position[0]) == pytest.approx(x, rel=1e-9, abs=1e-12)
        assert float(settles[0].velocity[0]) == pytest.approx(speed, rel=1e-9, abs=1e-12)
        # rolling after: (v + k R w x n) / (1 + k), from the kept angular momentum
        rolling = (u + F(2, 5) * w / 10) / F(7, 5)
        assert run.velocity[0] == R(rolling) and run.velocity[2] == 0


def test_a_time_inside_the_pile_up_sums_the_bounces_before_it():
    # e = 99/100 rolling from t = 0 at 1/7: by t = 50 the whole flights 0.99^i (from 0.99)
    # that end by then, and the next flight's height; the events before 50 are those of
    # the run asked to stop at 200
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, -5), (0, -20, 0), name="ball")
    floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="floor", restitution=R(99, 100), tangential="coulomb",
                    friction=R(1, 5))
    run = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=50)
    long = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=200)
    assert [(x.t, x.kind) for x in run.events] == [(x.t, x.kind) for x in long.events
                                                    if x.t <= 50]
    t, rise = F(0), F(99, 20)
    while t + 2 * rise / 10 <= 50:
        t, rise = t + 2 * rise / 10, rise * F(99, 100)
    tau = 50 - t
    assert run.summed > 50 and run.t == 50
    assert run.position[0] == R(50, 7)
    assert run.position[2] == R(1, 10) + R(rise * tau - 5 * tau ** 2)
    assert run.velocity[2] == R(rise - 10 * tau)


def test_a_slip_reversed_at_every_bounce_without_bound_has_no_limit():
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, -5), name="ball")
    floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="floor", restitution=R(1, 2), tangential="rough",
                    tangential_restitution=1)
    with pytest.raises(InputError, match="reverses at every bounce without shrinking"):
        bounces(ball, (floor,), gravity=(0, 0, -10), horizon=10)


def test_walton_bounces_that_return_a_quarter_of_the_slip_are_summed():
    # rough, beta = 1/4 <= e = 1/2, no bound: each bounce sends the slip s to -s/4 and
    # moves the centre by -(1 + beta) k s / (1 + k); summed by hand bounce by bounce
    e, beta, k = F(1, 2), F(1, 4), F(2, 5)
    u, slip, landing, t, x = F(1), F(3), F(5), F(0), F(0)
    for _ in range(200):  # 2^-200 of the first flight: beyond 40 digits
        u -= (1 + beta) * k / (1 + k) * slip
        slip *= -beta
        flight = 2 * e * landing / 10
        t, x, landing = t + flight, x + u * flight, landing * e
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, -5), (0, -20, 0), name="ball")
    floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="floor", restitution=R(e), tangential="rough",
                    tangential_restitution=R(beta))
    run = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=10)
    (settle,) = [x for x in run.events if x.kind == "settles"]
    assert "returns -1/4 of the slip" in settle.course
    assert settle.t == R(1) and abs(settle.position[0] - R(x)) < R(1, 10 ** 40)
    # the slip dies out: it rolls at (v + k R w x n)/(1 + k) = (1 - 4/5)/(7/5) = 1/7
    assert settle.velocity.T == sp.Matrix([[R(1, 7), 0, 0]])
    assert run.position[0] == settle.position[0] + R(9, 7)
