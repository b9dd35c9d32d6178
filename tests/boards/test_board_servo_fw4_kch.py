from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import (
    SBServoBoardConsoleBackend,
    SRV4ServoBoardConsoleBackend,
    SRV4ServoBoardFw4ConsoleBackend,
)
from j5aio.boards.sb import SBServoBoard
from j5aio.boards.sr.kch import Colour, KCHBoard
from j5aio.boards.sr.v4 import ServoBoard, ServoBoardFw4
from j5aio.components import LED, RGBLED, Flag, FlashingLED, PulseServo, Servo, SupplySensor


def test_servo_board_fw4_is_a_servo_board_with_more() -> None:
    board = ServoBoardFw4("S", SRV4ServoBoardFw4ConsoleBackend("S"))
    assert isinstance(board, ServoBoard)
    assert [servo.identifier for servo in board.servos] == list(range(12))
    assert all(type(servo) is PulseServo for servo in board.servos)
    assert isinstance(board.supply, SupplySensor)
    assert isinstance(board.power_good, Flag)
    assert board.power_good.identifier == ServoBoardFw4.POWER_GOOD
    assert board.watchdog_failed.identifier == ServoBoardFw4.WATCHDOG_FAILED
    assert ServoBoardFw4.supported_components() == {PulseServo, SupplySensor, Flag}
    assert "4.3" in ServoBoardFw4.name


def test_the_sourcebots_board_has_eight_servos() -> None:
    board = SBServoBoard("S", SBServoBoardConsoleBackend("S"))
    assert isinstance(board, ServoBoardFw4)
    assert len(board.servos) == SBServoBoard.SERVO_COUNT == 8
    assert "SourceBots" in SBServoBoard.name


def test_the_firmware_2_board_is_unchanged() -> None:
    board = ServoBoard("S", SRV4ServoBoardConsoleBackend("S"))
    assert all(type(servo) is Servo for servo in board.servos)
    assert len(board.servos) == 12


def test_kch_components() -> None:
    board = KCHBoard("S", KCHConsoleBackend("S"))
    assert [led.identifier for led in board.leds] == [0, 1, 2]
    assert all(isinstance(led, RGBLED) for led in board.leds)
    assert isinstance(board.start_led, FlashingLED)
    assert isinstance(board.start_led, LED)
    assert KCHBoard.supported_components() == {RGBLED, FlashingLED}
    colours = {value for name, value in vars(Colour).items() if name.isupper()}
    assert len(colours) == 8
    assert all(set(colour) <= {0.0, 1.0} for colour in colours)
