"""Moved to :mod:`rigidimpact.model.impulse` (the bodies' generalized velocities, mass
matrix and contact rows sit below the laws that use them); this name still imports it."""

from rigidimpact.model.impulse import *  # noqa: F403
from rigidimpact.model.impulse import __all__ as __all__
