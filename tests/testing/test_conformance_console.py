"""The conformance suites, run against every backend of the console environment.

Readings are fed through a :class:`ConsoleScript` standing in for the user at the prompt.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from datetime import timedelta

from j5aio.backends.console.arduino import ArduinoConsoleBackend
from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
)
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.boards.sr.v4.power_board import PowerOutputPosition
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.testing.conformance import (
    BatterySensorInterfaceConformance,
    BatterySensorSubject,
    ButtonInterfaceConformance,
    ButtonSubject,
    GPIOPinInterfaceConformance,
    GPIOPinSubject,
    LEDInterfaceConformance,
    LEDSubject,
    MotorInterfaceConformance,
    MotorSubject,
    PiezoInterfaceConformance,
    PiezoSubject,
    PowerOutputInterfaceConformance,
    PowerOutputSubject,
    ServoInterfaceConformance,
    ServoSubject,
    StringCommandInterfaceConformance,
    StringCommandSubject,
    UltrasoundInterfaceConformance,
    UltrasoundSubject,
)
from j5aio.testing.conformance.gpio_pin import pin_modes
from j5aio.testing.conformance.ultrasound import SPEED_OF_SOUND
from j5aio.testing.console import ConsoleScript


class ConsoleSuite:
    """Makes each console backend with a fresh script playing the user."""

    script: ConsoleScript

    def power_board(self) -> SRV4PowerBoardConsoleBackend:
        self.script = ConsoleScript()
        return SRV4PowerBoardConsoleBackend("SERIAL", self.script.console_class())

    def arduino(self) -> SBArduinoConsoleBackend:
        self.script = ConsoleScript()
        return SBArduinoConsoleBackend("SERIAL", self.script.console_class())

    def pins(self, backend: ArduinoConsoleBackend) -> GPIOPinSubject:
        """The pins of the backend's board, with the modes the board definition claims."""
        board = backend.board("SERIAL", backend)
        assert isinstance(board, ArduinoUno)
        return GPIOPinSubject(
            backend=backend, identifiers=sorted(board.pins.keys()), modes=pin_modes(board.pins),
            set_input=self.answer_input, set_voltage=self.answer_voltage,
        )

    async def answer_input(self, identifier: int, high: bool) -> None:
        self.script.answer(f"Pin {identifier} digital", str(high).lower(), replace=True)

    async def answer_voltage(self, identifier: int, volts: float) -> None:
        self.script.answer(f"Pin {identifier} ADC", str(volts), replace=True)


# --- SR v4 power board --------------------------------------------------------------


class TestPowerBoardConsoleLEDs(ConsoleSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        backend = self.power_board()
        return LEDSubject(backend=backend, identifiers=[0, 1], traffic=self.script.traffic)


class TestPowerBoardConsoleButton(ConsoleSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.script.answer("Start button state", str(pressed).lower(), replace=True)

        async def press(identifier: int) -> None:
            self.script.answer("Hit return to press start button", "")

        return ButtonSubject(
            backend=self.power_board(), identifiers=[0], set_pressed=set_pressed, press=press,
        )


class TestPowerBoardConsoleBattery(ConsoleSuite, BatterySensorInterfaceConformance):
    async def make_backend(self) -> BatterySensorSubject:
        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            self.script.answer("Battery voltage", str(volts), replace=True)
            self.script.answer("Battery current", str(amps), replace=True)

        return BatterySensorSubject(
            backend=self.power_board(), identifiers=[0], set_reading=set_reading,
        )


class TestPowerBoardConsolePiezo(ConsoleSuite, PiezoInterfaceConformance):
    async def make_backend(self) -> PiezoSubject:
        async def observe(identifier: int) -> Sequence[tuple[timedelta, float]]:
            notes = []
            for line in self.script.printed:
                found = re.search(r"Buzzing at ([\d.]+)Hz for (\d+)ms", line)
                if found:
                    duration = timedelta(milliseconds=int(found[2]))
                    notes.append((duration, float(found[1])))
            return notes

        return PiezoSubject(backend=self.power_board(), identifiers=[0], observe=observe)


class TestPowerBoardConsoleOutputs(ConsoleSuite, PowerOutputInterfaceConformance):
    async def make_backend(self) -> PowerOutputSubject:
        async def set_current(identifier: int, amps: float) -> None:
            self.script.answer(f"Current for power output {identifier}", str(amps), replace=True)

        backend = self.power_board()
        return PowerOutputSubject(
            backend=backend,
            identifiers=range(len(PowerOutputPosition)),
            set_current=set_current,
            traffic=self.script.traffic,
        )


# --- SR v4 motor and servo boards ---------------------------------------------------


class TestMotorBoardConsole(ConsoleSuite, MotorInterfaceConformance):
    async def make_backend(self) -> MotorSubject:
        script = self.script = ConsoleScript()
        backend = SRV4MotorBoardConsoleBackend("SERIAL", script.console_class())

        async def observe(identifier: int) -> MotorState:
            # What the console last printed for the motor: "...: Setting motor 0 to 0.5."
            for line in reversed(script.printed):
                found = re.search(rf": Setting motor {identifier} to (\S+)\.$", line)
                if found:
                    shown = found[1]
                    if shown in MotorSpecialState.__members__:
                        return MotorSpecialState[shown]
                    return float(shown)
            return MotorSpecialState.BRAKE  # nothing printed yet: as the board starts

        return MotorSubject(
            backend=backend, identifiers=[0, 1], observe=observe, traffic=script.traffic,
        )


class TestServoBoardConsole(ConsoleSuite, ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        self.script = ConsoleScript()
        backend = SRV4ServoBoardConsoleBackend("SERIAL", self.script.console_class())
        return ServoSubject(backend=backend, identifiers=range(12))


# --- SR Ruggeduino ------------------------------------------------------------------


class RuggeduinoSuite(ConsoleSuite):
    def ruggeduino(self) -> SRV4RuggeduinoConsoleBackend:
        self.script = ConsoleScript()
        return SRV4RuggeduinoConsoleBackend("SERIAL", self.script.console_class())


class TestRuggeduinoConsolePins(RuggeduinoSuite, GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        return self.pins(self.ruggeduino())


class TestRuggeduinoConsoleLED(RuggeduinoSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        return LEDSubject(backend=self.ruggeduino(), identifiers=[0])


class TestRuggeduinoConsoleStringCommand(RuggeduinoSuite, StringCommandInterfaceConformance):
    async def make_backend(self) -> StringCommandSubject:
        backend = self.ruggeduino()
        exchanges = [("v", "SRduino:1"), ("a", "0123"), ("l", "1")]
        for _ in range(2):
            for command, reply in exchanges:
                self.script.answer(f'string command "{command}"', reply)
        return StringCommandSubject(backend=backend, exchanges=exchanges)


# --- SourceBots Arduino ---------------------------------------------------------------


class TestSBArduinoConsolePins(ConsoleSuite, GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        return self.pins(self.arduino())


class TestSBArduinoConsoleLED(ConsoleSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        return LEDSubject(backend=self.arduino(), identifiers=[0])


class TestSBArduinoConsoleServos(ConsoleSuite, ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        return ServoSubject(backend=self.arduino(), identifiers=range(16))


class TestSBArduinoConsoleUltrasound(ConsoleSuite, UltrasoundInterfaceConformance):
    async def make_backend(self) -> UltrasoundSubject:
        async def place_object(trigger: int, echo: int, metres: float | None) -> None:
            pins = f"{trigger}/{echo}"
            # The console cannot say "no echo"; 0 is what the firmware reports for one.
            distance = 0.0 if metres is None else metres
            micros = distance * 2 / SPEED_OF_SOUND * 1e6
            self.script.answer(f"Distance for ultrasound sensor on pins {pins}", str(distance),
                               replace=True)
            self.script.answer(f"Response time for ultrasound sensor on pins {pins}",
                               str(micros), replace=True)

        return UltrasoundSubject(
            backend=self.arduino(), identifiers=range(2, 20), pairs=[(4, 5), (18, 19)],
            place_object=place_object,
        )

