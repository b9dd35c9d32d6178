"""The student path: ``from j5aio.sync import KitRobot`` finds the whole kit, no backend named."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from j5aio.sync import BaseRobot, KitRobot

from .sync_fakes import ROOT, child_env


def run_program(source: str, tmp_path: Path, **environ: str) -> subprocess.CompletedProcess[str]:
    script = tmp_path / "program.py"
    script.write_text(source, encoding="utf-8")
    return subprocess.run(
        [sys.executable, str(script)],
        capture_output=True, text=True, timeout=60, cwd=ROOT,
        env={**child_env(), **environ}, check=False,
    )


def test_sync_kit_robot_is_generated_from_the_core_one() -> None:
    from j5aio.kit import KitRobot as CoreKitRobot
    from j5aio.sync.wrapping import core_class_of

    assert issubclass(KitRobot, BaseRobot)
    assert core_class_of(KitRobot) is CoreKitRobot
    for name in ("power_board", "motor_boards", "servo_boards", "arduinos", "ruggeduinos", "kch"):
        assert isinstance(getattr(KitRobot, name), property), name


def test_kit_robot_drives_the_simulated_kit(tmp_path: Path) -> None:
    result = run_program(
        "from j5aio.sync import KitRobot, MotorBoard, PowerBoard\n"
        "robot = KitRobot()\n"
        "assert isinstance(robot.power_board, PowerBoard)\n"
        "assert isinstance(robot.motor_boards[0], MotorBoard)\n"
        "robot.motor_boards[0].motors[1].power = 0.25\n"
        "print(robot.environment.name, robot.motor_boards[0].motors[1].power)\n"
        "print(robot.power_board.battery_sensor.voltage > 0)\n"
        "from j5aio.sync import GPIOPin\n"
        "print(all(isinstance(pin, GPIOPin) for pin in robot.arduinos[0].pins))\n"
        "print([pin.mode.name for pin in robot.arduinos[0].pins][-1])\n",
        tmp_path, J5AIO_ENV="sim",
    )
    assert result.returncode == 0, result.stderr
    lines = result.stdout.split("\n")
    assert lines[0].endswith(" 0.25")
    assert lines[1:4] == ["True", "True", "ANALOGUE_INPUT"]


def test_the_sync_kit_robot_lights_the_kch_of_the_sr2023_kit(tmp_path: Path) -> None:
    result = run_program(
        "from j5aio.sync import KitRobot, KCHBoard\n"
        "from j5aio.boards.sr.kch import Colour\n"
        "from j5aio.simulator.kit import current_kit\n"
        "robot = KitRobot()\n"
        "assert isinstance(robot.kch, KCHBoard)\n"
        "robot.kch.leds[0].colour = Colour.BLUE\n"
        "print(current_kit().simulators('kch')[0].colours[0])\n",
        tmp_path, J5AIO_ENV="sim", J5AIO_KIT="sr2023",
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split("\n")[0] == "(False, False, True)"


def test_a_student_subclass_adds_its_own_names(tmp_path: Path) -> None:
    result = run_program(
        "from j5aio.sync import KitRobot\n"
        "class MyRobot(KitRobot):\n"
        "    def __init__(self, speed: float) -> None:\n"
        "        super().__init__()\n"
        "        self.left = self.motor_boards[0].motors[0]\n"
        "        self.speed = speed\n"
        "robot = MyRobot(0.5)\n"
        "robot.left.power = robot.speed\n"
        "print(robot.left.power)\n",
        tmp_path, J5AIO_ENV="sim",
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "0.5"


def test_a_failed_search_gives_up_the_robot_lock(tmp_path: Path) -> None:
    result = run_program(
        "from j5aio.sync import BaseRobot, Environment, KitRobot\n"
        "empty = Environment('nothing here')\n"
        "try:\n"
        "    KitRobot(environment=empty)\n"
        "except NotImplementedError as error:\n"
        "    print('refused:', error)\n"
        "robot = BaseRobot()\n"  # the lock is free again
        "print('lock free')\n",
        tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert "refused:" in result.stdout
    assert "lock free" in result.stdout


def test_a_misspelt_set_says_what_was_meant(tmp_path: Path) -> None:
    result = run_program(
        "from j5aio.sync import KitRobot\n"
        "robot = KitRobot()\n"
        "motor = robot.motor_boards[0].motors[0]\n"
        "try:\n"
        "    motor.powr = 0.5\n"
        "except AttributeError as error:\n"
        "    print(error)\n"
        "try:\n"
        "    robot.power_board.battery_sensor.voltage = 3\n"
        "except AttributeError as error:\n"
        "    print(error)\n"
        "robot.motor_boards[0].motors[2]\n",
        tmp_path, J5AIO_ENV="sim",
    )
    lines = result.stdout.splitlines()
    assert lines[0] == "'Motor' object has no attribute 'powr' to set. Did you mean: 'power'?"
    assert "has no setter" in lines[1]  # Python's own words for a read-only property
    assert result.stderr.rstrip().endswith(
        "NoSuchComponentError: Student Robotics v4 Motor Board - SIMMB0 has motors 0 to 1: "
        "there is no motor 2",
    )


def test_j5_calls_the_ruggeduino_command_and_names_get_board_group_arguments(
    tmp_path: Path,
) -> None:
    result = run_program(
        "from j5aio.backends.hardware import NotSupportedByHardwareError\n"
        "from j5aio.boards.sr.v4 import Ruggeduino\n"
        "from j5aio.simulator.environment import SRV4RuggeduinoSimulatedBackend\n"
        "from j5aio.simulator.kit import KitConfig, use_kit\n"
        "from j5aio.sync import BoardGroup\n"
        "use_kit(KitConfig(ruggeduinos=1))\n"
        "group = BoardGroup.get_board_group(board=Ruggeduino,"
        " backend=SRV4RuggeduinoSimulatedBackend)\n"
        "command = group[0].command\n"
        "print(callable(command))\n"
        "try:\n"
        "    command('x')\n"
        "except NotSupportedByHardwareError as error:\n"
        "    print('refused by the official firmware')\n",
        tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["True", "refused by the official firmware"]


def test_the_facade_confirms_acknowledgements_later(tmp_path: Path) -> None:
    # On today's kit a student's motor command returns once written; the board's ACK is
    # read before that board's next call (here, reading the power back).
    result = run_program(
        "from j5aio.sync import KitRobot\n"
        "robot = KitRobot()\n"
        "motor = robot.motor_boards[0].motors[0]\n"
        "motor.power = 0.5\n"
        "backend = motor._core._backend\n"
        "print(backend.owes_acknowledgement())\n"
        "print(motor.power, backend.owes_acknowledgement())\n",
        tmp_path, J5AIO_ENV="sim", J5AIO_KIT="sr2023",
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split("\n")[:2] == ["True", "0.5 False"]
