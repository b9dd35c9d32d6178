"""Components: the smallest logical parts of a board, and the interfaces that drive them.

Each component (an :class:`LED`, a :class:`Motor`, a :class:`GPIOPin` ...) checks what
the user asks for and then awaits its interface, which a backend implements.
"""

from j5aio.components.battery_sensor import BatterySensor, BatterySensorInterface
from j5aio.components.button import Button, ButtonInterface
from j5aio.components.component import Component, DerivedComponent, Interface
from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor
from j5aio.components.flag import Flag, FlagInterface
from j5aio.components.flashing_led import FlashingLED, FlashingLEDInterface
from j5aio.components.gpio_pin import (
    FirmwareMode,
    GPIOPin,
    GPIOPinInterface,
    GPIOPinMode,
    PinMode,
)
from j5aio.components.led import LED, LEDInterface
from j5aio.components.motor import (
    Motor,
    MotorInterface,
    MotorSpecialState,
    MotorState,
    check_motor_state,
)
from j5aio.components.piezo import Duration, Note, Piezo, PiezoInterface, Pitch
from j5aio.components.power_output import PowerOutput, PowerOutputGroup, PowerOutputInterface
from j5aio.components.pulse_servo import PulseLimits, PulseServo, PulseServoInterface
from j5aio.components.rgb_led import RGBLED, RGBChannel, RGBColour, RGBLEDInterface
from j5aio.components.servo import Servo, ServoInterface, ServoPosition
from j5aio.components.string_command import (
    StringCommandComponent,
    StringCommandComponentInterface,
)
from j5aio.components.supply_sensor import SupplySensor, SupplySensorInterface
from j5aio.errors import NotSupportedByComponentError  # where j5 had it

__all__ = [
    "LED",
    "RGBLED",
    "BatterySensor",
    "BatterySensorInterface",
    "Button",
    "ButtonInterface",
    "Component",
    "DerivedComponent",
    "Duration",
    "FirmwareMode",
    "Flag",
    "FlagInterface",
    "FlashingLED",
    "FlashingLEDInterface",
    "GPIOPin",
    "GPIOPinInterface",
    "GPIOPinMode",
    "Interface",
    "LEDInterface",
    "Motor",
    "MotorInterface",
    "MotorSpecialState",
    "MotorState",
    "NotSupportedByComponentError",
    "Note",
    "Piezo",
    "PiezoInterface",
    "PinMode",
    "Pitch",
    "PowerOutput",
    "PowerOutputGroup",
    "PowerOutputInterface",
    "PulseLimits",
    "PulseServo",
    "PulseServoInterface",
    "RGBChannel",
    "RGBColour",
    "RGBLEDInterface",
    "Servo",
    "ServoInterface",
    "ServoPosition",
    "StringCommandComponent",
    "StringCommandComponentInterface",
    "SupplySensor",
    "SupplySensorInterface",
    "UltrasoundInterface",
    "UltrasoundSensor",
    "check_motor_state",
]
