"""rigidimpact: derive, verify and simulate impulsive planar collisions of rigid bodies."""

from __future__ import annotations
