"""The generator: the committed module is fresh, and its rules hold on a made-up class."""

from __future__ import annotations

import importlib.util
import sys
import types
import uuid
from pathlib import Path

import pytest

from j5aio import lifetime, syncgen
from j5aio.sync import _generated
from tests.module_from_file import load_module

from .sync_fakes import ROOT

TOOL_PATH = ROOT / "tools" / "gen_sync.py"


def load_tool() -> types.ModuleType:
    return load_module("gen_sync_under_test", TOOL_PATH, register=True)


@pytest.fixture(scope="module")
def gen() -> types.ModuleType:
    return syncgen


def test_committed_package_is_up_to_date(gen: types.ModuleType) -> None:
    folder = Path(_generated.__file__).parent
    fresh: dict[str, str] = gen.generate_core()
    assert {"__init__.py", "robot.py", "sr.py", "components.py"} <= set(fresh)
    committed = {path.name: path.read_text(encoding="utf-8") for path in folder.glob("*.py")}
    assert committed == fresh, "j5aio/sync/_generated is stale: run python tools/gen_sync.py"


def test_check_option_reports_staleness(
    gen: types.ModuleType, tmp_path: Path, capsys: pytest.CaptureFixture[str],
) -> None:
    tool = load_tool()
    target = tmp_path / "generated"
    assert tool.main(["--check", "--output", str(target)]) == 1
    assert not target.exists()  # (a check writes nothing)
    assert tool.main(["--output", str(target)]) == 0
    assert tool.main(["--check", "--output", str(target)]) == 0
    fresh: dict[str, str] = gen.generate_core()
    assert {path.name: path.read_text(encoding="utf-8") for path in target.iterdir()} == fresh

    # one module edited by hand, and one that is no longer generated: both are stale
    (target / "sr.py").write_text("# edited\n", encoding="utf-8")
    (target / "gone.py").write_text("# an old family\n", encoding="utf-8")
    capsys.readouterr()
    assert tool.main(["--check", "--output", str(target)]) == 1
    assert "sr.py, gone.py" in capsys.readouterr().err
    assert tool.main(["--output", str(target)]) == 0
    assert not (target / "gone.py").exists()
    assert (target / "sr.py").read_text(encoding="utf-8") == fresh["sr.py"]
    assert tool.main(["--check", "--output", str(target)]) == 0


def test_each_family_holds_the_classes_of_its_core_modules(gen: types.ModuleType) -> None:
    from j5aio.boards.sr.v4.motor_board import MotorBoard
    from j5aio.components.motor import Motor
    from j5aio.kit import KitRobot

    assert gen.core_family(MotorBoard.__module__) == "sr"
    assert gen.core_family(Motor.__module__) == "components"
    assert gen.core_family(KitRobot.__module__) == "robot"
    assert gen.core_family("j5aio.boards.srx") == "robot"  # a prefix is a whole package
    for cls in gen.discover().classes:
        family = gen.core_family(cls.__module__)
        wrapper = getattr(_generated, cls.__name__)
        assert wrapper.__module__ == f"{gen.CORE_PACKAGE}.{family}", cls


def test_a_kit_module_with_no_boards_is_refused(gen: types.ModuleType) -> None:
    with pytest.raises(ValueError, match="found no board or component classes"):
        gen.generate(["j5aio.errors"])


def test_discovery_finds_every_board_and_component(gen: types.ModuleType) -> None:
    from j5aio.backends.environment import Environment
    from j5aio.boards.board import Board
    from j5aio.boards.board_group import BoardGroup
    from j5aio.components.component import Component
    from j5aio.robot import BaseRobot

    discovery = gen.discover()
    classes = set(discovery.classes)
    assert {BoardGroup, Environment, BaseRobot, Board, Component} <= classes
    for cls in classes:
        for base in cls.__mro__[1:]:
            if base in classes:
                assert discovery.classes.index(base) < discovery.classes.index(cls)
    assert "CONSOLE_ENVIRONMENT" in discovery.environments
    for cls in Board.__subclasses__():
        if cls.__module__.startswith("j5aio."):
            assert cls in classes


def test_every_coroutine_of_a_wrapped_class_is_reachable(gen: types.ModuleType) -> None:
    import inspect

    discovery = gen.discover()
    for cls in discovery.classes:
        wrapper = getattr(_generated, cls.__name__)
        for name, member in inspect.getmembers(cls):
            if name.startswith("_") or not inspect.iscoroutinefunction(member):
                continue
            face = name[4:] if name.startswith(("get_", "set_")) else name
            assert hasattr(wrapper, face) or hasattr(wrapper, name), f"{cls.__name__}.{name}"


def test_generated_classes_use_slots() -> None:
    for name in _generated.__all__:
        obj = getattr(_generated, name)
        if isinstance(obj, type):
            assert "__slots__" in vars(obj), name


def test_rendering_rules(gen: types.ModuleType, tmp_path: Path) -> None:
    """A made-up component: pairs, lone getters, setters with extras, defaults."""
    source = '''
from __future__ import annotations
import enum
from collections.abc import Mapping

class Colour(enum.Enum):
    RED = 1

class Lamp:
    """A lamp."""

    def __init__(
        self, name: str, *, colour: Colour = Colour.RED, level: float = float("inf"),
    ) -> None:
        self.name = name
        self.options: dict[str, int] = {}

    async def get_brightness(self) -> float:
        """Return the brightness."""
        return 1.0

    async def set_brightness(self, value: float) -> None:
        """Set the brightness."""

    async def get_hours(self) -> int:
        """Return the hours lit."""
        return 3

    async def get_channel(self, channel: int) -> float:
        return 0.0

    async def set_mode(self, mode: str, /, *extra: int, **more: str) -> None:
        """Set the mode."""

    def twin(self) -> Lamp:
        """Return a twin."""
        return self

    def by_name(self) -> Mapping[str, Lamp]:
        """All lamps."""
        return {"me": self}

    @property
    def size(self) -> tuple[int, ...]:
        """The size."""
        return (1,)
'''
    (tmp_path / "sync_gen_fake_component.py").write_text(source, encoding="utf-8")
    sys.path.insert(0, str(tmp_path))
    try:
        module = importlib.import_module("sync_gen_fake_component")
        text = gen.render_module(gen.Discovery(classes=[module.Lamp]))
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop("sync_gen_fake_component", None)
    assert "class Lamp(_SyncWrapper):" in text
    assert "    def brightness(self) -> float:" in text
    assert "    @brightness.setter" in text
    assert "    def hours(self) -> int:" in text
    assert "@hours.setter" not in text
    assert "def get_channel(self, channel: int) -> float:" in text
    assert "def set_mode(self, mode: str, /, *extra: int, **more: str) -> None:" in text
    assert "_call(self._core.set_mode, mode, *extra, **more)" in text
    assert 'return cast("Lamp", _wrap(self._core.twin()))' in text
    assert 'return cast("Mapping[str, Lamp]", _wrap(self._core.by_name()))' in text
    assert "colour: Colour = Colour.RED" in text
    assert "from sync_gen_fake_component import Colour" in text
    assert '_register_later("sync_gen_fake_component", "Lamp", Lamp)' in text
    assert 'level: float = float("inf")' in text
    assert "def name(self) -> str:" in text
    assert "def options(self) -> dict[str, int]:" in text
    assert "def size(self) -> tuple[int, ...]:" in text
    assert '"""Call ``get_channel``."""' in text


KIT_SOURCE = '''
from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar

from j5aio.backends.backend import Backend
from j5aio.boards.board import Board
from j5aio.components.identified import IdentifiedComponent
from j5aio.components.component import Component, Interface
from j5aio.components.led import LED


class HornInterface(Interface):
    @abstractmethod
    async def get_horn_volume(self, identifier: int) -> int: ...

    @abstractmethod
    async def set_horn_volume(self, identifier: int, volume: int) -> None: ...


class Horn(IdentifiedComponent[HornInterface]):
    """A horn."""

    __slots__ = ()

    @classmethod
    def interface_class(cls) -> type[HornInterface]:
        return HornInterface

    async def get_volume(self) -> int:
        """How loud."""
        return await self._backend.get_horn_volume(self._identifier)

    async def set_volume(self, volume: int) -> None:
        await self._backend.set_horn_volume(self._identifier, volume)


class Cart(Board):
    """A cart with a horn and a lamp."""

    name: ClassVar[str] = "Cart"

    def __init__(self, serial_number: str, backend: Backend) -> None:
        super().__init__(serial_number, backend)
        self._horn = Horn(0, backend)
        self._lamp = LED(0, backend)

    @property
    def horn(self) -> Horn:
        """The horn."""
        return self._horn

    @property
    def lamp(self) -> LED:
        """The lamp."""
        return self._lamp

    @staticmethod
    def supported_components() -> set[type[Component]]:
        return {Horn, LED}

    async def make_safe(self) -> None:
        await self._horn.set_volume(0)
'''


def test_a_kits_board_and_component_are_wrapped_on_j5aios_wrappers(tmp_path: Path) -> None:
    from j5aio import sync
    from j5aio.components.led import LEDInterface

    name = f"fake_kit_{uuid.uuid4().hex}"
    (tmp_path / f"{name}.py").write_text(KIT_SOURCE, encoding="utf-8")
    sys.path.insert(0, str(tmp_path))
    try:
        kit = importlib.import_module(name)
        text = syncgen.generate([name])
        assert f"import {name} as _{name}" in text
        assert f"class Horn(_sync.IdentifiedComponent[_{name}.HornInterface]):" in text
        assert "class Cart(_sync.Board):" in text
        assert "    def horn(self) -> Horn:" in text
        assert "    def lamp(self) -> _sync.LED:" in text
        assert "_components_identified" not in text  # nothing private of j5aio
        (tmp_path / f"{name}_sync.py").write_text(text, encoding="utf-8")
        wrappers = importlib.import_module(f"{name}_sync")

        class Horns:
            volume = 3

            async def get_horn_volume(self, identifier: int) -> int:
                return self.volume

            async def set_horn_volume(self, identifier: int, volume: int) -> None:
                self.volume = volume

        class LEDs(LEDInterface):
            async def get_led_state(self, identifier: int) -> bool:
                return True

            async def set_led_state(self, identifier: int, state: bool) -> None:
                pass

        # the kit's interface exists only at run time here, so the class is made at run time
        both = type("Both", (Horns, kit.HornInterface, LEDs), {})
        cart = wrappers.Cart("C1", both())
        assert isinstance(cart.horn, wrappers.Horn)
        assert isinstance(cart.lamp, sync.LED)
        assert cart.horn.volume == 3
        cart.horn.volume = 7
        assert cart.horn.volume == 7
        assert cart.lamp.state is True
        # the stand-in backend has no safe state: the safety net must not try it at exit
        lifetime.untrack(cart._core)
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop(name, None)
        sys.modules.pop(f"{name}_sync", None)
