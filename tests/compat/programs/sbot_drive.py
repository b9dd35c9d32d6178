"""An sbot program as a team writes it: drive, turn, lift, look at the switches."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

from sbot import (
    BRAKE,
    COAST,
    AnalogPin,
    GPIOPinMode,
    Note,
    arduino,
    comp,
    motors,
    power,
    servos,
    utils,
)

print("zone", comp.zone, "competition", comp.is_competition)

arduino.set_pin_mode(3, GPIOPinMode.INPUT_PULLUP)
arduino.set_pin_mode(4, GPIOPinMode.INPUT)
arduino.set_pin_mode(AnalogPin.A0, GPIOPinMode.INPUT)
arduino.set_pin_mode(13, GPIOPinMode.OUTPUT)

motors.set_power(0, 0.5)
motors.set_power(1, 0.5)
utils.sleep(0.2)
print("powers", motors.get_power(0), motors.get_power(1))
motors.set_power(1, -0.25)
print("turning", motors.get_power(1))

servos.set_position(0, 1)
servos.set_position(1, -1)
servos.set_position(2, 0.5)
print("servo", servos.get_position(0), servos.get_position(1), servos.get_position(2))

switch = arduino.digital_read(3)
bumper = arduino.digital_read(4)
volts = arduino.analog_read(AnalogPin.A0)
distance = arduino.measure_ultrasound_distance(8, 9)
print("sensors", switch, bumper, volts, distance)
arduino.digital_write(13, True)

battery = power.get_battery_data()
print("battery", battery.voltage, battery.current)
print("current", motors.get_motor_current(0))

utils.sound_buzzer(Note.A6, 0.5)
motors.set_power(0, BRAKE)
motors.set_power(1, COAST)
