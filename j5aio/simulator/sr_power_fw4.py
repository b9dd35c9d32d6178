r"""Simulator of the SR Power Board v4 running firmware 4.4 (USB CDC serial, text).

Protocol (:doc:`/internals/sr-power-board`). The board is a CDC serial port (baud rate
ignored). Each
``\n``-terminated ASCII line is one command; a ``\r`` cuts the line there; 63 bytes
without ``\n`` discard the buffer. Every line gets exactly one reply line: ``ACK``, data,
or ``NACK:<reason>``. The replies produced from one USB packet (one
:meth:`~j5aio.simulator.base.SerialBoardSimulator.receive`) share a 64-byte buffer, so a host that
sends several commands at once may get them cut.

Outputs 0-6 are H0, H1, L0, L1, L2 (the brain, always on unless ``*SYS:BRAIN:SET:0``),
L3 and the 5 V rail. The start buttons are latched: a press (the moment a button goes
down) is remembered until the next ``BTN:START:GET?``, which reports it once.
``*RESET`` clears the over-current latches, switches every output off but the brain,
darkens both LEDs, stops the buzzer and clears the button latches. Pulling the USB
cable switches every output but the brain off, stops the buzzer and lights both LEDs.

The firmware's timers (the buzzer's note, the flashing LEDs, which toggle once a second)
follow a clock (:mod:`j5aio.simulator.clock`): a simulated kit's clock, which runs in real
or scaled time, or, for a board made on its own, a manual clock that stands still until
moved on (:meth:`~SRPowerBoardFw4Simulator.use_clock`,
:meth:`~SRPowerBoardFw4Simulator.advance`). They are worked out whenever the board's state
is read or a command arrives. Over-current trips happen when the outside says so
(:meth:`~SRPowerBoardFw4Simulator.trip_output`).
"""

from __future__ import annotations

from typing import ClassVar, Final

from j5aio._records import FrozenRecord, frozen_record

from .base import SerialBoardSimulator
from .clock import BoardTime, Clock
from .loads import PowerBoardLoads
from .sr_text_line import LINE_LIMIT, BoundedLineInput, answer_lines

__all__ = ["BuzzerNote", "SRPowerBoardFw4Simulator"]

_OUTPUT_COUNT: Final = 7
_BRAIN: Final = 4
_MAX_FREQUENCY: Final = 10_000
_FAN_ON_ABOVE_C: Final = 40
_DEFAULT_DELAY_COEFFICIENTS: Final = (100, 100, 20, 40, 2000)
_LED_NAMES: Final = ("RUN", "ERR")
_LED_VALUES: Final = ("0", "1", "F")
_BOOT_NOTE: Final = (523, 150)


# A frozen dataclass whose ``__init__`` is written here, the rest coming from FrozenRecord
# as ``@dataclass(frozen=True)`` would make it: a simulated kit's start makes this module,
# and making the generated methods costs a few hundred microseconds. A test checks it.
@frozen_record
class BuzzerNote(FrozenRecord):
    """A note the host asked the buzzer to play (``NOTE:<frequency>:<duration>``)."""

    frequency: int
    """The frequency sent, in Hz (the buzzer plays at most 10 kHz)."""
    duration_ms: int
    """The duration sent, in ms."""

    def __init__(self, frequency: int, duration_ms: int) -> None:
        object.__setattr__(self, "frequency", frequency)
        object.__setattr__(self, "duration_ms", duration_ms)


def _leading_number(text: str) -> int | None:
    """The firmware's number parse: leading digits (the first character must be one)."""
    digits = ""
    for character in text:
        if not character.isdigit():
            break
        digits += character
    return int(digits) if digits else None


class SRPowerBoardFw4Simulator(PowerBoardLoads, SerialBoardSimulator):
    """An SR Power Board v4 with firmware 4.4, a USB CDC serial port.

    :param serial_number: the asset tag (it is also the USB serial number).
    :param version: the firmware version ``*IDN?`` reports.
    :param battery_voltage: the battery voltage, in volts.
    """

    baudrate: ClassVar[int] = 115_200
    boot_delay: ClassVar[float] = 0.0
    resets_on_open: ClassVar[bool] = False
    powered_by_usb: ClassVar[bool] = False
    #: Number of outputs (H0, H1, L0, L1, L2, L3, 5 V).
    OUTPUT_COUNT: ClassVar[int] = _OUTPUT_COUNT

    def __init__(
        self,
        serial_number: str,
        *,
        version: str = "4.4.2",
        battery_voltage: float = 12.0,
    ) -> None:
        super().__init__(
            serial_number,
            usb_vid=0x1BDA,
            usb_pid=0x0010,
            manufacturer="Student Robotics",
            product="Power Board v4",
        )
        self.version = version
        self._input = BoundedLineInput(LINE_LIMIT)
        self._outputs = [False] * _OUTPUT_COUNT
        self._latches = [False] * _OUTPUT_COUNT
        self._output_ma = [0] * _OUTPUT_COUNT
        self._start_loads(battery_voltage)
        self._temperature = 25
        self._fan_forced = False
        self._regulator_mv = 5000
        self._leds = ["0", "0"]
        self._held = [False, False]
        self._pressed = [False, False]
        self._time = BoardTime()
        self._note: BuzzerNote | None = None
        self._note_ends_ms = 0
        self._delay_coefficients: tuple[int, ...] = _DEFAULT_DELAY_COEFFICIENTS
        #: Every note the host asked for, oldest first (each replaced the one before).
        self.note_history: list[BuzzerNote] = []
        self._boot()

    # --- outside control ---

    def press_start(self, *, external: bool = False) -> None:
        """Press (and hold) the internal start button, or the external one.

        The press latches: the next ``BTN:START:GET?`` reports it, once, even if the
        button was released before. Holding the button does not press it again.
        """
        if not self._held[external]:
            self._pressed[external] = True
        self._held[external] = True

    def release_start(self, *, external: bool = False) -> None:
        """Release the internal start button, or the external one."""
        self._held[external] = False

    def click_start(self, *, external: bool = False) -> None:
        """Press and release a start button; the board remembers the press until read."""
        self.press_start(external=external)
        self.release_start(external=external)

    @property
    def temperature(self) -> int:
        """The board's temperature, in °C; the fan runs above 40 °C."""
        return self._temperature

    @temperature.setter
    def temperature(self, celsius: int) -> None:
        self._temperature = celsius

    @property
    def regulator_voltage(self) -> float:
        """The 5 V regulator's voltage, in volts."""
        return self._regulator_mv / 1000

    @regulator_voltage.setter
    def regulator_voltage(self, volts: float) -> None:
        self._regulator_mv = round(volts * 1000)

    def set_output_current(self, output: int, amps: float) -> None:
        """Make ``output`` (0-6) draw ``amps`` while it is on."""
        self._output_ma[output] = round(amps * 1000)

    def trip_output(self, output: int) -> None:
        """Trip the over-current protection of ``output``: off, and latched off."""
        self._latches[output] = True
        self._outputs[output] = False
        self._tell_listeners()

    def use_clock(self, clock: Clock) -> None:
        """Run the firmware's timers on ``clock`` from now on (a kit gives its own)."""
        self._time.follow(clock)

    @property
    def clock(self) -> Clock:
        """The clock the firmware's timers follow."""
        return self._time.clock

    def advance(self, seconds: float) -> None:
        """Let ``seconds`` pass beside the clock: the buzzer plays on, flashing LEDs toggle.

        :raises ValueError: ``seconds`` is negative.
        """
        self._time.skip(seconds)

    @property
    def uptime(self) -> float:
        """Seconds the firmware has run on its clock (the time its timers go by)."""
        return self._time.seconds()

    @property
    def _now_ms(self) -> int:
        """The firmware's millisecond tick; reading it ends a note whose time is up."""
        now = self._time.milliseconds()
        if self._note is not None and now >= self._note_ends_ms:
            self._note = None
        return now

    # --- readable state ---

    @property
    def outputs(self) -> tuple[bool, ...]:
        """Whether each output is on (H0, H1, L0, L1, L2, L3, 5 V)."""
        return tuple(self._outputs)

    @property
    def overcurrent_latches(self) -> tuple[bool, ...]:
        """Whether each output is latched off by over-current."""
        return tuple(self._latches)

    @property
    def led_modes(self) -> tuple[str, ...]:
        """The RUN and ERROR LEDs as the firmware holds them: ``"0"``, ``"1"`` or ``"F"``."""
        return tuple(self._leds)

    @property
    def run_led(self) -> bool:
        """Whether the RUN LED is lit now.

        A flashing LED toggles once a second on the firmware's tick: lit in the even
        seconds of :attr:`uptime`, dark in the odd ones.
        """
        return self._lit(0)

    @property
    def error_led(self) -> bool:
        """Whether the ERROR LED is lit now."""
        return self._lit(1)

    @property
    def fan(self) -> bool:
        """Whether the fan runs (above 40 °C, or forced)."""
        return self._fan_forced or self._temperature > _FAN_ON_ABOVE_C

    @property
    def playing(self) -> BuzzerNote | None:
        """The note the buzzer is playing now, or ``None`` when it is silent."""
        _ = self._now_ms  # a note whose time is up has ended
        return self._note

    @property
    def start_latches(self) -> tuple[bool, bool]:
        """The internal and external start button latches (pressed since the last read)."""
        return self._pressed[0], self._pressed[1]

    def _lit(self, led: int) -> bool:
        if self._leds[led] == "F":
            return (self._now_ms // 1000) % 2 == 0
        return self._leds[led] == "1"

    # --- firmware ---

    def _boot(self) -> bytes:
        self._input.reset()
        self._outputs = [False] * _OUTPUT_COUNT
        self._outputs[_BRAIN] = True
        self._latches = [False] * _OUTPUT_COUNT
        self._pressed = [False, False]
        self._fan_forced = False
        self._delay_coefficients = _DEFAULT_DELAY_COEFFICIENTS
        self._start_note(*_BOOT_NOTE)
        # RUN and ERROR light at power-up; USB enumeration turns ERROR off.
        self._leds = ["1", "1" if not self.connected else "0"]
        return b""

    def unplug(self) -> None:
        """Pull the USB cable: the board's own safe state (outputs off but the brain)."""
        super().unplug()
        self._outputs = [index == _BRAIN and on for index, on in enumerate(self._outputs)]
        self._note = None
        self._leds = ["1", "1"]
        self._input.reset()
        self._tell_listeners()

    def plug(self) -> None:
        """Plug the USB cable back in: the host enumerates the board (ERROR LED off)."""
        super().plug()
        self._leds[1] = "0"

    def _process(self, data: bytes) -> bytes:
        return answer_lines(self._input, data, self._run)

    def _run(self, line: bytes) -> bytes:
        command = line.decode("ascii", errors="replace")
        return self._execute(command).encode("ascii", errors="replace")

    def _start_note(self, frequency: int, duration_ms: int) -> None:
        now = self._time.milliseconds()
        if frequency == 0 or duration_ms == 0:
            self._note = None
            return
        self._note = BuzzerNote(frequency, duration_ms)
        self._note_ends_ms = now + duration_ms

    def _execute(self, command: str) -> str:
        fields = command.split(":")
        handlers = {
            "*IDN?": self._identify,
            "*STATUS?": self._status,
            "*RESET": self._reset,
            "*SYS": self._system,
            "OUT": self._output,
            "BATT": self._battery,
            "LED": self._led,
            "BTN": self._button,
            "NOTE": self._buzzer,
            "ECHO": self._echo,
        }
        handler = handlers.get(fields[0])
        if handler is None:
            return f"NACK:Unknown command: '{fields[0]}'"
        return handler(fields[1:])

    def _identify(self, _args: list[str]) -> str:
        return f"Student Robotics:PBv4B:{self.serial_number}:{self.version}"

    def _status(self, _args: list[str]) -> str:
        latches = ",".join("1" if latch else "0" for latch in self._latches)
        return f"{latches}:{self._temperature}:{int(self.fan)}:{self._regulator_mv}"

    def _reset(self, _args: list[str]) -> str:
        self._latches = [False] * _OUTPUT_COUNT
        self._outputs = [index == _BRAIN for index in range(_OUTPUT_COUNT)]
        self._leds = ["0", "0"]
        self._note = None
        self._pressed = [False, False]
        return "ACK"

    def _system(self, args: list[str]) -> str:
        if not args:
            return "NACK:Missing system command"
        name, rest = args[0], args[1:]
        if name == "DELAY_COEFF" and rest[:1] == ["GET?"]:
            return ":".join(str(value) for value in self._delay_coefficients)
        if rest[:1] != ["SET"] or len(rest) < 2:
            return "NACK:Invalid system command"
        if name == "FAN":
            self._fan_forced = rest[1][:1] == "1"
            return "ACK"
        if name == "BRAIN":
            self._outputs[_BRAIN] = rest[1][:1] == "1"
            return "ACK"
        values = [_leading_number(value) for value in rest[1:]]
        if name == "DELAY_COEFF" and len(values) == 5 and None not in values:
            self._delay_coefficients = tuple(v for v in values if v is not None)
            return "ACK"
        return "NACK:Invalid system command"

    def _output(self, args: list[str]) -> str:
        if not args or not args[0]:
            return "NACK:Missing output number"
        if len(args[0]) != 1 or args[0] not in "0123456":
            return "NACK:Invalid output number"
        output = int(args[0])
        if len(args) < 2:
            return "NACK:Missing output command"
        if args[1] == "GET?":
            return str(int(self._outputs[output]))
        if args[1] == "I?":
            on = self._outputs[output]
            return str(self._output_ma[output] + self._supplied_ma[output] if on else 0)
        if args[1] != "SET":
            return "NACK:Unknown output command"
        if output == _BRAIN:
            return "NACK:Brain output cannot be controlled"
        if len(args) < 3 or not args[2]:
            return "NACK:Missing output enable argument"
        if args[2][0] not in "01":
            return "NACK:Invalid output enable argument"
        enable = args[2][0] == "1"
        if not (enable and self._latches[output]):  # a latched output stays off, still ACKed
            self._outputs[output] = enable
        return "ACK"

    def _battery(self, args: list[str]) -> str:
        if not args:
            return "NACK:Missing argument"
        if args[0] == "V?":
            return str(round(self.loaded_voltage * 1000))
        if args[0] == "I?":
            return str(self._battery_ma + round(self.load_current * 1000))
        return "NACK:Unknown battery command"

    def _led(self, args: list[str]) -> str:
        if not args or not args[0]:
            return "NACK:Missing LED name"
        if args[0] not in _LED_NAMES:
            return "NACK:Invalid LED name"
        led = _LED_NAMES.index(args[0])
        if len(args) < 2:
            return "NACK:Missing LED argument"
        if args[1] == "GET?":
            return self._leds[led]
        if args[1] != "SET":
            return "NACK:Invalid LED argument"
        if len(args) < 3 or not args[2]:
            return "NACK:Missing LED value"
        if args[2] not in _LED_VALUES:
            return "NACK:Invalid LED value"
        self._leds[led] = args[2]
        return "ACK"

    def _button(self, args: list[str]) -> str:
        if not args or not args[0]:
            return "NACK:Missing button name"
        if args[0] != "START":
            return "NACK:Invalid button name"
        if len(args) < 2:
            return "NACK:Missing button command"
        if args[1] != "GET?":
            return "NACK:Invalid button command"
        reply = f"{int(self._pressed[0])}:{int(self._pressed[1])}"
        self._pressed = [False, False]
        return reply

    def _buzzer(self, args: list[str]) -> str:
        if not args or not args[0]:
            return "NACK:Missing note frequency"
        if args[0] == "GET?":
            now = self._now_ms
            if self._note is None:
                return "0:0"
            remaining = self._note_ends_ms - now
            return f"{min(self._note.frequency, _MAX_FREQUENCY)}:{remaining}"
        frequency = _leading_number(args[0])
        if frequency is None or frequency > 0xFFFF:
            return "NACK:Invalid note frequency"
        if len(args) < 2 or not args[1]:
            return "NACK:Missing note duration"
        duration = _leading_number(args[1])
        if duration is None or duration > 0xFFFFFFFF:
            return "NACK:Invalid note duration"
        self.note_history.append(BuzzerNote(frequency, duration))
        self._start_note(min(frequency, _MAX_FREQUENCY), duration)
        return "ACK"

    def _echo(self, args: list[str]) -> str:
        return args[0] if args else ""
