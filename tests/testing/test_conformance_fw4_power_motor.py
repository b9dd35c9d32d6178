"""The conformance suites against the SR power board fw 4.4 and motor board fw 4.4/4.5.

Each hardware backend runs over its simulator (through a :class:`RecordingStream`, so the
suites check that refused calls send nothing), and each console backend with a
:class:`ConsoleScript` playing the user.
"""

from __future__ import annotations

import re
from collections.abc import Awaitable, Callable, Sequence
from datetime import timedelta
from typing import Any, ClassVar

import anyio

from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardFw4ConsoleBackend,
    SRV4PowerBoardFw4ConsoleBackend,
)
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardFw4HardwareBackend,
    SRV4PowerBoardFw4HardwareBackend,
)
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.board import Board
from j5aio.components.flashing_led import LEDMode
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.simulator import MotorDrive, SRMotorBoardFw4Simulator, SRPowerBoardFw4Simulator
from j5aio.simulator.base import SerialBoardSimulator
from j5aio.testing.conformance import (
    BatterySensorInterfaceConformance,
    BatterySensorSubject,
    ButtonInterfaceConformance,
    ButtonSubject,
    FlashingLEDInterfaceConformance,
    FlashingLEDSubject,
    MonitoredMotorInterfaceConformance,
    MonitoredMotorSubject,
    PiezoInterfaceConformance,
    PiezoSubject,
    PowerOutputInterfaceConformance,
    PowerOutputSubject,
)
from j5aio.testing.console import ConsoleScript
from j5aio.testing.transports import RecordingStream

#: Every output but L2 (4), which powers the brain and cannot be switched.
SWITCHABLE_OUTPUTS = [0, 1, 2, 3, 5, 6]
#: Powers the motor suite sets. Power 0 is left out: this board brakes at 0, so the
#: simulator cannot show it apart from BRAKE (the backend test covers reading 0.0 back).
FW4_POWERS = (1.0, 0.5, 0.25, -0.25, -0.5, -1.0)


async def over(
    backend_class: type[SerialHardwareBackend], sim: SerialBoardSimulator,
) -> tuple[Board, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(stream, port="sim", serial_number="SIM0")
    await board.setup()
    stream.clear()
    return board, stream


class PowerSuite:
    sim: SRPowerBoardFw4Simulator
    backend: SRV4PowerBoardFw4HardwareBackend
    traffic: Callable[[], bytes]
    cleanup: Callable[[], Awaitable[None]]

    async def board(self) -> None:
        self.sim = SRPowerBoardFw4Simulator("srSIM")
        board, stream = await over(SRV4PowerBoardFw4HardwareBackend, self.sim)
        assert isinstance(board.backend, SRV4PowerBoardFw4HardwareBackend)
        self.backend = board.backend
        self.traffic = lambda: stream.sent
        self.cleanup = board.close

    def common(self) -> dict[str, Any]:
        """The subject arguments every power board suite gives."""
        return {"backend": self.backend, "traffic": self.traffic, "cleanup": self.cleanup}


class TestFw4PowerOutputs(PowerSuite, PowerOutputInterfaceConformance):
    async def make_backend(self) -> PowerOutputSubject:
        await self.board()

        async def observe(identifier: int) -> bool:
            return self.sim.outputs[identifier]

        async def set_current(identifier: int, amps: float) -> None:
            self.sim.set_output_current(identifier, amps)

        return PowerOutputSubject(
            **self.common(), identifiers=SWITCHABLE_OUTPUTS,
            observe=observe, set_current=set_current,
        )


class TestFw4PowerLEDs(PowerSuite, FlashingLEDInterfaceConformance):
    async def make_backend(self) -> FlashingLEDSubject:
        await self.board()

        async def observe(identifier: int) -> bool:
            return self.sim.run_led if identifier == 0 else self.sim.error_led

        async def observe_mode(identifier: int) -> LEDMode:
            return {"0": LEDMode.OFF, "1": LEDMode.ON, "F": LEDMode.FLASH}[
                self.sim.led_modes[identifier]
            ]

        return FlashingLEDSubject(
            **self.common(), identifiers=[0, 1], observe=observe, observe_mode=observe_mode,
        )


class TestFw4PowerButton(PowerSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        await self.board()

        async def set_pressed(identifier: int, pressed: bool) -> None:
            (self.sim.press_start if pressed else self.sim.release_start)()

        async def press(identifier: int) -> None:
            self.sim.press_start()
            await anyio.sleep(SRV4PowerBoardFw4HardwareBackend.BUTTON_POLL_INTERVAL * 3)
            self.sim.release_start()

        return ButtonSubject(
            **self.common(), identifiers=[0], set_pressed=set_pressed, press=press,
        )


class TestFw4PowerBattery(PowerSuite, BatterySensorInterfaceConformance):
    async def make_backend(self) -> BatterySensorSubject:
        await self.board()

        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            self.sim.battery_voltage = volts
            self.sim.battery_current = amps

        return BatterySensorSubject(
            **self.common(), identifiers=[0], set_reading=set_reading,
        )


class TestFw4PowerPiezo(PowerSuite, PiezoInterfaceConformance):
    async def make_backend(self) -> PiezoSubject:
        await self.board()

        async def observe(identifier: int) -> Sequence[tuple[timedelta, float]]:
            return [
                (timedelta(milliseconds=note.duration_ms), float(note.frequency))
                for note in self.sim.note_history
            ]

        return PiezoSubject(**self.common(), identifiers=[0], observe=observe)


class TestFw4MotorBoard(MonitoredMotorInterfaceConformance):
    powers: ClassVar[tuple[float, ...]] = FW4_POWERS
    # The board steps powers by 0.001.
    power_tolerance: ClassVar[float] = 0.001

    async def make_backend(self) -> MonitoredMotorSubject:
        sim = SRMotorBoardFw4Simulator("srSIM")
        board, stream = await over(SRV4MotorBoardFw4HardwareBackend, sim)

        async def observe(identifier: int) -> MotorState:
            channel = sim.motors[identifier]
            if channel.drive is MotorDrive.COAST:
                return MotorSpecialState.COAST
            if channel.drive is MotorDrive.BRAKE:
                return MotorSpecialState.BRAKE
            return channel.power

        async def set_current(identifier: int, amps: float) -> None:
            sim.set_motor_current(identifier, amps)

        async def set_fault(identifier: int, fault: bool) -> None:
            sim.set_fault(identifier, fault)

        assert isinstance(board.backend, SRV4MotorBoardFw4HardwareBackend)
        return MonitoredMotorSubject(
            backend=board.backend, identifiers=[0, 1], observe=observe,
            traffic=lambda: stream.sent, cleanup=board.close,
            set_current=set_current, set_fault=set_fault,
        )


# --- console --------------------------------------------------------------------------


class ConsolePowerSuite:
    script: ConsoleScript

    def power_board(self) -> SRV4PowerBoardFw4ConsoleBackend:
        self.script = ConsoleScript()
        return SRV4PowerBoardFw4ConsoleBackend("SERIAL", self.script.console_class())


class TestFw4PowerConsoleOutputs(ConsolePowerSuite, PowerOutputInterfaceConformance):
    async def make_backend(self) -> PowerOutputSubject:
        async def set_current(identifier: int, amps: float) -> None:
            self.script.answer(f"Current for power output {identifier}", str(amps), replace=True)

        return PowerOutputSubject(
            backend=self.power_board(), identifiers=SWITCHABLE_OUTPUTS, set_current=set_current,
        )


class TestFw4PowerConsoleLEDs(ConsolePowerSuite, FlashingLEDInterfaceConformance):
    async def make_backend(self) -> FlashingLEDSubject:
        return FlashingLEDSubject(backend=self.power_board(), identifiers=[0, 1])


class TestFw4PowerConsoleButton(ConsolePowerSuite, ButtonInterfaceConformance):
    async def make_backend(self) -> ButtonSubject:
        async def set_pressed(identifier: int, pressed: bool) -> None:
            self.script.answer("Start button state", str(pressed).lower(), replace=True)

        async def press(identifier: int) -> None:
            self.script.answer("Hit return to press start button", "")

        return ButtonSubject(
            backend=self.power_board(), identifiers=[0], set_pressed=set_pressed, press=press,
        )


class TestFw4PowerConsoleBattery(ConsolePowerSuite, BatterySensorInterfaceConformance):
    async def make_backend(self) -> BatterySensorSubject:
        async def set_reading(identifier: int, volts: float, amps: float) -> None:
            self.script.answer("Battery voltage", str(volts), replace=True)
            self.script.answer("Battery current", str(amps), replace=True)

        return BatterySensorSubject(
            backend=self.power_board(), identifiers=[0], set_reading=set_reading,
        )


class TestFw4PowerConsolePiezo(ConsolePowerSuite, PiezoInterfaceConformance):
    async def make_backend(self) -> PiezoSubject:
        async def observe(identifier: int) -> Sequence[tuple[timedelta, float]]:
            found = (re.search(r"Buzzing at ([\d.]+)Hz for (\d+)ms", line)
                     for line in self.script.printed)
            return [(timedelta(milliseconds=int(m[2])), float(m[1])) for m in found if m]

        return PiezoSubject(backend=self.power_board(), identifiers=[0], observe=observe)


class TestFw4MotorConsole(MonitoredMotorInterfaceConformance):
    async def make_backend(self) -> MonitoredMotorSubject:
        script = ConsoleScript()
        backend = SRV4MotorBoardFw4ConsoleBackend("SERIAL", script.console_class())

        async def set_current(identifier: int, amps: float) -> None:
            script.answer(f"Current of motor {identifier}", str(amps), replace=True)

        async def set_fault(identifier: int, fault: bool) -> None:
            for motor in (0, 1):
                answer = str(fault and motor == identifier).lower()
                script.answer(f"Does motor {motor} have a fault", answer, replace=True)

        return MonitoredMotorSubject(
            backend=backend, identifiers=[0, 1], set_current=set_current, set_fault=set_fault,
        )
