"""The simulated backends of the boards of the kits from 2023 on (firmware 4, the sb2024 Arduino).

As in :mod:`j5aio.simulator.sim_backends`: each is the board's hardware backend whose
``discover`` looks at the boards of :func:`~j5aio.simulator.kit.current_kit` made from its
kind's simulators, and nothing else. Each is imported, with its board's hardware backend,
the first time it is looked up here, so that a program on an older kit imports none of
these boards' backends, and one on a kit of these boards only those of the boards it has.
"""

from typing import TYPE_CHECKING

from j5aio._lazy import lazy_exports

if TYPE_CHECKING:
    from ._backends.sb_arduino_2024 import (
        SBArduino2024SimulatedBackend as SBArduino2024SimulatedBackend,
    )
    from ._backends.servo_fw4 import (
        SBServoBoardSimulatedBackend as SBServoBoardSimulatedBackend,
    )
    from ._backends.servo_fw4 import (
        SRV4ServoBoardFw4SimulatedBackend as SRV4ServoBoardFw4SimulatedBackend,
    )
    from ._backends.sr_arduino_fw2 import (
        SRArduinoSimulatedBackend as SRArduinoSimulatedBackend,
    )
    from ._backends.sr_motor_fw4 import (
        SRV4MotorBoardFw4SimulatedBackend as SRV4MotorBoardFw4SimulatedBackend,
    )
    from ._backends.sr_power_fw4 import (
        SRV4PowerBoardFw4SimulatedBackend as SRV4PowerBoardFw4SimulatedBackend,
    )

if not TYPE_CHECKING:  # type checkers see the names imported above; __all__ is the table's
    __getattr__, __dir__ = lazy_exports(
        __name__,
        {
            "j5aio.simulator._backends.sr_power_fw4": ["SRV4PowerBoardFw4SimulatedBackend"],
            "j5aio.simulator._backends.sr_motor_fw4": ["SRV4MotorBoardFw4SimulatedBackend"],
            "j5aio.simulator._backends.servo_fw4": [
                "SBServoBoardSimulatedBackend",
                "SRV4ServoBoardFw4SimulatedBackend",
            ],
            "j5aio.simulator._backends.sr_arduino_fw2": ["SRArduinoSimulatedBackend"],
            "j5aio.simulator._backends.sb_arduino_2024": ["SBArduino2024SimulatedBackend"],
        },
    )
