"""The re-strike after the impact: derived condition, windows, event search.

The reference here is independent of the library's solver and search: the motion after
the impact comes from the paper's equation (5) (as typed in `paper.py`), and a
brute-force sweep samples the ball's position relative to the rod on a fine grid of
times and looks for the ball crossing the segment.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from rigidimpact.analyses import restrike
from rigidimpact.cli import main
from rigidimpact.paper.published import REFERENCES
from rigidimpact.simulate.flight import Flyer, first_contact
from rigidimpact.symbolic.notation import symbol
from rigidimpact.verify import run_checks

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
_VELOCITIES = sp.lambdify((theta, e, m, M, L, v_ix),
                          [REFERENCES[f"barbell.{k}"].expr for k in ("v_fx", "V_x", "omega_z")])
with mpmath.workdps(60):  # the paper's equation, solved here independently of the library
    THETA_C = mpmath.findroot(lambda x: mpmath.tan(x) - 1 / (mpmath.pi - x), 0.3)


def paper_flyers(angle: float, restitution: float, ratio: float, half: float = 0.5):
    """Ball and barbell just after the impact, from the paper's eq. (5)."""
    v_fx, v_x, omega = _VELOCITIES(angle, restitution, ratio, 1.0, half, 1.0)
    centre = (half * math.cos(angle), half * math.sin(angle))
    ball = Flyer("ball", "particle", (0.0, 0.0), (v_fx, 0.0), 0.0)
    bar = Flyer("barbell", "barbell", centre, (v_x, 0.0), omega,
                ((-centre[0], -centre[1]), centre), ("A", "B"))
    return ball, bar


def brute_force(angle: float, restitution: float, ratio: float, steps: int = 40000):
    """The first sampled turn (tau) at which the ball has crossed the rod, or None.

    The ball (relative to C) runs on a straight line; it is within the rod's reach
    (|p| <= L = 1) from tau = 0 until the line leaves the unit circle. Samples tau over that
    stretch (at most 2.2 pi: the B half must arrive by 2(pi - theta)) and looks for a change
    of side of the rod while the ball is within reach.
    """
    v_fx, v_x, omega = _VELOCITIES(angle, restitution, ratio, 1.0, 1.0, 1.0)
    start = np.array([-math.cos(angle), -math.sin(angle)])  # sphere A, relative to C
    drift = np.array([(v_fx - v_x) / omega, 0.0])            # per radian of turn
    speed2 = drift @ drift
    leaves = -2 * (start @ drift) / speed2 if speed2 > 0 else math.inf
    if leaves <= 0:
        return None
    tau = np.linspace(0.0, min(leaves, 2.2 * np.pi), steps + 1)[1:]
    px, py = start[0] + drift[0] * tau, start[1] + drift[1] * tau
    phi = angle + tau
    side = np.cos(phi) * py - np.sin(phi) * px
    crossed = np.sign(side[1:]) != np.sign(side[:-1])
    hits = np.flatnonzero(crossed)
    return None if hits.size == 0 else tau[hits[0] + 1]


def test_theta_c_solves_the_papers_equation_to_30_digits():
    with mpmath.workdps(60):
        ours = restrike.critical_angle().theta_c
        assert abs(ours - THETA_C) < mpmath.mpf(10) ** -38
        assert mpmath.nstr(ours * 180 / mpmath.pi, 12) == "19.6642901283"  # paper: ~19.7


@pytest.mark.parametrize("ratio", ["0.001", "1", "7/3", "1000"])
def test_the_e0_critical_angle_does_not_depend_on_the_mass_ratio(ratio):
    result = restrike.critical_angle(0, ratio)
    assert abs(result.theta_c - THETA_C) < mpmath.mpf(10) ** -35
    assert [lo.kind for lo, _ in result.windows] == ["limit"]


def test_the_restrike_checks_run_in_verify_and_pass():
    rows = [r for r in run_checks(lambda i: i.startswith("restrike."))]
    assert {r.id for r in rows} >= {"restrike.drift", "restrike.critical", "restrike.sphere_b",
                                    "restrike.theta_c", "restrike.monotone"}
    assert all(r.status == "pass" for r in rows), [r.detail for r in rows]


def test_the_critical_check_rejects_a_wrong_condition(monkeypatch):
    real = restrike.derive()
    wrong = real.critical.subs(sp.pi, 2 * sp.pi)  # tan(theta) = 1/(2 pi - theta)
    monkeypatch.setattr(restrike, "derive", lambda: type(real)(**{**real.__dict__,
                                                                  "critical": wrong}))
    [row] = run_checks(lambda i: i == "restrike.critical")
    assert row.status == "fail"


def test_the_at_rest_edges_have_their_closed_form():
    # k = 0 when m sin^2(theta) = e (m + 2M): with e = 0.3 and m = M, sin^2 = 0.9
    result = restrike.critical_angle("0.3", 1)
    lo = result.windows[0][0]
    assert lo.kind == "at rest"
    with mpmath.workdps(50):
        assert abs(mpmath.sin(lo.rad) ** 2 - mpmath.mpf(9) / 10) < mpmath.mpf(10) ** -35


def _inside(windows, degrees):
    return any(lo <= degrees <= hi for lo, hi in windows)


@pytest.mark.parametrize("restitution, ratio", [(0.0, 1.0), (0.1, 4.0), (0.3, 1.0),
                                                (0.05, 1.0), (0.6, 2.0), (1.0, 10.0),
                                                (0.2, 0.5), (0.499, 1.0), (0.501, 1.0)])
def test_windows_agree_with_a_brute_force_sweep(restitution, ratio):
    windows = [[float(x) for x in w] for w in restrike.windows(str(restitution), str(ratio))]
    edges = [x for w in windows for x in w]
    checked = 0
    for degrees in np.linspace(0.5, 179.5, 180):
        if any(abs(degrees - x) < 0.2 for x in edges):
            continue  # too close to an edge for the sampled sweep to resolve
        hit = brute_force(math.radians(degrees), restitution, ratio) is not None
        assert hit == _inside(windows, degrees), (degrees, windows)
        checked += 1
    assert checked > 150


@pytest.mark.parametrize("restitution, ratio", [(0.0, 1.0), (0.3, 1.0), (0.1, 4.0)])
def test_event_search_agrees_with_the_brute_force_sweep(restitution, ratio):
    for degrees in np.linspace(1.0, 179.0, 60):
        angle = math.radians(degrees)
        ball, bar = paper_flyers(angle, restitution, ratio)
        hit = first_contact(ball, bar)
        expected = brute_force(angle, restitution, ratio)
        if expected is None:
            assert hit is None, degrees
            continue
        assert hit is not None, degrees
        assert hit.part in ("rod", "B")  # the B half comes round first, never A
        assert abs(hit.t * bar.spin - expected) <= 2.2 * np.pi / 40000, degrees


def test_sweep_and_mpmath_turn_agree_with_the_event_search():
    angles = np.radians(np.linspace(0.5, 179.5, 200))
    for restitution, ratio in [(0.0, 1.0), (0.3, 1.0), (0.1, 4.0)]:
        swept = restrike.sweep(angles, restitution, ratio)
        for angle, hit, turn in zip(angles, swept.hit, swept.turn, strict=True):
            ball, bar = paper_flyers(angle, restitution, ratio)
            found = first_contact(ball, bar)
            assert hit == (found is not None)
            if hit:
                assert abs(found.t * bar.spin - turn) < 1e-9
                exact = restrike.restrike_turn(angle, str(restitution), str(ratio))
                assert abs(float(exact) - turn) < 1e-12


def _simulated_boundary(lo: float, hi: float, restitution: float, ratio: float) -> float:
    """Bisect on the initial angle with the event search deciding hit / no hit."""
    def hits(angle):
        return first_contact(*paper_flyers(angle, restitution, ratio)) is not None

    inside = hits(lo)
    assert hits(hi) != inside
    while hi - lo > 1e-12:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if hits(mid) == inside else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("restitution, ratio, which", [(0.0, 1.0, (0, 1)), (0.3, 1.0, (0, 1)),
                                                       (0.3, 1.0, (0, 0)), (0.1, 4.0, (1, 0)),
                                                       (1.0, 10.0, (0, 0))])
def test_derived_edges_match_the_simulated_boundary_to_1e9_rad(restitution, ratio, which):
    window, end = which
    edge = restrike.critical_angle(str(restitution), str(ratio)).windows[window][end]
    assert edge.kind in ("outrace", "at rest")
    x = float(edge.rad)
    simulated = _simulated_boundary(x - 1e-4, x + 1e-4, restitution, ratio)
    assert abs(simulated - x) < 1e-9


def test_grazing_at_the_rods_end_names_sphere_b():
    below = first_contact(*paper_flyers(float(THETA_C) - 1e-11, 0.0, 1.0))
    above = first_contact(*paper_flyers(float(THETA_C) + 1e-9, 0.0, 1.0))
    assert below is not None and below.part == "B"
    assert above is None
    # the turn is 2 (pi - theta_c), just short of a revolution (the paper's words)
    _, bar = paper_flyers(float(THETA_C), 0.0, 1.0)
    assert abs(below.t * bar.spin - 2 * (math.pi - float(THETA_C))) < 1e-6


def test_a_ball_at_rest_relative_to_the_centre_is_met_by_b_after_half_a_turn():
    angle = math.asin(math.sqrt(0.9))  # k = 0 for e = 0.3, m = M
    ball, bar = paper_flyers(angle, 0.3, 1.0)
    assert abs(ball.velocity[0] - bar.velocity[0]) < 1e-15
    hit = first_contact(ball, bar)
    assert hit is not None and hit.part == "B"
    assert abs(hit.t * bar.spin - math.pi) < 1e-9


@pytest.mark.parametrize("degrees, restitution, ratio, expected", [
    (1e-4, 0.0, 1.0, True),       # e = 0: every small angle is struck again
    (1e-4, 0.3, 1.0, False),      # e > 0: the ball bounces off and away
    (180 - 1e-4, 0.1, 4.0, True),  # near 180: struck again when m/M >= 2e
    (180 - 1e-4, 0.5, 1.0 - 1e-3, False),
])
def test_near_0_and_180_degrees(degrees, restitution, ratio, expected):
    angle = math.radians(degrees)
    hit = first_contact(*paper_flyers(angle, restitution, ratio))
    assert (hit is not None) == expected
    swept = restrike.sweep([angle], restitution, ratio)
    assert bool(swept.hit[0]) == expected
    if expected:
        exact = restrike.restrike_turn(mpmath.radians(mpmath.mpf(degrees)), str(restitution),
                                       str(ratio))
        _, bar = paper_flyers(angle, restitution, ratio)
        assert abs(hit.t * bar.spin - float(exact)) < 1e-6 * float(exact)


def test_near_180_the_window_exists_exactly_when_m_over_M_is_at_least_2e():
    # from the expansion of the condition at theta -> pi: (2e - m/M) decides the sign
    assert restrike.windows("0.25", "0.51")[-1][1] == 180
    assert not restrike.windows("0.25", "0.49") or restrike.windows("0.25", "0.49")[-1][1] < 180


def test_bad_parameters_name_the_field():
    from rigidimpact.errors import InputError

    with pytest.raises(InputError, match="e"):
        restrike.critical_angle("1.5", 1)
    with pytest.raises(InputError, match="mass-ratio"):
        restrike.critical_angle(0, "-1")
    with pytest.raises(InputError):
        restrike.critical_angle("nan", 1)


@pytest.mark.slow
@pytest.mark.parametrize("restitution", [0.02, 0.15, 0.25, 0.4, 0.45, 0.7, 0.9])
@pytest.mark.parametrize("ratio", [0.2, 0.7, 1.5, 3.0, 8.0, 50.0])
def test_windows_agree_with_brute_force_over_a_wide_grid(restitution, ratio):
    test_windows_agree_with_a_brute_force_sweep(restitution, ratio)


def _flight_restrikes(theta: float, e: float, ratio: float, steps: int = 20000) -> bool:
    """An independent brute force in the lab frame: the impact from the paper's eq. (5)
    (L = v = M = 1, m = ratio), then the ball's straight flight and the rod's turn about
    its drifting centre sampled in time until the ball is out of the rod's reach; a
    re-strike is the ball crossing the rod's line while within its half-length."""
    s, c = math.sin(theta), math.cos(theta)
    f = ratio * (1 + e) / (2 + ratio * (1 + s * s))
    ball, centre, spin = 1 - 2 * f / ratio, f, f * s
    rel = ball - centre  # the ball's velocity relative to the centre, along x
    if rel * c <= 0:  # it starts at distance L and only moves away
        return False
    t = np.linspace(2 * c / rel * 1e-7, 2 * c / rel, steps)
    px, py = -c + rel * t, -s + 0 * t
    phi = theta + spin * t
    cross = np.cos(phi) * py - np.sin(phi) * px
    inside = np.hypot(px, py) <= 1 + 1e-12
    flips = np.sign(cross[1:]) != np.sign(cross[:-1])
    return bool(np.any(flips & inside[1:] & inside[:-1]))


@pytest.mark.parametrize("e, ratio", [
    ("0.1", "0.01"), ("0.1", "1"), ("0.1", "100"), ("0.5", "0.01"), ("0.5", "100"),
    ("0.9", "0.01"), ("0.9", "1"), ("0.9", "100"), ("0.3", "1"),
    # e (1 + 2M/m) = 1 + e: the condition's root at 180 degrees is of fifth order
    ("0.5", "1"), ("0.25", "0.5"),
])
def test_windows_agree_with_a_brute_force_flight(e, ratio):
    windows = restrike.critical_angle(e, ratio).windows_deg  # never refused on this grid
    edges = [float(x) for w in windows for x in w] + [0.0, 90.0, 180.0]
    for degrees in np.arange(1.0, 180.0, 1.0):
        if min(abs(degrees - x) for x in edges) < 0.5:
            continue  # at 90 degrees the ball leaves the reach at once (T = 0)
        inside = any(float(a) < degrees < float(b) for a, b in windows)
        assert _flight_restrikes(math.radians(degrees), float(e), float(ratio)) == inside


def test_no_window_at_the_fifth_order_root(capsys):
    # e = 1/2, m/M = 1: sphere B reaches the ball's exit direction just after the ball
    # has left (short by 7e-5 rad at 168 degrees, 3e-10 at 179, computed to 50 digits)
    assert restrike.critical_angle("0.5", "1").windows_deg == []
    assert main(["critical-angle", "--e", "0.5", "--mass-ratio", "1"]) == 0
    assert "no re-strike" in capsys.readouterr().out


@pytest.mark.parametrize("count", [4, pytest.param(15, marks=pytest.mark.slow)])
def test_the_scan_reads_in_double_precision_only_signs_it_is_sure_of(monkeypatch, count):
    # the scan for the outrace edges reads a grid point in double precision where its
    # sign is sure (away from the ends and from zero) and at 40 digits elsewhere; the
    # windows and their edges must be those of the scan at 40 digits everywhere, to
    # every digit, over a seeded family of e and m/M (0.27 of the time on 90 cases)
    import random
    from fractions import Fraction

    rng = random.Random(45)
    cases = [(Fraction(rng.randint(0, 20), 20), Fraction(rng.randint(1, 40), rng.randint(1, 40)))
             for _ in range(count)]

    def windows():
        restrike._analysis.cache_clear()
        found = []
        for e, ratio in cases:
            r = restrike.critical_angle(str(e), str(ratio))
            found.append([(a.kind, b.kind, a.rad, b.rad) for a, b in r.windows])
        restrike._analysis.cache_clear()
        return found

    quick = windows()
    monkeypatch.setattr(restrike, "_quick", lambda reduced, orders: lambda x: None)
    assert quick == windows()
    assert any(kind == "outrace" for case in quick for w in case for kind in w[:2])
