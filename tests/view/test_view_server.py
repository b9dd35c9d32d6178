"""The live view's server, observer and simulator controls, without a browser."""

from __future__ import annotations

import asyncio
import contextlib
import io
import json
import logging
from collections.abc import AsyncIterator
from typing import Any

import pytest

pytest.importorskip("aiohttp", reason="the view extra is not installed")

import aiohttp

from j5aio.backends.backend import CALL_OBSERVERS
from j5aio.backends.hardware.transports.trace import TRACE, WIRE_LOGGER_PREFIX
from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit
from j5aio.view import (
    VIEW_PORT_VARIABLE,
    LiveView,
    serve_view,
    start_view,
    view_requested,
)
from j5aio.view.controls import ControlError, apply_control, controls_of
from j5aio.view.describe import ComponentInfo, board_components
from j5aio.view.state import ViewState


@contextlib.asynccontextmanager
async def kit_and_view(
    config: KitConfig | None = None,
) -> AsyncIterator[tuple[KitRobot, SimulatedKit, LiveView]]:
    kit = use_kit(config or KitConfig(motor_boards=1, ruggeduinos=1))
    async with (
        KitRobot(environment=SIMULATED_ENVIRONMENT) as robot,
        serve_view(out=io.StringIO()) as view,
    ):
        yield robot, kit, view


def ws_url(view: LiveView) -> str:
    return view.url.replace("/?", "/ws?")


def control_url(view: LiveView) -> str:
    return view.url.replace("/?", "/control?")


async def messages_until(ws: Any, check: Any, timeout: float = 5.0) -> dict[str, Any]:
    async with asyncio.timeout(timeout):
        while True:
            message = json.loads((await ws.receive()).data)
            if check(message):
                return dict(message)


async def test_the_page_the_socket_and_the_controls() -> None:
    async with kit_and_view() as (robot, _kit, view), aiohttp.ClientSession() as session:
        async with session.get(view.url) as response:
            assert response.status == 200
            page = await response.text()
            assert "j5aio live view" in page and "{{" not in page
            policy = response.headers["Content-Security-Policy"]
            assert "script-src 'nonce-" in policy and "default-src 'none'" in policy
            assert response.headers["Referrer-Policy"] == "no-referrer"
        async with session.get(view.url.split("?")[0]) as response:
            assert response.status == 403
        async with session.get(view.url, headers={"Origin": "http://elsewhere:1"}) as response:
            assert response.status == 403
        async with session.get(view.url.replace("/?", "/etc/passwd?")) as response:
            assert response.status == 404  # no file access: one page only

        async with session.ws_connect(ws_url(view)) as ws:
            first = await messages_until(ws, lambda m: "boards" in m)
            serials = [b["serial"] for b in first["boards"]]
            assert serials == sorted(b.serial_number for b in robot.boards())
            motor_board = next(b for b in first["boards"] if b["serial"] == "SIMMB0")
            assert motor_board["state"] == "connected" and motor_board["simulated"]
            assert [c["id"] for c in motor_board["components"]] == [
                "SIMMB0:motor:0",
                "SIMMB0:motor:1",
            ]
            assert view.watchers == 1

            await robot.motor_boards[0].motors[0].set_power(-0.4)
            message = await messages_until(ws, lambda m: "values" in m)
            assert ["SIMMB0:motor:0", "motor_state", -0.4] in message["values"]
            # the wire log of the motor board, recorded while someone watches
            await robot.motor_boards[0].motors[0].set_power(0.2)
            message = await messages_until(ws, lambda m: "log" in m)
            assert any("SIMMB0" in port and "->" in line for port, line in message["log"])

            async def control(target: str, value: Any) -> tuple[int, dict[str, Any]]:
                async with session.post(
                    control_url(view), json={"control": target, "value": value}
                ) as r:
                    return r.status, await r.json()

            assert await control("SIMPB0:battery-voltage", 11.5) == (200, {"ok": True})
            assert await robot.power_board.battery_sensor.get_voltage() == pytest.approx(
                11.5, abs=0.05
            )
            status, body = await control("SIMPB0:battery-voltage", "lots")
            assert status == 400 and "number" in body["error"]
            assert (await control("NOPE:plug", True))[0] == 404
            async with session.post(control_url(view), data="not json") as response:
                assert response.status == 400

            assert await control("SIMMB0:plug", False) == (200, {"ok": True})
            message = await messages_until(
                ws,
                lambda m: any(
                    b["serial"] == "SIMMB0" and b["state"] == "disconnected"
                    for b in m.get("boards", [])
                ),
            )
            assert await control("SIMMB0:plug", True) == (200, {"ok": True})
            await messages_until(
                ws,
                lambda m: any(
                    b["serial"] == "SIMMB0" and b["state"] == "connected"
                    for b in m.get("boards", [])
                ),
            )
        for _ in range(100):
            if view.watchers == 0:
                break
            await asyncio.sleep(0.02)
        assert view.watchers == 0
    assert view.state not in CALL_OBSERVERS


async def test_controls_of_each_simulated_board() -> None:
    async with kit_and_view() as (robot, kit, _view):
        await robot.arduinos[0].ultrasound_sensors[4, 5].distance()
        power, arduino, rugged = robot.power_board, robot.arduinos[0], robot.ruggeduinos[0]
        names = [c["name"] for c in controls_of(power, board_components(power))]
        assert names == ["start-button", "battery-voltage", "plug"]
        state = ViewState()
        state(arduino.backend, "get_ultrasound_distance", (4, 5), None, None)
        state.changes(0, 0)
        record = next(r for r in state.boards() if r.board is arduino)
        named = {c["name"]: c for c in controls_of(arduino, record.components)}
        assert {f"pin-{n}" for n in range(2, 14)} | {f"analog-{n}" for n in range(14, 20)} <= set(
            named
        )
        assert named["ultrasound-4-5"]["value"] is None and named["plug"]["value"] is True

        apply_control(arduino, "pin-3", "high")
        assert kit.sb_arduinos[0].pins.input_level(3) is True
        apply_control(arduino, "pin-3", "float")
        assert kit.sb_arduinos[0].pins.input_level(3) is None
        apply_control(rugged, "analog-15", 1.25)
        assert await rugged.pins[15].analogue_read() == pytest.approx(1.25, abs=0.01)
        apply_control(arduino, "ultrasound-4-5", 0.75)
        assert await arduino.ultrasound_sensors[4, 5].distance() == pytest.approx(0.75, abs=0.01)
        assert controls_of(arduino, record.components)[-2]["value"] == pytest.approx(0.75, abs=0.01)
        apply_control(arduino, "ultrasound-4-5", None)
        apply_control(power, "start-button", True)
        assert await power.start_button.get_is_pressed()
        await asyncio.sleep(0.4)
        assert not await power.start_button.get_is_pressed()

        for board, name, value in [
            (arduino, "pin-3", "up"),
            (arduino, "pin-1", "high"),
            (arduino, "analog-14", 9.0),
            (arduino, "analog-14", True),
            (arduino, "analog-x", 1.0),
            (arduino, "ultrasound-4", 1.0),
            (arduino, "start-button", True),
            (power, "plug", "yes"),
            (power, "battery-voltage", float("nan")),
            (robot.motor_boards[0], "pin-3", "high"),
        ]:
            with pytest.raises(ControlError):
                apply_control(board, name, value)


async def test_hardware_boards_are_read_only() -> None:
    from j5aio.environments import console_environment

    with contextlib.redirect_stdout(io.StringIO()):
        async with KitRobot(environment=console_environment()) as robot:
            board = robot.power_board
            assert controls_of(board, board_components(board)) == []
            with pytest.raises(ControlError, match="read-only"):
                apply_control(board, "start-button", True)


async def test_errors_and_closed_boards_show_as_states() -> None:
    kit = use_kit(KitConfig(motor_boards=1))
    state = ViewState()
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        board = robot.motor_boards[0]
        from j5aio.errors import BoardDisconnectionError

        state(board.backend, "set_motor_state", (0, 0.5), None, BoardDisconnectionError("gone"))
        assert state.error_of(board) == "gone"
        state(board.backend, "set_motor_state", (0, 0.5), None, ValueError("not a link error"))
        assert state.error_of(board) == "gone"
        state(board.backend, "set_motor_state", (0, 0.25), None, None)
        state(board.backend, "get_motor_state", (0,), 0.5, None)  # newer: shown
        assert state.error_of(board) is None
        state(board.backend, "set_motor_state", ([1], 0.1), None, None)  # unhashable: not kept
        assert state.changes(0, 0).values == [("SIMMB0:motor:0", "motor_state", 0.5)]
        assert state.changes(state.changes(0, 0).value_mark, 0).values == []

        class Stranger:
            pass

        state(Stranger(), "set_motor_state", (0, 0.5), None, None)  # type: ignore[arg-type]
        assert len(state.changes(0, 0).values) == 1
        assert kit
        await board.close()
        assert next(r for r in state.boards() if r.board is board).closed


def test_the_wire_log_is_kept_bounded_and_levels_restored() -> None:
    state = ViewState()
    logger = logging.getLogger(WIRE_LOGGER_PREFIX)
    before = (logger.level, logger.propagate)
    state.watch_wire()
    state.watch_wire()
    assert logger.isEnabledFor(TRACE) and not logger.propagate
    port_logger = logging.getLogger(f"{WIRE_LOGGER_PREFIX}.sim://kit/SIMMB0")
    for i in range(2100):
        port_logger.log(TRACE, "-> %r", bytes([i % 256]))
    changes = state.changes(0, 0)
    assert len(changes.log) == 2000 and changes.dropped_log_lines == 100
    assert changes.log[-1][0] == "sim://kit/SIMMB0"
    assert state.changes(0, changes.log_mark).log == []
    state.unwatch_wire()
    assert logger.isEnabledFor(TRACE)
    state.unwatch_wire()
    assert (logger.level, logger.propagate) == before


async def test_start_view_options(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv(VIEW_PORT_VARIABLE, "not a port")
    with pytest.raises(ValueError, match="port number"):
        start_view()
    with pytest.raises(ValueError, match="65535"):
        start_view(port=70000)
    monkeypatch.delenv(VIEW_PORT_VARIABLE)
    view = start_view(host="127.0.0.2")
    try:
        out, err = capsys.readouterr()
        assert out == f"View: {view.url}\n" and view.url.startswith("http://127.0.0.2:")
        assert "WARNING" in err and "127.0.0.2" in err
        with pytest.raises(OSError):
            start_view(host="127.0.0.2", port=int(view.url.split(":")[2].split("/")[0]))
    finally:
        view.close()
        view.close()
    monkeypatch.setenv("J5AIO_VIEW", "0")
    assert not view_requested()
    monkeypatch.setenv("J5AIO_VIEW", "1")
    assert view_requested()


async def test_the_kch_and_the_fw4_boards_of_the_sr2023_kit() -> None:
    from j5aio.boards.sr.kch import Colour

    kit = use_kit("sr2023")
    state = ViewState()
    CALL_OBSERVERS.append(state)
    try:
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            kch = robot.kch
            assert kch is not None
            await kch.leds[1].set_colour(Colour.CYAN)
            await kch.start_led.flash()
            values = state.changes(0, 0).values
            for channel, duty in (("red", 0.0), ("green", 1.0), ("blue", 1.0)):
                assert ("SIMKCH0:rgbled:1", f"rgb_led_channel_duty_cycle.{channel}", duty) in (
                    values
                )
            assert ("SIMKCH0:flashingled:0", "led_mode", "FLASH") in values
            # Switched on after flashing: the newer value comes later, so the page ends
            # with it.
            await kch.start_led.set_state(True)
            await kch.start_led.flash()
            await kch.start_led.set_state(False)
            modes = [v for c, f, v in state.changes(0, 0).values if f == "led_mode"]
            assert modes == ["OFF"]  # one value per field: the newest
            record = next(r for r in state.boards() if r.board is kch)
            assert record.names[ComponentInfo("flashingled", "0")] == "start LED"

            # The sr2023 boards are simulated: their controls are offered, through the fw 4
            # simulators' API; the KCH is simulated but has nothing to poke.
            power = robot.power_board
            names = [c["name"] for c in controls_of(power, board_components(power))]
            assert names == ["start-button", "battery-voltage", "plug"]
            apply_control(power, "start-button", True)
            assert controls_of(power, board_components(power))[0]["value"] is True
            assert await power.start_button.get_is_pressed()
            assert controls_of(kch, board_components(kch)) == []
            assert kit.simulators("kch")
    finally:
        CALL_OBSERVERS.remove(state)


async def test_the_arena_is_sent_once_and_the_pose_as_it_moves() -> None:
    async with (
        kit_and_view(KitConfig(1, 1, 0, 0, 0)) as (robot, kit, view),
        aiohttp.ClientSession() as session,
        session.ws_connect(ws_url(view)) as ws,
    ):
        first = await messages_until(ws, lambda m: "arena" in m)
        assert first["arena"]["key"] == kit.name
        assert len(first["arena"]["markers"]) == len(kit.world.arena.markers)
        start = first["pose"]
        assert (start["x"], start["y"]) == (kit.world.pose.x, kit.world.pose.y)
        assert start["camera"] is not None

        # The motors drive the robot: the page is sent the pose as it moves, and the arena
        # is not sent again.
        left, right = robot.motor_boards[0].motors
        await left.set_power(0.8)
        await right.set_power(0.8)
        moved = await messages_until(
            ws, lambda m: "arena" in m or ("pose" in m and m["pose"]["y"] > start["y"] + 50)
        )
        assert "arena" not in moved
        assert moved["pose"]["x"] == pytest.approx(start["x"], abs=1)
        await left.set_power(0)
        await right.set_power(0)


async def test_every_page_shares_one_reading_of_the_program_per_tick() -> None:
    """Another open page costs the robot's loop nothing more: the readings are shared."""
    pages, wanted = 6, 3
    async with kit_and_view() as (_robot, _kit, view), aiohttp.ClientSession() as session:
        server = view.server
        board_readings = 0
        snapshot = server._snapshot

        def counting(with_boards: bool) -> dict[str, Any]:
            nonlocal board_readings
            board_readings += with_boards
            return snapshot(with_boards)

        server._snapshot = counting  # type: ignore[method-assign]
        received = [0] * pages

        async def watch(index: int) -> None:
            async with session.ws_connect(ws_url(view)) as ws:
                while received[index] < wanted:
                    if "boards" in json.loads((await ws.receive()).data):
                        received[index] += 1

        async with asyncio.timeout(30), asyncio.TaskGroup() as group:
            for index in range(pages):
                group.create_task(watch(index))
        # Read once per page, each page's board lists would need a reading each.
        assert board_readings * 2 <= sum(received)
        assert server.readings >= board_readings
