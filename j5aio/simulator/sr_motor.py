"""What both firmwares of the SR Motor Board v4 share, as simulated.

The board is a UART behind an FTDI FT232R USB-serial adapter, the only part powered
from USB. The controller sits on the isolated side, fed by the board's 12 V input (a
power board output): while :attr:`~SRMotorBoardSimulator.powered` is false its port is
there but nothing answers and no motor is driven; when power comes the controller boots.
A board that reset into its bootloader stops answering until it is rebooted.
"""

from __future__ import annotations

import enum
from abc import ABC, abstractmethod
from typing import ClassVar

from .base import SerialBoardSimulator

__all__ = ["MotorDrive", "SRMotorBoardSimulator"]


class MotorDrive(enum.Enum):
    """What a motor driver is doing (the same on both firmwares)."""

    COAST = "coast"
    """Driver disabled: the outputs float."""
    BRAKE = "brake"
    """Driver enabled with both half-bridges low."""
    FORWARD = "forward"
    """Driving forwards with some duty."""
    REVERSE = "reverse"
    """Driving in reverse with some duty."""


class SRMotorBoardSimulator(SerialBoardSimulator, ABC):
    """An SR Motor Board v4: its USB-serial adapter and its 12 V input.

    A firmware's simulator implements ``_stop_controller`` (what losing power does to
    it), besides what every serial board implements.

    :param serial_number: the FTDI serial number, which is also the asset tag.
    """

    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = False
    #: Number of motor outputs.
    MOTOR_COUNT: ClassVar[int] = 2

    def __init__(self, serial_number: str) -> None:
        super().__init__(
            serial_number,
            usb_vid=0x0403,
            usb_pid=0x6001,
            manufacturer="Student Robotics",
            product="MCV4B",
        )
        self._in_bootloader = False
        self._powered = True

    @property
    def powered(self) -> bool:
        """Whether the board's 12 V input is on (it starts on: a kit's wiring switches it).

        Switching it off stops the controller: nothing answers, a motor that was driven
        coasts to a stop and a braked one stays stopped (its state still says so).
        Switching it on boots the controller (the motors coast).
        """
        return self._powered

    @powered.setter
    def powered(self, on: bool) -> None:
        if on and not self._powered:
            self._powered = True
            self.reset()
        elif not on and self._powered:
            self._powered = False
            self._stop_controller()
            self._tell_listeners()

    @property
    def in_bootloader(self) -> bool:
        """Whether the board has reset into its bootloader (and stopped answering)."""
        return self._in_bootloader

    @abstractmethod
    def _stop_controller(self) -> None:
        """The controller lost power: forget what it was reading, coast the driven motors."""
