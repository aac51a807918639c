"""Studies built on the core: the critical angle of re-strike, accuracy against time, the
hard-case suite, and the comparison with measurements."""
