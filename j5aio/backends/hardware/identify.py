"""Telling which board answers on a serial port: :func:`attach`, and discovery that asks once.

Every registered board kind (:mod:`j5aio.board_kinds`) whose hardware backend is a
:class:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend` can be identified:
its :meth:`~j5aio.backends.hardware.serial_backend.SerialHardwareBackend.identify` runs
its handshake over a freshly opened port (at its own baud rate) and says whether the
board is one of its kind. The kinds are tried in their ``identify_order``; a port listed
with a USB vendor and product ID is tried only with the kinds that use that ID.

:func:`discover_serial_boards` finds every serial board on this computer's ports, asking
each port once: a port whose USB identity only one kind uses is opened by that kind, and
a port that several kinds share (the Arduinos) is identified as :func:`attach` does,
with the shorter waits of identification, so no port is opened by one backend after
another with a full boot wait each.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence

import anyio
import anyio.to_thread

from j5aio.backends.hardware import port_search, registry
from j5aio.backends.hardware.options import DiscoveryOptions, StreamOpener
from j5aio.backends.hardware.port_search import REOPEN_DELAY
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports.discovery import PortInfo, find_port
from j5aio.backends.hardware.transports.lent import LentStream
from j5aio.boards.board import Board
from j5aio.errors import CommunicationError
from j5aio.safety import hooks as safety_hooks

__all__ = [
    "QUICK_BUDGET",
    "QUICK_SCALE",
    "REOPEN_DELAY",
    "attach",
    "discover_serial_boards",
    "serial_backends",
]

_log = logging.getLogger(__name__)

#: Multiplies every kind's identification waits in the first round of :func:`attach`,
#: which asks every kind over one opening of the port per baud rate: enough for a board
#: that answers at once, not for one still booting (the full round then finds it).
QUICK_SCALE = 0.05

#: Seconds each kind has, in that first round, to recognise a board that answers at once
#: (multiplied by the time scale); a kind that takes longer is asked again in the full
#: round.
QUICK_BUDGET = 0.05


def _candidates(
    port: PortInfo | None, backends: Sequence[type[SerialHardwareBackend]]
) -> tuple[type[SerialHardwareBackend], ...]:
    """The backends worth trying on ``port``: those using its USB ID, if it has one."""
    if port is None or port.vid is None or port.pid is None:
        return tuple(backends)
    matching = tuple(backend for backend in backends if (port.vid, port.pid) in backend.USB_IDS)
    return matching or tuple(backends)


async def _answering_kind(
    port: str,
    backends: Sequence[type[SerialHardwareBackend]],
    opener: StreamOpener | None,
    time_scale: float,
) -> type[SerialHardwareBackend] | None:
    """The first of ``backends`` whose handshake the board on ``port`` answers at once.

    The port is opened once for each baud rate, and every kind at that rate runs its
    handshake in turn over the open port, with its waits shortened by
    :data:`QUICK_SCALE` and its time capped by :data:`QUICK_BUDGET`; each handshake
    begins by ending whatever the kinds before it left half-sent. ``None`` if no kind is
    answered so (a board still booting, one whose firmware a kind cannot drive, or a port
    that will not open: the full round decides).
    """
    by_rate: dict[int, list[type[SerialHardwareBackend]]] = {}
    for backend in backends:
        by_rate.setdefault(backend.BAUDRATE, []).append(backend)
    for index, kinds in enumerate(by_rate.values()):
        if index:
            await anyio.sleep(REOPEN_DELAY)
        try:
            stream = await kinds[0]._open_stream(port, opener)
        except CommunicationError:
            return None
        try:
            for backend in kinds:
                board: Board | None = None
                with anyio.move_on_after(QUICK_BUDGET * time_scale):
                    try:
                        board = await backend.from_stream(
                            LentStream(stream),
                            port=port,
                            serial_number=port,
                            time_scale=time_scale * backend.IDENTIFY_TIME_SCALE * QUICK_SCALE,
                        )
                    except CommunicationError as error:
                        _log.debug("%s on %s: no quick answer: %s", backend.__name__, port, error)
                if board is not None:
                    await board.close()
                    return backend
        finally:
            with anyio.CancelScope(shield=True):
                await stream.aclose()
    return None


async def attach(
    port: str, *, time_scale: float = 1.0, opener: StreamOpener | None = None
) -> Board:
    """Identify the serial board on ``port`` and return it, set up and ready.

    First every registered serial board kind asks at once, in its ``identify_order``,
    over one opening of the port per baud rate, with short waits: the first kind the
    board answers opens it. If none is answered so (a board still booting, say), each
    kind is tried again in turn, opening the port afresh at its own baud rate with its
    full identification waits, until one recognises the board. The board's
    ``firmware_version`` is what it reported. A port already held by a board gives back
    that board.

    :param port: a device path (a pseudo-terminal works) or a pyserial URL.
    :param time_scale: multiplies the waits for the board to boot and answer.
    :param opener: opens the port at a baud rate; the real serial port by default.
    :raises UnsupportedFirmwareError: a known board answered, but runs firmware j5aio
        cannot drive (and no other kind recognised it).
    :raises CommunicationError: no kind recognised the board; the message lists what
        was tried.
    """
    safety_hooks.install()  # a program's way to a board: it gets the safety hooks
    backends = serial_backends()

    async def connect() -> Board:
        found = await anyio.to_thread.run_sync(find_port, port)
        serial_number = found.serial_number if found and found.serial_number else port
        candidates = _candidates(found, backends)
        answering = await _answering_kind(port, candidates, opener, time_scale)
        if answering is not None:
            await anyio.sleep(REOPEN_DELAY)
            board = await answering.identify(
                port, serial_number=serial_number, opener=opener, time_scale=time_scale
            )
            if board is not None:
                return board
            await anyio.sleep(REOPEN_DELAY)
        return await port_search.identify_on_port(
            port, serial_number, candidates, opener, time_scale
        )

    board = await registry.claim(port, SerialHardwareBackend, connect)
    try:
        await board.setup()
    except BaseException:
        with anyio.CancelScope(shield=True):
            await board.close()
        raise
    return board


def serial_backends() -> tuple[type[SerialHardwareBackend], ...]:
    """The registered serial hardware backends, in the order identification tries them."""
    return port_search.registered_backends(SerialHardwareBackend)


async def discover_serial_boards(
    *,
    options: DiscoveryOptions | None = None,
    backends: Sequence[type[SerialHardwareBackend]] | None = None,
) -> list[Board]:
    """Find the serial boards of every registered kind, opening each port once.

    A port whose USB identity matches one kind is opened by that kind's backend; a port
    that matches several (the Arduinos share their USB IDs) is identified among them in
    their ``identify_order``. Ports are looked at concurrently. Boards already held are
    given back; ports held by something else are skipped. The boards are not set up.
    It is :func:`~j5aio.backends.hardware.port_search.search_ports` for every serial
    backend.

    :param options: stand-in port lists and openers, a time scale, and whether a failing
        board is skipped (logged) rather than raised.
    :param backends: the serial backends to look with, in identification order; every
        registered one (:func:`serial_backends`) by default.
    :raises CommunicationError: a board could not be identified or failed its handshake
        (unless ``options.skip_failures``).
    """
    return await port_search.search_ports(
        SerialHardwareBackend,
        options=options,
        backends=serial_backends() if backends is None else backends,
    )
