"""Checks of user input shared by the components.

Each check raises ``TypeError`` for a value of the wrong type and ``ValueError`` for a
value out of range, with a message that names the quantity, says what is allowed and
shows what was given. Nothing here talks to a backend.
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING, TypeGuard

if TYPE_CHECKING:
    from numbers import Real

__all__ = ["check_bool", "check_number", "check_timeout", "describe"]


def describe(value: object) -> str:
    """Show ``value`` and its type, for the "got ..." part of an error message."""
    return f"{value!r} (a {type(value).__name__})"


def check_bool(value: object, *, name: str, allowed: str) -> bool:
    """Return ``value`` if it is a bool.

    :param value: what the user gave.
    :param name: what the value is, e.g. ``"LED state"``.
    :param allowed: the allowed values in words, e.g. ``"True (on) or False (off)"``.
    :raises TypeError: ``value`` is not a bool (``1`` and ``0`` are refused too).
    """
    if not isinstance(value, bool):
        raise TypeError(f"{name} must be {allowed}; got {describe(value)}")
    return value


def check_number(
    value: object, *, name: str, low: float, high: float, allowed: str,
) -> float:
    """Return ``value`` as a float if it is a number in ``[low, high]``.

    :param value: what the user gave.
    :param name: what the value is, e.g. ``"motor power"``.
    :param low: the smallest allowed value.
    :param high: the largest allowed value.
    :param allowed: the allowed values in words, e.g. ``"a float between -1 and 1"``.
    :raises TypeError: ``value`` is not a real number, or is a bool.
    :raises ValueError: ``value`` is NaN or outside ``[low, high]``.
    """
    if isinstance(value, bool) or not _is_real(value):
        raise TypeError(f"{name} must be {allowed}; got {describe(value)}")
    try:
        number = float(value)
    except OverflowError:  # an int too large for a float is certainly out of range
        number = math.inf
    if not low <= number <= high:  # also false for NaN
        raise ValueError(f"{name} must be {allowed}; got {value!r}")
    return number


def _is_real(value: object) -> TypeGuard[Real]:
    """Whether ``value`` is a :class:`numbers.Real`, importing :mod:`numbers` for nothing else.

    An int or a float is one. Any other type is one only once registered with (or derived
    from) ``numbers.Real``, which needs :mod:`numbers` imported: while it is not, nothing
    else can be one, and a program that passes ints and floats never imports it.
    """
    if isinstance(value, int | float):
        return True
    numbers = sys.modules.get("numbers")
    return numbers is not None and isinstance(value, numbers.Real)


def check_timeout(timeout: object) -> float | None:
    """Return ``timeout`` if it is ``None`` or a number of seconds that is not negative.

    :raises TypeError: ``timeout`` is neither ``None`` nor a number (or is a bool).
    :raises ValueError: ``timeout`` is negative or NaN.
    """
    if timeout is None:
        return None
    return check_number(
        timeout,
        name="timeout",
        low=0.0,
        high=math.inf,
        allowed="None (wait for ever) or a number of seconds that is 0 or more",
    )
