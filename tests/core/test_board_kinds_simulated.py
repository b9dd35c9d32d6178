"""Simulated kits made from the registry: named kits, J5AIO_KIT and registered kinds."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator

import pytest

from j5aio.board_kinds import KitDefinition, register, unregister
from j5aio.boards.board import Board
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.simulator import kit as kit_module
from j5aio.simulator.environment import kit_discovery_options, simulated_backend
from j5aio.simulator.kit import KitConfig, SimulatedKit, current_kit, use_kit
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator

from .kind_fakes import GEN9, Gen9HardwareBackend, Gen9SimulatedBackend, MotorBoardGen9


@pytest.fixture(autouse=True)
def _no_current_kit() -> Iterator[None]:
    saved = kit_module._current
    kit_module._current = None
    yield
    kit_module._current = saved


@pytest.fixture
async def _close_boards() -> AsyncIterator[None]:
    yield
    for board in list(Board.BOARDS):
        await board.close()


def test_a_named_kit_has_its_boards_and_a_matching_config() -> None:
    kit = SimulatedKit("sr2019", time_scale=0.5)
    assert kit.definition is not None and kit.definition.name == "sr2019"
    assert kit.config == KitConfig(1, 1, 1, 0, 1, time_scale=0.5)
    assert [sim.serial_number for sim in kit.ruggeduinos] == ["SIMRD0"]
    assert kit.simulator_names() == ("sr-power", "sr-motor", "sr-servo", "sr-ruggeduino")
    assert kit.simulators("sr-ruggeduino") == kit.ruggeduinos
    assert kit.simulators("sb-arduino") == ()
    assert kit.kind_of(kit.ruggeduinos[0]).name == "sr-ruggeduino-fw1"
    assert "<SimulatedKit" in repr(kit) and "sr2019>" in repr(kit)
    with pytest.raises(KeyError, match="is not a board of"):
        kit.kind_of(SRRuggeduinoSimulator("X"))


def test_kit_arguments_are_checked() -> None:
    with pytest.raises(TypeError, match="give the time scale in the KitConfig"):
        SimulatedKit(KitConfig(), time_scale=1.0)
    with pytest.raises(TypeError, match="a kit is a KitConfig, a KitDefinition or a kit's name"):
        SimulatedKit(3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="time_scale must be 0 or more"):
        SimulatedKit("sr2019", time_scale=-1)
    with pytest.raises(ValueError, match="no kit called 'moon'; choose one of"):
        use_kit("moon")
    with pytest.raises(ValueError, match="simulator called 'nothing', which is not registered"):
        SimulatedKit(KitDefinition("x", "x", {"nothing": 1}))
    with pytest.raises(ValueError, match="must be between 0 and 99, not 100"):
        SimulatedKit(KitDefinition("x", "x", {"sr-motor": 100}))


def test_simulators_sharing_a_serial_prefix_are_refused() -> None:
    from dataclasses import replace

    clash = replace(
        GEN9, simulators=(replace(GEN9.simulators[0], serial_prefix="SIMMB", kits={}),)
    )
    register(clash)
    try:
        with pytest.raises(ValueError, match="'sr-motor' and 'test-motor-gen9' both number"):
            SimulatedKit(KitDefinition("x", "x", {"sr-motor": 1, "test-motor-gen9": 1}))
    finally:
        unregister(clash.name)


def test_j5aio_kit_chooses_the_first_current_kit(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("J5AIO_KIT", "sr2019")
    assert current_kit().definition.name == "sr2019"  # type: ignore[union-attr]
    kit_module._current = None
    monkeypatch.setenv("J5AIO_KIT", "moon")
    with pytest.raises(ValueError, match="J5AIO_KIT='moon': there is no kit called 'moon'"):
        current_kit()
    kit_module._current = None
    monkeypatch.setenv("J5AIO_KIT", "")
    assert current_kit().definition.name == "default"  # type: ignore[union-attr]


@pytest.mark.usefixtures("_close_boards")
async def test_a_registered_kind_s_simulated_backend_finds_its_own_boards() -> None:
    register(GEN9)
    try:
        backend = simulated_backend(GEN9)
        assert backend is Gen9SimulatedBackend  # the one the kind names, not one made
        assert issubclass(backend, Gen9HardwareBackend)
        kit = use_kit(KitDefinition("x", "x", {"sr-motor": 1, "test-motor-gen9": 2}))
        boards = await backend.discover()
        for board in boards:
            await board.setup()  # so that the fixture closes it
        assert sorted(board.serial_number for board in boards) == ["SIMG90", "SIMG91"]
        assert all(isinstance(board, MotorBoardGen9) for board in boards)
        options = kit_discovery_options(kit, kind=GEN9)
        assert options.port_source is not None
        assert len(list(options.port_source())) == 2
        assert all(isinstance(sim, SRMotorBoardFw3Simulator) for sim in kit.serial_simulators())
    finally:
        unregister(GEN9.name)


def test_a_kind_without_simulators_has_no_simulated_backend() -> None:
    from dataclasses import replace

    assert simulated_backend(replace(GEN9, simulators=(), simulated=None)) is None
    own = replace(GEN9, simulated=Gen9HardwareBackend)
    assert simulated_backend(own) is Gen9HardwareBackend
    assert issubclass(MotorBoardGen9, MotorBoard)


class HatSimulator:
    """A board reached neither by serial port nor USB (a HAT's GPIO)."""

    def __init__(self, serial_number: str) -> None:
        self.serial_number = serial_number


def test_a_simulator_of_another_shape_is_in_the_kit_but_not_served_on_a_pty() -> None:
    from dataclasses import replace

    from j5aio.board_kinds import SimulatorEntry
    from j5aio.simulator import SERIAL_SIMULATORS

    hat = replace(
        GEN9,
        name="test-hat",
        hardware=None,
        simulated=Gen9HardwareBackend,
        simulators=(
            SimulatorEntry(
                "test-hat", lambda serial: HatSimulator(serial), "hat", "HAT", transport="other"
            ),
        ),
    )
    register(hat)
    try:
        assert not hat.simulators[0].is_serial
        assert "test-hat" not in SERIAL_SIMULATORS
        kit = SimulatedKit(KitDefinition("x", "x", {"sr-motor": 1, "test-hat": 1}))
        others = kit.other_simulators()
        assert [type(sim) for sim in others] == [HatSimulator]
        assert kit.kind_of(others[0]) is hat
        assert len(kit) == 1  # the boards reached by USB or a serial port
    finally:
        unregister(hat.name)


@pytest.mark.usefixtures("_close_boards")
async def test_a_backend_whose_usb_ids_miss_its_simulators_says_so() -> None:
    from j5aio.simulator.discovery import UnmatchedSimulatorWarning

    class NoUsbIds(Gen9SimulatedBackend):
        """A backend whose author forgot the USB IDs."""

        USB_IDS = frozenset()

    register(GEN9)
    try:
        use_kit(KitDefinition("x", "x", {"test-motor-gen9": 1}))
        with pytest.warns(
            UnmatchedSimulatorWarning,
            match=r"'test-motor-gen9'.*USB_IDS \(none\).*SIMG90 reports [0-9A-F]{4}:[0-9A-F]{4}",
        ):
            assert await NoUsbIds.discover() == []
        boards = await Gen9SimulatedBackend.discover()  # with its IDs: found, and no warning
        for board in boards:
            await board.setup()
        assert [board.serial_number for board in boards] == ["SIMG90"]
    finally:
        unregister(GEN9.name)


def test_a_backend_no_kind_names_cannot_find_a_kind_s_boards() -> None:
    from j5aio.simulator.discovery import kind_options

    with pytest.raises(LookupError, match="Gen9HardwareBackend is the simulated backend of no"):
        kind_options(Gen9HardwareBackend)
