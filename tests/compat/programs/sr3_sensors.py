"""An sr-robot3 program reading the Arduino: digital, analogue (volts), ultrasound (mm)."""

from sr.robot3 import A0, A1, INPUT, INPUT_PULLUP, OUTPUT, Robot

robot = Robot(wait_for_start=False)
arduino = robot.arduino

arduino.pins[3].mode = INPUT_PULLUP
arduino.pins[4].mode = INPUT
print("digital", arduino.pins[3].digital_read(), arduino.pins[4].digital_read())
print("analogue", arduino.pins[A0].analog_read(), arduino.pins[A1].analog_read())
print("ultrasound", arduino.ultrasound_measure(6, 7), arduino.ultrasound_measure(8, 9))
print("after ultrasound", arduino.pins[6].mode, arduino.pins[6].digital_read())
arduino.pins[13].mode = OUTPUT
arduino.pins[13].digital_write(True)
print("output reads back", arduino.pins[13].digital_read())
arduino.pins[13].digital_write(False)
print("output reads back", arduino.pins[13].digital_read())
arduino.pins[A0].mode = INPUT_PULLUP
print("A0 as digital", arduino.pins[A0].digital_read())
arduino.pins[A0].mode = INPUT
print("A0 again", arduino.pins[A0].analog_read())
print("command", arduino.command("v"))
print("pin letter", arduino.map_pin_number(19))
print("identity", list(arduino.identify()))
