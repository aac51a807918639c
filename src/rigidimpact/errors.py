"""The one exception that bad input raises, naming the field that is wrong.

Examples
--------
>>> err = InputError("bodies[0].mass", "must be positive, got -1")
>>> str(err)
'bodies[0].mass: must be positive, got -1'
"""

from __future__ import annotations

__all__ = ["InputError"]


class InputError(ValueError):
    """Bad input: a message of one line that starts with the field at fault.

    Parameters
    ----------
    field : str
        Where the problem is (``"contact.restitution"``, ``"bodies[1].shape"``, ...).
    message : str
        What is wrong with it.

    Examples
    --------
    >>> InputError("values.e", "must lie in [0, 1], got 1.5").field
    'values.e'
    """

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        self.message = " ".join(message.split())
        super().__init__(f"{field}: {self.message}" if field else self.message)
