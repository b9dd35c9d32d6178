"""The console backend of the Student Robotics v4 Motor Board with firmware 4.4 / 4.5."""

from __future__ import annotations

from j5aio.backends.console.sr.v4.motor_board import SRV4MotorBoardConsoleBackend
from j5aio.boards.sr.v4.motor_board_fw4 import MotorBoardFw4
from j5aio.components.monitored_motor import MonitoredMotorInterface
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.components.voltage_sensor import VoltageSensorInterface

__all__ = ["SRV4MotorBoardFw4ConsoleBackend"]


class SRV4MotorBoardFw4ConsoleBackend(
    MonitoredMotorInterface, VoltageSensorInterface, SRV4MotorBoardConsoleBackend,
):
    """The firmware 4 Motor Board on the console: prints each change with the duty driven.

    The duty is ``|power|`` in steps of 0.1 % (``round(p x 1000)``); currents, fault
    flags and the input voltage are asked for.

    :param serial: the board's serial number.
    :param console_class: the console to talk through.
    """

    board = MotorBoardFw4

    @staticmethod
    def describe_drive(power: MotorState) -> str:
        """Say what the firmware 4 board does for ``power``, e.g. ``forward at 50.0% duty``."""
        if isinstance(power, MotorSpecialState):
            return "brake" if power is MotorSpecialState.BRAKE else "coast"
        value = round(power * 1000)
        if value == 0:
            return "brake"
        direction = "forward" if value > 0 else "reverse"
        return f"{direction} at {abs(value) / 10:.1f}% duty"

    async def get_motor_current(self, identifier: int) -> float:
        """Ask for the current motor ``identifier`` draws, in amps."""
        self._check_identifier("motor", identifier, self._MOTORS)
        return await self._console.read(f"Current of motor {identifier} [amps]", float)

    async def get_motor_fault(self, identifier: int) -> bool:
        """Ask whether the driver of motor ``identifier`` reports a fault."""
        self._check_identifier("motor", identifier, self._MOTORS)
        return await self._console.read(f"Does motor {identifier} have a fault [true/false]", bool)

    async def get_voltage_sensor_voltage(self, identifier: int) -> float:
        """Ask for the board's input voltage, in volts."""
        self._check_identifier("voltage sensor", identifier, range(1))
        return await self._console.read("Motor board input voltage [volts]", float)
