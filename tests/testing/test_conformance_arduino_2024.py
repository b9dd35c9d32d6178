"""The conformance suites against the SR Arduino (fw 2) and SourceBots Arduino (sb2024).

Each hardware backend runs over its board simulator, through a :class:`RecordingStream`
so that the suites check refused calls send nothing; each console backend runs with a
:class:`ConsoleScript` playing the user. The pin modes are the ones the board classes
claim, digital modes on A0-A5 included: the backends must do all of them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from j5aio.backends.console.arduino import ArduinoConsoleBackend
from j5aio.backends.console.arduino_ultrasound import ArduinoUltrasoundConsoleBackend
from j5aio.backends.console.sb import SBArduino2024ConsoleBackend
from j5aio.backends.console.sr.v4 import SRArduinoConsoleBackend
from j5aio.backends.hardware.arduino_gpio import ArduinoGPIOBackend
from j5aio.backends.hardware.sb import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4 import SRArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.components.gpio_pin import GPIOPinInterface, GPIOPinMode
from j5aio.errors import NotSupportedByHardwareError
from j5aio.simulator import SBArduino2024Simulator, SRRuggeduinoSimulator
from j5aio.simulator.arduino_base import ArduinoBoardSimulator
from j5aio.testing.conformance import (
    GPIOPinInterfaceConformance,
    GPIOPinSubject,
    LEDInterfaceConformance,
    LEDSubject,
    StringCommandInterfaceConformance,
    StringCommandSubject,
    UltrasoundInterfaceConformance,
    UltrasoundSubject,
)
from j5aio.testing.conformance.gpio_pin import pin_modes
from j5aio.testing.conformance.ultrasound import SPEED_OF_SOUND
from j5aio.testing.console import ConsoleScript
from j5aio.testing.transports import RecordingStream

PAIRS = [(4, 5), (12, 13), (18, 19)]


def sr_fw2(serial: str) -> SRRuggeduinoSimulator:
    return SRRuggeduinoSimulator(serial, firmware_version=2)


class HardwareSuite:
    """Connects the backend under test to a fresh simulator of its board."""

    backend_class: type[ArduinoGPIOBackend]
    simulator: Callable[[str], ArduinoBoardSimulator]
    sim: ArduinoBoardSimulator
    stream: RecordingStream

    async def connect(self) -> tuple[ArduinoUno, dict[str, Any]]:
        self.sim = self.simulator("SIM0")
        self.stream = RecordingStream(SimulatorStream(self.sim, time_scale=0))
        board = await self.backend_class.from_stream(
            self.stream, port="sim", serial_number="SIM0", time_scale=0,
        )
        assert isinstance(board, ArduinoUno)
        await board.setup()
        self.stream.clear()
        return board, {
            "backend": board.backend, "cleanup": board.close, "traffic": lambda: self.stream.sent,
        }


class HardwarePins(HardwareSuite, GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        board, args = await self.connect()

        async def observe_output(identifier: int) -> bool:
            return self.sim.output_level(identifier)

        async def set_input(identifier: int, high: bool) -> None:
            self.sim.set_input_level(identifier, high)

        async def set_voltage(identifier: int, volts: float) -> None:
            self.sim.set_analogue(identifier, volts=volts)

        return GPIOPinSubject(
            **args, identifiers=sorted(board.pins.keys()), modes=pin_modes(board.pins),
            observe_output=observe_output, set_input=set_input, set_voltage=set_voltage,
        )


class HardwareLED(HardwareSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        board, args = await self.connect()
        await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)

        async def observe(identifier: int) -> bool:
            return self.sim.output_level(13)

        return LEDSubject(**args, identifiers=[0], observe=observe)


class HardwareUltrasound(HardwareSuite, UltrasoundInterfaceConformance):
    async def make_backend(self) -> UltrasoundSubject:
        _, args = await self.connect()

        async def place_object(trigger: int, echo: int, metres: float | None) -> None:
            self.sim.set_ultrasound_distance(trigger, echo, metres)

        return UltrasoundSubject(
            **args, identifiers=range(2, 20), pairs=PAIRS, place_object=place_object,
        )


class TestSRArduinoPins(HardwarePins):
    backend_class = SRArduinoHardwareBackend
    simulator = staticmethod(sr_fw2)


class TestSRArduinoLED(HardwareLED):
    backend_class = SRArduinoHardwareBackend
    simulator = staticmethod(sr_fw2)


class TestSRArduinoUltrasound(HardwareUltrasound):
    backend_class = SRArduinoHardwareBackend
    simulator = staticmethod(sr_fw2)


class TestSRArduinoStringCommand(HardwareSuite, StringCommandInterfaceConformance):
    backend_class = SRArduinoHardwareBackend
    simulator = staticmethod(sr_fw2)

    async def make_backend(self) -> StringCommandSubject:
        _, args = await self.connect()
        self.sim.set_analogue(14, raw=123)
        self.sim.set_input_level(3, True)
        return StringCommandSubject(
            backend=args["backend"], cleanup=args["cleanup"],
            exchanges=[("v", "SRduino:2"), ("ao", "123"), ("rd", "h"), ("rc", "l")],
        )


class TestSBArduino2024Pins(HardwarePins):
    backend_class = SBArduino2024HardwareBackend
    simulator = SBArduino2024Simulator


class TestSBArduino2024LED(HardwareLED):
    backend_class = SBArduino2024HardwareBackend
    simulator = SBArduino2024Simulator


class TestSBArduino2024Ultrasound(HardwareUltrasound):
    backend_class = SBArduino2024HardwareBackend
    simulator = SBArduino2024Simulator


@pytest.mark.parametrize(
    ("backend_class", "simulator"),
    [(SRArduinoHardwareBackend, sr_fw2), (SBArduino2024HardwareBackend, SBArduino2024Simulator)],
)
async def test_backends_take_every_mode_the_board_claims(
    backend_class: type[ArduinoGPIOBackend], simulator: Callable[[str], ArduinoBoardSimulator],
) -> None:
    board = await backend_class.from_stream(
        SimulatorStream(simulator("SIM0"), time_scale=0), port="sim", serial_number="SIM0",
        time_scale=0,
    )
    assert isinstance(board, ArduinoUno)
    backend = board.backend
    assert isinstance(backend, GPIOPinInterface)
    refused = []
    for pin, modes in pin_modes(board.pins).items():
        for mode in sorted(modes):
            try:
                await backend.set_gpio_pin_mode(pin, mode)
            except NotSupportedByHardwareError:
                refused.append((pin, mode.name))
    await board.close()
    assert refused == []


# --- the console ------------------------------------------------------------------------


class ConsoleSuite:
    backend_class: type[ArduinoUltrasoundConsoleBackend]
    script: ConsoleScript

    def backend(self) -> ArduinoUltrasoundConsoleBackend:
        self.script = ConsoleScript()
        return self.backend_class("SERIAL", self.script.console_class())


class ConsolePins(ConsoleSuite, GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        backend: ArduinoConsoleBackend = self.backend()
        board = backend.board("SERIAL", backend)
        assert isinstance(board, ArduinoUno)

        async def set_input(identifier: int, high: bool) -> None:
            self.script.answer(f"Pin {identifier} digital", str(high).lower(), replace=True)

        async def set_voltage(identifier: int, volts: float) -> None:
            self.script.answer(f"Pin {identifier} ADC", str(volts), replace=True)

        return GPIOPinSubject(
            backend=backend, identifiers=sorted(board.pins.keys()), modes=pin_modes(board.pins),
            set_input=set_input, set_voltage=set_voltage,
        )


class ConsoleLED(ConsoleSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        return LEDSubject(backend=self.backend(), identifiers=[0])


class ConsoleUltrasound(ConsoleSuite, UltrasoundInterfaceConformance):
    async def make_backend(self) -> UltrasoundSubject:
        async def place_object(trigger: int, echo: int, metres: float | None) -> None:
            pins = f"{trigger}/{echo}"
            distance = 0.0 if metres is None else metres  # 0 is the firmware's "no echo"
            micros = distance * 2 / SPEED_OF_SOUND * 1e6
            self.script.answer(f"Distance for ultrasound sensor on pins {pins}", str(distance),
                               replace=True)
            self.script.answer(f"Response time for ultrasound sensor on pins {pins}",
                               str(micros), replace=True)

        return UltrasoundSubject(
            backend=self.backend(), identifiers=range(2, 20), pairs=PAIRS,
            place_object=place_object,
        )


class TestSRArduinoConsolePins(ConsolePins):
    backend_class = SRArduinoConsoleBackend


class TestSRArduinoConsoleLED(ConsoleLED):
    backend_class = SRArduinoConsoleBackend


class TestSRArduinoConsoleUltrasound(ConsoleUltrasound):
    backend_class = SRArduinoConsoleBackend


class TestSRArduinoConsoleStringCommand(ConsoleSuite, StringCommandInterfaceConformance):
    backend_class = SRArduinoConsoleBackend

    async def make_backend(self) -> StringCommandSubject:
        backend = self.backend()
        assert isinstance(backend, SRArduinoConsoleBackend)
        exchanges = [("v", "SRduino:2"), ("ao", "123"), ("rd", "h")]
        for _ in range(2):
            for command, reply in exchanges:
                self.script.answer(f'string command "{command}"', reply)
        return StringCommandSubject(backend=backend, exchanges=exchanges)


class TestSBArduino2024ConsolePins(ConsolePins):
    backend_class = SBArduino2024ConsoleBackend


class TestSBArduino2024ConsoleLED(ConsoleLED):
    backend_class = SBArduino2024ConsoleBackend


class TestSBArduino2024ConsoleUltrasound(ConsoleUltrasound):
    backend_class = SBArduino2024ConsoleBackend
