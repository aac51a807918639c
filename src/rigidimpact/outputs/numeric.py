"""Moved to :mod:`rigidimpact.symbolic.numeric` (numbers from expressions sit below the
solvers that use them); this name still imports it."""

from rigidimpact.symbolic.numeric import *  # noqa: F403
from rigidimpact.symbolic.numeric import __all__ as __all__
