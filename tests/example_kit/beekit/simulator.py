"""The Bee Board simulated from its protocol table, byte for byte."""

from __future__ import annotations

from typing import ClassVar

from j5aio.simulator import SerialBoardSimulator
from j5aio.simulator.line_assembler import LineAssembler

__all__ = ["BeeSimulator"]


class BeeSimulator(SerialBoardSimulator):
    """A simulated Bee Board.

    :param serial_number: the USB serial number it reports.
    :param version: the firmware version it answers the handshake with.
    """

    baudrate: ClassVar[int] = 57_600
    #: Motor steps each way (a power of 1).
    MOTOR_STEPS: ClassVar[int] = 100
    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = True

    def __init__(self, serial_number: str = "BEE0", *, version: str = "2.1") -> None:
        super().__init__(
            serial_number,
            usb_vid=0x1209,
            usb_pid=0xBEE0,
            manufacturer="Bee Robotics",
            product="Bee Board",
        )
        self.version = version
        self.motor_steps = [0, 0]
        self.led = False
        self.button_held = False
        self.commands: list[bytes] = []
        self._lines = LineAssembler(terminator=ord("\n"))

    def _boot(self) -> bytes:
        self.motor_steps = [0, 0]
        self.led = False
        self._lines.reset()
        return b""

    def _process(self, data: bytes) -> bytes:
        replies = b""
        for line in self._lines.feed(data):
            self.commands.append(line)
            replies += self._answer(line) + b"\n"
        return replies

    def _answer(self, line: bytes) -> bytes:
        if line == b"?":
            return b"BEE:" + self.version.encode()
        if line == b"B":
            return b"B1" if self.button_held else b"B0"
        if line in (b"L0", b"L1"):
            self.led = line == b"L1"
            return b"OK"
        if line[:1] == b"M" and line[1:2] in (b"0", b"1") and line[2:3] == b" ":
            try:
                steps = int(line[3:])
            except ValueError:
                return b"ERR bad steps " + line[3:]
            if not -self.MOTOR_STEPS <= steps <= self.MOTOR_STEPS:
                return b"ERR steps out of range " + line[3:]
            self.motor_steps[int(line[1:2])] = steps
            return b"OK"
        return b"ERR unknown command " + line
