"""Shared by the benches that measure whole child interpreters (imports, start-up, memory).

Each case is a Python program run in a fresh child process: j5aio's with this checkout
first on the path, the peer's (j5 0.12) with the peer's own interpreter from
:mod:`_peers`. Rounds are interleaved (every case once per round, in a shuffled order) so
that the machine's noise hits every case alike; the figures are medians over rounds.
Children may write byte code (``PYTHONDONTWRITEBYTECODE`` is dropped for them) and each
case runs once, unmeasured, first: the figures are those of an installed package, whose
modules are compiled once, not at every start.
"""

from __future__ import annotations

import os
import random
import socket
import statistics
import subprocess
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _peers import J5_PEER, peer_python  # type: ignore[import-not-found]

__all__ = [
    "J5_ROBOT",
    "REPO",
    "Case",
    "j5_python",
    "j5aio_env",
    "print_table",
    "run_interleaved",
    "run_reporting",
]

REPO = Path(__file__).resolve().parent.parent

#: The robot of j5's quick start on j5 0.12's console backends (a power board and the
#: motor boards), made as ``robot``: the peer's side of the start-up and memory benches.
J5_ROBOT = """\
from j5 import BaseRobot, BoardGroup
from j5.backends.console.sr.v4 import SRV4MotorBoardConsoleBackend, SRV4PowerBoardConsoleBackend
from j5.boards.sr.v4 import MotorBoard, PowerBoard

class MyRobot(BaseRobot):
    def __init__(self) -> None:
        self.power_board = BoardGroup.get_board_group(
            PowerBoard, SRV4PowerBoardConsoleBackend,
        ).singular()
        self.motor_boards = BoardGroup.get_board_group(MotorBoard, SRV4MotorBoardConsoleBackend)

robot = MyRobot()
"""


def j5aio_env(**extra: str) -> dict[str, str]:
    """The environment of a j5aio child: this checkout first on the path, and ``extra``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        [str(REPO), *filter(None, [os.environ.get("PYTHONPATH")])]
    )
    env.pop("J5AIO_ENV", None)
    # Measure as an installed package runs: from byte code cached by the warm-up run.
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    # A robot holds a lock (a TCP port): give each child its own, so that robot programs
    # running elsewhere on the machine (tests, say) neither block nor are blocked by it.
    env["J5AIO_LOCK_PORT"] = str(_free_port())
    env.update(extra)
    return env


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def j5_python() -> Path | None:
    """The interpreter of j5 0.12's own venv, or None (with a note) if it cannot be made."""
    try:
        return Path(peer_python(*J5_PEER))
    except RuntimeError as error:
        print(f"bench: j5 is left out: {error}", file=sys.stderr)
        return None


@dataclass
class Case:
    """One program to run in child processes.

    :param name: its label in the table.
    :param argv: the child's command line.
    :param env: the child's environment.
    :param values: what each run measured (filled in by :func:`run_interleaved`).
    """

    name: str
    argv: list[str]
    env: dict[str, str]
    values: list[float] = field(default_factory=list)

    @property
    def median(self) -> float:
        """The median of the runs so far."""
        return statistics.median(self.values)


def run_interleaved(
    cases: Sequence[Case], rounds: int, measure: Callable[[Case], float], *, warmup: bool = True,
) -> None:
    """Measure every case once per round, in a new shuffled order each round.

    :param warmup: run each case once first, unmeasured (byte-code caches, disk cache).
    """
    if warmup:
        for case in cases:
            measure(case)
    order = list(cases)
    for _ in range(rounds):
        random.shuffle(order)
        for case in order:
            case.values.append(measure(case))


def run_reporting(case: Case, marker: str, *, stdin: int | None = subprocess.DEVNULL) -> str:
    """Run ``case`` to the end and return the text after ``marker`` on its output's last
    line carrying it.

    :raises RuntimeError: the child failed or never printed ``marker``; the message has
        its output.
    """
    done = subprocess.run(
        case.argv, env=case.env, stdin=stdin, capture_output=True, text=True, check=False,
    )
    lines = [line for line in done.stdout.splitlines() if line.startswith(marker)]
    if done.returncode != 0 or not lines:
        raise RuntimeError(
            f"{case.name}: the child failed (exit {done.returncode}):\n"
            f"{done.stdout[-2000:]}\n{done.stderr[-2000:]}"
        )
    return lines[-1][len(marker):].strip()


def print_table(
    title: str, cases: Sequence[Case], unit: str, *, reference: Case | None,
    scale: float = 1.0, extra: Callable[[Case], str] | None = None,
) -> None:
    """Print each case's median, minimum and ratio to ``reference``'s median."""
    print(f"\n{title}")
    width = max(len(case.name) for case in cases)
    for case in cases:
        ratio = ""
        if reference is not None and reference.values and case is not reference:
            ratio = f"  {case.median / reference.median:5.2f}x {reference.name}"
        more = f"  {extra(case)}" if extra is not None else ""
        print(
            f"  {case.name:<{width}}  median {case.median * scale:8.1f} {unit}"
            f"  min {min(case.values) * scale:8.1f} {unit}{ratio}{more}"
        )
