"""sbot README's start-up example: ``override.env`` says SKIP_WAIT_START, the program starts."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

from sbot import motors, utils

utils.load_boards()
utils.wait_start()
motors.set_power(0, -0.5)
print("started")
