"""``python -m rigidimpact``: the command line."""

from __future__ import annotations

from rigidimpact.cli import run

if __name__ == "__main__":
    run()
