"""Searching serial ports for the boards of several kinds, each port opened once.

The machinery under :func:`~j5aio.backends.hardware.identify.discover_serial_boards`
and :func:`~j5aio.backends.hardware.identify.attach`, and under
:meth:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend.discover` when
other kinds use the same USB IDs: which backends are registered
(:func:`registered_backends`), trying them in turn on one port
(:func:`identify_on_port`), and searching every port (:func:`search_ports`).

It works with any backend class given to it (``base``: the serial backend base class,
as its callers pass it), so that the serial backend, which uses it, is not imported
here, and identification, which uses both, sits above them.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any, cast

import anyio
import anyio.to_thread

from j5aio.backends._kinds import board_kinds
from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions, StreamOpener
from j5aio.backends.hardware.transports._at_once import call_blocking
from j5aio.backends.hardware.transports.discovery import (
    ComPortLike,
    PortInfo,
    list_serial_ports,
    match_ports,
)
from j5aio.boards.board import Board
from j5aio.errors import CommunicationError, UnsupportedFirmwareError

if TYPE_CHECKING:
    from j5aio.backends.hardware.serial_backend import SerialHardwareBackend

__all__ = ["REOPEN_DELAY", "identify_on_port", "registered_backends", "search_ports"]

_log = logging.getLogger("j5aio.backends.hardware.identify")  # the name teams' settings know

#: Seconds between one kind's probe closing the port and the next kind's opening it, so
#: that the board (or a simulator serving a pseudo-terminal) sees the port close, and the
#: reopening resets it as a fresh open does.
REOPEN_DELAY = 0.1


def registered_backends(base: type) -> tuple[type[SerialHardwareBackend[Any]], ...]:
    """The registered kinds' hardware backends that are ``base`` subclasses, in identify order.

    The kinds are those of the registry (:func:`j5aio.board_kinds.board_kinds`), which
    imports each kind's hardware backend the first time it is read here.
    """
    found = [
        (kind.identify_order, kind.hardware)
        for kind in board_kinds()
        if isinstance(kind.hardware, type) and issubclass(kind.hardware, base)
    ]
    return tuple(
        cast("type[SerialHardwareBackend[Any]]", backend)
        for _, backend in sorted(found, key=lambda item: item[0])
    )


async def identify_on_port(
    port: str,
    serial_number: str,
    backends: Sequence[type[SerialHardwareBackend[Board]]],
    opener: StreamOpener | None,
    time_scale: float,
    *,
    port_source: Callable[[], Iterable[ComPortLike]] | None = None,
) -> Board:
    """Try each backend on ``port`` in turn; return the first board that answers as its kind.

    Each backend opens the port afresh at its own baud rate (:data:`REOPEN_DELAY` after
    the one before closed it) and runs its full handshake
    (:meth:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend.identify`).
    A board found through ``port_source`` (discovery) is looked for again by its serial
    number if it vanishes; one asked for by its port (``port_source`` None), at that port.

    :raises UnsupportedFirmwareError: a backend's kind answered, but runs firmware it
        cannot drive (and no other backend recognised the board).
    :raises CommunicationError: no backend recognised the board; the message lists them.
    """
    unsupported: list[UnsupportedFirmwareError] = []
    for index, backend in enumerate(backends):
        if index:
            await anyio.sleep(REOPEN_DELAY)
        try:
            board = await backend.identify(
                port,
                serial_number=serial_number,
                opener=opener,
                time_scale=time_scale,
                port_source=port_source,
                by_port=port_source is None,
            )
        except UnsupportedFirmwareError as error:
            _log.info("%s on %s: %s", backend.__name__, port, error)
            unsupported.append(error)
            continue
        if board is not None:
            return board
    if unsupported:
        raise unsupported[0]
    tried = ", ".join(f"{backend.board.name} ({backend.__name__})" for backend in backends)
    raise CommunicationError(
        f"no supported board answered on {port}; tried: {tried}. Is it plugged in and "
        "powered, and does it run its usual firmware?"
    )


async def search_ports(
    base: type,
    *,
    options: DiscoveryOptions | None,
    backends: Sequence[type[SerialHardwareBackend[Board]]],
) -> list[Board]:
    """Find the boards of ``backends`` on the serial ports, opening each port once.

    A port whose USB identity matches one backend is opened by it; a port that matches
    several (the Arduinos share their USB IDs) is identified among them in turn
    (:func:`identify_on_port`). Ports are looked at concurrently. A board that vanished
    and is listed again is brought back as the same board; a port held by a board of
    ``base`` gives back that board, one held by anything else is skipped. The boards are
    not set up.

    :param base: the serial backend base class, which every backend derives from: a port
        held by one of its boards is given back, and its ``collect`` gathers the results.
    :param options: stand-in port lists and openers, a time scale, and whether a failing
        board is skipped (logged) rather than raised; the real thing if ``None``.
    :param backends: the backends to look with, in identification order.
    :raises CommunicationError: a board could not be identified or failed its handshake
        (unless ``options.skip_failures``).
    """
    options = options or DiscoveryOptions()
    source = options.port_source
    ports = await call_blocking(list_serial_ports, source, worker=source)
    wanted: dict[str, tuple[PortInfo, list[type[SerialHardwareBackend[Board]]]]] = {}
    for backend in backends:
        matched = match_ports(
            ports, set(backend.USB_IDS), backend.USB_MANUFACTURER, backend.USB_PRODUCT
        )
        for port in matched:
            if backend.has_serial_number(port):
                wanted.setdefault(port.device, (port, []))[1].append(backend)
    results: dict[str, Board | Exception] = {}

    async def connect_one(port: PortInfo, kinds: list[type[SerialHardwareBackend[Board]]]) -> None:
        serial_number = port.serial_number or port.device
        source = options.port_source

        async def connect() -> Board:
            if len(kinds) == 1:
                return await kinds[0].open_port(
                    port.device,
                    serial_number,
                    options.opener,
                    options.time_scale,
                    port_source=source,
                )
            return await identify_on_port(
                port.device,
                serial_number,
                kinds,
                options.opener,
                options.time_scale,
                port_source=source,
            )

        claimant = kinds[0] if len(kinds) == 1 else base
        try:
            # A board that vanished and is listed again (perhaps on another path) is
            # brought back as the same Board, not opened as a new one.
            for kind in kinds:
                known = kind._lost_board(serial_number, options)
                if known is not None:
                    await kind._found_again(known)
                    results[port.device] = known
                    return
            results[port.device] = await registry.claim(port.device, claimant, connect)
        except registry.PortInUseError as exc:
            _log.info("Skipping %s: %s", port.device, exc)
        except Exception as exc:
            results[port.device] = exc

    async with anyio.create_task_group() as group:
        for port, kinds in wanted.values():
            group.start_soon(connect_one, port, kinds)
    gather = cast("type[SerialHardwareBackend[Any]]", base).collect
    return gather(results, skip_failures=options.skip_failures)
