"""The Blinken board for j5aio: four LEDs on a serial text protocol.

The protocol (115200 baud, lines ending in ``\\n``):

========================  ====================  ======================================
Send                      Reply                 Meaning
========================  ====================  ======================================
``V``                     ``BLINKEN:<version>``  which board and firmware
``L<n> <0|1>``            ``OK``                turn LED ``n`` (0 to 3) off or on
``L<n>?``                 ``0`` or ``1``        whether LED ``n`` is on
anything else             ``ERR <reason>``
========================  ====================  ======================================
"""

from j5aio_blinken.backend import BlinkenHardwareBackend
from j5aio_blinken.board import BlinkenBoard
from j5aio_blinken.console import BlinkenConsoleBackend
from j5aio_blinken.simulator import BlinkenSimulator

__all__ = ["BlinkenBoard", "BlinkenConsoleBackend", "BlinkenHardwareBackend", "BlinkenSimulator"]
