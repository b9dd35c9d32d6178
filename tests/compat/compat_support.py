"""Running a program written for a competition's API under ``j5aio run --api``, recorded."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
PROGRAMS = Path(__file__).resolve().parent / "programs"
RECORDED_RUN = Path(__file__).resolve().parent / "recorded_run.py"


@dataclass
class Run:
    """What a program printed, its exit status, and what each simulated board received."""

    returncode: int
    stdout: str
    stderr: str
    boards: dict[str, Any]

    def lines(self, prefix: str) -> list[str]:
        """The rest of each printed line that is ``prefix``, or starts with it and a space."""
        return [
            line.removeprefix(prefix).removeprefix(" ")
            for line in self.stdout.splitlines()
            if line == prefix or line.startswith(prefix + " ")
        ]

    def line(self, prefix: str) -> str:
        """The one printed line that starts with ``prefix``."""
        found = self.lines(prefix)
        assert len(found) == 1, (prefix, self.stdout, self.stderr[-3000:])
        return found[0]

    def received(self, board: str) -> str:
        """What the board whose name starts with ``board`` received, as text."""
        names = [name for name in self.boards if name.startswith(board)]
        assert len(names) == 1, (board, list(self.boards))
        text: str = self.boards[names[0]]["received"]
        return text

    def state(self, board: str) -> dict[str, Any]:
        """The final state of the board whose name starts with ``board``."""
        names = [name for name in self.boards if name.startswith(board)]
        assert len(names) == 1, (board, list(self.boards))
        state: dict[str, Any] = self.boards[names[0]]["state"]
        return state


def run_program(
    program: str,
    tmp_path: Path,
    *options: str,
    api: str | None = "sr-robot3",
    kit: str = "sr2023",
    setup: str = "",
    arguments: tuple[str, ...] = (),
    timeout: float = 90,
) -> Run:
    """Run ``programs/<program>`` with ``python -m j5aio run --api API --sim --kit KIT``.

    ``api=None`` leaves ``--api`` out.
    """
    report = tmp_path / "boards.json"
    env = {k: v for k, v in os.environ.items() if not k.startswith(("J5AIO_ENV", "J5AIO_KIT"))}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    env["J5AIO_KIT"] = kit
    env["J5AIO_START_FILE"] = str(tmp_path / "start")
    env["J5AIO_MEDIA_ROOTS"] = str(tmp_path / "media")
    env["COMPAT_SETUP"] = setup
    command = [
        sys.executable, str(RECORDED_RUN), str(report), "--",
        "run", *(("--api", api) if api else ()), "--sim", "--kit", kit, "--no-log", *options,
        str(PROGRAMS / program), *arguments,
    ]
    result = subprocess.run(
        command, capture_output=True, text=True, timeout=timeout, env=env, cwd=tmp_path,
        check=False,
    )
    boards = json.loads(report.read_text()) if report.exists() else {}
    return Run(result.returncode, result.stdout, result.stderr, boards)
