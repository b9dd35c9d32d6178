"""The simulated backends of the SR v4 boards of firmware 3 (and 2) and the 2019 Arduinos.

Each is the board's hardware backend whose ``discover`` looks at the boards of
:func:`~j5aio.simulator.kit.current_kit` made from its kind's simulators (see
:mod:`j5aio.simulator.discovery`), and nothing else: from there on every call runs the
hardware backend's own code (its polls included) over a simulated transport, as on a
robot. Each board kind names its simulated backend (``simulated=`` of
:class:`~j5aio.board_kinds.BoardKind`); the simulated environment looks it up here the
first time it needs it. Each is imported, with its board's hardware backend, the first
time it is looked up, so a kit imports the backends of the boards it has and no others
(the default kit, say, none of the Ruggeduino's). The later boards' are in
:mod:`j5aio.simulator.sim_backends_2023`.

A plugin's simulated backend is written the same way, with
:func:`~j5aio.simulator.discovery.kind_options`::

    class BeeSimulatedBackend(BeeBackend):
        @classmethod
        async def discover(cls, *, options=None):
            return await super().discover(options=options or kind_options(cls))
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from ._backends.sb_arduino_2019 import (
        SBArduinoSimulatedBackend as SBArduinoSimulatedBackend,
    )
    from ._backends.sr_motor_fw3 import (
        SRV4MotorBoardSimulatedBackend as SRV4MotorBoardSimulatedBackend,
    )
    from ._backends.sr_power_fw3 import (
        SRV4PowerBoardSimulatedBackend as SRV4PowerBoardSimulatedBackend,
    )
    from ._backends.sr_ruggeduino_fw1 import (
        SRV4RuggeduinoSimulatedBackend as SRV4RuggeduinoSimulatedBackend,
    )
    from ._backends.sr_servo_fw2 import (
        SRV4ServoBoardSimulatedBackend as SRV4ServoBoardSimulatedBackend,
    )

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.simulator._backends.sr_power_fw3": ["SRV4PowerBoardSimulatedBackend"],
            "j5aio.simulator._backends.sr_motor_fw3": ["SRV4MotorBoardSimulatedBackend"],
            "j5aio.simulator._backends.sr_servo_fw2": ["SRV4ServoBoardSimulatedBackend"],
            "j5aio.simulator._backends.sb_arduino_2019": ["SBArduinoSimulatedBackend"],
            "j5aio.simulator._backends.sr_ruggeduino_fw1": ["SRV4RuggeduinoSimulatedBackend"],
        },
    )
