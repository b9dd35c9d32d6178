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
from j5aio.boards.sr.v4 import ServoBoardFw4
from j5aio.components.rgb_led import RGBChannel
from j5aio.components.servo import ServoPosition
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.sr_servo_fw4 import SBServoBoardFw4Simulator, SRServoBoardFw4Simulator
from j5aio.testing.conformance import (
    FlagInterfaceConformance,
    FlagSubject,
    FlashingLEDInterfaceConformance,
    FlashingLEDSubject,
    PulseServoInterfaceConformance,
    PulseServoSubject,
    RGBLEDInterfaceConformance,
    RGBLEDSubject,
    SupplySensorInterfaceConformance,
    SupplySensorSubject,
)
from j5aio.testing.console import ConsoleScript
from j5aio.testing.transports import RecordingStream


async def servo_subject(
    backend_class: type[SRV4ServoBoardFw4HardwareBackend] | type[SBServoBoardHardwareBackend],
    sim: SRServoBoardFw4Simulator,
) -> PulseServoSubject:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(stream, port="sim", serial_number=sim.serial_number)
    await board.setup()
    stream.clear()
    assert isinstance(board.backend, backend_class)

    lower, upper = board.backend.firmware.default_limits  # the kit library's defaults
    middle, half = (lower + upper) / 2, (upper - lower) / 2

    async def observe(identifier: int) -> ServoPosition:
        pulse = sim.pulse_widths[identifier]
        return None if pulse is None else (pulse - middle) / half

    async def observe_pulse(identifier: int) -> int | None:
        return sim.pulse_widths[identifier]

    return PulseServoSubject(
        backend=board.backend, identifiers=range(sim.SERVO_COUNT), observe=observe,
        observe_pulse=observe_pulse, traffic=lambda: stream.sent, cleanup=board.close,
    )


async def servo_board(
    sim: SRServoBoardFw4Simulator,
) -> tuple[SRV4ServoBoardFw4HardwareBackend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await SRV4ServoBoardFw4HardwareBackend.from_stream(
        stream, port="sim", serial_number=sim.serial_number,
    )
    assert isinstance(board.backend, SRV4ServoBoardFw4HardwareBackend)
    return board.backend, stream


class TestSRServoBoardFw4(PulseServoInterfaceConformance):
    async def make_backend(self) -> PulseServoSubject:
        return await servo_subject(SRV4ServoBoardFw4HardwareBackend, SRServoBoardFw4Simulator("S"))


class TestSBServoBoardFw4(PulseServoInterfaceConformance):
    async def make_backend(self) -> PulseServoSubject:
        return await servo_subject(SBServoBoardHardwareBackend, SBServoBoardFw4Simulator("S"))


class TestSRServoBoardFw4Console(PulseServoInterfaceConformance):
    async def make_backend(self) -> PulseServoSubject:
        backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", ConsoleScript().console_class())
        return PulseServoSubject(backend=backend, identifiers=range(12))


class TestSBServoBoardFw4Console(PulseServoInterfaceConformance):
    async def make_backend(self) -> PulseServoSubject:
        backend = SBServoBoardConsoleBackend("SERIAL", ConsoleScript().console_class())
        return PulseServoSubject(backend=backend, identifiers=range(8))


class TestServoBoardFw4Supply(SupplySensorInterfaceConformance):
    async def make_backend(self) -> SupplySensorSubject:
        sim = SRServoBoardFw4Simulator("S")
        backend, stream = await servo_board(sim)

        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            sim.set_supply(voltage=volts, current=amps)

        return SupplySensorSubject(
            backend=backend, identifiers=[0], set_reading=set_reading, traffic=lambda: stream.sent,
        )


class TestServoBoardFw4Flags(FlagInterfaceConformance):
    async def make_backend(self) -> FlagSubject:
        sim = SRServoBoardFw4Simulator("S")
        backend, stream = await servo_board(sim)

        async def set_flag(identifier: int, raised: bool) -> None:
            if identifier == ServoBoardFw4.POWER_GOOD:
                sim.power_good = raised
            else:
                sim.watchdog_failed = raised

        return FlagSubject(
            backend=backend, identifiers=[0, 1], set_flag=set_flag, traffic=lambda: stream.sent,
        )


class TestServoBoardFw4ConsoleSupplyAndFlags(FlagInterfaceConformance):
    async def make_backend(self) -> FlagSubject:
        self.script = ConsoleScript()
        backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", self.script.console_class())
        names = ("Power good", "Watchdog failed")

        async def set_flag(identifier: int, raised: bool) -> None:
            self.script.answer(names[identifier], str(raised).lower(), replace=True)

        return FlagSubject(backend=backend, identifiers=[0, 1], set_flag=set_flag)


class TestServoBoardFw4ConsoleSupply(SupplySensorInterfaceConformance):
    async def make_backend(self) -> SupplySensorSubject:
        self.script = ConsoleScript()
        backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", self.script.console_class())

        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            self.script.answer("Servo supply voltage", str(volts), replace=True)
            self.script.answer("Servo supply current", str(amps), replace=True)

        return SupplySensorSubject(backend=backend, identifiers=[0], set_reading=set_reading)


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


class TestKCHStartLED(FlashingLEDInterfaceConformance):
    async def make_backend(self) -> FlashingLEDSubject:
        simulator = KCHSimulator()
        board = simulator.board()
        assert isinstance(board.backend, KCHHardwareBackend)

        async def observe(identifier: int) -> bool:
            return simulator.start_led

        return FlashingLEDSubject(
            backend=board.backend, identifiers=[0], observe=observe, cleanup=board.close,
        )


class TestKCHConsoleUserLEDs(OnOffRGBLEDs):
    async def make_backend(self) -> RGBLEDSubject:
        backend = KCHConsoleBackend("SERIAL", ConsoleScript().console_class())
        return RGBLEDSubject(backend=backend, identifiers=range(3))


class TestKCHConsoleStartLED(FlashingLEDInterfaceConformance):
    async def make_backend(self) -> FlashingLEDSubject:
        backend = KCHConsoleBackend("SERIAL", ConsoleScript().console_class())
        return FlashingLEDSubject(backend=backend, identifiers=[0])
