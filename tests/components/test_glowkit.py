"""The worked example of docs/new-component.rst runs: a new kind of component, end to end."""

from __future__ import annotations

import importlib
import inspect
import re
import sys
import uuid
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest

from j5aio import sync, syncgen
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.transports import SimulatorStream
from j5aio.components import DistanceSensor, DistanceSensorInterface
from j5aio.testing import RecordingStream
from j5aio.testing.conformance import DistanceSensorInterfaceConformance, DistanceSensorSubject
from j5aio.testing.console import ConsoleScript
from j5aio.testing.plugin import PtySimulatorFactory
from j5aio.view.describe import Update, board_components, describe_call

from .glowkit import boards, light_sensor
from .glowkit.backend import GlowBackend
from .glowkit.boards import GlowBoard
from .glowkit.conformance import LightSensorInterfaceConformance, LightSensorSubject
from .glowkit.console import GlowConsoleBackend
from .glowkit.light_sensor import LightSensor, LightSensorInterface
from .glowkit.simulator import GlowSimulator


class Connected:
    """A Glow Board's backend over an in-memory stream to a fresh simulator."""

    simulator: GlowSimulator
    stream: RecordingStream

    async def connect(self) -> GlowBoard:
        self.simulator = GlowSimulator()
        self.stream = RecordingStream(SimulatorStream(self.simulator, time_scale=0))
        board = await GlowBackend.from_stream(
            self.stream, port="sim", serial_number="GLOW1", time_scale=0,
        )
        await board.setup()
        self.stream.clear()
        return board

    async def connect_backend(self) -> GlowBackend:
        board = await self.connect()
        assert isinstance(board.backend, GlowBackend)
        return board.backend


@pytest.fixture
async def glow() -> AsyncIterator[tuple[GlowBoard, Connected]]:
    connected = Connected()
    board = await connected.connect()
    yield board, connected
    await board.close()


async def test_a_program_reads_the_new_component_and_the_built_in_one(
    glow: tuple[GlowBoard, Connected],
) -> None:
    board, connected = glow
    connected.simulator.lux[2] = 480.0
    connected.simulator.object_mm = 250

    sensor = board.light_sensors[2]
    await sensor.set_gain(16)
    assert await sensor.get_gain() == 16
    assert connected.simulator.gains == [1, 1, 16, 1]
    assert await sensor.get_lux() == 480.0
    assert await board.distance_sensors[0].distance_mm() == 250.0
    assert await board.distance_sensors[0].distance() == 0.25
    connected.simulator.object_mm = None
    assert await board.distance_sensors[0].distance() is None
    assert connected.stream.sent == b"G2 16\nG2\nL2\nD\nD\nD\n"


@pytest.mark.parametrize(
    ("gain", "error", "says"),
    [
        (3, ValueError, "a gain must be one of (1, 4, 16, 64); got 3"),
        (4.0, TypeError, "a gain must be an int, one of (1, 4, 16, 64); got 4.0"),
        (True, TypeError, "got True"),
    ],
)
async def test_a_bad_gain_is_refused_by_the_component_sending_nothing(
    glow: tuple[GlowBoard, Connected], gain: object, error: type[Exception], says: str,
) -> None:
    board, connected = glow
    with pytest.raises(error, match=re.escape(says)):
        await board.light_sensors[0].set_gain(gain)  # type: ignore[arg-type]
    assert connected.stream.sent == b""
    assert connected.simulator.gains == [1, 1, 1, 1]


async def test_a_missing_sensor_is_a_clear_error(glow: tuple[GlowBoard, Connected]) -> None:
    board, _ = glow
    with pytest.raises(LookupError, match="light sensor"):
        board.light_sensors[4]
    assert [type(c) for c in board.light_sensors] == [LightSensor] * 4
    assert [type(c) for c in board.distance_sensors] == [DistanceSensor]


class TestGlowLightSensors(Connected, LightSensorInterfaceConformance):
    async def make_backend(self) -> LightSensorSubject:
        backend = await self.connect_backend()

        async def set_lux(identifier: int, lux: float) -> None:
            self.simulator.lux[identifier] = lux

        async def observe_gain(identifier: int) -> int:
            return self.simulator.gains[identifier]

        return LightSensorSubject(
            backend=backend,
            identifiers=range(4),
            set_lux=set_lux,
            observe_gain=observe_gain,
            traffic=lambda: self.stream.sent,
        )


class TestGlowDistanceSensor(Connected, DistanceSensorInterfaceConformance):
    async def make_backend(self) -> DistanceSensorSubject:
        backend = await self.connect_backend()

        async def place_object(identifier: int, millimetres: float | None) -> None:
            self.simulator.object_mm = millimetres

        return DistanceSensorSubject(
            backend=backend,
            identifiers=[0],
            place_object=place_object,
            traffic=lambda: self.stream.sent,
        )


def test_a_backend_without_the_new_interface_is_refused_when_its_class_is_made() -> None:
    with pytest.raises(TypeError, match=re.escape(
        "backend Forgetful cannot drive GlowBoard: it does not implement "
        "LightSensorInterface (for LightSensor)",
    )):
        class Forgetful(SerialHardwareBackend[GlowBoard], DistanceSensorInterface):
            board = GlowBoard

            async def _handshake(self, *, time_scale: float) -> None:
                return None

            async def get_distance_sensor_mm(self, identifier: int) -> float | None:
                return None

    class Half(SerialHardwareBackend[GlowBoard], LightSensorInterface, DistanceSensorInterface):
        board = GlowBoard

        async def _handshake(self, *, time_scale: float) -> None:
            return None

        async def get_light_sensor_lux(self, identifier: int) -> float:
            return 0.0

        async def get_distance_sensor_mm(self, identifier: int) -> float | None:
            return None

    assert inspect.isabstract(Half)
    assert sorted(Half.__abstractmethods__) == ["get_light_sensor_gain", "set_light_sensor_gain"]


class ConsoleGlow:
    """A Glow Board's console backend, whose prompts a :class:`ConsoleScript` answers."""

    script: ConsoleScript

    def console_backend(self) -> GlowConsoleBackend:
        self.script = ConsoleScript()
        return GlowConsoleBackend("GLOW1", self.script.console_class())

    def printed(self) -> bytes:
        """What the console printed: the console's traffic, for the suites' ``traffic``."""
        return "\n".join(self.script.printed).encode()


class TestGlowConsoleLightSensors(ConsoleGlow, LightSensorInterfaceConformance):
    async def make_backend(self) -> LightSensorSubject:
        backend = self.console_backend()

        async def set_lux(identifier: int, lux: float) -> None:
            self.script.answer(f"Light on light sensor {identifier} ", str(lux), replace=True)

        async def observe_gain(identifier: int) -> int:
            said = f"Light sensor {identifier} gain set to "
            last = [line for line in self.script.printed if said in line][-1]
            return int(last.rpartition(said)[2])

        return LightSensorSubject(
            backend=backend, identifiers=range(4), set_lux=set_lux,
            observe_gain=observe_gain, traffic=self.printed,
        )


class TestGlowConsoleDistanceSensor(ConsoleGlow, DistanceSensorInterfaceConformance):
    async def make_backend(self) -> DistanceSensorSubject:
        backend = self.console_backend()

        async def place_object(identifier: int, millimetres: float | None) -> None:
            answer = "-" if millimetres is None else str(millimetres)
            self.script.answer(f"distance sensor {identifier} ", answer, replace=True)

        return DistanceSensorSubject(
            backend=backend, identifiers=[0], place_object=place_object, traffic=self.printed,
        )


async def test_the_console_asks_again_until_the_answer_is_a_distance() -> None:
    script = ConsoleScript()
    board = GlowBoard("GLOW1", GlowConsoleBackend("GLOW1", script.console_class()))
    for answer in ("far", "-5", "250"):
        script.answer("Distance for distance sensor 0", answer)
    assert await board.distance_sensors[0].distance() == 0.25
    assert len(script.prompts) == 3
    assert any("Unable to construct" in line for line in script.printed)


async def test_the_live_view_shows_the_new_component_by_the_naming_rule(
    glow: tuple[GlowBoard, Connected],
) -> None:
    board, _ = glow
    kinds = {(info.kind, info.identifier) for info in board_components(board)}
    assert kinds == {("lightsensor", "0"), ("lightsensor", "1"), ("lightsensor", "2"),
                     ("lightsensor", "3"), ("distancesensor", "0")}
    assert describe_call(board, "set_light_sensor_gain", (2, 16), None) == Update(
        "lightsensor", "2", "light_sensor_gain", 16,
    )
    assert describe_call(board, "get_distance_sensor_mm", (0,), 250.0) == Update(
        "distancesensor", "0", "distance_sensor_mm", 250.0,
    )


def test_the_sync_face_is_generated_and_drives_the_board(
    tmp_path: Path, j5aio_pty_simulator: PtySimulatorFactory,
) -> None:
    text = syncgen.generate([boards.__name__, light_sensor.__name__])
    assert "class LightSensor(_sync.IdentifiedComponent[" in text
    assert "    def lux(self) -> float:" in text
    assert "    @gain.setter" in text
    assert "class GlowBoard(_sync.Board):" in text

    name = f"glow_sync_{uuid.uuid4().hex}"
    (tmp_path / f"{name}.py").write_text(text, encoding="utf-8")
    sys.path.insert(0, str(tmp_path))
    try:
        glow_sync = importlib.import_module(name)
        simulator = GlowSimulator()
        simulator.lux[1] = 12.5
        simulator.object_mm = 1234
        path = j5aio_pty_simulator(simulator)
        # typed as any board here: the generated module is imported at run time
        glow: Any = sync.BoardGroup.get_board_group(
            GlowBoard, GlowBackend, ports=[path],
        ).singular()
        try:
            assert type(glow) is glow_sync.GlowBoard
            glow.light_sensors[1].gain = 64
            assert glow.light_sensors[1].gain == 64
            assert glow.light_sensors[1].lux == 12.5
            assert isinstance(glow.distance_sensors[0], sync.DistanceSensor)
            assert glow.distance_sensors[0].distance() == 1.234
            assert simulator.gains == [1, 64, 1, 1]
            with pytest.raises(AttributeError):
                glow.light_sensors[1].gian = 4
        finally:
            glow.close()
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop(name, None)
