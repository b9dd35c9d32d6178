"""Conformance suites: the tests any backend claiming an interface can run against itself.

There is one suite per interface. Subclass it in a test module, in a class whose name
starts with ``Test``, and implement ``make_backend`` to return your backend wrapped in the
suite's subject, with hooks that let the suite observe the board and feed it inputs::

    from j5aio.testing.conformance import LEDInterfaceConformance, LEDSubject

    class TestMyBoardLEDs(LEDInterfaceConformance):
        async def make_backend(self) -> LEDSubject:
            self.simulator = MyBoardSimulator()
            board = await MyBoardBackend.from_stream(
                SimulatorStream(self.simulator, time_scale=0), port="sim", serial_number="S1",
            )
            await board.setup()

            async def observe(identifier: int) -> bool:
                return self.simulator.leds[identifier]

            return LEDSubject(backend=board.backend, identifiers=range(4), observe=observe)

pytest then runs every test of the suite against ``MyBoardBackend``. The suites are
async tests: run them with pytest-asyncio (they carry its ``asyncio`` marker, so strict
mode works; ``asyncio_mode = "auto"`` is simplest for your own async tests).

Tests that need a hook the subject does not give are skipped, saying which hook would
enable them. Some checks need a hook but live inside other tests (comparing what the board
shows with what the backend reports needs ``observe``; checking that a refused call sends
nothing needs ``traffic``): without the hook they are left out, so every suite also has
``test_every_hook_is_given``, which skips naming each hook left out, and the pytest plugin
lists all of these skips at the end of the run. A green run with such skips has *not*
checked everything: a scaling or rounding bug, for one, is caught only through
``observe``.

To write the suite of an interface of your own, start from
:mod:`j5aio.testing.conformance.base`.

Capabilities are declared on the subject, not assumed: a motor board without BRAKE or
COAST gives ``MotorSubject(special_states=())`` and must refuse them with
:class:`~j5aio.errors.NotSupportedByHardwareError`; ``power_step`` sets how exactly
powers are checked.
"""

from ._base import InterfaceConformance, Subject
from .battery_sensor import BatterySensorInterfaceConformance, BatterySensorSubject
from .button import ButtonInterfaceConformance, ButtonSubject
from .distance_sensor import DistanceSensorInterfaceConformance, DistanceSensorSubject
from .flag import FlagInterfaceConformance, FlagSubject
from .flashing_led import FlashingLEDInterfaceConformance, FlashingLEDSubject
from .gpio_pin import GPIOPinInterfaceConformance, GPIOPinSubject, pin_modes
from .led import LEDInterfaceConformance, LEDSubject
from .monitored_motor import MonitoredMotorInterfaceConformance, MonitoredMotorSubject
from .motor import MotorInterfaceConformance, MotorSubject
from .piezo import PiezoInterfaceConformance, PiezoSubject
from .power_output import PowerOutputInterfaceConformance, PowerOutputSubject
from .pulse_servo import PulseServoInterfaceConformance, PulseServoSubject
from .rgb_led import RGBLEDInterfaceConformance, RGBLEDSubject
from .servo import ServoInterfaceConformance, ServoSubject
from .string_command import StringCommandInterfaceConformance, StringCommandSubject
from .supply_sensor import SupplySensorInterfaceConformance, SupplySensorSubject
from .ultrasound import UltrasoundInterfaceConformance, UltrasoundSubject

__all__ = [
    "BatterySensorInterfaceConformance",
    "BatterySensorSubject",
    "ButtonInterfaceConformance",
    "ButtonSubject",
    "DistanceSensorInterfaceConformance",
    "DistanceSensorSubject",
    "FlagInterfaceConformance",
    "FlagSubject",
    "FlashingLEDInterfaceConformance",
    "FlashingLEDSubject",
    "GPIOPinInterfaceConformance",
    "GPIOPinSubject",
    "InterfaceConformance",
    "LEDInterfaceConformance",
    "LEDSubject",
    "MonitoredMotorInterfaceConformance",
    "MonitoredMotorSubject",
    "MotorInterfaceConformance",
    "MotorSubject",
    "PiezoInterfaceConformance",
    "PiezoSubject",
    "PowerOutputInterfaceConformance",
    "PowerOutputSubject",
    "PulseServoInterfaceConformance",
    "PulseServoSubject",
    "RGBLEDInterfaceConformance",
    "RGBLEDSubject",
    "ServoInterfaceConformance",
    "ServoSubject",
    "StringCommandInterfaceConformance",
    "StringCommandSubject",
    "Subject",
    "SupplySensorInterfaceConformance",
    "SupplySensorSubject",
    "UltrasoundInterfaceConformance",
    "UltrasoundSubject",
    "pin_modes",
]
