"""The conformance suites on the Bee Board, with the capabilities it declares."""

from __future__ import annotations

import pytest
from beekit.backend import BeeBackend
from beekit.console import BeeConsoleBackend
from beekit.simulator import BeeSimulator

from j5aio.backends.hardware.transports import SimulatorStream, read_line
from j5aio.components.motor import MotorState
from j5aio.testing import RecordingStream
from j5aio.testing.conformance import (
    ButtonInterfaceConformance,
    ButtonSubject,
    LEDInterfaceConformance,
    LEDSubject,
    MotorInterfaceConformance,
    MotorSubject,
)
from j5aio.testing.console import ConsoleScript


class BeeSuite:
    """Connects a backend to a fresh simulator, recording what it sends."""

    backend_class: type[BeeBackend] = BeeBackend
    simulator: BeeSimulator
    stream: RecordingStream

    async def connect(self) -> BeeBackend:
        self.simulator = BeeSimulator()
        self.stream = RecordingStream(SimulatorStream(self.simulator, time_scale=0))
        board = await self.backend_class.from_stream(
            self.stream, port="sim", serial_number="B1", time_scale=0,
        )
        await board.setup()
        self.stream.clear()
        assert isinstance(board.backend, BeeBackend)
        return board.backend


class TestBeeMotors(BeeSuite, MotorInterfaceConformance):
    async def make_backend(self) -> MotorSubject:
        backend = await self.connect()

        async def observe(identifier: int) -> MotorState:
            return self.simulator.motor_steps[identifier] / 100

        return MotorSubject(
            backend=backend,
            identifiers=[0, 1],
            observe=observe,
            special_states=(),  # no BRAKE, no COAST: the suite checks they are refused
            power_step=1 / 100,
            traffic=lambda: self.stream.sent,
        )


class TestBeeLED(BeeSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        backend = await self.connect()

        async def observe(identifier: int) -> bool:
            return self.simulator.led

        return LEDSubject(
            backend=backend, identifiers=[0], observe=observe, traffic=lambda: self.stream.sent,
        )


class TestBeeButton(BeeSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        backend = await self.connect()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.simulator.button_held = pressed

        # No press hook: the suite holds the button down with set_pressed until the
        # backend's polling has seen it, then lets go (a latched press, no sleeping).
        return ButtonSubject(
            backend=backend, identifiers=[0], set_pressed=set_pressed,
            traffic=lambda: self.stream.sent,
        )


class BeeConsoleSuite:
    """Makes a console backend whose prompts a :class:`ConsoleScript` answers."""

    script: ConsoleScript

    def console_backend(self) -> BeeConsoleBackend:
        self.script = ConsoleScript()
        return BeeConsoleBackend("SERIAL", self.script.console_class())


class TestBeeConsoleMotors(BeeConsoleSuite, MotorInterfaceConformance):
    async def make_backend(self) -> MotorSubject:
        return MotorSubject(
            backend=self.console_backend(), identifiers=[0, 1], special_states=(),
            power_step=1 / 100,
        )


class TestBeeConsoleLED(BeeConsoleSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        return LEDSubject(backend=self.console_backend(), identifiers=[0])


class TestBeeConsoleButton(BeeConsoleSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        backend = self.console_backend()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.script.answer("Button held", str(pressed).lower(), replace=True)

        async def press(identifier: int) -> None:
            self.script.answer("Hit return to press the button", "")

        return ButtonSubject(
            backend=backend, identifiers=[0], set_pressed=set_pressed, press=press,
        )


class TruncatingBeeBackend(BeeBackend):
    """A deliberately broken backend: ``int()`` where ``round()`` belongs."""

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        assert isinstance(power, float)
        await self.exchange(b"M%d %d\n" % (identifier, int(power * 100)), read_line())
        self._powers[identifier] = power  # and it reports what it was asked, not what it did


class TruncatingBeeMotors(TestBeeMotors):  # not named Test...: pytest does not collect it
    backend_class = TruncatingBeeBackend


async def test_the_motor_suite_catches_a_truncating_backend() -> None:
    suite = TruncatingBeeMotors()
    subject = await suite.make_backend()
    try:
        await suite.test_every_identifier(subject)  # exact powers: the bug does not show
        with pytest.raises(AssertionError, match=r"set to 0\.667 but the board shows 0\.66"):
            await suite.test_the_board_shows_each_power(subject)
    finally:
        await subject.aclose()
