"""CONSOLE_ENVIRONMENT: every board on the console, printing and asking instead of hardware.

Its backends are the console backends of the registered board kinds
(:func:`j5aio.board_kinds.board_kinds`). A console backend makes up one board, so a board
family is shown through the backend registered for exactly that class, or else its
first generation's.
"""

from __future__ import annotations

from j5aio.backends._kinds import board_kinds
from j5aio.backends.environment import Environment

__all__ = ["CONSOLE_ENVIRONMENT"]

CONSOLE_ENVIRONMENT = Environment.from_backends(
    "ConsoleEnvironment",
    (kind.console for kind in board_kinds() if kind.console is not None),
    gather=False,
)
"""The console environment: each board is printed to and asked about on the terminal."""
