"""The live view in a real browser: Debian's chromium driven by selenium.

Skipped, with the reason, where selenium, chromium or chromedriver is missing.
"""

from __future__ import annotations

import contextlib
import functools
import io
import json
import math
import statistics
import time
import urllib.error
import urllib.request
from collections.abc import AsyncIterator, Callable, Iterator
from typing import Any

import anyio
import pytest

from j5aio.kit import KitRobot
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import KitConfig, use_kit
from j5aio.view.describe import board_components, component_id
from j5aio.vision.arena_map import ArenaMap
from j5aio.vision.track import PositionTracker
from tests.module_from_file import ROOT, load_module


def _load_tool() -> Any:
    """tools/view_screenshot.py: the chromium launcher, shared with the screenshot script."""
    return load_module("view_screenshot_tool", ROOT / "tools" / "view_screenshot.py")


TOOL = _load_tool()

REASON = TOOL.missing_browser()
pytestmark = pytest.mark.skipif(REASON is not None, reason=f"no browser to test in: {REASON}")

#: How soon the page must show a change the program made, as the median of
#: several changes: one stall of a loaded machine running a browser must not fail the test.
SHOW_WITHIN = 0.2
#: How long a change may take at all before the page is taken not to show it.
SHOW_AT_ALL = 2.0


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    import shutil

    driver, profile = TOOL.launch_chromium()
    try:
        yield driver
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)


def wait_for(check: Callable[[], Any], timeout: float = 5.0, step: float = 0.005) -> Any:
    deadline = time.monotonic() + timeout
    while True:
        result = check()
        if result:
            return result
        if time.monotonic() > deadline:
            raise AssertionError(f"not seen within {timeout} s (last: {result!r})")
        time.sleep(step)


def attribute(driver: Any, selector: str, name: str) -> str | None:
    value = driver.execute_script(
        "const e = document.querySelector(arguments[0]); return e && e.getAttribute(arguments[1]);",
        selector,
        name,
    )
    return None if value is None else str(value)


@contextlib.asynccontextmanager
async def robot_with_view(
    config: KitConfig | str | None = None,
) -> AsyncIterator[tuple[KitRobot, str]]:
    kit = use_kit(config or KitConfig(motor_boards=1, ruggeduinos=1))
    assert kit
    out = io.StringIO()
    async with contextlib.AsyncExitStack() as stack:
        with contextlib.redirect_stdout(out):
            robot = await stack.enter_async_context(
                KitRobot(environment=SIMULATED_ENVIRONMENT, view=True)
            )
        line = out.getvalue().strip()
        assert line.startswith("View: http://127.0.0.1:"), line
        yield robot, line.removeprefix("View: ")


def board_state_is(driver: Any, serial: str, state: str) -> bool:
    return attribute(driver, f'[data-board="{serial}"]', "data-state") == state


async def in_thread(function: Callable[..., Any], *args: Any) -> Any:
    return await anyio.to_thread.run_sync(function, *args)


async def test_a_program_seen_and_poked_in_the_browser(browser: Any) -> None:
    async with robot_with_view() as (robot, url):
        await in_thread(browser.get, url)
        await in_thread(wait_for, lambda: attribute(browser, "#status", "data-status") == "live")

        # Every board and every component is on the page.
        def shown() -> set[str]:
            return set(
                browser.execute_script(
                    "return [...document.querySelectorAll('[data-component]')]"
                    ".map(e => e.dataset.component)"
                )
            )

        expected = {
            component_id(board.serial_number, info)
            for board in robot.boards()
            for info in board_components(board)
        }
        assert len(robot.boards()) == 6  # with the simulated kit's camera
        await in_thread(wait_for, lambda: expected <= shown())
        for board in robot.boards():
            assert attribute(browser, f'[data-board="{board.serial_number}"]', "data-state") == (
                "connected"
            )

        # Values the program changes show within 200 ms (the median of five changes).
        motor = robot.motor_boards[0].motors[1]
        selector = f'[data-component="{robot.motor_boards[0].serial_number}:motor:1"]'
        # The page is sent changes every TICK_SECONDS; bench/bench_view.py measures the
        # latency's distribution, and one stall of a loaded machine must not fail this test.
        from j5aio.view.server import TICK_SECONDS

        assert TICK_SECONDS <= SHOW_WITHIN / 2
        delays = []
        for power in (0.25, -0.75, 0.1, -0.3, 0.5):
            started = time.monotonic()
            await motor.set_power(power)
            await in_thread(
                wait_for,
                lambda p=power: attribute(browser, selector, "data-value") == str(p),
                SHOW_AT_ALL,
            )
            delays.append(time.monotonic() - started)
        assert statistics.median(delays) < SHOW_WITHIN, delays
        await robot.power_board.run_led.set_state(True)
        led = f'[data-component="{robot.power_board.serial_number}:led:0"]'
        await in_thread(wait_for, lambda: attribute(browser, led, "data-value") == "true")
        from j5aio.components.motor import MotorSpecialState

        await motor.set_power(MotorSpecialState.BRAKE)
        await in_thread(wait_for, lambda: attribute(browser, selector, "data-value") == "BRAKE")

        # The start button, clicked on the page, is seen by the program.
        power_serial = robot.power_board.serial_number
        button = f'[data-control="{power_serial}:start-button"]'
        await in_thread(wait_for, lambda: attribute(browser, button, "data-value") == "false")
        async with anyio.create_task_group() as tasks:
            tasks.start_soon(
                in_thread, lambda: browser.find_element("css selector", button).click()
            )
            await robot.power_board.start_button.wait_until_pressed(timeout=5)

        # An analogue voltage set on the page is what the program reads.
        arduino = robot.arduinos[0]
        control = f'[data-control="{arduino.serial_number}:analog-14"]'

        def type_voltage() -> None:
            field = browser.find_element("css selector", control)
            field.click()  # focused: the page no longer refreshes the field's value
            browser.execute_script("arguments[0].select()", field)
            field.send_keys("2.5\n")  # typed over the selection; Enter sends it

        await in_thread(type_voltage)
        for attempt in range(500):  # the page's request reaches the simulator soon after
            if abs(await arduino.pins[14].analogue_read() - 2.5) < 0.01:
                break
            if attempt in (150, 300):  # typing the same value again is harmless
                await in_thread(type_voltage)
            await anyio.sleep(0.02)
        else:
            typed = await in_thread(attribute, browser, control, "value")
            problem = await in_thread(
                lambda: browser.execute_script(
                    "return [...document.querySelectorAll('.controls .error')]"
                    ".map(e => e.textContent).join(' ')"
                )
            )
            pytest.fail(f"the program never read the voltage typed ({typed!r}; {problem!r})")
        pin = f'[data-component="{arduino.serial_number}:gpiopin:14"]'

        def shows_volts() -> bool:
            text = attribute(browser, pin, "data-value")
            try:
                return abs(float(text or "") - 2.5) < 0.01
            except ValueError:  # not a reading yet (the pin's mode came first)
                return False

        await in_thread(wait_for, shows_volts)

        # Unplugging a board shows on the page; plugging it back in too.
        motor_serial = robot.motor_boards[0].serial_number
        plug = f'[data-control="{motor_serial}:plug"]'
        section = f'[data-board="{motor_serial}"]'

        def click_plug_until(state: str, plugged_before: str) -> None:
            # The button sends an absolute value (unplug while the page shows the board
            # plugged), so a click the page lost under load is clicked again safely.
            for attempt in range(3):
                if attribute(browser, plug, "data-value") == plugged_before:
                    browser.find_element("css selector", plug).click()
                try:
                    wait_for(lambda: attribute(browser, section, "data-state") == state, 3.0)
                    return
                except AssertionError:
                    if attempt == 2:
                        raise

        await in_thread(click_plug_until, "disconnected", "true")
        await in_thread(wait_for, lambda: attribute(browser, plug, "data-value") == "false")
        await in_thread(click_plug_until, "connected", "false")

        # A wire log pane shows the bytes of a serial board.
        def wire_text() -> str:
            return str(
                browser.execute_script(
                    "return document.querySelector(arguments[0]).textContent",
                    f'[data-wire-log="{motor_serial}"]',
                )
            )

        await motor.set_power(0.1)
        await in_thread(wait_for, lambda: "->" in wire_text())


async def test_the_kch_leds_in_their_colours_and_the_start_led_flashing(browser: Any) -> None:
    from j5aio.boards.sr.kch import Colour

    async with robot_with_view("sr2023") as (robot, url):
        kch = robot.kch
        assert kch is not None
        await in_thread(browser.get, url)
        await in_thread(wait_for, lambda: board_state_is(browser, kch.serial_number, "connected"))
        serial = kch.serial_number

        def tile(kind: str, identifier: int) -> str:
            return f'[data-component="{serial}:{kind}:{identifier}"]'

        for identifier, colour, name in (
            (0, Colour.GREEN, "green"),
            (2, Colour.MAGENTA, "magenta"),
        ):
            await kch.leds[identifier].set_colour(colour)
            await in_thread(
                wait_for,
                lambda i=identifier, n=name: (
                    attribute(browser, tile("rgbled", i), "data-value") == n
                ),
            )
        await kch.leds[2].set_colour((1, 0, 0))
        await in_thread(
            wait_for, lambda: attribute(browser, tile("rgbled", 2), "data-value") == "red"
        )

        # The dot is lit in the LED's colour; LED B, never set, is dark.
        def dot_colour(identifier: int) -> str:
            return str(
                browser.execute_script(
                    "return getComputedStyle(document.querySelector(arguments[0] + ' .dot'))"
                    ".backgroundColor",
                    tile("rgbled", identifier),
                )
            )

        assert await in_thread(dot_colour, 0) == "rgb(0, 255, 0)"
        assert await in_thread(attribute, browser, tile("rgbled", 1), "data-value") in ("", "off")

        # The start LED flashes (as while waiting for the start), then is switched off.
        start = tile("flashingled", 0)
        await kch.start_led.flash()
        await in_thread(wait_for, lambda: attribute(browser, start, "data-value") == "FLASH")
        assert (
            await in_thread(
                lambda: browser.execute_script(
                    "return document.querySelector(arguments[0]).textContent", start
                )
            )
            == "Start LEDflashing"
        )
        assert await in_thread(
            lambda: bool(browser.find_elements("css selector", f"{start} .dot.flash"))
        )
        await kch.start_led.set_state(False)
        await in_thread(wait_for, lambda: attribute(browser, start, "data-value") == "OFF")
        assert not await in_thread(
            lambda: browser.find_elements("css selector", f"{start} .dot.flash")
        )
        # The fw 4 power board's run LED is a flashing LED too, named by the board.
        run = f'[data-component="{robot.power_board.serial_number}:flashingled:0"]'
        await robot.power_board.run_led.set_state(True)
        await in_thread(wait_for, lambda: attribute(browser, run, "data-value") == "ON")


async def test_the_arena_is_drawn_and_the_robot_moves_on_it(browser: Any) -> None:
    async with robot_with_view(KitConfig(1, 1, 0, 0, 0)) as (robot, url):
        from j5aio.simulator.kit import current_kit

        world = current_kit().world
        await in_thread(browser.get, url)
        await in_thread(wait_for, lambda: attribute(browser, "#arena-figure", "hidden") is None)
        # Every wall marker and token is drawn, with its id.
        ids = await in_thread(
            lambda: browser.execute_script(
                "return [...document.querySelectorAll('#arena [data-marker]')]"
                ".map(e => [e.dataset.marker, e.textContent])"
            )
        )
        assert ids == [[str(m.marker_id), str(m.marker_id)] for m in world.arena.markers]
        tokens = await in_thread(
            lambda: browser.execute_script(
                "return [...document.querySelectorAll('#arena [data-token]')]"
                ".map(e => e.dataset.token)"
            )
        )
        assert tokens == [str(t.marker_id) for t in world.arena.tokens]
        robot_pose = "#arena [data-robot]"

        def pose() -> tuple[float, float, float] | None:
            text = attribute(browser, robot_pose, "data-pose")
            if not text:
                return None
            x, y, heading = (float(part) for part in text.split(","))
            return x, y, heading

        start = await in_thread(wait_for, pose)
        assert start == pytest.approx(
            (world.pose.x, world.pose.y, math.degrees(world.pose.heading)), abs=1
        )
        # The camera's field of view is drawn from the robot's front.
        points = await in_thread(attribute, browser, "#arena .fov", "points")
        assert points is not None and len(points.split()) == 3

        # Driving forwards moves the robot on the page (north: it starts heading north);
        # turning on the spot turns it.
        left, right = robot.motor_boards[0].motors
        await left.set_power(0.8)
        await right.set_power(0.8)
        await in_thread(wait_for, lambda: (pose() or start)[1] > start[1] + 100)
        await left.set_power(0.5)
        await right.set_power(-0.5)
        await in_thread(wait_for, lambda: abs((pose() or start)[2] - start[2]) > 20)
        await left.set_power(0)
        await right.set_power(0)
        shown = await in_thread(pose)
        assert shown is not None
        assert shown[:2] == pytest.approx((world.pose.x, world.pose.y), abs=150)

        # Where a tracker believes the robot is, is drawn beside it.
        estimate = "#arena [data-estimate]"
        assert await in_thread(attribute, browser, estimate, "display") == "none"
        tracker = PositionTracker(None, ArenaMap.standard())
        tracker.reset((1000.0, 1200.0, 0.0))
        tracker.estimate()
        await in_thread(
            wait_for, lambda: attribute(browser, estimate, "data-estimate") == "1000,1200,0.0"
        )
        assert await in_thread(attribute, browser, estimate, "display") == "inline"
        text = await in_thread(lambda: browser.find_element("css selector", "#pose-text").text)
        assert "believed at x 1.00 m, y 1.20 m" in text


async def test_wrong_token_and_foreign_origin_refused(browser: Any) -> None:
    async with robot_with_view() as (robot, url):
        base, token = url.split("/?token=")
        await in_thread(browser.get, f"{base}/?token=wrong")
        body = await in_thread(lambda: browser.find_element("css selector", "body").text)
        assert "wrong or missing token" in body
        assert not await in_thread(
            lambda: browser.find_elements("css selector", "[data-component]")
        )

        # A page of another origin may not open the WebSocket nor send controls, even
        # with the right token.
        await in_thread(browser.get, "data:text/html,<title>elsewhere</title>")
        outcome = await in_thread(
            lambda: browser.execute_async_script(
                """
            const [base, token, control, done] = arguments;
            const result = {};
            const ws = new WebSocket(base.replace('http', 'ws') + '/ws?token=' + token);
            ws.onopen = () => { result.ws = 'open'; };
            ws.onerror = () => { result.ws = 'refused'; };
            fetch(base + '/control?token=' + token, {method: 'POST',
                  headers: {'Content-Type': 'application/json'},
                  body: JSON.stringify({control, value: 1.0})})
              .then(r => { result.control = r.status; }, () => { result.control = 'refused'; });
            setTimeout(() => done(result), 2000);
            """,
                base,
                token,
                f"{robot.power_board.serial_number}:battery-voltage",
            )
        )
        assert outcome == {"ws": "refused", "control": "refused"}
        assert await robot.power_board.battery_sensor.get_voltage() != pytest.approx(1.0)

        # The same refusals without a browser, for an Origin header a script could forge.
        def post(origin: str | None, token_text: str) -> int:
            request = urllib.request.Request(
                f"{base}/control?token={token_text}",
                data=json.dumps({"control": "SIMMB0:plug", "value": True}).encode(),
                headers={
                    "Content-Type": "application/json",
                    **({"Origin": origin} if origin else {}),
                },
                method="POST",
            )
            try:
                with urllib.request.urlopen(request, timeout=5) as response:
                    return int(response.status)
            except urllib.error.HTTPError as error:
                return int(error.code)

        assert await in_thread(post, "http://evil.example", token) == 403
        assert await in_thread(post, None, "wrong") == 403
        assert await in_thread(post, base, token) == 200


def test_the_demo_in_the_browser_and_its_screenshot(browser: Any, tmp_path: Any) -> None:
    process, url = TOOL.start_demo(30)
    try:
        browser.get(url)
        boards = ("SIMPB0", "SIMMB0", "SIMMB1", "SIMSB0", "SIMSBA0")
        for serial in boards:
            wait_for(functools.partial(board_state_is, browser, serial, "connected"))
        motor = '[data-component="SIMMB0:motor:0"]'
        wait_for(lambda: attribute(browser, motor, "data-value") not in (None, ""))
        first = attribute(browser, motor, "data-value")
        wait_for(lambda: attribute(browser, motor, "data-value") != first, timeout=10)
        wait_for(
            lambda: attribute(
                browser, '[data-component="SIMSBA0:ultrasoundsensor:6-7"]', "data-value"
            )
        )
        wait_for(lambda: attribute(browser, '[data-series="SIMMB0:motor:0"]', "data-series"))
        shot = tmp_path / "view.png"
        browser.save_screenshot(str(shot))
        assert shot.read_bytes().startswith(b"\x89PNG")
    finally:
        rest = TOOL.stop(process)
    assert "every simulated motor is braked" in rest  # interrupted, the robot stopped safely
