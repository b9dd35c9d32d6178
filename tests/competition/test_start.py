"""Tests of the start flow: buttons, the start file, the trigger, LEDs and beep."""

from __future__ import annotations

from collections.abc import Iterator
from datetime import timedelta
from pathlib import Path

import anyio
import pytest

from j5aio.boards.sr.v4 import PowerBoard
from j5aio.competition import start
from j5aio.competition.start import (
    START_FILE_VARIABLE,
    clear_trigger,
    start_file,
    trigger_start,
    wait_for_start,
)
from j5aio.components.button import Button
from j5aio.components.piezo import Duration, Note, Piezo, Pitch
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit


@pytest.fixture(autouse=True)
def _fresh(monkeypatch: pytest.MonkeyPatch, tmp_path: Path, fresh_kit: None) -> Iterator[None]:
    monkeypatch.setenv(START_FILE_VARIABLE, str(tmp_path / "start"))
    clear_trigger()
    yield
    clear_trigger()


async def power_board() -> tuple[SimulatedKit, PowerBoard]:
    kit = use_kit(KitConfig(1, 0, 0, 0, 0))
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    return kit, board


def test_start_file_default_and_override(monkeypatch: pytest.MonkeyPatch) -> None:
    assert start_file().name == "start"
    monkeypatch.delenv(START_FILE_VARIABLE)
    assert start_file().name == "j5aio-start"


async def test_the_simulated_start_button_starts(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(start, "_FLASH_POLLS", 1)
    beeps: list[tuple[object, object]] = []
    original_buzz = Piezo.buzz

    async def buzz(
        piezo: Piezo, duration: Duration, pitch: Pitch, *, blocking: bool = False
    ) -> None:
        beeps.append((duration, pitch))
        await original_buzz(piezo, duration, pitch, blocking=blocking)

    monkeypatch.setattr(Piezo, "buzz", buzz)
    kit, board = await power_board()
    simulator = kit.power_boards[0]
    seen_led: set[bool] = set()

    async def press_later() -> None:
        for _ in range(6):
            await anyio.sleep(0.05)
            seen_led.add(simulator.run_led)
        simulator.press_start()

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(press_later)
        assert await wait_for_start([board], timeout=5) == "button"
    assert beeps == [(timedelta(milliseconds=100), Note.A6)]  # one short beep
    assert seen_led == {True, False}  # the run LED flashed while waiting
    assert simulator.run_led  # and is lit after the start


async def test_a_press_before_the_wait_is_discarded_once(monkeypatch: pytest.MonkeyPatch) -> None:
    kit, board = await power_board()
    reads: list[bool] = []
    original = Button.get_is_pressed

    async def counting(button: Button) -> bool:
        reads.append(await original(button))
        return reads[-1]

    monkeypatch.setattr(Button, "get_is_pressed", counting)
    kit.power_boards[0].press_start()  # held (or latched) before the wait
    trigger_start()
    assert await wait_for_start([board], timeout=5) == "trigger"
    assert reads == [True]  # the discarding read came first; the trigger then won


async def test_the_start_file_starts_and_a_stale_one_does_not(tmp_path: Path) -> None:
    path = tmp_path / "start"
    path.touch()  # left over from an earlier run
    with pytest.raises(TimeoutError):
        await wait_for_start([], timeout=0.2)
    assert not path.exists()

    async def poke() -> None:
        await anyio.sleep(0.1)
        path.touch()

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(poke)
        assert await wait_for_start([], timeout=5) == "start file"
    assert not path.exists()


async def test_a_directory_at_the_start_file_never_starts(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    (tmp_path / "start").mkdir()
    for _ in range(2):
        with pytest.raises(TimeoutError):
            await wait_for_start([], timeout=0.2)
    assert caplog.text.count("is not a regular file") == 1  # reported once, not each poll
    assert (tmp_path / "start").is_dir()


async def test_a_link_at_the_start_file_never_starts(tmp_path: Path) -> None:
    (tmp_path / "target").touch()
    (tmp_path / "start").symlink_to(tmp_path / "target")
    with pytest.raises(TimeoutError):
        await wait_for_start([], timeout=0.2)
    assert (tmp_path / "target").exists()


async def test_another_users_start_file_never_starts(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    path = tmp_path / "start"
    path.touch()
    owner = path.stat().st_uid
    monkeypatch.setattr(start, "_trusted_owners", lambda: {owner + 1})  # not its owner
    with pytest.raises(TimeoutError):
        await wait_for_start([], timeout=0.2)
    assert path.exists()
    assert f"belongs to another user (uid {owner})" in caplog.text
    monkeypatch.setattr(start, "_trusted_owners", lambda: None)  # a system without users
    with pytest.raises(TimeoutError):  # the stale file is removed as the wait begins
        await wait_for_start([], timeout=0.2)
    assert not path.exists()


async def test_a_start_file_that_cannot_be_removed_never_starts(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    path = tmp_path / "start"
    path.touch()

    def refuse(self: Path, missing_ok: bool = False) -> None:
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(Path, "unlink", refuse)
    with pytest.raises(TimeoutError):
        await wait_for_start([], timeout=0.2)
    assert "cannot be removed: Operation not permitted" in caplog.text


def test_a_start_file_that_cannot_be_looked_at_is_reported(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    def refuse(self: Path) -> None:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(Path, "lstat", refuse)
    assert not start._take_start_file(Path("/nowhere/start"))
    assert "cannot be looked at: Permission denied" in caplog.text


async def test_a_trigger_from_another_thread_starts() -> None:
    async def later() -> None:
        await anyio.to_thread.run_sync(trigger_start)

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(later)
        assert await wait_for_start([], timeout=5) == "trigger"
    with pytest.raises(TimeoutError):  # taken: the next wait waits again
        await wait_for_start([], timeout=0.1)


async def test_the_kch_start_led_flashes_while_waiting() -> None:
    simulator = KCHSimulator()
    kch = simulator.board()
    try:
        async def later() -> None:
            await anyio.sleep(0.4)
            trigger_start()

        async with anyio.create_task_group() as tasks:
            tasks.start_soon(later)
            await wait_for_start([kch], timeout=5)
        assert simulator.start_led_changes >= 2
        assert not simulator.start_led
    finally:
        await kch.close()


async def test_bad_timeouts_are_refused() -> None:
    with pytest.raises(TypeError):
        await wait_for_start([], timeout="1")  # type: ignore[arg-type]
    with pytest.raises(ValueError):
        await wait_for_start([], timeout=-1)


async def test_a_failing_start_button_reaches_the_waiter_as_itself(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from j5aio.errors import CommunicationError

    _, board = await power_board()

    async def broken(button: Button, timeout: float | None = None) -> None:
        raise CommunicationError("Power Board SIMPB0: no answer")

    monkeypatch.setattr(Button, "wait_until_pressed", broken)
    with pytest.raises(CommunicationError, match="no answer"):
        await wait_for_start([board], timeout=5)


async def test_a_press_from_another_thread_starts() -> None:
    kit, board = await power_board()
    simulator = kit.power_boards[0]

    async def press_from_a_thread() -> None:
        await anyio.sleep(0.1)
        await anyio.to_thread.run_sync(simulator.press_start)

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(press_from_a_thread)
        assert await wait_for_start([board], timeout=30) == "button"


async def test_a_trigger_wakes_the_wait_without_polling(monkeypatch: pytest.MonkeyPatch) -> None:
    # With the start file looked for once an hour, only a wake-up can start this wait.
    monkeypatch.setattr(start, "POLL_INTERVAL", 3600.0)

    async def later() -> None:
        await anyio.sleep(0.05)
        await anyio.to_thread.run_sync(trigger_start, "remote start")

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(later)
        assert await wait_for_start([], timeout=30) == "remote start"


async def test_a_trigger_from_the_loop_itself_wakes_the_wait(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(start, "POLL_INTERVAL", 3600.0)
    caplog.set_level("INFO")

    async def later() -> None:
        await anyio.sleep(0.05)
        trigger_start("remote start")

    async with anyio.create_task_group() as tasks:
        tasks.start_soon(later)
        assert await wait_for_start([], timeout=30) == "remote start"
    assert "Started (by the remote start)" in caplog.text
    assert not start._waiters  # the wait unregistered itself


async def test_a_trigger_before_the_wait_is_kept_for_it() -> None:
    trigger_start("remote start")
    assert await wait_for_start([], timeout=5) == "remote start"
    trigger_start()
    clear_trigger()
    with pytest.raises(TimeoutError):
        await wait_for_start([], timeout=0.1)


def test_trigger_start_refuses_a_non_text_how() -> None:
    with pytest.raises(TypeError, match="how must be text"):
        trigger_start(3)  # type: ignore[arg-type]


def test_a_trigger_to_a_closed_loop_is_harmless() -> None:
    import asyncio

    loop = asyncio.new_event_loop()
    loop.close()
    waiter = (loop, asyncio.Event())
    start._waiters.add(waiter)
    try:
        trigger_start()  # that loop's wait is over; nothing to wake
    finally:
        start._waiters.discard(waiter)
    assert start._take_trigger() == "trigger"


def test_a_start_file_taken_by_another_wait_first_is_not_a_start(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    path = tmp_path / "start"
    path.touch()

    def gone(self: Path, missing_ok: bool = False) -> None:
        raise FileNotFoundError(2, "No such file or directory")

    monkeypatch.setattr(Path, "unlink", gone)
    assert not start._take_start_file(path)
