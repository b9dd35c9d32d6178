"""A tiny board and backend for testing the framework core."""

from __future__ import annotations

from collections.abc import Sequence

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.components.component import Component, Interface
from j5aio.components.led import LEDInterface


class Lamp(Component):
    """A component needing the LED interface."""

    def __init__(self, identifier: int, backend: LEDInterface) -> None:
        self._identifier = identifier
        self._backend = backend

    @property
    def identifier(self) -> int:
        return self._identifier

    @classmethod
    def interface_class(cls) -> type[Interface]:
        return LEDInterface


class LampBoard(Board):
    """A board with one lamp; made safe by switching it off."""

    name = "Lamp Board"

    def __init__(self, serial_number: str, backend: LampBackend) -> None:
        super().__init__(serial_number, backend)
        self.lamp_backend = backend
        self.setup_calls = 0
        self.safe_calls = 0

    @staticmethod
    def supported_components() -> set[type[Component]]:
        return {Lamp}

    async def _setup(self) -> None:
        self.setup_calls += 1

    async def make_safe(self) -> None:
        self.safe_calls += 1
        await self.lamp_backend.set_led_state(0, False)


class LampBackend(LEDInterface, Backend):
    """Finds the boards listed in ``serials``; remembers LED states."""

    board = LampBoard
    serials: Sequence[str] = ("B", "A")

    def __init__(self) -> None:
        self.states: dict[int, bool] = {0: True}
        self.closed = False

    @classmethod
    async def discover(cls) -> Sequence[Board]:
        return [LampBoard(serial, cls()) for serial in cls.serials]

    @property
    def firmware_version(self) -> str | None:
        return "1.0"

    async def get_led_state(self, identifier: int) -> bool:
        return self.states[identifier]

    async def set_led_state(self, identifier: int, state: bool) -> None:
        self.states[identifier] = state

    async def close(self) -> None:
        self.closed = True
