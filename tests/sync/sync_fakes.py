"""Helpers for the sync facade tests: console boards driven by scripted answers."""

from __future__ import annotations

import os
import subprocess
import sys
from collections import deque
from collections.abc import Iterable
from pathlib import Path

from j5aio.backends.console import CONSOLE_ENVIRONMENT, ConsoleBackend
from j5aio.backends.console.console import Console
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.sync import _generated as sync
from j5aio.sync._runtime import call
from j5aio.sync.wrapping import wrap

ROOT = Path(__file__).resolve().parents[2]


class ScriptedConsoleLog:
    """What the consoles printed, and the answers they will give to prompts."""

    def __init__(self, answers: Iterable[str] = ()) -> None:
        self.printed: list[str] = []
        self.prompts: list[str] = []
        self.answers: deque[str] = deque(answers)

    def console_class(self) -> type[Console]:
        log = self

        def ask(prompt: str) -> str:
            log.prompts.append(prompt)
            return log.answers.popleft()

        class LoggedConsole(Console):
            def __init__(self, descriptor: str, *_ignored: object) -> None:
                super().__init__(descriptor, log.printed.append, ask)

        return LoggedConsole


def set_up(log: ScriptedConsoleLog, board_class: type[Board], serial: str) -> object:
    """A set-up core board of ``board_class`` on its console backend, as its sync wrapper."""
    backend = CONSOLE_ENVIRONMENT.get_backend(board_class)
    assert issubclass(backend, ConsoleBackend)
    core = board_class(serial, backend(serial, console_class=log.console_class()))
    call(core.setup)
    return wrap(core)


def power_board(log: ScriptedConsoleLog, serial: str = "PB1") -> sync.PowerBoard:
    board = set_up(log, PowerBoard, serial)
    assert isinstance(board, sync.PowerBoard)
    return board


def motor_board(log: ScriptedConsoleLog, serial: str = "MB1") -> sync.MotorBoard:
    board = set_up(log, MotorBoard, serial)
    assert isinstance(board, sync.MotorBoard)
    return board


def child_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONUNBUFFERED"] = "1"
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    return env


def start_script(source: str, tmp_path: Path) -> subprocess.Popen[str]:
    """Start ``source`` as a program in a child Python, with pipes for all three streams."""
    script = tmp_path / "program.py"
    script.write_text(source, encoding="utf-8")
    return subprocess.Popen(
        [sys.executable, str(script)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=child_env(),
        cwd=tmp_path,
    )


def wait_for_line(process: subprocess.Popen[str], wanted: str) -> list[str]:
    """Read the child's output until a line containing ``wanted``; return the lines read."""
    assert process.stdout is not None
    lines: list[str] = []
    for line in process.stdout:
        lines.append(line.rstrip("\n"))
        if wanted in line:
            return lines
    raise AssertionError(f"{wanted!r} never printed; got {lines!r}")
