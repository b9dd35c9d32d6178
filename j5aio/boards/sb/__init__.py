"""Boards made by SourceBots."""

from j5aio.boards.sb.arduino import SBArduinoBoard, UltrasoundSensors
from j5aio.boards.sb.arduino_2024 import SBArduino2024Board
from j5aio.boards.sb.servo_board import SBServoBoard

__all__ = ["SBArduino2024Board", "SBArduinoBoard", "SBServoBoard", "UltrasoundSensors"]
