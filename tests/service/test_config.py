from __future__ import annotations

from pathlib import Path

import pytest

from j5aio.service.config import (
    ServiceConfig,
    ServiceConfigError,
    find_config,
    parse_mqtt_url,
    read_astoria_config,
    service_disabled,
)

ASTORIA_TOML = """
[mqtt]
host = "10.0.0.5"
port = 1884
enable_tls = false
topic_prefix = "robot"
force_protocol_version_3_1 = true

[wifi]
interface = "wlan0"
bridge = "br0"
enable_wpa3 = false

[system]
cache_dir = "/var/cache/astoria"
"""


def write(tmp_path: Path, text: str, name: str = "astoria.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_astoria_file_gives_its_mqtt_table(tmp_path: Path) -> None:
    config = read_astoria_config(write(tmp_path, ASTORIA_TOML))
    assert (config.host, config.port, config.topic_prefix) == ("10.0.0.5", 1884, "robot")
    assert config.mqtt_v311 and not config.tls
    # as sr-robot3 publishes them: no prefix
    assert config.frame_topic == "camera/annotated"
    assert config.topic("astmetad") == "robot/astmetad"


def test_astoria_defaults(tmp_path: Path) -> None:
    config = read_astoria_config(write(tmp_path, '[mqtt]\nhost = "localhost"\nport = 1883\n'))
    assert config.topic_prefix == "astoria"
    assert not config.tls and not config.mqtt_v311


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("[wifi]\n", "no [mqtt] table"),
        ('[mqtt]\nport = 1883\n', "must give 'host'"),
        ('[mqtt]\nhost = "h"\n', "must give 'port'"),
        ('[mqtt]\nhost = "h"\nport = "1883"\n', "port must be a int"),
        ('[mqtt]\nhost = "h"\nport = true\n', "port must be a int"),
        ('[mqtt]\nhost = "h"\nport = 1883\nenable_tls = 1\n', "enable_tls must be a bool"),
        ('[mqtt]\nhost = "h"\nport = 1883\nprefix = "x"\n', "does not know: prefix"),
        ('[mqtt]\nhost = "h"\nport = 70000\n', "from 1 to 65535"),
        ('[mqtt]\nhost = "h"\nport = 1883\ntopic_prefix = "a/#"\n', "without '+', '#'"),
        ("[mqtt\n", "not valid TOML"),
    ],
)
def test_bad_astoria_file_says_what_is_wrong(tmp_path: Path, text: str, words: str) -> None:
    path = write(tmp_path, text)
    with pytest.raises(ServiceConfigError, match=words.replace("[", r"\[").replace("+", r"\+")):
        read_astoria_config(path)


def test_unreadable_and_huge_astoria_files(tmp_path: Path) -> None:
    with pytest.raises(ServiceConfigError, match="cannot be read"):
        read_astoria_config(tmp_path)  # a directory
    big = write(tmp_path, "# " + "x" * 70_000)
    with pytest.raises(ServiceConfigError, match="larger than"):
        read_astoria_config(big)
    binary = tmp_path / "bin.toml"
    binary.write_bytes(b"\xff\xfe")
    with pytest.raises(ServiceConfigError, match="not valid TOML"):
        read_astoria_config(binary)


def test_url_as_sbot_reads_it() -> None:
    config = parse_mqtt_url("mqtts://team:secret@broker.local/sbot/robot1", "SBOT_MQTT_URL")
    assert (config.host, config.port, config.tls) == ("broker.local", 8883, True)
    assert (config.username, config.password) == ("team", "secret")
    assert config.topic_prefix == "sbot/robot1"
    assert config.topic("start_button") == "sbot/robot1/start_button"
    assert config.frame_topic == "sbot/robot1/camera/annotated"
    assert "secret" not in repr(config)
    plain = parse_mqtt_url("mqtt://127.0.0.1:1999")
    assert (plain.port, plain.tls, plain.topic_prefix) == (1999, False, "")
    assert plain.topic("start_button") == "start_button"
    assert plain.frame_topic == "camera/annotated"


@pytest.mark.parametrize(
    ("url", "words"),
    [
        ("http://h/x", "mqtt:// or mqtts://"),
        ("mqtt:///prefix", "names no host"),
        ("mqtt://h:99999/x", "from 1 to 65535"),
        ("mqtt://h:abc/x", "from 1 to 65535"),
    ],
)
def test_bad_url(url: str, words: str) -> None:
    with pytest.raises(ServiceConfigError, match=words):
        parse_mqtt_url(url)


def test_config_checks_its_fields() -> None:
    with pytest.raises(ServiceConfigError, match="host"):
        ServiceConfig(host="")
    with pytest.raises(ServiceConfigError, match="port"):
        ServiceConfig(host="h", port=0)


def test_find_config_order(tmp_path: Path) -> None:
    toml = write(tmp_path, ASTORIA_TOML)
    missing = tmp_path / "missing.toml"
    paths = (missing, toml)
    assert find_config({}, (missing,)) is None
    found = find_config({}, paths)
    assert found is not None and found.source == str(toml)
    sbot = find_config({"SBOT_MQTT_URL": "mqtt://s:1/p"}, paths)
    assert sbot is not None and (sbot.host, sbot.source) == ("s", "SBOT_MQTT_URL")
    ours = find_config(
        {"SBOT_MQTT_URL": "mqtt://s:1/p", "J5AIO_MQTT_URL": "mqtt://j:2/q"}, paths
    )
    assert ours is not None and (ours.host, ours.source) == ("j", "J5AIO_MQTT_URL")
    for off in ("off", "OFF", "0", "no", "false"):
        assert find_config({"J5AIO_SERVICE": off, "J5AIO_MQTT_URL": "mqtt://j"}, paths) is None
        assert service_disabled({"J5AIO_SERVICE": off})
    assert not service_disabled({"J5AIO_SERVICE": "on"})
    assert find_config({"J5AIO_SERVICE": "on"}, paths) is not None


def test_find_config_reads_the_working_directory(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write(tmp_path, ASTORIA_TOML)
    monkeypatch.chdir(tmp_path)
    for name in ("J5AIO_SERVICE", "J5AIO_MQTT_URL", "SBOT_MQTT_URL"):
        monkeypatch.delenv(name, raising=False)
    config = find_config()
    assert config is not None and config.host == "10.0.0.5"
