"""Where nothing configures the robot service, starting it reads no configuration at all."""

from __future__ import annotations

import logging
import os
from pathlib import Path

import pytest

from j5aio.competition import service_state
from j5aio.service import auto, config
from j5aio.service.auto import start_service


def test_the_quick_look_reads_what_find_config_reads() -> None:
    assert service_state._SERVICE_VARIABLE == config.SERVICE_VARIABLE
    assert set(service_state._URL_VARIABLES) == {
        config.MQTT_URL_VARIABLE,
        config.SBOT_MQTT_URL_VARIABLE,
    }
    assert tuple(map(Path, service_state._CONFIG_PATHS)) == config.ASTORIA_CONFIG_PATHS
    assert service_state._OFF == config._OFF


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
    monkeypatch.setattr(service_state, "_CONFIG_PATHS", ("astoria.toml",))
    assert service_state.service_may_be_configured(environ) is expected
    # Whatever the quick look says, find_config agrees where it says "not configured".
    if not expected:
        assert config.find_config(environ, search_paths=(Path("astoria.toml"),)) is None


def test_astorias_file_in_the_working_directory_may_configure_it(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.chdir(tmp_path)
    assert not service_state.service_may_be_configured({}) or os.path.isfile("/etc/astoria.toml")
    (tmp_path / "astoria.toml").write_text("[mqtt]\nhost = 'localhost'\nport = 1883\n")
    assert service_state.service_may_be_configured({})
    assert not service_state.service_may_be_configured({"J5AIO_SERVICE": "no"})


async def test_nothing_configured_starts_nothing_and_says_so(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(service_state, "_CONFIG_PATHS", ("astoria.toml",))
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
    monkeypatch.setattr(auto, "service_may_be_configured", lambda environ: True)
    assert await start_service(environ={}) is None  # find_config: nothing configures it


def test_the_quick_look_reads_the_processs_environment_by_default(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("J5AIO_MQTT_URL", "mqtt://robot.invalid")
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    assert service_state.service_may_be_configured()
    monkeypatch.setenv("J5AIO_SERVICE", "off")
    assert not service_state.service_may_be_configured()
