from __future__ import annotations

import math
from datetime import timedelta

import anyio
import pytest

from j5aio.boards.board_group import BoardGroup
from j5aio.boards.sr.v4 import PowerBoard, PowerOutputGroup, PowerOutputPosition
from j5aio.components import LED, BatterySensor, Button, Piezo, PowerOutput
from j5aio.errors import CommunicationError

from .board_fakes import FakePowerBoardBackend


def make_board() -> tuple[PowerBoard, FakePowerBoardBackend]:
    backend = FakePowerBoardBackend()
    return PowerBoard("PB1", backend), backend


def test_identity() -> None:
    board, backend = make_board()
    assert PowerBoard.name == "Student Robotics v4 Power Board"
    assert board.serial_number == "PB1"
    assert board.firmware_version == "fake-1"
    assert board.backend is backend
    assert repr(board) == "<PowerBoard serial_number='PB1'>"
    assert PowerBoard.supported_components() == {PowerOutput, Piezo, Button, BatterySensor, LED}


def test_output_positions_are_the_wire_numbers() -> None:
    assert [(p.name, p.value) for p in PowerOutputPosition] == [
        ("H0", 0), ("H1", 1), ("L0", 2), ("L1", 3), ("L2", 4), ("L3", 5),
    ]


def test_components() -> None:
    board, _ = make_board()
    assert isinstance(board.outputs, PowerOutputGroup)
    assert len(board.outputs) == 6
    for position in PowerOutputPosition:
        assert board.outputs[position].identifier == position.value
    assert [output.identifier for output in board.outputs] == [0, 1, 2, 3, 4, 5]
    assert board.piezo.identifier == 0
    assert board.start_button.identifier == 0
    assert board.battery_sensor.identifier == 0
    assert board.run_led.identifier == 0
    assert board.error_led.identifier == 1
    # also reachable where j5 keeps them
    assert board._run_led is board.run_led
    assert board._error_led is board.error_led


@pytest.mark.parametrize(
    "attribute",
    ["outputs", "piezo", "start_button", "battery_sensor", "run_led", "error_led"],
)
def test_components_are_read_only(attribute: str) -> None:
    board, _ = make_board()
    with pytest.raises(AttributeError):
        setattr(board, attribute, None)


async def test_components_reach_the_backend() -> None:
    board, backend = make_board()
    await board.outputs[PowerOutputPosition.L2].set_is_enabled(True)
    await board.error_led.set_state(True)
    await board.piezo.buzz(0.25, 440)
    assert backend.outputs == {4: True}
    assert backend.leds == {1: True}
    assert backend.named("buzz") == [(0, timedelta(seconds=0.25), 440.0)]
    assert await board.battery_sensor.get_voltage() == 12.0


async def test_make_safe_powers_every_output_off() -> None:
    board, backend = make_board()
    await board.outputs.power_on()
    await board.make_safe()
    assert backend.outputs == dict.fromkeys(range(6), False)
    assert backend.named("set_power_output_enabled")[-6:] == [(i, False) for i in range(6)]


async def test_setup_registers_without_touching_the_hardware() -> None:
    board, backend = make_board()
    await board.setup()
    assert board in PowerBoard.BOARDS
    assert backend.calls == []


async def test_board_group_through_discovery() -> None:
    group = await BoardGroup.get_board_group(PowerBoard, FakePowerBoardBackend)
    assert group.singular().serial_number == "FAKE1"


class RecordedSleeps:
    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.durations: list[float] = []
        self._real_sleep = anyio.sleep
        monkeypatch.setattr(anyio, "sleep", self.sleep)

    async def sleep(self, delay: float) -> None:
        self.durations.append(delay)
        await self._real_sleep(0)


async def test_wait_for_start_flash_looks_every_50ms_like_j5_on_a_backend_that_asks(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    board, backend = make_board()
    monkeypatch.setattr(type(backend), "WAITS_FOR_PRESSES", False)  # as the console
    backend.pressed_on_poll = 20
    sleeps = RecordedSleeps(monkeypatch)

    await board.wait_for_start_flash()

    assert backend.button_polls == 20
    assert sleeps.durations == [0.05] * 19
    # (led, state, looks seen when it changed): before looks 1, 7, 13 and 19 the LED
    # toggles, starting with on; once pressed it is left on.
    assert backend.named("set_led_state") == [
        (0, True, 1), (0, False, 7), (0, True, 13), (0, False, 19), (0, True, 20),
    ]
    assert backend.named("wait_until_button_pressed") == []


async def test_wait_for_start_flash_toggles_every_0_3_s_until_pressed(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    board, backend = make_board()
    backend.press = anyio.Event()
    sleeps = RecordedSleeps(monkeypatch)
    original = backend.set_led_state

    async def set_led_state(identifier: int, state: bool) -> None:
        await original(identifier, state)
        assert backend.press is not None
        if len(backend.named("set_led_state")) == 4:
            backend.press.set()  # pressed after the fourth change

    monkeypatch.setattr(backend, "set_led_state", set_led_state)
    await board.wait_for_start_flash()

    assert backend.named("wait_until_button_pressed") == [(0,)]  # the backend waits
    changes = [state for _, state, _ in backend.named("set_led_state")]
    assert changes[:4] == [True, False, True, False]  # toggling, starting with on...
    assert changes[-1] is True  # ...and left on once pressed
    assert sleeps.durations == [pytest.approx(0.3)] * len(sleeps.durations)
    assert sleeps.durations
    assert backend.leds[0] is True


async def test_wait_for_start_flash_already_pressed_only_lights_the_led() -> None:
    board, backend = make_board()
    backend.pressed_on_poll = 1
    await board.wait_for_start_flash()
    assert backend.named("set_led_state") == [(0, True, 1)]
    assert backend.named("wait_until_button_pressed") == []


async def test_wait_for_start_flash_pressed_as_it_begins_lights_the_led() -> None:
    board, backend = make_board()
    backend.press = anyio.Event()
    backend.press.set()
    await board.wait_for_start_flash()
    assert backend.named("set_led_state")[-1][:2] == (0, True)
    assert backend.leds[0] is True


async def test_wait_for_start_flash_raises_what_the_backend_raises() -> None:
    board, backend = make_board()

    async def broken(identifier: int) -> None:
        raise CommunicationError("Power Board FAKE1: no answer")

    backend.wait_until_button_pressed = broken  # type: ignore[method-assign]
    with pytest.raises(CommunicationError, match="no answer"):
        await board.wait_for_start_flash()


async def test_wait_for_start_flash_lets_other_tasks_run() -> None:
    board, backend = make_board()
    backend.press = anyio.Event()  # never pressed
    ticks = 0

    async def ticker() -> None:
        nonlocal ticks
        while True:
            ticks += 1
            await anyio.sleep(0.01)

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(ticker)
        with anyio.move_on_after(0.3):
            await board.wait_for_start_flash()
        tasks.cancel_scope.cancel()
    assert ticks >= 10
    assert backend.named("set_led_state")  # the LED flashed meanwhile


async def test_wait_for_start_flash_times_out() -> None:
    board, backend = make_board()
    backend.press = anyio.Event()  # never pressed
    start = anyio.current_time()
    with pytest.raises(TimeoutError, match=r"start button was not pressed within 0\.2 s"):
        await board.wait_for_start_flash(timeout=0.2)
    elapsed = anyio.current_time() - start
    assert 0.19 <= elapsed < 2
    assert backend.named("wait_until_button_pressed") == [(0,)]


async def test_wait_for_start_flash_is_cancellable() -> None:
    board, backend = make_board()
    backend.press = anyio.Event()  # never pressed
    with anyio.move_on_after(0.12) as scope:
        await board.wait_for_start_flash()
    assert scope.cancelled_caught
    calls = len(backend.calls)
    await anyio.sleep(0.4)
    assert len(backend.calls) == calls  # nothing keeps flashing the LED after the cancel


@pytest.mark.parametrize("timeout", [-1, -0.01, math.nan])
async def test_wait_for_start_flash_refuses_bad_timeouts(timeout: float) -> None:
    board, backend = make_board()
    with pytest.raises(ValueError, match="timeout"):
        await board.wait_for_start_flash(timeout=timeout)
    assert backend.calls == []


@pytest.mark.parametrize("timeout", ["1", True, [1]])
async def test_wait_for_start_flash_refuses_non_numbers(timeout: object) -> None:
    board, backend = make_board()
    with pytest.raises(TypeError, match="timeout"):
        await board.wait_for_start_flash(timeout=timeout)  # type: ignore[arg-type]
    assert backend.calls == []
