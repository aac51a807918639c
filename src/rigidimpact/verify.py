"""Checking derived results against the paper: the check lists, and running them.

Each check compares a derived result with the paper's by the two independent tests of
:mod:`rigidimpact.symbolic.compare` (an exact symbolic zero, and agreement to 40 digits at seeded
points); ``rigidimpact verify`` runs the paper's checks below, the re-strike's
(``restrike.CHECKS``) and the textbook catalogue's (``catalogue.CHECKS``).

Examples
--------
>>> [c.status for c in run_checks(lambda i: i == "discs.solution")]
['pass']
"""

from __future__ import annotations

import random
import time
from collections.abc import Callable
from dataclasses import dataclass

import sympy as sp

from rigidimpact.analyses import restrike
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.paper import catalogue, problems
from rigidimpact.paper.published import REFERENCES
from rigidimpact.solve.impact import Impact
from rigidimpact.symbolic.compare import (
    SEED,
    Verdict,
    agree,
    same_equation,
    symbolic_zero,
)
from rigidimpact.symbolic.compare import all_of as _all
from rigidimpact.symbolic.evaluate import value_at
from rigidimpact.symbolic.notation import symbol
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Verdict", "Check", "agree", "same_equation", "symbolic_zero", "run_checks",
           "CHECKS", "register"]

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))


@dataclass(frozen=True)
class Check:
    """One row of ``rigidimpact verify``."""

    id: str
    paper: str
    description: str
    status: str
    detail: str
    seconds: float


def _ref(key: str) -> sp.Expr:
    return REFERENCES[key].expr


# ---- the checks ----------------------------------------------------------------------

CHECKS: list[tuple[str, str, str, Callable[[], Verdict]]] = []


def register(check_id: str, paper: str, description: str):
    """Add one of the paper's checks to this module's list (a decorator for the checks
    below; other modules give their checks as an explicit ``CHECKS`` tuple).

    Examples
    --------
    >>> @register("demo.zero", "-", "zero is zero")
    ... def _demo() -> Verdict:
    ...     return Verdict(True, "trivially")
    >>> [c.status for c in run_checks(lambda i: i == "demo.zero")]
    ['pass']
    >>> del CHECKS[-1]
    """

    def add(fn: Callable[[], Verdict]) -> Callable[[], Verdict]:
        if any(row[0] == check_id for row in CHECKS):
            raise ValueError(f"check {check_id!r} is registered twice")
        CHECKS.append((check_id, paper, description, fn))
        return fn

    return add


_check = register


def _barbell() -> problems.Derivation:
    return problems.barbell()


@_check("barbell.equations", "(1), (2), (4)",
        "the laws built from the bodies are the paper's equations (with V_y = 0 from (13))")
def _barbell_equations() -> Verdict:
    by_number = {eq.paper: eq for eq in problems.barbell_impact().equations()}
    no_y = {symbol("V_y"): 0, symbol("v_fy"): 0}
    unknowns = [symbol(n) for n in ("v_fx", "V_x", "omega_z")]
    return _all([
        ("(1)", same_equation(by_number["(1), (12)"].residual, _ref("barbell.eq1"), unknowns)),
        ("(2)", same_equation(by_number["(2), (14)"].residual.xreplace(no_y), _ref("barbell.eq2"),
                              unknowns)),
        ("(4)", same_equation(by_number["(3), (4)"].residual, _ref("barbell.eq4"), unknowns)),
    ])


@_check("barbell.f", "(5)", "the dimensionless ratio f recognised in V_x / v_ix")
def _barbell_f() -> Verdict:
    return agree(_barbell().definitions["f"], _ref("barbell.f"))


@_check("barbell.solution", "(5)", "v_fx, V_x and omega_z solved from (1), (2), (4)")
def _barbell_solution() -> Verdict:
    d = _barbell()
    f = symbol("f")
    named_back = {k: d.named[k].xreplace({f: d.definitions["f"]}) for k in d.named}
    return _all([(k, agree(d.results[k], _ref(f"barbell.{k}"))) for k in
                 ("v_fx", "V_x", "omega_z")]
                + [(f"{k} via f", agree(named_back[k], _ref(f"barbell.{k}"))) for k in
                   ("v_fx", "V_x", "omega_z")])


@_check("barbell.head-on", "(5), section 1",
        "theta = 0: no spin; e = 0 and e = 1 give the 1-D results")
def _barbell_head_on() -> Verdict:
    r = _barbell().results
    at = {theta: 0}
    return _all([
        ("omega_z = 0", agree(r["omega_z"].xreplace(at), 0)),
        ("e = 0 v_fx", agree(r["v_fx"].xreplace({**at, e: 0}), _ref("barbell.theta0.e0"))),
        ("e = 0 V_x", agree(r["V_x"].xreplace({**at, e: 0}), _ref("barbell.theta0.e0"))),
        ("e = 1 v_fx", agree(r["v_fx"].xreplace({**at, e: 1}), _ref("barbell.theta0.e1.v_fx"))),
        ("e = 1 V_x", agree(r["V_x"].xreplace({**at, e: 1}), _ref("barbell.theta0.e1.V_x"))),
    ])


@_check("barbell.right-angle", "section 2", "theta = 90 degrees, e = 0: v_fx = 2 V_x")
def _barbell_right_angle() -> Verdict:
    r = _barbell().results
    at = {theta: sp.pi / 2, e: 0}
    return _all([("v_fx", agree(r["v_fx"].xreplace(at), _ref("barbell.theta90.e0.v_fx"))),
                 ("v_fx = 2 V_x", agree(r["v_fx"].xreplace(at), 2 * r["V_x"].xreplace(at)))])


@_check("barbell.energy", "(6) -> (7)", "K_i - K_f over K_i reduces to (7)")
def _barbell_energy() -> Verdict:
    return agree(_barbell().results["energy_loss_fraction"],
                 _ref("barbell.energy_loss_fraction"))


@_check("barbell.energy-minimum", "section 2",
        "no loss at e = 1; for e < 1 the loss is least at theta = 90 degrees")
def _barbell_energy_minimum() -> Verdict:
    loss = _barbell().results["energy_loss_fraction"]
    slope = sp.diff(loss, theta)
    # loss(theta) - loss(90) is (1 - e^2) times a square over positive factors
    excess = tidy(loss - loss.xreplace({theta: sp.pi / 2}))
    by_hand = ((1 - e**2) * 2 * M * m * sp.cos(theta) ** 2
               / ((2 * M + m * (1 + sp.sin(theta) ** 2)) * (2 * M + 2 * m)))
    return _all([("e = 1", agree(loss.xreplace({e: 1}), 0)),
                 ("slope at 90", agree(slope.xreplace({theta: sp.pi / 2}), 0)),
                 ("excess over 90 is non-negative", agree(excess, by_hand))])


@_check("barbell.sphere-A", "section 2, before (4)",
        "sphere A leaves with a -y velocity for 0 < theta < 90 degrees")
def _barbell_sphere_a() -> Verdict:
    v_a = problems.sphere_a_velocity()
    # the paper's kinematics v_2f = V + omega x (-R), with omega from (5)
    by_paper = -_ref("barbell.omega_z") * L * sp.cos(theta)
    verdict = agree(v_a[1], by_paper)
    rng = random.Random(SEED)
    one = sp.Integer(1)
    values = [value_at(v_a[1], {theta: sp.Rational(repr(rng.uniform(1e-3, 1.57))), m: one,
                                M: one, L: one, e: sp.Rational(repr(rng.uniform(0, 1))),
                                v_ix: one}) for _ in range(20)]
    negative = all(v < 0 for v in values)
    return Verdict(verdict.passed and negative,
                   f"{verdict.detail}; sign {'negative' if negative else 'NOT negative'} at "
                   f"20 angles in (0, 90) degrees")


@_check("sticking.h", "section 2", "the pair's centre S is h = mL/(2M + m) from C")
def _sticking_h() -> Verdict:
    return agree(problems.sticking().results["h"], _ref("sticking.h"))


@_check("sticking.equations", "(8), (9)",
        "the composite body's laws are the paper's (8) and (9) (with u_y = 0)")
def _sticking_equations() -> Verdict:
    eqs = problems.sticking().equations
    no_y = {symbol("u_y"): 0}
    unknowns = [symbol("u_x"), symbol("omega_z")]
    return _all([("(8)", same_equation(eqs[0].residual, _ref("sticking.eq8"), unknowns)),
                 ("(9)", same_equation(eqs[2].residual.xreplace(no_y), _ref("sticking.eq9"),
                                       unknowns))])


@_check("sticking.routes", "(10)",
        "u_x and omega_z by four routes: composite, alternative, parallel axis, solver")
def _sticking_routes() -> Verdict:
    return _all([(f"{route} {key}", agree(values[key], _ref(f"sticking.{key}")))
                 for route, values in problems.sticking_routes().items()
                 for key in ("u_x", "omega_z")])


@_check("sticking.right-angle", "section 2",
        "at theta = 90 degrees sticking and bouncing with e = 0 leave the same motion")
def _sticking_right_angle() -> Verdict:
    at = {theta: sp.pi / 2}
    stuck = problems.barbell_solution(0, "stick")
    bounced = problems.barbell_solution(0)
    pairs = [("v_fx", stuck.first_after.velocity[0], bounced.first_after.velocity[0]),
             ("V_x", stuck.second_after.velocity[0], bounced.second_after.velocity[0]),
             ("omega_z", stuck.second_after.spin, bounced.second_after.spin)]
    return _all([(name, agree(a.xreplace(at), b.xreplace(at))) for name, a, b in pairs])


@_check("discs.solution", "(16)", "equal smooth discs: V_1fx and V_2fx")
def _discs() -> Verdict:
    r = problems.discs().results
    return _all([(k, agree(r[k], _ref(f"discs.{k}"))) for k in ("V_1fx", "V_2fx")])


@_check("discs.right-angle", "section 3",
        "an elastic oblique impact on a disc at rest: the discs leave at right angles")
def _discs_right_angle() -> Verdict:
    speed, angle, mass, radius = symbol("v"), symbol("phi"), symbol("m"), symbol("r")
    first = Body.disc(mass, radius, side=-1, name="disc1",
                      velocity=(speed * sp.cos(angle), speed * sp.sin(angle)))
    second = Body.disc(mass, radius, name="disc2")
    sol = Impact(first, second, Contact(restitution=1)).solve()
    v1, v2 = sol.first_after.velocity, sol.second_after.velocity
    return _all([("dot product", agree(v1.dot(v2), 0)),
                 ("disc 1 along y", agree(v1[0], 0)),
                 ("disc 2 along x", agree(v2[1], 0))])


def _two_body_results() -> dict[str, sp.Expr]:
    return dict(problems.two_body().results)


@_check("two-body.central", "(15)", "a central impact leaves both spins unchanged")
def _two_body_central() -> Verdict:
    r = _two_body_results()
    central = {symbol("R_1y"): 0, symbol("R_2y"): 0}
    return _all([(f"omega_{k}fz", agree(r[f"omega_{k}fz"].xreplace(central),
                                        symbol(f"omega_{k}iz"))) for k in (1, 2)])


@_check("two-body.laws", "(11)-(14)", "the general solution satisfies every law it came from")
def _two_body_laws() -> Verdict:
    solution = problems.two_body().solution
    assert solution is not None  # a built-in problem keeps its solved impact
    return _all([(eq.paper, agree(eq.residual.xreplace(solution.values), 0))
                 for eq in solution.equations])


@_check("two-body.barbell", "(5) from (11)-(14)",
        "the general theory with a particle and a barbell gives (5)")
def _two_body_barbell() -> Verdict:
    r = _two_body_results()
    particle = {symbol("R_1x"): 0, symbol("R_1y"): 0}
    barbell = {symbol("m_1"): m, symbol("m_2"): 2 * M, symbol("I_2"): 2 * M * L**2,
               symbol("R_2x"): L * sp.cos(theta), symbol("R_2y"): L * sp.sin(theta),
               symbol("V_1ix"): v_ix, symbol("V_1iy"): 0, symbol("omega_1iz"): 0,
               symbol("V_2ix"): 0, symbol("V_2iy"): 0, symbol("omega_2iz"): 0}

    def reduce(expr: sp.Expr) -> sp.Expr:
        return tidy(tidy(expr.xreplace(particle)).xreplace(barbell))  # I_1 cancels once R_1 = 0

    return _all([("v_fx", agree(reduce(r["V_1fx"]), _ref("barbell.v_fx"))),
                 ("V_x", agree(reduce(r["V_2fx"]), _ref("barbell.V_x"))),
                 ("omega_z", agree(reduce(r["omega_2fz"]), _ref("barbell.omega_z")))])


@_check("two-body.discs", "(16) from (11)-(14)",
        "the general theory with two equal discs gives (16)")
def _two_body_discs() -> Verdict:
    r = _two_body_results()
    radius = symbol("r")
    discs = {symbol("m_1"): m, symbol("m_2"): m, symbol("I_1"): m * radius**2 / 2,
             symbol("I_2"): m * radius**2 / 2, symbol("R_1x"): -radius, symbol("R_1y"): 0,
             symbol("R_2x"): radius, symbol("R_2y"): 0, symbol("omega_1iz"): 0,
             symbol("omega_2iz"): 0}
    return _all([(k, agree(tidy(r[k].xreplace(discs)), _ref(f"discs.{k}")))
                 for k in ("V_1fx", "V_2fx")])


def _every() -> list[tuple[str, str, str, Callable[[], Verdict]]]:
    """The paper's checks, section 2's re-strike checks and the textbook catalogue."""
    return [*CHECKS, *restrike.CHECKS,
            *((cid, "catalogue", text, fn) for cid, text, fn in catalogue.CHECKS)]


def _run_one(check_id: str, paper: str, description: str,
             fn: Callable[[], Verdict]) -> Check:
    start = time.perf_counter()
    try:
        verdict = fn()
    except Exception as exc:  # a crashing check is a failed check, reported as such
        verdict = Verdict(False, f"error: {type(exc).__name__}: {exc}")
    return Check(check_id, paper, description, "pass" if verdict.passed else "fail",
                 verdict.detail, time.perf_counter() - start)


# rough seconds per group of checks (``run_checks(jobs=1)``), to start the longest first
GROUP_WEIGHTS = {"restrike": 2.4, "two-body": 1.8, "barbell": 1.3, "sticking": 1.2,
                 "catalogue": 1.1}


def _group(check_id: str) -> str:
    """Checks that derive the same problem run in one process, which derives it once."""
    return check_id.split(".")[0]


def _quiet_worker() -> None:
    """Ctrl-C reaches the whole process group: only the parent answers it (one line)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _run_group(ids: tuple[str, ...]) -> list[Check]:
    """The checks with these ids, in one worker process (problems derived there once)."""
    by_id = {entry[0]: entry for entry in _every()}
    return [_run_one(*by_id[i]) for i in ids]


def run_checks(select: Callable[[str], bool] = lambda _id: True,
               jobs: int = 1) -> list[Check]:
    """Run every registered check (or those `select` keeps) and time each.

    With ``jobs > 1`` the checks run in that many worker processes, grouped by the
    problem they derive (a problem is derived once per process), and come back in the
    usual order.

    Examples
    --------
    >>> [c.status for c in run_checks(lambda i: i == "barbell.f")]
    ['pass']
    """
    chosen = [entry for entry in _every() if select(entry[0])]
    if jobs <= 1 or len(chosen) < 2:
        return [_run_one(*entry) for entry in chosen]
    import multiprocessing
    import threading

    groups: dict[str, list[str]] = {}
    for entry in chosen:
        groups.setdefault(_group(entry[0]), []).append(entry[0])
    # the longest groups first, so the last to finish is a short one
    ordered = sorted(groups, key=lambda g: -GROUP_WEIGHTS.get(g, 1.0))
    # a forked worker starts with everything this process has imported; a process
    # with other threads (a test run, a notebook) is not forked, since a copy can
    # inherit a lock some other thread held: its workers start fresh
    method = ("fork" if threading.active_count() == 1
              and "fork" in multiprocessing.get_all_start_methods() else "spawn")
    with multiprocessing.get_context(method).Pool(min(jobs, len(groups)),
                                                  initializer=_quiet_worker) as pool:
        found = pool.map(_run_group, [tuple(groups[g]) for g in ordered], chunksize=1)
    by_id = {check.id: check for group in found for check in group}
    return [by_id[entry[0]] for entry in chosen]
