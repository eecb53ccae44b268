"""Defensive arrays: values stored in frozen dataclasses are private, read-only copies."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def frozen_array(values: ArrayLike, dtype: type = np.float64) -> NDArray:
    """A read-only copy of ``values``: the caller's array can change, this one cannot."""
    out = np.array(values, dtype=dtype)
    out.setflags(write=False)
    return out
