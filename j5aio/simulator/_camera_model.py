"""The simulated robot's camera as a kit holds it: its calibration, resolution and lighting.

Both the kit (:mod:`j5aio.simulator.kit`, which gives each kit a camera) and the camera
that draws the pictures (:mod:`j5aio.simulator.camera`, which reads the kit) need it, so
it lives here, below both. Its names are documented, and imported, as
:mod:`j5aio.simulator.camera`'s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from j5aio.vision.calibration import CameraCalibration

if TYPE_CHECKING:  # (the renderer is imported only when a picture is drawn)
    from j5aio.vision.render import Lighting

__all__ = ["DEFAULT_CALIBRATION", "SimulatedCamera"]

#: The simulated camera's default (documented as
#: :data:`j5aio.simulator.camera.DEFAULT_CALIBRATION`).
DEFAULT_CALIBRATION = CameraCalibration(1387.5, 1387.5, 639.5, 359.5, (), (1280, 720))


@dataclass(frozen=True)
class SimulatedCamera:
    """The camera on the simulated robot.

    :param calibration: its pinhole model (also its resolution, if no ``resolution``).
    :param resolution: ``(width, height)`` of its pictures; the calibration is scaled.
    :param lighting: brightness, blur and noise of its pictures.
    """

    calibration: CameraCalibration = DEFAULT_CALIBRATION
    resolution: tuple[int, int] | None = None
    lighting: Lighting | None = field(default=None)

    def model(self) -> tuple[CameraCalibration, tuple[int, int]]:
        """The calibration and resolution its pictures have."""
        calibration = self.calibration
        if self.resolution is not None and self.resolution != calibration.resolution:
            calibration = calibration.scaled_to(*self.resolution)
        resolution = calibration.resolution or self.resolution or (1280, 720)
        return calibration, resolution


# Documented, and imported, as j5aio.simulator.camera's (set once the dataclass is made:
# making it reads the module its __module__ names, which may not be imported yet).
SimulatedCamera.__module__ = "j5aio.simulator.camera"
