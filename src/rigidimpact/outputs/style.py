"""The figures' one size and resolution, so a notebook's stored PNG stays the same."""

FIGSIZE = (8.0, 4.0)
DPI = 100
