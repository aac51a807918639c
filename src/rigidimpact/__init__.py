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

# primitives and contact
from rigidimpact.bodies import Body, join
from rigidimpact.contact import Contact
from rigidimpact.errors import InputError

# solving
from rigidimpact.impact import Impact
from rigidimpact.laws import Equation
from rigidimpact.notation import symbol
from rigidimpact.problems import PROBLEMS, Derivation, derive

# after the impact (importing restrike also adds its checks to `run_checks`)
from rigidimpact.restrike import critical_angle

# scenes and checks
from rigidimpact.scene import Scene, load_scene, parse_scene
from rigidimpact.simulate import make_plan, run
from rigidimpact.solution import Solution
from rigidimpact.verify import run_checks

__all__ = [
    "Body", "join", "Contact", "InputError",
    "Impact", "Equation", "Solution", "symbol", "PROBLEMS", "Derivation", "derive",
    "Scene", "load_scene", "parse_scene", "run_checks",
    "critical_angle", "make_plan", "run",
]
__version__ = "0.1.0"
