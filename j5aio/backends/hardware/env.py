"""The hardware environment: the backends that find and drive each kind of real board.

Its backends are the hardware backends of the registered board kinds
(:func:`j5aio.board_kinds.board_kinds`): j5aio's own and those of installed plugins. Each
is imported the first time a board of its class is asked for.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from j5aio.backends._kinds import BoardKind, board_kinds
from j5aio.backends.environment import Environment

if TYPE_CHECKING:
    from j5aio.backends.backend import Backend

    #: Every hardware backend, in the order listing tries them (the registry's order).
    #: The SourceBots Arduino comes before the Ruggeduino: both use the same USB IDs.
    #: Reading it imports them all.
    HARDWARE_BACKENDS: tuple[type[Backend], ...]

__all__ = ["HARDWARE_BACKENDS", "HARDWARE_ENVIRONMENT"]


def _loader(kind: BoardKind) -> Callable[[], type[Backend]]:
    def load() -> type[Backend]:
        backend = kind.hardware
        assert backend is not None  # (only kinds with one are registered)
        return backend

    return load


def _make_environment() -> Environment:
    environment = Environment("HardwareEnvironment")
    for kind in board_kinds():
        if kind.backend_reference("hardware") is not None:
            environment.register_lazily(kind.board, _loader(kind))
    return environment


#: Real boards: SR v4 power (fw 3), motor (fw 3), servo (fw 2) boards and Ruggeduino
#: (fw 1), the SourceBots Arduino (2019 protocol), and every plugin's boards.
HARDWARE_ENVIRONMENT = _make_environment()


def __getattr__(name: str) -> Any:  # PEP 562: HARDWARE_BACKENDS, made on first use
    if name != "HARDWARE_BACKENDS":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = tuple(HARDWARE_ENVIRONMENT.backends)
    globals()[name] = value
    return value
