"""The power board's outputs by name, and which of them a kit switches on.

Outputs are named as printed on the SR v4 power board: ``H0``, ``H1`` (high current),
``L0`` to ``L3`` (low current; L2 powers the brain), and, on firmware 4, ``5V`` (the
5 V rail); they are numbered 0 to 6 in that order, as on the wire. Anywhere j5aio takes
an output from a person (a kit file, ``KitRobot(power_on=...)``), a name in any case or
a number will do.
"""

from __future__ import annotations

from typing import Final

__all__ = ["BRAIN_OUTPUT", "OUTPUT_NAMES", "output_name", "output_number"]

#: The outputs' names, by number.
OUTPUT_NAMES: Final = ("H0", "H1", "L0", "L1", "L2", "L3", "5V")
#: L2: the output that powers the brain; it feeds no board and is never switched by j5aio.
BRAIN_OUTPUT: Final = 4

_ALIASES: Final = {"FIVE_VOLT": 6}


def output_number(output: int | str, *, count: int = len(OUTPUT_NAMES)) -> int:
    """The number of a power board output given by name (``"H0"``) or number.

    :param output: the output: a name (``H0``, ``H1``, ``L0``, ``L1``, ``L2``, ``L3``,
        ``5V``; any case) or a number.
    :param count: how many outputs the power board has (6 on firmware 3, 7 on 4).
    :raises ValueError: there is no such output on the board.
    :raises TypeError: ``output`` is neither a name nor a number.
    """
    allowed = ", ".join(OUTPUT_NAMES[:count])
    if isinstance(output, str):
        name = output.strip().upper()
        number = _ALIASES.get(name, OUTPUT_NAMES.index(name) if name in OUTPUT_NAMES else -1)
    elif isinstance(output, int) and not isinstance(output, bool):
        number = output
    else:
        raise TypeError(
            f"a power output is a name ({allowed}) or a number, not {type(output).__name__}"
        )
    if not 0 <= number < count:
        raise ValueError(
            f"the power board has no output {output!r}: it has {allowed} (or 0 to {count - 1})"
        )
    return number


def output_name(number: int) -> str:
    """The name printed beside output ``number`` (``0`` is ``"H0"``)."""
    return OUTPUT_NAMES[number]
