"""Where nothing configures the robot service, starting it reads no configuration at all."""

from __future__ import annotations

import logging
import os
from pathlib import Path

import pytest

from j5aio.service import auto, config
from j5aio.service.auto import start_service


def test_the_quick_look_reads_what_find_config_reads() -> None:
    assert auto._SERVICE_VARIABLE == config.SERVICE_VARIABLE
    assert set(auto._URL_VARIABLES) == {config.MQTT_URL_VARIABLE, config.SBOT_MQTT_URL_VARIABLE}
    assert tuple(map(Path, auto._CONFIG_PATHS)) == config.ASTORIA_CONFIG_PATHS
    assert auto._OFF == config._OFF


@pytest.mark.parametrize(
    ("environ", "expected"),
    [
        ({}, False),
        ({"J5AIO_MQTT_URL": "mqtt://robot"}, True),
        ({"SBOT_MQTT_URL": "mqtt://robot"}, True),
        ({"SBOT_MQTT_URL": ""}, False),
        ({"J5AIO_SERVICE": " OFF ", "J5AIO_MQTT_URL": "mqtt://robot"}, False),
        ({"J5AIO_SERVICE": "on", "J5AIO_MQTT_URL": "mqtt://robot"}, True),
    ],
)
def test_the_variables_say_whether_it_may_be_configured(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, environ: dict[str, str], expected: bool
) -> None:
    monkeypatch.chdir(tmp_path)  # (no astoria.toml here)
    monkeypatch.setattr(auto, "_CONFIG_PATHS", ("astoria.toml",))
    assert auto._may_be_configured(environ) is expected
    # Whatever the quick look says, find_config agrees where it says "not configured".
    if not expected:
        assert config.find_config(environ, search_paths=(Path("astoria.toml"),)) is None


def test_astorias_file_in_the_working_directory_may_configure_it(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.chdir(tmp_path)
    assert not auto._may_be_configured({}) or os.path.isfile("/etc/astoria.toml")
    (tmp_path / "astoria.toml").write_text("[mqtt]\nhost = 'localhost'\nport = 1883\n")
    assert auto._may_be_configured({})
    assert not auto._may_be_configured({"J5AIO_SERVICE": "no"})


async def test_nothing_configured_starts_nothing_and_says_so(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(auto, "_CONFIG_PATHS", ("astoria.toml",))
    with caplog.at_level(logging.DEBUG, logger="j5aio.service.auto"):
        assert await start_service(environ={}) is None
    assert "Robot service: not configured here" in caplog.text


@pytest.mark.skipif(
    os.path.isfile("/etc/astoria.toml"),
    reason="this machine has astoria's configuration: the service is configured",
)
async def test_find_config_decides_where_the_quick_look_cannot_tell(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(auto, "_may_be_configured", lambda environ: True)
    assert await start_service(environ={}) is None  # find_config: nothing configures it
