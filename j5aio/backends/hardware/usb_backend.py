"""The base of every backend that drives its board with USB control transfers.

:meth:`USBHardwareBackend.discover` finds the devices by vendor and product ID, and
:meth:`USBHardwareBackend.from_usb_device` (the seam the simulated environment uses,
with a simulated device) reads the serial number, runs the handshake and returns the
board. Each device is driven through one :class:`~.transports.usb_link.USBLink`, whose
worker thread runs its transfers in order (a simulated device's link runs them in the
event loop until it polls). The bus is scanned on a worker thread, a finder that answers
at once (the simulated kit's) in the event loop. A device a live backend holds is never
opened twice (see :mod:`~j5aio.backends.hardware.registry`).

A board that vanishes (errno 19) is looked for again by vendor, product and serial
number (see :mod:`.reconnect`); a replugged device gets a new bus address, so its key in
the registry moves with it, and the same board object keeps working.
"""

from __future__ import annotations

import functools
import logging
from abc import abstractmethod
from collections.abc import Awaitable, Callable, Mapping, Sequence
from typing import ClassVar

import anyio
import anyio.to_thread

from j5aio.backends.backend import Backend
from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.reconnect import Reconnecting
from j5aio.backends.hardware.transports._at_once import call_blocking
from j5aio.backends.hardware.transports.discovery import USBFinder, find_usb_devices
from j5aio.backends.hardware.transports.usb_link import USBDeviceLike, USBLink
from j5aio.boards.board import Board
from j5aio.errors import BoardDisconnectionError, DeviceMissingSerialNumberError

__all__ = ["USBHardwareBackend", "device_key"]

_log = logging.getLogger(__name__)


def device_key(device: USBDeviceLike) -> str:
    """Return the registry key of ``device``: its bus and address, when it has them."""
    bus = getattr(device, "bus", None)
    address = getattr(device, "address", None)
    ids = f"{device.idVendor:04x}:{device.idProduct:04x}"
    if bus is not None and address is not None:
        return f"usb:{ids}@{bus}.{address}"
    return f"usb:{ids}#{id(device)}"


async def _find(vid: int, pid: int, finder: USBFinder | None) -> list[USBDeviceLike]:
    """The devices ``finder`` finds, scanned for on a worker thread (a bus scan blocks).

    A finder that answers at once (the simulated kit's) runs here: no thread starts.
    """
    find = functools.partial(find_usb_devices, vid, pid, finder=finder)
    return await call_blocking(find, worker=finder)


class USBHardwareBackend(Reconnecting, Backend):
    """A backend that drives one board through USB control transfers.

    :param link: the link to the device; the backend owns and closes it.
    :param key: the device's key in the registry of open devices.
    """

    #: The USB vendor ID of the board.
    VID: ClassVar[int]
    #: The USB product ID of the board.
    PID: ClassVar[int]

    def __init__(self, link: USBLink, *, key: str) -> None:
        self._link = link
        self._key = key
        self._firmware_version: str | None = None
        self._serial_number: str | None = None
        self._finder: USBFinder | None = None
        self._found_by_discovery = False

    @property
    def link(self) -> USBLink:
        """The link to the device (for tools and tests)."""
        return self._link

    @property
    def port(self) -> str:
        """A name for the device's place on the bus (its registry key)."""
        return self._key

    @property
    def firmware_version(self) -> str | None:
        """The firmware version the board reported during the handshake.

        ``_handshake`` sets it (``self.firmware_version = "4"``); ``None`` until then.
        """
        return self._firmware_version

    @firmware_version.setter
    def firmware_version(self, version: str | None) -> None:
        self._firmware_version = version

    @classmethod
    async def from_usb_device(cls, device: USBDeviceLike) -> Board:
        """Read the serial number, run the handshake and return the board (not yet set up).

        :param device: a pyusb device, or a stand-in with the same shape (a simulator).
        :raises DeviceMissingSerialNumberError: the device reports no serial number.
        :raises UnsupportedFirmwareError: the board runs firmware this backend cannot drive.
        :raises CommunicationError: a transfer failed.
        """
        link = USBLink(device, board_name=cls.board.name)
        try:
            serial_number = await link.read_serial_number()
            if not serial_number:
                raise DeviceMissingSerialNumberError(
                    f"Found a {cls.board.name} that reports no USB serial number, so it "
                    "cannot be told apart from other boards; its firmware may need to be "
                    "reinstalled.",
                )
            backend = cls(link, key=device_key(device))
            backend._serial_number = serial_number
            await backend._handshake()
        except BaseException:
            with anyio.CancelScope(shield=True):
                await link.aclose()
            raise
        return cls.board(serial_number, backend)

    @classmethod
    def default_discovery_options(cls) -> DiscoveryOptions:
        """The options :meth:`discover` uses when it is given none: this machine's own.

        A simulated backend returns the current simulated kit's instead
        (:class:`~j5aio.simulator.discovery.KitDiscovery`).
        """
        return DiscoveryOptions()

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find every connected board of this kind and return them (not yet set up).

        A device this backend already holds gives back its board.

        :param options: a stand-in USB finder, and whether a failing board is skipped; by
            default :meth:`default_discovery_options`.
        :raises CommunicationError: the bus could not be scanned, or a board failed its
            handshake (unless skipped).
        """
        options = options or cls.default_discovery_options()
        found = await _find(cls.VID, cls.PID, options.usb_finder)
        devices = [device for device in found if cls.drives_device(device)]
        boards: list[Board] = []
        for device in devices:
            try:
                board = await registry.claim(
                    device_key(device),
                    cls,
                    functools.partial(cls.from_usb_device, device),
                )
                backend = board.backend
                assert isinstance(backend, USBHardwareBackend)
                if not backend._found_by_discovery:
                    backend._finder = options.usb_finder
                    backend._found_by_discovery = True
                if not backend.is_connected:
                    await backend.reconnect()
            except registry.PortInUseError as exc:  # pragma: no cover - one backend per VID:PID
                _log.info("Skipping a USB device: %s", exc)
                continue
            except Exception as exc:
                if not options.skip_failures:
                    raise
                _log.warning("Could not connect to a %s: %s", cls.board.name, exc)
                continue
            boards.append(board)
        return sorted(boards, key=lambda board: board.serial_number)

    #: Whether the board has exactly one USB interface. The SR power and servo boards'
    #: serial firmwares (4.x) keep their control-transfer predecessors' IDs but are CDC
    #: serial devices with more interfaces, driven through their serial ports instead.
    SINGLE_INTERFACE: ClassVar[bool] = False

    @classmethod
    def drives_device(cls, device: USBDeviceLike) -> bool:
        """Whether ``device``, found by this backend's vendor and product ID, is its board.

        Every such device is, unless :attr:`SINGLE_INTERFACE` is set: then only a device
        with one USB interface is (one whose configuration cannot be read is tried, and
        its handshake decides). A backend may override this for other rules.
        """
        if not cls.SINGLE_INTERFACE:
            return True
        get_configuration = getattr(device, "get_active_configuration", None)
        if get_configuration is None:
            return True
        try:
            interfaces = int(get_configuration().bNumInterfaces)
        except Exception:  # no permission, not configured: let the handshake tell
            return True
        return interfaces == 1

    @abstractmethod
    async def _handshake(self) -> None:
        """Check the firmware version (set :attr:`firmware_version`) and initialise."""

    async def _reopen(self) -> None:
        """Find the device again by vendor, product and serial number; handshake anew."""
        if not self._found_by_discovery:
            raise BoardDisconnectionError(
                f"{self._key}: this board was not found by discovery, so it cannot be found again"
            )
        for device in await _find(self.VID, self.PID, self._finder):
            if device_key(device) in registry.held() and device_key(device) != self._key:
                continue  # another board's device
            link = USBLink(device, board_name=self.board.name)
            try:
                serial_number = await link.read_serial_number()
            except Exception:
                await link.aclose()
                continue
            if serial_number != self._serial_number:
                await link.aclose()
                continue
            old, self._link = self._link, link
            old.close_now(timeout=0)
            registry.move(self._key, device_key(device), self)
            self._key = device_key(device)
            self._lost = False
            try:
                self.reset_board_state()
                await self._handshake()
            except BaseException:
                self._lost = True
                with anyio.CancelScope(shield=True):
                    await link.aclose()
                raise
            return
        raise BoardDisconnectionError(f"{self._serial_number} is not on the bus")

    async def control_read(
        self,
        index: int,
        length: int,
        errors: Mapping[int, str] | None = None,
        *,
        idempotent: bool = True,
    ) -> bytes:
        """Read ``length`` bytes from command ``index`` (a control transfer in).

        The one way in for built-in and plugin USB backends alike, as
        :meth:`.SerialHardwareBackend.exchange` is for serial ones: transfers run in
        order on the board's link, under the reconnection policy.

        :param errors: messages for the errnos this command is known to fail with.
        :param idempotent: whether the read may be repeated after the board vanished
            and came back.
        :raises ~j5aio.errors.USBCommunicationError: the transfer failed.
        :raises BoardDisconnectionError: the device has gone (it is looked for again).
        """

        def call() -> Awaitable[bytes]:  # the link is looked up anew for a retry
            return self._link.control_read(index, length, errors=errors)

        if self._lost or self._closed_for_good:
            return await self._guarded(call, idempotent=idempotent)
        try:  # the board is there: the call goes straight to the link
            return await self._link.control_read(index, length, errors=errors)
        except BoardDisconnectionError as error:
            return await self._retry_after(error, call, idempotent=idempotent)

    async def control_write(
        self,
        index: int,
        value: int,
        data: bytes = b"",
        errors: Mapping[int, str] | None = None,
        *,
        then: Callable[[], None] | None = None,
        idempotent: bool = True,
    ) -> None:
        """Write command ``index`` with ``value`` and ``data`` (a control transfer out).

        As :meth:`control_read`, the one way in for every USB backend.

        :param errors: messages for the errnos this command is known to fail with.
        :param then: called once the board has accepted the write, even for a cancelled
            caller: update caches there.
        :param idempotent: whether the write may be repeated after the board vanished
            and came back (a piezo note may not).
        :raises ~j5aio.errors.USBCommunicationError: the transfer failed.
        :raises BoardDisconnectionError: the device has gone (it is looked for again).
        """

        def call() -> Awaitable[None]:  # the link is looked up anew for a retry
            return self._link.control_write(index, value, data, errors=errors, then=then)

        if self._lost or self._closed_for_good:
            await self._guarded(call, idempotent=idempotent)
            return
        try:  # the board is there: the call goes straight to the link
            await self._link.control_write(index, value, data, errors=errors, then=then)
        except BoardDisconnectionError as error:
            await self._retry_after(error, call, idempotent=idempotent)

    def _forget(self) -> None:
        """Free the device unless the board will be looked for again."""
        self._mark_lost()
        if not self.reconnect_policy.enabled or not self._found_by_discovery:
            registry.release(self._key, self)

    #: The longest :meth:`close_now` waits for the worker thread's last transfers.
    CLOSE_NOW_TIMEOUT: ClassVar[float] = 0.25

    def close_now(self) -> None:
        """Stop the device's worker thread (bounded wait) and free it; not looked for again."""
        self._closed_for_good = True
        registry.release(self._key, self)
        self._link.close_now(self.CLOSE_NOW_TIMEOUT)

    async def close(self) -> None:
        """Stop the device's worker thread and free it for rediscovery."""
        self._closed_for_good = True
        registry.release(self._key, self)
        await self._link.aclose()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self._key}>"
