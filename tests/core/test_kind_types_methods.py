"""The registry's dataclasses write their own methods: they behave as ``@dataclass`` makes them."""

from __future__ import annotations

import inspect

from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.board_kinds import BoardKind, KitDefinition, SimulatorClass, SimulatorEntry
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from tests.dataclass_twins import assert_like_generated

_ENTRY = SimulatorEntry("sr-x", SRMotorBoardFw3Simulator, "x", "SIMX", transport="serial")


def test_simulator_entry_is_the_generated_dataclass() -> None:
    assert_like_generated(
        SimulatorEntry,
        [
            (("a", SRMotorBoardFw3Simulator, "one", "SIMA"), {"transport": "serial"}),
            (("a", SRMotorBoardFw3Simulator, "one", "SIMA", {}), {"transport": "serial"}),
            (("b", SimulatorClass("m.n:C"), "two", "SIMB", {"default": 2}), {"transport": "usb"}),
        ],
    )


def test_an_omitted_mapping_is_a_new_empty_dict() -> None:
    first = SimulatorEntry("a", SRMotorBoardFw3Simulator, "one", "SIMA", transport="serial")
    second = SimulatorEntry("b", SRMotorBoardFw3Simulator, "two", "SIMB", transport="serial")
    assert first.kits == {} and type(first.kits) is dict and first.kits is not second.kits
    kit = KitDefinition("k", "a kit", {"sr-motor": 1})
    assert dict(kit.wiring) == {} and dict(kit.serials) == {}
    # The documentation shows the default as an empty mapping.
    assert str(inspect.signature(SimulatorEntry).parameters["kits"]).endswith("= {}")


def test_board_kind_is_the_generated_dataclass() -> None:
    assert_like_generated(
        BoardKind,
        [
            (("k-one", MotorBoard, "one"), {}),
            (
                ("k-two", "j5aio.boards.sr.v4:MotorBoard", "two"),
                {
                    "hardware": SRV4MotorBoardHardwareBackend,
                    "simulators": (_ENTRY,),
                    "simulated": SRV4MotorBoardHardwareBackend,
                    "identify_order": 5,
                    "package": "plugin",
                },
            ),
            (("k-one", MotorBoard, "one"), {"identify_order": 7}),
        ],
    )


def test_kit_definition_is_the_generated_dataclass() -> None:
    assert_like_generated(
        KitDefinition,
        [
            (("k", "a kit", {"sr-motor": 2}), {}),
            (
                ("k", "a kit", {"sr-motor": 2}, "plugin"),
                {"wiring": {"sr-motor": ("H0", "H1")}, "serials": {"sr-motor": ("A", "B")}},
            ),
            (("other", "another", {}), {}),
        ],
    )
