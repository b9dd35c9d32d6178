"""The SourceBots Arduino running the sb2024 firmware: every pin digital, ultrasound, no servos."""

from __future__ import annotations

from typing import ClassVar

from j5aio.boards.arduino.all_digital import AllDigitalUno

__all__ = ["SBArduino2024Board"]


class SBArduino2024Board(AllDigitalUno):
    """The SourceBots Arduino of the 2024 kit (firmware ``2.0``, the sb2024 protocol).

    Every pin from 2 to 19 is a digital input, input with pull-up or output; A0 to A5
    (14 to 19) also read voltages. An ultrasound sensor works on any two pins:
    ``board.ultrasound_sensors[trigger, echo]``, whose ``distance()`` is ``None`` when
    no echo comes back. The firmware drives no servos.

    :param serial_number: the board's serial number.
    :param backend: the backend that drives the board.
    """

    name: ClassVar[str] = "SourceBots Arduino (sb2024)"
