"""A simulated Blinken board, written from the protocol in the package's docstring."""

from __future__ import annotations

from typing import ClassVar

from j5aio.simulator.base import SerialBoardSimulator
from j5aio.simulator.line_assembler import LineAssembler

__all__ = ["BlinkenSimulator"]


class BlinkenSimulator(SerialBoardSimulator):
    """Four LEDs that a host turns on and off by text commands."""

    baudrate: ClassVar[int] = 115_200
    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = True

    def __init__(self, serial_number: str) -> None:
        super().__init__(
            serial_number, usb_vid=0x1209, usb_pid=0x0001, manufacturer="Blinken", product="Blinken"
        )
        self.leds = [False] * 4
        self._lines = LineAssembler()

    def _boot(self) -> bytes:
        return b""

    def _process(self, data: bytes) -> bytes:
        return b"".join(self._answer(line) + b"\n" for line in self._lines.feed(data))

    def _answer(self, line: bytes) -> bytes:
        if line == b"V":
            return b"BLINKEN:1"
        if len(line) >= 3 and line[:1] == b"L" and line[1:2] in b"0123":
            led = int(line[1:2])
            rest = line[2:]
            if rest == b"?":
                return b"1" if self.leds[led] else b"0"
            if rest in (b" 0", b" 1"):
                self.leds[led] = rest == b" 1"
                return b"OK"
        return b"ERR unknown command"
