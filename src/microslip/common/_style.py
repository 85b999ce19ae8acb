"""Plot style shared by the result objects and the paper's figures (private)."""

from __future__ import annotations

import numpy as np


def element_colors(J: int):
    """One colour per element, consistent across the figures (element 1 first)."""
    import matplotlib

    cmap = matplotlib.colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, J)]
