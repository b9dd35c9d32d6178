from __future__ import annotations

import asyncio
import logging
import sys

import pytest

from j5aio.boards.board import Board
from j5aio.safety import make_all_safe_uncancellably, rescue

from .conftest import LampBackend, LampBoard


class SlowBoard(LampBoard):
    async def make_safe(self) -> None:
        await asyncio.sleep(0.05)
        await super().make_safe()


async def test_cancelling_the_caller_does_not_stop_make_safe() -> None:
    board = SlowBoard("slow", LampBackend())
    await board.setup()
    task = asyncio.ensure_future(make_all_safe_uncancellably())
    await asyncio.sleep(0.01)
    task.cancel()
    await asyncio.sleep(0)
    task.cancel()  # a second, impatient cancellation
    with pytest.raises(asyncio.CancelledError):
        await task
    assert board.safe_calls == 1
    assert board.lamp_backend.states[0] is False


async def test_a_hanging_board_is_given_up_on(caplog: pytest.LogCaptureFixture) -> None:
    class Hanging(LampBoard):
        async def make_safe(self) -> None:
            await asyncio.sleep(10)

    await Hanging("h", LampBackend()).setup()
    with caplog.at_level(logging.ERROR):
        await make_all_safe_uncancellably(timeout=0.05)
    assert "gave up waiting" in caplog.text


async def test_unexpected_failure_is_logged(
    caplog: pytest.LogCaptureFixture, monkeypatch: pytest.MonkeyPatch,
) -> None:
    async def explode() -> list[BaseException]:
        raise RuntimeError("registry broken")

    monkeypatch.setattr(Board, "make_all_safe", staticmethod(explode))
    with caplog.at_level(logging.ERROR):
        await make_all_safe_uncancellably()
    assert "registry broken" in caplog.text


def test_the_orderly_path_and_the_registry_refuse_a_hook_that_is_not_callable() -> None:
    from j5aio.safety import orderly, registry

    with pytest.raises(TypeError, match="the safe-state pass must be a callable"):
        orderly.run_pass_through(None)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="a loop watcher must be a callable"):
        registry.on_board_in_loop(42)  # type: ignore[arg-type]


async def test_a_board_opened_in_a_loop_is_told_to_each_watcher_once() -> None:
    from j5aio.safety import registry, rescue

    seen: list[asyncio.AbstractEventLoop] = []
    registry.on_board_in_loop(seen.append)
    registry.on_board_in_loop(seen.append)  # given twice: called once
    try:
        board = LampBoard("watched", LampBackend())
        assert seen == [asyncio.get_running_loop()]
        assert id(asyncio.get_running_loop()) in rescue._watchers  # the rescue watches it
        board.close_now()
    finally:
        registry._loop_watchers.remove(seen.append)


async def test_the_uncancellable_pass_runs_through_board_make_all_safe(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    calls: list[str] = []

    async def replaced() -> list[BaseException]:
        calls.append("kit's own")
        return []

    monkeypatch.setattr(Board, "make_all_safe", staticmethod(replaced))
    await make_all_safe_uncancellably()
    assert calls == ["kit's own"]


def test_importing_the_registry_alone_sets_the_rescue_watching() -> None:
    # The registry does not import the rescue; the safety package does, before any of
    # its modules, so that no board opened in a loop goes unwatched.
    import subprocess
    import sys
    from pathlib import Path

    program = (
        "import sys\n"
        "from j5aio.safety import registry\n"
        "print('j5aio.safety.rescue' in sys.modules, len(registry._loop_watchers))\n"
    )
    root = Path(__file__).resolve().parents[2]
    result = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, cwd=root,
        timeout=60, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["True", "1"]


def test_a_loop_watcher_closed_as_the_interpreter_shuts_down_does_nothing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A program stopped while its loop ran leaves the watcher task to the garbage collector
    # at shutdown, after the exit hook made every board safe; the module's globals may be
    # gone by then, so the watcher must touch nothing (a traceback at exit was the symptom).
    loop = asyncio.new_event_loop()
    calls: list[str] = []
    monkeypatch.setattr(rescue, "make_all_safe_now", lambda reason, **_: calls.append(reason))
    try:
        shutting_down = [False]
        monkeypatch.setattr(sys, "is_finalizing", lambda: shutting_down[0])
        watcher = rescue._watch_loop(loop)
        watcher.send(None)  # waiting for the loop's end
        shutting_down[0] = True
        monkeypatch.setattr(rescue, "_watchers", None)  # as module teardown leaves it
        watcher.close()
        assert calls == []
        monkeypatch.undo()
        monkeypatch.setattr(rescue, "make_all_safe_now", lambda reason, **_: calls.append(reason))
        watcher = rescue._watch_loop(loop)
        watcher.send(None)
        watcher.close()  # an ordinary end (the runner cancels it): the rescue runs
        assert calls == ["its event loop finished"]
    finally:
        loop.close()
