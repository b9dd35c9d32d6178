"""sr-robot3's power board: outputs, battery sensor, piezo and LEDs, on j5aio's power board."""

from __future__ import annotations

from datetime import timedelta
from enum import IntEnum
from typing import TYPE_CHECKING, Final

from j5aio.compat._shared import status
from j5aio.compat.sr_robot3.exceptions import disconnected
from j5aio.compat.sr_robot3.utils import BoardIdentity, float_bounds_check
from j5aio.components.flashing_led import LEDMode
from j5aio.errors import CommunicationError
from j5aio.sync import FlashingLED, PowerBoardFw4, ProtectedPowerOutput
from j5aio.sync.wrapping import call, unwrap

if TYPE_CHECKING:
    from j5aio.sync import LED, PowerOutput
    from j5aio.sync import PowerBoard as CorePowerBoard

__all__ = [
    "BRAIN_OUTPUT",
    "BatterySensor",
    "Led",
    "Note",
    "Output",
    "Outputs",
    "Piezo",
    "PowerBoard",
    "PowerOutputPosition",
    "PowerStatus",
]


class PowerOutputPosition(IntEnum):
    """The power board's outputs, numbered as on the wire."""

    H0 = 0
    H1 = 1
    L0 = 2
    L1 = 3
    L2 = 4
    L3 = 5
    FIVE_VOLT = 6


#: The output that powers the brain: always on, and not switchable from a program.
BRAIN_OUTPUT: Final = PowerOutputPosition.L2


class Note(IntEnum):
    """Notes of scientific pitch notation, in whole hertz (sr-robot3's values)."""

    C6 = 1047
    D6 = 1175
    E6 = 1319
    F6 = 1397
    G6 = 1568
    A6 = 1760
    B6 = 1976
    C7 = 2093
    D7 = 2349
    E7 = 2637
    F7 = 2794
    G7 = 3136
    A7 = 3520
    B7 = 3951
    C8 = 4186


class PowerStatus(status.PowerBoardStatus):
    """The power board's status: output trips, temperature (°C), fan, 5 V regulator (V)."""

    __slots__ = ()


class Output:
    """One power output.

    :param output: j5aio's output.
    :param index: its number (:class:`PowerOutputPosition`).
    """

    __slots__ = ("_index", "_output")

    def __init__(self, output: PowerOutput, index: int) -> None:
        self._output = output
        self._index = index

    @property
    def is_enabled(self) -> bool:
        """Whether the output is on (an over-current trip switches it off)."""
        try:
            return self._output.is_enabled
        except CommunicationError as error:
            raise disconnected(error) from error

    @is_enabled.setter
    def is_enabled(self, value: bool) -> None:
        if self._index == BRAIN_OUTPUT:
            raise RuntimeError("Brain output cannot be controlled via this API.")
        try:
            self._output.is_enabled = bool(value)
        except CommunicationError as error:
            raise disconnected(error) from error

    @property
    def current(self) -> float:
        """The output's current draw, in amps (10 % tolerance)."""
        try:
            return self._output.current
        except CommunicationError as error:
            raise disconnected(error) from error

    @property
    def overcurrent(self) -> bool:
        """Whether the output has tripped on over-current (cleared by a reset)."""
        if not isinstance(self._output, ProtectedPowerOutput):
            return False  # (a firmware 3 board does not report trips)
        try:
            return self._output.is_overcurrent
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__} index={self._index} {self._output!r}>"


class Outputs:
    """The power board's outputs, by number: ``outputs[OUT_H0]``.

    :param board: j5aio's power board.
    """

    __slots__ = ("_board", "_outputs")

    def __init__(self, board: CorePowerBoard) -> None:
        self._board = board
        self._outputs = tuple(Output(output, index) for index, output in enumerate(board.outputs))

    def __getitem__(self, key: int) -> Output:
        return self._outputs[key]

    def __len__(self) -> int:
        return len(self._outputs)

    def power_off(self) -> None:
        """Switch off every output but the brain's."""
        for output in self._outputs:
            if output._index != BRAIN_OUTPUT:
                output.is_enabled = False

    def power_on(self) -> None:
        """Switch on every output (the brain's is always on)."""
        for output in self._outputs:
            if output._index != BRAIN_OUTPUT:
                output.is_enabled = True

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._board!r}>"


class Led:
    """An LED of the power board (run or error).

    :param led: j5aio's LED.
    """

    __slots__ = ("_led",)

    def __init__(self, led: LED) -> None:
        self._led = led

    def _set(self, mode: LEDMode) -> None:
        try:
            if isinstance(self._led, FlashingLED):
                self._led.mode = mode
            else:  # (a firmware 3 board's LED cannot flash by itself: it is lit)
                self._led.state = mode is not LEDMode.OFF
        except CommunicationError as error:
            raise disconnected(error) from error

    def on(self) -> None:
        """Light the LED."""
        self._set(LEDMode.ON)

    def off(self) -> None:
        """Put the LED out."""
        self._set(LEDMode.OFF)

    def flash(self) -> None:
        """Flash the LED at 1 Hz."""
        self._set(LEDMode.FLASH)

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__} {self._led!r}>"


class BatterySensor:
    """The battery's voltage and current.

    :param board: j5aio's power board.
    """

    __slots__ = ("_get_current", "_get_voltage", "_sensor")

    def __init__(self, board: CorePowerBoard) -> None:
        self._sensor = board.battery_sensor
        core = unwrap(self._sensor)  # (its coroutines, called through the facade's runtime)
        self._get_voltage = core.get_voltage
        self._get_current = core.get_current

    @property
    def voltage(self) -> float:
        """The battery's voltage, in volts."""
        try:
            voltage: float = call(self._get_voltage)
        except CommunicationError as error:
            raise disconnected(error) from error
        return voltage

    @property
    def current(self) -> float:
        """The current drawn from the battery, in amps."""
        try:
            current: float = call(self._get_current)
        except CommunicationError as error:
            raise disconnected(error) from error
        return current

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._sensor!r}>"


class Piezo:
    """The power board's buzzer.

    :param board: j5aio's power board.
    """

    __slots__ = ("_piezo",)

    def __init__(self, board: CorePowerBoard) -> None:
        self._piezo = board.piezo

    def buzz(self, frequency: float, duration: float, *, blocking: bool = False) -> None:
        """Play a tone of ``frequency`` hertz for ``duration`` seconds.

        A tone replaces the one playing. It returns at once, unless ``blocking`` is true:
        then it returns when the tone has finished.

        :raises TypeError: ``frequency`` or ``duration`` is not a number.
        :raises ValueError: ``frequency`` is outside 8 to 10000 Hz, or ``duration`` is
            negative or longer than about 24 days.
        """
        hertz = int(float_bounds_check(
            frequency, 8, 10_000, "Frequency must be between 8 and 10000Hz"))
        milliseconds = int(float_bounds_check(
            duration * 1000 if isinstance(duration, (int, float)) else duration,
            0, 2**31 - 1,
            f"Duration is a float in seconds between 0 and {(2**31 - 1) / 1000:,.0f}"))
        if milliseconds == 0:
            return  # (nothing to play: j5aio's piezo refuses an empty note)
        try:
            self._piezo.buzz(timedelta(milliseconds=milliseconds), hertz, blocking=blocking)
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._piezo!r}>"


class PowerBoard:
    """The power board, as sr-robot3 shows it.

    :param board: j5aio's power board.
    """

    __slots__ = ("_battery_sensor", "_board", "_error_led", "_outputs", "_piezo", "_run_led")

    def __init__(self, board: CorePowerBoard) -> None:
        self._board = board
        self._outputs = Outputs(board)
        self._battery_sensor = BatterySensor(board)
        self._piezo = Piezo(board)
        self._run_led = Led(board.run_led)
        self._error_led = Led(board.error_led)

    @staticmethod
    def get_board_type() -> str:
        """The board's type: ``PBv4B``."""
        return "PBv4B"

    @property
    def outputs(self) -> Outputs:
        """The power outputs."""
        return self._outputs

    @property
    def battery_sensor(self) -> BatterySensor:
        """The battery's voltage and current."""
        return self._battery_sensor

    @property
    def piezo(self) -> Piezo:
        """The buzzer."""
        return self._piezo

    def identify(self) -> BoardIdentity:
        """The board's identity: maker, type, asset tag and firmware version."""
        return BoardIdentity(
            "Student Robotics", self.get_board_type(), self._board.serial_number,
            self._board.firmware_version or "",
        )

    @property
    def status(self) -> PowerStatus:
        """The board's status: output trips, temperature, fan and regulator voltage.

        :raises BoardDisconnectionError: the board did not answer (or a firmware 3
            board, which reports none of these).
        """
        board = self._board
        if not isinstance(board, PowerBoardFw4):
            raise disconnected(CommunicationError(
                f"{board.name} does not report a status (it needs firmware 4)"))
        try:
            return PowerStatus(
                overcurrent=tuple(output.overcurrent for output in self._outputs._outputs),
                temperature=round(board.temperature_sensor.temperature),
                fan_running=board.fan.is_running,
                regulator_voltage=board.regulator_sensor.voltage,
            )
        except CommunicationError as error:
            raise disconnected(error) from error

    def reset(self) -> None:
        """Reset the board: every output off but the brain's, the buzzer silent."""
        try:
            self._board.make_safe()
        except CommunicationError as error:
            raise disconnected(error) from error

    def _start_button(self) -> bool:
        """Whether start was pressed since the last look (the board latches it)."""
        try:
            return self._board.start_button.is_pressed
        except CommunicationError as error:
            raise disconnected(error) from error

    def __repr__(self) -> str:
        return f"<{type(self).__qualname__}: {self._board!r}>"
