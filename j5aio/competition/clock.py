"""The robot's clock: real time, or scaled when a simulated kit runs faster or slower.

Robot code should use ``robot.time()`` and ``await robot.sleep(seconds)`` rather than
``time.time()`` and ``anyio.sleep``, so that a simulation can run at another speed: with
``J5AIO_TIME_SCALE=F`` (``python -m j5aio run --sim --time-scale F``) every robot second
lasts ``F`` real seconds, as the simulated boards' own delays do. The match's duration
is in robot seconds too.
"""

from __future__ import annotations

import math
import os
import time
from typing import Final

import anyio

from j5aio.components._checks import check_number

__all__ = ["TIME_SCALE_VARIABLE", "MatchClock", "time_scale_from_environment"]

#: The environment variable holding the time scale (real seconds per robot second).
TIME_SCALE_VARIABLE: Final = "J5AIO_TIME_SCALE"


def time_scale_from_environment() -> float:
    """The time scale in ``J5AIO_TIME_SCALE``, or 1 (real time) if it is not set.

    :raises ValueError: it is set but is not a number more than 0.
    """
    text = os.environ.get(TIME_SCALE_VARIABLE, "").strip()
    if not text:
        return 1.0
    try:
        scale = float(text)
    except ValueError:
        scale = math.nan
    if not (math.isfinite(scale) and scale > 0):
        raise ValueError(
            f"{TIME_SCALE_VARIABLE} must be a number more than 0 (real seconds per robot "
            f"second), not {text!r}"
        )
    return scale


class MatchClock:
    """Robot time: seconds since the clock was made, divided by the time scale.

    :param scale: real seconds per robot second (``2`` runs at half speed); the
        environment's (:func:`time_scale_from_environment`) if omitted.
    :raises ValueError: ``scale`` is not a number more than 0.
    """

    def __init__(self, scale: float | None = None) -> None:
        if scale is None:
            scale = time_scale_from_environment()
        if isinstance(scale, bool) or not isinstance(scale, int | float):
            raise TypeError(f"scale must be a number, not {type(scale).__name__}")
        if not (math.isfinite(scale) and scale > 0):
            raise ValueError(f"scale must be a number more than 0, not {scale}")
        self._scale = float(scale)
        self._origin = time.monotonic()

    @property
    def scale(self) -> float:
        """Real seconds per robot second."""
        return self._scale

    def time(self) -> float:
        """Robot seconds since the clock was made."""
        return (time.monotonic() - self._origin) / self._scale

    def to_real(self, seconds: float) -> float:
        """How many real seconds ``seconds`` robot seconds last."""
        return seconds * self._scale

    async def sleep(self, seconds: float) -> None:
        """Wait ``seconds`` robot seconds, letting other tasks run.

        :raises TypeError: ``seconds`` is not a number.
        :raises ValueError: ``seconds`` is negative or NaN.
        """
        wait = check_number(
            seconds, name="sleep time", low=0, high=math.inf, allowed="0 or more seconds"
        )
        await anyio.sleep(self.to_real(wait))
