"""The pytest plugin's fixtures, used directly and from a separate pytest run (pytester)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import anyio
import pytest
import serial

from j5aio.backends.hardware.sb import SBArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream, memory_stream_pair
from j5aio.boards.board import Board
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.boards.sr.v4.motor_board import MotorBoard
from j5aio.boards.sr.v4.power_board import PowerBoard
from j5aio.boards.sr.v4.ruggeduino import Ruggeduino
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import BoardDisconnectionError
from j5aio.simulator import SBArduinoSimulator
from j5aio.simulator.kit import current_kit
from j5aio.simulator.sr_motor_fw3 import MotorMode
from j5aio.testing import Fault, FaultyStream, OpenSimulatedKit
from j5aio.testing.plugin import FaultyStreamFactory, PtySimulatorFactory

pytest_plugins = ["pytester"]


# --- j5aio_sim_kit ----------------------------------------------------------------------


async def test_sim_kit_has_the_default_kit_set_up(j5aio_sim_kit: OpenSimulatedKit) -> None:
    kit = j5aio_sim_kit.kit
    assert current_kit() is kit
    assert len(j5aio_sim_kit.group(MotorBoard)) == len(kit.motor_boards) == 2
    assert len(j5aio_sim_kit.group(PowerBoard)) == len(kit.power_boards) == 1
    assert set(j5aio_sim_kit.boards) <= Board.BOARDS
    # every board simulator, and the camera of the kit's world
    assert len(j5aio_sim_kit.boards) == len(kit) + (kit.camera is not None)


async def test_sim_kit_drives_the_simulators(j5aio_sim_kit: OpenSimulatedKit) -> None:
    motor = j5aio_sim_kit.group(MotorBoard)[0].motors[1]
    simulator = j5aio_sim_kit.kit.motor_boards[0]
    await motor.set_power(-1.0)
    assert simulator.motors[1].mode is MotorMode.REVERSE
    await motor.set_power(MotorSpecialState.COAST)
    assert simulator.motors[1].mode.name == "COAST"


@pytest.mark.j5aio_kit(motor_boards=1, power_boards=0, servo_boards=0, sb_arduinos=0)
async def test_sim_kit_marker_chooses_the_boards(j5aio_sim_kit: OpenSimulatedKit) -> None:
    assert len(j5aio_sim_kit.kit) == 1
    assert len(j5aio_sim_kit.group(MotorBoard)) == 1
    assert len(j5aio_sim_kit.group(PowerBoard)) == 0


@pytest.mark.j5aio_kit("sr2019")
async def test_sim_kit_marker_takes_a_kit_by_name(j5aio_sim_kit: OpenSimulatedKit) -> None:
    definition = j5aio_sim_kit.kit.definition
    assert definition is not None and definition.name == "sr2019"
    assert len(j5aio_sim_kit.group(Ruggeduino)) == 1


@pytest.mark.parametrize(
    ("args", "counts", "message"),
    [
        (("sr2019", "sb2019"), {}, "takes one kit"),
        (("sr2019",), {"motor_boards": 1}, "not both"),
        ((3,), {}, "a kit's name .* not 3"),
    ],
)
def test_sim_kit_marker_refuses_what_is_not_one_kit(
    args: tuple[object, ...], counts: dict[str, object], message: str
) -> None:
    from j5aio.testing.plugin import _marked_kit

    with pytest.raises(TypeError, match=message):
        _marked_kit(args, counts)


def test_sim_kit_from_a_sync_test(j5aio_sim_kit: OpenSimulatedKit) -> None:
    assert j5aio_sim_kit.kit.power_boards[0].run_led
    assert [board.serial_number for board in j5aio_sim_kit.group(MotorBoard)] == [
        simulator.serial_number for simulator in j5aio_sim_kit.kit.motor_boards
    ]


async def test_sim_kit_group_of_an_unknown_board(j5aio_sim_kit: OpenSimulatedKit) -> None:
    class NoSuchBoard(PowerBoard):
        pass

    with pytest.raises(KeyError, match=r"no NoSuchBoard group; it has: .*MotorBoard"):
        j5aio_sim_kit.group(NoSuchBoard)


# --- j5aio_clean_boards -----------------------------------------------------------------


def test_fixtures_clean_up_after_the_test(pytester: pytest.Pytester) -> None:
    """Run in a pytest of its own, without this project's conftest that clears boards.

    pytest-asyncio runs in strict mode there, as in a suite that has not chosen auto mode.
    """
    pytester.makepyfile(
        test_sim_kit="""
        import pytest

        from j5aio.boards.board import Board
        from j5aio.simulator.kit import current_kit

        seen = {}

        @pytest.mark.asyncio
        async def test_uses_kit(j5aio_sim_kit):
            seen["kit"] = j5aio_sim_kit.kit
            seen["boards"] = list(j5aio_sim_kit.boards)
            assert Board.BOARDS

        def test_afterwards():
            assert not Board.BOARDS
            assert current_kit() is not seen["kit"]
            assert all(board._is_closed for board in seen["boards"])
        """,
        test_clean_boards="""
        from j5aio.boards.board import Board

        class Fake:
            pass

        def test_leaves_a_board(j5aio_clean_boards):
            Board.BOARDS.add(Fake())

        def test_sees_none():
            assert not Board.BOARDS

        def test_leaks_a_board():
            Board.BOARDS.add(Fake())

        def test_sees_the_leak():
            assert len(Board.BOARDS) == 1
            Board.BOARDS.clear()
        """,
        test_suite_subject="""
        from j5aio.components.led import LEDInterface
        from j5aio.testing.conformance import LEDInterfaceConformance, LEDSubject

        released = []

        class LEDs(LEDInterface):
            def __init__(self):
                self.states = [False, False]

            async def get_led_state(self, identifier):
                if identifier not in (0, 1):
                    raise KeyError(identifier)
                return self.states[identifier]

            async def set_led_state(self, identifier, state):
                if identifier not in (0, 1):
                    raise KeyError(identifier)
                self.states[identifier] = state

        class TestLEDs(LEDInterfaceConformance):
            async def make_backend(self):
                async def cleanup():
                    released.append(True)

                return LEDSubject(backend=LEDs(), identifiers=[0, 1], cleanup=cleanup)

        def test_each_backend_was_released():
            assert released == [True] * 4
        """,
    )
    result = pytester.runpytest_subprocess("-o", "asyncio_mode=strict")
    result.assert_outcomes(passed=10, skipped=1)
    # a passing run says it in one line...
    result.stdout.fnmatch_lines(
        ["j5aio conformance: 1 check not run for want of a subject's hook ('observe', "
         "'traffic'); -rs lists them"],
    )
    assert "TestLEDs::test_every_hook_is_given" not in result.stdout.str()
    # ...and -rs lists each check with its reason
    listed = pytester.runpytest_subprocess("-o", "asyncio_mode=strict", "-rs")
    listed.stdout.fnmatch_lines(
        [
            "*j5aio conformance: checks not run for want of a hook*",
            "*TestLEDs::test_every_hook_is_given: no 'traffic', 'observe' (each a hook of*",
        ],
    )


async def test_clean_boards_in_an_async_test(j5aio_clean_boards: None) -> None:
    await anyio.lowlevel.checkpoint()
    assert isinstance(Board.BOARDS, set)


# --- j5aio_faulty_stream ----------------------------------------------------------------


async def test_faulty_stream_wraps_and_injects(j5aio_faulty_stream: FaultyStreamFactory) -> None:
    host, board = memory_stream_pair()
    faulty = j5aio_faulty_stream(host, schedule={0: Fault.drop()})
    assert isinstance(faulty, FaultyStream)
    assert faulty.inner is host
    assert j5aio_faulty_stream.streams == [faulty]
    await faulty.send(b"first\n")
    assert await board.receive() == b"first\n"
    await board.send(b"dropped\n")
    await faulty.send(b"second\n")
    await board.receive()
    await board.send(b"kept\n")
    with anyio.fail_after(1):
        assert await faulty.receive() == b"kept\n"


async def test_faulty_stream_disconnect(j5aio_faulty_stream: FaultyStreamFactory) -> None:
    faulty = j5aio_faulty_stream(SimulatorStream(SBArduinoSimulator("SIM0"), time_scale=0))
    faulty.disconnect()
    with pytest.raises(BoardDisconnectionError):
        await faulty.send(b"v\n")


def test_faulty_stream_factory_closes_what_it_made() -> None:
    factory = FaultyStreamFactory()
    host, _ = memory_stream_pair()
    factory(host)
    factory.close()
    assert host.is_closed
    assert factory.streams == []


def test_faulty_stream_from_a_sync_test(j5aio_faulty_stream: FaultyStreamFactory) -> None:
    host, _ = memory_stream_pair()
    faulty = j5aio_faulty_stream(host)
    faulty.silence()
    assert faulty.is_silent


# --- j5aio_pty_simulator ----------------------------------------------------------------


def test_pty_simulator_by_name_from_a_sync_test(
    j5aio_pty_simulator: PtySimulatorFactory,
) -> None:
    path = j5aio_pty_simulator("sb-arduino", serial_number="PTY0")
    assert os.path.exists(path)
    server = j5aio_pty_simulator.servers[0]
    assert server.path == path
    assert server.simulator.serial_number == "PTY0"  # type: ignore[attr-defined]
    with serial.Serial(path, 115200, timeout=1):
        deadline = time.monotonic() + 5
        while server.opened_count == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert server.opened_count == 1


async def test_pty_simulator_attach_from_an_async_test(
    j5aio_pty_simulator: PtySimulatorFactory,
) -> None:
    simulator = SBArduinoSimulator("PTY1")
    path = j5aio_pty_simulator(simulator)
    board = await SBArduinoHardwareBackend.attach(path, time_scale=0.1)
    try:
        assert isinstance(board, SBArduinoBoard)
        await board.setup()
        await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
        await board.pins[13].digital_write(True)
        assert simulator.output_level(13)
    finally:
        await board.close()


def test_pty_simulator_unknown_name(j5aio_pty_simulator: PtySimulatorFactory) -> None:
    with pytest.raises(ValueError, match=r"called 'nope'; choose one of .*sr-motor"):
        j5aio_pty_simulator("nope")
    assert j5aio_pty_simulator.servers == []


def test_pty_simulator_stops_servers_afterwards() -> None:
    factory = PtySimulatorFactory()
    factory("sr-motor")
    server = factory.servers[0]
    assert server.is_serving
    factory.close()
    assert not server.is_serving
    assert factory.servers == []


def test_plugin_is_registered_by_entry_point(pytester: pytest.Pytester) -> None:
    listed = pytester.runpytest_subprocess("--fixtures").stdout.str()
    for fixture in ("j5aio_sim_kit", "j5aio_pty_simulator", "j5aio_faulty_stream",
                    "j5aio_clean_boards"):
        assert f"{fixture} -- " in listed
    markers = pytester.runpytest_subprocess("--markers").stdout.str()
    assert "@pytest.mark.j5aio_kit(kit=None, **counts)" in markers


# Found first on the path, this stands in for pytest-asyncio and fails to import, as
# the real package does where it is not installed.
BLOCKER = """
raise ModuleNotFoundError("No module named 'pytest_asyncio'", name="pytest_asyncio")
"""

SUITE = """
def test_a_plain_test_runs(j5aio_clean_boards):
    assert True


def test_the_async_fixture_says_what_to_install(j5aio_sim_kit):
    raise AssertionError("never reached")
"""


def test_the_plugin_loads_without_pytest_asyncio(tmp_path: Path) -> None:
    blocked = tmp_path / "blocked" / "pytest_asyncio"
    blocked.mkdir(parents=True)
    (blocked / "__init__.py").write_text(BLOCKER)
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "test_suite.py").write_text(SUITE)
    worktree = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(blocked.parent), str(worktree)])}
    env.pop("PYTEST_ADDOPTS", None)
    result = subprocess.run(
        [
            sys.executable, "-m", "pytest",
            "-p", "no:asyncio", "-p", "no:cacheprovider", "-q", "-rE", str(suite),
        ],
        capture_output=True,
        text=True,
        cwd=suite,
        env=env,
        timeout=120,
        check=False,
    )
    output = result.stdout + result.stderr
    assert "ModuleNotFoundError" not in output, output
    assert "1 passed" in output, output
    assert "1 error" in output, output
    assert "needs pytest-asyncio: install it" in output, output
