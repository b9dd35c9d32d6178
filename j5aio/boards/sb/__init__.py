"""Boards made by SourceBots."""

from j5aio.boards.sb.arduino import SBArduinoBoard, UltrasoundSensors
from j5aio.boards.sb.servo_board import SBServoBoard

__all__ = ["SBArduinoBoard", "SBServoBoard", "UltrasoundSensors"]
