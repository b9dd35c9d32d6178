"""A real Mosquitto broker for tests and benchmarks, on a free port of 127.0.0.1.

The robot service (:mod:`j5aio.service`) talks MQTT; testing it against a real broker
finds what a fake would hide (reconnection after the broker went away, retained
messages, a slow client). This starts Debian's ``mosquitto`` (``apt-get install
mosquitto``) as a broker of the caller's own, with a throw-away configuration::

    broker, folder = start_broker()
    try:
        ...  # connect to 127.0.0.1:broker.port
        broker.restart()  # as a crashed broker coming back, on the same port
    finally:
        broker.stop()
        folder.cleanup()
"""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Final

__all__ = ["MOSQUITTO", "Broker", "free_port", "start_broker"]

#: The broker program: ``J5AIO_TEST_MOSQUITTO`` if set, else ``mosquitto`` found on the
#: ``PATH`` or in ``/usr/sbin`` (where Debian puts it); ``None`` when there is none.
MOSQUITTO: Final = os.environ.get("J5AIO_TEST_MOSQUITTO") or shutil.which(
    "mosquitto", path=os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/sbin"])
)

#: Seconds a broker may take to listen once started.
_START_TIMEOUT: Final = 10.0


def free_port() -> int:
    """A TCP port of 127.0.0.1 that nothing listens on now."""
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
    """One mosquitto process on a free port, stopped and started again on it at will.

    :param directory: where its configuration and its log (``mosquitto.log``) go.
    :raises RuntimeError: mosquitto is not installed.
    """

    def __init__(self, directory: Path) -> None:
        if MOSQUITTO is None:
            raise RuntimeError("mosquitto is not installed (Debian: apt-get install mosquitto)")
        self._program = MOSQUITTO
        #: The port it listens on, on 127.0.0.1 (anonymous clients allowed).
        self.port = free_port()
        #: Its configuration file.
        self.config = directory / "mosquitto.conf"
        #: Its log file (what it prints, kept across restarts).
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
        """Whether its process is running."""
        return self._process is not None and self._process.poll() is None

    def start(self) -> float:
        """Start it and wait until it accepts connections.

        :returns: the moment it first accepted one (:func:`time.perf_counter`).
        :raises RuntimeError: it is running already, it exited (its log is in the
            message), or it did not listen within 10 s.
        """
        if self.running:
            raise RuntimeError(f"the broker on port {self.port} is running already")
        with self.log.open("ab") as log:
            self._process = subprocess.Popen(
                [self._program, "-c", str(self.config)], stdout=log, stderr=log,
                stdin=subprocess.DEVNULL,
            )
        deadline = time.monotonic() + _START_TIMEOUT
        while not _accepts(self.port):
            if self._process.poll() is not None:
                raise RuntimeError(
                    f"mosquitto exited with {self._process.returncode}: "
                    + self.log.read_text(errors="replace")[-2000:]
                )
            if time.monotonic() > deadline:
                self.stop()
                raise RuntimeError(f"mosquitto did not listen within {_START_TIMEOUT:g} s")
            time.sleep(0.001)
        return time.perf_counter()

    def stop(self) -> None:
        """Kill it, as a crash would (no goodbye to the clients); nothing if it is stopped."""
        process, self._process = self._process, None
        if process is not None and process.poll() is None:
            process.kill()
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(timeout=10)

    def restart(self) -> float:
        """Kill it and start it again on the same port; see :meth:`start`."""
        self.stop()
        return self.start()


def start_broker() -> tuple[Broker, tempfile.TemporaryDirectory[str]]:
    """Start a broker of its own, with a temporary folder for its files.

    The caller stops the broker and cleans the folder up when done.

    :raises RuntimeError: mosquitto is not installed, or would not start (five tries: a
        free port may be taken before mosquitto binds it).
    """
    directory = tempfile.TemporaryDirectory(prefix="j5aio-mosquitto-")
    failures: list[str] = []
    for _ in range(5):
        try:
            broker = Broker(Path(directory.name))
            broker.start()
        except RuntimeError as error:
            failures.append(str(error))
            if MOSQUITTO is None:
                break
            continue
        return broker, directory
    directory.cleanup()
    raise RuntimeError(f"mosquitto could not be started on a free port: {failures[-1]}")
