"""rigidimpact: derive, verify and simulate impulsive collisions of rigid bodies, in the
plane and in space.

Starting from C. E. Mungan, "Collision of a ball with a barbell and related impulse
problems", Eur. J. Phys. 28 (2007) 563-568.

Examples
--------
>>> import rigidimpact as ri
>>> ri.derive("sticking").results["h"]
L*m/(2*M + m)
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the real names, for type checkers; at run time they load on first use
    from rigidimpact import mechanics as mechanics
    from rigidimpact.analyses.distributions import distributions as distributions
    from rigidimpact.analyses.restrike import critical_angle as critical_angle
    from rigidimpact.errors import InputError as InputError
    from rigidimpact.figures import animate as animate
    from rigidimpact.figures import draw as draw
    from rigidimpact.figures import draw_distributions as draw_distributions
    from rigidimpact.laws.cone import cone_impact as cone_impact
    from rigidimpact.laws.contact import Contact as Contact
    from rigidimpact.laws.law import RESTITUTION_LAWS as RESTITUTION_LAWS
    from rigidimpact.laws.law import EnergeticRestitution as EnergeticRestitution
    from rigidimpact.laws.law import Equation as Equation
    from rigidimpact.laws.law import NewtonRestitution as NewtonRestitution
    from rigidimpact.laws.law import PoissonRestitution as PoissonRestitution
    from rigidimpact.model.bodies import Body as Body
    from rigidimpact.model.bodies import join as join
    from rigidimpact.model.space import Body3 as Body3
    from rigidimpact.outputs.code import to_code as to_code
    from rigidimpact.outputs.live import live_page as live_page
    from rigidimpact.paper.problems import PROBLEMS as PROBLEMS
    from rigidimpact.paper.problems import derive as derive
    from rigidimpact.scenes.scene import Scene as Scene
    from rigidimpact.scenes.scene import load_scene as load_scene
    from rigidimpact.scenes.scene import parse_scene as parse_scene
    from rigidimpact.scenes.space import SpaceScene as SpaceScene
    from rigidimpact.scenes.space import load_any as load_any
    from rigidimpact.scenes.space import load_space_scene as load_space_scene
    from rigidimpact.simulate import make_plan as make_plan
    from rigidimpact.simulate import run as run
    from rigidimpact.solve.collision import Collision as Collision
    from rigidimpact.solve.collision import Compliant as Compliant
    from rigidimpact.solve.collision import Outcome as Outcome
    from rigidimpact.solve.collision import Rule as Rule
    from rigidimpact.solve.collision import Sequential as Sequential
    from rigidimpact.solve.collision import Simultaneous as Simultaneous
    from rigidimpact.solve.collision import chain as chain
    from rigidimpact.solve.collision import cluster as cluster
    from rigidimpact.solve.collision import fan as fan
    from rigidimpact.solve.derivation import Derivation as Derivation
    from rigidimpact.solve.impact import Impact as Impact
    from rigidimpact.solve.rules.driven import Driven as Driven
    from rigidimpact.solve.solution import Solution as Solution
    from rigidimpact.solve.space import SpaceCollision as SpaceCollision
    from rigidimpact.symbolic.distributions import histogram as histogram
    from rigidimpact.symbolic.distributions import monte_carlo as monte_carlo
    from rigidimpact.symbolic.distributions import pushforward as pushforward
    from rigidimpact.symbolic.notation import symbol as symbol
    from rigidimpact.symbolic.numeric import Kernel as Kernel
    from rigidimpact.symbolic.numeric import evaluate as evaluate
    from rigidimpact.verify import run_checks as run_checks

# name -> module; imported on first use, so `import rigidimpact` (and the command line's
# start) costs only what is used
_PUBLIC = {
    # primitives and contact
    "Body": "model.bodies", "join": "model.bodies", "Contact": "laws.contact",
    "InputError": "errors",
    # solving
    "Impact": "solve.impact", "Equation": "laws.law", "Solution": "solve.solution",
    "RESTITUTION_LAWS": "laws.law", "NewtonRestitution": "laws.law",
    "PoissonRestitution": "laws.law", "EnergeticRestitution": "laws.law",
    "symbol": "symbolic.notation", "PROBLEMS": "paper.problems",
    "Derivation": "solve.derivation", "derive": "paper.problems",
    # several contacts: the collision, its rules and what they give
    "Collision": "solve.collision", "Simultaneous": "solve.collision",
    "Sequential": "solve.collision", "Compliant": "solve.collision",
    "Outcome": "solve.collision", "Rule": "solve.collision", "chain": "solve.collision",
    "cluster": "solve.collision",
    "fan": "solve.collision",
    # three dimensions: bodies with spin, one rough contact with a circular cone
    "Body3": "model.space", "SpaceCollision": "solve.space", "SpaceScene": "scenes.space",
    "load_space_scene": "scenes.space", "load_any": "scenes.space",
    # scenes and checks
    "Scene": "scenes.scene", "load_scene": "scenes.scene", "parse_scene": "scenes.scene",
    "run_checks": "verify",
    # after the impact
    "critical_angle": "analyses.restrike", "make_plan": "simulate", "run": "simulate",
    "draw": "figures", "animate": "figures",
    # the driven rule; the 3-D contact law in contact space
    "Driven": "solve.rules.driven", "cone_impact": "laws.cone",
    # numbers from closed forms: a compiled kernel, one evaluation
    "Kernel": "symbolic.numeric", "evaluate": "symbolic.numeric",
    # random inputs: a scene's distributions and their picture; the Monte Carlo, its
    # histogram, the exact density
    "distributions": "analyses.distributions", "draw_distributions": "figures",
    "monte_carlo": "symbolic.distributions", "histogram": "symbolic.distributions",
    "pushforward": "symbolic.distributions",
    # the derivation as code (C, JavaScript, ...) and as a live page
    "to_code": "outputs.code", "live_page": "outputs.live",
}

__all__ = list(_PUBLIC)
__version__ = "0.1.0"


def __getattr__(name: str) -> Any:
    if name == "mechanics":  # the sympy.physics.mechanics bridge, a folder of its own
        return import_module("rigidimpact.mechanics")
    if name in _PUBLIC:
        value = getattr(import_module(f"rigidimpact.{_PUBLIC[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rigidimpact' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *_PUBLIC, "mechanics"])
