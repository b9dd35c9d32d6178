"""sbot's number conversions and checks, so that values reach the boards as sbot sends them."""

from __future__ import annotations

__all__ = ["float_bounds_check", "map_to_float", "map_to_int"]


def map_to_int(x: float, in_min: float, in_max: float, out_min: int, out_max: int) -> int:
    """Map ``x`` from [in_min, in_max] onto [out_min, out_max], truncated to an int.

    sbot truncates (``int()``) rather than rounds; the compatibility layer does the same
    so that a program's values reach the board as the same numbers.
    """
    return int((x - in_min) * (out_max - out_min) / (in_max - in_min) + out_min)


def map_to_float(
    x: int, in_min: int, in_max: int, out_min: float, out_max: float, precision: int = 3,
) -> float:
    """Map ``x`` from [in_min, in_max] onto [out_min, out_max], rounded to ``precision``."""
    return round((x - in_min) * (out_max - out_min) / (in_max - in_min) + out_min, precision)


def float_bounds_check(value: object, min_val: float, max_val: float, err_msg: str) -> float:
    """Return ``value`` as a float if it lies in [min_val, max_val].

    :raises TypeError: ``value`` cannot be made a float (the message is ``err_msg``).
    :raises ValueError: it is outside the bounds, or NaN (the message is ``err_msg``).
    """
    try:
        new_val = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError) as error:
        raise TypeError(err_msg) from error
    if not min_val <= new_val <= max_val:
        raise ValueError(err_msg)
    return new_val
