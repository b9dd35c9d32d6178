"""The registry of board kinds: j5aio's own, registered ones and plugins' entry points."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Iterator
from typing import Any

import pytest

from j5aio import _entry_points, board_kinds
from j5aio.backends import _kinds
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.board_kinds import (
    BoardKind,
    BoardPluginWarning,
    KitDefinition,
    SimulatorClass,
    SimulatorEntry,
    find_simulator,
    get_kit,
    kits,
    register,
    simulator_entries,
    unregister,
)
from j5aio.boards.sr.v4 import MotorBoard, PowerBoard
from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator

from .kind_fakes import GEN9


@pytest.fixture
def gen9() -> Iterator[BoardKind]:
    register(GEN9)
    yield GEN9
    unregister(GEN9.name)


def test_j5aios_own_kinds_and_kits_are_registered() -> None:
    names = [kind.name for kind in board_kinds.board_kinds()]
    assert names[:5] == [
        "sr-v4-power-fw3", "sr-v4-motor-fw3", "sr-v4-servo-fw2", "sb-arduino-2019",
        "sr-ruggeduino-fw1",
    ]
    assert {"default", "sr2019", "sb2019"} <= set(kits())
    assert dict(get_kit("sr2019").boards) == {
        "sr-power": 1, "sr-motor": 1, "sr-servo": 1, "sr-ruggeduino": 1,
    }
    assert get_kit(" SB2019 ").name == "sb2019"
    kind, entry = find_simulator("sr-power")
    assert kind.board is PowerBoard
    assert entry.factory == SimulatorClass("j5aio.simulator.sr_power_fw3:SRPowerBoardFw3Simulator")
    assert isinstance(entry.factory, SimulatorClass)
    assert entry.factory.resolve() is SRPowerBoardFw3Simulator
    assert not entry.is_serial
    assert find_simulator("sr-motor")[1].is_serial


def test_unknown_names_list_what_there_is() -> None:
    with pytest.raises(ValueError, match="no kit called 'moon'; choose one of: default, sr2019"):
        get_kit("moon")
    with pytest.raises(TypeError, match="a kit name must be a str, not int"):
        get_kit(3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="no simulator called 'sr-moon'; choose one of: sr-power"):
        find_simulator("sr-moon")
    with pytest.raises(KeyError, match="no board kind or kit called 'moon'"):
        unregister("moon")


def test_a_registered_kind_joins_the_simulators_and_the_kits_it_names(gen9: BoardKind) -> None:
    assert simulator_entries()["test-motor-gen9"] == (gen9, gen9.simulators[0])
    assert SERIAL_SIMULATORS["test-motor-gen9"] is SRMotorBoardFw3Simulator
    assert "test-motor-gen9" in SERIAL_SIMULATORS
    assert get_kit("sr2019").boards["test-motor-gen9"] == 2
    assert "test-motor-gen9" not in get_kit("sb2019").boards
    with pytest.raises(ValueError, match="board kind called 'test-motor-gen9' is already"):
        register(gen9)


def test_names_already_taken_are_refused() -> None:
    clash = BoardKind(
        "test-clash", MotorBoard, "x",
        simulators=(SimulatorEntry(
            "sr-motor", SRMotorBoardFw3Simulator, "x", "SIMX", transport="serial"
        ),),
        simulated=SRV4MotorBoardHardwareBackend,
    )
    with pytest.raises(ValueError, match="simulator called 'sr-motor' is already registered"):
        register(clash)
    with pytest.raises(ValueError, match="kit called 'sr2019' is already registered"):
        register(KitDefinition("sr2019", "again", {}))
    with pytest.raises(TypeError, match="register takes a BoardKind or a KitDefinition, not str"):
        register("sr2019")  # type: ignore[arg-type]


def test_a_kit_needing_a_missing_simulator_says_so() -> None:
    register(KitDefinition("test-broken", "needs a board nobody registered", {"nothing": 1}))
    try:
        with pytest.raises(ValueError, match="needs simulators that are not registered: nothing"):
            get_kit("test-broken")
    finally:
        unregister("test-broken")


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: BoardKind("has space", MotorBoard, "x"), "without spaces, not 'has space'"),
        (lambda: BoardKind("k", int, "x"), "board must be a Board subclass"),  # type: ignore[arg-type]
        (lambda: BoardKind("k", MotorBoard, "x", hardware=int), "hardware must be a Backend"),  # type: ignore[arg-type]
        (
            lambda: BoardKind("k", PowerBoard, "x", hardware=SRV4MotorBoardHardwareBackend),
            "drives MotorBoard, not PowerBoard",
        ),
        (lambda: BoardKind("k", MotorBoard, "x", simulators=("s",)), "must be SimulatorEntry"),  # type: ignore[arg-type]
        (lambda: SimulatorEntry("s", 3, "x", "P", transport="serial"), "must be callable"),  # type: ignore[arg-type]
        (
            lambda: SimulatorEntry(
                "s", SRMotorBoardFw3Simulator, "x", "P", {"k": -1}, transport="serial"
            ),
            "0 or more",
        ),
        (lambda: KitDefinition("k", "x", {"sr-motor": 1.5}), "give a whole number"),  # type: ignore[dict-item]
        (
            lambda: SimulatorEntry("", SRMotorBoardFw3Simulator, "x", "P", transport="serial"),
            "non-empty string",
        ),
        (
            lambda: SimulatorEntry("s", SRMotorBoardFw3Simulator, "x", "P", transport="pipe"),  # type: ignore[arg-type]
            "its transport is one of 'serial', 'usb', 'other', not 'pipe'",
        ),
        (
            lambda: BoardKind(
                "k", MotorBoard, "x", hardware=SRV4MotorBoardHardwareBackend,
                simulators=(
                    SimulatorEntry("s", SRMotorBoardFw3Simulator, "x", "P", transport="serial"),
                ),
            ),
            "has simulators but names no simulated backend",
        ),
    ],
)
def test_entries_check_what_they_are_given(make: Any, message: str) -> None:
    with pytest.raises((TypeError, ValueError), match=message):
        make()


MOTOR_FW3 = "j5aio.backends.hardware.sr.v4.motor_board:SRV4MotorBoardHardwareBackend"


def test_a_backend_given_by_import_path_is_imported_when_first_read() -> None:
    kind = BoardKind("k", MotorBoard, "x", hardware=MOTOR_FW3, console=None)
    assert vars(kind)["_hardware"] == MOTOR_FW3  # not imported yet
    assert kind.hardware is SRV4MotorBoardHardwareBackend
    assert vars(kind)["_hardware"] is SRV4MotorBoardHardwareBackend  # once only
    assert kind.console is None
    assert kind == BoardKind("k", MotorBoard, "x", hardware=SRV4MotorBoardHardwareBackend)
    assert BoardKind.hardware is None  # the class's default


def test_a_simulator_class_named_by_path_is_imported_on_first_use(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import sys

    path = "j5aio.simulator.sr_motor_fw3:SRMotorBoardFw3Simulator"
    monkeypatch.delitem(sys.modules, "j5aio.simulator.sr_motor_fw3")
    factory = SimulatorClass(path)
    entry = SimulatorEntry("m", factory, "a motor board", "SIMM", transport="serial")
    assert "j5aio.simulator.sr_motor_fw3" not in sys.modules
    assert entry.is_serial  # declared: nothing is imported or made
    made = factory("SIMM0")
    assert type(made).__name__ == "SRMotorBoardFw3Simulator"
    assert made.serial_number == "SIMM0"  # type: ignore[attr-defined]
    assert factory.resolve() is type(made)
    assert repr(factory) == f"SimulatorClass({path!r})"
    assert factory == SimulatorClass(path) and hash(factory) == hash(SimulatorClass(path))
    assert factory != path


@pytest.mark.parametrize("path", ["", "no_colon", "module:", ":Name", "m:not-a-name", 3])
def test_a_simulator_class_path_must_name_a_module_and_a_class(path: Any) -> None:
    with pytest.raises(ValueError, match=r"'package\.module:ClassName'"):
        SimulatorClass(path)


def test_a_simulator_class_path_naming_no_class_fails_when_used() -> None:
    with pytest.raises(TypeError, match="is not a class"):
        SimulatorClass("j5aio.simulator.kit:current_kit")("S")
    with pytest.raises(ImportError):
        SimulatorClass("no.such.module:Simulator").resolve()


MOTOR_BOARD = "j5aio.boards.sr.v4.motor_board:MotorBoard"


def test_a_board_given_by_import_path_is_imported_when_first_read() -> None:
    kind = BoardKind("k", MOTOR_BOARD, "x", hardware=MOTOR_FW3)
    assert vars(kind)["_board"] == MOTOR_BOARD  # not imported yet
    assert kind.board_reference() == MOTOR_BOARD
    assert kind.board is MotorBoard
    assert vars(kind)["_board"] is MotorBoard  # once only
    assert kind.hardware is SRV4MotorBoardHardwareBackend  # checked against the board
    assert kind == BoardKind("k", MotorBoard, "x", hardware=SRV4MotorBoardHardwareBackend)
    assert BoardKind("k", MotorBoard, "x").board_reference() == MOTOR_BOARD  # a class: its path


def test_a_board_kind_has_no_default_board() -> None:
    with pytest.raises(TypeError, match="board"):
        BoardKind("k")  # type: ignore[call-arg]
    assert [field.name for field in dataclasses.fields(BoardKind)][:3] == [
        "name", "board", "description",
    ]


@pytest.mark.parametrize(
    ("reference", "error", "message"),
    [
        ("no.such.module:Board", ImportError, "no"),
        ("j5aio.boards.sr.v4.motor_board:NoSuchBoard", AttributeError, "NoSuch"),
        (MOTOR_FW3, TypeError, "board must be a Board subclass"),
    ],
)
def test_a_bad_board_import_path_fails_when_read(
    reference: str, error: type[Exception], message: str,
) -> None:
    kind = BoardKind("k", reference, "x")
    with pytest.raises(error, match=message):
        kind.board  # noqa: B018


def test_a_board_import_path_must_name_a_module_and_a_class() -> None:
    with pytest.raises(ValueError, match=r"'package\.module:ClassName'"):
        BoardKind("k", "no_colon", "x")
    with pytest.raises(TypeError, match="board must be a Board subclass"):
        BoardKind("k", int, "x")  # type: ignore[arg-type]


def test_a_backend_named_by_path_is_checked_against_a_board_named_by_path() -> None:
    kind = BoardKind(
        "k", MOTOR_BOARD, "x",
        hardware="j5aio.backends.hardware.sr.v4.power_board:SRV4PowerBoardHardwareBackend",
    )
    with pytest.raises(TypeError, match="drives PowerBoard, not MotorBoard"):
        kind.hardware  # noqa: B018


def test_a_backends_import_path_is_known_without_importing_it() -> None:
    kind = BoardKind("k", MotorBoard, "x", hardware=MOTOR_FW3, console=None)
    assert kind.backend_reference("hardware") == MOTOR_FW3
    assert vars(kind)["_hardware"] == MOTOR_FW3  # still not imported
    assert kind.backend_reference("console") is None
    assert kind.backend_reference("simulated") is None
    given = BoardKind("k", MotorBoard, "x", hardware=SRV4MotorBoardHardwareBackend)
    assert given.backend_reference("hardware") == MOTOR_FW3  # a class: its path
    with pytest.raises(ValueError, match="a backend role is one of hardware, console, simulated"):
        kind.backend_reference("board")


def test_the_builtin_kinds_name_their_backends_by_path_and_they_resolve() -> None:
    from j5aio.backends import _builtin_kinds

    kinds = [k for k in _builtin_kinds.entries() if isinstance(k, BoardKind)]
    assert any(isinstance(vars(k)["_console"], str) for k in kinds)
    for kind in kinds:
        for role in ("hardware", "console", "simulated"):
            backend = getattr(kind, role)
            assert backend is None or issubclass(backend.board, kind.board)
    assert kinds[0].console is not None


@pytest.mark.parametrize(
    ("reference", "error", "message"),
    [
        ("no.such.module:Backend", ImportError, "no"),
        ("j5aio.backends.hardware.sr.v4.motor_board:NoSuchBackend", AttributeError, "NoSuch"),
        ("j5aio.boards.sr.v4.motor_board:MotorBoard", TypeError, "hardware must be a Backend"),
        (
            "j5aio.backends.hardware.sr.v4.power_board:SRV4PowerBoardHardwareBackend",
            TypeError,
            "drives PowerBoard, not MotorBoard",
        ),
    ],
)
def test_a_bad_import_path_fails_when_read(
    reference: str, error: type[Exception], message: str,
) -> None:
    kind = BoardKind("k", MotorBoard, "x", hardware=reference)
    with pytest.raises(error, match=message):
        kind.hardware  # noqa: B018


@pytest.mark.parametrize("reference", ["", "no_colon", "module:", "module:not a name", ":Name"])
def test_an_import_path_must_name_a_module_and_a_class(reference: str) -> None:
    with pytest.raises(ValueError, match=r"'package\.module:ClassName'"):
        BoardKind("k", MotorBoard, "x", console=reference)


# --- plugins through the entry point group ---------------------------------------------


class FakeEntryPoint:
    def __init__(self, name: str, obj: object) -> None:
        self.name = name
        self.value = f"fake_plugin:{name}"
        self.package = "j5aio-fake-plugin"
        self._obj = obj

    def load(self) -> object:
        if isinstance(self._obj, Exception):
            raise self._obj
        return self._obj


@pytest.fixture
def fresh_registry(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[FakeEntryPoint]]:
    plugins: list[FakeEntryPoint] = []

    def find(group: str) -> list[FakeEntryPoint]:
        assert group == "j5aio.boards"
        return plugins

    monkeypatch.setattr(_entry_points, "find", find)
    monkeypatch.setattr(_kinds, "_registry", _kinds._Registry())
    yield plugins


def test_plugins_are_loaded_and_marked_with_their_package(
    fresh_registry: list[FakeEntryPoint],
) -> None:
    kit = KitDefinition("test-kit", "a plugin's kit", {"test-motor-gen9": 1})
    fresh_registry.append(FakeEntryPoint("gen9", GEN9))
    fresh_registry.append(FakeEntryPoint("kit", lambda: [kit]))
    kinds = {kind.name: kind for kind in board_kinds.board_kinds()}
    assert kinds["test-motor-gen9"].package == "j5aio-fake-plugin"
    assert kinds["sr-v4-motor-fw3"].package == "j5aio"
    assert get_kit("test-kit").package == "j5aio-fake-plugin"
    assert get_kit("sr2019").boards["test-motor-gen9"] == 2


def test_loading_a_plugin_imports_none_of_the_backends_it_names_by_path(
    fresh_registry: list[FakeEntryPoint],
) -> None:
    lazy = BoardKind(
        "test-lazy", "no_such_plugin.boards:Board", "x",
        hardware="no_such_plugin.backend:Backend", console="no_such_plugin.console:Console",
    )
    fresh_registry.append(FakeEntryPoint("lazy", [lazy]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a plugin left out would warn
        kind = {kind.name: kind for kind in board_kinds.board_kinds()}["test-lazy"]
    assert kind.package == "j5aio-fake-plugin"
    assert kind.backend_reference("hardware") == "no_such_plugin.backend:Backend"
    assert kind.board_reference() == "no_such_plugin.boards:Board"
    with pytest.raises(ImportError, match="no_such_plugin"):
        _ = kind.hardware
    with pytest.raises(ImportError, match="no_such_plugin"):
        _ = kind.board


@pytest.mark.parametrize(
    ("obj", "message"),
    [
        (ImportError("No module named 'fake_plugin'"), "ImportError: No module named"),
        (42, "must give a BoardKind, a KitDefinition, an iterable"),
        (lambda: [GEN9, "x"], "must give a BoardKind"),
        (
            BoardKind(
                "test-dup", MotorBoard, "x",
                simulators=(
                    SimulatorEntry(
                        "sr-motor", SRMotorBoardFw3Simulator, "x", "P", transport="serial"
                    ),
                ),
                simulated=SRV4MotorBoardHardwareBackend,
            ),
            "simulator called 'sr-motor' is already registered",
        ),
    ],
)
def test_a_broken_plugin_is_left_out_with_a_warning_naming_its_package(
    fresh_registry: list[FakeEntryPoint], obj: object, message: str
) -> None:
    fresh_registry.append(FakeEntryPoint("broken", obj))
    with pytest.warns(BoardPluginWarning, match="left out the board plugin 'broken'") as caught:
        kinds = board_kinds.board_kinds()
    text = str(caught[0].message)
    assert "of package 'j5aio-fake-plugin'" in text
    assert message in text
    assert {kind.name for kind in kinds} >= {"sr-v4-motor-fw3"}
    assert "test-dup" not in {kind.name for kind in kinds}


def test_reading_the_kinds_while_they_load_is_refused(
    fresh_registry: list[FakeEntryPoint],
) -> None:
    fresh_registry.append(FakeEntryPoint("nested", lambda: board_kinds.board_kinds()))
    with pytest.warns(BoardPluginWarning, match="RuntimeError: the board kinds were read while"):
        board_kinds.board_kinds()


def test_a_kit_definition_says_how_its_boards_are_wired_and_numbered() -> None:
    kit = KitDefinition(
        "wired", "a wired kit", {"sr-power-fw4": 1, "sr-motor-fw4": 2},
        wiring={"sr-motor-fw4": ("H0", 1)}, serials={"sr-motor-fw4": ("A", "B")},
    )
    assert kit.wiring == {"sr-motor-fw4": ("H0", 1)}
    assert kit.serials == {"sr-motor-fw4": ("A", "B")}
    one = KitDefinition(
        "one", "one board", {"sr-motor": 1}, wiring={"sr-motor": "L1"}  # type: ignore[dict-item]
    )
    assert one.wiring == {"sr-motor": ("L1",)}



def test_a_kit_a_plugins_board_joins_keeps_its_wiring(gen9: BoardKind) -> None:
    kit = get_kit("sr2019")
    assert kit.boards["test-motor-gen9"] == 2
    assert kit.wiring == {"sr-motor": ("H0",), "sr-servo": ("L0",)}


@pytest.mark.parametrize(
    ("wiring", "serials", "match"),
    [
        ({"sr-servo": ("L0",)}, {}, "names 'sr-servo', which the kit has no boards of"),
        ({"sr-motor": ("H0",)}, {}, "give 1 for 'sr-motor', which the kit has 2 of"),
        ({"sr-motor": ("H0", "L2")}, {}, "cannot be wired to L2"),
        ({"sr-motor": ("H0", "Q1")}, {}, "no output 'Q1'"),
        ({"sr-motor": ("H0", None)}, {}, "give an output's name"),
        ({}, {"sr-motor": ("A", "A")}, "serial number 'A' is given twice"),
        ({}, {"sr-motor": ("A", "B C")}, "without spaces"),
        ({}, {"sr-motor": ("A", 7)}, "without spaces"),
    ],
)
def test_a_kit_definitions_wiring_and_serials_are_checked(
    wiring: dict[str, Any], serials: dict[str, Any], match: str
) -> None:
    with pytest.raises(ValueError, match=match):
        KitDefinition("bad", "a bad kit", {"sr-motor": 2}, wiring=wiring, serials=serials)
