"""Components: the smallest logical parts of a board, and the interfaces that drive them.

Each component (an :class:`LED`, a :class:`Motor`, a :class:`GPIOPin` ...) checks what
the user asks for and then awaits its interface, which a backend implements.
"""

from j5aio.components.battery_sensor import BatterySensor, BatterySensorInterface
from j5aio.components.button import Button, ButtonInterface
from j5aio.components.component import Component, DerivedComponent, Interface
from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor
from j5aio.components.gpio_pin import (
    FirmwareMode,
    GPIOPin,
    GPIOPinInterface,
    GPIOPinMode,
    PinMode,
)
from j5aio.components.led import LED, LEDInterface
from j5aio.components.marker_camera import MarkerCamera, MarkerCameraInterface
from j5aio.components.motor import (
    Motor,
    MotorInterface,
    MotorSpecialState,
    MotorState,
    check_motor_state,
)
from j5aio.components.piezo import Duration, Note, Piezo, PiezoInterface, Pitch
from j5aio.components.power_output import PowerOutput, PowerOutputGroup, PowerOutputInterface
from j5aio.components.rgb_led import RGBLED, RGBChannel, RGBColour, RGBLEDInterface
from j5aio.components.servo import Servo, ServoInterface, ServoPosition
from j5aio.components.string_command import (
    StringCommandComponent,
    StringCommandComponentInterface,
)

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
    "GPIOPin",
    "GPIOPinInterface",
    "GPIOPinMode",
    "Interface",
    "LEDInterface",
    "MarkerCamera",
    "MarkerCameraInterface",
    "Motor",
    "MotorInterface",
    "MotorSpecialState",
    "MotorState",
    "Note",
    "Piezo",
    "PiezoInterface",
    "PinMode",
    "Pitch",
    "PowerOutput",
    "PowerOutputGroup",
    "PowerOutputInterface",
    "RGBChannel",
    "RGBColour",
    "RGBLEDInterface",
    "Servo",
    "ServoInterface",
    "ServoPosition",
    "StringCommandComponent",
    "StringCommandComponentInterface",
    "UltrasoundInterface",
    "UltrasoundSensor",
    "check_motor_state",
]
