"""sbot (SourceBots' own library, from PyPI) drives j5aio's sb2024 simulators.

What it sees must be what the internals docs say the boards do (docs/internals/: the power,
motor and servo boards, the SourceBots Arduino, and how sbot drives a serial board).
"""

from __future__ import annotations

from j5aio.simulator import MotorDrive, PinMode

from .peer_support import ServedKit, require, run_peer

require("sbot", "sbot")

PEER = r"""
import json, os
from sbot import AnalogPin, GPIOPinMode, BRAKE, arduino, motors, power, servos, utils

utils.load_boards()
out = {}
out["boards"] = [repr(power), repr(motors), repr(servos)]
power.set_output(0, True)
out["output0"] = power.is_output_on(0)
out["output4"] = power.is_output_on(4)
try:
    power.set_output(4, False)
except RuntimeError as error:
    out["brain"] = str(error)
out["battery"] = list(power.get_battery_data())
motors.set_power(0, 0.5)
motors.set_power(1, -1)
out["motors"] = [motors.get_power(0), motors.get_power(1)]
motors.set_power(1, BRAKE)
out["braked"] = motors.get_power(1)
out["motor_current"] = motors.get_motor_current(0)
servos.set_position(0, 0.5)
out["servo"] = servos.get_position(0)
out["servo_off"] = servos.get_position(1)
arduino.set_pin_mode(5, GPIOPinMode.OUTPUT)
arduino.digital_write(5, True)
arduino.set_pin_mode(6, GPIOPinMode.INPUT_PULLUP)
out["digital"] = [arduino.digital_read(3), arduino.digital_read(4)]
out["analogue"] = arduino.analog_read(AnalogPin.A0)
out["ultrasound"] = [arduino.measure_ultrasound_distance(8, 9),
                     arduino.measure_ultrasound_distance(10, 11),
                     arduino.measure_ultrasound_distance(12, 13)]
print("RESULT " + json.dumps(out), flush=True)
"""

NACK_PEER = r"""
import json
from sbot import servos, utils

utils.load_boards()
out = {}
servos.set_duty_limits(0, 300, 600)
try:
    servos.set_position(0, -1)  # 300 µs: below SR firmware 4.3's 500 µs
except RuntimeError as error:
    out["nack"] = str(error)
servos.set_position(0, 1)  # 600 µs: within it
out["position"] = servos.get_position(0)
print("RESULT " + json.dumps(out), flush=True)
"""


def _env(kit: ServedKit, **kinds: str) -> dict[str, str]:
    env = {f"SBOT_MANUAL_{kind}_PORTS": kit.path(name) for kind, name in kinds.items()}
    env["SBOT_SKIP_WAIT_START"] = "1"
    return env


def test_sbot_drives_the_sb2024_kit(served: list[ServedKit]) -> None:
    kit = ServedKit({
        "sr-power-fw4": "PB1", "sb-motor-fw4": "MB1", "sb-servo-fw4": "SB1",
        "sb-arduino-2024": "AR1",
    })
    served.append(kit)
    power = kit.simulators["sr-power-fw4"]
    power.battery_voltage = 12.25
    power.battery_current = 2.5
    motor = kit.simulators["sb-motor-fw4"]
    motor.set_motor_current(0, 0.75)
    arduino = kit.simulators["sb-arduino-2024"]
    arduino.set_input_level(3, True)
    arduino.set_input_level(4, False)
    arduino.set_analogue(14, volts=2.5)
    arduino.set_ultrasound_distance(8, 9, 0.5)
    arduino.set_ultrasound_echo(12, 13, 40_000)  # beyond 32.7 ms: the firmware wraps it

    got = run_peer(PEER, env=_env(
        kit, POWER="sr-power-fw4", MOTOR="sb-motor-fw4", SERVO="sb-servo-fw4",
        ARDUINO="sb-arduino-2024",
    ))

    # Identity: sbot names each board by the asset tag of its *IDN? reply.
    assert got["boards"] == ["<Power PB1>", "<Motor MB1>", "<Servo SB1>"]
    assert got["output0"] is True
    assert got["output4"] is True  # L2, the brain's, is always on
    assert "Brain output" in got["brain"]
    assert got["battery"] == [12.25, 2.5]
    # Motors: power read back; BRAKE is SET:0 and reads back as 0 (§2B).
    assert got["motors"] == [0.5, -1.0]
    assert got["braked"] == 0
    assert got["motor_current"] == 0.75
    # Servos: sbot's default limits 350-1980 µs; 0.5 gives 1572 µs, stored as 1570 (5 µs
    # ticks), which reads back as 0.497 (§3B).
    assert got["servo"] == 0.497
    assert got["servo_off"] is None
    # Arduino (§5B): pins, pull-up, analogue, ultrasound; no echo and a wrapped echo.
    assert got["digital"] == [True, False]
    assert arduino.pin_mode(5) is PinMode.OUTPUT and arduino.output_level(5) is True
    assert arduino.pin_mode(6) is PinMode.INPUT_PULLUP
    assert abs(got["analogue"] - 2.5) < 0.01
    assert got["ultrasound"][0] == 500
    assert got["ultrasound"][1] == 0  # no echo
    # 40 000 µs held in a signed 16-bit int is -25 536; 5 x -25 536 / 29 in C is -4402.
    # (sbot passes the wrapped reading on; j5aio's backend calls it no echo.)
    assert got["ultrasound"][2] == -4402
    # At exit sbot resets the power, motor and servo boards (§7): outputs off but L2,
    # motors coasting, servos off.
    assert power.outputs == (False, False, False, False, True, False, False)
    assert [m.drive for m in motor.motors] == [MotorDrive.COAST, MotorDrive.COAST]
    assert all(pulse is None for pulse in kit.simulators["sb-servo-fw4"].pulse_widths)


def test_sbot_sees_the_firmwares_nack_text(served: list[ServedKit]) -> None:
    # sbot's duty limits go down to 300 µs, SR firmware 4.3's to 500 µs: the board
    # NACKs, and sbot raises the firmware's text (§3B, §7).
    kit = ServedKit({"sr-servo-fw4": "SB1"})
    served.append(kit)
    env = _env(kit, SERVO="sr-servo-fw4")
    env["SBOT_NO_POWERBOARD"] = "1"
    got = run_peer(NACK_PEER, env=env)
    assert got["nack"] == "Invalid servo setpoint"
    assert got["position"] == 1.0
