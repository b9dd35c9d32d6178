"""The units the competitions' APIs give their readings in, worked out from j5aio's.

A named adapter shared by the compat modules, so that the next competition's API needs
none of its own:

- the Arduinos' ADC: j5aio gives volts as ``reading / 1024 x 5``; sr-robot3 and sbot give
  ``reading / 1023 x 5``, rounded to 3 places (:func:`volts_on_1023_scale`);
- ultrasound: j5aio gives metres, or ``None`` with no echo; sr-robot3 and sbot give whole
  millimetres, and 0 with no echo (:func:`whole_millimetres`).
"""

from __future__ import annotations

from typing import Final

__all__ = ["volts_on_1023_scale", "whole_millimetres"]

_J5AIO_ADC_STEPS: Final = 1024
_ADC_MAX: Final = 1023
_REFERENCE: Final = 5.0


def volts_on_1023_scale(volts: float) -> float:
    """The reading of an ADC value that j5aio gave as ``volts``, on the 1023 scale.

    The firmware sends the 10-bit ADC value; it is worked back exactly from j5aio's
    volts, then mapped as sr-robot3 and sbot map it: ``value / 1023 x 5``, 3 places.
    """
    reading = max(0, min(_ADC_MAX, round(volts * _J5AIO_ADC_STEPS / _REFERENCE)))
    return round(reading * _REFERENCE / _ADC_MAX, 3)


def whole_millimetres(metres: float | None) -> int:
    """An ultrasound distance in whole millimetres, 0 for no echo (``None``).

    The firmware measures in whole millimetres, which j5aio gives as metres: rounding
    gives the firmware's figure back.
    """
    return 0 if metres is None else round(metres * 1000)
