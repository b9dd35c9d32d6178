"""List the boards connected to this computer (``python -m j5aio list``).

:func:`find_boards` runs the discovery of every backend of the hardware environment (the
serial ones together, through
:func:`~j5aio.backends.hardware.identify.discover_serial_boards`, so that a port the
Arduinos share is asked once and each board is found once), notes
each board's kind, serial number, firmware version and port, and closes again the
boards it opened (a board that a running robot already holds is reported and left
alone). :func:`format_boards` turns the list into text for people.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from typing import Any, Final, cast

import anyio

from j5aio.backends.hardware import registry
from j5aio.backends.hardware.env import HARDWARE_BACKENDS
from j5aio.backends.hardware.identify import discover_serial_boards, serial_backends
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.boards.board import Board
from j5aio.errors import CommunicationError

__all__ = ["LISTING_TIME_SCALE", "FoundBoard", "find_boards", "format_boards"]

#: Listing multiplies the backends' waits by this. Ports that several kinds share (the
#: Arduinos) are identified with each kind's shorter identification waits
#: (``IDENTIFY_TIME_SCALE``), so the usual waits serve elsewhere.
LISTING_TIME_SCALE: Final = 1.0


@dataclass(frozen=True)
class FoundBoard:
    """A board found by :func:`find_boards`."""

    #: The kind of board, e.g. ``"Student Robotics v4 Motor Board"``.
    board_type: str
    #: The board's serial number.
    serial_number: str
    #: The firmware version it reported, if it has one.
    firmware_version: str | None
    #: The serial port, or the USB bus position, it was found on.
    port: str


async def find_boards(
    *,
    options: DiscoveryOptions | None = None,
    problems: list[str] | None = None,
) -> list[FoundBoard]:
    """Return every board the hardware environment finds, one backend after another.

    A board that fails its handshake is logged and left out rather than stopping the
    listing. A kind of board that cannot be looked for at all (for example the USB boards
    on a machine without libusb) is left out too, when ``problems`` is given: the reason
    is appended to it and the other kinds are still listed.

    :param options: stand-in port lists and USB finders for tests; by default the real
        ones, with :data:`LISTING_TIME_SCALE` and failing boards skipped.
    :param problems: collects why a kind of board could not be looked for; without it
        such a failure is raised.
    :raises CommunicationError: a kind of board could not be looked for, and
        ``problems`` was not given.
    """
    if options is None:
        options = DiscoveryOptions(time_scale=LISTING_TIME_SCALE, skip_failures=True)
    else:
        options = dataclasses.replace(options, skip_failures=True)
    held_before = registry.held()
    found: list[FoundBoard] = []
    opened: list[Board] = []
    try:
        serial = [b for b in HARDWARE_BACKENDS if issubclass(b, SerialHardwareBackend)]
        searches: list[tuple[object, Callable[[], Awaitable[Sequence[Board]]]]] = [
            # Hardware backends' discovery takes options (serial and USB ones do).
            (backend, functools.partial(cast(Any, backend).discover, options=options))
            for backend in HARDWARE_BACKENDS
            if backend not in serial
        ]
        if serial:
            ordered = sorted(serial, key=lambda b: serial_backends().index(b))
            searches.append(
                (
                    "serial boards",
                    functools.partial(discover_serial_boards, options=options, backends=ordered),
                )
            )
        for what, search in searches:
            try:
                boards = await search()
            except CommunicationError as error:
                if problems is None:
                    raise
                label = what if isinstance(what, str) else cast(Any, what).board.name
                problems.append(f"{label}: {error}")
                continue
            for board in boards:
                port = str(getattr(board.backend, "port", ""))
                found.append(
                    FoundBoard(board.name, board.serial_number, board.firmware_version, port),
                )
                if port not in held_before:
                    opened.append(board)
    finally:
        with anyio.CancelScope(shield=True):
            for board in opened:
                await board.close()
    return found


def format_boards(boards: Sequence[FoundBoard]) -> str:
    """Return a table of ``boards`` for people, or a plain sentence when there are none."""
    if not boards:
        return (
            "No boards found. Check that each board is plugged in by USB and powered, "
            "then try again."
        )
    headings = ("Board", "Serial number", "Firmware", "Port")
    rows = [
        (board.board_type, board.serial_number, board.firmware_version or "-", board.port)
        for board in boards
    ]
    widths = [max(len(row[column]) for row in [headings, *rows]) for column in range(4)]
    lines = [
        "  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
        for row in [headings, *rows]
    ]
    count = f"{len(boards)} board{'s' if len(boards) != 1 else ''} found."
    return "\n".join([*lines, count])
