from __future__ import annotations

import math
from datetime import timedelta

import anyio
import pytest

from j5aio.boards.board_group import BoardGroup
from j5aio.boards.sr.v4 import PowerBoard, PowerOutputGroup, PowerOutputPosition
from j5aio.components import LED, BatterySensor, Button, Piezo, PowerOutput

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


async def test_wait_for_start_flash_polls_every_50ms_and_toggles_every_6th_poll(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    board, backend = make_board()
    backend.pressed_on_poll = 20
    sleeps = RecordedSleeps(monkeypatch)

    await board.wait_for_start_flash()

    assert backend.button_polls == 20
    assert sleeps.durations == [0.05] * 19
    # (led, state, polls seen when it changed): before polls 1, 7, 13 and 19 the LED
    # toggles, starting with on; once pressed it is left on.
    assert backend.named("set_led_state") == [
        (0, True, 1), (0, False, 7), (0, True, 13), (0, False, 19), (0, True, 20),
    ]
    assert backend.leds[0] is True


async def test_wait_for_start_flash_already_pressed_only_lights_the_led() -> None:
    board, backend = make_board()
    backend.pressed_on_poll = 1
    await board.wait_for_start_flash()
    assert backend.named("set_led_state") == [(0, True, 1)]


async def test_wait_for_start_flash_lets_other_tasks_run() -> None:
    board, backend = make_board()
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
    assert backend.button_polls >= 2


async def test_wait_for_start_flash_times_out() -> None:
    board, backend = make_board()
    start = anyio.current_time()
    with pytest.raises(TimeoutError, match=r"start button was not pressed within 0\.2 s"):
        await board.wait_for_start_flash(timeout=0.2)
    elapsed = anyio.current_time() - start
    assert 0.19 <= elapsed < 2
    assert 3 <= backend.button_polls <= 40


async def test_wait_for_start_flash_is_cancellable() -> None:
    board, backend = make_board()
    with anyio.move_on_after(0.12) as scope:
        await board.wait_for_start_flash()
    assert scope.cancelled_caught
    polls = backend.button_polls
    await anyio.sleep(0.15)
    assert backend.button_polls == polls  # nothing keeps polling after the cancel


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
