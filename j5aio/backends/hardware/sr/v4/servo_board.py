"""The hardware backend of the SR v4 Servo Board, firmware 2 (USB control transfers).

Handshake: read ``wIndex`` 9 (must be 2), write ``wIndex`` 12 once to start the pulse
generator, then centre all 12 servos (``wIndex`` 0…11, ``wValue`` 0). Positions cannot
be read back, so they are the ones last written.
"""

from __future__ import annotations

from typing import ClassVar

import j5aio.backends.hardware.sr.v4.servo_fw2_codec as codec
from j5aio.backends.hardware.transports.usb_link import USBLink
from j5aio.backends.hardware.usb_backend import USBHardwareBackend
from j5aio.boards.sr.v4.servo_board import ServoBoard
from j5aio.components.servo import ServoInterface, ServoPosition
from j5aio.errors import NotSupportedByHardwareError, UnsupportedFirmwareError

__all__ = ["SRV4ServoBoardHardwareBackend"]

_POWER_HINT = (
    "the servo board did not answer; is it powered from 12 V as well as USB? (It needs "
    "its 12 V supply to start.)"
)
_HANDSHAKE_ERRORS = {
    5: _POWER_HINT,
    110: _POWER_HINT,
    32: "the servo board refused the version request; it may run firmware other than version 2",
}


class SRV4ServoBoardHardwareBackend(ServoInterface, USBHardwareBackend):
    """Drives an SR v4 Servo Board running firmware 2."""

    board = ServoBoard
    # Firmware 4.x (same IDs) is a CDC serial device, found through its serial port.
    SINGLE_INTERFACE: ClassVar[bool] = True
    VID: ClassVar[int] = codec.VID
    PID: ClassVar[int] = codec.PID

    def __init__(self, link: USBLink, *, key: str) -> None:
        super().__init__(link, key=key)
        self._positions: list[ServoPosition] = [0.0] * codec.SERVO_COUNT

    def reset_board_state(self) -> None:
        """Forget the positions: the handshake centres every servo again."""
        self._positions = [0.0] * codec.SERVO_COUNT

    async def _handshake(self) -> None:
        command = codec.FIRMWARE_VERSION
        reply = await self.control_read(command.index, command.length, errors=_HANDSHAKE_ERRORS)
        version = str(codec.parse_u32(reply))
        if version not in codec.SUPPORTED_VERSIONS:
            raise UnsupportedFirmwareError(self.board.name, version, codec.SUPPORTED_VERSIONS)
        self.firmware_version = version
        await self.control_write(codec.INIT_WRITE, 0, errors=_HANDSHAKE_ERRORS)
        for servo in range(codec.SERVO_COUNT):
            await self.set_servo_position(servo, 0.0)

    def make_safe_now(self, timeout: float) -> bool:
        """Send nothing: like :meth:`.ServoBoard.make_safe`, servos stay where they are.

        Firmware 2 cannot unpower a servo, and moving one at exit could hurt whatever
        it holds; see :meth:`.Backend.make_safe_now`.
        """
        return False

    async def get_servo_position(self, identifier: int) -> ServoPosition:
        """Return the position last written to a servo (the board cannot report it)."""
        return self._positions[codec.servo_write_index(identifier)]

    async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
        """Move a servo to ``round(position x 100)`` on the board's -100…100 scale.

        :raises NotSupportedByHardwareError: ``None``: the board cannot unpower a servo.
        """
        index = codec.servo_write_index(identifier)
        if position is None:
            raise NotSupportedByHardwareError(
                f"{self.board.name} cannot unpower a servo (position None); give a "
                "position between -1 and 1",
            )
        value = codec.encode_position(position)

        def remember() -> None:
            self._positions[index] = position

        await self.control_write(index, value, then=remember)
