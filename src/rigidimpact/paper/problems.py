"""The paper's problems built from primitives and solved: each gives a :class:`Derivation`.

Built-in names: ``barbell`` (section 1), ``sticking`` (the clay ball of
figure 2), ``discs`` (equal smooth discs, eq. 16) and ``two-body`` (the general smooth
planar impact of section 3). Nothing here is typed in from the paper's results: every
result is solved from the laws; :mod:`rigidimpact.paper.published` holds what it is checked against.

Examples
--------
>>> d = derive("barbell")
>>> d.results["V_x"]
m*v_ix*(e + 1)/(2*M + m*sin(theta)**2 + m)
>>> d.named["v_fx"]
v_ix*(-2*M*f + m)/m
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Mapping
from dataclasses import replace

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws import law as laws
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.bodies import Body, join
from rigidimpact.solve.derivation import Derivation
from rigidimpact.solve.impact import Impact
from rigidimpact.solve.solution import Solution
from rigidimpact.symbolic.notation import Given, symbol
from rigidimpact.symbolic.rewrite import recognise, solve_linear, tidy

__all__ = [
    "PROBLEMS",
    "derive",
    "barbell_impact",
    "barbell",
    "sticking",
    "sticking_routes",
    "sphere_a_velocity",
    "discs",
    "two_body",
]

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
BALL_BARBELL_UNKNOWNS = (("v_fx", "v_fy", "omega"), ("V_x", "V_y", "omega_z"))
# Mungan's equation numbers for the generic laws, attached to the paper's own problems only
PAPER_NUMBERS = (
    ("normal momentum", "(1), (12)"),
    ("tangential momentum", "(13)"),
    ("pair tangential momentum", "(13), summed"),
    ("angular momentum", "(2), (14)"),
    ("restitution", "(3), (4)"),
    ("no slip", "(8)-(9), fig. 2"),
)


def barbell_impact(restitution: sp.Expr = e, tangential: str = "smooth") -> Impact:
    """Section 1: a ball (point mass m, speed v_ix along x) strikes sphere A of a barbell
    at rest (two masses M, rod 2L at angle theta to x).

    Examples
    --------
    >>> [str(u) for u in barbell_impact().unknowns]
    ['v_fx', 'v_fy', 'V_x', 'V_y', 'omega_z']
    """
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    return Impact(ball, bar, Contact(restitution=restitution, tangential=tangential),
                  BALL_BARBELL_UNKNOWNS, PAPER_NUMBERS)


@functools.cache
def barbell_solution(restitution: sp.Expr = e, tangential: str = "smooth") -> Solution:
    """The solved :func:`barbell_impact`, solved once per process (several derivations
    and checks start from the same impact).

    Examples
    --------
    >>> barbell_solution(0, "stick") is barbell_solution(0, "stick")
    True
    """
    return barbell_impact(restitution, tangential).solve()


def _timed(build: Callable[[], Derivation]) -> Callable[[], Derivation]:
    """Time a problem's derivation once; later calls return the same (immutable) result."""

    @functools.cache
    def run() -> Derivation:
        start = time.perf_counter()
        derivation = build()
        return replace(derivation, seconds=time.perf_counter() - start)

    functools.update_wrapper(run, build)
    return run


# the givens the paper's problems share, their symbols set as mathematics
_BALL = Given("ball: point mass {} moving along x with speed {}", symbol("m"), symbol("v_ix"))
_BARBELL = Given("barbell: masses {} at both ends of a massless rod of length 2{}, at rest, "
                 "rod at angle {} to x", symbol("M"), symbol("L"), symbol("theta"))
# body k of the two (k = 1, 2): placeholders for either body's data
_BODY_K = Given("body k: mass {}, central inertia {}, centre {} = {} from O, velocity {}, "
                "spin {}", *sp.symbols("m_k I_k R_k"), sp.symbols("R_kx R_ky"),
                sp.symbols("V_kix V_kiy"), sp.Symbol("omega_kiz"))


@_timed
def barbell() -> Derivation:
    """The ball and the barbell of section 1: eqs. (1), (2), (4) solved, (5) and (7).

    Examples
    --------
    >>> barbell().results["omega_z"]
    m*v_ix*(e + 1)*sin(theta)/(L*(2*M + m*sin(theta)**2 + m))
    """
    impact = barbell_impact()
    solution = barbell_solution()
    values = solution.values
    f = symbol("f")
    f_definition = tidy(values[symbol("V_x")] / v_ix)
    results = {
        "v_fx": values[symbol("v_fx")],
        "V_x": values[symbol("V_x")],
        "omega_z": values[symbol("omega_z")],
        "f": f_definition,
        "energy_loss_fraction": solution.energy_loss_fraction,
    }
    named = {key: recognise(results[key], f, f_definition, e)
             for key in ("v_fx", "V_x", "omega_z")}
    return Derivation(
        "barbell",
        "A ball strikes one end of a barbell at an angle (section 1)",
        (_BALL,
         _BARBELL + Given("; sphere A is struck at O"),
         Given("contact: smooth, Newton restitution {} along x", e)),
        impact.equations(),
        impact.unknowns,
        results,
        named,
        {"f": f_definition},
        solution,
    )


def sphere_a_velocity() -> sp.ImmutableMatrix:
    """Velocity of the struck sphere A just after the impact (section 2).

    Its y component is negative for 0 < theta < 90 degrees although the impulse is
    along +x: the rod's rotation carries A sideways.

    Examples
    --------
    >>> sphere_a_velocity()[1]
    -m*v_ix*(e + 1)*sin(theta)*cos(theta)/(2*M + m*sin(theta)**2 + m)
    """
    bar = barbell_solution().second_after
    sphere_a = next(p for p in bar.parts if p.label == "A")
    return bar.point_velocity(sphere_a.position).applyfunc(tidy)


@functools.cache
def _composite_route() -> tuple[tuple[Equation, ...], dict[str, sp.Expr]]:
    """Eqs. (8)-(9): ball and barbell move as one body (u, omega) about S after."""
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    centre = join(ball, bar).position
    u_x, u_y, omega = symbol("u_x"), symbol("u_y"), symbol("omega_z")
    u = sp.Matrix([u_x, u_y])

    def carried(body: Body) -> Body:
        arm = body.position - centre  # velocity of a point rigidly carried about S
        return body.with_motion(u + sp.Matrix([-omega * arm[1], omega * arm[0]]), omega
                                if not body.inertia.is_zero else 0)

    ball_after, bar_after = carried(ball), carried(bar)
    equations = (
        laws.normal_momentum(ball, ball_after, bar, bar_after),
        laws.pair_tangential_momentum(ball, ball_after, bar, bar_after),
        laws.angular_momentum(bar, bar_after),
    )
    solved = solve_linear([eq.residual for eq in equations], [u_x, u_y, omega])
    numbered = tuple(Equation(eq.label, p, tidy(eq.lhs), tidy(eq.rhs)) for eq, p in
                     zip(equations, ("(8)", "(8), y", "(9)"), strict=True))
    return numbered, {"u_x": tidy(solved[u_x]), "omega_z": tidy(solved[omega])}


def sticking_routes() -> dict[str, dict[str, sp.Expr]]:
    """The clay ball's u_x and omega_z by four independent routes.

    ``composite``: eqs. (8)-(9), the pair moving as one body about S.
    ``alternative``: eqs. (1) and (4) with e = 0 and eq. (2) with V_y = omega h cos(theta).
    ``parallel-axis``: the textbook route, :func:`~rigidimpact.model.bodies.join`, inertia about S.
    ``impact``: the general solver with a sticking contact and e = 0.

    Examples
    --------
    >>> sorted(sticking_routes())
    ['alternative', 'composite', 'impact', 'parallel-axis']
    """
    routes = {"composite": _composite_route()[1]}

    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    h = _sticking_h()
    smooth = barbell_impact(restitution=0)
    v_fx, V_x, V_y, omega = (symbol(n) for n in ("v_fx", "V_x", "V_y", "omega_z"))
    by_number = {eq.paper: eq for eq in smooth.equations()}
    modified = [by_number["(1), (12)"], by_number["(3), (4)"],
                by_number["(2), (14)"].subs(V_y, omega * h * sp.cos(theta))]
    solved = solve_linear([eq.residual for eq in modified], [v_fx, V_x, omega])
    routes["alternative"] = {
        "u_x": tidy((m * solved[v_fx] + 2 * M * solved[V_x]) / (2 * M + m)),
        "omega_z": tidy(solved[omega]),
    }

    composite = join(ball, bar)
    routes["parallel-axis"] = {"u_x": composite.velocity[0], "omega_z": composite.spin}

    stuck = barbell_solution(0, "stick")
    routes["impact"] = {
        "u_x": tidy((stuck.first_after.momentum[0] + stuck.second_after.momentum[0])
                    / (2 * M + m)),
        "omega_z": stuck.second_after.spin,
    }
    return routes


@functools.cache
def _sticking_h() -> sp.Expr:
    """Distance from the barbell's centre C to the pair's centre S, along the rod."""
    ball = Body.particle(m, velocity=(v_ix, 0), name="ball")
    bar = Body.barbell(M, L, theta)
    offset = bar.position - join(ball, bar).position
    along_rod = offset[0] * sp.cos(theta) + offset[1] * sp.sin(theta)
    return tidy(along_rod)


@_timed
def sticking() -> Derivation:
    """The clay ball of figure 2: it sticks to sphere A; eqs. (8)-(10).

    Examples
    --------
    >>> sticking().results["omega_z"]
    m*v_ix*sin(theta)/(2*L*(M + m))
    """
    equations, values = _composite_route()
    h = _sticking_h()
    results = {"u_x": values["u_x"], "omega_z": values["omega_z"], "h": h}
    return Derivation(
        "sticking",
        "A clay ball sticks to one end of a barbell (figure 2)",
        (_BALL + Given("; it sticks to sphere A"),
         _BARBELL,
         Given("after: ball and barbell move as one rigid body with centre S, velocity {} "
               "and spin {}", symbol("u"), symbol("omega_z"))),
        equations,
        (symbol("u_x"), symbol("u_y"), symbol("omega_z")),
        results,
    )


@_timed
def discs() -> Derivation:
    """Equal smooth discs, neither spinning: the impact is central; eq. (16).

    Examples
    --------
    >>> discs().results["V_1fx"]
    V_1ix*(1 - e)/2 + V_2ix*(e + 1)/2
    """
    mass, radius = symbol("m"), symbol("r")
    names = ("V_1ix", "V_1iy", "V_2ix", "V_2iy")
    v1x, v1y, v2x, v2y = (symbol(n) for n in names)
    first = Body.disc(mass, radius, side=-1, velocity=(v1x, v1y), name="disc1")
    second = Body.disc(mass, radius, side=1, velocity=(v2x, v2y), name="disc2")
    impact = Impact(first, second, Contact(restitution=e), numbers=PAPER_NUMBERS)
    solution = impact.solve()
    res = solution.results()

    def by_velocity(expr: sp.Expr) -> sp.Expr:
        # the paper writes (16) as a weighted sum of the two initial velocities
        numerator, denominator = sp.fraction(expr)
        return sp.collect(sp.expand(numerator), [v1x, v2x]) / denominator

    results = {"V_1fx": by_velocity(res["disc1.vx"]), "V_2fx": by_velocity(res["disc2.vx"]),
               "V_1fy": res["disc1.vy"], "V_2fy": res["disc2.vy"],
               "omega_1fz": res["disc1.omega"], "omega_2fz": res["disc2.omega"]}
    return Derivation(
        "discs",
        "Two equal smooth discs collide (eq. 16)",
        (Given("discs: equal masses {} and radii {}, not spinning, centres on the normal",
               symbol("m"), symbol("r")),
         Given("velocities {} and {}; smooth contact, restitution {}",
               (symbol("V_1ix"), symbol("V_1iy")), (symbol("V_2ix"), symbol("V_2iy")),
               symbol("e"))),
        impact.equations(),
        impact.unknowns,
        results,
        solution=solution,
    )


def two_body_impact(restitution: sp.Expr = e) -> Impact:
    """Section 3: two general rigid bodies, smooth contact, in the paper's notation."""
    bodies = []
    for k in (1, 2):
        s = {n: symbol(n.format(k=k)) for n in ("m_{k}", "I_{k}", "R_{k}x", "R_{k}y",
                                                "V_{k}ix", "V_{k}iy", "omega_{k}iz")}
        bodies.append(Body.rigid(s["m_{k}"], s["I_{k}"], (s["R_{k}x"], s["R_{k}y"]),
                                 velocity=(s["V_{k}ix"], s["V_{k}iy"]),
                                 spin=s["omega_{k}iz"], name=f"body{k}"))
    return Impact(bodies[0], bodies[1], Contact(restitution=restitution),
                  numbers=PAPER_NUMBERS)


@_timed
def two_body() -> Derivation:
    """The general smooth planar impact of section 3: eqs. (11)-(14) solved.

    Examples
    --------
    >>> two_body().results["V_1fy"]
    V_1iy
    """
    impact = two_body_impact()
    solution = impact.solve()
    results = {str(u): solution.values[u] for u in impact.unknowns}
    # the normal impulse J collects the long common factor of every result: written
    # straight from the core (u+ = u- + M^-1 J^T J), not by eliminating e again
    J = symbol("J")
    by_impulse = impact.in_terms_of(J)
    named = {str(u): by_impulse[u] for u in impact.unknowns if results[str(u)].has(e)}
    return Derivation(
        "two-body",
        "Two rigid bodies, smooth contact (section 3)",
        (_BODY_K, Given("contact: smooth, normal along x, Newton restitution {}", e)),
        impact.equations(),
        impact.unknowns,
        results,
        named,
        {"J": solution.normal_impulse},
        solution,
    )


PROBLEMS: Mapping[str, Callable[[], Derivation]] = {
    "barbell": barbell,
    "sticking": sticking,
    "discs": discs,
    "two-body": two_body,
}


def derive(name: str) -> Derivation:
    """Derive a built-in problem by name.

    Examples
    --------
    >>> derive("discs").problem
    'discs'
    """
    try:
        build = PROBLEMS[name]
    except KeyError:
        raise InputError("problem", f"unknown problem {name!r}; built-in problems are "
                         f"{', '.join(PROBLEMS)}") from None
    return build()
