"""sbot's ``power``: the power board's outputs, battery and status."""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING, NamedTuple, cast

from j5aio.compat._shared import status

from ._errors import translate_errors
from ._kit import KitLink

if TYPE_CHECKING:
    from j5aio.sync import ProtectedPowerOutput

__all__ = ["BRAIN_OUTPUT", "BatteryData", "Power", "PowerOutputPosition", "PowerStatus"]


class PowerOutputPosition(IntEnum):
    """The power board's outputs, numbered as on the wire."""

    H0 = 0
    H1 = 1
    L0 = 2
    L1 = 3
    L2 = 4
    L3 = 5
    FIVE_VOLT = 6


class BatteryData(NamedTuple):
    """The battery's voltage (V) and the current drawn from it (A)."""

    voltage: float
    current: float


class PowerStatus(status.PowerBoardStatus):
    """The power board's status: trips, temperature (°C), fan, 5 V regulator (V)."""

    __slots__ = ()

    # sbot's class has this classmethod itself, so its API surface lists it here.
    from_status_response = vars(status.PowerBoardStatus)["from_status_response"]


#: The output that powers the brain: always on, not switchable.
BRAIN_OUTPUT = PowerOutputPosition.L2


@translate_errors
class Power:
    """The power board: switch its outputs, read its meters.

    :param boards: the kit the power board is found on.
    """

    __slots__ = ("_boards", "_outputs")

    def __init__(self, boards: KitLink) -> None:
        self._boards = boards
        # The facade's outputs, each looked up once (a lookup costs as much as a call).
        self._outputs: dict[int, ProtectedPowerOutput] = {}

    def _output(self, id: int) -> ProtectedPowerOutput:
        board = self._boards.power_board()
        found = self._outputs.get(id)
        if found is None:
            if isinstance(id, bool) or not isinstance(id, int):
                raise TypeError(f"a power output is an int from 0 to 6, not {id!r}")
            if not 0 <= id < len(PowerOutputPosition):
                raise ValueError(f"Output {id} does not exist on power board")
            found = cast("ProtectedPowerOutput", board.outputs[id])
            self._outputs[id] = found
        return found

    def set_output(self, id: int, on: bool) -> None:
        """Switch output ``id`` on or off (an output tripped by over-current stays off).

        :raises RuntimeError: ``id`` is L2, the brain's output.
        :raises ValueError: there is no output ``id``.
        """
        output = self._output(id)
        if id == BRAIN_OUTPUT:
            raise RuntimeError("Brain output cannot be controlled via this API.")
        output.is_enabled = bool(on)

    def is_output_on(self, id: int) -> bool:
        """Return whether output ``id`` is on."""
        return self._output(id).is_enabled

    def get_output_current(self, id: int) -> float:
        """Return the current output ``id`` gives, in amps (±10 %)."""
        return self._output(id).current

    def get_battery_data(self) -> BatteryData:
        """Return the battery's voltage and current."""
        sensor = self._boards.power_board().battery_sensor
        return BatteryData(voltage=sensor.voltage, current=sensor.current)

    def status(self) -> PowerStatus:
        """Return the power board's status."""
        board = self._boards.power_board()
        return PowerStatus(
            overcurrent=tuple(
                board.outputs[position].is_overcurrent  # type: ignore[attr-defined]
                for position in PowerOutputPosition
            ),
            temperature=int(board.temperature_sensor.temperature),
            fan_running=board.fan.is_running,
            regulator_voltage=board.regulator_sensor.voltage,
            other=[],
        )

    def reset(self) -> None:
        """Reset the power board: every output off but the brain's, the buzzer silent."""
        self._boards.power_board().make_safe()

    def __repr__(self) -> str:
        if not self._boards.loaded:
            return f"<{self.__class__.__qualname__} no power board>"
        return f"<{self.__class__.__qualname__} {self._boards.power_board().serial_number}>"
