"""The exceptions raised by j5aio.

Everything j5aio raises on purpose derives from :class:`J5AIOError`, except where a
built-in exception says it better (``TypeError`` and ``ValueError`` for bad user input,
``KeyError`` / ``IndexError`` for lookups, ``OSError`` for the robot lock).

The hierarchy::

    J5AIOError
    ├── CommunicationError                  talking to a board failed
    │   ├── BoardDisconnectionError         the board (or its port) went away
    │   │   └── GameOverError               the match is over: no board can be opened
    │   ├── CommunicationTimeoutError       the board did not answer in time
    │   ├── EarlierCommandError             a command acknowledged later had failed
    │   ├── USBCommunicationError           a USB transfer failed (carries the pyusb error)
    │   ├── DeviceMissingSerialNumberError  a board without a serial number was found
    │   ├── UnexpectedReplyError            the board answered something we cannot parse
    │   └── UnsupportedFirmwareError        the board runs firmware we cannot drive
    ├── NotSupportedByHardwareError         the hardware cannot do what was asked
    ├── NotSupportedByComponentError        the component cannot do what was asked
    └── BadGPIOPinModeError                 a pin operation in the wrong pin mode
    UnableToObtainLock (OSError)            another robot program is already running
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = [
    "BadGPIOPinModeError",
    "BoardDisconnectionError",
    "CommunicationError",
    "CommunicationTimeoutError",
    "DeviceMissingSerialNumberError",
    "EarlierCommandError",
    "GameOverError",
    "J5AIOError",
    "NotSupportedByComponentError",
    "NotSupportedByHardwareError",
    "USBCommunicationError",
    "UnableToObtainLock",
    "UnexpectedReplyError",
    "UnsupportedFirmwareError",
]


class J5AIOError(Exception):
    """The base class of every error that j5aio raises on purpose."""


class CommunicationError(J5AIOError):
    """Talking to a board failed.

    Raised when a board does not answer, answers something unexpected, or its port
    fails. A more specific subclass is raised where one fits, so ``except
    CommunicationError`` catches every way a board can misbehave.
    """


class BoardDisconnectionError(CommunicationError):
    """The board, or the port it was reached through, has gone away.

    Check the USB cable and the board's power, then run the program again.
    """


class GameOverError(BoardDisconnectionError):
    """The match is over: no board can be opened or driven any more.

    Raised when a program asks for boards after game over; the process is ending.
    """


class CommunicationTimeoutError(CommunicationError):
    """The board did not answer within the time allowed."""


class EarlierCommandError(CommunicationError):
    """A command that was sent earlier, and returned before its acknowledgement, failed.

    Raised only while acknowledgements are confirmed later (see
    :func:`j5aio.backends.acknowledgements.acknowledge_later`): the board refused the
    earlier command, or did not acknowledge it in time, and this was found when its
    acknowledgement was read, before the board's next request (which was not sent).

    :param message: what failed, naming the earlier command.
    :param command: the bytes of the earlier command.
    """

    def __init__(self, message: str, command: bytes) -> None:
        super().__init__(message)
        self.command = command


class USBCommunicationError(CommunicationError):
    """A USB transfer to a board failed.

    :param message: what failed, naming the board.
    :param usb_error: the exception pyusb raised, kept for inspection.
    """

    def __init__(self, message: str, usb_error: BaseException | None = None) -> None:
        super().__init__(message)
        self.usb_error = usb_error

    @property
    def errno(self) -> int | None:
        """The errno of the underlying USB error, if it had one."""
        return getattr(self.usb_error, "errno", None)


class DeviceMissingSerialNumberError(CommunicationError):
    """A board was found that does not report a serial number, so it cannot be told apart."""


class UnexpectedReplyError(CommunicationError):
    """A board sent a reply that does not fit its protocol."""


class UnsupportedFirmwareError(CommunicationError):
    """A board runs a firmware version that this backend cannot drive.

    :param board: the human name of the board.
    :param found: the version the board reported.
    :param supported: the versions this backend supports.
    """

    def __init__(self, board: str, found: str, supported: Iterable[str]) -> None:
        self.board = board
        self.found = found
        self.supported = tuple(supported)
        allowed = ", ".join(self.supported)
        super().__init__(
            f"{board} reports firmware version {found!r}, but this backend supports only "
            f"{allowed}. Update the board's firmware or use a backend for that version.",
        )


class NotSupportedByHardwareError(J5AIOError):
    """The hardware cannot do what was asked (for example, a servo board that cannot unpower a servo)."""  # noqa: E501


class NotSupportedByComponentError(J5AIOError):
    """The component cannot do what was asked (for example, a pin mode the pin lacks)."""


class BadGPIOPinModeError(J5AIOError):
    """A GPIO pin operation was attempted while the pin is in a mode that does not allow it.

    Set ``pin.mode`` (``await pin.set_mode(...)``) to a suitable mode first.
    """


class UnableToObtainLock(OSError):  # noqa: N818 - the name j5 users know
    """Another robot is already running on this machine.

    Only one robot program may drive the boards at a time. Stop the other program (or
    close the other robot) and try again.
    """
