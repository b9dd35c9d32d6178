"""CONSOLE_ENVIRONMENT: every board on the console, printing and asking instead of hardware."""

from __future__ import annotations

from j5aio.backends.console.camera import CameraConsoleBackend
from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
)
from j5aio.backends.environment import Environment

__all__ = ["CONSOLE_ENVIRONMENT"]

CONSOLE_ENVIRONMENT = Environment("ConsoleEnvironment")
"""The console environment: each board is printed to and asked about on the terminal."""

for _backend in (
    SRV4PowerBoardConsoleBackend,
    SRV4MotorBoardConsoleBackend,
    SRV4ServoBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SBArduinoConsoleBackend,
    CameraConsoleBackend,
):
    CONSOLE_ENVIRONMENT.register_backend(_backend)
