"""The conformance suites on the Bee Board, with the capabilities it declares."""

from __future__ import annotations

import re

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
    simulator_class: type[BeeSimulator] = BeeSimulator
    simulator: BeeSimulator
    stream: RecordingStream

    async def connect(self) -> BeeBackend:
        self.simulator = self.simulator_class()
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
            return self.simulator.motor_steps[identifier] / self.simulator.MOTOR_STEPS

        return MotorSubject(
            backend=backend,
            identifiers=[0, 1],
            observe=observe,
            special_states=(),  # no BRAKE, no COAST: the suite checks they are refused
            power_step=1 / self.backend_class.MOTOR_STEPS,
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
    """Makes a console backend whose prompts a :class:`ConsoleScript` answers.

    The console is its board: what it printed is what it did (``observe``), and the
    lines it printed are what it sent (``traffic``).
    """

    script: ConsoleScript

    def console_backend(self) -> BeeConsoleBackend:
        self.script = ConsoleScript()
        return BeeConsoleBackend("SERIAL", self.script.console_class())

    def last_printed(self, pattern: str) -> re.Match[str]:
        """The last line printed that matches ``pattern``."""
        for line in reversed(self.script.printed):
            found = re.search(pattern, line)
            if found:
                return found
        raise AssertionError(f"the console printed no line like {pattern!r}")

    def printed(self) -> bytes:
        return "\n".join(self.script.printed).encode()


class TestBeeConsoleMotors(BeeConsoleSuite, MotorInterfaceConformance):
    async def make_backend(self) -> MotorSubject:
        async def observe(identifier: int) -> MotorState:
            return float(self.last_printed(rf"Motor {identifier} power set to (\S+)")[1])

        return MotorSubject(
            backend=self.console_backend(), identifiers=[0, 1], special_states=(),
            power_step=1 / BeeBackend.MOTOR_STEPS, observe=observe, traffic=self.printed,
        )


class TestBeeConsoleLED(BeeConsoleSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        async def observe(identifier: int) -> bool:
            return self.last_printed(r"LED (on|off)")[1] == "on"

        return LEDSubject(
            backend=self.console_backend(), identifiers=[0], observe=observe,
            traffic=self.printed,
        )


class TestBeeConsoleButton(BeeConsoleSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        backend = self.console_backend()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.script.answer("Button held", str(pressed).lower(), replace=True)

        async def press(identifier: int) -> None:
            self.script.answer("Hit return to press the button", "")

        return ButtonSubject(
            backend=backend, identifiers=[0], set_pressed=set_pressed, press=press,
            traffic=self.printed,
        )


class TruncatingBeeBackend(BeeBackend):
    """A deliberately broken backend: ``int()`` where ``round()`` belongs."""

    async def set_motor_state(self, identifier: int, power: MotorState) -> None:
        assert isinstance(power, float)
        await self.exchange(b"M%d %d\n" % (identifier, int(power * self.MOTOR_STEPS)), read_line())
        self._powers[identifier] = power  # and it reports what it was asked, not what it did


def suite_at(steps: int, backend: type[BeeBackend]) -> TestBeeMotors:
    """The motor suite on ``backend`` and a board, both of ``steps`` steps each way."""

    class Simulator(BeeSimulator):
        MOTOR_STEPS = steps

    class Backend(backend):  # type: ignore[valid-type, misc]
        MOTOR_STEPS = steps

    class Suite(TestBeeMotors):  # made here: pytest does not collect it
        backend_class = Backend
        simulator_class = Simulator

    return Suite()


RESOLUTIONS = [100, 125, 127, 255]


@pytest.mark.parametrize("steps", RESOLUTIONS)
async def test_the_motor_suite_catches_a_truncating_backend(steps: int) -> None:
    suite = suite_at(steps, TruncatingBeeBackend)
    subject = await suite.make_backend()
    try:
        if steps == 100:  # every exact power is a whole number of steps: the bug hides
            await suite.test_every_identifier(subject)
        with pytest.raises(AssertionError, match="rounded rather than truncated"):
            await suite.test_the_board_shows_each_power(subject)
    finally:
        await subject.aclose()


@pytest.mark.parametrize("steps", RESOLUTIONS)
async def test_the_rounding_backend_passes_at_every_resolution(steps: int) -> None:
    suite = suite_at(steps, BeeBackend)
    subject = await suite.make_backend()
    try:
        await suite.test_the_board_shows_each_power(subject)
        await suite.test_every_identifier(subject)
    finally:
        await subject.aclose()
