import math

import anyio
import pytest

from j5aio.components import Button, ButtonInterface

from .component_fakes import RecordingBackend


async def test_get_is_pressed_reads_the_button() -> None:
    backend = RecordingBackend()
    button = Button(2, backend)

    assert await button.get_is_pressed() is False
    backend.pressed.set()
    assert await button.get_is_pressed() is True
    assert backend.calls == [("get_button_state", (2,)), ("get_button_state", (2,))]


async def test_wait_until_pressed_returns_once_pressed() -> None:
    backend = RecordingBackend()
    button = Button(0, backend)
    finished = anyio.Event()

    async def wait() -> None:
        await button.wait_until_pressed()
        finished.set()

    async with anyio.create_task_group() as tg:
        tg.start_soon(wait)
        await anyio.wait_all_tasks_blocked()
        assert not finished.is_set()
        backend.pressed.set()
    assert finished.is_set()
    assert backend.calls == [("wait_until_button_pressed", (0,))]


async def test_wait_until_pressed_with_a_timeout_returns_when_pressed_in_time() -> None:
    backend = RecordingBackend()
    backend.pressed.set()
    await Button(0, backend).wait_until_pressed(timeout=5)
    assert backend.wait_cancelled is False


async def test_wait_until_pressed_raises_timeout_error_and_stops_waiting() -> None:
    backend = RecordingBackend()
    with pytest.raises(TimeoutError, match=r"not pressed within 0\.01 s; pass a longer timeout"):
        await Button(1, backend).wait_until_pressed(timeout=0.01)
    assert backend.wait_cancelled is True


async def test_wait_until_pressed_with_zero_timeout_times_out_at_once() -> None:
    backend = RecordingBackend()
    with pytest.raises(TimeoutError):
        await Button(1, backend).wait_until_pressed(timeout=0)


async def test_wait_until_pressed_is_cancellable() -> None:
    backend = RecordingBackend()
    button = Button(1, backend)

    with anyio.CancelScope() as scope:
        async with anyio.create_task_group() as tg:
            tg.start_soon(button.wait_until_pressed)
            await anyio.wait_all_tasks_blocked()
            scope.cancel()
    assert scope.cancelled_caught
    assert backend.wait_cancelled is True


@pytest.mark.parametrize("timeout", ["1", True, [1]])
async def test_wait_until_pressed_refuses_a_timeout_of_the_wrong_type(timeout: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=r"timeout must be None .* got"):
        await Button(1, backend).wait_until_pressed(timeout=timeout)  # type: ignore[arg-type]
    assert backend.calls == []


@pytest.mark.parametrize("timeout", [-1, -0.001, math.nan])
async def test_wait_until_pressed_refuses_a_negative_timeout(timeout: float) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"number of seconds that is 0 or more"):
        await Button(1, backend).wait_until_pressed(timeout=timeout)
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    assert Button(4, RecordingBackend()).identifier == 4
    assert Button.interface_class() is ButtonInterface
