"""The contact and its laws as objects: restitution (Newton, Poisson, energetic),
tangential (smooth, stick, Coulomb, rough) with Routh's and Walton's exact regimes, and the
compliance that reproduces e."""
