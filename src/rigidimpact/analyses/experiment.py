"""The rigid model against measurements: a sphere striking a flat obliquely.

Kharaz, Gorham and Salman (Powder Technology 120, 2001) shot 5 mm alumina spheres at a
glass anvil at 3.9 m/s with no spin, from near normal incidence to 65 degrees, and
measured the rebound: the tangential coefficient of restitution of the centre
``e_t = |v_t after| / |v_t before|``, the rebound angle from the normal and the spin. Two
independent digitisations of their figures and a published spring-dashpot simulation of
the same impacts ship with the package (``data/kharaz2001``, sources in each file).

The model is the toolkit's own: a solid sphere and a fixed flat, one Coulomb contact with
Newton's restitution, solved by Routh's method (:class:`~rigidimpact.solve.impact.Impact`). A
sphere on a flat has no coupling between the normal and the tangential impulse (W_nt = 0),
so the contact either slides throughout (gross slip, where
``e_t = 1 - mu (1 + e) cot(angle)``) or stops sliding and rolls (``e_t = 5/7``); the three
restitution laws agree on that straight impulse path.

Examples
--------
>>> model = sphere_on_flat()
>>> [round(float(x), 4) for x in model.e_t([40.0], mu=0.092, e=1.0)]
[0.7807]
"""

from __future__ import annotations

import csv
import functools
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.laws.compliance import tangential_bounce
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.impact import Impact

__all__ = ["Measurements", "load_kharaz", "SphereOnFlat", "sphere_on_flat", "Fit", "fit",
           "SPEED", "RADIUS", "GROSS_SLIP_DEG", "compliant_bounce", "CompliantSphereOnFlat",
           "fit_compliant", "TANGENTIAL_STEPS"]

SPEED = 3.9  # m/s, the impact speed of the experiment and of the simulation
RADIUS = 2.5e-3  # m, the spheres' radius
GROSS_SLIP_DEG = 35.0  # from here up the contact slides throughout (for mu near 0.1)
QUANTITIES = ("e_t", "rebound_angle", "omega")
# steps per normal contact period of the tangentially compliant contact: its explicit
# scheme is first order; at 5 degrees e_t moves 3e-3 from 1000 to 4000 steps and 7e-4
# from 4000 to 16000
TANGENTIAL_STEPS = 4000
Angles = Sequence[float] | np.ndarray  # impact angles from the normal, in degrees


@dataclass(frozen=True)
class Measurements:
    """One data set: for each quantity, impact angles (degrees) and values."""

    name: str
    points: dict[str, tuple[np.ndarray, np.ndarray]]


def _rows(name: str) -> list[dict[str, str]]:
    text = resources.files("rigidimpact").joinpath("data", "kharaz2001", name).read_text(
        encoding="utf-8")
    return list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))


def load_kharaz() -> dict[str, Measurements]:
    """Both digitisations of the measurements and the spring-dashpot simulation.

    Examples
    --------
    >>> data = load_kharaz()
    >>> sorted(data), len(data["mfix"].points["e_t"][0])
    (['lethe', 'mfix', 'simulation'], 8)
    """
    found = {}
    for key, name in (("mfix", "digitized-mfix-dem05.csv"), ("lethe", "digitized-lethe.csv")):
        points: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        rows = _rows(name)
        for quantity in QUANTITIES:
            chosen = [r for r in rows if r["quantity"] == quantity]
            points[quantity] = (np.array([float(r["impact_angle_deg"]) for r in chosen]),
                                np.array([float(r["value"]) for r in chosen]))
        found[key] = Measurements(key, points)
    rows = _rows("mfix-dem05-spring-dashpot-simulation.csv")
    angles = np.array([float(r["impact_angle_deg"]) for r in rows])
    columns = {"e_t": "e_t", "omega": "omega_rad_s", "rebound_angle": "rebound_angle_deg"}
    found["simulation"] = Measurements("simulation", {
        q: (angles, np.array([float(r[c]) for r in rows])) for q, c in columns.items()})
    return found


@dataclass(frozen=True)
class SphereOnFlat:
    """The rigid model's motion after, as NumPy functions of the impact angle (degrees),
    the friction coefficient and the restitution coefficient."""

    kernels: dict[str, Any]
    results: dict[str, sp.Expr]
    speed: float = SPEED
    radius: float = RADIUS

    def _after(self, degrees: Angles, mu: float, e: float) -> dict[str, np.ndarray]:
        angle = np.radians(np.asarray(degrees, dtype=float))
        return {k: np.asarray(f(angle, self.speed, self.radius, mu, e), dtype=float)
                for k, f in self.kernels.items()}

    def e_t(self, degrees: Angles, mu: float, e: float) -> np.ndarray:
        """|v_t after| / |v_t before| of the centre."""
        after = self._after(degrees, mu, e)
        return np.abs(after["vt"]) / (self.speed * np.sin(np.radians(degrees)))

    def rebound_angle(self, degrees: Angles, mu: float, e: float) -> np.ndarray:
        """atan(|v_t after| / |v_n after|) in degrees."""
        after = self._after(degrees, mu, e)
        return np.degrees(np.arctan2(np.abs(after["vt"]), np.abs(after["vn"])))

    def omega(self, degrees: Angles, mu: float, e: float) -> np.ndarray:
        """The spin after (rad/s, its size)."""
        return np.abs(self._after(degrees, mu, e)["omega"])

    def predict(self, quantity: str, degrees: Angles, mu: float,
                e: float) -> np.ndarray:
        return getattr(self, quantity)(degrees, mu, e)


@functools.cache
def sphere_on_flat() -> SphereOnFlat:
    """Derive the oblique impact of a solid sphere on a rough fixed flat once, in closed
    form over every course (slip throughout, or slip then roll), and compile it."""
    angle = sp.Symbol("alpha", positive=True)
    v, r, m = sp.symbols("v r m", positive=True)
    e = sp.Symbol("e", nonnegative=True)
    mu = sp.Symbol("mu", nonnegative=True)
    ball = Body.sphere(m, r, (0, r), 1, (v * sp.sin(angle), -v * sp.cos(angle)), 0, "ball")
    flat = Body.fixed("flat")
    solution = Impact(ball, flat, Contact(normal=(0, -1), restitution=e,
                                          tangential="coulomb", friction=mu)).solve()
    found = solution.results()
    # the ball's mass cancels; the flat's normal is -y, so v_t is x and v_n is y
    results = {"vt": found["ball.vx"], "vn": found["ball.vy"], "omega": found["ball.omega"]}
    # the courses' conditions mix the angle with scalars: each point is evaluated by
    # plain Python (a handful of points, a fit of a few hundred calls)
    kernels = {k: np.vectorize(sp.lambdify((angle, v, r, mu, e), x.subs(m, 1),
                                           modules="math"))
               for k, x in results.items()}
    return SphereOnFlat(kernels, results)


@dataclass(frozen=True)
class Fit:
    """The friction and restitution coefficients that fit the measurements best.

    ``rms`` holds each quantity's root-mean-square residual over the points fitted
    (e_t, rebound angle in degrees, spin in rad/s), ``points`` how many there were.
    """

    mu: float
    e: float
    rms: dict[str, float]
    points: int
    cost: float
    from_deg: float
    ratio: float | None = None  # the tangentially compliant model's k_t / k_n


def _scales(data: dict[str, Measurements]) -> dict[str, float]:
    """Each quantity's residual is divided by the spread of its values (so the three are
    weighed alike; an angle in degrees and a spin in rad/s are not comparable)."""
    scales = {}
    for quantity in QUANTITIES:
        values = np.concatenate([d.points[quantity][1] for d in data.values()])
        scales[quantity] = float(np.ptp(values))
    return scales


def fit(data: dict[str, Measurements] | None = None, from_deg: float = GROSS_SLIP_DEG,
        quantities: Sequence[str] = QUANTITIES) -> Fit:
    """Least squares for (mu, e) over both digitisations at impact angles from `from_deg`
    up (the gross-slip range, where the rigid model's assumptions hold), each quantity's
    residual scaled by the spread of its measured values.

    Examples
    --------
    >>> found = fit()
    >>> 0.05 < found.mu < 0.2 and 0.8 < found.e <= 1.0
    True
    """
    from scipy.optimize import least_squares

    if data is None:
        data = {k: v for k, v in load_kharaz().items() if k != "simulation"}
    model = sphere_on_flat()
    scales = _scales(data)
    chosen = [(q, d.points[q][0][d.points[q][0] >= from_deg],
               d.points[q][1][d.points[q][0] >= from_deg])
              for d in data.values() for q in quantities]

    def residuals(p: np.ndarray) -> np.ndarray:
        return np.concatenate([(model.predict(q, a, p[0], p[1]) - y) / scales[q]
                               for q, a, y in chosen])

    found = least_squares(residuals, x0=[0.1, 0.9], bounds=([0.0, 0.0], [2.0, 1.0]),
                          xtol=1e-12, ftol=1e-12)
    mu, e = (float(x) for x in found.x)
    rms = {}
    for quantity in quantities:
        parts = [model.predict(q, a, mu, e) - y for q, a, y in chosen if q == quantity]
        joined = np.concatenate(parts)
        rms[quantity] = float(np.sqrt(np.mean(joined**2)))
    return Fit(mu, e, rms, sum(len(a) for _, a, _ in chosen), float(found.cost), from_deg)


def departures(result: Fit, data: dict[str, Measurements] | None = None,
               below_deg: float = 30.0) -> dict[str, float]:
    """The largest |model - measurement| of each quantity at impact angles below
    `below_deg`, with the fitted coefficients: where the rigid model leaves the data (the
    contact's tangential compliance lets the sphere spring back sideways, which a rigid
    contact that sticks cannot do).

    Examples
    --------
    >>> round(departures(fit())["e_t"], 2) > 0.05
    True
    """
    if data is None:
        data = {k: v for k, v in load_kharaz().items() if k != "simulation"}
    model = sphere_on_flat()
    worst: dict[str, float] = {}
    for d in data.values():
        for q in QUANTITIES:
            angles, values = d.points[q]
            keep = (angles < below_deg) & (angles > 0.5)
            if keep.any():
                gap = np.abs(model.predict(q, angles[keep], result.mu, result.e) - values[keep])
                worst[q] = max(worst.get(q, 0.0), float(gap.max()))
    return worst


def compliant_bounce(degrees: Angles, mu: float, e: float, ratio: float,
                     steps: int = TANGENTIAL_STEPS) -> dict[str, np.ndarray]:
    """A solid sphere striking a flat with a tangentially compliant contact
    (:func:`rigidimpact.laws.compliance.tangential_bounce`), for every impact angle at
    once: the centre's tangential and normal velocity and the spin after, at the
    experiment's speed and radius. The sphere, once its contact stops sliding, is sprung
    back sideways: the rigid contact, which rolls it away at 5/7, cannot.

    Examples
    --------
    With the coefficients of the published spring-dashpot simulation (mu = 0.092, e = 1,
    k_t / k_n = 1.48 / 1.72) at 40 degrees:

    >>> after = compliant_bounce([40.0], 0.092, 1.0, 1.48 / 1.72)
    >>> round(float(abs(after["vt"][0]) / (SPEED * np.sin(np.radians(40.0)))), 4)
    0.7807
    """
    angle = np.radians(np.asarray(degrees, dtype=float))
    vt, vn, spin = tangential_bounce(SPEED * np.sin(angle), -SPEED * np.cos(angle), 0.0, mu,
                                     e, ratio, 0.4, steps)
    return {"vt": vt, "vn": vn, "omega": spin / RADIUS}


@dataclass(frozen=True)
class CompliantSphereOnFlat:
    """The tangentially compliant model's motion after (:func:`compliant_bounce`), with
    the same quantities as :class:`SphereOnFlat`."""

    ratio: float
    steps: int = TANGENTIAL_STEPS

    def predict(self, quantity: str, degrees: Angles, mu: float, e: float) -> np.ndarray:
        degrees = np.asarray(degrees, dtype=float)
        after = compliant_bounce(degrees, mu, e, self.ratio, self.steps)
        if quantity == "e_t":
            return np.abs(after["vt"]) / (SPEED * np.sin(np.radians(degrees)))
        if quantity == "rebound_angle":
            return np.degrees(np.arctan2(np.abs(after["vt"]), np.abs(after["vn"])))
        return np.abs(after["omega"])


def fit_compliant(data: dict[str, Measurements] | None = None, steps: int = 2000,
                  quantities: Sequence[str] = QUANTITIES) -> Fit:
    """Least squares for (mu, e, k_t / k_n) of the tangentially compliant model over both
    digitisations at every impact angle (above 0.5 degrees, where e_t is 0 / 0), each
    quantity's residual scaled as in :func:`fit`; the rms residuals are then evaluated at
    :data:`TANGENTIAL_STEPS`."""
    from scipy.optimize import least_squares

    if data is None:
        data = {k: v for k, v in load_kharaz().items() if k != "simulation"}
    scales = _scales(data)
    chosen = [(q, d.points[q][0][d.points[q][0] > 0.5], d.points[q][1][d.points[q][0] > 0.5])
              for d in data.values() for q in quantities]

    def residuals(p: np.ndarray) -> np.ndarray:
        model = CompliantSphereOnFlat(float(p[2]), steps)
        return np.concatenate([(model.predict(q, a, p[0], p[1]) - y) / scales[q]
                               for q, a, y in chosen])

    found = least_squares(residuals, x0=[0.1, 0.95, 0.8],
                          bounds=([0.0, 0.5, 0.05], [1.0, 1.0, 5.0]), xtol=1e-10,
                          ftol=1e-10)
    mu, e, ratio = (float(x) for x in found.x)
    model = CompliantSphereOnFlat(ratio)
    rms = {}
    for quantity in quantities:
        joined = np.concatenate([model.predict(q, a, mu, e) - y
                                 for q, a, y in chosen if q == quantity])
        rms[quantity] = float(np.sqrt(np.mean(joined**2)))
    return Fit(mu, e, rms, sum(len(a) for _, a, _ in chosen), float(found.cost), 0.0,
               ratio)
