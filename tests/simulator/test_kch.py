import anyio
import pytest
from gpiozero.pins.mock import MockFactory

from j5aio.backends.hardware.sr.kch import KCHHardwareBackend
from j5aio.boards.sr.kch import Colour, KCHBoard
from j5aio.simulator.kch import KCHSimulator


async def test_the_simulated_kch_runs_the_real_backend_and_shows_the_leds(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    simulator = KCHSimulator()
    board = simulator.board("SR0SIM")
    assert isinstance(board, KCHBoard)
    assert board.serial_number == "SR0SIM"
    await board.setup()
    assert simulator.colours == ((False, False, False),) * 3
    await board.leds[0].set_colour(Colour.RED)
    await board.leds[1].set_colour(Colour.CYAN)
    await board.leds[2].set_colour(Colour.WHITE)
    assert simulator.colours == ((True, False, False), (False, True, True), (True, True, True))
    assert not simulator.start_led
    await board.start_led.set_state(True)
    assert simulator.start_led
    before = simulator.start_led_changes
    monkeypatch.setattr(KCHHardwareBackend, "FLASH_PERIOD", 0.04)
    await board.start_led.flash()
    with anyio.fail_after(5):
        while simulator.start_led_changes < before + 4:  # noqa: ASYNC110 - a thread flashes it
            await anyio.sleep(0.01)
    await board.make_safe()
    assert not simulator.start_led
    assert simulator.colours[2] == (True, True, True)  # colours stay once made safe
    await board.close()


async def test_closing_the_kch_releases_its_pins_and_every_led_goes_dark() -> None:
    simulator = KCHSimulator()
    board = simulator.board()
    assert isinstance(board, KCHBoard)
    await board.leds[0].set_colour(Colour.RED)
    await board.leds[2].set_colour(Colour.WHITE)
    await board.start_led.set_state(True)
    assert simulator.colours[0] == (True, False, False) and simulator.start_led
    await board.close()  # as at the end of a program
    pin = simulator.pin_factory.pin(24)
    assert pin.function == "input"  # released: gpiozero no longer drives it
    assert simulator.colours == ((False, False, False),) * 3
    assert not simulator.start_led


def test_a_given_pin_factory_is_used() -> None:
    factory = MockFactory()
    simulator = KCHSimulator(factory)
    assert simulator.pin_factory is factory
    pin = factory.pin(24)
    pin.drive_high()  # an input held high lights nothing: no pin drives the LED
    assert simulator.colours[0] == (False, False, False)
    pin.function = "output"
    pin.state = True
    assert simulator.colours[0] == (True, False, False)


async def test_the_board_is_given_back_while_open_and_made_anew_after() -> None:
    from j5aio.backends.hardware.sr.kch import KCHHardwareBackend

    class Simulated(KCHHardwareBackend):
        pass

    simulator = KCHSimulator()
    board = simulator.board("A", backend_class=Simulated)
    assert type(board.backend) is Simulated
    assert simulator.board("B") is board
    await board.close()
    assert isinstance(board.backend, Simulated)
    assert board.backend.closed
    again = simulator.board("B")
    assert again is not board
    assert again.serial_number == "B"
    assert type(again.backend) is KCHHardwareBackend
    await again.close()
