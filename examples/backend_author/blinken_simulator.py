"""A simulator of the Blinkenboard, speaking its protocol byte for byte.

It has the shape of :class:`~j5aio.backends.hardware.transports.SerialSimulatorLike`, so
a :class:`~j5aio.backends.hardware.transports.SimulatorStream` can connect a backend to
it in memory, and ``serve_on_pty`` can serve it to any program as a serial port.
"""

from __future__ import annotations


class BlinkenSimulator:
    """A simulated Blinkenboard.

    :param version: the firmware version it reports.
    """

    baudrate = 115_200
    boot_delay = 0.0

    def __init__(self, version: str = "1.2") -> None:
        self.version = version
        self.leds = [False] * 4
        self.button_held = False
        self.connected = True
        self.commands: list[bytes] = []
        self._partial = b""

    def open(self) -> bytes:
        """The host opened the port: forget any half-received line."""
        self._partial = b""
        return b""

    def receive(self, data: bytes) -> bytes:
        """Handle bytes from the host; return the board's replies."""
        self._partial += data
        replies = b""
        while b"\n" in self._partial:
            line, self._partial = self._partial.split(b"\n", 1)
            self.commands.append(line)
            replies += self._answer(line) + b"\n"
        return replies

    def _answer(self, line: bytes) -> bytes:
        if line == b"?":
            return b"BLINKEN:" + self.version.encode()
        if line == b"B":
            return b"B1" if self.button_held else b"B0"
        if len(line) == 3 and line[:1] == b"L" and line[1:2] in b"0123" and line[2:] in b"01":
            self.leds[int(line[1:2])] = line[2:] == b"1"
            return b"OK"
        return b"ERR unknown command " + line
