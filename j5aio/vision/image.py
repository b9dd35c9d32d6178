"""The type of a picture: a numpy array of uint8, greyscale (H x W) or BGR (H x W x 3).

numpy is optional: at run time :data:`Image` is only a name for documentation.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, TypeAlias

__all__ = ["Image"]

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

    Image: TypeAlias = npt.NDArray[np.uint8]
else:
    Image: TypeAlias = Any
