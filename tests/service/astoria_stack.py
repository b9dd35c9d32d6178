"""astoria 0.11.3's own daemons (astdiskd, astmetad, astprocd) and ``astctl``, as on a robot.

They run from a virtual environment with astoria installed: ``J5AIO_TEST_ASTORIA`` names
its ``bin`` folder (``/work/venv-astoria/bin`` by default). astdiskd's USB-stick watcher
needs udisks on the system bus; without it astdiskd still serves *static disks*, folders
that ``astctl static-disk add`` mounts as if they were sticks, which is what the tests use.
"""

from __future__ import annotations

import os
import signal
import subprocess
from pathlib import Path

import anyio

from tests.service.broker import Broker

ASTORIA_BIN = Path(os.environ.get("J5AIO_TEST_ASTORIA", "/work/venv-astoria/bin"))
DAEMONS = ("astdiskd", "astmetad", "astprocd")


def astoria_missing() -> str | None:
    """Why astoria's tools cannot run here, or ``None`` if they can."""
    for name in (*DAEMONS, "astctl"):
        if not (ASTORIA_BIN / name).exists():
            return f"astoria 0.11.3 is not installed in {ASTORIA_BIN} (set J5AIO_TEST_ASTORIA)"
    return None


class AstoriaStack:
    """astoria's daemons in ``directory`` (holding their astoria.toml), on ``broker``."""

    def __init__(self, directory: Path, broker: Broker, env: dict[str, str] | None = None):
        self.directory = directory
        cache = directory / "cache"
        cache.mkdir(exist_ok=True)
        extra = "".join(f'{key} = "{value}"\n' for key, value in (env or {}).items())
        (directory / "astoria.toml").write_text(
            f'[mqtt]\nhost = "127.0.0.1"\nport = {broker.port}\ntopic_prefix = "astoria"\n\n'
            '[wifi]\ninterface = "wlan0"\nbridge = "br0"\nenable_wpa3 = false\n\n'
            f'[system]\ncache_dir = "{cache}"\n\n'
            f"[env]\n{extra}"
        )
        self._processes: list[subprocess.Popen[bytes]] = []

    def start(self) -> None:
        for name in DAEMONS:
            with (self.directory / f"{name}.log").open("ab") as log:
                self._processes.append(subprocess.Popen(
                    [str(ASTORIA_BIN / name)], cwd=self.directory, stdout=log, stderr=log,
                    stdin=subprocess.DEVNULL,
                ))

    def stop(self) -> None:
        """SIGINT, as systemd would stop them (astprocd ends the team's code first)."""
        for process in reversed(self._processes):
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
        for process in reversed(self._processes):
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        self._processes.clear()

    async def astctl(self, *args: str) -> str:
        result = await anyio.run_process(
            [str(ASTORIA_BIN / "astctl"), *args], cwd=self.directory, check=False
        )
        output = (result.stdout + result.stderr).decode(errors="replace")
        if result.returncode != 0:
            raise AssertionError(f"astctl {' '.join(args)} failed: {output}")
        return output
