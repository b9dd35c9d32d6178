"""CONSOLE_ENVIRONMENT: every board on the console, printing and asking instead of hardware."""

from __future__ import annotations

from j5aio.backends.console.sb.arduino import SBArduinoConsoleBackend
from j5aio.backends.console.sb.arduino_2024 import SBArduino2024ConsoleBackend
from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SBServoBoardConsoleBackend,
    SRArduinoConsoleBackend,
    SRV4MotorBoardConsoleBackend,
    SRV4PowerBoardConsoleBackend,
    SRV4RuggeduinoConsoleBackend,
    SRV4ServoBoardConsoleBackend,
    SRV4ServoBoardFw4ConsoleBackend,
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
    SRV4ServoBoardFw4ConsoleBackend,
    SBServoBoardConsoleBackend,
    KCHConsoleBackend,
    SRArduinoConsoleBackend,
    SBArduino2024ConsoleBackend,
):
    CONSOLE_ENVIRONMENT.register_backend(_backend)
