"""A real Mosquitto broker for the robot service's tests, on a free port of 127.0.0.1."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import tempfile
import time
from pathlib import Path

#: Debian's broker (``apt-get install mosquitto``; ``.ci/run`` installs it).
MOSQUITTO = os.environ.get("J5AIO_TEST_MOSQUITTO") or shutil.which(
    "mosquitto", path=os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/sbin"])
)


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def _accepts(port: int) -> bool:
    try:
        with socket.create_connection(("127.0.0.1", port), timeout=0.2):
            return True
    except OSError:
        return False


class Broker:
    """One mosquitto process, stopped and started again on the same port at will."""

    def __init__(self, directory: Path) -> None:
        assert MOSQUITTO is not None
        self.port = free_port()
        self.config = directory / "mosquitto.conf"
        self.log = directory / "mosquitto.log"
        self.config.write_text(
            f"listener {self.port} 127.0.0.1\n"
            "allow_anonymous true\n"
            "persistence false\n"
            "log_dest stderr\n"
        )
        self._process: subprocess.Popen[bytes] | None = None

    @property
    def running(self) -> bool:
        return self._process is not None and self._process.poll() is None

    def start(self) -> None:
        assert not self.running
        with self.log.open("ab") as log:
            self._process = subprocess.Popen(
                [str(MOSQUITTO), "-c", str(self.config)], stdout=log, stderr=log,
                stdin=subprocess.DEVNULL,
            )
        deadline = time.monotonic() + 10
        while not _accepts(self.port):
            if self._process.poll() is not None:
                raise RuntimeError(
                    f"mosquitto exited with {self._process.returncode}: "
                    + self.log.read_text(errors="replace")[-2000:]
                )
            if time.monotonic() > deadline:
                self.stop()
                raise RuntimeError("mosquitto did not listen within 10 s")
            time.sleep(0.02)

    def stop(self) -> None:
        """Kill it, as a crash would (no goodbye to the clients)."""
        process, self._process = self._process, None
        if process is not None and process.poll() is None:
            process.kill()
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(timeout=10)

    def restart(self) -> None:
        self.stop()
        self.start()


def start_broker() -> tuple[Broker, tempfile.TemporaryDirectory[str]]:
    directory = tempfile.TemporaryDirectory(prefix="j5aio-mosquitto-")
    for _ in range(5):  # the free port may be taken before mosquitto binds it
        broker = Broker(Path(directory.name))
        try:
            broker.start()
        except RuntimeError:
            continue
        return broker, directory
    directory.cleanup()
    raise RuntimeError("mosquitto could not be started on a free port")
