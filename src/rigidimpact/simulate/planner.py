"""The planner: from a scene's ``[simulate]`` table to the smallest model that answers it.

A scene asks a question (``until``: the state at separation, the next contact, or a
time) and may ask for extra physics (``effects``). The planner picks the runners in
order — the impulse (algebraic) always, free flight in closed form when the question
reaches past the impact, an integrated compliant model only when an effect needs one —
and lists what it leaves out, so ``--explain`` can say why the answer costs what it does.

Examples
--------
>>> plan = make_plan({"until": "restrike"})
>>> [step.model for step in plan.steps]
['impulse', 'free-flight']
>>> plan.not_simulated  # doctest: +NORMALIZE_WHITESPACE
('rod-compliance', 'contact-compliance', 'gravity', 'tangential-compliance',
 'rolling-resistance', 'pivot-friction')
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import SIMULATE_SETTINGS

__all__ = ["Plan", "Step", "make_plan", "EFFECTS", "SETTINGS"]

# every effect a scene may ask for, and what leaving it out means
EFFECTS = {
    "rod-compliance": "the barbell's rod is rigid: the impact is instantaneous",
    "contact-compliance": "the contact is rigid: Newton's e acts in an instant",
    "gravity": "a horizontal table; asked for (g = 9.81 unless set) it would not change "
               "the relative motion, since every body falls alike",
    "tangential-compliance": "the contact is rigid across the normal too: it sticks or "
                             "slides in an instant (Routh's method)",
    "rolling-resistance": "a sphere rolling on a plane keeps its speed",
    "pivot-friction": "a sphere lying on a plane keeps its spin about the normal",
}
# the effects that need a coefficient of their own, and the setting that gives it
COEFFICIENTS = {"rolling-resistance": "rolling_resistance", "pivot-friction": "pivot_friction"}
SETTINGS = SIMULATE_SETTINGS  # the scene's schema names them: a value put elsewhere is told
INTEGRATORS = ("auto", "RK45", "DOP853", "Radau", "BDF", "LSODA")  # scipy's solve_ivp methods
UNTIL = ("separation", "restrike")
DEFAULTS = {"rod_stiffness": 1e7, "contact_stiffness": 1e5, "tolerance": 1e-6, "g": 9.81,
            "stiffness_ratio": 1.0}
# what the compliant runs can honour in float64 and in reasonable time (a pairing of
# stiffnesses that is too costly is refused later, from its estimated step count)
RANGES = {
    "rod_stiffness": (1e-3, 1e16, "outside it the run either cannot resolve the spring "
                      "in float64 or lasts for ages"),
    "contact_stiffness": (1e-3, 1e16, "outside it the run either cannot resolve the "
                          "contact in float64 or lasts for ages"),
    "tolerance": (1e-12, 1e-1, "float64 cannot meet a tighter one, and a looser one "
                  "is no answer"),
    "g": (1e-6, 1e6, "a gravity outside it belongs to another problem"),
    "stiffness_ratio": (1e-3, 1e3, "k_t/k_n outside it is a contact that does not hold "
                        "sideways or one that is rigid across"),
    "rolling_resistance": (1e-9, 1.0, "a coefficient of rolling resistance (0.005 to "
                           "0.015 for a pool ball on cloth)"),
    "pivot_friction": (1e-9, 1.0, "a coefficient of pivoting friction (about 0.01 for a "
                       "pool ball on cloth)"),
}


@dataclass(frozen=True)
class Step:
    """One runner of a plan and why it is there."""

    model: str
    why: str


@dataclass(frozen=True)
class Plan:
    """What `simulate` will run.

    Parameters
    ----------
    until : str or float
        ``"separation"``, ``"restrike"`` or a time after the impact.
    effects : tuple of str
        The extra physics asked for, in the catalogue's order.
    not_simulated : tuple of str
        The catalogue's effects left out.
    steps : tuple of Step
    settings : mapping
        Stiffnesses and tolerance, with defaults filled in.
    integrator : str
        ``auto`` (picked from the model's stiffness) or a SciPy ``solve_ivp`` method.
    """

    until: str | float
    effects: tuple[str, ...]
    not_simulated: tuple[str, ...]
    steps: tuple[Step, ...]
    settings: Mapping[str, float]
    integrator: str = "auto"

    def explain(self) -> str:
        """The plan in words, one line a step.

        Examples
        --------
        >>> print(make_plan({}).explain())
        until: separation
        1. impulse: the impact as an instant: momentum laws and restitution, solved exactly
        left out: rod-compliance (the barbell's rod is rigid: the impact is instantaneous)
        left out: contact-compliance (the contact is rigid: Newton's e acts in an instant)
        left out: gravity (a horizontal table; asked for (g = 9.81 unless set) it would not change the relative motion, since every body falls alike)
        left out: tangential-compliance (the contact is rigid across the normal too: it sticks or slides in an instant (Routh's method))
        left out: rolling-resistance (a sphere rolling on a plane keeps its speed)
        left out: pivot-friction (a sphere lying on a plane keeps its spin about the normal)
        """  # noqa: E501
        lines = [f"until: {self.until}"]
        lines += [f"{k}. {s.model}: {s.why}" for k, s in enumerate(self.steps, 1)]
        lines += [f"left out: {name} ({EFFECTS[name]})" for name in self.not_simulated]
        return "\n".join(lines)


def _number(table: Mapping[str, Any], key: str) -> float:
    value = table.get(key, DEFAULTS.get(key))
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"simulate.{key}", f"must be a number, got {value!r}")
    if not math.isfinite(value) or value <= 0:
        raise InputError(f"simulate.{key}", f"must be positive and finite, got {value!r}")
    low, high, why = RANGES[key]
    if not low <= value <= high:
        raise InputError(f"simulate.{key}", f"must lie in [{low:g}, {high:g}], got "
                         f"{value!r}: {why}")
    return float(value)


def goes_past_impact(table: Mapping[str, Any]) -> bool:
    """Whether a ``[simulate]`` table asks for the motion after the impact (``until`` a
    time or ``"restrike"``, or a count of ``impacts``), not only the impact itself.

    Examples
    --------
    >>> goes_past_impact({}), goes_past_impact({"until": 2}), goes_past_impact({"impacts": 3})
    (False, True, True)
    """
    return table.get("until", "separation") != "separation" or "impacts" in table


def make_plan(table: Mapping[str, Any]) -> Plan:
    """Check a ``[simulate]`` table and plan the run.

    Examples
    --------
    >>> make_plan({"until": 0.5, "effects": ["gravity"]}).effects
    ('gravity',)
    >>> make_plan({"until": "later"})
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: simulate.until: must be 'separation', 'restrike' or a time after the impact, got 'later'
    """  # noqa: E501
    unknown = sorted(set(table) - SETTINGS)
    if unknown:
        raise InputError(f"simulate.{unknown[0]}", f"unknown setting; expected one of "
                         f"{', '.join(sorted(SETTINGS))}")
    until = table.get("until", "separation")
    if isinstance(until, bool) or not (until in UNTIL or isinstance(until, (int, float))
                                       and math.isfinite(until) and until > 0):
        raise InputError("simulate.until", f"must be 'separation', 'restrike' or a time "
                         f"after the impact, got {until!r}")
    effects = table.get("effects", [])
    if not isinstance(effects, list) or not all(isinstance(x, str) for x in effects):
        raise InputError("simulate.effects", "must be a list of names")
    for name in effects:
        if name not in EFFECTS:
            raise InputError("simulate.effects", f"unknown effect {name!r}; expected "
                             f"some of {', '.join(EFFECTS)}")
    asked = tuple(name for name in EFFECTS if name in effects)
    integrator = table.get("integrator", "auto")
    if integrator not in INTEGRATORS:
        raise InputError("simulate.integrator", f"must be one of {', '.join(INTEGRATORS)}, "
                         f"got {integrator!r}")
    settings = {key: _number(table, key) for key in DEFAULTS}
    for effect, key in COEFFICIENTS.items():
        if effect in asked and key not in table:
            raise InputError(f"simulate.{key}", f"{effect} needs its coefficient, e.g. "
                             f"{key} = 0.01")
        if key in table and effect not in asked:
            raise InputError(f"simulate.{key}", f"is read with effects = [\"{effect}\"], "
                             "which this scene does not ask for")
        if effect in asked:
            if "gravity" not in asked:
                raise InputError("simulate.effects", f"{effect} acts through the weight "
                                 "a plane carries: ask for \"gravity\" too")
            settings[key] = _number(table, key)
    steps = [Step("impulse", "the impact as an instant: momentum laws and restitution, "
                             "solved exactly")]
    compliant = [x for x in asked if x.endswith("-compliance")]
    if "tangential-compliance" in asked:
        if "stiffness_ratio" not in table:
            raise InputError("simulate.stiffness_ratio", "tangential-compliance needs "
                             "k_t/k_n, e.g. stiffness_ratio = 0.79 (notebook 11's fit)")
        steps = [Step("tangential", "tangential-compliance asked for: a lumped contact (a "
                                    "normal spring-dashpot and a tangential spring capped "
                                    "by Coulomb) integrated over the contact")]
    elif compliant:
        steps = [Step("compliant", f"{' and '.join(compliant)} asked for: the impact "
                                   "takes time, integrated with scipy (DOP853, or LSODA "
                                   "when stiff)")]
    if "gravity" in asked:
        steps.append(Step("gravity", f"uniform gravity g = {settings['g']:g} along -y in "
                                     "every phase after the instant of impact (an "
                                     "impulse is too brief for it to matter)"))
    for effect in COEFFICIENTS:
        if effect in asked:
            steps.append(Step(effect, f"{effect} asked for: a sphere lying on a plane is "
                              "worn by it (coefficient "
                              f"{settings[COEFFICIENTS[effect]]:g}), in closed form"))
    if until != "separation":
        steps.append(Step("free-flight", "no force between impacts: straight lines and "
                                         "steady spin in closed form, with an exact "
                                         "search for the next contact"))
    return Plan(until, asked, tuple(x for x in EFFECTS if x not in asked), tuple(steps),
                settings, integrator)
