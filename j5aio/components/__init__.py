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
    from j5aio.components.battery_sensor import BatterySensor as BatterySensor
    from j5aio.components.battery_sensor import BatterySensorInterface as BatterySensorInterface
    from j5aio.components.button import Button as Button
    from j5aio.components.button import ButtonInterface as ButtonInterface
    from j5aio.components.component import Component as Component
    from j5aio.components.component import DerivedComponent as DerivedComponent
    from j5aio.components.component import Interface as Interface
    from j5aio.components.derived.ultrasound import UltrasoundInterface as UltrasoundInterface
    from j5aio.components.derived.ultrasound import UltrasoundSensor as UltrasoundSensor
    from j5aio.components.distance_sensor import DistanceSensor as DistanceSensor
    from j5aio.components.distance_sensor import DistanceSensorInterface as DistanceSensorInterface
    from j5aio.components.distance_sensor import Rangefinder as Rangefinder
    from j5aio.components.fan import Fan as Fan
    from j5aio.components.fan import FanInterface as FanInterface
    from j5aio.components.flag import Flag as Flag
    from j5aio.components.flag import FlagInterface as FlagInterface
    from j5aio.components.flashing_led import FlashingLED as FlashingLED
    from j5aio.components.flashing_led import FlashingLEDInterface as FlashingLEDInterface
    from j5aio.components.flashing_led import LEDMode as LEDMode
    from j5aio.components.gpio_pin import FirmwareMode as FirmwareMode
    from j5aio.components.gpio_pin import GPIOPin as GPIOPin
    from j5aio.components.gpio_pin import GPIOPinInterface as GPIOPinInterface
    from j5aio.components.gpio_pin import GPIOPinMode as GPIOPinMode
    from j5aio.components.gpio_pin import PinMode as PinMode
    from j5aio.components.identified import IdentifiedComponent as IdentifiedComponent
    from j5aio.components.identified import checked_backend as checked_backend
    from j5aio.components.led import LED as LED
    from j5aio.components.led import LEDInterface as LEDInterface
    from j5aio.components.marker_camera import MarkerCamera as MarkerCamera
    from j5aio.components.marker_camera import MarkerCameraInterface as MarkerCameraInterface
    from j5aio.components.monitored_motor import MonitoredMotor as MonitoredMotor
    from j5aio.components.monitored_motor import MonitoredMotorInterface as MonitoredMotorInterface
    from j5aio.components.motor import Motor as Motor
    from j5aio.components.motor import MotorInterface as MotorInterface
    from j5aio.components.motor import MotorSpecialState as MotorSpecialState
    from j5aio.components.motor import MotorState as MotorState
    from j5aio.components.motor import check_motor_state as check_motor_state
    from j5aio.components.piezo import Duration as Duration
    from j5aio.components.piezo import Note as Note
    from j5aio.components.piezo import Piezo as Piezo
    from j5aio.components.piezo import PiezoInterface as PiezoInterface
    from j5aio.components.piezo import Pitch as Pitch
    from j5aio.components.power_output import PowerOutput as PowerOutput
    from j5aio.components.power_output import PowerOutputGroup as PowerOutputGroup
    from j5aio.components.power_output import PowerOutputInterface as PowerOutputInterface
    from j5aio.components.protected_power_output import ProtectedPowerOutput as ProtectedPowerOutput
    from j5aio.components.protected_power_output import (
        ProtectedPowerOutputInterface as ProtectedPowerOutputInterface,
    )
    from j5aio.components.pulse_servo import PulseLimits as PulseLimits
    from j5aio.components.pulse_servo import PulseServo as PulseServo
    from j5aio.components.pulse_servo import PulseServoInterface as PulseServoInterface
    from j5aio.components.rgb_led import RGBLED as RGBLED
    from j5aio.components.rgb_led import RGBChannel as RGBChannel
    from j5aio.components.rgb_led import RGBColour as RGBColour
    from j5aio.components.rgb_led import RGBLEDInterface as RGBLEDInterface
    from j5aio.components.servo import Servo as Servo
    from j5aio.components.servo import ServoInterface as ServoInterface
    from j5aio.components.servo import ServoPosition as ServoPosition
    from j5aio.components.string_command import StringCommandComponent as StringCommandComponent
    from j5aio.components.string_command import (
        StringCommandComponentInterface as StringCommandComponentInterface,
    )
    from j5aio.components.supply_sensor import SupplySensor as SupplySensor
    from j5aio.components.supply_sensor import SupplySensorInterface as SupplySensorInterface
    from j5aio.components.temperature_sensor import TemperatureSensor as TemperatureSensor
    from j5aio.components.temperature_sensor import (
        TemperatureSensorInterface as TemperatureSensorInterface,
    )
    from j5aio.components.voltage_sensor import VoltageSensor as VoltageSensor
    from j5aio.components.voltage_sensor import VoltageSensorInterface as VoltageSensorInterface
    from j5aio.errors import NotSupportedByComponentError as NotSupportedByComponentError

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
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
