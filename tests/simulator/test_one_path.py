"""One path: every simulated board runs through its hardware backend, as on a robot.

The simulated environment may change where a backend finds its boards (``discover``:
the kit's simulators instead of the computer's ports and USB bus), and nothing else: the
backend's handshake, codec, polls and error handling are the hardware backend's own.
"""

from __future__ import annotations

import inspect

import pytest

from j5aio.backends.backend import Backend
from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.backends.hardware.sr.kch import KCHHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.backends.hardware.transports.usb_link import USBLink
from j5aio.board_kinds import BoardKind, board_kinds, kits, simulator_entries
from j5aio.boards.camera import CameraBoard
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT, SimulatedUSBDevice, simulated_backend
from j5aio.simulator.kch import KCHSimulator
from j5aio.simulator.kit import use_kit

pytestmark = pytest.mark.usefixtures("fresh_kit")

#: What a class statement adds by itself (docstring, module, abc and typing machinery,
#: and the instance dict's descriptors a class gets when a slotted mixin comes first).
_CLASS_MACHINERY = frozenset({
    "__abstractmethods__", "__dict__", "__doc__", "__firstlineno__", "__module__",
    "__orig_bases__", "__parameters__", "__qualname__", "__slots__", "__static_attributes__",
    "__weakref__", "_abc_impl",
})

#: What a simulated backend may change: where it finds its boards.
_TRANSPORT_ONLY = frozenset({"discover", "default_discovery_options"})


def _code(cls: type, name: str) -> object:
    """What ``cls.name`` runs: the function under any classmethod or observing wrapper."""
    value = inspect.getattr_static(cls, name, None)
    if isinstance(value, classmethod | staticmethod):
        value = value.__func__
    return inspect.unwrap(value) if callable(value) else value


def added_by(backend: type[Backend], hardware: type[Backend]) -> set[str]:
    """The names whose code ``backend`` changes from ``hardware``'s (a subclass of it)."""
    assert issubclass(backend, hardware), f"{backend.__name__} is not a {hardware.__name__}"
    names: set[str] = set()
    for cls in backend.__mro__:
        if cls is hardware:
            break
        names.update(vars(cls))
    return {
        name for name in names - _CLASS_MACHINERY
        if _code(backend, name) is not _code(hardware, name)
    }


def kit_kinds() -> list[tuple[str, BoardKind]]:
    """Every (kit, kind) pair: each kind of board of every registered kit."""
    entries = simulator_entries()
    pairs: dict[tuple[str, str], tuple[str, BoardKind]] = {}
    for kit in kits().values():
        for name in kit.boards:
            kind = entries[name][0]
            pairs[kit.name, kind.name] = (kit.name, kind)
    return list(pairs.values())


@pytest.mark.parametrize(("kit_name", "kind"), kit_kinds(), ids=lambda v: getattr(v, "name", v))
def test_the_simulated_backend_only_swaps_the_transport_of_the_hardware_one(
    kit_name: str, kind: BoardKind
) -> None:
    backend = simulated_backend(kind)
    hardware = kind.hardware
    assert backend is not None and hardware is not None, f"{kind.name} is not simulated"
    assert added_by(backend, hardware) <= _TRANSPORT_ONLY


def test_a_backend_that_replaces_hardware_code_is_caught() -> None:
    kind = next(k for k in board_kinds() if k.name == "sr-v4-power-fw3")
    hardware = kind.hardware
    assert hardware is not None
    backend = simulated_backend(kind)
    assert backend is not None

    class ListensInsteadOfPolling(backend):  # type: ignore[misc, valid-type]
        async def _poll_button(self, *args: object, **kwargs: object) -> None:
            raise AssertionError("never called")

    assert added_by(ListensInsteadOfPolling, hardware) - _TRANSPORT_ONLY == {"_poll_button"}
    with pytest.raises(AssertionError, match="is not a"):
        added_by(FrameCameraBackend, hardware)  # type: ignore[type-abstract]


def test_the_simulated_camera_swaps_only_its_frame_source() -> None:
    """The camera's transport is where its frames come from: rendered, not captured."""
    backend = SIMULATED_ENVIRONMENT.get_backend(CameraBoard)
    assert issubclass(backend, FrameCameraBackend)
    interface = {
        "see_markers", "see_marker_ids", "capture_frame", "save_annotated_frame",
        "get_calibration", "_see", "_see_ids", "_save", "_detector_here",
    }
    assert not interface & added_by(backend, FrameCameraBackend)  # type: ignore[type-abstract]


@pytest.mark.parametrize("kit_name", ["sr2019", "sb2019", "sr2023", "sb2024"])
async def test_every_board_of_the_kit_is_opened_by_its_hardware_backend(kit_name: str) -> None:
    kit = use_kit(kit_name)
    for simulator_name in kit.simulator_names():
        kind = kit.kind_of(kit.simulators(simulator_name)[0])
        expected = simulated_backend(kind)
        assert expected is not None and kind.hardware is not None
        group = await SIMULATED_ENVIRONMENT.get_board_group(kind.board)
        assert len(group) >= 1
        for board in group:
            backend = board.backend
            assert type(backend) is expected
            assert isinstance(backend, kind.hardware)
            link = getattr(backend, "link", None)
            if isinstance(link, USBLink):  # a USB board: the pyusb device is the simulator
                assert isinstance(link.device, SimulatedUSBDevice)
            elif isinstance(link, SerialLink):  # a serial port whose far end is the simulator
                assert isinstance(link.stream, SimulatorStream)
            else:  # the KCH: the GPIO pins are the simulator's mock pins
                assert isinstance(backend, KCHHardwareBackend)
                (simulator,) = kit.simulators(simulator_name)
                assert isinstance(simulator, KCHSimulator)
                assert simulator.board() is board
