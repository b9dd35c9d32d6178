"""sr-robot3 (Student Robotics' own library, from PyPI) drives j5aio's sr2023 simulators.

What it sees must be what the internals docs say the boards do (docs/internals/: the power,
motor and servo boards, the SR Arduino, and how sr-robot3 drives a serial board).
"""

from __future__ import annotations

import json

from j5aio.simulator import MotorDrive

from .peer_support import ServedKit, require, run_peer

require("sr.robot3", "sr-robot3")

PEER = r"""
import json, os
paths = json.loads(os.environ["PEER_PATHS"])
from sr.robot3 import Robot, BRAKE, OUT_H0

r = Robot(
    manual_boards={
        "PBv4B": [paths["sr-power-fw4"]], "MCv4B": [paths["sr-motor-fw4"]],
        "SBv4B": [paths["sr-servo-fw4"]], "Arduino": [paths["sr-arduino-fw2"]],
    },
    wait_for_start=False,
)
out = {}
out["identity"] = [list(board.identify()) for board in
                   (r.power_board, r.motor_board, r.servo_board, r.arduino)]
out["battery"] = [r.power_board.battery_sensor.voltage, r.power_board.battery_sensor.current]
out["h0_current"] = r.power_board.outputs[OUT_H0].current
r.motor_board.motors[0].power = 0.5
r.motor_board.motors[1].power = -0.25
out["motors"] = [m.power for m in r.motor_board.motors]
out["motor_current"] = r.motor_board.motors[0].current
r.motor_board.motors[1].power = BRAKE
out["braked"] = r.motor_board.motors[1].power
r.servo_board.servos[0].position = 0.5
r.servo_board.servos[1].position = -1
out["servos"] = [r.servo_board.servos[0].position, r.servo_board.servos[1].position,
                 r.servo_board.servos[2].position]
out["servo_supply"] = [r.servo_board.voltage, r.servo_board.current]
arduino = r.arduino
out["digital"] = [arduino.pins[3].digital_read(), arduino.pins[4].digital_read()]
out["analogue"] = arduino.pins[14].analog_read()
out["ultrasound"] = [arduino.ultrasound_measure(6, 7), arduino.ultrasound_measure(8, 9)]
out["version_command"] = arduino.command("v")
print("RESULT " + json.dumps(out), flush=True)
"""


def test_sr_robot3_drives_the_sr2023_kit(served: list[ServedKit]) -> None:
    kit = ServedKit({
        "sr-power-fw4": "PB1", "sr-motor-fw4": "MB1", "sr-servo-fw4": "SB1",
        "sr-arduino-fw2": "AR1",
    })
    served.append(kit)
    power = kit.simulators["sr-power-fw4"]
    power.battery_voltage = 11.5
    power.battery_current = 1.25
    power.set_output_current(0, 2.0)
    motor = kit.simulators["sr-motor-fw4"]
    motor.set_motor_current(0, 1.5)
    arduino = kit.simulators["sr-arduino-fw2"]
    arduino.set_input_level(3, True)
    arduino.set_input_level(4, False)
    arduino.set_analogue(14, volts=2.5)
    arduino.set_ultrasound_distance(6, 7, 0.5)
    paths = {name: kit.path(name) for name in kit.simulators}

    got = run_peer(PEER, env={"PEER_PATHS": json.dumps(paths)})

    # Identity (§1B, §2B, §3B, §4): type, asset tag and version as the boards say them.
    assert got["identity"][:3] == [
        ["Student Robotics", "PBv4B", "PB1", "4.4.2"],
        ["Student Robotics", "MCv4B", "MB1", "4.4.1"],
        ["Student Robotics", "SBv4B", "SB1", "4.3"],
    ]
    assert got["identity"][3][1:] == ["SRduino", paths["sr-arduino-fw2"], "2"]
    # Meters read back.
    assert got["battery"] == [11.5, 1.25]
    assert got["h0_current"] == 2.0
    # Motors: power read back, BRAKE is SET:0 (§2B).
    assert got["motors"] == [0.5, -0.25]
    assert got["motor_current"] == 1.5
    assert got["braked"] == 0  # sr-robot3 reads a brake back as power 0 (BRAKE == 0)
    # Servos: 1000-2000 µs by default, 5 µs ticks; a servo never set is off.
    assert got["servos"] == [0.5, -1.0, None]
    assert got["servo_supply"][0] > 0
    # Arduino pins, analogue value and ultrasound (§4).
    assert got["digital"] == [True, False]
    assert abs(got["analogue"] - 2.5) < 0.01
    assert got["ultrasound"][0] == 500
    assert got["ultrasound"][1] == 0  # no echo
    assert got["version_command"] == "SRduino:2"
    # sr-robot3 powered every output on at start (L2, the brain's, is always on) ...
    # ... and reset every board at exit (§7: atexit *RESET): outputs off but L2,
    # motors coasting, servos off.
    assert power.outputs == (False, False, False, False, True, False, False)
    assert [m.drive for m in motor.motors] == [MotorDrive.COAST, MotorDrive.COAST]
    assert all(pulse is None for pulse in kit.simulators["sr-servo-fw4"].pulse_widths)
