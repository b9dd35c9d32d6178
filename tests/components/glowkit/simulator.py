"""The Glow Board simulated from its protocol table, byte for byte."""

from __future__ import annotations

from typing import ClassVar

from j5aio.simulator import SerialBoardSimulator
from j5aio.simulator.line_assembler import LineAssembler

__all__ = ["GlowSimulator"]


class GlowSimulator(SerialBoardSimulator):
    """A simulated Glow Board.

    Set :attr:`lux` (the light on each sensor) and :attr:`object_mm` (where the nearest
    object is, ``None`` for nothing in range) to change what it reads.

    :param serial_number: the USB serial number it reports.
    """

    baudrate: ClassVar[int] = 57_600
    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = True

    #: The farthest the distance sensor sees, in millimetres.
    RANGE_MM: ClassVar[float] = 2000.0

    def __init__(self, serial_number: str = "GLOW0") -> None:
        super().__init__(
            serial_number,
            usb_vid=0x1209,
            usb_pid=0x6C0E,
            manufacturer="Glow Robotics",
            product="Glow Board",
        )
        self.lux = [0.0, 0.0, 0.0, 0.0]
        self.gains = [1, 1, 1, 1]
        self.object_mm: float | None = None
        self._lines = LineAssembler(terminator=ord("\n"))

    def _boot(self) -> bytes:
        self.gains = [1, 1, 1, 1]
        self._lines.reset()
        return b""

    def _process(self, data: bytes) -> bytes:
        return b"".join(self._answer(line) + b"\n" for line in self._lines.feed(data))

    def _answer(self, line: bytes) -> bytes:
        if line == b"?":
            return b"GLOW:1.2"
        if line == b"D":
            if self.object_mm is None or self.object_mm > self.RANGE_MM:
                return b"-"
            return b"%d" % round(self.object_mm)
        command, sensor, rest = line[:1], line[1:2], line[2:]
        if sensor not in (b"0", b"1", b"2", b"3"):
            return b"ERR unknown command " + line
        if command == b"L" and not rest:
            return b"%.1f" % self.lux[int(sensor)]
        if command == b"G" and not rest:
            return b"%d" % self.gains[int(sensor)]
        if command == b"G" and rest in (b" 1", b" 4", b" 16", b" 64"):
            self.gains[int(sensor)] = int(rest)
            return b"OK"
        return b"ERR unknown command " + line
