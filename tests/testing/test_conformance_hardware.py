"""The conformance suites, run against every hardware and every simulated-environment backend.

Each suite runs twice, with the board from two sources:

``direct``
    the hardware backend connected straight to a fresh board simulator: serial backends
    through a :class:`SimulatorStream` wrapped in a :class:`RecordingStream` (so the
    suites check that refused calls send nothing), USB backends with the simulator as
    their pyusb device;
``sim-env``
    the simulated environment's backend, its board found by the environment's own
    discovery in the plugin's ``j5aio_sim_kit``.

Either way the suites observe and feed the boards through the simulators. The Ruggeduino
string command runs directly only, against a team's own firmware: the kit's Ruggeduino
runs SR's firmware, which has no string commands.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from datetime import timedelta
from typing import Any, Generic, TypeVar

import pytest

from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.backends.hardware.sb import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.kch import KCHHardwareBackend
from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardHardwareBackend,
    SRV4PowerBoardHardwareBackend,
    SRV4RuggeduinoHardwareBackend,
    SRV4ServoBoardHardwareBackend,
)
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import (
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.backends.hardware.transports.memory import SerialSimulatorLike, SimulatorStream
from j5aio.backends.hardware.usb_backend import USBHardwareBackend
from j5aio.boards.arduino.uno import ArduinoUno
from j5aio.boards.board import Board
from j5aio.boards.camera import CameraBoard
from j5aio.boards.sb import SBArduino2024Board, SBServoBoard
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.boards.sr.kch import KCHBoard
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, ServoBoardFw4, SRArduinoBoard
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.boards.sr.v4.servo_board import ServoBoard
from j5aio.components.gpio_pin import GPIOPinInterface, GPIOPinMode
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.components.servo import ServoPosition
from j5aio.errors import NotSupportedByHardwareError
from j5aio.simulator import (
    MotorMode,
    SBArduinoSimulator,
    SRMotorBoardFw3Simulator,
    SRPowerBoardFw3Simulator,
    SRRuggeduinoSimulator,
    SRServoBoardFw2Simulator,
)
from j5aio.simulator.arduino_base import ArduinoBoardSimulator
from j5aio.simulator.base import UsbBoardSimulator
from j5aio.simulator.discovery import KitDiscovery
from j5aio.simulator.environment import SIMULATED_BACKENDS
from j5aio.testing import OpenSimulatedKit
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
from j5aio.testing.transports import RecordingStream

pytestmark = pytest.mark.j5aio_kit(
    power_boards=1, motor_boards=1, servo_boards=1, sb_arduinos=1, ruggeduinos=1,
)

SimT = TypeVar("SimT")


def test_every_simulated_backend_is_a_hardware_backend_tested_here() -> None:
    tested = {
        SRV4PowerBoardHardwareBackend, SRV4MotorBoardHardwareBackend,
        SRV4ServoBoardHardwareBackend, SRV4RuggeduinoHardwareBackend, SBArduinoHardwareBackend,
    }
    # Today's kits' backends are tested in test_conformance_fw4_*.py and
    # test_conformance_arduino_2024.py; the KCH's simulated backend is its own class.
    today = {
        SRV4PowerBoardFw4HardwareBackend, SRV4MotorBoardFw4HardwareBackend,
        SRV4ServoBoardFw4HardwareBackend, SBServoBoardHardwareBackend,
        SRArduinoHardwareBackend, SBArduino2024HardwareBackend, KCHHardwareBackend,
    }
    # The camera's simulated backend renders its arena (tested in tests/vision).
    today.add(FrameCameraBackend)
    own = [backend for backend in SIMULATED_BACKENDS if backend.__module__.startswith("j5aio.")]
    # (Each one's hardware backend: its first base after the kit's discovery mixin.)
    hardware = {
        next(base for base in backend.__mro__[1:] if base is not KitDiscovery) for backend in own
    }
    assert hardware == tested | today  # plugins test their own


async def over_simulator(
    backend_class: type[SerialHardwareBackend], simulator: SerialSimulatorLike,
) -> tuple[Board, RecordingStream]:
    """Connect a serial backend to ``simulator`` and set its board up, recording traffic."""
    stream = RecordingStream(SimulatorStream(simulator, time_scale=0))
    # The simulator boots at once; a small time scale keeps the boot limit generous
    # on a loaded machine.
    board = await backend_class.from_stream(
        stream, port="sim", serial_number="SIM0", time_scale=0.01,
    )
    await board.setup()
    stream.clear()
    return board, stream


async def from_usb(backend_class: type[USBHardwareBackend], simulator: UsbBoardSimulator) -> Board:
    """Connect a USB backend to ``simulator`` (as its pyusb device) and set its board up."""
    board = await backend_class.from_usb_device(simulator)
    await board.setup()
    return board


async def kit_owns_it() -> None:
    """Nothing to release: the j5aio_sim_kit fixture closes the kit's boards."""


@dataclass
class Connected(Generic[SimT]):
    """A set-up board under test, the simulator behind it, and how to release it."""

    board: Board
    sim: SimT
    cleanup: Callable[[], Awaitable[None]]
    traffic: Callable[[], bytes] | None = None

    @property
    def backend(self) -> Any:
        return self.board.backend

    def subject_args(self) -> dict[str, Any]:
        """The arguments every subject takes from here."""
        return {"backend": self.backend, "traffic": self.traffic, "cleanup": self.cleanup}


class FromEitherSource:
    """Gives each test its board from both sources: ``direct`` and ``sim-env``."""

    kit: OpenSimulatedKit | None

    @pytest.fixture(autouse=True, params=["direct", "sim-env"])
    def _source(self, request: pytest.FixtureRequest) -> None:
        self.kit = request.getfixturevalue("j5aio_sim_kit") if request.param == "sim-env" else None

    def from_kit(self, board_type: type[Board], sims: Sequence[SimT]) -> Connected[SimT]:
        assert self.kit is not None
        board = self.kit.group(board_type)[0]
        assert type(board.backend) in SIMULATED_BACKENDS
        return Connected(board, sims[0], kit_owns_it)

    async def usb(
        self,
        backend_class: type[USBHardwareBackend],
        sim: SimT,
        sims: Callable[[], Sequence[SimT]],
    ) -> Connected[SimT]:
        if self.kit is not None:
            return self.from_kit(backend_class.board, sims())
        board = await from_usb(backend_class, sim)  # type: ignore[arg-type]
        return Connected(board, sim, board.close)

    async def serial(
        self,
        backend_class: type[SerialHardwareBackend],
        sim: SimT,
        sims: Callable[[], Sequence[SimT]],
    ) -> Connected[SimT]:
        if self.kit is not None:
            return self.from_kit(backend_class.board, sims())
        board, stream = await over_simulator(backend_class, sim)  # type: ignore[arg-type]
        return Connected(board, sim, board.close, lambda: stream.sent)

    def kit_sims(self) -> OpenSimulatedKit:
        assert self.kit is not None
        return self.kit


# --- SR v4 power board (USB, firmware 3) ----------------------------------------------


class PowerBoardSuite(FromEitherSource):
    async def power_board(self) -> Connected[SRPowerBoardFw3Simulator]:
        return await self.usb(
            SRV4PowerBoardHardwareBackend, SRPowerBoardFw3Simulator("SIMPB0"),
            lambda: self.kit_sims().kit.power_boards,
        )


class TestPowerBoardOutputs(PowerBoardSuite, PowerOutputInterfaceConformance):
    async def make_backend(self) -> PowerOutputSubject:
        it = await self.power_board()

        async def observe(identifier: int) -> bool:
            return it.sim.outputs[identifier]

        async def set_current(identifier: int, amps: float) -> None:
            it.sim.set_output_current(identifier, amps)

        return PowerOutputSubject(
            **it.subject_args(), identifiers=range(6), observe=observe, set_current=set_current,
        )


class TestPowerBoardLEDs(PowerBoardSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        it = await self.power_board()

        async def observe(identifier: int) -> bool:
            return it.sim.run_led if identifier == 0 else it.sim.error_led

        return LEDSubject(**it.subject_args(), identifiers=[0, 1], observe=observe)


class TestPowerBoardButton(PowerBoardSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        it = await self.power_board()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            (it.sim.press_start if pressed else it.sim.release_start)()

        async def press(identifier: int) -> None:
            it.sim.press_start()  # latched: held until the suite calls release

        async def release(identifier: int) -> None:
            it.sim.release_start()

        return ButtonSubject(
            **it.subject_args(), identifiers=[0], set_pressed=set_pressed, press=press,
            release=release,
        )


class TestPowerBoardBattery(PowerBoardSuite, BatterySensorInterfaceConformance):
    async def make_backend(self) -> BatterySensorSubject:
        it = await self.power_board()

        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            it.sim.battery_voltage = volts
            it.sim.battery_current = amps

        return BatterySensorSubject(**it.subject_args(), identifiers=[0], set_reading=set_reading)


class TestPowerBoardPiezo(PowerBoardSuite, PiezoInterfaceConformance):
    async def make_backend(self) -> PiezoSubject:
        it = await self.power_board()

        async def observe(identifier: int) -> Sequence[tuple[timedelta, float]]:
            return [
                (timedelta(milliseconds=note.duration_ms), float(note.frequency))
                for note in it.sim.note_queue
            ]

        return PiezoSubject(**it.subject_args(), identifiers=[0], observe=observe)


# --- SR v4 servo board (USB, firmware 2) and motor board (serial, firmware 3) --------------


class TestServoBoard(FromEitherSource, ServoInterfaceConformance):
    async def make_backend(self) -> ServoSubject:
        it = await self.usb(
            SRV4ServoBoardHardwareBackend, SRServoBoardFw2Simulator("SIMSB0"),
            lambda: self.kit_sims().kit.servo_boards,
        )

        async def observe(identifier: int) -> ServoPosition:
            return it.sim.positions[identifier] / 100

        return ServoSubject(**it.subject_args(), identifiers=range(12), observe=observe)


class TestMotorBoard(FromEitherSource, MotorInterfaceConformance):
    async def make_backend(self) -> MotorSubject:
        it = await self.serial(
            SRV4MotorBoardHardwareBackend, SRMotorBoardFw3Simulator("SIMMB0"),
            lambda: self.kit_sims().kit.motor_boards,
        )

        async def observe(identifier: int) -> MotorState:
            output = it.sim.motors[identifier]
            if output.mode is MotorMode.BRAKE:
                return MotorSpecialState.BRAKE
            if output.mode is MotorMode.COAST:
                return MotorSpecialState.COAST
            # The signed duty the board drives, which is the power set (j5's bytes saturated
            # from 0.8).
            return output.power

        return MotorSubject(
            **it.subject_args(), identifiers=[0, 1], observe=observe, power_step=1 / 125,
        )


# --- Arduinos (serial) ----------------------------------------------------------------


class ArduinoSuite(FromEitherSource):
    backend_class: type[SerialHardwareBackend]
    #: The pins the firmware reads analogue values on.
    analogue_pins: range

    async def arduino(self) -> Connected[ArduinoBoardSimulator]:
        sim: ArduinoBoardSimulator
        if self.backend_class is SRV4RuggeduinoHardwareBackend:
            sim = SRRuggeduinoSimulator("SIMRD0")
            return await self.serial(
                self.backend_class, sim, lambda: self.kit_sims().kit.ruggeduinos,
            )
        sim = SBArduinoSimulator("SIMSBA0")
        return await self.serial(self.backend_class, sim, lambda: self.kit_sims().kit.sb_arduinos)


class ArduinoPins(ArduinoSuite, GPIOPinInterfaceConformance):
    async def make_backend(self) -> GPIOPinSubject:
        it = await self.arduino()
        assert isinstance(it.board, ArduinoUno)

        async def observe_output(identifier: int) -> bool:
            return it.sim.output_level(identifier)

        async def set_input(identifier: int, high: bool) -> None:
            it.sim.set_input_level(identifier, high)

        async def set_voltage(identifier: int, volts: float) -> None:
            it.sim.set_analogue(identifier, volts=volts)

        # The modes the backends support: fewer than the board claims on pins 14 to 19
        # (see test_backends_take_every_mode_the_board_claims).
        modes = {
            pin: claimed if pin < it.board.FIRST_ANALOGUE_PIN
            else claimed & {GPIOPinMode.ANALOGUE_INPUT} if pin in self.analogue_pins
            else frozenset()
            for pin, claimed in pin_modes(it.board.pins).items()
        }
        return GPIOPinSubject(
            **it.subject_args(), identifiers=sorted(modes), modes=modes,
            observe_output=observe_output, set_input=set_input, set_voltage=set_voltage,
        )


class ArduinoLED(ArduinoSuite, LEDInterfaceConformance):
    async def make_backend(self) -> LEDSubject:
        it = await self.arduino()
        # The LED is on pin 13, which must be an output for the LED to work.
        await it.backend.set_gpio_pin_mode(13, GPIOPinMode.DIGITAL_OUTPUT)

        async def observe(identifier: int) -> bool:
            return it.sim.output_level(13)

        return LEDSubject(**it.subject_args(), identifiers=[0], observe=observe)


class TestRuggeduinoPins(ArduinoPins):
    backend_class = SRV4RuggeduinoHardwareBackend
    analogue_pins = range(14, 20)


class TestRuggeduinoLED(ArduinoLED):
    backend_class = SRV4RuggeduinoHardwareBackend


class TestSBArduinoPins(ArduinoPins):
    backend_class = SBArduinoHardwareBackend
    analogue_pins = range(14, 18)


class TestSBArduinoLED(ArduinoLED):
    backend_class = SBArduinoHardwareBackend


class TestSBArduinoServos(ArduinoSuite, ServoInterfaceConformance):
    backend_class = SBArduinoHardwareBackend

    async def make_backend(self) -> ServoSubject:
        it = await self.arduino()
        return ServoSubject(**it.subject_args(), identifiers=range(16))


class TestSBArduinoUltrasound(ArduinoSuite, UltrasoundInterfaceConformance):
    backend_class = SBArduinoHardwareBackend

    async def make_backend(self) -> UltrasoundSubject:
        it = await self.arduino()

        async def place_object(trigger: int, echo: int, metres: float | None) -> None:
            it.sim.set_ultrasound_distance(trigger, echo, metres)

        return UltrasoundSubject(
            **it.subject_args(), identifiers=range(2, 20), pairs=[(4, 5), (12, 13)],
            place_object=place_object,
        )


class TeamFirmware:
    """A team's own firmware on a Ruggeduino: answers ``v``, and upper-cases commands."""

    baudrate = 115_200
    boot_delay = 0.0
    connected = True

    def open(self) -> bytes:
        return b""

    def receive(self, data: bytes) -> bytes:
        if data == b"v":
            return b"TeamDuino:1\n"
        return data.upper() + b"\n"


class TestRuggeduinoStringCommand(StringCommandInterfaceConformance):
    async def make_backend(self) -> StringCommandSubject:
        board, _ = await over_simulator(SRV4RuggeduinoHardwareBackend, TeamFirmware())
        assert isinstance(board.backend, SRV4RuggeduinoHardwareBackend)
        return StringCommandSubject(
            backend=board.backend, cleanup=board.close,
            exchanges=[("ping", "PING"), ("speed 3", "SPEED 3"), ("go", "GO")],
        )


@pytest.mark.parametrize(
    ("backend_class", "simulator"),
    [(SRV4RuggeduinoHardwareBackend, SRRuggeduinoSimulator),
     (SBArduinoHardwareBackend, SBArduinoSimulator)],
)
async def test_backends_take_every_mode_the_board_claims(
    backend_class: type[SerialHardwareBackend], simulator: type[ArduinoBoardSimulator],
) -> None:
    board, _ = await over_simulator(backend_class, simulator("SIM0"))
    assert isinstance(board, ArduinoUno)
    backend = board.backend
    assert isinstance(backend, GPIOPinInterface)
    refused = []
    for pin, modes in pin_modes(board.pins).items():
        for mode in sorted(modes):
            try:
                await backend.set_gpio_pin_mode(pin, mode)
                if mode is GPIOPinMode.ANALOGUE_INPUT:
                    await backend.read_gpio_pin_analogue_value(pin)
            except NotSupportedByHardwareError:
                refused.append((pin, mode.name))
    await board.close()
    # The SourceBots 2019 firmware reports A0-A3 only (its ``A`` command): reading A4 or A5
    # is a limit of that firmware, refused before any traffic.
    firmware_limits = (
        [(18, "ANALOGUE_INPUT"), (19, "ANALOGUE_INPUT")]
        if backend_class is SBArduinoHardwareBackend
        else []
    )
    assert refused == firmware_limits


def test_the_kit_has_one_board_of_each_kind() -> None:
    assert {
        PowerBoard, MotorBoard, ServoBoard, SBArduinoBoard, Ruggeduino,
        PowerBoardFw4, MotorBoardFw4, ServoBoardFw4, SBServoBoard, SRArduinoBoard,
        SBArduino2024Board, KCHBoard, CameraBoard,
    } == {
        backend.board for backend in SIMULATED_BACKENDS if backend.__module__.startswith("j5aio.")
    }
