"""Tests of SIMULATED_ENVIRONMENT: the hardware backends talking to the simulated kit."""

from __future__ import annotations

import time

import anyio
import pytest

from j5aio.backends.hardware import registry
from j5aio.backends.hardware.env import HARDWARE_ENVIRONMENT
from j5aio.backends.hardware.listing import find_boards
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.boards.camera import CameraBoard
from j5aio.boards.sb import SBArduinoBoard
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard, Ruggeduino, ServoBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.simulator.clock import ManualClock
from j5aio.simulator.environment import (
    MINIMUM_TIMEOUT_SCALE,
    SIMULATED_BACKENDS,
    SIMULATED_ENVIRONMENT,
    SimulatedUSBDevice,
    kit_discovery_options,
    port_name,
)
from j5aio.simulator.kit import KitConfig, SimulatedKit, use_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode

pytestmark = pytest.mark.usefixtures("fresh_kit")


def test_every_simulated_backend_is_the_hardware_backend_for_its_board() -> None:
    assert SIMULATED_ENVIRONMENT.supported_boards == HARDWARE_ENVIRONMENT.supported_boards
    for backend in SIMULATED_BACKENDS:
        assert SIMULATED_ENVIRONMENT.get_backend(backend.board) is backend
        if backend.board is CameraBoard:
            continue  # the simulated camera renders its arena instead of capturing frames
        assert issubclass(backend, HARDWARE_ENVIRONMENT.get_backend(backend.board))


async def test_the_default_kit_is_found_board_for_board() -> None:
    kit = use_kit()
    power = await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)
    motors = await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)
    servos = await SIMULATED_ENVIRONMENT.get_board_group(ServoBoard)
    arduinos = await SIMULATED_ENVIRONMENT.get_board_group(SBArduinoBoard)
    ruggeduinos = await SIMULATED_ENVIRONMENT.get_board_group(Ruggeduino)
    assert [b.serial_number for b in power] == [s.serial_number for s in kit.power_boards]
    assert [b.serial_number for b in motors] == ["SIMMB0", "SIMMB1"]
    assert [b.serial_number for b in servos] == ["SIMSB0"]
    assert [b.serial_number for b in arduinos] == ["SIMSBA0"]
    assert len(ruggeduinos) == 0
    assert power[0].firmware_version == "3"
    assert motors[0].firmware_version == "3"


async def test_commands_travel_through_the_real_protocol_to_the_simulators() -> None:
    kit = use_kit(KitConfig(motor_boards=1))
    motor_board = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    power_board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    servo_board = (await SIMULATED_ENVIRONMENT.get_board_group(ServoBoard)).singular()
    arduino = (await SIMULATED_ENVIRONMENT.get_board_group(SBArduinoBoard)).singular()

    await motor_board.motors[1].set_power(-0.6)
    await motor_board.motors[0].set_power(MotorSpecialState.COAST)
    assert kit.motor_boards[0].motors[1].mode is MotorMode.REVERSE
    assert kit.motor_boards[0].motors[1].duty_percent == 60  # duty = power
    assert kit.motor_boards[0].motors[0].mode is MotorMode.COAST

    await power_board.run_led.set_state(False)
    assert kit.power_boards[0].run_led is False
    kit.power_boards[0].battery_voltage = 11.5
    assert await power_board.battery_sensor.get_voltage() == pytest.approx(11.5, abs=0.01)

    await servo_board.servos[2].set_position(0.5)
    assert kit.servo_boards[0].positions[2] == 50

    pin = arduino.pins[5]
    await pin.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await pin.digital_write(True)
    assert kit.sb_arduinos[0].output_level(5) is True
    kit.sb_arduinos[0].set_ultrasound_distance(6, 7, 0.75)
    distance = await arduino.ultrasound_sensors[6, 7].distance()
    assert distance == pytest.approx(0.75, abs=0.01)


async def test_unplugged_boards_are_not_found() -> None:
    kit = use_kit()
    kit.motor_boards[0].unplug()
    kit.servo_boards[0].unplug()
    motors = await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)
    servos = await SIMULATED_ENVIRONMENT.get_board_group(ServoBoard)
    assert [b.serial_number for b in motors] == ["SIMMB1"]
    assert len(servos) == 0


async def test_looking_again_gives_back_the_same_boards() -> None:
    use_kit()
    first = await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)
    again = await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)
    assert list(first) == list(again)
    power_first = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    power_again = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    assert power_first is power_again


async def test_a_new_kit_gives_new_boards_on_its_own_ports() -> None:
    first_kit = use_kit(KitConfig(motor_boards=1))
    first = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    second_kit = use_kit(KitConfig(motor_boards=1))
    second = (await SIMULATED_ENVIRONMENT.get_board_group(MotorBoard)).singular()
    assert first is not second
    await second.motors[0].set_power(0.6)
    assert second_kit.motor_boards[0].motors[0].mode is MotorMode.FORWARD
    assert first_kit.motor_boards[0].motors[0].mode is not MotorMode.FORWARD
    assert first_kit.name in str(getattr(first.backend, "port", ""))
    assert second_kit.name in str(getattr(second.backend, "port", ""))


async def test_arduinos_of_each_kind_are_found_by_their_own_backend_only() -> None:
    use_kit(KitConfig(sb_arduinos=1, ruggeduinos=2))
    arduinos = await SIMULATED_ENVIRONMENT.get_board_group(SBArduinoBoard)
    ruggeduinos = await SIMULATED_ENVIRONMENT.get_board_group(Ruggeduino)
    assert [b.serial_number for b in arduinos] == ["SIMSBA0"]
    assert [b.serial_number for b in ruggeduinos] == ["SIMRD0", "SIMRD1"]


async def test_the_kit_time_scale_slows_the_arduino_boot() -> None:
    use_kit(KitConfig(power_boards=0, motor_boards=0, servo_boards=0, time_scale=0.2))
    started = time.monotonic()
    arduinos = await SIMULATED_ENVIRONMENT.get_board_group(SBArduinoBoard)
    elapsed = time.monotonic() - started
    assert len(arduinos) == 1
    # The simulated Arduino takes 1.5 s to boot at full scale.
    assert 0.3 <= elapsed < 3


async def test_piezo_notes_play_out_on_the_kit_clock_with_no_transfer() -> None:
    kit = use_kit(KitConfig(motor_boards=0))
    clock = ManualClock()
    kit.use_clock(clock)
    power_board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()
    await power_board.piezo.buzz(0.15, 440)
    await power_board.piezo.buzz(0.1, 880)
    assert [note.frequency for note in kit.power_boards[0].note_queue] == [440, 880]
    clock.advance(0.2)  # the first has ended, the second plays
    assert [note.frequency for note in kit.power_boards[0].note_queue] == [880]
    clock.advance(0.05)
    assert kit.power_boards[0].note_queue == []


async def test_hardware_listing_finds_the_whole_kit_with_kit_discovery_options() -> None:
    kit = SimulatedKit(KitConfig(ruggeduinos=1))
    found = await find_boards(options=kit_discovery_options(kit))
    assert sorted(board.serial_number for board in found) == sorted(
        str(simulator.serial_number) for simulator in kit
    )
    motor = next(board for board in found if board.serial_number == "SIMMB0")
    assert motor.port == port_name(kit, kit.motor_boards[0])
    assert motor.firmware_version == "3"
    assert registry.held() == frozenset()  # listing closes what it opened


def test_timeouts_follow_the_kit_time_scale_but_never_vanish() -> None:
    assert kit_discovery_options(SimulatedKit()).time_scale == MINIMUM_TIMEOUT_SCALE
    slow = SimulatedKit(KitConfig(time_scale=1.0))
    assert kit_discovery_options(slow).time_scale == 1.0
    assert kit_discovery_options(slow, timeout_scale=0.5).time_scale == 0.5


def test_usb_stand_in_shows_the_simulator_and_its_place_in_the_kit() -> None:
    kit = SimulatedKit()
    simulator = kit.power_boards[0]
    device = SimulatedUSBDevice(simulator, kit)
    assert device.simulator is simulator
    assert (device.idVendor, device.idProduct) == (simulator.idVendor, simulator.idProduct)
    assert device.serial_number == "SIMPB0"
    assert device.manufacturer == "Student Robotics"  # other attributes are the simulator's
    assert (device.bus, device.address) == (kit.name, "SIMPB0")
    assert "SIMPB0" in repr(device)
    assert port_name(kit, kit.motor_boards[1]) == f"sim://{kit.name}/SIMMB1"


async def test_the_start_button_is_polled_over_the_link_as_on_a_robot(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Read often (the simulator's doorbell makes the reads in between 50 times rarer).
    monkeypatch.setattr(SRV4PowerBoardHardwareBackend, "BUTTON_POLL_INTERVAL", 0.001)
    kit = use_kit(KitConfig(motor_boards=0, servo_boards=0, sb_arduinos=0))
    simulator = kit.power_boards[0]
    reads = 0
    original = simulator._read

    def counting(command: int, length: int) -> bytes:
        nonlocal reads
        reads += command == 8  # the button
        return original(command, length)

    simulator._read = counting  # type: ignore[method-assign]
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()

    async def press_after_two_polls() -> None:
        with anyio.fail_after(30):
            while reads < 2:  # noqa: ASYNC110 - the hardware backend's poll, on the USB thread
                await anyio.sleep(0.001)
        await anyio.to_thread.run_sync(simulator.press_start)

    async with anyio.create_task_group() as group:
        group.start_soon(press_after_two_polls)
        await board.start_button.wait_until_pressed()
    assert reads >= 3  # read again and again until a read saw the button down
    simulator.release_start()


async def test_a_press_wakes_the_poll_before_its_interval(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A poll every hour: only the simulator's doorbell can end this wait, through the
    # poll's own read of the button (the protocol), not around it.
    monkeypatch.setattr(SRV4PowerBoardHardwareBackend, "BUTTON_POLL_INTERVAL", 3600.0)
    kit = use_kit(KitConfig(motor_boards=0, servo_boards=0, sb_arduinos=0))
    simulator = kit.power_boards[0]
    events: list[str] = []
    original = simulator._read

    def noting(command: int, length: int) -> bytes:
        reply = original(command, length)
        if command == 8:  # the button
            events.append(f"read {int.from_bytes(reply, 'little')}")
        return reply

    simulator._read = noting  # type: ignore[method-assign]
    board = (await SIMULATED_ENVIRONMENT.get_board_group(PowerBoard)).singular()

    async def press_after_the_first_read() -> None:
        while not events:  # noqa: ASYNC110 - the hardware backend's poll, on the USB thread
            await anyio.sleep(0.001)
        events.append("press")
        await anyio.to_thread.run_sync(simulator.press_start)

    with anyio.fail_after(30):
        async with anyio.create_task_group() as group:
            group.start_soon(press_after_the_first_read)
            await board.start_button.wait_until_pressed()
    assert events == ["read 0", "press", "read 1"]
    simulator.release_start()
