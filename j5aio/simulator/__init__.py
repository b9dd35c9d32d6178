"""Board simulators that speak each board's wire protocol, byte for byte.

Each simulator is written from the protocol description alone (the protocol pages of
:doc:`/internals/index`), so that
it checks the host code rather than mirroring it. They are synchronous state machines with
no clock; transports wrap them.

Serial boards (:class:`~j5aio.simulator.base.SerialBoardSimulator`):

- :class:`~j5aio.simulator.sr_motor_fw3.SRMotorBoardFw3Simulator`: SR Motor Board v4, firmware 3,
  binary, 1 Mbaud.
- :class:`~j5aio.simulator.sr_motor_fw4.SRMotorBoardFw4Simulator`: SR Motor Board v4, firmware 4.4 /
  4.5, text, 115 200 baud.
- :class:`~j5aio.simulator.sr_power_fw4.SRPowerBoardFw4Simulator`: SR Power Board v4, firmware 4.4,
  CDC serial, text.
- :class:`~j5aio.simulator.sr_ruggeduino_fw1.SRRuggeduinoSimulator`: SR Ruggeduino single-character
  firmware 1 or 2.
- :class:`~j5aio.simulator.sb_arduino_2019.SBArduinoSimulator`: SourceBots Arduino, 2019 line
  protocol (2019.6.0 / 2019.8.0).
- :class:`~j5aio.simulator.sr_servo_fw4.SRServoBoardFw4Simulator` /
  :class:`~j5aio.simulator.sr_servo_fw4.SBServoBoardFw4Simulator`: SR Servo Board v4, serial
  firmware 4.3 (12 servos) and the SourceBots fork 4.4 (8 servos).
- :class:`~j5aio.simulator.sb_arduino_2024.SBArduino2024Simulator`: SourceBots Arduino, sb2024 colon
  protocol (``2.0``).

USB control-transfer boards (:class:`~j5aio.simulator.base.UsbBoardSimulator`, shaped like a pyusb
device):

- :class:`~j5aio.simulator.sr_power_fw3.SRPowerBoardFw3Simulator`: SR Power Board v4, firmware 3.
- :class:`~j5aio.simulator.sr_servo_fw2.SRServoBoardFw2Simulator`: SR Servo Board v4, firmware 2.

:data:`~j5aio.simulator.SERIAL_SIMULATORS` maps a command-line name to a factory taking a serial
number.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Final, Protocol

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.simulator.arduino_base import ARDUINO_UNO_R3 as ARDUINO_UNO_R3
    from j5aio.simulator.arduino_base import ArduinoBoardSimulator as ArduinoBoardSimulator
    from j5aio.simulator.arduino_base import UsbIdentity as UsbIdentity
    from j5aio.simulator.arduino_pins import ArduinoUnoPins as ArduinoUnoPins
    from j5aio.simulator.arduino_pins import PinMode as PinMode
    from j5aio.simulator.base import SerialBoardSimulator as SerialBoardSimulator
    from j5aio.simulator.base import SimulatorUnpluggedError as SimulatorUnpluggedError
    from j5aio.simulator.base import UsbBoardSimulator as UsbBoardSimulator
    from j5aio.simulator.sb_arduino_2019 import SBArduinoFirmware as SBArduinoFirmware
    from j5aio.simulator.sb_arduino_2019 import SBArduinoSimulator as SBArduinoSimulator
    from j5aio.simulator.sb_arduino_2024 import SBArduino2024Simulator as SBArduino2024Simulator
    from j5aio.simulator.sr_motor import MotorDrive as MotorDrive
    from j5aio.simulator.sr_motor_fw3 import MotorMode as MotorMode
    from j5aio.simulator.sr_motor_fw3 import MotorOutput as MotorOutput
    from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator as SRMotorBoardFw3Simulator
    from j5aio.simulator.sr_motor_fw4 import MotorChannel as MotorChannel
    from j5aio.simulator.sr_motor_fw4 import SRMotorBoardFw4Simulator as SRMotorBoardFw4Simulator
    from j5aio.simulator.sr_power_fw3 import PiezoNote as PiezoNote
    from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator as SRPowerBoardFw3Simulator
    from j5aio.simulator.sr_power_fw4 import BuzzerNote as BuzzerNote
    from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator as SRPowerBoardFw4Simulator
    from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator as SRRuggeduinoSimulator
    from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator as SRServoBoardFw2Simulator
    from j5aio.simulator.sr_servo_fw4 import SBServoBoardFw4Simulator as SBServoBoardFw4Simulator
    from j5aio.simulator.sr_servo_fw4 import SRServoBoardFw4Simulator as SRServoBoardFw4Simulator


class SerialSimulatorFactory(Protocol):
    """Makes a serial board simulator with the given USB serial number."""

    def __call__(self, serial_number: str) -> SerialBoardSimulator:
        """Make the simulator."""
        ...


def _unwrap(factory: object) -> object:
    """A factory as given, or the class a :class:`~j5aio.board_kinds.SimulatorClass` names.

    (One that makes its class with more arguments stays as it is.)
    """
    from j5aio.board_kinds import SimulatorClass

    if isinstance(factory, SimulatorClass) and factory.serial_keyword is None and not (
        factory.keywords
    ):
        return factory.resolve()
    return factory


class _SerialSimulators(Mapping[str, SerialSimulatorFactory]):
    """The serial simulators of the board kind registry, by name; read-only."""

    def _factories(self) -> dict[str, SerialSimulatorFactory]:
        from j5aio.board_kinds import simulator_entries

        return {
            name: _unwrap(entry.factory)  # type: ignore[misc]
            for name, (kind, entry) in simulator_entries().items()
            if entry.is_serial
        }

    def __getitem__(self, name: str) -> SerialSimulatorFactory:
        return self._factories()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._factories())

    def __len__(self) -> int:
        return len(self._factories())

    def __repr__(self) -> str:
        return f"SERIAL_SIMULATORS({', '.join(self)})"


#: Serial board simulators by command-line name (``python -m j5aio simulate <name>``),
#: from the registry of board kinds (:func:`j5aio.board_kinds.simulator_entries`), so
#: plugins' simulators are here too.
SERIAL_SIMULATORS: Final[Mapping[str, SerialSimulatorFactory]] = _SerialSimulators()

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.simulator.arduino_base": [
                "ARDUINO_UNO_R3",
                "ArduinoBoardSimulator",
                "UsbIdentity",
            ],
            "j5aio.simulator.arduino_pins": ["ArduinoUnoPins", "PinMode"],
            "j5aio.simulator.base": [
                "SerialBoardSimulator",
                "SimulatorUnpluggedError",
                "UsbBoardSimulator",
            ],
            "j5aio.simulator.sb_arduino_2019": ["SBArduinoFirmware", "SBArduinoSimulator"],
            "j5aio.simulator.sb_arduino_2024": ["SBArduino2024Simulator"],
            "j5aio.simulator.sr_motor": ["MotorDrive"],
            "j5aio.simulator.sr_motor_fw3": [
                "MotorMode",
                "MotorOutput",
                "SRMotorBoardFw3Simulator",
            ],
            "j5aio.simulator.sr_motor_fw4": ["MotorChannel", "SRMotorBoardFw4Simulator"],
            "j5aio.simulator.sr_power_fw3": ["PiezoNote", "SRPowerBoardFw3Simulator"],
            "j5aio.simulator.sr_power_fw4": ["BuzzerNote", "SRPowerBoardFw4Simulator"],
            "j5aio.simulator.sr_ruggeduino_fw1": ["SRRuggeduinoSimulator"],
            "j5aio.simulator.sr_servo_fw2": ["SRServoBoardFw2Simulator"],
            "j5aio.simulator.sr_servo_fw4": [
                "SBServoBoardFw4Simulator",
                "SRServoBoardFw4Simulator",
            ],
        },
        own=("SERIAL_SIMULATORS", "SerialSimulatorFactory"),
    )
