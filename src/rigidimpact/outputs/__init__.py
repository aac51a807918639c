"""What a derivation is turned into: LaTeX, numeric kernels, plots, sweeps, and files
written atomically."""
