"""Wait for the start button, then play a short tune on the piezo.

Run it and answer the start button prompt (or pipe the answer in)::

    echo true | python examples/sync_start_and_buzz.py
"""

from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.boards.sr.v4 import PowerBoard
from j5aio.components.piezo import Note
from j5aio.sync import BoardGroup

power_board = BoardGroup.get_board_group(PowerBoard, SRV4PowerBoardConsoleBackend).singular()

print("Press the start button to begin.")
power_board.wait_for_start_flash(timeout=30)
print("Started!")

for note in (Note.C6, Note.E6, Note.G6):
    power_board.piezo.buzz(0.2, note, blocking=True)
