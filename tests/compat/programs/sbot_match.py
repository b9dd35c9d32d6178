"""An sbot program that drives until the match ends (it never stops by itself)."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

from sbot import comp, motors, utils

print("zone", comp.zone, "competition", comp.is_competition, flush=True)
while True:
    motors.set_power(0, 0.5)
    utils.sleep(0.05)
