"""Choosing where a program's boards are: real hardware, the simulated kit, or the console.

A program may pass an :class:`~j5aio.backends.environment.Environment` explicitly; when it
does not, :func:`get_default_environment` reads the ``J5AIO_ENV`` environment variable:

======================  ==========================================================
``J5AIO_ENV``           environment
======================  ==========================================================
unset or ``hardware``   the boards plugged into this computer
``sim``                 the simulated kit (:mod:`j5aio.simulator.environment`)
``console``             print what the boards would do, and ask for readings
======================  ==========================================================

``python -m j5aio run --sim program.py`` sets ``J5AIO_ENV=sim`` for the program. Which
simulated kit it is comes from ``J5AIO_KIT`` (``--kit NAME``): see
:mod:`j5aio.simulator.kit`.

When a program looked for real boards only because nobody chose otherwise, and found none,
:func:`hint_no_hardware` prints one line saying how to try the program without hardware.
The hardware environment that :func:`get_default_environment` returns when ``J5AIO_ENV``
is unset drives the same backends as :func:`hardware_environment`, and prints that line
itself when the hardware cannot even be looked at (no USB library, say).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Final, TextIO, TypeVar

from j5aio.backends.environment import Environment
from j5aio.boards.board import Board
from j5aio.boards.board_group import BoardGroup
from j5aio.errors import CommunicationError

__all__ = [
    "ENVIRONMENT_NAMES",
    "ENVIRONMENT_VARIABLE",
    "console_environment",
    "environment_was_chosen",
    "get_default_environment",
    "get_environment",
    "hardware_environment",
    "hint_no_hardware",
    "no_hardware_hint",
    "simulated_environment",
]

#: The environment variable that chooses the default environment.
ENVIRONMENT_VARIABLE: Final = "J5AIO_ENV"

#: The values ``J5AIO_ENV`` may take.
ENVIRONMENT_NAMES: Final = ("hardware", "sim", "console")

_hint_shown = False

BoardT = TypeVar("BoardT", bound=Board)


def hardware_environment() -> Environment:
    """The environment of the boards plugged into this computer."""
    from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT

    return HARDWARE_ENVIRONMENT


def console_environment() -> Environment:
    """The environment that prints what boards would do and asks for their readings."""
    from j5aio.backends.console import CONSOLE_ENVIRONMENT

    return CONSOLE_ENVIRONMENT


def simulated_environment() -> Environment:
    """The environment of the simulated kit (see :mod:`j5aio.simulator.environment`)."""
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    return SIMULATED_ENVIRONMENT


_ENVIRONMENTS: Final[dict[str, Callable[[], Environment]]] = {
    "hardware": hardware_environment,
    "sim": simulated_environment,
    "console": console_environment,
}


def get_environment(name: str) -> Environment:
    """Return the environment called ``name``: ``"hardware"``, ``"sim"`` or ``"console"``.

    :raises TypeError: ``name`` is not a string.
    :raises ValueError: ``name`` is not one of those.
    """
    if not isinstance(name, str):
        raise TypeError(f"an environment name must be a str, not {type(name).__name__}")
    try:
        factory = _ENVIRONMENTS[name.strip().lower()]
    except KeyError:
        raise ValueError(
            f"unknown environment {name!r}: choose one of {', '.join(ENVIRONMENT_NAMES)}"
        ) from None
    return factory()


def environment_was_chosen() -> bool:
    """Whether ``J5AIO_ENV`` chooses an environment (rather than hardware by default)."""
    return bool(os.environ.get(ENVIRONMENT_VARIABLE, "").strip())


class _HardwareByDefault(Environment):
    """The hardware environment, used because nothing chose another.

    It shares the hardware environment's backends. When the hardware cannot even be
    looked at (no USB library, say), it prints :func:`no_hardware_hint` before the error.
    """

    def __init__(self, hardware: Environment) -> None:
        super().__init__(hardware.name, gather=hardware.gather)
        self._slots = hardware._slots  # the same backends, loaded once for both
        self.found_any = False

    async def get_board_group(self, board: type[BoardT]) -> BoardGroup[BoardT]:
        """Find every ``board`` on the hardware; see :meth:`Environment.get_board_group`.

        Finding none, when no board at all has been found yet, prints the hint too.
        """
        try:
            group = await super().get_board_group(board)
        except CommunicationError:
            hint_no_hardware()
            raise
        if group:
            self.found_any = True
        elif not self.found_any:
            hint_no_hardware(what=board.name)
        return group


@cache
def _hardware_by_default() -> Environment:
    return _HardwareByDefault(hardware_environment())


def get_default_environment() -> Environment:
    """Return the environment named by ``J5AIO_ENV``, or the hardware one when it is unset.

    :raises ValueError: ``J5AIO_ENV`` names no environment (the message lists the choices).
    """
    name = os.environ.get(ENVIRONMENT_VARIABLE, "").strip()
    if not name:
        return _hardware_by_default()
    try:
        return get_environment(name)
    except ValueError:
        raise ValueError(
            f"{ENVIRONMENT_VARIABLE}={name!r} is not an environment: set it to one of "
            f"{', '.join(ENVIRONMENT_NAMES)}, or unset it to use the hardware"
        ) from None


def _program_name() -> str:
    program = Path(sys.argv[0]).name if sys.argv and sys.argv[0] else ""
    return program if program.endswith(".py") else "program.py"


def no_hardware_hint(what: str = "boards") -> str:
    """The line :func:`hint_no_hardware` prints, naming the running program if it can.

    :param what: what was not found: ``"boards"``, or the name of one kind of board.
    """
    return (
        f"j5aio: no {what} found. To try your program without hardware: "
        f"python -m j5aio run --sim {_program_name()} "
        f"(or set {ENVIRONMENT_VARIABLE}=sim)"
    )


def hint_no_hardware(*, file: TextIO | None = None, what: str = "boards") -> bool:
    """Print, once per program, how to run without hardware; return whether it printed.

    Call it when real boards were looked for only by default and none were found. It
    prints nothing when ``J5AIO_ENV`` chose the environment, or when it already printed.

    :param file: where to print; standard error by default.
    :param what: what was not found, for the message (see :func:`no_hardware_hint`).
    """
    global _hint_shown
    if _hint_shown or environment_was_chosen():
        return False
    _hint_shown = True
    print(no_hardware_hint(what), file=file if file is not None else sys.stderr, flush=True)
    return True
