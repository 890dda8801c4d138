"""A solver plugin module that calls sys.exit() when it is imported (for the registry tests)."""

import sys

sys.exit(0)
