"""The bridge from sympy.physics.mechanics: the impact map of any system built there (M
and J from the system and its contact points, solved by rigidimpact's laws), and hybrid
simulation through its impacts with Poincare maps."""
