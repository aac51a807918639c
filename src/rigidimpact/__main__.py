"""``python -m rigidimpact``: the command line."""

from __future__ import annotations

import sys

from rigidimpact.cli import main

if __name__ == "__main__":
    sys.exit(main())
