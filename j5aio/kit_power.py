"""Powering the kit's boards at start-up, and saying so when a board has no power.

On the Student Robotics kit the motor boards and the servo board take their 12 V from
the power board's outputs, which are off when the power board starts. Without it a
motor board's controller does not answer at all (only its USB-serial chip is powered
from USB), and a servo board answers but reports its 12 V missing. So
:class:`~j5aio.kit.KitRobot` does as sr-robot3 and sbot do: it finds the power board
first, switches on the outputs that feed the other boards (:data:`DEFAULT_POWER_ON`:
every output but L2, the brain's), waits :data:`POWER_UP_WAIT` seconds for those boards
to boot, and only then looks for them.

Afterwards, where j5aio can tell that a board has no power it warns with a
:class:`KitPowerWarning` naming the output to switch on: a motor board whose USB-serial
chip is there but whose controller stays silent, a servo board that reports no 12 V.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Mapping
from enum import Enum
from typing import Final

from j5aio import power_hints
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.power_hints import power_hint
from j5aio.power_outputs import BRAIN_OUTPUT, OUTPUT_NAMES, output_name, output_number

__all__ = [
    "DEFAULT_POWER_ON",
    "POWER_UP_WAIT",
    "KitPowerWarning",
    "PowerOnChoice",
    "boot_wait",
    "check_power_on",
    "feeding_outputs",
    "output_feeding",
    "outputs_to_switch_on",
    "power_hint",
    "power_up_message",
    "remember_feeding",
    "silent_motor_boards",
    "unpowered_simulated_boards",
    "warn_unpowered",
    "wire_simulated_kit",
]

#: The outputs switched on at start-up by default: every one but L2 (the brain's), as
#: sr-robot3 and sbot do. A firmware 3 power board has no 5 V output (6), so it is
#: skipped there.
DEFAULT_POWER_ON: Final = tuple(n for n in range(len(OUTPUT_NAMES)) if n != BRAIN_OUTPUT)

#: Seconds to wait, after switching outputs on, for the boards they feed to boot (on a
#: simulated kit, scaled by its time scale).
POWER_UP_WAIT: Final = 0.5

PowerOnChoice = bool | Iterable[int | str | Enum] | None
"""What to switch on at start-up: ``True`` or ``None`` for :data:`DEFAULT_POWER_ON`,
``False`` for nothing, or the outputs (names such as ``"H0"``, numbers, or the boards'
output enums such as ``PowerBoardOutput.H0``)."""


class KitPowerWarning(UserWarning):
    """A board of the kit seems to have no power: the message names the output to switch on."""


def check_power_on(power_on: object) -> tuple[int, ...]:
    """The output numbers a ``power_on`` choice asks for (see :data:`PowerOnChoice`).

    :raises TypeError: ``power_on`` is not a bool, ``None`` or an iterable of outputs.
    :raises ValueError: an output does not exist, or is L2: the brain's output is never
        switched by j5aio.
    """
    if power_on is None or power_on is True:
        return DEFAULT_POWER_ON
    if power_on is False:
        return ()
    if isinstance(power_on, str | bytes) or not isinstance(power_on, Iterable):
        raise TypeError(
            "power_on is True (every output but L2), False (none) or the outputs to "
            f"switch on, such as ['H0', 'L0']; not {power_on!r}"
        )
    chosen: list[int] = []
    for output in power_on:
        value = output.value if isinstance(output, Enum) else output  # an output enum, too
        number = output_number(value)
        if number == BRAIN_OUTPUT:
            raise ValueError(
                "power_on cannot include L2: it powers the brain, and the power board "
                "keeps it on by itself"
            )
        if number not in chosen:
            chosen.append(number)
    return tuple(chosen)


def outputs_to_switch_on(chosen: Iterable[int], board: PowerBoard) -> tuple[int, ...]:
    """The chosen outputs that ``board`` has (a firmware 3 board has no 5 V output)."""
    present = {output.identifier for output in board.outputs}
    return tuple(number for number in chosen if number in present)


#: The output feeding each board, by serial number, as the robots of this program found
#: it (see :func:`remember_feeding`).
_feeding_seen: dict[str, int] = {}


def remember_feeding(feeding: Mapping[str, int]) -> None:
    """Remember which output feeds each board (a robot starting does), for later messages."""
    _feeding_seen.update(feeding)


def output_feeding(serial_number: str) -> int | None:
    """The output feeding the board ``serial_number``, if this program knows it.

    From what a robot starting found (:func:`remember_feeding`), else from the kit file
    (``J5AIO_KIT_FILE``).
    """
    if serial_number in _feeding_seen:
        return _feeding_seen[serial_number]
    from j5aio.simulator.kit_file import wiring_from_environment

    return wiring_from_environment().get(serial_number)


def power_up_message(outputs: Iterable[int], wait: float) -> str:
    """What powering the kit up did, for people: the outputs switched on, and the wait."""
    names = ", ".join(output_name(number) for number in outputs)
    return (
        f"Switched on outputs {names} to power the kit's boards (L2 powers the brain); "
        f"waiting {wait:g} s for them to boot"
    )


def warn_unpowered(
    silent_motor_boards: Iterable[str],
    unpowered_servo_boards: Iterable[str],
    feeding: Mapping[str, int],
    *,
    missing_boards: Iterable[str] = (),
) -> list[str]:
    """Warn (:class:`KitPowerWarning`) about each board without power; return the messages.

    :param silent_motor_boards: serial numbers of motor boards whose USB-serial chip is
        plugged in but whose controller does not answer.
    :param unpowered_servo_boards: serial numbers of servo boards reporting no 12 V.
    :param feeding: the output feeding each board, by serial number, where it is known.
    :param missing_boards: other boards known to be there without power, which could
        not be reached (a simulated firmware 2 servo board, say), by serial number.
    """
    messages = [
        f"motor board {serial} is plugged in but does not answer: its 12 V input is off. "
        + power_hint(feeding.get(serial))
        for serial in silent_motor_boards
    ] + [
        f"servo board {serial} reports no 12 V, so its servos will not move. "
        + power_hint(feeding.get(serial))
        for serial in unpowered_servo_boards
    ] + [
        f"board {serial} has no power, so it could not be reached. "
        + power_hint(feeding.get(serial))
        for serial in missing_boards
    ]
    for message in messages:
        warnings.warn(message, KitPowerWarning, stacklevel=3)
    return messages


def unpowered_simulated_boards(environment: object) -> list[str]:
    """Serial numbers of the simulated kit's boards whose power output is off, if any."""
    kit = _simulated_kit_of(environment)
    if kit is None:
        return []
    from j5aio.simulator.kit import SimulatedKit

    assert isinstance(kit, SimulatedKit)
    wiring = kit.wiring
    if wiring is None:
        return []
    return [
        str(getattr(fed, "serial_number", "?")) for fed, _ in wiring.feeds if not fed.powered
    ]


#: The USB strings of the motor board's USB-serial chip, which is powered from USB.
_MOTOR_BOARD_USB: Final = ("Student Robotics", "MCV4B")


def _simulated_kit_of(environment: object) -> object | None:
    """The current simulated kit, if ``environment`` is the simulated environment."""
    import sys

    module = sys.modules.get("j5aio.simulator.environment")
    if module is None or environment is not getattr(module, "SIMULATED_ENVIRONMENT", None):
        return None
    from j5aio.simulator.kit import current_kit

    return current_kit()


def wire_simulated_kit(environment: object) -> None:
    """On the simulated kit, wire it now if it waited for a robot to start (see ``wire``).

    From then on its motor and servo boards take their 12 V from the power board's
    outputs, as on the robot.
    """
    kit = _simulated_kit_of(environment)
    if kit is not None:
        from j5aio.simulator.kit import SimulatedKit

        assert isinstance(kit, SimulatedKit)
        kit.wire()


def boot_wait(environment: object, seconds: float = POWER_UP_WAIT) -> float:
    """Seconds to wait for boards to boot after their outputs come on, in ``environment``.

    ``seconds`` on hardware; on the simulated kit, scaled by its time scale.
    """
    kit = _simulated_kit_of(environment)
    if kit is None:
        return seconds
    from j5aio.simulator.kit import SimulatedKit

    assert isinstance(kit, SimulatedKit)
    return seconds * kit.time_scale


def feeding_outputs(environment: object) -> dict[str, int]:
    """The output feeding each board, by serial number, where j5aio knows it.

    On the simulated kit, from its wiring; elsewhere from the kit file
    (``J5AIO_KIT_FILE``), if one is given.
    """
    kit = _simulated_kit_of(environment)
    if kit is not None:
        from j5aio.simulator.kit import SimulatedKit

        assert isinstance(kit, SimulatedKit)
        wiring = kit.wiring
        if wiring is None:
            return {}
        return {
            str(getattr(fed, "serial_number", "")): output for fed, output in wiring.feeds
        }
    from j5aio.simulator.kit_file import wiring_from_environment

    return wiring_from_environment()


async def silent_motor_boards(environment: object, found: Iterable[str]) -> list[str]:
    """Serial numbers of motor boards whose USB-serial chip is listed but that were not found.

    Ports are listed as the environment lists them: the simulated kit's, or the
    computer's for the hardware; another environment (the console) has none.
    """
    import anyio.to_thread

    from j5aio.backends.hardware.transports.discovery import PortInfo, list_serial_ports

    kit = _simulated_kit_of(environment)
    ports: list[PortInfo]
    if kit is not None:
        from j5aio.simulator.discovery import kit_discovery_options
        from j5aio.simulator.kit import SimulatedKit

        assert isinstance(kit, SimulatedKit)
        ports = list_serial_ports(kit_discovery_options(kit).port_source)
    elif _is_hardware(environment):
        ports = await anyio.to_thread.run_sync(list_serial_ports)
    else:
        return []
    known = set(found)
    return sorted(
        port.serial_number
        for port in ports
        if (port.manufacturer, port.product) == _MOTOR_BOARD_USB
        and port.serial_number
        and port.serial_number not in known
    )


def _is_hardware(environment: object) -> bool:
    from j5aio.environments import hardware_environment

    name = getattr(environment, "name", None)
    return name is not None and name == hardware_environment().name


# Backends name the output feeding a silent board (j5aio.power_hints) from this wiring.
power_hints.use_wiring(output_feeding)
