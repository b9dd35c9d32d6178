r"""The hardware backend of the SR v4 Motor Board, firmware 3 (binary protocol at 1 Mbaud).

Handshake: ``00 01`` (a resync byte, which the firmware ignores when idle and which
swallows a half-sent speed command, then the version query), answered ``MCV4B:3\n``;
then both motors are braked: ``02 02 03 02``. The board cannot be read back, so the
motor states are the ones last sent.

A power ``p`` is sent as ``round(p x 100) + 128``, so the board drives a duty of ``|p|``.
A robot tuned against j5, which sent ``round(p x 125) + 128`` (full speed from 0.8), can
opt in to j5's bytes with :class:`SRV4MotorBoardJ5ScaleHardwareBackend`, or by setting
:attr:`SRV4MotorBoardHardwareBackend.SPEED_SCALE` to ``J5_SCALE`` on a subclass.

Correlation guarantee: the board answers only the version query, so no reply can be
mistaken for another. A motor command that did not go out whole (a timeout part way)
marks the link dirty; the next command is then preceded by ``00 01``, and the link
waits for the version line: the ``00`` swallows the half-sent command, and the answer
shows the board is listening again.
"""

from __future__ import annotations

from typing import ClassVar

import j5aio.backends.hardware.sr.v4.motor_fw3_codec as codec
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports.readers import read_line
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.components.motor import MotorInterface, MotorSpecialState, MotorState
from j5aio.errors import UnsupportedFirmwareError

__all__ = ["SRV4MotorBoardHardwareBackend", "SRV4MotorBoardJ5ScaleHardwareBackend"]

_VERSION_LINE = read_line(max_length=64)


class SRV4MotorBoardHardwareBackend(MotorInterface, SerialHardwareBackend):
    """Drives an SR v4 Motor Board running firmware 3."""

    board = MotorBoard

    BAUDRATE: ClassVar[int] = codec.BAUDRATE
    DEFAULT_TIMEOUT: ClassVar[float] = 0.25
    USB_IDS: ClassVar[frozenset[tuple[int, int]]] = frozenset({(0x0403, 0x6001)})
    USB_MANUFACTURER: ClassVar[str | None] = "Student Robotics"
    USB_PRODUCT: ClassVar[str | None] = "MCV4B"
    #: Speed steps per unit of power: ``LINEAR_SCALE`` (duty = power, the default) or
    #: ``J5_SCALE`` (j5's bytes, full duty from power 0.8).
    SPEED_SCALE: ClassVar[int] = codec.LINEAR_SCALE

    def __init__(self, link: SerialLink, *, port: str) -> None:
        super().__init__(link, port=port)
        self._states: list[MotorState] = [MotorSpecialState.BRAKE] * codec.MOTOR_COUNT

    def reset_board_state(self) -> None:
        """Forget the motor states: the handshake brakes both motors again."""
        self._states = [MotorSpecialState.BRAKE] * codec.MOTOR_COUNT

    async def _handshake(self, *, time_scale: float) -> None:
        line = await self.exchange(codec.RESYNC_AND_VERSION_QUERY, _VERSION_LINE)
        version = codec.parse_version_reply(line)
        if version not in codec.SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, codec.SUPPORTED_VERSIONS)
        self.firmware_version = version
        self._link.set_resync(codec.RESYNC_AND_VERSION_QUERY, codec.encode_version_reply(version))
        for motor in range(codec.MOTOR_COUNT):
            await self.set_motor_state(motor, MotorSpecialState.BRAKE)

    def _check_motor(self, identifier: int) -> None:
        if identifier not in range(codec.MOTOR_COUNT):
            raise ValueError(f"{self.board.name} has motors 0 and 1, not {identifier!r}")

    async def get_motor_state(self, identifier: int) -> MotorState:
        """Return the state last sent to a motor (the board cannot report it)."""
        self._check_motor(identifier)
        return self._states[identifier]

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        """Set a motor to a power in [-1, 1] (``round(p x SPEED_SCALE) + 128``), BRAKE or COAST."""
        if identifier not in range(codec.MOTOR_COUNT):
            self._check_motor(identifier)  # raises, naming the board
        command = codec.encode_motor_command(identifier, power, scale=self.SPEED_SCALE)

        def remember() -> None:
            self._states[identifier] = power

        await self.send(command, then=remember)

    def make_safe_now(self, timeout: float) -> bool:
        """Brake both motors at once, synchronously (the safety net; see :class:`.Backend`).

        A resync byte goes first, so that a speed command cut in half by the program's end
        cannot swallow the first brake command.
        """
        if self._link.is_closed:
            return False
        brake = MotorSpecialState.BRAKE
        commands = b"".join(
            codec.encode_motor_command(motor, brake) for motor in range(codec.MOTOR_COUNT)
        )
        self._link.send_now(bytes((codec.CMD_RESYNC,)) + commands, timeout=timeout)
        self._states = [brake] * codec.MOTOR_COUNT
        return True


class SRV4MotorBoardJ5ScaleHardwareBackend(SRV4MotorBoardHardwareBackend):
    """Drives a firmware 3 Motor Board with j5's bytes, ``round(p x 125) + 128``.

    For a robot tuned against j5: the duty is ``1.25 x |p|``, full from ``|p| = 0.8``.
    Choose it with ``BoardGroup.get_board_group(MotorBoard,
    SRV4MotorBoardJ5ScaleHardwareBackend)``, or register it in an environment.
    """

    SPEED_SCALE: ClassVar[int] = codec.J5_SCALE
