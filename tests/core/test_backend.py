from __future__ import annotations

import logging
from collections.abc import Sequence

import pytest

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.errors import NotSupportedByHardwareError

from .conftest import LampBackend, LampBoard


def test_backend_missing_an_interface_is_refused_naming_it() -> None:
    with pytest.raises(TypeError, match=r"LEDInterface \(for Lamp\)"):

        class Incomplete(Backend):
            board = LampBoard

            @classmethod
            async def discover(cls) -> Sequence[Board]:
                return []

            @property
            def firmware_version(self) -> str | None:
                return None


def test_abstract_intermediate_backend_is_not_checked() -> None:
    class Partial(Backend):
        board = LampBoard  # abstract: discover is missing

    assert Partial.board is LampBoard


async def test_attach_is_refused_by_default() -> None:
    with pytest.raises(NotSupportedByHardwareError, match="cannot attach"):
        await LampBackend.attach("/dev/ttyUSB0")


async def test_interface_calls_are_logged_at_debug(caplog: pytest.LogCaptureFixture) -> None:
    backend = LampBackend()
    with caplog.at_level(logging.DEBUG):
        await backend.set_led_state(0, False)
        assert await backend.get_led_state(0) is False
    messages = [r.getMessage() for r in caplog.records]
    assert "set_led_state(identifier=0, state=False)" in messages
    assert "get_led_state(identifier=0) -> False" in messages


async def test_default_close_does_nothing() -> None:
    class Quiet(LampBackend):
        pass

    await Backend.close(Quiet())
