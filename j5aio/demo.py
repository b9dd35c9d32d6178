"""The demo: an async robot on the simulated kit, showing what the boards do as it runs.

``python -m j5aio demo`` runs it. A :class:`~j5aio.kit.KitRobot` runs three tasks at
once on a fresh simulated kit:

- **drive** drives forwards, and turns on the spot when asked to (or every few seconds);
- **sense** watches an ultrasound sensor on the SourceBots Arduino and the battery, and
  asks drive to turn when a wall comes close;
- **signal** blinks the power board's run LED, and beeps and raises a flag servo when a
  wall is seen.

On a kit with a KCH (``sr2023``), its user LED A shows what drive does (green forwards,
yellow turning) and LED B turns red while a wall is close.

A tiny simulated world moves the wall nearer as the motors drive and further away as the
robot turns, and loads the battery as the motors work. Every half second a ``boards``
line shows the state of the simulated boards themselves (read from the simulators, not
from the robot). When the time is up the tasks are cancelled, the robot makes every
board safe, and the demo checks that every simulated motor is braked.
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass, field
from typing import Final, TextIO, TypeVar

import anyio
from anyio.abc import ObjectReceiveStream, ObjectSendStream

from j5aio.board_kinds import simulator_entries
from j5aio.boards.sb.arduino_2024 import SBArduino2024Board
from j5aio.boards.sr.kch import Colour
from j5aio.components.derived.ultrasound import UltrasoundSensor
from j5aio.kit import KitRobot
from j5aio.power_outputs import OUTPUT_NAMES
from j5aio.simulator.arduino_base import ArduinoBoardSimulator
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.kit import SimulatedKit, kit_from_environment, use_kit
from j5aio.simulator.kit_file import kit_file_from_environment
from j5aio.simulator.sr_motor import MotorDrive
from j5aio.simulator.sr_motor_fw3 import MotorMode, MotorOutput, SRMotorBoardFw3Simulator
from j5aio.simulator.sr_motor_fw4 import MotorChannel, SRMotorBoardFw4Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator
from j5aio.simulator.sr_servo_fw4 import SRServoBoardFw4Simulator

__all__ = ["DEFAULT_SECONDS", "all_motors_braked", "demo", "run_demo"]

T = TypeVar("T")

#: How long the demo robot runs by default, in seconds.
DEFAULT_SECONDS: Final = 6.0

#: The Arduino pins of the ultrasound sensor: trigger and echo.
TRIGGER_PIN: Final = 6
ECHO_PIN: Final = 7
#: How close a wall may come before the robot turns away, in metres.
TURN_DISTANCE: Final = 0.4
#: How long the run LED stays on, then off, when blinking, in seconds.
BLINK_INTERVAL: Final = 0.3
#: How far away the wall starts, in metres.
START_DISTANCE: Final = 1.2


def _of_type(kit: SimulatedKit, kinds: tuple[type[T], ...]) -> list[T]:
    """The simulators of ``kit`` that are instances of ``kinds`` (any generation), in order."""
    return [
        simulator
        for name in kit.simulator_names()
        for simulator in kit.simulators(name)
        if isinstance(simulator, kinds)
    ]


def _motor_boards(kit: SimulatedKit) -> list[SRMotorBoardFw3Simulator | SRMotorBoardFw4Simulator]:
    return _of_type(kit, (SRMotorBoardFw3Simulator, SRMotorBoardFw4Simulator))


def _power_boards(kit: SimulatedKit) -> list[SRPowerBoardFw3Simulator | SRPowerBoardFw4Simulator]:
    return _of_type(kit, (SRPowerBoardFw3Simulator, SRPowerBoardFw4Simulator))


def _servo_boards(kit: SimulatedKit) -> list[SRServoBoardFw2Simulator | SRServoBoardFw4Simulator]:
    return _of_type(kit, (SRServoBoardFw2Simulator, SRServoBoardFw4Simulator))


class _Log:
    """Prints one line per event, with the time since the demo started."""

    def __init__(self, out: TextIO) -> None:
        self._out = out
        self._start = time.monotonic()

    @property
    def elapsed(self) -> float:
        return time.monotonic() - self._start

    def __call__(self, who: str, message: str) -> None:
        print(f"{self.elapsed:5.2f} s  {who:<7} {message}", file=self._out, flush=True)


@dataclass
class _World:
    """The room the robot drives in: a wall ahead, and a battery that runs down."""

    kit: SimulatedKit
    distance: float = START_DISTANCE
    elapsed: float = 0.0

    def step(self, seconds: float) -> None:
        """Move the world on by ``seconds``, from what the simulated motors do now."""
        left, right = (output.power for output in _motor_boards(self.kit)[0].motors)
        forwards = (left + right) / 2
        turning = abs(left - right) / 2
        self.distance -= forwards * 0.6 * seconds
        if turning > 0.2:
            self.distance += 1.5 * seconds  # turning away: the wall drops out of view
        self.distance = min(max(self.distance, 0.05), 2.0)
        self.elapsed += seconds
        for arduino in _of_type(self.kit, (ArduinoBoardSimulator,)):
            arduino.set_ultrasound_distance(TRIGGER_PIN, ECHO_PIN, self.distance)
        for power in _power_boards(self.kit):
            # The battery runs down; the kit's wiring adds what the motors draw.
            power.battery_current = 0.3
            power.battery_voltage = 12.4 - 0.02 * self.elapsed


@dataclass
class _Shared:
    """What the tasks tell each other."""

    wall_ahead: anyio.Event = field(default_factory=anyio.Event)


async def _drive(robot: KitRobot, shared: _Shared, log: _Log) -> None:
    left, right = robot.motor_boards[0].motors
    status_led = robot.kch.leds[0] if robot.kch is not None else None
    while True:
        log("drive", "forwards: both motors at +0.6")
        await left.set_power(0.6)
        await right.set_power(0.6)
        if status_led is not None:
            await status_led.set_colour(Colour.GREEN)
        with anyio.move_on_after(3.0):
            await shared.wall_ahead.wait()
        shared.wall_ahead = anyio.Event()
        log("drive", "turning on the spot: left +0.5, right -0.5")
        await left.set_power(0.5)
        await right.set_power(-0.5)
        if status_led is not None:
            await status_led.set_colour(Colour.YELLOW)
        await anyio.sleep(0.6)


async def _ultrasound(robot: KitRobot) -> UltrasoundSensor | None:
    """The ultrasound sensor on the kit's Arduino; ``None`` if its Arduino has none."""
    boards: list[object] = [*robot.arduinos, *robot.ruggeduinos]
    if SBArduino2024Board in robot.environment.supported_boards:
        boards += await robot.environment.get_board_group(SBArduino2024Board)
    for board in boards:
        sensors = getattr(board, "ultrasound_sensors", None)
        if sensors is not None:
            sensor: UltrasoundSensor = sensors[TRIGGER_PIN, ECHO_PIN]
            return sensor
    return None


async def _sense(
    robot: KitRobot, shared: _Shared, alerts: ObjectSendStream[float], log: _Log
) -> None:
    # A kit without an Arduino that measures echoes has no ultrasound sensor: drive turns
    # on time.
    sensor = await _ultrasound(robot)
    battery = robot.power_board.battery_sensor
    warned = False
    next_battery = 0.0
    while True:
        distance = await sensor.distance() if sensor is not None else None
        if distance is not None and distance < TURN_DISTANCE and not warned:
            log("sense", f"wall {distance:.2f} m ahead: asking drive to turn")
            shared.wall_ahead.set()
            await alerts.send(distance)
            warned = True
        elif distance is not None and distance > TURN_DISTANCE + 0.2:
            warned = False
        if log.elapsed >= next_battery:
            volts = await battery.get_voltage()
            amps = await battery.get_current()
            log("sense", f"battery {volts:.2f} V, {amps:.2f} A")
            next_battery += 1.5
        await anyio.sleep(0.1)


async def _signal(robot: KitRobot, alerts: ObjectReceiveStream[float], log: _Log) -> None:
    run_led = robot.power_board.run_led
    flag = robot.servo_boards[0].servos[0]
    wall_led = robot.kch.leds[1] if robot.kch is not None else None
    lit = False
    flag_down_at: float | None = None
    while True:
        alert: float | None = None
        with anyio.move_on_after(BLINK_INTERVAL):
            alert = await alerts.receive()
        if alert is not None:
            log("signal", "beep (880 Hz, 0.15 s) and raise the flag servo")
            await robot.power_board.piezo.buzz(0.15, 880)
            await flag.set_position(1.0)
            if wall_led is not None:
                await wall_led.set_colour(Colour.RED)
            flag_down_at = log.elapsed + 0.75
            continue
        lit = not lit
        await run_led.set_state(lit)
        if flag_down_at is not None and log.elapsed >= flag_down_at:
            await flag.set_position(-1.0)
            flag_down_at = None
            if wall_led is not None:
                await wall_led.set_colour(Colour.OFF)


def _describe_motor(output: MotorOutput | MotorChannel) -> str:
    if isinstance(output, MotorChannel):
        drive = output.drive
        if drive in (MotorDrive.COAST, MotorDrive.BRAKE):
            return str(drive.value)
        return f"{drive.value} {round(output.duty * 100)}%"
    if output.mode in (MotorMode.COAST, MotorMode.BRAKE):
        return str(output.mode.value)
    return f"{output.mode.value} {output.duty_percent}%"


def _is_braked(output: MotorOutput | MotorChannel) -> bool:
    if isinstance(output, MotorChannel):
        return output.drive is MotorDrive.BRAKE
    return output.mode is MotorMode.BRAKE


def describe_boards(kit: SimulatedKit, world: _World | None = None) -> str:
    """One line saying what the simulated boards of ``kit`` are doing now."""
    parts = []
    for board in _motor_boards(kit):
        motors = ", ".join(_describe_motor(output) for output in board.motors)
        parts.append(f"{board.serial_number} [{motors}]")
    for power in _power_boards(kit):
        led = "on" if power.run_led else "off"
        if isinstance(power, SRPowerBoardFw4Simulator):
            frequency = None if power.playing is None else power.playing.frequency
        else:
            queue = power.note_queue
            frequency = queue[0].frequency if queue else None
        piezo = "quiet" if frequency is None else f"{frequency} Hz"
        on = [OUTPUT_NAMES[n] for n, lit in enumerate(power.outputs) if lit] or ["none"]
        parts.append(
            f"outputs on: {', '.join(on)}, battery {power.loaded_voltage:.2f} V, "
            f"run LED {led}, piezo {piezo}"
        )
    for servos in _servo_boards(kit):
        if isinstance(servos, SRServoBoardFw4Simulator):
            pulse = servos.pulse_widths[0]
            parts.append("flag servo off" if pulse is None else f"flag servo {pulse} µs")
        else:
            parts.append(f"flag servo {servos.positions[0] / 100:+.1f}")
    for kch in _of_type(kit, (KCHSimulator,)):
        leds = ", ".join(
            f"{letter} {_COLOUR_NAMES[lit]}" for letter, lit in zip("ABC", kch.colours, strict=True)
        )
        parts.append(f"KCH LEDs {leds}")
    if world is not None:
        parts.append(f"wall {world.distance:.2f} m")
    return " | ".join(parts)


_COLOUR_NAMES: Final = {
    (False, False, False): "off", (True, False, False): "red", (True, True, False): "yellow",
    (False, True, False): "green", (False, True, True): "cyan", (False, False, True): "blue",
    (True, False, True): "magenta", (True, True, True): "white",
}


async def _show_boards(kit: SimulatedKit, world: _World, log: _Log) -> None:
    while True:
        log("boards", describe_boards(kit, world))
        await anyio.sleep(0.5)


async def _run_world(world: _World) -> None:
    last = time.monotonic()
    while True:
        await anyio.sleep(0.05)
        now = time.monotonic()
        world.step(now - last)
        last = now


def all_motors_braked(kit: SimulatedKit) -> bool:
    """Whether every motor of every simulated motor board in ``kit`` is braked or unpowered.

    A motor board without power (its power board output off, as the power board's safe
    state leaves it) drives nothing.
    """
    return all(
        _is_braked(output) or not board.powered
        for board in _motor_boards(kit)
        for output in board.motors
    )


async def demo(
    seconds: float = DEFAULT_SECONDS, *, out: TextIO | None = None, kit: str | None = None
) -> bool:
    """Run the demo robot for ``seconds`` on a fresh simulated kit.

    :param seconds: how long the robot's tasks run.
    :param out: where to print; standard output by default.
    :param kit: the name of the kit (:func:`j5aio.board_kinds.kits`); if omitted, the
        kit of the file ``J5AIO_KIT_FILE`` names, else the one ``J5AIO_KIT`` names, else
        the default kit.
    :returns: whether every simulated motor was braked at the end.
    :raises ValueError: ``seconds`` is not positive, or there is no such kit.
    """
    if not seconds > 0:
        raise ValueError(f"seconds must be more than 0, not {seconds}")
    out = out if out is not None else sys.stdout
    if kit is None:
        from j5aio.simulator.kit_file import KIT_FILE_VARIABLE, time_scale_of

        from_file = kit_file_from_environment()
        if from_file is not None:
            scale = time_scale_of(os.environ[KIT_FILE_VARIABLE].strip())
            simulated = use_kit(from_file, time_scale=scale, wired=True)
        else:
            simulated = use_kit(kit_from_environment(), wired=True)
    else:
        simulated = use_kit(kit, wired=True)
    kit_summary = _kit_summary(simulated)
    return await _run(simulated, kit_summary, seconds, out)


async def _run(kit: SimulatedKit, kit_summary: str, seconds: float, out: TextIO) -> bool:
    world = _World(kit)
    world.step(0.0)
    print(
        f"j5aio demo: a robot on the simulated kit for {seconds:g} s. The kit: "
        f"{kit_summary}.\n"
        "Three tasks run at once (drive, sense, signal); every 0.5 s a 'boards' line shows "
        "what the simulated boards are doing.\n",
        file=out,
        flush=True,
    )
    log = _Log(out)
    started = False
    try:
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            started = True
            log("robot", f"found {len(_boards(robot))} boards; starting the tasks")
            send, receive = anyio.create_memory_object_stream[float](10)
            shared = _Shared()
            with anyio.move_on_after(seconds):
                async with send, receive, anyio.create_task_group() as tasks:
                    tasks.start_soon(_run_world, world)
                    tasks.start_soon(_show_boards, kit, world, log)
                    tasks.start_soon(_drive, robot, shared, log)
                    tasks.start_soon(_sense, robot, shared, send, log)
                    tasks.start_soon(_signal, robot, receive, log)
            log("robot", "time is up: tasks cancelled, making every board safe")
    finally:
        # Also when the demo is interrupted (Ctrl-C): the robot made the boards safe. A
        # robot that never started (its lock was taken, say) ran no motor: no report.
        if started:
            braked = _report(kit, log, out)
    return braked


def _report(kit: SimulatedKit, log: _Log, out: TextIO) -> bool:
    braked = all_motors_braked(kit)
    log("boards", describe_boards(kit))
    if braked:
        print("\nThe robot has stopped: every simulated motor is braked.", file=out, flush=True)
    else:  # pragma: no cover - a make-safe failure
        print("\nWARNING: some simulated motors were left running.", file=out, flush=True)
    return braked


def _boards(robot: KitRobot) -> list[object]:
    boards: list[object] = [
        robot.power_board,
        *robot.motor_boards,
        *robot.servo_boards,
        *robot.arduinos,
        *robot.ruggeduinos,  # (the SR Arduinos are in robot.arduinos too)
        *([robot.kch] if robot.kch is not None else []),
    ]
    return list({id(board): board for board in boards}.values())


def _kit_summary(kit: SimulatedKit) -> str:
    entries = simulator_entries()
    parts = [
        f"{len(kit.simulators(name))} x {entries[name][1].description}"
        for name in kit.simulator_names()
        if kit.simulators(name)
    ]
    named = f"'{kit.definition.name}': " if kit.definition is not None else ""
    return named + ", ".join(parts)


def run_demo(
    seconds: float = DEFAULT_SECONDS, *, out: TextIO | None = None, kit: str | None = None
) -> bool:
    """Run :func:`demo` in a new event loop; return whether every motor ended braked."""
    return anyio.run(lambda: demo(seconds, out=out, kit=kit))
