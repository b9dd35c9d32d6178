"""Wait for the start button (a few seconds at most), then play a short tune on the piezo.

Run it on the simulated kit, or on the robot::

    python -m j5aio run --sim examples/sync_start_and_buzz.py

Nobody presses the simulated kit's button, so there the wait runs out and the robot
starts anyway: every wait in j5aio can be given a ``timeout``.
"""

from j5aio.components.piezo import Note
from j5aio.sync import KitRobot

START_WAIT = 3.0

robot = KitRobot()

print("Press the start button to begin.")
try:
    robot.power_board.wait_for_start_flash(timeout=START_WAIT)
    print("Started!")
except TimeoutError:
    print(f"Nobody pressed start within {START_WAIT:.0f} s: starting anyway.")

for note in (Note.C6, Note.E6, Note.G6):
    robot.power_board.piezo.buzz(0.2, note, blocking=True)
print("Tune played.")
