"""Conformance suites: the tests any backend claiming an interface can run against itself.

There is one suite per interface. Subclass it in a test module, in a class whose name
starts with ``Test``, and implement ``make_backend`` to return your backend wrapped in the
suite's subject, with hooks that let the suite observe the board and feed it inputs::

    from j5aio.testing.conformance import LEDInterfaceConformance, LEDSubject

    class TestMyBoardLEDs(LEDInterfaceConformance):
        async def make_backend(self) -> LEDSubject:
            backend = await MyBoardBackend.connect(...)
            return LEDSubject(backend=backend, identifiers=range(4))

pytest then runs every test of the suite against ``MyBoardBackend``. Tests that need a
hook the subject does not give are skipped, saying which hook would enable them.
"""

from ._base import InterfaceConformance, Subject
from .battery_sensor import BatterySensorInterfaceConformance, BatterySensorSubject
from .button import ButtonInterfaceConformance, ButtonSubject
from .flashing_led import FlashingLEDInterfaceConformance, FlashingLEDSubject
from .gpio_pin import GPIOPinInterfaceConformance, GPIOPinSubject, pin_modes
from .led import LEDInterfaceConformance, LEDSubject
from .monitored_motor import MonitoredMotorInterfaceConformance, MonitoredMotorSubject
from .motor import MotorInterfaceConformance, MotorSubject
from .piezo import PiezoInterfaceConformance, PiezoSubject
from .power_output import PowerOutputInterfaceConformance, PowerOutputSubject
from .rgb_led import RGBLEDInterfaceConformance, RGBLEDSubject
from .servo import ServoInterfaceConformance, ServoSubject
from .string_command import StringCommandInterfaceConformance, StringCommandSubject
from .ultrasound import UltrasoundInterfaceConformance, UltrasoundSubject

__all__ = [
    "BatterySensorInterfaceConformance",
    "BatterySensorSubject",
    "ButtonInterfaceConformance",
    "ButtonSubject",
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
    "RGBLEDInterfaceConformance",
    "RGBLEDSubject",
    "ServoInterfaceConformance",
    "ServoSubject",
    "StringCommandInterfaceConformance",
    "StringCommandSubject",
    "Subject",
    "UltrasoundInterfaceConformance",
    "UltrasoundSubject",
    "pin_modes",
]
