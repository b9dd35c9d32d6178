"""The boards' ``*STATUS?`` answers, as both peers read them (each subclasses these)."""

from __future__ import annotations

from typing import NamedTuple, Self

__all__ = ["MotorBoardStatus", "PowerBoardStatus", "ServoBoardStatus"]


def _flags(text: str) -> tuple[bool, ...]:
    """A comma-separated list of ``0`` / ``1`` flags."""
    return tuple(flag == "1" for flag in text.split(","))


class PowerBoardStatus(NamedTuple):
    """The power board's status: output trips, temperature (°C), fan, 5 V regulator (V)."""

    overcurrent: tuple[bool, ...]
    temperature: int
    fan_running: bool
    regulator_voltage: float
    other: list[str] = []

    @classmethod
    def from_status_response(cls, response: str) -> Self:
        """Read the board's answer to ``*STATUS?``: ``<trips>:<°C>:<fan>:<mV>[:...]``.

        :raises ValueError: the answer is not of that form.
        """
        trips, temperature, fan, millivolts, *other = response.split(":")
        return cls(
            overcurrent=_flags(trips),
            temperature=int(temperature),
            fan_running=fan == "1",
            regulator_voltage=float(millivolts) / 1000,
            other=other,
        )


class MotorBoardStatus(NamedTuple):
    """The motor board's status: a fault flag per motor, and its input voltage (V)."""

    output_faults: tuple[bool, ...]
    input_voltage: float
    other: list[str] = []

    @classmethod
    def from_status_response(cls, response: str) -> Self:
        """Read the board's answer to ``*STATUS?``: ``<faults>:<mV>[:...]``.

        :raises ValueError: the answer is not of that form.
        """
        faults, millivolts, *other = response.split(":")
        return cls(_flags(faults), float(millivolts) / 1000, other)


class ServoBoardStatus(NamedTuple):
    """The servo board's status: whether its watchdog fired, whether its supply is good."""

    watchdog_failed: bool
    power_good: bool

    @classmethod
    def from_status_response(cls, response: str) -> Self:
        """Read the board's answer to ``*STATUS?``: ``<watchdog failed>:<power good>``.

        :raises IndexError: the answer has fewer than two fields.
        """
        fields = response.split(":")
        return cls(watchdog_failed=fields[0] == "1", power_good=fields[1] == "1")
