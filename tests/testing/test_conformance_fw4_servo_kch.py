"""The conformance suites, run against the servo board fw 4.3 / SB 4.4 and KCH backends.

Each hardware backend runs over its simulator: the servo boards through a
:class:`SimulatorStream` wrapped in a :class:`RecordingStream` (so the suites check that
refused calls send nothing), the KCH over the gpiozero mock pins of a
:class:`KCHSimulator` (its simulated form). The console backends run with a script
playing the user.
"""

from __future__ import annotations

from typing import ClassVar

from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SBServoBoardConsoleBackend,
    SRV4ServoBoardFw4ConsoleBackend,
)
from j5aio.backends.hardware.sr.kch import KCHHardwareBackend
from j5aio.backends.hardware.sr.v4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.components.rgb_led import RGBChannel
from j5aio.components.servo import ServoPosition
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.sr_servo_fw4 import SBServoBoardFw4Simulator, SRServoBoardFw4Simulator
from j5aio.testing.conformance import (
    LEDInterfaceConformance,
    LEDSubject,
    RGBLEDInterfaceConformance,
    RGBLEDSubject,
    ServoInterfaceConformance,
    ServoSubject,
)
from j5aio.testing.console import ConsoleScript
from j5aio.testing.transports import RecordingStream


async def servo_subject(
    backend_class: type[SRV4ServoBoardFw4HardwareBackend] | type[SBServoBoardHardwareBackend],
    sim: SRServoBoardFw4Simulator,
) -> ServoSubject:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(stream, port="sim", serial_number=sim.serial_number)
    await board.setup()
    stream.clear()
    assert isinstance(board.backend, backend_class)

    async def observe(identifier: int) -> ServoPosition:
        pulse = sim.pulse_widths[identifier]
        return None if pulse is None else (pulse - 1500) / 500  # default limits 1000-2000 µs

    return ServoSubject(
        backend=board.backend, identifiers=range(sim.SERVO_COUNT), observe=observe,
        traffic=lambda: stream.sent, cleanup=board.close,
    )


class TestSRServoBoardFw4(ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        return await servo_subject(SRV4ServoBoardFw4HardwareBackend, SRServoBoardFw4Simulator("S"))


class TestSBServoBoardFw4(ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        return await servo_subject(SBServoBoardHardwareBackend, SBServoBoardFw4Simulator("S"))


class TestSRServoBoardFw4Console(ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", ConsoleScript().console_class())
        return ServoSubject(backend=backend, identifiers=range(12))


class TestSBServoBoardFw4Console(ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        backend = SBServoBoardConsoleBackend("SERIAL", ConsoleScript().console_class())
        return ServoSubject(backend=backend, identifiers=range(8))


# --- KCH ------------------------------------------------------------------------------


class OnOffRGBLEDs(RGBLEDInterfaceConformance):
    """The KCH's LED parts are on or off."""

    duty_cycle_tolerance: ClassVar[float] = 0.5
    duty_cycles: ClassVar[tuple[float, ...]] = (1.0, 0.0)


class TestKCHUserLEDs(OnOffRGBLEDs):
    async def make_backend(self) -> RGBLEDSubject:
        simulator = KCHSimulator()
        board = simulator.board()
        assert isinstance(board.backend, KCHHardwareBackend)

        async def observe(identifier: int, channel: RGBChannel) -> float:
            return 1.0 if simulator.colours[identifier][channel] else 0.0

        return RGBLEDSubject(
            backend=board.backend, identifiers=range(3), observe=observe, cleanup=board.close,
        )


class TestKCHStartLED(LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        simulator = KCHSimulator()
        board = simulator.board()
        assert isinstance(board.backend, KCHHardwareBackend)

        async def observe(identifier: int) -> bool:
            return simulator.start_led

        return LEDSubject(
            backend=board.backend, identifiers=[0], observe=observe, cleanup=board.close,
        )


class TestKCHConsoleUserLEDs(OnOffRGBLEDs):
    async def make_backend(self) -> RGBLEDSubject:
        backend = KCHConsoleBackend("SERIAL", ConsoleScript().console_class())
        return RGBLEDSubject(backend=backend, identifiers=range(3))


class TestKCHConsoleStartLED(LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        backend = KCHConsoleBackend("SERIAL", ConsoleScript().console_class())
        return LEDSubject(backend=backend, identifiers=[0])
