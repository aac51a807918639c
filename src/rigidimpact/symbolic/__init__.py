"""Symbols and their LaTeX names, geometry, targeted rewriting, the bounded expression
parser and the comparison machinery (symbolic zero, high-precision agreement)."""
