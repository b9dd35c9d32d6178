"""j5aio.testing.mosquitto: a broker of the test's own, started, restarted and stopped."""

from __future__ import annotations

import socket
from pathlib import Path

import pytest

from j5aio.testing import mosquitto
from j5aio.testing.mosquitto import MOSQUITTO, Broker, free_port, start_broker


def accepts(port: int) -> bool:
    try:
        with socket.create_connection(("127.0.0.1", port), timeout=1):
            return True
    except OSError:
        return False


needs_mosquitto = pytest.mark.skipif(
    MOSQUITTO is None, reason="mosquitto is not installed (Debian: apt-get install mosquitto)",
)


def test_a_free_port_is_one_nothing_listens_on() -> None:
    assert not accepts(free_port())


@needs_mosquitto
def test_a_broker_listens_comes_back_on_its_port_and_stops() -> None:
    broker, folder = start_broker()
    try:
        assert broker.running and accepts(broker.port)
        with pytest.raises(RuntimeError, match="is running already"):
            broker.start()
        port = broker.port
        broker.restart()
        assert broker.running and broker.port == port and accepts(port)
        broker.stop()
        assert not broker.running and not accepts(port)
        broker.stop()  # stopping a stopped broker does nothing
        assert broker.log.exists()
    finally:
        broker.stop()
        folder.cleanup()


@needs_mosquitto
def test_a_broker_that_exits_says_why(tmp_path: Path) -> None:
    broker = Broker(tmp_path)
    broker.config.write_text("no_such_option true\n")
    with pytest.raises(RuntimeError, match="mosquitto exited with"):
        broker.start()
    assert not broker.running


def test_without_mosquitto_a_broker_cannot_be_made(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(mosquitto, "MOSQUITTO", None)
    with pytest.raises(RuntimeError, match="mosquitto is not installed"):
        Broker(tmp_path)
    with pytest.raises(RuntimeError, match=r"could not be started.*not installed"):
        start_broker()
