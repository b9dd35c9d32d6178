"""The wrapper round every interface coroutine: its signature is read only when it is needed."""

from __future__ import annotations

import inspect
import logging
from collections.abc import Iterator, Sequence
from typing import Any

import pytest

from j5aio.backends.backend import CALL_OBSERVERS, Backend
from j5aio.boards.board import Board
from j5aio.components.component import Component, Interface
from j5aio.components.led import LEDInterface


class _Light(Component):
    def __init__(self, identifier: int, backend: LEDInterface) -> None:
        self._identifier = identifier

    @property
    def identifier(self) -> int:
        return self._identifier

    @classmethod
    def interface_class(cls) -> type[Interface]:
        return LEDInterface


class _LightBoard(Board):
    name = "Light Board"

    @staticmethod
    def supported_components() -> set[type[Component]]:
        return {_Light}

    async def make_safe(self) -> None:
        pass


def _make_backend_class() -> type[Any]:
    class LightBackend(LEDInterface, Backend):
        board = _LightBoard

        def __init__(self) -> None:
            self.states: dict[int, bool] = {}

        @classmethod
        async def discover(cls) -> Sequence[Board]:
            return []

        @property
        def firmware_version(self) -> str | None:
            return None

        async def get_led_state(self, identifier: int) -> bool:
            return self.states.get(identifier, False)

        async def set_led_state(self, identifier: int, state: bool) -> None:
            self.states[identifier] = state

    return LightBackend


@pytest.fixture
def calls() -> Iterator[list[tuple[Any, ...]]]:
    seen: list[tuple[Any, ...]] = []

    def observer(*call: Any) -> None:
        seen.append(call)

    CALL_OBSERVERS.append(observer)
    try:
        yield seen
    finally:
        CALL_OBSERVERS.remove(observer)


@pytest.fixture
def signatures_read(monkeypatch: pytest.MonkeyPatch) -> list[object]:
    """Every callable whose signature ``inspect.signature`` is asked for, in order."""
    read: list[object] = []
    real_signature = inspect.signature

    def counting_signature(target: Any, *args: Any, **kwargs: Any) -> inspect.Signature:
        read.append(target)
        return real_signature(target, *args, **kwargs)

    monkeypatch.setattr(inspect, "signature", counting_signature)
    return read


def test_making_a_backend_class_reads_no_signature(signatures_read: list[object]) -> None:
    backend_class = _make_backend_class()
    assert signatures_read == []
    assert getattr(backend_class.set_led_state, "__j5aio_logged__", False)


async def test_a_plain_call_reads_no_signature(
    monkeypatch: pytest.MonkeyPatch, calls: list[tuple[Any, ...]]
) -> None:
    backend = _make_backend_class()()
    monkeypatch.setattr(inspect, "signature", None)  # any use would fail the call
    await backend.set_led_state(1, True)
    assert calls == [(backend, "set_led_state", (1, True), None, None)]


async def test_keyword_calls_are_observed_in_order_every_time(
    calls: list[tuple[Any, ...]],
) -> None:
    backend = _make_backend_class()()
    await backend.set_led_state(state=True, identifier=2)
    await backend.set_led_state(state=False, identifier=3)  # the signature read once, kept
    assert [call[2] for call in calls] == [(2, True), (3, False)]


async def test_debug_log_names_the_arguments_of_each_call(
    caplog: pytest.LogCaptureFixture,
) -> None:
    backend = _make_backend_class()()
    with caplog.at_level(logging.DEBUG):
        await backend.set_led_state(4, True)
        assert await backend.get_led_state(identifier=4) is True
        await backend.set_led_state(4, state=False)
    messages = [record.getMessage() for record in caplog.records]
    assert "set_led_state(identifier=4, state=True)" in messages
    assert "get_led_state(identifier=4) -> True" in messages
    assert "set_led_state(identifier=4, state=False)" in messages


async def test_a_quiet_call_hands_over_the_backend_s_own_coroutine() -> None:
    backend_class = _make_backend_class()
    backend = backend_class()
    call = backend.set_led_state(5, True)  # nothing observed, logged or owed
    assert call.cr_code is inspect.unwrap(backend_class.set_led_state).__code__
    await call
    assert backend.states == {5: True}


async def test_an_observed_call_goes_through_the_wrapper(
    calls: list[tuple[Any, ...]],
) -> None:
    backend_class = _make_backend_class()
    backend = backend_class()
    observed = backend.set_led_state(6, True)
    assert observed.cr_code is not inspect.unwrap(backend_class.set_led_state).__code__
    await observed
    assert calls == [(backend, "set_led_state", (6, True), None, None)]


async def test_a_logged_call_goes_through_the_wrapper(caplog: pytest.LogCaptureFixture) -> None:
    backend_class = _make_backend_class()
    backend = backend_class()
    with caplog.at_level(logging.DEBUG):
        logged = backend.set_led_state(6, False)
        assert logged.cr_code is not inspect.unwrap(backend_class.set_led_state).__code__
        await logged
    assert "set_led_state(identifier=6, state=False)" in caplog.text


def test_interface_methods_are_still_known_as_coroutine_functions() -> None:
    from j5aio.syncgen._members import _is_coroutine_function

    backend_class = _make_backend_class()
    assert inspect.iscoroutinefunction(inspect.unwrap(backend_class.set_led_state))
    assert _is_coroutine_function(backend_class.set_led_state)


async def test_the_signature_is_read_once_for_every_observed_call(
    signatures_read: list[object], calls: list[tuple[Any, ...]]
) -> None:
    signatures_read.clear()  # (what pytest read setting up the test's fixtures)
    backend_class = _make_backend_class()
    backend = backend_class()
    await backend.set_led_state(state=True, identifier=7)
    await backend.set_led_state(identifier=8, state=False)
    await backend_class().set_led_state(state=True, identifier=9)
    assert signatures_read == [inspect.unwrap(backend_class.set_led_state)]
    assert [call[2] for call in calls] == [(7, True), (8, False), (9, True)]


def test_each_wrapper_is_one_function_holding_no_other() -> None:
    # (every backend class made on a start wraps each of its interface methods: what each
    # wrapper holds is paid for once per method on every start)
    backend_class = _make_backend_class()
    for name in ("get_led_state", "set_led_state"):
        wrapper = getattr(backend_class, name)
        held = [cell.cell_contents for cell in wrapper.__closure__ or ()]
        functions = [value for value in held if inspect.isfunction(value)]
        assert functions == [inspect.unwrap(wrapper)]


async def test_an_observer_is_told_of_a_failed_call_with_its_keyword_arguments(
    calls: list[tuple[Any, ...]],
) -> None:
    backend = _make_backend_class()()

    backend.states = None  # (the call then fails)
    with pytest.raises(TypeError):
        await backend.set_led_state(state=True, identifier=10)
    assert len(calls) == 1
    assert calls[0][:3] == (backend, "set_led_state", (10, True))
    assert calls[0][3] is None and isinstance(calls[0][4], TypeError)
