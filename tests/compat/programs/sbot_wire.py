"""A short sbot program whose wire commands are compared: sbot itself against j5aio."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is sbot itself, or j5aio.compat.sbot under the test harness)

from sbot import BRAKE, COAST, AnalogPin, GPIOPinMode, Note, arduino, motors, power, servos, utils

utils.load_boards()  # (SKIP_WAIT_START: the program finds the boards itself)

# The power board.
power.is_output_on(0)
power.set_output(1, False)
power.is_output_on(1)
power.get_output_current(0)
power.get_battery_data()
utils.sound_buzzer(Note.C7, 0.25)

# The motor board.
motors.get_power(0)
motors.set_power(0, 0.5)
motors.set_power(1, -0.754)
motors.get_power(1)
motors.get_motor_current(0)
motors.set_power(0, BRAKE)
motors.set_power(1, COAST)

# The servo board.
servos.get_position(0)
servos.set_position(0, 0.5)
servos.set_position(1, -1)
servos.set_duty_limits(2, 1000, 2000)
servos.set_position(2, 0.333)
servos.get_position(2)
servos.get_current(0)
servos.get_voltage(0)

# The Arduino.
arduino.digital_read(2)
arduino.set_pin_mode(3, GPIOPinMode.INPUT_PULLUP)
arduino.digital_read(3)
arduino.set_pin_mode(AnalogPin.A0, GPIOPinMode.INPUT)
arduino.analog_read(AnalogPin.A0)
arduino.measure_ultrasound_distance(8, 9)
arduino.set_pin_mode(13, GPIOPinMode.OUTPUT)
arduino.digital_write(13, True)
arduino.digital_write(13, False)
