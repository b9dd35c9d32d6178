"""The hardware environment: the backend that drives each kind of real board."""

from __future__ import annotations

from j5aio.backends.camera.opencv import OpenCVCameraBackend
from j5aio.backends.environment import Environment
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend

__all__ = ["HARDWARE_BACKENDS", "HARDWARE_ENVIRONMENT"]

#: Every hardware backend, in the order listing tries them. The SourceBots Arduino
#: comes before the Ruggeduino: both use the same USB IDs, and an Arduino that fails
#: the SourceBots handshake is then tried as a Ruggeduino.
HARDWARE_BACKENDS = (
    SRV4PowerBoardHardwareBackend,
    SRV4MotorBoardHardwareBackend,
    SRV4ServoBoardHardwareBackend,
    SBArduinoHardwareBackend,
    SRV4RuggeduinoHardwareBackend,
)

#: Real boards: SR v4 power (fw 3), motor (fw 3), servo (fw 2) boards and Ruggeduino
#: (fw 1), and the SourceBots Arduino (2019 protocol).
HARDWARE_ENVIRONMENT = Environment("HardwareEnvironment")
for _backend in HARDWARE_BACKENDS:
    HARDWARE_ENVIRONMENT.register_backend(_backend)
# Webcams (the optional extra j5aio[vision]; without it none is found).
HARDWARE_ENVIRONMENT.register_backend(OpenCVCameraBackend)
