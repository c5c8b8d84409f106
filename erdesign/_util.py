"""Small helpers shared by the kernels (not part of the public API)."""

from __future__ import annotations

import numpy as np

__all__ = ["scalar_or_array"]


def scalar_or_array(x):
    """A Python float for 0-d input, the numpy array otherwise (keeps doctests and JSON output plain)."""
    arr = np.asarray(x)
    return float(arr) if arr.ndim == 0 else arr
