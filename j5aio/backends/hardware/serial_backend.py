"""The base of every backend that reaches its board through a serial port.

A serial backend can be made three ways, all ending in the same handshake:

* :meth:`SerialHardwareBackend.discover` lists the serial ports, keeps those whose USB
  identity matches the board, opens each and runs the handshake;
* :meth:`SerialHardwareBackend.attach` opens one explicit port (a device path, a
  pseudo-terminal or a pyserial URL) with no discovery;
* :meth:`SerialHardwareBackend.from_stream` runs the handshake over a stream that is
  already open. This is the seam the simulated environment uses: it hands over a
  :class:`~j5aio.backends.hardware.transports.memory.SimulatorStream`.

Ports are claimed in :mod:`~j5aio.backends.hardware.registry`, so a port that a live
backend holds is never opened twice. Every failure is a :class:`~j5aio.errors.CommunicationError`.

A board found by discovery or attached by port is looked for again when it vanishes
(see :mod:`.reconnect`): by its USB serial number for a discovered board (its port
path may change), at the same path for an attached one. A board made with
:meth:`SerialHardwareBackend.from_stream` cannot be reopened, so it stays lost.
"""

from __future__ import annotations

import logging
from abc import abstractmethod
from collections.abc import Awaitable, Callable, Iterable, Mapping, Sequence
from typing import ClassVar, TypeVar, cast, overload

import anyio
import anyio.to_thread

from j5aio.backends.backend import Backend, BoardT
from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions, StreamOpener
from j5aio.backends.hardware.reconnect import Reconnecting
from j5aio.backends.hardware.transports.discovery import (
    ComPortLike,
    PortInfo,
    find_port,
    list_serial_ports,
    match_ports,
)
from j5aio.backends.hardware.transports.readers import ReplyReader
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.boards.board import Board
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    DeviceMissingSerialNumberError,
    UnsupportedFirmwareError,
)
from j5aio.safety import hooks as safety_hooks

__all__ = ["SerialHardwareBackend", "scaled"]

_log = logging.getLogger(__name__)

T = TypeVar("T")
U = TypeVar("U")

#: The shortest wait a time scale can produce, so that a zero scale still lets an
#: instantly ready simulator answer.
MINIMUM_WAIT = 0.005


def scaled(seconds: float, time_scale: float) -> float:
    """Return ``seconds x time_scale``, but never less than ``MINIMUM_WAIT``."""
    return max(seconds * time_scale, MINIMUM_WAIT)


class _Origin:
    """How a board was found, so that it can be found again.

    A plain class, not a dataclass: one is made for every board found, nothing compares
    or prints them, and a dataclass would cost every start the generation of its methods.
    """

    __slots__ = ("by_port", "opener", "port_source", "serial_number", "time_scale")

    def __init__(
        self,
        serial_number: str,
        by_port: bool,
        opener: StreamOpener | None,
        port_source: Callable[[], Iterable[ComPortLike]] | None,
        time_scale: float,
    ) -> None:
        self.serial_number = serial_number
        self.by_port = by_port
        self.opener = opener
        self.port_source = port_source
        self.time_scale = time_scale


class SerialHardwareBackend(Reconnecting, Backend[BoardT]):
    """A backend that drives one board through one serial port.

    A subclass for a new board (``class BeeBackend(SerialHardwareBackend[BeeBoard],
    MotorInterface, ...)``) gives:

    * ``board``: the board class it drives (also the type argument, so that
      :meth:`attach`, :meth:`from_stream` and :meth:`discover` return it typed);
    * :attr:`BAUDRATE` and :attr:`DEFAULT_TIMEOUT` (seconds to wait for a reply), and for
      discovery the USB identity: :attr:`USB_IDS`, optionally :attr:`USB_MANUFACTURER` /
      :attr:`USB_PRODUCT`;
    * :meth:`_handshake`, the one method it must implement: called once on a freshly
      opened port, it checks that the board is the right one and runs firmware it can
      drive (raising :class:`~j5aio.errors.CommunicationError` or
      :class:`~j5aio.errors.UnsupportedFirmwareError` if not) and records the firmware
      version by setting :attr:`firmware_version`;
    * the interface coroutines, which talk to the board with :meth:`exchange` (a request
      and its reply, read by a :class:`~j5aio.backends.hardware.transports.readers.ReplyReader`)
      and :meth:`send` (a command with no reply), the one way in for built-in and
      plugin backends alike. Both serialise access to the port, time out after
      :attr:`DEFAULT_TIMEOUT` and raise :class:`~j5aio.errors.CommunicationError`
      subclasses naming the port; a vanished port is forgotten, so that rediscovery
      opens it afresh. Their ``then=`` callback is where a backend updates what it
      remembers of the board: it runs once the board has the command, even for a
      cancelled caller;
    * optionally ``_link_ready``, to name the probe that puts the link back in step
      after a timeout.

    :param link: the link to the board's port; the backend owns and closes it.
    :param port: the port's path or URL.
    """

    #: The line speed of the board's UART.
    BAUDRATE: ClassVar[int] = 115_200
    #: Seconds to wait for a reply.
    DEFAULT_TIMEOUT: ClassVar[float] = 0.25
    #: The USB (vendor, product) IDs of the board's USB-serial adapter.
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset()
    #: The USB manufacturer string the board must report, if it is checked.
    USB_MANUFACTURER: ClassVar[str | None] = None
    #: The USB product string the board must report, if it is checked.
    USB_PRODUCT: ClassVar[str | None] = None
    #: Skip a port without a USB serial number (with a warning) instead of raising.
    SKIP_PORTS_WITHOUT_SERIAL: ClassVar[bool] = False
    #: Multiplies the handshake's waits when :meth:`identify` asks whether a board is of
    #: this kind (a board that boots and answers in time needs far less than a handshake
    #: allows for a slow one).
    IDENTIFY_TIME_SCALE: ClassVar[float] = 1.0

    def __init__(self, link: SerialLink, *, port: str) -> None:
        self._link = link
        self._port = port
        self._firmware_version: str | None = None
        self._origin: _Origin | None = None

    @property
    def port(self) -> str:
        """The path or URL of the board's port."""
        return self._port

    @property
    def link(self) -> SerialLink:
        """The link to the board (for tools and tests)."""
        return self._link

    _acknowledges_later: ClassVar[bool] = True  # (the interface calls read the link's state)

    def owes_acknowledgement(self) -> bool:
        """Whether the link still owes the acknowledgement of a command confirmed later."""
        return self._link.unconfirmed is not None

    async def confirm_acknowledgement(self) -> None:
        """Read and check the acknowledgement the link still owes (see :meth:`command`).

        :raises ~j5aio.errors.EarlierCommandError: the earlier command had failed.
        :raises ~j5aio.errors.BoardDisconnectionError: the port has gone (the board is
            marked lost, as any call that finds it gone does).
        """
        try:  # the steps of _guarded, written out (this runs on every call that owes one)
            if self._lost or self._closed_for_good:
                await self._check_connected()
            await self._link.confirm()
        except BoardDisconnectionError as error:
            await self._retry_after(error, lambda: self._link.confirm(), idempotent=False)

    @property
    def firmware_version(self) -> str | None:
        """The firmware version the board reported during the handshake.

        :meth:`_handshake` sets it (``self.firmware_version = "3"``); ``None`` until then.
        """
        return self._firmware_version

    @firmware_version.setter
    def firmware_version(self, version: str | None) -> None:
        self._firmware_version = version

    # -- making a backend ---------------------------------------------------------------

    @classmethod
    async def from_stream(
        cls,
        stream: ByteStream,
        *,
        port: str,
        serial_number: str,
        time_scale: float = 1.0,
    ) -> BoardT:
        """Run the handshake over an open ``stream`` and return the board (not yet set up).

        The backend owns ``stream`` from now on, and closes it if the handshake fails.

        :param port: the port's name, for errors and the wire log.
        :param serial_number: the serial number to give the board.
        :param time_scale: multiplies the waits for the board to boot.
        :raises CommunicationError: the board did not answer as it should.
        :raises UnsupportedFirmwareError: the board runs firmware this backend cannot drive.
        """
        link = SerialLink(stream, name=port, default_timeout=cls.DEFAULT_TIMEOUT)
        backend = cls(link, port=port)
        try:
            await backend._handshake(time_scale=time_scale)
        except BaseException:
            await link.aclose()
            raise
        backend._link_ready()
        return cast(BoardT, cls.board(serial_number, backend))

    @classmethod
    async def attach(
        cls,
        port: str,
        *,
        time_scale: float = 1.0,
        opener: StreamOpener | None = None,
    ) -> BoardT:
        """Open the board on ``port`` without discovery and return it (not yet set up).

        The serial number is the port's USB serial number if the system lists the port
        with one, and otherwise ``port`` itself. A port this backend already holds gives
        back the same board.

        :param port: a device path (a pseudo-terminal works) or a pyserial URL.
        :param time_scale: multiplies the waits for the board to boot.
        :param opener: opens the port;
            :func:`~j5aio.backends.hardware.transports.serial_stream.open_serial_stream` by default.
        :raises PortInUseError: another kind of backend holds the port.
        :raises CommunicationError: the port could not be opened, or the board did not
            answer as it should.
        """
        safety_hooks.install()  # a program's way to a board: it gets the safety hooks

        async def connect() -> BoardT:
            found = await anyio.to_thread.run_sync(find_port, port)
            serial_number = found.serial_number if found and found.serial_number else port
            origin = _Origin(serial_number, True, opener, None, time_scale)
            return await cls._open(port, origin)

        return cast(BoardT, await registry.claim(port, cls, connect))

    @classmethod
    def default_discovery_options(cls) -> DiscoveryOptions:
        """The options :meth:`discover` uses when it is given none: this machine's own.

        A simulated backend returns the current simulated kit's instead
        (:class:`~j5aio.simulator.discovery.KitDiscovery`).
        """
        return DiscoveryOptions()

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[BoardT]:
        """Open every port whose USB identity matches this board and return the boards.

        When other registered kinds of board use the same USB IDs (the Arduinos), each
        such port is identified once among them instead
        (:func:`~j5aio.backends.hardware.port_search.search_ports`): this backend's
        boards are returned, and the others' stay held for their own discovery to give
        back without opening the port again. Boards are opened concurrently. A port this
        backend already holds gives back its board; a port held by another kind of
        backend is skipped.

        :param options: stand-in port lists and openers, a time scale, and whether a
            failing board is skipped; by default :meth:`default_discovery_options`.
        :raises DeviceMissingSerialNumberError: a matching port has no serial number.
        :raises CommunicationError: a board failed its handshake (unless skipped).
        """
        from j5aio.backends.hardware.port_search import search_ports

        options = options or cls.default_discovery_options()
        sharing = cls._kinds_sharing_ports() if options.identify_shared_ports else ()
        backends = sharing if len(sharing) > 1 else (cls,)
        found = await search_ports(SerialHardwareBackend, options=options, backends=backends)
        # Boards of the other kinds stay held, for their own discovery to give back.
        return [cast(BoardT, board) for board in found if isinstance(board.backend, cls)]

    @classmethod
    async def identify(
        cls,
        port: str,
        *,
        serial_number: str,
        opener: StreamOpener | None = None,
        time_scale: float = 1.0,
        port_source: Callable[[], Iterable[ComPortLike]] | None = None,
        by_port: bool = True,
    ) -> BoardT | None:
        """Open ``port`` at this board's baud rate and return the board if it is one.

        This is how :func:`~j5aio.backends.hardware.identify.attach` and discovery of ports that
        several kinds share tell boards apart: the handshake runs with its waits scaled
        by ``time_scale`` and :data:`IDENTIFY_TIME_SCALE`. A board whose answers show it
        is another kind (a wrong reply, no reply) gives ``None``, and the port is closed
        again. Override it when the handshake alone cannot tell, or would disturb other
        kinds of board.

        :param port: the port's path or URL.
        :param serial_number: the serial number to give the board.
        :param opener: opens the port; the real serial port by default.
        :param time_scale: multiplies the waits for the board to boot and answer.
        :param port_source: the port list discovery searched, to search again when a
            discovered board vanishes (see :mod:`.reconnect`).
        :param by_port: the board was asked for by its port (``attach``), so it is looked
            for again at the same path; else by its serial number.
        :raises UnsupportedFirmwareError: the board is of this kind but runs firmware this
            backend cannot drive.
        :raises CommunicationError: the port could not be opened.
        """
        stream = await cls._open_stream(port, opener)  # a port that will not open: raise
        try:
            board = await cls.from_stream(
                stream,
                port=port,
                serial_number=serial_number,
                time_scale=time_scale * cls.IDENTIFY_TIME_SCALE,
            )
        except UnsupportedFirmwareError:
            raise
        except CommunicationError as error:
            _log.debug("%s on %s: not this kind: %s", cls.__name__, port, error)
            return None
        origin = _Origin(serial_number, by_port, opener, port_source, time_scale)
        cast(SerialHardwareBackend[BoardT], board.backend)._origin = origin
        return board

    @classmethod
    def _kinds_sharing_ports(cls) -> tuple[type[SerialHardwareBackend], ...]:
        """Return this backend and the registered kinds that use any of its USB IDs, in order.

        Empty when no registered kind is this backend or one of its bases.
        """
        from j5aio.backends.hardware.port_search import registered_backends

        registered = registered_backends(SerialHardwareBackend)
        if not any(issubclass(cls, backend) for backend in registered):
            return ()
        return tuple(
            cls if issubclass(cls, backend) else backend
            for backend in registered
            if issubclass(cls, backend) or backend.USB_IDS & cls.USB_IDS
        )

    @classmethod
    def has_serial_number(cls, port: PortInfo) -> bool:
        """Whether ``port`` has a USB serial number; without one, skip it or raise.

        :raises DeviceMissingSerialNumberError: it has none and
            :data:`SKIP_PORTS_WITHOUT_SERIAL` is false.
        """
        if port.serial_number:
            return True
        message = (
            f"Found a {cls.board.name} on {port.device} that reports no USB serial number, "
            "so it cannot be told apart from other boards"
        )
        if cls.SKIP_PORTS_WITHOUT_SERIAL:
            _log.warning("%s; skipping it.", message)
            return False
        raise DeviceMissingSerialNumberError(
            f"{message}. Its USB-serial adapter may need reprogramming; ask your kit supplier.",
        )

    @staticmethod
    def collect(
        results: Mapping[str, Board | Exception], *, skip_failures: bool,
    ) -> list[Board]:
        """Return the boards among ``results`` (by port), sorted by serial number.

        Failures are logged; the first is raised unless ``skip_failures``.
        """
        boards = [item for item in results.values() if isinstance(item, Board)]
        failures = [(port, item) for port, item in results.items() if isinstance(item, Exception)]
        for port, failure in failures:
            _log.warning("Could not connect to the board on %s: %s", port, failure)
        if failures and not skip_failures:
            raise failures[0][1]
        return sorted(boards, key=lambda board: board.serial_number)

    @classmethod
    def _lost_board(cls, serial_number: str, options: DiscoveryOptions) -> Board | None:
        """Return the lost board with ``serial_number`` found by the same kind of search."""
        known = registry.find_serial(cls, serial_number)
        if known is None:
            return None
        backend = known.backend
        assert isinstance(backend, SerialHardwareBackend)
        origin = backend._origin
        if backend.is_connected or origin is None or origin.by_port:
            return None
        if origin.port_source is not options.port_source:
            return None
        return known

    @staticmethod
    async def _found_again(board: Board) -> None:
        backend = board.backend
        if isinstance(backend, Reconnecting) and not backend.is_connected:
            await backend.reconnect()

    @classmethod
    async def _open_stream(cls, port: str, opener: StreamOpener | None) -> ByteStream:
        if opener is None:
            # (imported here: pyserial's asyncio stream is needed for a real port only)
            from j5aio.backends.hardware.transports.serial_stream import open_serial_stream

            return await open_serial_stream(port, cls.BAUDRATE)
        return await opener(port, cls.BAUDRATE)

    @classmethod
    async def open_port(
        cls,
        port: str,
        serial_number: str,
        opener: StreamOpener | None = None,
        time_scale: float = 1.0,
        *,
        port_source: Callable[[], Iterable[ComPortLike]] | None = None,
    ) -> BoardT:
        """Open ``port``, found by discovery, and run the handshake (no port claim).

        The board is looked for by its serial number if it vanishes.

        :raises CommunicationError: the port could not be opened, or the handshake failed.
        """
        origin = _Origin(serial_number, False, opener, port_source, time_scale)
        return await cls._open(port, origin)

    @classmethod
    async def _open(cls, port: str, origin: _Origin) -> BoardT:
        stream = await cls._open_stream(port, origin.opener)
        board = await cls.from_stream(
            stream,
            port=port,
            serial_number=origin.serial_number,
            time_scale=origin.time_scale,
        )
        backend = board.backend
        assert isinstance(backend, SerialHardwareBackend)
        backend._origin = origin
        return board

    async def _reopen(self) -> None:
        """Find the board again (see :mod:`.reconnect`), on a new link."""
        origin = self._origin
        if origin is None:
            raise BoardDisconnectionError(
                f"{self._port}: this board was given as an open stream, so it cannot be reopened"
            )
        port = self._port
        if not origin.by_port:
            listed = await anyio.to_thread.run_sync(list_serial_ports, origin.port_source)
            matched = match_ports(
                listed, set(self.USB_IDS), self.USB_MANUFACTURER, self.USB_PRODUCT
            )
            found = [item for item in matched if item.serial_number == origin.serial_number]
            if not found:
                raise BoardDisconnectionError(f"{origin.serial_number} is not listed")
            port = found[0].device
        stream = await self._open_stream(port, origin.opener)
        link = SerialLink(stream, name=port, default_timeout=self.DEFAULT_TIMEOUT)
        try:
            registry.move(self._port, port, self)
        except BaseException:
            link.close_now()
            raise
        self._port = port
        self._link = link
        self._lost = False
        try:
            self.reset_board_state()
            await self._handshake(time_scale=origin.time_scale)
        except BaseException:
            self._lost = True
            link.close_now()
            raise
        self._link_ready()

    @abstractmethod
    async def _handshake(self, *, time_scale: float) -> None:
        """Check the board and its firmware version; set :attr:`firmware_version`."""

    def _link_ready(self) -> None:
        """Configure the link once the handshake has passed (a hook; nothing here).

        Called on every new link (the first, and after a reconnection), once the board
        is known to run firmware this backend drives: the place to name the
        resynchronisation probe (:meth:`.SerialLink.set_resync_line`), which is sent
        only to a board that understands it.
        """

    # -- talking to the board -----------------------------------------------------------

    @overload
    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        timeout: float | None = None,
        *,
        idempotent: bool = True,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> T: ...

    @overload
    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        timeout: float | None = None,
        *,
        then: Callable[[T], U],
        idempotent: bool = True,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> U: ...

    async def exchange(
        self,
        request: bytes,
        reader: ReplyReader[T],
        timeout: float | None = None,
        *,
        then: Callable[[T], object] | None = None,
        idempotent: bool = True,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> object:
        """Send ``request`` and return the reply that ``reader`` reads (or ``then(reply)``).

        Runs to completion once started, whoever cancels the caller (see
        :class:`~j5aio.backends.hardware.transports.serial_link.SerialLink`), so a reply
        is always read by the request that asked for it.

        :param timeout: seconds to wait for the reply; :attr:`DEFAULT_TIMEOUT` by default.
        :param then: called with the reply as soon as it has arrived, even if the caller
            has been cancelled meanwhile; its result is returned instead of the reply.
            Parse the reply and update what the backend remembers of the board here, so
            that the cache changes when, and only when, the board has been told.
        :param idempotent: whether the request may be sent again after the board vanished
            and came back (see :mod:`.reconnect`); ``False`` for one that must not repeat.
        :param when_dirty: for a firmware that can tag a request so that its reply names
            it: returns the tagged request and a correlating reader, used instead only
            while a late reply may be on its way (see
            :meth:`.SerialLink.exchange`).
        :raises CommunicationError: no reply in time, or a reply ``reader`` refuses.
        :raises BoardDisconnectionError: the port has gone (it is looked for again).
        """

        def call() -> Awaitable[object]:  # the link is looked up anew for a retry
            return self._link.exchange(
                request, reader, timeout=timeout, then=then,  # type: ignore[arg-type]
                when_dirty=when_dirty,
            )

        if self._lost or self._closed_for_good:
            return await self._guarded(call, idempotent=idempotent)
        try:  # the board is there: the call goes straight to the link
            return await self._link.exchange(
                request, reader, timeout=timeout, then=then,  # type: ignore[arg-type]
                when_dirty=when_dirty,
            )
        except BoardDisconnectionError as error:
            return await self._retry_after(error, call, idempotent=idempotent)

    async def command(
        self,
        request: bytes,
        reader: ReplyReader[T],
        timeout: float | None = None,
        *,
        then: Callable[[T], object] | None = None,
        idempotent: bool = True,
        when_dirty: Callable[[], tuple[bytes, ReplyReader[T]]] | None = None,
    ) -> None:
        """Send ``request``, a command whose reply only acknowledges it; check the reply.

        As :meth:`exchange`, but nothing of the reply is returned: ``reader`` and
        ``then`` check it (``then`` raises if the board refused, and updates what the
        backend remembers). Inside
        :func:`~j5aio.backends.acknowledgements.acknowledge_later` it may return as
        soon as the command is written; the reply is then checked before the board's
        next request (see :meth:`.SerialLink.command`).

        :raises CommunicationError: no reply in time, or a reply ``then`` refuses.
        :raises ~j5aio.errors.EarlierCommandError: the board's previous command, whose
            acknowledgement was read now, had failed (this one was not sent).
        :raises BoardDisconnectionError: the port has gone (it is looked for again).
        """

        def call() -> Awaitable[None]:  # the link is looked up anew for a retry
            return self._link.command(
                request, reader, timeout=timeout, then=then, when_dirty=when_dirty
            )

        if self._lost or self._closed_for_good:
            await self._guarded(call, idempotent=idempotent)
            return
        try:  # the board is there: the call goes straight to the link
            await self._link.command(
                request, reader, timeout=timeout, then=then, when_dirty=when_dirty
            )
        except BoardDisconnectionError as error:
            await self._retry_after(error, call, idempotent=idempotent)

    async def send(
        self, data: bytes, *, then: Callable[[], None] | None = None, idempotent: bool = True
    ) -> None:
        """Send ``data``, a command the board does not answer.

        Runs to completion once started, as :meth:`exchange` does.

        :param then: called once the bytes have gone, even if the caller has been
            cancelled meanwhile (update what the backend remembers here).
        :param idempotent: as for :meth:`exchange`.
        :raises ~j5aio.errors.CommunicationTimeoutError: the bytes could not be sent in time.
        :raises BoardDisconnectionError: the port has gone (it is looked for again).
        """
        def call() -> Awaitable[None]:  # the link is looked up anew for a retry
            return self._link.send(data, then=then)

        if self._lost or self._closed_for_good:
            await self._guarded(call, idempotent=idempotent)
            return
        try:  # the board is there: the call goes straight to the link
            await self._link.send(data, then=then)
        except BoardDisconnectionError as error:
            await self._retry_after(error, call, idempotent=idempotent)

    def _forget(self) -> None:
        """Close the link at once; free the port only if the board will not be looked for."""
        self._mark_lost()
        if not self.reconnect_policy.enabled:
            registry.release(self._port, self)
        self._link.close_now()

    def close_now(self) -> None:
        """Close the port at once, synchronously, and free it; it is not looked for again."""
        self._closed_for_good = True
        registry.release(self._port, self)
        self._link.close_now()

    async def close(self) -> None:
        """Close the port and free it for rediscovery; the board is not looked for again."""
        self._closed_for_good = True
        registry.release(self._port, self)
        await self._link.aclose()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} port={self._port!r}>"
