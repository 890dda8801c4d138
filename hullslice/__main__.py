"""``python -m hullslice``: the command line."""

from .cli import run

run()
