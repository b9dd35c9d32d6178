"""Components: the smallest logical parts of a board, and the interfaces that drive them.

Each component (an :class:`~j5aio.components.led.LED`, a :class:`~j5aio.components.motor.Motor`, a
:class:`~j5aio.components.gpio_pin.GPIOPin` ...) checks what the user asks for and then awaits its
interface, which a backend implements.

A part that none of these fits gets a new kind of component, made on the same public
bases: :class:`~j5aio.components.component.Interface` for its interface,
:class:`~j5aio.components.identified.IdentifiedComponent` for a component its board
numbers, :class:`~j5aio.components.component.DerivedComponent` for one built from other
components. :doc:`/new-component` works one through, from its interface to its
conformance suite.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from j5aio.components.battery_sensor import BatterySensor, BatterySensorInterface
    from j5aio.components.button import Button, ButtonInterface
    from j5aio.components.component import Component, DerivedComponent, Interface
    from j5aio.components.derived.ultrasound import UltrasoundInterface, UltrasoundSensor
    from j5aio.components.distance_sensor import (
        DistanceSensor,
        DistanceSensorInterface,
        Rangefinder,
    )
    from j5aio.components.fan import Fan, FanInterface
    from j5aio.components.flag import Flag, FlagInterface
    from j5aio.components.flashing_led import FlashingLED, FlashingLEDInterface, LEDMode
    from j5aio.components.gpio_pin import (
        FirmwareMode,
        GPIOPin,
        GPIOPinInterface,
        GPIOPinMode,
        PinMode,
    )
    from j5aio.components.identified import IdentifiedComponent, checked_backend
    from j5aio.components.led import LED, LEDInterface
    from j5aio.components.marker_camera import MarkerCamera, MarkerCameraInterface
    from j5aio.components.monitored_motor import MonitoredMotor, MonitoredMotorInterface
    from j5aio.components.motor import (
        Motor,
        MotorInterface,
        MotorSpecialState,
        MotorState,
        check_motor_state,
    )
    from j5aio.components.piezo import Duration, Note, Piezo, PiezoInterface, Pitch
    from j5aio.components.power_output import PowerOutput, PowerOutputGroup, PowerOutputInterface
    from j5aio.components.protected_power_output import (
        ProtectedPowerOutput,
        ProtectedPowerOutputInterface,
    )
    from j5aio.components.pulse_servo import PulseLimits, PulseServo, PulseServoInterface
    from j5aio.components.rgb_led import RGBLED, RGBChannel, RGBColour, RGBLEDInterface
    from j5aio.components.servo import Servo, ServoInterface, ServoPosition
    from j5aio.components.string_command import (
        StringCommandComponent,
        StringCommandComponentInterface,
    )
    from j5aio.components.supply_sensor import SupplySensor, SupplySensorInterface
    from j5aio.components.temperature_sensor import TemperatureSensor, TemperatureSensorInterface
    from j5aio.components.voltage_sensor import VoltageSensor, VoltageSensorInterface
    from j5aio.errors import NotSupportedByComponentError

__all__ = [
    "LED",
    "RGBLED",
    "BatterySensor",
    "BatterySensorInterface",
    "Button",
    "ButtonInterface",
    "Component",
    "DerivedComponent",
    "DistanceSensor",
    "DistanceSensorInterface",
    "Duration",
    "Fan",
    "FanInterface",
    "FirmwareMode",
    "Flag",
    "FlagInterface",
    "FlashingLED",
    "FlashingLEDInterface",
    "GPIOPin",
    "GPIOPinInterface",
    "GPIOPinMode",
    "IdentifiedComponent",
    "Interface",
    "LEDInterface",
    "LEDMode",
    "MarkerCamera",
    "MarkerCameraInterface",
    "MonitoredMotor",
    "MonitoredMotorInterface",
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
    "ProtectedPowerOutput",
    "ProtectedPowerOutputInterface",
    "PulseLimits",
    "PulseServo",
    "PulseServoInterface",
    "RGBChannel",
    "RGBColour",
    "RGBLEDInterface",
    "Rangefinder",
    "Servo",
    "ServoInterface",
    "ServoPosition",
    "StringCommandComponent",
    "StringCommandComponentInterface",
    "SupplySensor",
    "SupplySensorInterface",
    "TemperatureSensor",
    "TemperatureSensorInterface",
    "UltrasoundInterface",
    "UltrasoundSensor",
    "VoltageSensor",
    "VoltageSensorInterface",
    "check_motor_state",
    "checked_backend",
]

if not TYPE_CHECKING:  # the names are imported above for type checkers
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.components.battery_sensor": ["BatterySensor", "BatterySensorInterface"],
            "j5aio.components.button": ["Button", "ButtonInterface"],
            "j5aio.components.component": ["Component", "DerivedComponent", "Interface"],
            "j5aio.components.derived.ultrasound": ["UltrasoundInterface", "UltrasoundSensor"],
            "j5aio.components.distance_sensor": [
                "DistanceSensor",
                "DistanceSensorInterface",
                "Rangefinder",
            ],
            "j5aio.components.fan": ["Fan", "FanInterface"],
            "j5aio.components.flag": ["Flag", "FlagInterface"],
            "j5aio.components.flashing_led": ["FlashingLED", "FlashingLEDInterface", "LEDMode"],
            "j5aio.components.gpio_pin": [
                "FirmwareMode",
                "GPIOPin",
                "GPIOPinInterface",
                "GPIOPinMode",
                "PinMode",
            ],
            "j5aio.components.identified": ["IdentifiedComponent", "checked_backend"],
            "j5aio.components.led": ["LED", "LEDInterface"],
            "j5aio.components.marker_camera": ["MarkerCamera", "MarkerCameraInterface"],
            "j5aio.components.monitored_motor": ["MonitoredMotor", "MonitoredMotorInterface"],
            "j5aio.components.motor": [
                "Motor",
                "MotorInterface",
                "MotorSpecialState",
                "MotorState",
                "check_motor_state",
            ],
            "j5aio.components.piezo": ["Duration", "Note", "Piezo", "PiezoInterface", "Pitch"],
            "j5aio.components.power_output": [
                "PowerOutput",
                "PowerOutputGroup",
                "PowerOutputInterface",
            ],
            "j5aio.components.protected_power_output": [
                "ProtectedPowerOutput",
                "ProtectedPowerOutputInterface",
            ],
            "j5aio.components.pulse_servo": ["PulseLimits", "PulseServo", "PulseServoInterface"],
            "j5aio.components.rgb_led": ["RGBChannel", "RGBColour", "RGBLED", "RGBLEDInterface"],
            "j5aio.components.servo": ["Servo", "ServoInterface", "ServoPosition"],
            "j5aio.components.string_command": [
                "StringCommandComponent",
                "StringCommandComponentInterface",
            ],
            "j5aio.components.supply_sensor": ["SupplySensor", "SupplySensorInterface"],
            "j5aio.components.temperature_sensor": [
                "TemperatureSensor",
                "TemperatureSensorInterface",
            ],
            "j5aio.components.voltage_sensor": ["VoltageSensor", "VoltageSensorInterface"],
            "j5aio.errors": ["NotSupportedByComponentError"],
        },
    )
