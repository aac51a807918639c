"""rigidimpact: derive, verify and simulate impulsive planar collisions of rigid bodies.

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
    from rigidimpact.bodies import Body as Body
    from rigidimpact.bodies import join as join
    from rigidimpact.collision import Collision as Collision
    from rigidimpact.collision import Compliant as Compliant
    from rigidimpact.collision import Outcome as Outcome
    from rigidimpact.collision import Sequential as Sequential
    from rigidimpact.collision import Simultaneous as Simultaneous
    from rigidimpact.collision import chain as chain
    from rigidimpact.contact import Contact as Contact
    from rigidimpact.errors import InputError as InputError
    from rigidimpact.impact import Impact as Impact
    from rigidimpact.laws import Equation as Equation
    from rigidimpact.notation import symbol as symbol
    from rigidimpact.problems import PROBLEMS as PROBLEMS
    from rigidimpact.problems import Derivation as Derivation
    from rigidimpact.problems import derive as derive
    from rigidimpact.restrike import critical_angle as critical_angle
    from rigidimpact.scene import Scene as Scene
    from rigidimpact.scene import load_scene as load_scene
    from rigidimpact.scene import parse_scene as parse_scene
    from rigidimpact.simulate import make_plan as make_plan
    from rigidimpact.simulate import run as run
    from rigidimpact.solution import Solution as Solution
    from rigidimpact.verify import run_checks as run_checks

# name -> module; imported on first use, so `import rigidimpact` (and the command line's
# start) costs only what is used
_PUBLIC = {
    # primitives and contact
    "Body": "bodies", "join": "bodies", "Contact": "contact", "InputError": "errors",
    # solving
    "Impact": "impact", "Equation": "laws", "Solution": "solution", "symbol": "notation",
    "PROBLEMS": "problems", "Derivation": "problems", "derive": "problems",
    # several contacts: the collision, its rules and what they give
    "Collision": "collision", "Simultaneous": "collision", "Sequential": "collision",
    "Compliant": "collision", "Outcome": "collision", "chain": "collision",
    # scenes and checks
    "Scene": "scene", "load_scene": "scene", "parse_scene": "scene",
    "run_checks": "verify",
    # after the impact
    "critical_angle": "restrike", "make_plan": "simulate", "run": "simulate",
}

__all__ = list(_PUBLIC)
__version__ = "0.1.0"


def __getattr__(name: str) -> Any:
    if name in _PUBLIC:
        value = getattr(import_module(f"rigidimpact.{_PUBLIC[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rigidimpact' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *_PUBLIC])
