"""Array type aliases shared by the package (annotations only)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["FloatArray"]

#: A numpy array of float64 values, any shape.
FloatArray = npt.NDArray[np.float64]
