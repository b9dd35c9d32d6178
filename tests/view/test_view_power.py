"""The live view shows the kit's power: the outputs switched on, and boards without power."""

from __future__ import annotations

import io
import warnings

import pytest

pytest.importorskip("aiohttp", reason="the view extra is not installed")

from j5aio.kit import KitRobot
from j5aio.kit_power import KitPowerWarning
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import use_kit
from j5aio.view import serve_view


async def test_the_view_shows_the_outputs_and_names_the_output_to_switch_on(
    fresh_kit: None,
) -> None:
    use_kit("sr2023")
    async with serve_view(out=io.StringIO()) as view:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", KitPowerWarning)
            async with KitRobot(environment=SIMULATED_ENVIRONMENT, power_on=["L3"]):
                changes = view.state.changes(0, 0)
    power_lines = [text for port, text in changes.log if port == "power"]
    assert any("SIMMB0" in text and "output H0" in text for text in power_lines), power_lines
    assert any("SIMSB0" in text and "output L0" in text for text in power_lines), power_lines
    shown = {(key, name): value for key, name, value in changes.values}
    # L3 (output 5) was switched on; the servo board says it has no power.
    assert shown[("SIMPB0:protectedpoweroutput:5", "power_output_enabled")] is True
    assert shown[("SIMSB0:flag:0", "flag_state")] is False  # power good: no
