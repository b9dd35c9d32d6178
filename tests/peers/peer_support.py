"""Independent peers (sr-robot3, sbot from PyPI) drive j5aio's simulators over ptys.

Each peer runs in a child Python (both talk to their boards as the program starts and
keep module-level state), pointed at simulators this process serves on pseudo-terminals,
so that the test can look at what the simulated boards did, also after the peer's exit.
Run them with ``tox -e peers`` (see docs/simulator.rst); without the packages they are
skipped.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Iterator
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import pytest

from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.serve import PtyServer, serve_on_pty

ROOT = Path(__file__).resolve().parents[2]

if sys.platform == "win32":  # pragma: no cover
    pytest.skip("the peers are served on pseudo-terminals (POSIX only)", allow_module_level=True)


def require(module: str, package: str) -> None:
    """Skip the calling module unless ``module`` (from PyPI's ``package``) is installed."""
    if find_spec(module.split(".")[0]) is None or find_spec(module) is None:
        pytest.skip(
            f"{package} is not installed: run `tox -e peers` (it installs {package} from "
            "PyPI) to compare j5aio's simulators with it",
            allow_module_level=True,
        )


class ServedKit:
    """Simulators by name, each served on its own pseudo-terminal."""

    def __init__(self, boards: dict[str, str]) -> None:
        self.simulators: dict[str, Any] = {
            name: SERIAL_SIMULATORS[name](serial) for name, serial in boards.items()
        }
        self._servers: dict[str, PtyServer] = {}
        for name, simulator in self.simulators.items():
            self._servers[name] = serve_on_pty(simulator, time_scale=0)

    def path(self, name: str) -> str:
        """The pty of simulator ``name``."""
        return self._servers[name].path

    def close(self) -> None:
        for server in self._servers.values():
            server.close()


@pytest.fixture
def served() -> Iterator[list[ServedKit]]:
    kits: list[ServedKit] = []
    yield kits
    for kit in kits:
        kit.close()


def run_peer(source: str, *, env: dict[str, str], timeout: float = 90) -> dict[str, Any]:
    """Run ``source`` in a child Python; return the JSON object it printed last (``RESULT``)."""
    environment = {k: v for k, v in os.environ.items() if not k.startswith(("SBOT_", "J5AIO"))}
    environment.update(env)
    environment["PYTHONPATH"] = os.pathsep.join([str(ROOT), environment.get("PYTHONPATH", "")])
    result = subprocess.run(
        [sys.executable, "-c", source],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=environment,
        cwd=ROOT,
        check=False,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    lines = [line for line in result.stdout.splitlines() if line.startswith("RESULT ")]
    assert lines, (result.stdout[-2000:], result.stderr[-3000:])
    found: dict[str, Any] = json.loads(lines[-1].removeprefix("RESULT "))
    return found
