"""bench/bench_call_path.py: its counter counts a known path, and a real case runs."""

from __future__ import annotations

import importlib.util
import os
import sys
import textwrap
import threading
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from tests.module_from_file import ROOT, load_module


def load_bench() -> ModuleType:
    return load_module("bench_call_path", ROOT / "bench" / "bench_call_path.py", register=True)


bench = load_bench()

# A toy "package": host code that hands bytes to a toy board, some of it on a thread.
HOST = '''
import os
import threading

from toypkg.board import Board


def top(board, bytes_out):
    helper()
    worker = threading.Thread(target=on_thread, args=(board, bytes_out))
    worker.start()
    worker.join()
    after()


def helper():
    pass


def on_thread(board, bytes_out):
    encode = lambda: b"x"  # noqa: E731 - a lambda counts as a function of its own
    data = encode()
    if bytes_out == "board":
        board.receive(data)
    else:
        os.write(bytes_out, data)
    after()


def after():
    pass


def poll(board, times):
    for _ in range(times):
        read(board)


def read(board):
    board.receive(b"?")
'''

BOARD = '''
class Board:
    def receive(self, data):
        return self._inner(data)

    def _inner(self, data):
        return data
'''


@pytest.fixture
def toy(tmp_path: Path) -> Iterator[tuple[ModuleType, ModuleType, Path]]:
    package = tmp_path / "toypkg"
    (package / "board").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "host.py").write_text(textwrap.dedent(HOST))
    (package / "board" / "__init__.py").write_text(textwrap.dedent(BOARD))
    sys.path.insert(0, str(tmp_path))
    try:
        yield (
            importlib.import_module("toypkg.host"),
            importlib.import_module("toypkg.board"),
            package,
        )
    finally:
        sys.path.remove(str(tmp_path))
        for name in [name for name in sys.modules if name.startswith("toypkg")]:
            del sys.modules[name]


def test_counts_each_function_once_in_every_thread_up_to_the_hand_over(
    toy: tuple[ModuleType, ModuleType, Path],
) -> None:
    host, board, package = toy
    counter = bench.CallPathCounter(package, board_side=[package / "board"])
    with counter.installed():
        counter.record(1)
        host.top(board.Board(), "board")
        assert counter.wait(0)  # stopped by itself, at the hand-over
        segments = counter.stop()
    assert [segment.functions for segment in segments] == [[
        "toypkg.host:top",
        "toypkg.host:helper",
        "toypkg.host:on_thread",  # on the thread the call started
        "toypkg.host:on_thread.<locals>.<lambda>",
    ]]  # nothing after the hand-over (after() ran later), nothing of the board
    assert segments[0].ended_by == "toypkg.board:Board.receive"


def test_a_write_to_the_operating_system_is_a_hand_over(
    toy: tuple[ModuleType, ModuleType, Path],
) -> None:
    host, board, package = toy
    counter = bench.CallPathCounter(package, board_side=[package / "board"])
    read_end, write_end = os.pipe()
    try:
        with counter.installed():
            counter.record(1)
            host.top(board.Board(), write_end)
            segments = counter.stop()
    finally:
        os.close(read_end)
        os.close(write_end)
    assert segments[0].ended_by == "write"
    assert segments[0].functions[-1] == "toypkg.host:on_thread.<locals>.<lambda>"


def test_each_hand_over_ends_a_segment_and_an_open_recording_runs_until_stopped(
    toy: tuple[ModuleType, ModuleType, Path],
) -> None:
    host, board, package = toy
    counter = bench.CallPathCounter(package, board_side=[package / "board"])
    device = board.Board()
    with counter.installed():
        counter.record(3)
        host.poll(device, 5)
        polls = counter.stop()
        counter.record(None)
        host.poll(device, 2)
        host.helper()
        assert not counter.wait(0)  # hand-overs do not end an open recording
        open_ended = counter.stop()
    # Each segment lists what it entered, afresh: read() again in each poll after the first.
    assert [segment.functions for segment in polls] == [
        ["toypkg.host:poll", "toypkg.host:read"], ["toypkg.host:read"], ["toypkg.host:read"],
    ]
    assert [segment.ended_by for segment in polls] == ["toypkg.board:Board.receive"] * 3
    assert [segment.functions for segment in open_ended] == [
        ["toypkg.host:poll", "toypkg.host:read", "toypkg.host:helper"],
    ]
    assert open_ended[0].ended_by is None


def test_profiling_ends_with_the_context(toy: tuple[ModuleType, ModuleType, Path]) -> None:
    _host, _board, package = toy
    counter = bench.CallPathCounter(package)
    with counter.installed():
        assert sys.getprofile() is not None
    assert sys.getprofile() is None
    started: list[object] = []
    thread = threading.Thread(target=lambda: started.append(sys.getprofile()))
    thread.start()
    thread.join()
    assert started == [None]


def test_a_real_case_counts_the_async_motor_call_to_the_simulated_board() -> None:
    result = bench.run_case("async motor.power fw3")
    steady, owed = result["segments"]  # fw 3 sends no acknowledgement: the same path
    for segment in (steady, owed):
        assert segment["functions"][0] == "j5aio.components.motor:Motor.set_power"
        assert segment["ended_by"] == "j5aio.simulator.base:SerialBoardSimulator.receive"
        assert not any(name.startswith("j5aio.simulator.") for name in segment["functions"])
    assert steady["functions"] == owed["functions"]
    lines = bench.describe(result, quiet=True)
    count = len(steady["functions"])
    assert lines == [
        f"  async motor.power fw3: to the bytes (nothing owed): {count} functions"
        f"{'  MET' if count <= 15 else '  NOT MET'}"
        " (stopped at j5aio.simulator.base:SerialBoardSimulator.receive)",
        f"  async motor.power fw3: to the bytes (the last ACK owed): {count} functions"
        " (stopped at j5aio.simulator.base:SerialBoardSimulator.receive)",
    ]


def test_a_sync_fw4_command_is_counted_with_nothing_owed_and_with_the_last_ack_owed() -> None:
    steady, owed = bench.run_case("sync motor.power fw4")["segments"]
    confirm = "j5aio.backends.hardware.serial_backend:SerialHardwareBackend.confirm_acknowledgement"
    # After a query nothing is owed; after a command, its ACK is read first, and counted.
    assert confirm not in steady["functions"]
    assert confirm in owed["functions"]
    assert set(steady["functions"]) < set(owed["functions"])
