"""sbot's LEDs on a robot with the HAT (the sr2023 kit's KCH), and a robot without an Arduino."""

# mypy: disable-error-code="import-not-found"
# (``sbot`` is j5aio.compat.sbot under ``j5aio run --api sbot`` or the test harness)

import json

from sbot import Colour, arduino, leds, utils

results: dict[str, object] = {}
leds.set_colour(0, Colour.CYAN)
leds.set_colour(2, Colour.YELLOW)
results["colours"] = [leds.get_colour(n).name for n in range(3)]
try:
    arduino.digital_read(3)
except ValueError as error:
    results["no_arduino"] = str(error)
results["repr"] = repr(arduino)
utils.sleep(0)
print("RESULT " + json.dumps(results), flush=True)
