"""An sbot program that finds the boards and waits for the start itself (SKIP_WAIT_START)."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

import json

from sbot import arduino, comp, motors, power, utils
from sbot.internal.exceptions import MetadataNotReadyError

results: dict[str, object] = {}
try:
    motors.set_power(0, 0.5)
except AssertionError as error:
    results["before_load"] = str(error)
try:
    print(comp.zone)
except MetadataNotReadyError as error:
    results["zone_early"] = str(error)
results["reprs"] = [repr(power), repr(arduino)]
utils.sleep(0.01)  # before the boards are found: plain time
utils.wait_start()  # finds the boards first
results["zone"] = comp.zone
results["competition"] = comp.is_competition
motors.set_power(1, 0.25)
print("RESULT " + json.dumps(results), flush=True)
