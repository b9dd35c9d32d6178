"""A robot's camera shows its annotated frames on the robot's web page through the service."""

from __future__ import annotations

import base64
import json
from pathlib import Path

import anyio
import pytest

from tests.service.broker import Broker
from tests.service.helpers import eventually

np = pytest.importorskip("numpy")
cv2 = pytest.importorskip("cv2")
pytest.importorskip("pyapriltags")
aiomqtt = pytest.importorskip("aiomqtt")

from j5aio.kit import KitRobot  # noqa: E402
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT  # noqa: E402
from j5aio.simulator.kit import use_kit  # noqa: E402


@pytest.fixture
def robot_service_env(
    broker: Broker, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> Broker:
    monkeypatch.delenv("J5AIO_SERVICE", raising=False)
    monkeypatch.setenv("J5AIO_MQTT_URL", f"mqtt://127.0.0.1:{broker.port}/robot")
    monkeypatch.setenv("J5AIO_START_FILE", str(tmp_path / "start"))
    monkeypatch.setenv("J5AIO_MEDIA_ROOTS", str(tmp_path / "media"))
    return broker


async def test_see_and_save_publish_the_annotated_frame(
    robot_service_env: Broker, fresh_kit: None, tmp_path: Path
) -> None:
    use_kit()
    frames: list[dict[str, object]] = []
    async with aiomqtt.Client("127.0.0.1", robot_service_env.port) as watcher:
        await watcher.subscribe("robot/camera/annotated", qos=1)

        async def watch() -> None:
            async for message in watcher.messages:
                assert isinstance(message.payload, bytes)
                frames.append(json.loads(message.payload))

        async with anyio.create_task_group() as group:
            group.start_soon(watch)
            async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
                assert robot.camera is not None
                service = robot._service
                assert service is not None
                await service.wait_connected(timeout=10)
                markers = await robot.camera.see()
                assert markers, "the simulated robot looks at the arena's markers"
                await eventually(lambda: len(frames) == 1)
                # save() writes the annotated picture and offers it too (taken once the
                # rate allows: five frames a second at most)
                with anyio.fail_after(10):
                    while len(frames) < 2:
                        await robot.camera.save(tmp_path / "seen.png")
                        await anyio.sleep(0.05)
                assert (tmp_path / "seen.png").is_file()
            group.cancel_scope.cancel()
    data = frames[0]["data"]
    assert isinstance(data, str) and data.startswith("data:image/jpeg;base64, ")
    jpeg = base64.b64decode(data.split(", ", 1)[1])
    picture = cv2.imdecode(np.frombuffer(jpeg, dtype=np.uint8), cv2.IMREAD_COLOR)
    assert picture is not None and picture.ndim == 3  # a colour picture: annotated
