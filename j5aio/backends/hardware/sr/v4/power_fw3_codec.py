"""The SR v4 power board's USB control-transfer protocol, firmware 3: pure encode and parse.

Every request is a vendor control transfer with ``bRequest`` 64 whose ``wIndex`` names
the command. Reads return little-endian unsigned integers; writes carry their argument
in ``wValue`` (the piezo carries ``<HH`` samples as data). The board stalls (errno 32)
on anything it does not understand, including a full piezo queue.

This module does no I/O: the hardware backend and the power board simulator both use it.
"""

from __future__ import annotations

import struct
from typing import TYPE_CHECKING, Final

from j5aio._lazy import lazy_exports
from j5aio._records import FrozenRecord, frozen_record
from j5aio.errors import NotSupportedByHardwareError, UnexpectedReplyError

if TYPE_CHECKING:
    from j5aio._timedelta import timedelta
    from j5aio.backends.hardware.sr.v4._power_fw3_battery import BatteryReading as BatteryReading

__all__ = [
    "BATTERY",
    "BUTTON",
    "ERROR_LED_WRITE",
    "FIRMWARE_VERSION",
    "OUTPUT_COUNT",
    "PID",
    "PIEZO_QUEUE_LENGTH",
    "PIEZO_WRITE",
    "REQUEST",
    "RUN_LED_WRITE",
    "SUPPORTED_VERSIONS",
    "VID",
    "BatteryReading",
    "ReadCommand",
    "check_led",
    "check_output",
    "encode_piezo_note",
    "led_write_index",
    "output_current_read",
    "parse_battery",
    "parse_u32",
]

#: USB vendor id (University of Southampton).
VID: Final = 0x1BDA
#: USB product id of the power board.
PID: Final = 0x0010
#: The ``bRequest`` of every transfer.
REQUEST: Final = 64
#: The firmware versions this codec speaks.
SUPPORTED_VERSIONS: Final = ("3",)
#: Outputs H0, H1, L0, L1, L2, L3 are numbered 0 to 5.
OUTPUT_COUNT: Final = 6
#: How many notes the firmware can hold queued.
PIEZO_QUEUE_LENGTH: Final = 31


# (It writes its own ``__init__`` and takes freezing, ``__repr__``, ``__eq__`` and
# ``__hash__`` from FrozenRecord, as ``@dataclass(frozen=True)`` would make them: the
# default kit imports it, and making the generated ones costs a quarter of a millisecond.
# A test checks them against those.)
@frozen_record
class ReadCommand(FrozenRecord):
    """A read request: the ``wIndex`` to ask and how many bytes the board answers."""

    index: int
    length: int

    def __init__(self, index: int, length: int) -> None:
        object.__setattr__(self, "index", index)
        object.__setattr__(self, "length", length)


#: Battery current then voltage, ``<II`` in mA and mV.
BATTERY: Final = ReadCommand(7, 8)
#: The start button's level, ``<I``; non-zero when pressed.
BUTTON: Final = ReadCommand(8, 4)
#: The firmware version, ``<I``.
FIRMWARE_VERSION: Final = ReadCommand(9, 4)

#: ``wIndex`` of the RUN LED write.
RUN_LED_WRITE: Final = 6
#: ``wIndex`` of the ERROR LED write.
ERROR_LED_WRITE: Final = 7
#: ``wIndex`` of the piezo write.
PIEZO_WRITE: Final = 8

_U16_MAX = 0xFFFF


def check_output(output: int) -> None:
    """Refuse a number that is not one of the power board's outputs (0 to 5).

    :raises ValueError: naming the outputs there are.
    """
    if output not in range(OUTPUT_COUNT):
        raise ValueError(f"the power board has outputs 0 to 5, not {output!r}")


def output_current_read(output: int) -> ReadCommand:
    """Return the read request for the current of ``output`` (0 to 5), in mA.

    :raises ValueError: no such output.
    """
    check_output(output)
    return ReadCommand(output, 4)


def check_led(led: int) -> None:
    """Refuse a number that is not one of the power board's LEDs (0 is RUN, 1 is ERROR).

    :raises ValueError: naming the LEDs there are.
    """
    if led not in (0, 1):
        raise ValueError(f"the power board has LEDs 0 (run) and 1 (error), not {led!r}")


def led_write_index(led: int) -> int:
    """Return the ``wIndex`` that writes LED ``led`` (0 is RUN, 1 is ERROR).

    :raises ValueError: no such LED.
    """
    check_led(led)
    return RUN_LED_WRITE if led == 0 else ERROR_LED_WRITE


def parse_u32(data: bytes) -> int:
    """Return the little-endian unsigned 32-bit integer of a 4-byte reply.

    :raises UnexpectedReplyError: the reply is not 4 bytes long.
    """
    if len(data) != 4:
        raise UnexpectedReplyError(f"expected a 4-byte reply, got {len(data)} bytes: {data!r}")
    (value,) = struct.unpack("<I", data)
    return int(value)


def parse_battery(data: bytes) -> BatteryReading:
    """Return the battery reading of an 8-byte reply (current first, then voltage).

    :raises UnexpectedReplyError: the reply is not 8 bytes long.
    """
    if len(data) != 8:
        raise UnexpectedReplyError(
            f"expected an 8-byte battery reply, got {len(data)} bytes: {data!r}",
        )
    from j5aio.backends.hardware.sr.v4._power_fw3_battery import BatteryReading

    current, voltage = struct.unpack("<II", data)
    return BatteryReading(int(current), int(voltage))


def encode_piezo_note(duration: timedelta, frequency: float) -> bytes:
    """Return one piezo sample, ``<HH`` (frequency Hz, duration ms), both rounded half to even.

    :raises NotSupportedByHardwareError: the rounded frequency or duration does not fit
        in 16 bits (at most 65535 Hz and 65535 ms).
    :raises ValueError: a negative frequency or duration.
    """
    from j5aio._timedelta import timedelta  # (its C module is loaded at a first note)

    duration_ms = round(duration / timedelta(milliseconds=1))
    frequency_hz = round(frequency)
    if duration_ms < 0 or frequency_hz < 0:
        raise ValueError(
            f"a piezo note needs a positive duration and pitch, not {duration} at {frequency} Hz",
        )
    if duration_ms > _U16_MAX:
        raise NotSupportedByHardwareError(
            f"the power board can buzz for at most 65535 ms, not {duration_ms} ms",
        )
    if frequency_hz > _U16_MAX:
        raise NotSupportedByHardwareError(
            f"the power board can buzz at most 65535 Hz, not {frequency_hz} Hz",
        )
    return struct.pack("<HH", frequency_hz, duration_ms)


# The battery's reading is made only when a program reads the battery: its class is
# defined in its own module, imported the first time the name is used.
if not TYPE_CHECKING:
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {"j5aio.backends.hardware.sr.v4._power_fw3_battery": ["BatteryReading"]},
    )
