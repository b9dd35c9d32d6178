"""sr-robot3's small helpers: board identities, ``singular``, number checks and mappings."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple, TypeVar

__all__ = [
    "BoardIdentity",
    "float_bounds_check",
    "list_ports",
    "map_to_float",
    "map_to_int",
    "singular",
]

T = TypeVar("T")


class BoardIdentity(NamedTuple):
    """Who a board says it is: the four fields of its ``*IDN?`` answer.

    :param manufacturer: who made the board.
    :param board_type: the board's short name, such as ``PBv4B``.
    :param asset_tag: the asset tag (serial number) printed on the board.
    :param sw_version: the firmware's version.
    """

    manufacturer: str = ""
    board_type: str = ""
    asset_tag: str = ""
    sw_version: str = ""


def singular(container: Mapping[str, T]) -> T:
    """Return the only board of a mapping of boards.

    :raises RuntimeError: there is not exactly one.
    """
    length = len(container)
    if length == 1:
        return next(iter(container.values()))
    if length == 0:
        raise RuntimeError("No boards of this type found")
    raise RuntimeError(f"expected only one to be connected, but found {length}")


def float_bounds_check(value: Any, min_val: float, max_val: float, err_msg: str) -> float:
    """Return ``value`` as a float if it is within ``[min_val, max_val]``.

    :raises TypeError: ``value`` cannot be made a float (the message is ``err_msg``).
    :raises ValueError: it is outside the bounds (the message is ``err_msg``).
    """
    try:
        new_value = float(value)
    except (ValueError, TypeError) as error:
        raise TypeError(err_msg) from error
    if not min_val <= new_value <= max_val:
        raise ValueError(err_msg)
    return new_value


def map_to_int(x: float, in_min: float, in_max: float, out_min: int, out_max: int) -> int:
    """Map ``x`` from one range onto another and truncate it to an int, as sr-robot3 does."""
    return int((x - in_min) * (out_max - out_min) / (in_max - in_min) + out_min)


def map_to_float(
    x: int, in_min: int, in_max: int, out_min: float, out_max: float, precision: int = 3,
) -> float:
    """Map ``x`` from one range onto another, rounded to ``precision`` places."""
    return round((x - in_min) * (out_max - out_min) / (in_max - in_min) + out_min, precision)


def list_ports() -> None:
    """Print every USB serial port: ``VID:PID - Manufacturer - Product - Serial Number``."""
    from serial.tools.list_ports import comports

    print("VID:PID - Manufacturer - Product - Serial Number")
    for port in comports():
        if port.vid and port.pid:
            print(
                f"{port.vid:04X}:{port.pid:04X} - {port.manufacturer} - {port.product} "
                f"- {port.serial_number}"
            )
