"""Without the robot extra (aiomqtt), j5aio imports and the service says what to install."""

from __future__ import annotations

import logging
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from j5aio.service import INSTALL_HINT, ServiceConfig, start_service
from tests.service.broker import Broker

BLOCK_AIOMQTT = textwrap.dedent(
    """
    import sys

    class Block:
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in ("aiomqtt", "paho"):
                raise ImportError(f"{name} is blocked for this test")
            return None

    sys.meta_path.insert(0, Block())
    """
)


def run(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True, text=True, timeout=120, check=False,
    )


def test_import_j5aio_does_not_import_aiomqtt() -> None:
    result = run(
        """
        import sys
        import j5aio, j5aio.service, j5aio.competition, j5aio.kit
        from j5aio.service import ServiceConfig, publish_frame, find_config
        assert not publish_frame(b"jpeg")
        assert "aiomqtt" not in sys.modules and "paho" not in sys.modules, "imported"
        print("OK")
        """
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "OK"


def test_without_aiomqtt_the_service_says_what_to_install() -> None:
    result = run(
        BLOCK_AIOMQTT
        + """
import asyncio, logging
logging.basicConfig(level=logging.ERROR, format="%(message)s")
from j5aio.service import RobotService, ServiceConfig, ServiceNotInstalledError, start_service
config = ServiceConfig(host="127.0.0.1", port=1)
try:
    RobotService(config)
except ServiceNotInstalledError as exc:
    print("RAISED:", exc)
print("STARTED:", asyncio.run(start_service(config)))
"""
    )
    assert result.returncode == 0, result.stderr
    assert "RAISED: Talking to the robot's service" in result.stdout
    assert INSTALL_HINT in result.stdout
    assert "STARTED: None" in result.stdout
    assert INSTALL_HINT in result.stderr  # logged by start_service


async def test_start_service_is_off_where_nothing_configures_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    if Path("/etc/astoria.toml").exists():  # noqa: ASYNC240 - one quick look
        pytest.skip("this machine has /etc/astoria.toml: the service is configured")
    monkeypatch.chdir(tmp_path)
    assert await start_service(environ={}) is None


async def test_start_service_with_a_bad_configuration_logs_and_goes_on(
    caplog: pytest.LogCaptureFixture,
) -> None:
    with caplog.at_level(logging.ERROR, "j5aio.service"):
        assert await start_service(environ={"J5AIO_MQTT_URL": "http://nowhere"}) is None
    assert "configuration is bad" in caplog.text and "mqtt://" in caplog.text
    assert await start_service(environ={"J5AIO_SERVICE": "off"}) is None


async def test_start_service_from_the_environment(broker: Broker) -> None:
    pytest.importorskip("aiomqtt")
    url = f"mqtt://127.0.0.1:{broker.port}/sbot"
    service = await start_service(environ={"J5AIO_MQTT_URL": url})
    assert service is not None
    try:
        await service.wait_connected(timeout=10)
        assert service.config.topic_prefix == "sbot"
        assert service.topics.frames == "sbot/camera/annotated"
    finally:
        await service.stop()
    explicit = await start_service(ServiceConfig(host="127.0.0.1", port=broker.port))
    assert explicit is not None
    await explicit.stop()
