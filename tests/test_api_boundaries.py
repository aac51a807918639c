"""Every public entry validates at its boundary: one InputError naming the argument, not
a raw error from SymPy, NumPy or Python, and no run without end."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.errors import InputError
from rigidimpact.mechanics.hybrid import Hybrid
from rigidimpact.simulate.bounces import spheres
from rigidimpact.simulate.sphere import flight, landing_time, sliding

q, u = me.dynamicsymbols("q u")
m, ell, e = sp.symbols("m l e", positive=True)


def _pendulum():
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", [q, N.z])
    A.set_ang_vel(N, u * N.z)
    hinge = me.Point("O")
    hinge.set_vel(N, 0)
    bob = hinge.locatenew("P", -ell * A.y)
    bob.v2pt_theory(hinge, N, A)
    kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
    kane.kanes_equations([me.Particle("p", bob, m)], [])
    return kane, N, bob


KANE, N, BOB = _pendulum()
C = ri.mechanics.contact


@pytest.mark.parametrize("call, needle", [
    (lambda: C(BOB, 0), "contact.normal: must be a sympy.physics.mechanics Vector"),
    (lambda: C("P2", -N.x), "contact.point: must be a sympy.physics.mechanics Point"),
    (lambda: C(BOB, 0 * N.x), "must not be the zero vector"),
    (lambda: ri.mechanics.impact(KANE, [1, 2]), "contacts[0]: must be made by"),
    (lambda: ri.mechanics.impact(KANE, C(BOB, -N.x)), "give a list of contacts"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, -N.x), C(BOB, N.y)]),
     "two contacts are named 'contact'"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, -N.x, restitution=e)], frame=N).at(
        {m: -1, ell: 1, e: 1, q: 0, u: 1}), "values.m: must be positive"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, -N.x, restitution=e)], frame=N).at(
        {m: 1, ell: 1, e: 1, q: 0, u: sp.nan}), "values.u(t): must be finite"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, -N.x, restitution=e)], frame=N).at(
        {m: 1, ell: 1, e: 1, q: 0, u: float("inf")}), "must be finite"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, -N.x, restitution=e)], frame=N).at(
        {m: 1, ell: 1, e: 1, q: 0, u: 1}).solve("simultaneous"), "rule: must be a rule"),
])
def test_the_mechanics_bridge_refuses_in_one_line(call, needle):
    with pytest.raises(InputError) as info:
        call()
    assert needle in str(info.value)


def test_friction_across_a_tangent_plane_takes_the_circular_cone():
    # a point that can move in three directions meets a floor: its tangent plane has two
    # directions, and friction acts in both (Coulomb's circular cone). By hand, with
    # n = y, t1 = x, t2 = n x t1 = -z: the slip (v.t1, v.t2) = (1, -1), P_n = (1 + e) 1
    # = 3/2, and mu P_n = 3/20 < |slip| / W_tt = sqrt(2): it slides throughout, P_t =
    # -(3/20) (1, -1) / sqrt(2)
    x, y, z, vx, vy, vz = me.dynamicsymbols("x y z vx vy vz")
    N3 = me.ReferenceFrame("N3")
    point = me.Point("ball")
    point.set_vel(N3, vx * N3.x + vy * N3.y + vz * N3.z)
    kane = me.KanesMethod(N3, [x, y, z], [vx, vy, vz],
                          [x.diff() - vx, y.diff() - vy, z.diff() - vz])
    kane.kanes_equations([me.Particle("b", point, 1)], [])
    rough = ri.mechanics.impact(kane, [C(point, N3.y, restitution=sp.Rational(1, 2),
                                         tangential="coulomb", friction=sp.Rational(1, 10))],
                                frame=N3).at({vx: 1, vy: -1, vz: 1}).solve()
    step = sp.Rational(3, 20) / sp.sqrt(2)
    assert [sp.simplify(a - b) for a, b in zip(
        rough.speeds_after, [1 - step, sp.Rational(1, 2), 1 - step], strict=True)] == [0] * 3
    smooth = ri.mechanics.impact(kane, [C(point, N3.y, restitution=sp.Rational(1, 2))],
                                 frame=N3).at({vx: 0, vy: -1, vz: 1}).solve()
    assert list(smooth.speeds_after) == [0, sp.Rational(1, 2), 1]  # by Newton's law


BALL = Hybrid(lambda t, x: np.array([x[1], -1.0]), lambda x: x[0],
              lambda x: np.array([0.0, -0.5 * x[1]]))


def test_a_zeno_run_stops_at_its_accumulation_time():
    # e = 1/2, g = 1, dropped from 1: bounces at sqrt(2) (1 + 1 + 1/2 + ...) = 3 sqrt(2)
    walk = BALL.simulate(np.array([1.0, 0.0]), impacts=10**6)
    assert walk.stopped == "zeno"
    assert walk.accumulation == pytest.approx(3 * np.sqrt(2), rel=1e-12)


def test_an_elastic_run_is_stopped_by_its_budget():
    elastic = Hybrid(lambda t, x: np.array([x[1], -1.0]), lambda x: x[0],
                     lambda x: np.array([0.0, -x[1]]))
    walk = elastic.simulate(np.array([1.0, 0.0]), impacts=10**5, steps=2000)
    assert walk.stopped == "budget" and len(walk.impact_times) < 10**5
    # the budget counts work: the same run stops at the same impact every time
    again = elastic.simulate(np.array([1.0, 0.0]), impacts=10**5, steps=2000)
    assert again.impact_times == walk.impact_times


def test_fixed_point_refuses_the_zeno_state():
    # the map v -> v/2 (the bounce speed halves) has no fixed point but v = 0, where the
    # flight between impacts vanishes; Newton's method once "converged" there
    with pytest.raises(InputError, match="Zeno"):
        BALL.fixed_point(np.array([0.0, 1.0]), [1])


@pytest.mark.parametrize("kwargs, needle", [
    ({"impacts": -1}, "impacts: must be at least 1"),
    ({"impacts": 2.5}, "impacts: must be a whole number"),
    ({"until": -1}, "until: must be a positive time"),
    ({"until": float("nan")}, "until: must be a positive time"),
])
def test_hybrid_simulate_checks_its_arguments(kwargs, needle):
    with pytest.raises(InputError, match=needle):
        BALL.simulate(np.array([1.0, 0.0]), **kwargs)


def test_a_sample_of_orders_past_its_cost_budget_is_refused_early():
    with pytest.raises(InputError, match="past the budget"):
        ri.chain(40).sampled_orders(10_000, 0)


class _Returns(ri.Rule):
    """A rule written outside the package that returns what it was made with."""

    name = "returns"

    def __init__(self, value):
        self.value = value

    def outcomes(self, problem):
        return self.value


class _Unwritten(ri.Rule):
    """A rule that never wrote its outcomes."""

    name = "unwritten"


def _two_walls():
    # a point in the plane meets two walls at once (x and y), both smooth
    x, y, vx, vy = me.dynamicsymbols("x y vx vy")
    frame = me.ReferenceFrame("F")
    point = me.Point("corner")
    point.set_vel(frame, vx * frame.x + vy * frame.y)
    kane = me.KanesMethod(frame, [x, y], [vx, vy], [x.diff() - vx, y.diff() - vy])
    kane.kanes_equations([me.Particle("b", point, 1)], [])
    return ri.mechanics.impact(kane, [C(point, -frame.x, name="wx"),
                                      C(point, -frame.y, name="wy")],
                               frame=frame).at({vx: 1, vy: 1})


@pytest.mark.parametrize("rule, needle", [
    (_Returns("nope"), "_Returns.outcomes(problem) must return a tuple of Solution (one per "
                       "outcome), not str 'nope'"),
    (_Returns(None), "must return a tuple of Solution (one per outcome), not NoneType"),
    (_Returns(["x"]), "must return a tuple of Solution (one per outcome); item 0 is str"),
    (_Returns(()), "with at least one outcome, not an empty one"),
    (_Unwritten(), "_Unwritten.outcomes(problem) is not written"),
])
@pytest.mark.parametrize("system", ["collision", "mechanics"])
def test_a_rule_that_returns_the_wrong_type_is_told_what_a_rule_returns(rule, needle, system):
    with pytest.raises(InputError) as info:
        (ri.chain(3) if system == "collision" else _two_walls()).solve(rule)
    assert str(info.value).startswith("rule: ") and needle in str(info.value)
    assert "\n" not in str(info.value)


def test_a_rule_that_returns_a_list_of_solutions_is_taken():
    inner = ri.Simultaneous()

    class Listed(ri.Rule):
        name = "listed"

        def outcomes(self, problem):
            return list(inner.outcomes(problem))

    (found,) = ri.chain(3).solve(Listed())
    assert found.results() == ri.chain(3).simultaneous().results()
    assert _two_walls().solve(Listed()).speeds_after == _two_walls().solve().speeds_after


M3, R3, V3 = sp.symbols("M3 R3 V3", positive=True)
FREE = sp.Symbol("w")  # no assumptions: the body's own check refuses a negative mass


def _sphere_on_floor():
    ball = ri.Body3.sphere(M3, R3, (0, 0, R3), (V3, 0, -1), name="ball")
    floor = ri.Contact(normal=(0, 0, 1), restitution=sp.Rational(1, 2),
                       bodies=("floor", "ball"), point=(0, 0, 0))
    return ri.SpaceCollision((ri.Body3.fixed("floor"), ball), (floor,))


def test_a_3d_body_and_collision_take_plain_python_numbers():
    ball = ri.Body3.sphere(M3, R3, velocity=(V3, 0, 0), name="ball").at(
        {M3: 2, R3: 0.5, V3: np.float64(3)})
    assert ball.mass == 2 and ball.radius == sp.Float(0.5)
    assert ball.velocity[0] == sp.Float(3.0)  # a float stays one, exact as given
    out = _sphere_on_floor().at({M3: 2, R3: 1, V3: 1}).solve()
    assert out.results()["ball.vz"] == sp.Rational(1, 2)  # Newton's law, e = 1/2
    assert out.results()["ball.vx"] == 1  # smooth: the slip is untouched


@pytest.mark.parametrize("values, needle", [
    ({M3: -1}, "values.M3: must be positive (the symbol is declared positive), not -1"),
    ({M3: 0.0}, "values.M3: must be positive"),
    ({M3: float("nan")}, "values.M3: must be finite, not nan"),
    ({R3: float("inf")}, "values.R3: must be finite, not inf"),
    ({M3: "2"}, "values.M3: must be a number or a SymPy expression, not str '2'"),
    ({M3: 2j}, "values.M3: must be a real number, not complex 2j"),
    ({M3: None}, "values.M3: must be a number or a SymPy expression, not NoneType"),
    ({M3: True}, "values.M3: must be a number or a SymPy expression, not bool"),
    ({"M3": 2}, "values: keys must be SymPy symbols"),
    ([(M3, 2)], "values: must be a dict of SymPy symbols to numbers, not list"),
])
@pytest.mark.parametrize("make", ["body", "collision"])
def test_3d_at_refuses_bad_values_in_one_line(values, needle, make):
    made = (ri.Body3.sphere(M3, R3, name="ball") if make == "body"
            else _sphere_on_floor())
    with pytest.raises(InputError) as info:
        made.at(values)
    assert needle in str(info.value) and "\n" not in str(info.value)


def test_3d_at_refuses_a_negative_mass_of_a_symbol_without_assumptions():
    with pytest.raises(InputError, match=r"^ball\.mass: must be positive, got -1$"):
        ri.Body3.sphere(FREE, 1, name="ball").at({FREE: -1})


NAN, INF = float("nan"), float("inf")
_STILL = ((3, 0, 0), (0, 0, 0))  # along the table, no spin
_FLIGHT = ((0, 0, 1), (1, 0, 0), (0, 0, 0), (0, 0, -10))


@pytest.mark.parametrize("call, needle", [
    (lambda: landing_time("h", 3, 10), "height: must be a number or a SymPy expression, "
                                        "not str 'h'"),
    (lambda: landing_time(2, "u", 10), "rise: must be a number or a SymPy expression"),
    (lambda: landing_time(2, 3, "g"), "g: must be a number or a SymPy expression"),
    (lambda: landing_time(2, 3j, 10), "rise: must be a real number, not complex 3j"),
    (lambda: landing_time(NAN, 3, 10), "height: must be finite, not nan"),
    (lambda: landing_time(2, 3, INF), "g: must be finite, not inf"),
    (lambda: landing_time(-1, 3, 10), "height: must be at least 0"),
    (lambda: sliding(*_STILL, "R", 0.4, 0.2, 9.8), "radius: must be a number or a SymPy "
                                                   "expression, not str 'R'"),
    (lambda: sliding(*_STILL, NAN, 0.4, 0.2, 9.8), "radius: must be finite, not nan"),
    (lambda: sliding(*_STILL, 1, INF, 0.2, 9.8), "k: must be finite, not inf"),
    (lambda: sliding(*_STILL, 1, 0.4, 0.2j, 9.8), "mu: must be a real number"),
    (lambda: sliding(*_STILL, 1, 0.4, "mu", 9.8), "mu: must be a number or a SymPy"),
    (lambda: sliding((NAN, 0, 0), (0, 0, 0), 1, 0.4, 0.2, 9.8), "v[0]: must be finite"),
    (lambda: sliding((1j, 0, 0), (0, 0, 0), 1, 0.4, 0.2, 9.8), "v[0]: must be a real"),
    (lambda: sliding((3, 0, 0), (0, "w", 0), 1, 0.4, 0.2, 9.8), "spin[1]: must be a number"),
    (lambda: sliding("abc", (0, 0, 0), 1, 0.4, 0.2, 9.8), "v: must be three numbers"),
    (lambda: flight(*_FLIGHT, "t"), "t: must be a number or a SymPy expression, not str"),
    (lambda: flight(*_FLIGHT, NAN), "t: must be finite, not nan"),
    (lambda: flight(*_FLIGHT, 1j), "t: must be a real number, not complex 1j"),
    (lambda: flight((0, 0, INF), *_FLIGHT[1:], 1), "position[2]: must be finite, not inf"),
    (lambda: flight(*_FLIGHT[:3], (0, 0, "g"), 1), "gravity[2]: must be a number"),
])
def test_sphere_motion_refuses_text_complex_and_non_finite_numbers(call, needle):
    with pytest.raises(InputError) as info:
        call()
    assert needle in str(info.value) and "\n" not in str(info.value)


def test_sphere_motion_takes_python_numpy_and_sympy_numbers():
    assert landing_time(2, 3, 10) == 1  # 2 + 3 t - 5 t^2 = 0
    assert landing_time(np.float64(2), np.int64(3), 10) == pytest.approx(1.0, rel=1e-15)
    # floats stand for the simple rationals they print as: rolls at t = 150/343
    assert sliding(*_STILL, 0.1, 0.4, 0.2, 9.8).t == sp.Rational(150, 343)
    h = sp.Symbol("h", positive=True)  # a SymPy symbol is a symbol on purpose
    assert landing_time(h, 0, 2) == sp.sqrt(h)
    place, _, _ = flight(np.array([0.0, 0.0, 1.0]), *_FLIGHT[1:], np.float64(0.5))
    assert float(place[2]) == pytest.approx(1 - 10 * 0.5**2 / 2)


def _rough_drop():
    # a ball thrown down and along onto a rough floor (e = 1/2, mu = 1/5)
    ball = ri.Body3.sphere(1, sp.Rational(1, 10), (0, 0, 1), (1, 0, -1), name="a")
    floor = ri.Contact(normal=(0, 0, 1), bodies=("table", "a"), point=(0, 0, 0),
                       name="floor", restitution=sp.Rational(1, 2), tangential="coulomb",
                       friction=sp.Rational(1, 5))
    return (ball,), (floor,)


@pytest.mark.parametrize("kwargs, needle", [
    ({"compliance": -1.0}, "compliance: the stiffness ratio k_t/k_n must be a positive "
                           "number, not -1.0"),
    ({"compliance": 0}, "compliance: the stiffness ratio k_t/k_n must be a positive"),
    ({"compliance": float("nan")}, "compliance: must be finite, not nan"),
    ({"compliance": float("inf")}, "compliance: must be finite, not inf"),
    ({"compliance": "1"}, "compliance: must be a number or a SymPy expression, not str"),
    ({"compliance": 1j}, "compliance: must be a real number"),
    ({"horizon": "1"}, "simulate.until (horizon): must be a number or a SymPy expression"),
    ({"horizon": float("nan")}, "simulate.until (horizon): must be finite, not nan"),
    ({"gravity": (0, 0, "g")}, "simulate.gravity[2]: must be a number or a SymPy"),
    ({"gravity": (0, 0, float("nan"))}, "simulate.gravity[2]: must be finite, not nan"),
    ({"gravity": "0 0 -10"}, "simulate.gravity: three numbers"),
    ({"rolling_resistance": float("nan")}, "simulate.rolling_resistance: must be finite"),
    ({"pivot_friction": "0.01"}, "simulate.pivot_friction: must be a number or a SymPy"),
])
def test_spheres_refuses_bad_settings_in_one_line(kwargs, needle):
    balls, planes = _rough_drop()
    with pytest.raises(InputError) as info:
        spheres(balls, planes, **({"impacts": 2} | kwargs))
    assert needle in str(info.value) and "\n" not in str(info.value)


def test_spheres_takes_a_positive_compliance_as_any_number():
    runs = [spheres(*_rough_drop(), impacts=1, compliance=ratio)
            for ratio in (0.79, sp.Float(0.79), np.float64(0.79))]
    assert runs[0].velocity == runs[1].velocity == runs[2].velocity
    # the compliant bounce differs from the rigid one: the tangential spring gives back
    assert runs[0].velocity != spheres(*_rough_drop(), impacts=1).velocity


g_ = sp.Symbol("g", positive=True)


def _falling_pendulum(formed=True):
    frame = me.ReferenceFrame("N")
    arm = frame.orientnew("A", "Axis", [q, frame.z])
    arm.set_ang_vel(frame, u * frame.z)
    hinge = me.Point("O")
    hinge.set_vel(frame, 0)
    bob = hinge.locatenew("P", -ell * arm.y)
    bob.v2pt_theory(hinge, frame, arm)
    kane = me.KanesMethod(frame, [q], [u], [q.diff() - u])
    if formed:
        kane.kanes_equations([me.Particle("p", bob, m)], [(bob, -m * g_ * frame.y)])
    return kane, frame, bob


PENDULUM, _, _ = _falling_pendulum()
UNFORMED, UNFORMED_FRAME, UNFORMED_BOB = _falling_pendulum(formed=False)


@pytest.mark.parametrize("call, needle", [
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: float("nan")}),
     "constants.g: must be finite, not nan"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: float("inf"), g_: 1}),
     "constants.l: must be finite, not inf"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: sp.nan}),
     "constants.g: must be finite, not nan"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: "9.8"}),
     "constants.g: must be a number or a SymPy expression, not str '9.8'"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: 2j}),
     "constants.g: must be a real number"),
    (lambda: ri.mechanics.flow_of(PENDULUM, [1, 2]), "constants: must be a dict"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1}), "constants: simulation needs "
                                                             "numbers for g"),
    (lambda: ri.mechanics.flow_of(UNFORMED, {m: 1, ell: 1, g_: 1}),
     "system: its equations of motion are not formed yet: call kanes_equations(bodies, "
     "loads) first"),
    (lambda: ri.mechanics.flow_of(3, {m: 1}), "system: must be a sympy.physics.mechanics "
                                              "KanesMethod or System, not int"),
    (lambda: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: 1})(0, np.zeros(3)),
     "x: must be the state [q, u] of 2 real numbers, not an array of float64 of shape (3,)"),
    (lambda: ri.mechanics.flow_of(me.System(me.ReferenceFrame("S")), {}),
     "system: its equations of motion are not formed yet: call form_eoms() first"),
    (lambda: ri.mechanics.impact(UNFORMED, [C(UNFORMED_BOB, -UNFORMED_FRAME.x)]),
     "system: its equations of motion are not formed yet: call kanes_equations"),
    (lambda: ri.mechanics.impact("kane", [C(BOB, -N.x)]),
     "system: must be a sympy.physics.mechanics KanesMethod or System, not str"),
])
def test_flow_and_impact_of_a_mechanics_system_refuse_in_one_line(call, needle):
    with pytest.raises(InputError) as info:
        call()
    message = str(info.value)
    assert needle in message and "\n" not in message and "Fr*" not in message


def test_flow_of_takes_python_numbers_and_a_zero_length_limit():
    rhs = ri.mechanics.flow_of(PENDULUM, {m: 2, ell: 1, g_: 9.8})
    # q'' = -(g / l) sin q
    assert rhs(0.0, np.array([0.1, 0.0])) == pytest.approx([0.0, -9.8 * np.sin(0.1)])
    assert rhs(0.0, [0.1, 0.0]) == pytest.approx([0.0, -9.8 * np.sin(0.1)])
    # a symbol declared positive may be put at its limit 0 (a walker's point foot)
    still = ri.mechanics.flow_of(PENDULUM, {m: 2, ell: 1, g_: 0})
    assert still(0.0, np.array([0.1, 0.5])).tolist() == [0.5, 0.0]


MAP = ri.mechanics.impact(KANE, [C(BOB, N.x, restitution=sp.Rational(1, 2))],
                          frame=N).kernel({m: 3, ell: 1})
AB = ri.Kernel.from_expr(sp.Symbol("a") * sp.Symbol("b") + 1)


def test_the_map_takes_huge_finite_states_its_one_pass_check_would_overflow_on():
    # the check sums the states first: a sum of huge finite numbers overflows, and the
    # states are then looked at one by one (and taken: they are finite), with no warning
    states = np.full((4, 1), 1e308)
    found = MAP(states, -states)
    assert found.speeds_after.shape == (4, 1)


@pytest.mark.parametrize("call, needle", [
    (lambda: MAP([[0.1, 0.2]], [[-1.0]]), "q: must be an array (states, 1) or one state of "
                                          "1, not one of shape (1, 2)"),
    (lambda: MAP(np.zeros((3, 1, 2)), np.zeros((3, 1))), "q: must be an array (states, 1)"),
    (lambda: MAP(np.zeros((3, 1)), np.zeros((3, 2))), "u: must be an array (states, 1)"),
    (lambda: MAP(np.zeros((3, 1)), np.zeros((2, 1))), "u: must have a row for each state "
                                                      "of q: q has 3 states, u 2"),
    (lambda: MAP("a", [[1.0]]), "q: must be real numbers, an array (states, 1), not str"),
    (lambda: MAP([[1j]], [[-1.0]]), "q: must be real numbers"),
    (lambda: MAP(None, [[1.0]]), "q: must be real numbers, an array (states, 1), not "
                                 "NoneType"),
    (lambda: MAP([[0.1], [0.2], [np.nan]], [[-1.0]] * 3), "q: must be finite: state 2 "
                                                         "holds NaN or an infinity"),
    (lambda: MAP([[0.1], [0.2]], [[-1.0], [np.inf]]), "u: must be finite: state 1"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, N.x, restitution=e)], frame=N).kernel(
        {m: float("nan"), ell: 1, e: 1}), "values.m: must be finite, not nan"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, N.x)], frame=N).kernel({m: "1", ell: 1}),
     "values.m: must be a number or a SymPy expression, not str '1'"),
    (lambda: ri.mechanics.impact(KANE, [C(BOB, N.x)], frame=N).kernel([1]),
     "values: must be a dict of SymPy symbols to numbers, not list"),
    (lambda: AB(a=np.ones(3), b=np.ones(2)), "values: the arrays do not broadcast "
                                             "together: a (3,), b (2,)"),
    (lambda: AB(a=np.ones(3)), "values: the kernel needs a number for b (its arguments: "
                               "a, b)"),
    (lambda: AB(a="1.5", b=1), "a: must be real numbers (a number or an array of them), "
                               "not str '1.5'"),
    (lambda: AB(a=1, b=2j), "b: must be real numbers"),
    (lambda: AB.mp(a="1.5", b=1), "a: must be a real number, not str '1.5'"),
    (lambda: AB.reference(a=1), "values: the kernel needs a number for b"),
    (lambda: AB.scale(a=1, b=sp.Symbol("x")), "b: must be a number, not x"),
    (lambda: ri.Kernel.from_expr("a*b"), "expr: must be a number or a SymPy expression, "
                                         "not str 'a*b'"),
    (lambda: ri.Kernel.from_expr([1, 2]), "expr: must be a number or a SymPy expression"),
])
def test_kernels_refuse_wrong_shapes_and_types_in_one_line(call, needle):
    with pytest.raises(InputError) as info:
        call()
    message = str(info.value)
    assert needle in message and "\n" not in message and "broadcast" not in message.split(
        ":")[0]


def test_kernels_take_numbers_of_every_kind():
    # e = 1/2, m = 3, l = 1, hitting the wall at rate -2 from q = 0: u after = 1
    assert MAP([[0.0]], [[-2.0]]).speeds_after.tolist() == [[1.0]]
    assert MAP([0.0], [-2.0]).speeds_after.tolist() == [[1.0]]  # one state as a row
    assert AB(a=sp.Integer(2), b=np.arange(3)).tolist() == [1.0, 3.0, 5.0]
    assert AB.mp(a=sp.Rational(1, 2), b=2) == 2
    assert ri.Kernel.from_expr(3)() == 3.0


# what the probe throws at each argument: wrong types, shapes and numbers
WRONG = ["x", b"1", None, 1j, float("nan"), float("inf"), [1, "a"], {"a": 1}, (1, 2),
         np.zeros((2, 3, 4)), np.array(["1"]), object(), sp.Symbol("z"), -1, True]
ENTRIES = {
    "Body3.at": lambda w: ri.Body3.sphere(M3, R3, name="ball").at({M3: w}),
    "SpaceCollision.at": lambda w: _sphere_on_floor().at({R3: w}),
    "landing_time": lambda w: landing_time(2, w, 10),
    "sliding": lambda w: sliding(*_STILL, w, 0.4, 0.2, 9.8),
    "flight": lambda w: flight(*_FLIGHT, w),
    "spheres": lambda w: spheres(*_rough_drop(), impacts=1, compliance=w),
    "flow_of": lambda w: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: w}),
    "flow_of(x)": lambda w: ri.mechanics.flow_of(PENDULUM, {m: 1, ell: 1, g_: 1})(0, w),
    "kernel": lambda w: MAP(w, [[-1.0]]),
    "Kernel": lambda w: AB(a=w, b=1.0),
    "Kernel.mp": lambda w: AB.mp(a=w, b=1),
    "impact": lambda w: ri.mechanics.impact(w, [C(BOB, N.x)]),
    "Collision.solve": lambda w: ri.chain(3).solve(w),
}


@pytest.mark.parametrize("entry", sorted(ENTRIES))
def test_a_seeded_probe_of_wrong_inputs_gets_one_line_from_the_package(entry):
    # seed 20261207: three wrong inputs drawn per entry, in a fixed order; every failure
    # is the package's own InputError of one line, never a library's message
    rng = np.random.default_rng(20261207)
    picks = sorted(rng.choice(len(WRONG), size=len(WRONG), replace=False))
    for k in picks:
        wrong = WRONG[k]
        try:
            ENTRIES[entry](wrong)
        except InputError as err:
            assert "\n" not in str(err) and str(err).split(":")[0].strip()
        except Exception as err:  # pragma: no cover - what the probe is for
            pytest.fail(f"{entry}({wrong!r}) raised {type(err).__name__}: {err}")
