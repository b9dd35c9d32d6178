from __future__ import annotations

import io
import os
from collections.abc import Iterator
from concurrent.futures import Future
from typing import TextIO

import anyio
import pytest

from j5aio.backends.console import stdin
from j5aio.backends.console.stdin import LineReader, read_stdin_line


class Pipe:
    """A pipe whose read end is a text stream, like a piped standard input."""

    def __init__(self) -> None:
        read_fd, write_fd = os.pipe()
        self.reader: TextIO = os.fdopen(read_fd, "r")
        self._write_fd = write_fd
        self._open = True

    def write(self, text: str) -> None:
        os.write(self._write_fd, text.encode())

    def close_writer(self) -> None:
        if self._open:
            os.close(self._write_fd)
            self._open = False

    def close(self) -> None:
        self.close_writer()
        self.reader.close()


@pytest.fixture
def pipe() -> Iterator[Pipe]:
    made = Pipe()
    yield made
    made.close()


def reader_of(pipe: Pipe) -> LineReader:
    return LineReader(lambda: pipe.reader)


async def test_lines_come_in_order_without_their_endings(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    pipe.write("one\r\ntwo\n")
    with anyio.fail_after(5):
        assert await lines.readline() == "one"
        assert await lines.readline() == "two"
        pipe.write("\n")
        assert await lines.readline() == ""


async def test_the_event_loop_runs_while_waiting_for_a_line(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    got: list[str] = []

    async def read_one() -> None:
        got.append(await lines.readline())

    with anyio.fail_after(5):
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(read_one)
            await anyio.sleep(0.1)  # the loop is free: this sleep ends on time
            assert got == []
            pipe.write("late\n")
    assert got == ["late"]


async def test_a_line_typed_after_a_cancelled_read_goes_to_the_next_reader(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    with anyio.move_on_after(0.05) as scope:
        await lines.readline()
    assert scope.cancelled_caught
    pipe.write("answer\n")
    with anyio.fail_after(5):
        assert await lines.readline() == "answer"


async def test_concurrent_readers_get_one_line_each_in_turn(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    got: dict[str, str] = {}

    async def read(name: str) -> None:
        got[name] = await lines.readline()

    with anyio.fail_after(5):
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(read, "first")
            await anyio.sleep(0.05)
            tasks.start_soon(read, "second")
            await anyio.sleep(0.05)
            pipe.write("a\n")
            await anyio.sleep(0.05)
            pipe.write("b\n")
    assert got == {"first": "a", "second": "b"}


async def test_end_of_file_raises_eof_error_now_and_later(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    pipe.write("last\n")
    pipe.close_writer()
    with anyio.fail_after(5):
        assert await lines.readline() == "last"
        with pytest.raises(EOFError):
            await lines.readline()
        with pytest.raises(EOFError):
            await lines.readline()


async def test_every_waiting_reader_hears_of_the_end(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    errors: list[BaseException] = []

    async def read() -> None:
        try:
            await lines.readline()
        except EOFError as exc:
            errors.append(exc)

    with anyio.fail_after(5):
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(read)
            tasks.start_soon(read)
            await anyio.sleep(0.05)
            pipe.close_writer()
    assert len(errors) == 2


async def test_a_broken_stream_ends_the_input() -> None:
    closed = io.StringIO()
    closed.close()
    lines = LineReader(lambda: closed)
    with anyio.fail_after(5), pytest.raises(EOFError, match="input stream failed"):
        await lines.readline()


def test_a_line_delivered_to_a_reader_that_gave_up_is_kept() -> None:
    lines = LineReader(lambda: io.StringIO())
    delivered: Future[str] = Future()
    delivered.set_result("kept")
    lines._withdraw(delivered)
    failed: Future[str] = Future()
    failed.set_exception(EOFError())
    lines._withdraw(failed)
    assert list(lines._spare) == ["kept"]


async def test_read_stdin_line_shows_the_prompt_then_reads(
    pipe: Pipe, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
) -> None:
    monkeypatch.setattr(stdin, "STDIN", reader_of(pipe))
    pipe.write("12.5\n")
    with anyio.fail_after(5):
        assert await read_stdin_line("Board(S): Voltage: ") == "12.5"
    assert capsys.readouterr().out == "Board(S): Voltage: "


async def test_a_line_typed_while_nobody_waits_is_kept_for_the_next_reader(pipe: Pipe) -> None:
    lines = reader_of(pipe)
    with anyio.move_on_after(0.05):
        await lines.readline()
    pipe.write("early\n")
    with anyio.fail_after(5):
        # The reader thread files the line away; there is no event to wait on.
        while not lines._spare:  # noqa: ASYNC110
            await anyio.sleep(0.01)
        assert await lines.readline() == "early"
