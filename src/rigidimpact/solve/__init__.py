"""The impulse problem for one contact or several (M, J, W), the rules as objects, the
solutions and the :class:`~rigidimpact.solve.derivation.Derivation` every path ends in."""
