"""What a simulation gives back, shared by the models and the dispatcher above them.

The models (:mod:`~rigidimpact.simulate.compliant`, :mod:`~rigidimpact.simulate.several`)
and the dispatcher (:mod:`~rigidimpact.simulate.runner`) all build an :class:`Outcome`;
this module sits below all three, so none of them imports another's internals.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.bodies import Body
from rigidimpact.simulate.flight import Flyer
from rigidimpact.simulate.numbers import as_float
from rigidimpact.simulate.planner import Plan

__all__ = ["Outcome", "FlightTrack", "flyer", "finite"]


@dataclass(frozen=True)
class Outcome:
    """What a simulation found, in the keys of docs/scenes.md.

    ``final`` holds each body's ``vx, vy, omega`` and its place ``x, y`` and the angle
    ``turn`` it has turned through since the impact, at the end time ``t``.
    """

    plan: Plan
    final: Mapping[str, float]
    events: list[dict[str, Any]]
    wall_s: float
    ode_steps: int = 0
    details: Mapping[str, Any] = field(default_factory=dict)
    trajectory: Any = field(default=None, repr=False)

    def as_json(self) -> dict[str, Any]:
        return {"effects": list(self.plan.effects),
                "not_simulated": list(self.plan.not_simulated),
                "final": dict(self.final), "events": self.events,
                "cost": {"wall_s": self.wall_s, "ode_steps": self.ode_steps},
                "until": self.plan.until, **self.details}


@dataclass(frozen=True)
class FlightTrack:
    """Closed-form free flight from the impact to ``t_end``, sampled on demand for plots."""

    flyers: tuple[Flyer, ...]
    t_end: float

    @property
    def t(self) -> np.ndarray:
        return np.linspace(0.0, self.t_end, 200) if self.t_end > 0 else np.zeros(1)

    def points(self) -> dict[str, np.ndarray]:
        """Tracked points over time: a segment body's two ends, else its centre."""
        out = {}
        for f in self.flyers:
            if f.ends is not None:
                ends = [f.ends_at(t) for t in self.t]
                for k, label in enumerate(f.labels):
                    out[f"{f.name}.{label}"] = np.array([pair[k] for pair in ends])
            else:
                out[f.name] = np.array([f.at(t)[0] for t in self.t])
        return out


def flyer(body: Body, values: Mapping[sp.Symbol, sp.Expr]) -> Flyer:
    """A body just after the impact, as numbers for free flight.

    Examples
    --------
    >>> flyer(Body.rod(1, 2, 0, 1, velocity=(0, 1)), {}).ends[1]
    (1.0, 0.0)
    """
    position = tuple(as_float(c, values) for c in body.position)
    velocity = tuple(as_float(c, values) for c in body.velocity)
    spin = as_float(body.spin, values)
    dims = dict(body.dimensions)
    if body.shape == "barbell":
        first, second = body.parts
        ends = tuple(tuple(as_float(c, values) for c in part.position - body.position)
                     for part in (first, second))
        return Flyer(body.name, body.shape, position, velocity, spin, ends,
                     (first.label, second.label))
    if body.shape == "rod":
        half, angle = as_float(dims["length"] / 2, values), as_float(dims["angle"], values)
        end = (half * math.cos(angle), half * math.sin(angle))
        return Flyer(body.name, body.shape, position, velocity, spin,
                     ((-end[0], -end[1]), end), ("end 1", "end 2"))
    radius = as_float(dims["radius"], values) if "radius" in dims else 0.0
    return Flyer(body.name, body.shape, position, velocity, spin, radius=radius)


def finite(outcome: Outcome) -> Outcome:
    """The outcome, unless float64 could not hold a number of it (never print NaN)."""
    bad = sorted(k for k, v in outcome.final.items() if not math.isfinite(v))
    if bad:
        raise InputError("simulate", f"{', '.join(bad)} left float64's range in this run; "
                         "scale the scene's numbers closer to 1")
    return outcome
