"""The conformance suites added for today's kits catch backends broken as they promise.

The correct backends run through each suite in test_conformance_fw4_servo_kch.py; here
the console backends, broken on purpose, show each suite failing.
"""

from __future__ import annotations

from typing import Any

import pytest

from j5aio.backends.console.sr.kch import KCHConsoleBackend
from j5aio.backends.console.sr.v4 import SRV4ServoBoardFw4ConsoleBackend
from j5aio.components.flashing_led import LEDMode
from j5aio.components.pulse_servo import PulseLimits
from j5aio.components.servo import ServoPosition
from j5aio.testing.conformance import (
    FlagInterfaceConformance,
    FlagSubject,
    FlashingLEDInterfaceConformance,
    FlashingLEDSubject,
    PulseServoInterfaceConformance,
    PulseServoSubject,
    SupplySensorInterfaceConformance,
    SupplySensorSubject,
)
from j5aio.testing.conformance._base import Subject
from j5aio.testing.console import ConsoleScript


async def run(suite: Any, test: str, subject: Subject) -> None:
    """Run one test of ``suite`` against ``subject`` (a broken backend), as pytest would."""

    class Suite(suite):  # type: ignore[misc]
        async def make_backend(self) -> Subject:
            return subject

    await getattr(Suite(), test)(subject)


def servo_backend(cls: type[SRV4ServoBoardFw4ConsoleBackend]) -> SRV4ServoBoardFw4ConsoleBackend:
    return cls("SERIAL", ConsoleScript().console_class())


async def test_pulse_servo_suite_catches_ignored_limits() -> None:
    class IgnoresLimits(SRV4ServoBoardFw4ConsoleBackend):
        async def set_servo_position(self, identifier: int, position: ServoPosition) -> None:
            saved = self._limits[identifier]
            self._limits[identifier] = (1000, 2000)
            await super().set_servo_position(identifier, position)
            self._limits[identifier] = saved

    subject = PulseServoSubject(backend=servo_backend(IgnoresLimits), identifiers=range(12))
    with pytest.raises(AssertionError, match=r"servo 0 should get a 500 µs pulse but reads 1000"):
        await run(PulseServoInterfaceConformance, "test_positions_follow_the_limits", subject)


async def test_pulse_servo_suite_catches_limits_beyond_the_range() -> None:
    class Lax(SRV4ServoBoardFw4ConsoleBackend):
        async def set_servo_pulse_limits(self, identifier: int, limits: PulseLimits) -> None:
            self._limits[identifier] = limits

    subject = PulseServoSubject(backend=servo_backend(Lax), identifiers=range(12))
    with pytest.raises(AssertionError, match=r"pulse limits \(499, 4000\) were accepted"):
        await run(PulseServoInterfaceConformance, "test_limits_outside_the_range_are_refused",
                  subject)


async def test_pulse_servo_suite_catches_a_range_upside_down() -> None:
    class UpsideDown(SRV4ServoBoardFw4ConsoleBackend):
        MIN_PULSE = 4000
        MAX_PULSE = 500

    subject = PulseServoSubject(backend=servo_backend(UpsideDown), identifiers=range(12))
    with pytest.raises(AssertionError):
        await run(PulseServoInterfaceConformance, "test_range_and_default_limits", subject)


async def test_pulse_servo_suite_catches_a_board_showing_another_pulse() -> None:
    async def observe_pulse(identifier: int) -> int | None:
        return 1500

    subject = PulseServoSubject(
        backend=servo_backend(SRV4ServoBoardFw4ConsoleBackend), identifiers=range(12),
        observe_pulse=observe_pulse,
    )
    with pytest.raises(AssertionError, match=r"servo 0 reads 500 µs, the board shows 1500"):
        await run(PulseServoInterfaceConformance, "test_positions_follow_the_limits", subject)


async def test_supply_suite_catches_millivolts() -> None:
    script = ConsoleScript()
    backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", script.console_class())

    async def set_reading(identifier: int, volts: float, amps: float) -> None:
        script.answer("Servo supply voltage", str(volts * 1000), replace=True)
        script.answer("Servo supply current", str(amps), replace=True)

    subject = SupplySensorSubject(backend=backend, identifiers=[0], set_reading=set_reading)
    with pytest.raises(AssertionError, match=r"supply 0 is at 5.5 V but reads 5500.0 V"):
        await run(SupplySensorInterfaceConformance, "test_readings_follow_the_supply", subject)


async def test_flag_suite_catches_crossed_flags() -> None:
    script = ConsoleScript()
    backend = SRV4ServoBoardFw4ConsoleBackend("SERIAL", script.console_class())
    names = ("Watchdog failed", "Power good")  # the wrong way round

    async def set_flag(identifier: int, raised: bool) -> None:
        script.answer(names[identifier], str(raised).lower(), replace=True)

    subject = FlagSubject(backend=backend, identifiers=[0, 1], set_flag=set_flag)
    with pytest.raises(AssertionError, match=r"flag 0 reads False with only flag 0 raised"):
        await run(FlagInterfaceConformance, "test_flags_follow_the_board", subject)


async def test_flashing_led_suite_catches_flashing_that_never_stops() -> None:
    class Stuck(KCHConsoleBackend):
        async def set_led_state(self, identifier: int, state: bool) -> None:
            self._start = state

    subject = FlashingLEDSubject(backend=Stuck("SERIAL", ConsoleScript().console_class()),
                                 identifiers=[0])
    with pytest.raises(AssertionError, match=r"LED 0 was set to LEDMode.OFF but reads back"):
        await run(FlashingLEDInterfaceConformance, "test_state_and_mode_agree", subject)


async def test_flashing_led_suite_catches_flashing_not_reported() -> None:
    class Forgetful(KCHConsoleBackend):
        async def get_led_mode(self, identifier: int) -> LEDMode:
            return LEDMode.OFF

    subject = FlashingLEDSubject(backend=Forgetful("SERIAL", ConsoleScript().console_class()),
                                 identifiers=[0])
    with pytest.raises(AssertionError, match=r"LED 0 was set to LEDMode.FLASH but reads back"):
        await run(FlashingLEDInterfaceConformance, "test_mode_round_trips", subject)
