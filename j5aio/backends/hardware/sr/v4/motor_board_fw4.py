r"""The hardware backend of the SR v4 Motor Board, firmware 4.4 / 4.5 (text, 115 200 baud).

Handshake: ``\x00\n*IDN?\n`` (the ``\x00`` line, NACKed, clears any half-received line
and keeps a firmware 3 board still), answered by a NACK and then
``Student Robotics:MCv4B:<asset tag>:<version>``. Version 4.4 or 4.5 (any patch) is
driven; a board that stays silent is asked firmware 3's version query, so that a
firmware 3 board gets :class:`~j5aio.errors.UnsupportedFirmwareError` naming what it
runs. The motors are left as they are (the board starts coasting).

Powers are linear in the duty: ``MOT:<n>:SET:<round(p x 1000)>``. BRAKE is
``MOT:<n>:SET:0`` and COAST ``MOT:<n>:DISABLE``. States are read from the board; since
it cannot tell a brake from power 0, the backend remembers what it last sent (the only
cached state, :attr:`SRV4MotorBoardFw4HardwareBackend.last_sent`).
"""

from __future__ import annotations

from typing import ClassVar

import j5aio.backends.hardware.sr.v4.motor_fw3_codec as fw3
import j5aio.backends.hardware.sr.v4.motor_fw4_codec as codec
from j5aio import power_hints
from j5aio.backends.hardware.sr.v4.motor_identify import probe_fw4_identity
from j5aio.backends.hardware.sr.v4.text_backend import SRTextBackend
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4.motor_board_fw4 import MotorBoardFw4
from j5aio.components.monitored_motor import MonitoredMotorInterface
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.components.voltage_sensor import VoltageSensorInterface
from j5aio.errors import CommunicationTimeoutError, UnsupportedFirmwareError

__all__ = ["SRV4MotorBoardFw4HardwareBackend"]

_SUPPORTED = ("4.4", "4.4.<patch>", "4.5", "4.5.<patch>")


class SRV4MotorBoardFw4HardwareBackend(
    MonitoredMotorInterface, VoltageSensorInterface, SRTextBackend,
):
    """Drives an SR v4 Motor Board running firmware 4.4 or 4.5."""

    board = MotorBoardFw4

    BAUDRATE: ClassVar[int] = codec.BAUDRATE
    DEFAULT_TIMEOUT: ClassVar[float] = 0.5
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x0403, 0x6001)})
    USB_MANUFACTURER: ClassVar[str | None] = "Student Robotics"
    USB_PRODUCT: ClassVar[str | None] = "MCV4B"

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self.asset_tag: str | None = None
        #: What this backend last sent to each motor (``None``: nothing yet).
        self.last_sent: list[MotorState | None] = [None] * codec.MOTOR_COUNT

    def forget_cached_state(self) -> None:
        """Forget what was last sent to the motors (after the board has reset, say)."""
        self.last_sent = [None] * codec.MOTOR_COUNT

    def reset_board_state(self) -> None:
        """Forget what was last sent: a board that came back has reset (both coast)."""
        self.forget_cached_state()

    def make_safe_now(self, timeout: float) -> bool:
        """Brake both motors at once, synchronously (the safety net; see :class:`.Backend`).

        A line ending goes first, so that a command cut in half by the program's end
        ends there (the board NACKs it) instead of swallowing the first brake. The
        replies are not waited for; the link drains them before its next exchange.
        """
        if self._link.is_closed:
            return False
        brake = MotorSpecialState.BRAKE
        commands = b"".join(
            codec.encode_set(motor, brake) for motor in range(codec.MOTOR_COUNT)
        )
        self._link.send_now(b"\n" + commands, timeout=timeout)
        self.last_sent = [brake] * codec.MOTOR_COUNT
        return True

    async def _handshake(self, *, time_scale: float) -> None:
        try:
            identity = await probe_fw4_identity(self._link, board=self.board.name)
        except CommunicationTimeoutError:
            await self._refuse_firmware_3()
            raise
        if not codec.is_supported_version(identity.version):
            raise UnsupportedFirmwareError(self.board.name, identity.version, _SUPPORTED)
        self.asset_tag = identity.asset_tag
        self.firmware_version = identity.version

    async def _refuse_firmware_3(self) -> None:
        """Ask a silent board for firmware 3's version; refuse it if it answers."""
        try:
            line = await self.exchange(fw3.RESYNC_AND_VERSION_QUERY, read_line(max_length=64))
        except CommunicationTimeoutError:
            return
        version = fw3.parse_version_reply(line)
        raise UnsupportedFirmwareError(self.board.name, version, _SUPPORTED)

    def _explain_timeout(self, error: CommunicationTimeoutError) -> CommunicationTimeoutError:
        """The timeout, saying what a silent motor board usually means: no 12 V."""
        hint = power_hints.power_hint(power_hints.output_feeding(self.asset_tag or ""))
        return CommunicationTimeoutError(
            f"{error}. A motor board that stops answering has usually lost its 12 V "
            f"input, which powers its controller. {hint}"
        )

    async def _status(self) -> codec.MotorStatus:
        return codec.parse_status(self.board.name, await self._query(codec.STATUS))

    async def get_motor_state(self, identifier: int) -> MotorState:
        """Read a motor's state: a power, BRAKE or COAST."""
        command = codec.encode_get(identifier)
        reading = codec.parse_reading(self.board.name, command, await self._query(command))
        return codec.decode_reading(reading, last_set=self.last_sent[identifier])

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Set a motor to a power in [-1, 1] (duty ``|p|``), BRAKE or COAST."""
        def remember() -> None:
            self.last_sent[identifier] = power

        await self._act(codec.encode_set(identifier, power), then=remember)

    async def get_motor_current(self, identifier: int) -> float:
        """Read the current a motor draws, in amperes (the board filters it)."""
        command = codec.encode_current(identifier)
        return codec.parse_current_ma(self.board.name, command, await self._query(command)) / 1000

    async def get_motor_fault(self, identifier: int) -> bool:
        """Read whether a motor's driver reports a fault (``*STATUS?``)."""
        codec.check_motor(identifier)
        return (await self._status()).faults[identifier]

    async def get_voltage_sensor_voltage(self, identifier: int) -> float:
        """Read the board's input voltage, in volts (``*STATUS?``)."""
        self._check_single(identifier, "voltage sensor")
        return (await self._status()).input_mv / 1000
