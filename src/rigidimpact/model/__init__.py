"""Bodies and their shapes, supports (pivots, fixed bodies) and roles (which quantity may
take which values)."""
