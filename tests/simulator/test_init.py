from __future__ import annotations

import importlib

import pytest

import j5aio.simulator as simulator
from j5aio.simulator import (
    SERIAL_SIMULATORS,
    SBArduino2024Simulator,
    SBArduinoSimulator,
    SBServoBoardFw4Simulator,
    SerialBoardSimulator,
    SRMotorBoardFw3Simulator,
    SRMotorBoardFw4Simulator,
    SRPowerBoardFw4Simulator,
    SRRuggeduinoSimulator,
    SRServoBoardFw4Simulator,
)


def test_serial_simulators_by_cli_name() -> None:
    # j5aio's own, and any an installed plugin registers.
    assert "sr-power" not in SERIAL_SIMULATORS  # a USB board cannot be served on a pty
    expected = {
        "sr-motor": SRMotorBoardFw3Simulator,
        "sr-ruggeduino": SRRuggeduinoSimulator,
        "sb-arduino": SBArduinoSimulator,
        "sr-power-fw4": SRPowerBoardFw4Simulator,
        "sr-motor-fw4": SRMotorBoardFw4Simulator,
        "sr-servo-fw4": SRServoBoardFw4Simulator,
        "sb-servo-fw4": SBServoBoardFw4Simulator,
        "sr-arduino-fw2": SRRuggeduinoSimulator,
        "sb-arduino-2024": SBArduino2024Simulator,
    }
    assert set(SERIAL_SIMULATORS) >= set(expected)
    for name, factory in SERIAL_SIMULATORS.items():
        if name not in expected:
            continue  # a plugin's
        board = factory("SER123")
        assert isinstance(board, SerialBoardSimulator)
        assert isinstance(board, expected[name])
        assert board.serial_number == "SER123"


def test_the_mapping_reads_the_registry() -> None:
    assert len(SERIAL_SIMULATORS) == len(list(SERIAL_SIMULATORS))
    assert "sr-motor" in repr(SERIAL_SIMULATORS)


def test_the_registry_cannot_be_changed() -> None:
    with pytest.raises(TypeError):
        SERIAL_SIMULATORS["x"] = SRMotorBoardFw3Simulator  # type: ignore[index]


def test_every_exported_name_exists() -> None:
    # (__all__ is made at run time from the package's table of lazy exports, so a type
    # checker does not see it)
    for name in importlib.import_module("j5aio.simulator").__all__:
        assert hasattr(simulator, name)
