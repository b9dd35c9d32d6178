"""sr-robot3 (Student Robotics' API, release 2026.0.3) on j5aio.

Every name of sr-robot3's ``sr.robot3`` is here, with its signatures, defaults, units and
behaviour, built on j5aio's boards through the sync facade. A team's program runs
unchanged with::

    python -m j5aio run --api sr-robot3 robot.py          # on the robot's boards
    python -m j5aio run --api sr-robot3 --sim --kit sr2023 robot.py   # simulated

or, written for j5aio, with ``from j5aio.compat.sr_robot3 import *``::

    robot = Robot()              # finds the boards, powers the outputs, waits for start
    robot.motor_board.motors[0].power = 0.5
    distance_mm = robot.arduino.ultrasound_measure(4, 5)
    robot.power_board.piezo.buzz(Note.A6, 0.5)

See "Coming from sr-robot3" in the documentation for what j5aio adds.
"""

from __future__ import annotations

from j5aio.compat.sr_robot3._logs import add_trace_level
from j5aio.compat.sr_robot3.arduino import AnalogPins, GPIOPinMode
from j5aio.compat.sr_robot3.astoria import RobotMode
from j5aio.compat.sr_robot3.exceptions import (
    BoardDisconnectionError,
    MetadataKeyError,
    MetadataNotReadyError,
)
from j5aio.compat.sr_robot3.kch import Colour, UserLED
from j5aio.compat.sr_robot3.motor_board import MotorPower
from j5aio.compat.sr_robot3.power_board import Note, PowerOutputPosition
from j5aio.compat.sr_robot3.raw_serial import RawSerialDevice
from j5aio.compat.sr_robot3.robot import SR_ROBOT3_VERSION, Robot
from j5aio.compat.sr_robot3.utils import list_ports

add_trace_level()

__version__ = SR_ROBOT3_VERSION

BRAKE = MotorPower.BRAKE
COAST = MotorPower.COAST

A0 = AnalogPins.A0
A1 = AnalogPins.A1
A2 = AnalogPins.A2
A3 = AnalogPins.A3
A4 = AnalogPins.A4
A5 = AnalogPins.A5

COMP = RobotMode.COMP
DEV = RobotMode.DEV

INPUT = GPIOPinMode.INPUT
INPUT_PULLUP = GPIOPinMode.INPUT_PULLUP
OUTPUT = GPIOPinMode.OUTPUT

OUT_H0 = PowerOutputPosition.H0
OUT_H1 = PowerOutputPosition.H1
OUT_L0 = PowerOutputPosition.L0
OUT_L1 = PowerOutputPosition.L1
OUT_L3 = PowerOutputPosition.L3
OUT_FIVE_VOLT = PowerOutputPosition.FIVE_VOLT

LED_A = UserLED.A
LED_B = UserLED.B
LED_C = UserLED.C

__all__ = [
    "A0",
    "A1",
    "A2",
    "A3",
    "A4",
    "A5",
    "BRAKE",
    "COAST",
    "COMP",
    "DEV",
    "INPUT",
    "INPUT_PULLUP",
    "LED_A",
    "LED_B",
    "LED_C",
    "OUTPUT",
    "OUT_FIVE_VOLT",
    "OUT_H0",
    "OUT_H1",
    "OUT_L0",
    "OUT_L1",
    "OUT_L3",
    "BoardDisconnectionError",
    "Colour",
    "MetadataKeyError",
    "MetadataNotReadyError",
    "Note",
    "RawSerialDevice",
    "Robot",
    "list_ports",
]
