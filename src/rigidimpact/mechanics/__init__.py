"""The bridge from sympy.physics.mechanics: the impact map of any system built there (M
and J from the system and its contact points, solved by rigidimpact's laws), and hybrid
simulation through its impacts with Poincare maps.

>>> import rigidimpact as ri
>>> ri.mechanics.contact  # doctest: +ELLIPSIS
<function contact at ...>
"""

from rigidimpact.mechanics.hybrid import FixedPoint, Hybrid, Walk, flow_of
from rigidimpact.mechanics.impact import ImpactMap, PointContact, SystemImpact, contact, impact

__all__ = ["impact", "contact", "SystemImpact", "ImpactMap", "PointContact", "Hybrid",
           "Walk", "FixedPoint", "flow_of"]
