"""The optional libraries of vision (numpy, OpenCV, pyapriltags), imported only when needed.

``import j5aio`` and ``import j5aio.vision`` never import them: a program that does not
look through a camera runs without them, and one that does is told what to install.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Final

__all__ = ["INSTALL_HINT", "VisionNotInstalledError", "require"]

#: What to run to get the vision libraries.
INSTALL_HINT: Final = "pip install 'j5aio[vision]'"

_PACKAGES: Final = {
    "numpy": "numpy",
    "cv2": "opencv-python-headless",
    "pyapriltags": "pyapriltags",
}


class VisionNotInstalledError(ImportError):
    """A camera was asked for, but the optional vision libraries are not installed."""


def require(module: str) -> ModuleType:
    """Import and return one of the vision libraries (``numpy``, ``cv2``, ``pyapriltags``).

    :raises ~j5aio.vision.VisionNotInstalledError: the library is not installed; the
        message says what to install.
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise VisionNotInstalledError(
            f"Cameras need the optional vision libraries, and {_PACKAGES[module]} "
            f"(module {module!r}) could not be imported ({exc}). Install them with: "
            f"{INSTALL_HINT}",
        ) from exc
