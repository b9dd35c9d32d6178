"""A robot on the simulated kit with the service, as a program meets it in a match:
metadata before the start, a malformed message, the broker killed mid-run, the remote
start. (The match timer's side is tested with the competition layer.)
"""

from __future__ import annotations

import logging
from pathlib import Path

import anyio
import pytest

from j5aio.competition.metadata import Mode
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import use_kit
from tests.service.broker import Broker
from tests.service.helpers import astmetad_message, eventually, start_event

aiomqtt = pytest.importorskip("aiomqtt")


@pytest.fixture
def service_env(broker: Broker, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Broker:
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    monkeypatch.delenv("J5AIO_METADATA", raising=False)
    monkeypatch.delenv("SBOT_METADATA_PATH", raising=False)
    monkeypatch.setenv("J5AIO_MQTT_URL", f"mqtt://127.0.0.1:{broker.port}/astoria")
    monkeypatch.setenv("J5AIO_START_FILE", str(tmp_path / "start"))
    monkeypatch.setenv("J5AIO_MEDIA_ROOTS", str(tmp_path / "media"))
    return broker


async def publish(port: int, topic: str, payload: object, retain: bool = False) -> None:
    import json

    data = payload if isinstance(payload, bytes) else json.dumps(payload)
    async with aiomqtt.Client("127.0.0.1", port) as client:
        await client.publish(topic, data, qos=1, retain=retain)


async def test_a_match_with_the_service_going_away_and_coming_back(
    service_env: Broker, fresh_kit: None, caplog: pytest.LogCaptureFixture
) -> None:
    broker = service_env
    use_kit()
    await publish(broker.port, "astoria/astmetad", astmetad_message(zone=2), retain=True)
    with caplog.at_level(logging.INFO, "j5aio.service"):
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            # the service's retained metadata is there as soon as the robot is made
            assert (robot.zone, robot.mode) == (2, Mode.DEV)
            motor = robot.motor_boards[0].motors[0]

            await publish(broker.port, "astoria/astmetad", b"{ not json")
            await motor.set_power(0.5)
            assert robot.zone == 2  # the last good metadata stays

            broker.stop()  # mid-run: the program goes on driving
            for _ in range(20):
                await motor.set_power(0.3)
                await anyio.sleep(0.01)
            assert robot.zone == 2

            broker.start()
            await publish(broker.port, "astoria/astmetad", astmetad_message(zone=3),
                          retain=True)
            await eventually(lambda: robot.zone == 3)

            started = anyio.Event()

            async def wait() -> None:
                await robot.wait_start(60)
                started.set()

            async with anyio.create_task_group() as group:
                group.start_soon(wait)
                # a start sent before the wait began may be ignored, as on astoria's
                # robots: press again until it is taken, as a volunteer would
                for _ in range(30):
                    await publish(broker.port, "astoria/broadcast/start_button",
                                  start_event())
                    with anyio.move_on_after(1):
                        await started.wait()
                    if started.is_set():
                        break
            assert started.is_set()
            assert await motor.get_power() == pytest.approx(0.3)
    messages = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert sum("not JSON" in m for m in messages) == 1
    assert any("lost the broker" in m for m in messages)
