"""Runs an sbot-style program on the simulated kit, then prints what the boards did.

Used by tests/compat/test_sbot_*.py as ``python -m j5aio run --api sbot --sim --kit
sb2024 --start-after 0 sbot_harness.py PROGRAM`` (``--api sbot`` makes ``import sbot``
give :mod:`j5aio.compat.sbot`). Before the program runs, the harness:

- sets the kit's inputs (``SBOT_HARNESS_BENCH=1``): pin 3 high, pin 4 low, A0 at 2.5 V,
  an obstacle 0.5 m from the ultrasound sensor on pins 8 and 9, motor 0 drawing 0.75 A,
  a 12.25 V battery giving 2.5 A;
- records every line each simulated board receives (``SBOT_HARNESS_RECORD=1``).

When the program ends (normally, or by ``SystemExit``), before the boards are made safe,
it prints one line ``KIT <json>``: outputs, motors, servos, pins, the note playing, and
the recorded lines; after a normal end it makes the boards safe, as the end of the
program does, and prints the same again as ``EXIT <json>``.
"""

from __future__ import annotations

import json
import os
import runpy
import sys
from typing import Any, TypeVar, cast

from j5aio.simulator.base import SerialBoardSimulator
from j5aio.simulator.kit import current_kit
from j5aio.simulator.sb_arduino_2024 import SBArduino2024Simulator
from j5aio.simulator.sr_motor_fw4 import SRMotorBoardFw4Simulator
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator
from j5aio.simulator.sr_servo_fw4 import SRServoBoardFw4Simulator

T = TypeVar("T")

_received: dict[str, list[str]] = {}


def _record() -> None:
    original = SerialBoardSimulator.receive

    def receive(self: SerialBoardSimulator, data: bytes) -> bytes:
        buffer = _partial.get(self.serial_number, b"") + bytes(data)
        *lines, rest = buffer.split(b"\n")
        _partial[self.serial_number] = rest
        _received.setdefault(self.serial_number, []).extend(
            line.decode("utf-8", "replace") for line in lines
        )
        return original(self, data)

    _partial: dict[str, bytes] = {}
    SerialBoardSimulator.receive = receive  # type: ignore[method-assign]


def _of(name: str, kind: type[T]) -> list[T]:
    """The kit's simulators called ``name``."""
    return [cast(T, simulator) for simulator in current_kit().simulators(name)]


def _bench() -> None:
    power = _of("sr-power-fw4", SRPowerBoardFw4Simulator)[0]
    power.battery_voltage = 12.25
    power.battery_current = 2.5
    _of("sb-motor-fw4", SRMotorBoardFw4Simulator)[0].set_motor_current(0, 0.75)
    arduino = _of("sb-arduino-2024", SBArduino2024Simulator)[0]
    arduino.set_input_level(3, True)
    arduino.set_input_level(4, False)
    arduino.set_analogue(14, volts=2.5)
    arduino.set_ultrasound_distance(8, 9, 0.5)


def _state() -> dict[str, Any]:
    power = _of("sr-power-fw4", SRPowerBoardFw4Simulator)[0]
    arduinos = _of("sb-arduino-2024", SBArduino2024Simulator)
    playing = power.playing
    return {
        "outputs": list(power.outputs),
        "note": None if playing is None else [playing.frequency, playing.duration_ms],
        "motors": [
            [channel.drive.name, channel.value]
            for board in _of("sb-motor-fw4", SRMotorBoardFw4Simulator)
            for channel in board.motors
        ],
        "servos": [
            pulse
            for board in _of("sb-servo-fw4", SRServoBoardFw4Simulator)
            for pulse in board.pulse_widths
        ],
        "pins": {
            str(pin): [arduino.pin_mode(pin).name, arduino.output_level(pin)]
            for arduino in arduinos[:1]
            for pin in range(2, 20)
        },
        "received": _received,
    }


def main() -> None:
    program = sys.argv[1]
    sys.argv = sys.argv[1:]
    if os.environ.get("SBOT_HARNESS_RECORD") == "1":
        _record()
    if os.environ.get("SBOT_HARNESS_BENCH") == "1":
        _bench()
    try:
        runpy.run_path(program, run_name="__main__")
    finally:
        print("KIT " + json.dumps(_state()), flush=True)
    from j5aio.sync import shutdown

    shutdown()  # (what the end of the program does: every board made safe)
    print("EXIT " + json.dumps(_state()), flush=True)


main()
