"""Mungan's paper (Eur. J. Phys. 28, 2007): its published results as data with their
equation numbers, its problems built from primitives, and the textbook catalogue."""
