r"""The SR v4 power board's serial text protocol, firmware 4.4: pure encode and parse.

The board is a USB CDC serial port (VID:PID ``1BDA:0010``, as firmware 3, which is a
control-transfer device instead). Each command is one ASCII line ending ``\n`` and gets
one reply line: ``ACK``, the data asked for, or ``NACK:<reason>``
(:doc:`/internals/sr-power-board`).

Outputs are numbered 0 to 6: H0, H1, L0, L1, L2, L3 and the 5 V regulator. L2 (4) powers
the brain and the firmware refuses to switch it, so :func:`encode_output_set` refuses it
before anything is sent.

This module does no I/O: the hardware backend uses it. Replies are parsed strictly:
anything the firmware cannot send is an :class:`~j5aio.errors.UnexpectedReplyError`
naming the board and the reply.
"""

from __future__ import annotations

from typing import Final

from j5aio._records import FrozenRecord, frozen_record
from j5aio._timedelta import timedelta
from j5aio.backends.hardware.sr.v4.text_protocol import (
    IDENTIFY,
    Identity,
    check_not_nack,
    command_line,
    parse_flag,
    parse_identity,
    parse_int,
    unexpected_reply,
    version_matches,
)
from j5aio.components.flashing_led import LEDMode
from j5aio.errors import NotSupportedByHardwareError, UnexpectedReplyError

__all__ = [
    "BATTERY_CURRENT",
    "BATTERY_VOLTAGE",
    "BOARD_TYPE",
    "BRAIN_OUTPUT",
    "BUTTON",
    "FIVE_VOLT_OUTPUT",
    "IDENTIFY",
    "LED_NAMES",
    "MAX_FREQUENCY",
    "MAX_NOTE_MS",
    "MIN_FREQUENCY",
    "OUTPUT_COUNT",
    "PID",
    "RESET",
    "STATUS",
    "SUPPORTED_VERSIONS",
    "VID",
    "ButtonLatches",
    "PowerStatus",
    "check_output",
    "encode_led_get",
    "encode_led_set",
    "encode_note",
    "encode_output_current",
    "encode_output_get",
    "encode_output_set",
    "is_supported_version",
    "parse_button",
    "parse_current_ma",
    "parse_identity_reply",
    "parse_led_mode",
    "parse_output_state",
    "parse_status",
]

#: USB vendor id (University of Southampton), shared with firmware 3.
VID: Final = 0x1BDA
#: USB product id, shared with firmware 3.
PID: Final = 0x0010
#: The board type field of the identity reply.
BOARD_TYPE: Final = "PBv4B"
#: The firmware versions this codec speaks: 4.4 and its patch releases (4.4.1, 4.4.2...).
SUPPORTED_VERSIONS: Final = ("4.4",)
#: The outputs: H0, H1, L0, L1, L2 (brain), L3, 5 V.
OUTPUT_COUNT: Final = 7
#: The output that powers the brain; the firmware will not switch it.
BRAIN_OUTPUT: Final = 4
#: The 5 V regulator's output.
FIVE_VOLT_OUTPUT: Final = 6
#: The LED names on the wire, by LED number (0 run, 1 error).
LED_NAMES: Final = ("RUN", "ERR")
#: The lowest buzzer frequency (below it the firmware's timer period overflows), in Hz.
MIN_FREQUENCY: Final = 8
#: The highest buzzer frequency (the firmware caps higher ones), in Hz.
MAX_FREQUENCY: Final = 10_000
#: The longest note, in ms (the hosts' limit, a signed 32-bit count).
MAX_NOTE_MS: Final = 2**31 - 1

#: Ask for the over-current latches, temperature, fan and 5 V regulator voltage.
STATUS: Final = b"*STATUS?\n"
#: Back to the safe state: latches cleared, outputs off but the brain, LEDs off, silence.
RESET: Final = b"*RESET\n"
#: Ask whether the start buttons were pressed since the last time (clears the latches).
BUTTON: Final = b"BTN:START:GET?\n"
#: Ask for the battery voltage, in mV.
BATTERY_VOLTAGE: Final = b"BATT:V?\n"
#: Ask for the battery current, in mA.
BATTERY_CURRENT: Final = b"BATT:I?\n"

_LED_VALUES: Final = {LEDMode.OFF: "0", LEDMode.ON: "1", LEDMode.FLASH: "F"}
_LED_REPLIES: Final = {b"0": LEDMode.OFF, b"1": LEDMode.ON, b"F": LEDMode.FLASH}
_MAX_MILLI: Final = 2**31 - 1
_TEMPERATURE_RANGE: Final = (-273, 1000)


# (The records here write their own ``__init__`` and take freezing, ``__repr__``, ``__eq__``
# and ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: a
# kit with this board makes them at start-up, and making the generated ones costs a
# quarter of a millisecond a class. A test checks them against those.)
@frozen_record
class PowerStatus(FrozenRecord):
    """The reply to ``*STATUS?``."""

    overcurrent: tuple[bool, ...]
    """Per output (H0, H1, L0, L1, L2, L3, 5 V): latched off by over-current."""
    temperature: int
    """The board's temperature, in °C."""
    fan: bool
    """Whether the fan is running."""
    regulator_mv: int
    """The 5 V regulator's voltage, in mV."""

    def __init__(
        self,
        overcurrent: tuple[bool, ...],
        temperature: int,
        fan: bool,
        regulator_mv: int,
    ) -> None:
        set_field = object.__setattr__
        set_field(self, "overcurrent", overcurrent)
        set_field(self, "temperature", temperature)
        set_field(self, "fan", fan)
        set_field(self, "regulator_mv", regulator_mv)


@frozen_record
class ButtonLatches(FrozenRecord):
    """The reply to ``BTN:START:GET?``: which start buttons were pressed since the last read."""

    internal: bool
    external: bool

    def __init__(self, internal: bool, external: bool) -> None:
        set_field = object.__setattr__
        set_field(self, "internal", internal)
        set_field(self, "external", external)

    @property
    def pressed(self) -> bool:
        """Whether either button was pressed."""
        return self.internal or self.external


def is_supported_version(version: str) -> bool:
    """Whether this codec speaks firmware ``version`` (4.4, or 4.4.<patch>)."""
    return version_matches(version, SUPPORTED_VERSIONS)


def parse_identity_reply(board: str, reply: bytes) -> Identity:
    """Return the identity in the reply to ``*IDN?``; the board type must be ``PBv4B``.

    :raises UnexpectedReplyError: the reply is not a power board's identity.
    """
    return parse_identity(board, reply, BOARD_TYPE)


def check_output(output: int) -> None:
    """Refuse a number that is not one of the power board's outputs.

    :raises ValueError: naming the outputs there are.
    """
    if output not in range(OUTPUT_COUNT):
        raise ValueError(
            f"the power board has outputs 0 to 6 (H0, H1, L0, L1, L2, L3, 5 V), not {output!r}",
        )


def encode_output_set(output: int, enabled: bool) -> bytes:
    """Return the command that switches ``output`` on or off.

    :raises ValueError: no such output.
    :raises NotSupportedByHardwareError: ``output`` is L2, the brain's output.
    """
    check_output(output)
    if output == BRAIN_OUTPUT:
        raise NotSupportedByHardwareError(
            "output L2 (4) powers the robot's brain: the power board does not let it be "
            "switched. Use another output for your devices.",
        )
    return command_line("OUT", output, "SET", int(enabled))


def encode_output_get(output: int) -> bytes:
    """Return the query of whether ``output`` is on.

    :raises ValueError: no such output.
    """
    check_output(output)
    return command_line("OUT", output, "GET?")


def encode_output_current(output: int) -> bytes:
    """Return the query of the current ``output`` draws, in mA.

    :raises ValueError: no such output.
    """
    check_output(output)
    return command_line("OUT", output, "I?")


def _led_name(led: int) -> str:
    if led not in range(len(LED_NAMES)):
        raise ValueError(f"the power board has LEDs 0 (run) and 1 (error), not {led!r}")
    return LED_NAMES[led]


def encode_led_set(led: int, mode: LEDMode) -> bytes:
    """Return the command that switches LED ``led`` (0 run, 1 error) off, on or to flashing.

    :raises ValueError: no such LED.
    """
    return command_line("LED", _led_name(led), "SET", _LED_VALUES[mode])


def encode_led_get(led: int) -> bytes:
    """Return the query of what LED ``led`` (0 run, 1 error) is doing.

    :raises ValueError: no such LED.
    """
    return command_line("LED", _led_name(led), "GET?")


def encode_note(duration: timedelta, frequency: float) -> bytes:
    """Return the command that plays ``frequency`` for ``duration``, replacing any note.

    The frequency and the duration in ms are rounded half to even.

    :raises NotSupportedByHardwareError: the frequency is outside 8 to 10000 Hz, or the
        duration rounds to less than 1 ms or more than 2³¹ - 1 ms.
    """
    hertz = round(frequency)
    if not MIN_FREQUENCY <= hertz <= MAX_FREQUENCY:
        raise NotSupportedByHardwareError(
            f"the power board's buzzer plays {MIN_FREQUENCY} to {MAX_FREQUENCY} Hz, "
            f"not {frequency} Hz",
        )
    milliseconds = round(duration / timedelta(milliseconds=1))
    if not 1 <= milliseconds <= MAX_NOTE_MS:
        raise NotSupportedByHardwareError(
            f"the power board plays notes of 1 to {MAX_NOTE_MS} ms, not {duration} "
            f"({milliseconds} ms)",
        )
    return command_line("NOTE", hertz, milliseconds)


def parse_output_state(board: str, command: bytes, reply: bytes) -> bool:
    """Return whether an output is on, from the reply to ``OUT:<n>:GET?``."""
    return parse_flag(board, command, reply)


def parse_current_ma(board: str, command: bytes, reply: bytes, *, signed: bool = False) -> int:
    """Return a current or voltage in mA / mV; negative only if ``signed`` (battery current)."""
    low = -_MAX_MILLI if signed else 0
    return parse_int(board, command, reply, low=low, high=_MAX_MILLI)


def parse_led_mode(board: str, command: bytes, reply: bytes) -> LEDMode:
    """Return the LED mode in the reply to ``LED:<name>:GET?`` (``0``, ``1`` or ``F``)."""
    check_not_nack(board, command, reply)
    try:
        return _LED_REPLIES[reply]
    except KeyError:
        raise unexpected_reply(board, command, reply, "'0', '1' or 'F'") from None


def parse_button(board: str, reply: bytes) -> ButtonLatches:
    """Return the start button latches in the reply to ``BTN:START:GET?`` (``<int>:<ext>``)."""
    check_not_nack(board, BUTTON, reply)
    fields = reply.split(b":")
    if len(fields) != 2 or any(field not in (b"0", b"1") for field in fields):
        raise unexpected_reply(board, BUTTON, reply, "'<internal 0/1>:<external 0/1>'")
    return ButtonLatches(fields[0] == b"1", fields[1] == b"1")


def parse_status(board: str, reply: bytes) -> PowerStatus:
    """Return the status in the reply to ``*STATUS?``.

    The reply is ``<oc0>,...,<oc6>:<temperature °C>:<fan 0/1>:<5 V regulator mV>``.
    """
    check_not_nack(board, STATUS, reply)
    expected = "'<7 comma-separated 0/1>:<°C>:<fan 0/1>:<regulator mV>'"
    fields = reply.split(b":")
    if len(fields) != 4:
        raise unexpected_reply(board, STATUS, reply, expected)
    latches = fields[0].split(b",")
    if len(latches) != OUTPUT_COUNT or any(flag not in (b"0", b"1") for flag in latches):
        raise unexpected_reply(board, STATUS, reply, expected)
    try:
        temperature = parse_int(
            board, STATUS, fields[1], low=_TEMPERATURE_RANGE[0], high=_TEMPERATURE_RANGE[1]
        )
        fan = parse_flag(board, STATUS, fields[2])
        regulator = parse_int(board, STATUS, fields[3], low=0, high=_MAX_MILLI)
    except UnexpectedReplyError:
        raise unexpected_reply(board, STATUS, reply, expected) from None
    return PowerStatus(tuple(flag == b"1" for flag in latches), temperature, fan, regulator)
