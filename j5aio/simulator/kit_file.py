"""Kit files: the simulated kit described as the team's own robot.

A team whose program names its boards by serial number
(``robot.motor_boards["SR0UK1L"]``) describes its robot in a small TOML file, and the
simulated kit then has those boards, with those serial numbers, wired as on the robot::

    # robot.toml
    based_on = "sr2023"        # optional: start from a named kit's boards
    time_scale = 0             # optional: 1.0 boots boards as slowly as the real ones

    [[board]]
    simulator = "sr-power-fw4"
    serial = "SRPB1X"

    [[board]]
    simulator = "sr-motor-fw4"
    serial = "SR0UK1L"
    output = "H0"              # the power board output feeding its 12 V

    [[board]]
    simulator = "sr-motor-fw4"
    serial = "SR0AB12"
    output = "H1"

Each ``[[board]]`` is one board: ``simulator`` is a simulator's name (``python -m j5aio
simulate --list`` lists them), ``serial`` its serial number (optional: the simulator's
numbering otherwise) and ``output`` the power output feeding it (optional, for motor and
servo boards: the default wiring otherwise; never ``L2``, the brain's). The boards listed
for a simulator replace the ``based_on`` kit's boards of that simulator; its other
boards stay.

Use it with ``python -m j5aio run --kit-file robot.toml program.py`` (also ``demo``),
with the ``J5AIO_KIT_FILE`` environment variable (which subprocesses and the
competition layers see), or from code: ``use_kit(load_kit_file("robot.toml"))``.
On the robot itself, where the boards are real, the file's wiring still names the
output to switch on when a board has no power.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Final

from j5aio.board_kinds import KitDefinition, get_kit, simulator_entries

__all__ = [
    "KIT_FILE_VARIABLE",
    "kit_file_from_environment",
    "load_kit_file",
    "parse_kit",
    "wiring_from_environment",
]

#: The environment variable naming a kit file; it wins over ``J5AIO_KIT``.
KIT_FILE_VARIABLE: Final = "J5AIO_KIT_FILE"

_TOP_KEYS: Final = frozenset({"based_on", "time_scale", "description", "board"})
_BOARD_KEYS: Final = frozenset({"simulator", "serial", "output"})


def _refuse_unknown(
    table: Mapping[str, object], known: frozenset[str], where: str, holder: str,
) -> None:
    """Refuse a setting of ``table`` that is not ``known``, naming those ``holder`` has."""
    unknown = sorted(set(table) - known)
    if unknown:
        raise ValueError(
            f"{where}unknown setting {', '.join(unknown)}; {holder} has "
            f"{', '.join(sorted(known))}"
        )


def load_kit_file(path: str | os.PathLike[str]) -> KitDefinition:
    """Read the kit file at ``path`` (see the module) and return its kit.

    :raises FileNotFoundError: there is no such file.
    :raises ValueError: it is not TOML, or says something a kit file cannot; the
        message names the file and what is allowed.
    """
    import tomllib  # (here: a program without a kit file never parses TOML)

    file = Path(path)
    try:
        data = tomllib.loads(file.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"kit file {file}: not valid TOML: {error}") from None
    try:
        return parse_kit(data, name=file.stem)
    except ValueError as error:
        raise ValueError(f"kit file {file}: {error}") from None


def time_scale_of(path: str | os.PathLike[str]) -> float | None:
    """The ``time_scale`` the kit file at ``path`` gives, or ``None`` if it gives none."""
    import tomllib

    data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    value = data.get("time_scale")
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or value < 0:
        raise ValueError(f"kit file {path}: time_scale must be a number of 0 or more")
    return float(value)


def parse_kit(data: Mapping[str, Any], *, name: str = "kit-file") -> KitDefinition:
    """The kit that the parsed contents of a kit file describe (the same in code).

    :param data: the file's contents, as ``tomllib`` gives them.
    :param name: the kit's name.
    :raises ValueError: the contents say something a kit file cannot.
    """
    _refuse_unknown(data, _TOP_KEYS, "", "a kit file")
    based_on = data.get("based_on")
    boards: dict[str, int] = {}
    wiring: dict[str, tuple[int | str, ...]] = {}
    description = str(data.get("description", f"the kit described in {name}"))
    if based_on is not None:
        if not isinstance(based_on, str):
            raise ValueError(f"based_on is a kit's name, not {based_on!r}")
        base = get_kit(based_on)
        boards = dict(base.boards)
        wiring = dict(base.wiring)
    listed = data.get("board", [])
    if not isinstance(listed, list) or not all(isinstance(b, dict) for b in listed):
        raise ValueError("each board is a [[board]] table")
    if not listed and based_on is None:
        raise ValueError("it lists no [[board]] and is based_on no kit: the kit would be empty")
    entries = simulator_entries()
    given: dict[str, list[dict[str, Any]]] = {}
    for number, board in enumerate(listed, start=1):
        _refuse_unknown(board, _BOARD_KEYS, f"board {number}: ", "a board")
        simulator = board.get("simulator")
        if simulator not in entries:
            raise ValueError(
                f"board {number}: simulator {simulator!r} does not exist; choose one of "
                f"{', '.join(entries)}"
            )
        given.setdefault(simulator, []).append(board)
    serials: dict[str, tuple[str, ...]] = {}
    for simulator, listed_boards in given.items():
        boards[simulator] = len(listed_boards)
        prefix = entries[simulator][1].serial_prefix
        serials[simulator] = tuple(
            str(board.get("serial", f"{prefix}{index}"))
            for index, board in enumerate(listed_boards)
        )
        outputs = [board.get("output") for board in listed_boards]
        if any(output is not None for output in outputs):
            if any(output is None for output in outputs):
                raise ValueError(
                    f"give every {simulator} board an output, or none (for the default wiring)"
                )
            wiring[simulator] = tuple(output for output in outputs if output is not None)
        else:
            wiring.pop(simulator, None)
    return KitDefinition(
        name.replace(" ", "-") or "kit-file",
        description,
        boards,
        wiring=wiring,
        serials=serials,
    )


def kit_file_from_environment() -> KitDefinition | None:
    """The kit of the file ``J5AIO_KIT_FILE`` names, or ``None`` when it is unset.

    :raises ValueError: the file cannot be read as a kit file (the message says why).
    """
    path = os.environ.get(KIT_FILE_VARIABLE, "").strip()
    if not path:
        return None
    try:
        return load_kit_file(path)
    except OSError as error:
        raise ValueError(f"{KIT_FILE_VARIABLE}={path!r}: {error}") from None


def wiring_from_environment() -> dict[str, int]:
    """The output feeding each board of the ``J5AIO_KIT_FILE`` kit, by serial number.

    Empty when no kit file is given, or it cannot be read.
    """
    from j5aio.power_outputs import output_number

    try:
        kit = kit_file_from_environment()
    except ValueError:
        return {}
    if kit is None:
        return {}
    feeding: dict[str, int] = {}
    for simulator, outputs in kit.wiring.items():
        for serial, output in zip(kit.serials.get(simulator, ()), outputs, strict=False):
            feeding[serial] = output_number(output)
    return feeding
