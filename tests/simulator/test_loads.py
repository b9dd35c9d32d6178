"""The power boards' shared load model: what the boards on their outputs draw."""

from __future__ import annotations

import pytest

from j5aio.simulator.loads import BATTERY_INTERNAL_RESISTANCE, PowerBoardLoads
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator


def boards() -> list[PowerBoardLoads]:
    return [SRPowerBoardFw3Simulator("P3"), SRPowerBoardFw4Simulator("P4")]


@pytest.mark.parametrize("board", boards(), ids=["fw3", "fw4"])
def test_only_outputs_that_are_on_load_the_battery(board: PowerBoardLoads) -> None:
    board.battery_voltage = 12.0
    board.set_supplied_current(0, 2.0)
    board.set_supplied_current(1, 3.0)
    board._outputs[0] = True
    board._outputs[1] = False
    assert board.load_current == pytest.approx(2.0)
    assert board.loaded_voltage == pytest.approx(12.0 - 2.0 * BATTERY_INTERNAL_RESISTANCE)
    board._outputs[1] = True
    assert board.load_current == pytest.approx(5.0)


@pytest.mark.parametrize("board", boards(), ids=["fw3", "fw4"])
def test_the_loaded_voltage_does_not_go_below_zero(board: PowerBoardLoads) -> None:
    board.battery_voltage = 0.1
    board.set_supplied_current(0, 1000.0)
    board._outputs[0] = True
    assert board.loaded_voltage == 0.0


@pytest.mark.parametrize("board", boards(), ids=["fw3", "fw4"])
@pytest.mark.parametrize("output", [-1, 7, 99])
def test_an_output_the_board_lacks_is_refused(board: PowerBoardLoads, output: int) -> None:
    with pytest.raises(IndexError, match=f"output {output} does not exist"):
        board.set_supplied_current(output, 1.0)


@pytest.mark.parametrize("board", boards(), ids=["fw3", "fw4"])
def test_the_battery_is_kept_in_millivolts_and_milliamps(board: PowerBoardLoads) -> None:
    board.battery_voltage = 11.1234
    board.battery_current = -0.5006  # charging
    assert board.battery_voltage == 11.123
    assert board.battery_current == -0.501
    with pytest.raises(ValueError, match="battery voltage cannot be negative"):
        board.battery_voltage = -1.0
