"""What to tell a person about a board that seems to have no power: the output to switch on.

A backend whose board stops answering because it lost its 12 V (a firmware 4 motor board)
says which power board output feeds it. It cannot know the kit's wiring itself: that is
known above the backends (what a robot found when it started, or the ``J5AIO_KIT_FILE``
kit file: :mod:`j5aio.kit_power`). So the layer that knows hands its lookup to this
module (:func:`use_wiring`, which importing :mod:`j5aio.kit_power` does), and a backend
asks :func:`output_feeding`, which knows nothing until then.
"""

from __future__ import annotations

from collections.abc import Callable

from j5aio.power_outputs import output_name

__all__ = ["output_feeding", "power_hint", "use_wiring"]

#: The output feeding a board, by its serial number, as the kit knows it (None: unknown).
_wiring: Callable[[str], int | None] | None = None


def use_wiring(lookup: Callable[[str], int | None]) -> None:
    """Find the output feeding a board with ``lookup(serial_number)`` from now on.

    :raises TypeError: ``lookup`` is not callable.
    """
    global _wiring
    if not callable(lookup):
        raise TypeError(f"the wiring lookup must be a callable, not {lookup!r}")
    _wiring = lookup


def output_feeding(serial_number: str) -> int | None:
    """The number of the output feeding the board ``serial_number``, or ``None`` if unknown."""
    return None if _wiring is None else _wiring(serial_number)


def power_hint(output: int | None) -> str:
    """What to do about a board without power, naming ``output`` if it is known."""
    if output is None:
        return (
            "Switch on the power board output that feeds its 12 V input (KitRobot switches "
            "on every output but L2 unless power_on says otherwise), and check the cable"
        )
    name = output_name(output)
    return (
        f"Switch on power board output {name}, which feeds it (KitRobot(power_on=...) "
        f"or robot.power_board.outputs[{output}].is_enabled = True)"
    )
