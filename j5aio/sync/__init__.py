"""The synchronous face of j5aio, for first-time students and for j5 programs.

Every class here wraps its async twin from the core and blocks until the board has
answered, exactly like j5. A program written for j5 runs with only its import line
changed::

    from j5aio.sync import BaseRobot, BoardGroup
    from j5aio.boards.sr.v4 import PowerBoard
    from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend

    class MyRobot(BaseRobot):
        def __init__(self) -> None:
            self.power_board = BoardGroup.get_board_group(
                PowerBoard, SRV4PowerBoardConsoleBackend,
            ).singular()

    robot = MyRobot()
    robot.power_board.outputs[0].is_enabled = True

An ``await x.get_power()`` / ``await x.set_power(v)`` pair of the core is the property
``x.power`` here; every other coroutine is a method of the same name that blocks. When
the program ends, however it ends (normally, by an exception, Ctrl-C or SIGTERM), every
board is made safe and its port closed. The wrappers are generated from the core by
:mod:`j5aio.syncgen`; a kit of your own gets the same typed wrappers for its boards with
``python -m j5aio sync-gen yourkit.boards -o yourkit/sync.py``, and board classes may be
given as the core's or as these wrappers (``BoardGroup.get_board_group(MotorBoard, ...)``
with either ``MotorBoard``).

``import j5aio.sync`` itself is light: the wrappers (and with them the core, the event
loop's modules and the board classes) are loaded the first time a name is used, one
family at a time (the robots; Student Robotics' boards; the components; ...): a program
loads the wrappers of what it uses.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from j5aio import __version__

if TYPE_CHECKING:
    from j5aio.sync import _generated
    from j5aio.sync._generated import *  # noqa: F403
    from j5aio.sync._runtime import shutdown

    __all__ = ["__version__", "shutdown"]
    __all__ += _generated.__all__


if not TYPE_CHECKING:  # the names are imported above for type checkers

    def __getattr__(name: str) -> Any:
        """Load the wrappers on first use, then give the name asked for (PEP 562)."""
        import importlib

        value: Any
        if name == "shutdown":
            from j5aio.sync._runtime import shutdown as value
        elif name == "__all__":
            generated = importlib.import_module("j5aio.sync._generated")
            value = ["__version__", "shutdown", *generated.__all__]
        elif name.startswith("__"):
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        else:
            generated = importlib.import_module("j5aio.sync._generated")
            if name in generated.__all__:
                value = getattr(generated, name)
            else:
                try:
                    value = importlib.import_module(f"{__name__}.{name}")
                except ModuleNotFoundError as error:
                    if error.name != f"{__name__}.{name}":
                        raise
                    raise AttributeError(
                        f"module {__name__!r} has no attribute {name!r}"
                    ) from None
        globals()[name] = value
        return value

    def __dir__() -> list[str]:
        """The names of the module, with the wrappers' (which loads them)."""
        return sorted({*globals(), *__getattr__("__all__")})
