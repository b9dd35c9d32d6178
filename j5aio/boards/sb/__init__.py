"""Boards made by SourceBots."""

from j5aio.boards.sb.arduino import SBArduinoBoard, UltrasoundSensors

__all__ = ["SBArduinoBoard", "UltrasoundSensors"]
