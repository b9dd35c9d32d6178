"""astoria 0.11.3's own daemons (astdiskd, astmetad, astprocd) and ``astctl``, as on a robot.

They run from a virtual environment with astoria installed: ``J5AIO_TEST_ASTORIA`` names
its ``bin`` folder (``/work/venv-astoria/bin`` by default; ``.ci/run`` makes one in
``.tox/astoria-0.11.3`` and sets the variable). astdiskd's USB-stick watcher
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

    def explain(self, *more: Path) -> str:
        """The daemons' logs (and the files ``more``), to say why a test failed."""
        parts = []
        for path in (*(self.directory / f"{name}.log" for name in DAEMONS), *more):
            text = path.read_text(errors="replace") if path.exists() else "(missing)"
            parts.append(f"--- {path.name}:\n{text[-3000:]}")
        return "\n".join(parts)

    async def ready(self, broker_port: int) -> None:
        """Wait until astprocd says it is running: it has then heard from astdiskd and
        astmetad (a stick added before that crashes astprocd 0.11.3's handler, which
        needs astmetad's metadata).
        """
        import json

        import aiomqtt

        async with aiomqtt.Client("127.0.0.1", broker_port) as watcher:
            await watcher.subscribe("astoria/astprocd", qos=1)
            with anyio.fail_after(60):
                async for message in watcher.messages:
                    assert isinstance(message.payload, bytes)
                    if json.loads(message.payload).get("status") == "RUNNING":
                        return

    async def trigger(self, broker_port: int, attempts: int = 5) -> None:
        """``astctl usercode trigger``, until the broker has passed the start on.

        astctl closes its connection as soon as it has written the event, without waiting
        for the broker's acknowledgement, and now and then the broker never gets it (seen
        here about once in ten runs on a loaded machine, with a client of our own
        subscribed beside the robot's: neither got it). So a watcher of our own says
        whether the broker passed it on, and astctl is run again only when it did not;
        an event the broker passed on and the robot missed still fails the test.
        """
        import aiomqtt

        async with aiomqtt.Client("127.0.0.1", broker_port) as watcher:
            await watcher.subscribe("astoria/broadcast/start_button", qos=1)
            for _ in range(attempts):
                await self.astctl("usercode", "trigger")
                with anyio.move_on_after(5):
                    async for _message in watcher.messages:
                        return
        raise AssertionError(f"astctl's remote start never reached the broker in {attempts} tries")

    async def astctl(self, *args: str) -> str:
        result = await anyio.run_process(
            [str(ASTORIA_BIN / "astctl"), *args], cwd=self.directory, check=False
        )
        output = (result.stdout + result.stderr).decode(errors="replace")
        if result.returncode != 0:
            raise AssertionError(f"astctl {' '.join(args)} failed: {output}")
        return output
